"""``sizer cam --to twincat-mc3``: the law itself as the controller's motion functions, with
its certificate (sizer.export.twincat_mc3, docs/cam-export.md "TwinCAT 3 MC3").

Called by sizer.cli.cam_command once the move is known; formats and writes, decides
nothing the export layer does not.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from sizer.cli.cam_output import publish_certificate
from sizer.errors import UserError
from sizer.report.cam_certificate import record_head

if TYPE_CHECKING:
    from sizer.export.profile import CamProfile
    from sizer.laws.per_move import RankedLaw

EXACT = "exact (the law the controller names)"


def export_segments(name: str, law: RankedLaw, h: float, T: float, linear: bool,
                    master_range: float | None, task: Any, output: Path,
                    certificate: Path | None, pair: Any, tolerance: float | None,
                    points: int | None, profile: CamProfile | None = None) -> None:
    """Write the move (or with ``task``, its machine cycle; or the ``profile`` given, a
    cycle of segments: sizer.export.cycle_profile) as motion functions."""
    from sizer.export import twincat_mc3
    from sizer.export.profile import move_profile
    from sizer.report.output import write_text_atomically

    for option, given in (("--tolerance", tolerance), ("--points", points)):
        if given is not None:
            raise UserError(f"{name} writes the law's own segments, not a point table: "
                            f"leave out {option}", field=option)
    field = "SPEC" if pair is None else "--law"
    try:
        if profile is None:
            named = twincat_mc3.named_law(law)
            profile = move_profile(law, h, T, linear, master_range, task)
        else:  # a cycle of segments: each move's own law or the ranked one
            named = _cycle_named(profile)
        functions = twincat_mc3.motion_functions(profile)
    except twincat_mc3.UnnamedLawError as error:
        raise UserError(str(error), field=field) from None
    errors = twincat_mc3.exact_errors(profile, functions)
    record = certificate_record(profile, functions, errors, named, name, output, pair, T)
    if len(profile.segments) > 1 and _is_segment_cycle(profile):
        from sizer.cli.cam_cycle import with_cycle

        record = with_cycle(record, profile, T)
        for s, p in zip(record["segments"], functions, strict=False):
            s["function_type"] = p.function_type
    lines = certificate_text(record)
    write_text_atomically(output, twincat_mc3.write(functions, ["sizer cam", *lines]),
                          "--output")
    publish_certificate(record, lines, certificate)


def _is_segment_cycle(profile: CamProfile) -> bool:
    from sizer.export.cycle_profile import FrozenShape

    return any(isinstance(s.law, FrozenShape) for s in profile.segments)


def _cycle_named(profile: CamProfile) -> Any:
    """What the certificate says of a cycle's function types: the ranked law's if every
    move is it, else a summary (each segment's type is in its record)."""
    from sizer.export import twincat_mc3

    types = [twincat_mc3.segment_type(s.law, s.name) for s in profile.segments]  # or refused
    moves = [t for t, s in zip(types, profile.segments, strict=True) if s.law is not None
             and t != twincat_mc3.LINEAR]
    kinds = sorted(set(moves)) or [twincat_mc3.LINEAR]
    polynomial = all(t in twincat_mc3.POLYNOMIALS.values() for t in moves)
    basis = ("the only polynomial of its degree 2m+1 with the written end conditions "
             "(position, SlaveVelocity and, for degree 5 and 7, SlaveAcceleration, for 7 "
             "SlaveJerk: 2m+2 conditions); a run: Linear of its speed")
    if not polynomial:
        named = [twincat_mc3.named_law(s.law) for s in profile.segments
                 if s.law is not None and twincat_mc3.segment_type(s.law) in
                 ("Sinusoid", "ModifiedSinusoid")]
        return twincat_mc3.NamedLaw(", ".join(kinds), "per segment (see segments)",
                                    basis + "; " + "; ".join(n.basis for n in named), False)
    return twincat_mc3.NamedLaw(", ".join(kinds), "per segment (see segments)", basis, True)


def certificate_record(profile: CamProfile, functions: Any, errors: Any, named: Any,
                       name: str, output: Path, pair: Any, duration: float
                       ) -> dict[str, Any]:
    """The certificate as plain data (the JSON of --certificate)."""
    mu, su = profile.master_unit, profile.slave_unit
    peak_v, peak_a = profile.peak_velocity, profile.peak_acceleration
    return {
        **record_head(name, "TwinCAT 3 MC3 motion functions (IEC 61131-3 initialisation "
                      "code)", str(output), profile, None if pair is None else pair.motor,
                      duration),
        "segments": [{"name": s.name, "start": s.start, "span": s.span, "stroke": s.stroke,
                      "function_type": p.function_type}
                     for s, p in zip(profile.segments, functions, strict=False)],
        "points": len(functions),
        "function_type": named.function_type,
        "definition": named.formula,
        "identification": {"basis": named.basis, "confirmed": named.confirmed},
        "interpolation": {"kind": "segment-exact",
                          "source": "infosys.beckhoff.com TF55xx TC3 MC3: "
                                    "MotionFunctionPoint (21872070667), EMotionFunctionType "
                                    "(21872045067), MC_CAM_REF (21872066827)"},
        "verdict": EXACT,
        "errors": {
            "position": {"max": errors.position, "at": errors.at[0], "unit": su,
                         "of_stroke": errors.position / abs(profile.stroke)},
            "velocity": {"max": errors.velocity, "at": errors.at[1], "unit": f"{su}/{mu}",
                         "of_peak": errors.velocity / peak_v},
            "acceleration": {"max": errors.acceleration, "at": errors.at[2],
                             "unit": f"{su}/{mu}^2", "of_peak": errors.acceleration / peak_a},
            "checked_abscissae": errors.checked,
        },
        "expected_characteristics": {
            "note": "the extreme slave dynamics MC_CamObject.ComputeCharacteristics should "
                    "return for the controller's curve to be this law",
            "peak_velocity": peak_v, "peak_acceleration": peak_a,
            "velocity_unit": f"{su}/{mu}", "acceleration_unit": f"{su}/{mu}^2"},
        "torques": "the sizing's: the controller's curve is the sized law",
    }


def certificate_text(record: dict[str, Any]) -> list[str]:
    """The certificate as the command prints it, line by line."""
    master, errors = record["master"], record["errors"]
    pos, vel, acc = errors["position"], errors["velocity"], errors["acceleration"]
    mu, su = master["unit"], record["slave_unit"]
    who = "" if record["motor"] is None else f" sized for {record['motor']}"
    kinds = ", ".join(f"{s['name']} {s['function_type']}" for s in record["segments"])
    expected = record["expected_characteristics"]
    identification = record["identification"]
    lines = [
        f"{record['file']}: {record['title']}, {record['points']} points over "
        f"{master['span']:g} {mu} ({master['kind']}), {record['law']}{who}, stroke "
        f"{record['stroke']:g} {su}",
        f"segments: {kinds}; {record['function_type']} = {record['definition']}",
        f"identification: {identification['basis']}",
        f"{record['verdict']}: largest errors position {pos['max']:.3g} {su} "
        f"({pos['of_stroke']:.2g} of the stroke), velocity {vel['max']:.3g} {vel['unit']} "
        f"({vel['of_peak']:.2g} of the peak), acceleration {acc['max']:.3g} {acc['unit']} "
        f"({acc['of_peak']:.2g} of the peak), over {errors['checked_abscissae']} abscissae",
        f"expected ComputeCharacteristics: peak velocity "
        f"{expected['peak_velocity']:.6g} {expected['velocity_unit']}, peak acceleration "
        f"{expected['peak_acceleration']:.6g} {expected['acceleration_unit']}",
    ]
    if not identification["confirmed"]:
        lines.append("note: the function type's formula is not published by Beckhoff; "
                     "check the expected peaks on the controller")
    lines += [f"note: {n}" for n in record.get("notes", [])]
    return lines
