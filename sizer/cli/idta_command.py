"""``sizer idta read`` and ``sizer idta write``: IDTA 02021 "Sizing of Power Drive Trains"
in (its ApplicationRequirements as a design) and out (sizer's result as its SizingResult).
The mapping is :mod:`sizer.idta`; this module reads and writes the files."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Annotated

import typer

idta_app = typer.Typer(
    name="idta",
    help="IDTA 02021 'Sizing of Power Drive Trains' (AAS submodel): read its "
         "ApplicationRequirements into a design, write a sizing as its SizingResult.",
    no_args_is_help=True,
    rich_markup_mode=None,  # plain help, as the app (sizer.cli.app)
    add_completion=False,
)

NOTE = "# note:"
"""The comment lines of a design written by 'idta read' that 'idta write' carries on as
Messages."""

RequiredOutput = Annotated[Path, typer.Option(
    "--output", "-o", dir_okay=False, metavar="FILE",
    help="Write to FILE (replaced atomically).")]


def _note(text: str) -> None:
    from sizer.report.printable import printable

    typer.echo(f"note: {printable(text)}", err=True)


@idta_app.command("read")
def read(
    source: Annotated[Path, typer.Argument(
        metavar="FILE", help="The submodel's JSON (a submodel, or an environment holding "
                             "it; its MotionSectionFile paths relative to its folder), or "
                             "one motion section CSV.", show_default=False)],
    output: RequiredOutput,
    motors: Annotated[list[str] | None, typer.Option(
        "--motors", metavar="CATALOG",
        help="The design's motors: a bundled catalog name or a file; repeat for more. "
             "Default: none named (sizer sizes against every bundled catalog).")] = None,
) -> None:
    """Read an IDTA 02021 submodel (JSON) or one motion section (CSV: 'idShort [unit]'
    headers, ';' between fields) into a design file, with its motion as a cam table
    FILE-motion.csv beside it (FILE-motion-1.csv, -2... for several moves between rests;
    a rest is a dwell). What the design cannot carry is printed as notes (and kept as
    comments at the top of the design).

    Example:

        sizer idta read axis.json -o axis.yaml && sizer size axis.yaml
    """
    import yaml

    from sizer.cli.output_guard import check_outputs
    from sizer.errors import UserError
    from sizer.idta.read import read_csv_design, read_submodel
    from sizer.io.files import read_user_text
    from sizer.report.output import write_text_atomically

    cam = output.with_name(f"{output.stem}-motion.csv")
    check_outputs([output, cam], [source], "--output")
    inputs: list[Path] = [source]
    text = read_user_text(source, what="IDTA 02021")
    if source.suffix.lower() == ".csv":
        result = read_csv_design(text, source=source.name, cam_file=cam.name)
    else:
        try:
            data = json.loads(text)
        except json.JSONDecodeError as error:
            raise UserError(f"not JSON: {error.msg}", file=str(source),
                            line=error.lineno) from None
        if not isinstance(data, dict):
            raise UserError("not a submodel or an environment (a JSON object)",
                            file=str(source))
        folder = source.parent

        def read_file(path: str) -> str:
            candidates = [folder / path.lstrip("/"), folder / Path(path).name]
            found = next((c for c in candidates if c.is_file()), candidates[0])
            inputs.append(found)
            return read_user_text(found, what="motion CSV")

        result = read_submodel(data, source=source.name, read_file=read_file,
                               cam_file=cam.name)
    design = dict(result.design)
    if motors:
        design["motors"] = list(motors)
    header = [f"# sizer design read from {source.name} (IDTA 02021 Sizing of Power Drive "
              "Trains) by 'sizer idta read'"]
    header += [f"{NOTE} {note}" for note in result.notes]
    body = yaml.safe_dump(design, sort_keys=False, allow_unicode=True)
    cams = [(output.with_name(name), text) for name, text in result.cams]
    check_outputs([output, *(path for path, _ in cams)], inputs, "--output")
    for path, text in cams:
        write_text_atomically(path, text)
    write_text_atomically(output, "\n".join(header) + "\n" + body)
    for note in result.notes:
        _note(note)


@idta_app.command("write")
def write(
    design: Annotated[Path, typer.Argument(metavar="DESIGN", help="The design file.",
                                           show_default=False)],
    output: RequiredOutput,
    motor: Annotated[str | None, typer.Option(
        "--motor", metavar="ID", help="Write this motor's best row, not the top-ranked "
                                      "feasible one.")] = None,
    submodel_id: Annotated[str | None, typer.Option(
        "--id", metavar="IRI", help="The submodel's id (default: urn:sizer:idta02021:"
                                    "<design file name>).")] = None,
) -> None:
    """Size DESIGN and write the chosen pair (the top-ranked feasible one, or --motor's) as
    the IDTA 02021 submodel with its SizingResult (AAS V3.0 JSON; FILE.aasx: the same
    submodel in an AASX package, with the 'aas' extra). Exit 1 when no pair is feasible
    (the top-ranked one is written, with its reason as an Error message).

    Example:

        sizer idta write axis.yaml -o axis-result.json
    """
    from datetime import UTC, datetime

    from sizer import __version__, api
    from sizer.cli.exit_codes import ExitCode
    from sizer.cli.output_guard import check_output
    from sizer.cli.progress import sizing_progress
    from sizer.errors import UserError
    from sizer.idta.write import pair_from_record, sizing_result_submodel
    from sizer.io.files import read_user_text
    from sizer.report.output import write_bytes_atomically, write_text_atomically

    check_output(output, [design])
    aasx = output.suffix.lower() == ".aasx"
    if aasx:
        from sizer.idta.aasx import INSTALL_HINT, aasx_available

        if not aasx_available():
            raise UserError(f"an .aasx output needs basyx-python-sdk: {INSTALL_HINT} (or "
                            "write the JSON: -o FILE.json)", field="--output")
    with sizing_progress(f"sizing {design.name}", unit="laws") as progress:
        result = api.size(str(design), progress=progress)
    rows = list(zip(result.results, result.records(), strict=True))
    if motor is not None:
        rows = [(c, r) for c, r in rows if r["motor"] == motor]
        if not rows:
            raise UserError(f"no motor {motor!r} in the design's results", field="--motor")
    if not rows:
        raise UserError("the design gives no motor/law pair", file=str(design))
    chosen, record = next(((c, r) for c, r in rows if r["feasible"]), rows[0])
    read_notes = tuple(line[len(NOTE):].strip() for line in read_user_text(design).splitlines()
                       if line.startswith(NOTE))
    pair = pair_from_record(record, manufacturer=chosen.motor_object.manufacturer,
                            part_number=chosen.motor_object.part_number,
                            notes=(*read_notes, *result.notes))
    # the design file's date (SOURCE_DATE_EPOCH where set), not the clock's: the same
    # input writes the same bytes
    stamp = float(os.environ.get("SOURCE_DATE_EPOCH") or design.stat().st_mtime)
    date = datetime.fromtimestamp(int(stamp), UTC)
    now = date.isoformat().replace("+00:00", "Z")
    submodel = sizing_result_submodel(
        pair, submodel_id=submodel_id or f"urn:sizer:idta02021:{design.name}",
        project=result.design_name or design.stem, tool=f"sizer {__version__}",
        created=now)
    if aasx:
        from sizer.idta.aasx import aasx_package

        write_bytes_atomically(output, aasx_package(submodel, created=date,
                                                    creator=f"sizer {__version__}"))
    else:
        write_text_atomically(output, json.dumps(submodel, indent=2, ensure_ascii=False)
                              + "\n")
    if not pair.feasible:
        typer.echo(f"no feasible pair: wrote {record['motor']} ({pair.reason})", err=True)
        raise typer.Exit(int(ExitCode.CHECK_FAILED))


def register(app: typer.Typer) -> None:
    app.add_typer(idta_app, name="idta")
