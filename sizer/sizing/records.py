"""A result row as plain data (``SizingResult.to_records``): numbers in SI, None where a
figure does not exist (no NaN or inf), so that it serializes as JSON as it stands."""

from __future__ import annotations

import math

from sizer.sizing.energy_check import ENERGY_FIGURES
from sizer.sizing.results import CandidateResult, Check

FIELDS = ("motor", "law", "spec", "feasible", "duration", "peak_torque", "rms_torque",
          "max_speed", "load_speed", "load_torque", "ratio", "gearbox", "limiting", "reason",
          "price", "mass", "rated_power")
"""The keys of a record, in order (then the energy figures where the design has those
checks, ``params``, ``stage_ratio`` and ``checks``)."""


def _plain(value: object) -> object:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def check_record(check: Check) -> dict[str, object]:
    return {"name": check.name, "value": _plain(check.value), "limit": _plain(check.limit),
            "unit": check.unit, "margin": _plain(check.margin), "required": check.required,
            "passed": check.passed}


def record(result: CandidateResult) -> dict[str, object]:
    """One candidate: its fields, shape parameters and checks."""
    out = {name: _plain(getattr(result, name)) for name in FIELDS}
    if result.drive is not None:  # designs with drives (issue 16): the pair's drive
        out = {**dict(list(out.items())[:1]), "drive": result.drive,
               **dict(list(out.items())[1:])}
    for name in ENERGY_FIGURES:  # designs with braking or heat checks: their figures
        value = getattr(result, name)
        if value is not None:
            out[name] = _plain(float(value))
    out["params"] = {k: float(v) for k, v in result.params.items()}
    if "stage_ratio" in result.extra:
        out["stage_ratio"] = _plain(result.extra["stage_ratio"])
    out["checks"] = [check_record(c) for c in result.checks]
    return out
