"""``sizer diff``: what a change of a design did to its sizing (docs/design-diff.md).

Two design files (``sizer diff A.yaml B.yaml``), or one file at git revisions
(``sizer diff FILE --rev REV``: the file as committed at REV against the work tree's;
``--rev REV1 --rev REV2``: at REV1 against REV2). A revision is read with ``git show``
(nothing in the work tree, the index or the repository changes); its relative paths
(catalogs, cam tables, data laws) resolve from the file's folder in the work tree, like
the work tree's file, so both sides are sized against the same catalogs as they are now.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from sizer.cli.catalog_option import CatalogOption
from sizer.cli.exit_codes import ExitCode
from sizer.cli.options import EnvelopeOption, FormatOption, JobsOption, MotorsOption, OutputOption
from sizer.cli.size_command import RANK_HELP, LawsOption
from sizer.errors import UserError
from sizer.report.formats import Format

if TYPE_CHECKING:
    from sizer.model.domain import Design

GIT_TIMEOUT = 60.0
"""Seconds a git command may take."""

RevOption = Annotated[list[str] | None, typer.Option(
    "--rev", metavar="REV",
    help="Compare one design file at git revisions: once, the file as committed at REV "
         "(before) against the work tree's file (after); twice, at the first REV against "
         "the second. Read with 'git show'; the work tree and index are not touched. "
         "Relative paths in the design (catalogs...) resolve from its folder in the work "
         "tree, for both sides (a warning names a file that differs at REV).",
    show_default=False)]


@dataclass(frozen=True)
class Side:
    """One side of the diff: the design loaded (with the options), its file's mapping
    (for the design changes), its label and the path errors name."""

    design: Design
    data: Any
    label: str
    path: Path


def diff(
    design_a: Annotated[Path, typer.Argument(
        metavar="A.yaml", help="The design before the change (with --rev: the file).",
        show_default=False)],
    design_b: Annotated[Path | None, typer.Argument(
        metavar="[B.yaml]", help="The design after the change (not with --rev).",
        show_default=False)] = None,
    rev: RevOption = None,
    catalog: CatalogOption = None,
    motor: MotorsOption = None,
    law: LawsOption = None,
    rank_by: Annotated[str | None, typer.Option(
        "--rank-by", "-r", metavar="KEY",
        help="The ranking the pairs are listed in, within each status (rank in B; in A "
             "for a removed pair). " + RANK_HELP, show_default=False)] = None,
    envelope: EnvelopeOption = None,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
    jobs: JobsOption = None,
) -> None:
    """Size two versions of a design and show what the change did.

    Pairs (motor, law) that became feasible or infeasible, every margin's change of the
    pairs in both (each check's margin, the duration or T_min, peak and RMS torque, the
    chosen ratio or gearbox), the changed limiting checks, pairs only in one version, and
    the design fields that differ. Both versions are sized with the same options
    (--catalog, --motor, --law, --envelope, as in 'sizer size').

    Exit code 1 when a pair feasible before is infeasible after (a regression), 0
    otherwise; 2 for bad input. Fields, formats and what resolves where with --rev:
    docs/design-diff.md.

    Examples:

        sizer diff before.yaml after.yaml

        sizer diff examples/indexing-table.yaml --rev HEAD --format md

        sizer diff design.yaml --rev main --rev HEAD --format json -o diff.json
    """
    from sizer.cli.output_guard import check_output
    from sizer.cli.size_command import check_laws, check_rank_key, size_loaded
    from sizer.report.diff_report import DiffDocument, publish_diff
    from sizer.sizing.design_diff import design_changes, diff_sizings, ranked_choices

    check_rank_key(rank_by)
    check_laws(law or ())
    revs = list(rev or ())
    if revs and design_b is not None:
        raise UserError("with --rev give one design file (it is compared with itself at "
                        "the revisions), not two", field="--rev")
    if len(revs) > 2:
        raise UserError(f"at most twice (before and after), got {len(revs)} revisions",
                        field="--rev")
    if not revs and design_b is None:
        raise UserError("give two design files (A.yaml B.yaml), or one with --rev REV",
                        field="B.yaml")
    inputs = [design_a] + ([design_b] if design_b is not None else [])
    check_output(output, [*inputs, *(catalog or ())])
    if revs:
        before = _revision(design_a, revs[0], catalog, motor, law, envelope)
        after = (_revision(design_a, revs[1], catalog, motor, law, envelope) if len(revs) == 2
                 else _file(design_a, catalog, motor, law, envelope, output))
    else:
        assert design_b is not None
        before = _file(design_a, catalog, motor, law, envelope, output)
        after = _file(design_b, catalog, motor, law, envelope, output)
    _refuse_plans(before, after)
    sized = [size_loaded(side.path, side.design, rank_by, workers=jobs, laws=law)
             for side in (before, after)]
    result = diff_sizings(sized[0], sized[1], laws_a=ranked_choices(before.design),
                          laws_b=ranked_choices(after.design),
                          design=design_changes(before.data, after.data))
    publish_diff(DiffDocument(result, before.label, after.label), fmt, output)
    if result.regressions:
        raise typer.Exit(ExitCode.CHECK_FAILED)


def _refuse_plans(*sides: Side) -> None:
    """A design without motors (no motors, and the load's limits) is planned, not
    sized (docs/planning.md): no motor/law pairs to compare."""
    from sizer.sizing.planning import plans_without_motor

    for side in sides:
        if plans_without_motor(side.design):
            raise UserError("a design without motors (with the load's limits) is planned, "
                            "not sized: sizer diff compares the motor/law pairs of two sizings",
                            file=side.label)


def _file(path: Path, catalog: Sequence[str] | None, motor: Sequence[str] | None,
          law: Sequence[str] | None, envelope: str | None, output: Path | None) -> Side:
    """A design file of the work tree, loaded as ``sizer size`` loads it."""
    from sizer.cli.catalog_option import is_machine
    from sizer.cli.size_command import load_overridden
    from sizer.input_limits import MAX_DESIGN_BYTES, MAX_DESIGN_NODES
    from sizer.io.yaml_source import read_yaml

    if is_machine(path):
        raise UserError("a machine file (axes:): sizer diff compares design files",
                        file=str(path))
    loaded = load_overridden(path, catalog, motor, None, envelope=envelope,
                             outputs=() if output is None else (output,), laws=law)
    data = read_yaml(path, limit=MAX_DESIGN_BYTES, max_nodes=MAX_DESIGN_NODES).data
    return Side(loaded, data, str(path), path)


def _revision(path: Path, rev: str, catalog: Sequence[str] | None,
              motor: Sequence[str] | None, law: Sequence[str] | None,
              envelope: str | None) -> Side:
    """The design file ``path`` as committed at ``rev`` (``git show``), its relative paths
    resolved from the file's folder in the work tree; loaded with the options."""
    from sizer import api
    from sizer.cli.catalog_option import check_catalog_references
    from sizer.cli.options import as_option
    from sizer.cli.reporting import report_warnings
    from sizer.input_limits import MAX_DESIGN_NODES
    from sizer.io.loader import design_of_source
    from sizer.io.yaml_source import parse_yaml

    check_catalog_references(catalog or ())
    text = git_show(path, rev)
    label = f"{rev}:{path}"
    source = parse_yaml(text, file=label, max_nodes=MAX_DESIGN_NODES)
    if "axes" in source.data:
        raise UserError("a machine file (axes:): sizer diff compares design files",
                        file=label)
    folder = path.parent if str(path.parent) else Path(".")
    design = design_of_source(source, folder, path.stem, [], catalog or ())
    report_warnings((*design.warnings, *_differing_files(design.files, folder, rev, label)))
    with as_option("motors", "--motor"):
        design = api.override(design, motors=motor or None, envelope=envelope or None)
    if law:
        with as_option("laws", "--law"):
            design = api.override(design, laws=list(dict.fromkeys(law)))
    return Side(design, source.data, label, Path(label))


def _differing_files(files: Sequence[Path], folder: Path, rev: str, label: str
                     ) -> list[str]:
    """A warning per file the revision's design read (a catalog, a cam table...) from the
    work tree whose text at ``rev`` differs, or that is not in ``rev``: the diff sizes
    that side with the work tree's file (docs/design-diff.md). Files outside the folder's
    repository are not looked at."""
    git = shutil.which("git")
    if git is None:
        return []
    root = _run_git(git, folder, "rev-parse", "--show-toplevel")
    if root.returncode != 0:
        return []
    top = Path(root.stdout.decode().strip()).resolve()
    warnings = []
    for file in dict.fromkeys(Path(f).resolve() for f in files):
        try:
            inside = file.relative_to(top).as_posix()
        except ValueError:
            continue
        shown = _run_git(git, folder, "show", f"{rev}:{inside}")
        try:
            same = shown.returncode == 0 and shown.stdout == file.read_bytes()
        except OSError:
            same = False
        if not same:
            what = "differs from its version" if shown.returncode == 0 else "is not"
            warnings.append(f"{label}: {inside} {what} at {rev}; this side is sized with "
                            f"the work tree's (relative paths resolve in the work tree)")
    return warnings


def _run_git(git: str, folder: Path, *args: str) -> subprocess.CompletedProcess[bytes]:
    """``git -C folder args`` (no optional locks, no prompt); a UserError naming --rev
    when git cannot run."""
    env = {**os.environ, "GIT_OPTIONAL_LOCKS": "0", "GIT_TERMINAL_PROMPT": "0"}
    try:
        return subprocess.run([git, "-C", str(folder), *args], capture_output=True,
                              env=env, timeout=GIT_TIMEOUT, check=False)
    except (OSError, subprocess.TimeoutExpired) as error:
        raise UserError(f"git failed: {error}", field="--rev") from None


def git_show(path: Path, rev: str) -> str:
    """The text of ``path`` as committed at ``rev``, read with ``git show`` from the file's
    folder (read only: no lock taken, nothing written); a UserError naming --rev when git
    is missing, the folder is in no repository, the revision is unknown or the file is not
    in it."""
    from sizer.input_limits import MAX_DESIGN_BYTES

    if not rev or rev.startswith("-") or any(c in rev for c in "\n\r\0"):
        raise UserError(f"not a revision: {rev!r}", field="--rev")
    git = shutil.which("git")
    if git is None:
        raise UserError("git is not installed (or not on PATH)", field="--rev")
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise UserError(f"no folder {folder} in the work tree to read the revision from",
                        file=str(path), field="--rev")

    def run(*args: str) -> subprocess.CompletedProcess[bytes]:
        return _run_git(git, folder, *args)

    inside = run("rev-parse", "--is-inside-work-tree")
    if inside.returncode != 0 or inside.stdout.strip() != b"true":
        raise UserError(f"{folder} is not in a git work tree", file=str(path), field="--rev")
    commit = run("rev-parse", "--verify", "--quiet", "--end-of-options", f"{rev}^{{commit}}")
    if commit.returncode != 0:
        raise UserError(f"unknown revision {rev!r}", field="--rev")
    shown = run("show", f"{commit.stdout.decode().strip()}:./{path.name}")
    if shown.returncode != 0:
        raise UserError(f"{path} is not in revision {rev!r}", file=str(path), field="--rev")
    if len(shown.stdout) > MAX_DESIGN_BYTES:
        raise UserError(f"larger than {MAX_DESIGN_BYTES} bytes at revision {rev!r}",
                        file=str(path), field="--rev")
    try:
        return shown.stdout.decode("utf-8")
    except UnicodeDecodeError:
        raise UserError(f"not UTF-8 text at revision {rev!r}", file=str(path),
                        field="--rev") from None


def register(app: typer.Typer) -> None:
    app.command("diff")(diff)
