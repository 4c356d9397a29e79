"""The motor's torques on a C1-or-smoother cam export (codesys-xyva, siemens-tcpu): the
written file read back as a law, as a user would, and the pair sized on it
(sizer.export.resized); what the certificate records and prints of them.

Shared by sizer.cli.cam_smooth and sizer.cli.cam_coefficients; decides nothing the export
layer does not.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sizer.report.printable import printable

if TYPE_CHECKING:
    from sizer.export.profile import CamProfile
    from sizer.export.resized import Resized
    from sizer.sizing.results import CandidateResult

LAW_ALONE = "a law alone: no motor to size"
CYCLE_WITHOUT_PAIR = "a cycle without a sized pair: no motor to size"

SpecOf = Callable[[tuple[float, float] | None], str]
"""The law spec that reads the written file back (with a span: the rows of one move)."""


def resized_export(spec_of: SpecOf, *, what: str, cycle: CamProfile | None, task: Any,
                   pair: CandidateResult | None, design: Path | None,
                   catalog: list[str] | None
                   ) -> tuple[Resized | None, str | None, list[str | None] | None]:
    """(the re-sizing, why there is none, the cycle's per-segment specs): a design's cycle
    of segments re-sized move by move on the file's spans; a single move on the whole
    file; nothing for a law alone or the task's ``--cycle`` (the file is not the move the
    motor was sized for). ``what`` names the file ('table', 'segments')."""
    if cycle is not None:
        if pair is None or design is None:
            return None, CYCLE_WITHOUT_PAIR, None
        from sizer.cli.cam_cycle import resized_cycle

        resized, specs = resized_cycle(design, catalog, pair, cycle, spec_of)
        return resized, None, specs
    if pair is None or design is None:
        return None, LAW_ALONE, None
    if task is not None:
        return None, (f"--cycle: the {what} is the whole machine cycle, not the move the "
                      f"motor was sized for; export the move alone for its torques"), None
    from sizer import api
    from sizer.export.resized import resize
    from sizer.laws import make_law

    spec = spec_of(None)
    make_law(spec)  # read back here: a file that does not read is said before sizing
    return resize(api.load(design, catalog or ()), pair, spec), None, None


def figures(result: CandidateResult) -> dict[str, Any]:
    """A result's torques and margins as the certificate records them."""
    return {"feasible": result.feasible,
            "peak_torque_Nm": result.peak_torque, "rms_torque_Nm": result.rms_torque,
            "margins": {str(c.name): {"margin": c.margin, "required": c.required,
                                      "passed": c.passed} for c in result.checks}}


def torques_record(resized: Resized | None, skipped: str | None, spec: str
                   ) -> dict[str, Any]:
    """The certificate's ``torques``: the sized law's and the exported file's (read back by
    ``spec``), and the checks the file fails that the law passed; or why none."""
    if resized is None:
        return {"computed": False, "why": skipped}
    return {"computed": True, "law": figures(resized.law),
            "exported": figures(resized.exported), "exported_spec": spec,
            "newly_failed": list(resized.newly_failed)}


def torque_lines(torques: dict[str, Any], exported: str) -> list[str]:
    """The certificate's lines on the torques (``exported`` names the file: 'exported
    table')."""
    if not torques["computed"]:
        return [f"torques: not re-computed ({torques['why']})"]
    lines = []
    for name, found in (("sized law", torques["law"]), (exported, torques["exported"])):
        margins = ", ".join(f"{k} {100 * m['margin']:.4g} %" + ("" if m["passed"] else " FAILS")
                            for k, m in found["margins"].items())
        lines.append(f"{name}: peak torque {_nm(found['peak_torque_Nm'])}, RMS "
                     f"{_nm(found['rms_torque_Nm'])}; margins: {margins}")
    if torques["newly_failed"]:
        lines.append(f"the {exported} FAILS " + ", ".join(torques["newly_failed"])
                     + ", which the sized law passed")
    return lines


def newly_failed_message(output: Path, resized: Resized | None) -> str | None:
    """What the command says (exit 1) when the exported profile fails a check the law
    passed; None when it does not."""
    if resized is None or not resized.newly_failed:
        return None
    return printable(f"{output}: the exported profile fails "
                     f"{', '.join(resized.newly_failed)}, which the sized law passed")


def _nm(value: float | None) -> str:
    return "-" if value is None else f"{value:.6g} N*m"
