"""One motor/law result (a CandidateResult) as a JSON object, CSV cells and table cells.

JSON and CSV are SI (s, N*m, rad/s) with margins as fractions; the display cells are for
people: duration in ms, speed in rpm, margins in %. A figure that does not exist
(no feasible duration, an unbounded requirement) is null in JSON with the reason beside it
(the result's ``reason``, a check's ``reason``), ``n/a`` in tables and an empty cell in
CSV (with the ``reason`` column); never ``nan`` or ``inf``.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from sizer.laws.base import format_parameter
from sizer.laws.data_spec import data_law_label, is_data_spec
from sizer.report.numbers import finite_or_none, full_or_empty, short_or_na
from sizer.sizing.checks import TOLERANCE, CheckName
from sizer.sizing.results import NOT_AVAILABLE, margin_percent

if TYPE_CHECKING:
    from sizer.sizing import CandidateResult, Check

RPM_PER_RAD_S = 30.0 / math.pi
"""rev/min per rad/s, for display."""

MARGINS = (CheckName.PEAK, CheckName.RMS, CheckName.SPEED)
"""The margins every row shows, by check name."""

CSV_HEADERS = (
    "rank", "motor", "law", "spec", "feasible", "duration [s]", "peak_torque [N*m]",
    "rms_torque [N*m]", "max_speed [rad/s]", "margin_peak [1]", "margin_rms [1]",
    "margin_speed [1]", "limiting", "reason", "price", "mass [kg]", "ratio", "gearbox",
    "envelope", "front",
)
"""``envelope`` is the rule that completed the regions of motors without curves
(sizer.envelope.completion), so that a CSV states what it assumed as the table does;
``front`` where the pair stands on the trade-off front (sizer.sizing.front: ``knee``,
``front`` or empty)."""


def summary_margin(result: CandidateResult, name: str) -> float | None:
    """The margin of a check for the summary columns; None where no duration is feasible.

    In minimize mode an infeasible pair has no duration: its checks describe the longest
    duration tried, which is no real operating point, so the summary leaves them out
    (the ``checks`` list of the JSON keeps them, with the reason).
    """
    if result.duration is None:
        return None
    return result.margin(name)


def check_passed(result: CandidateResult, check: Check) -> bool:
    """The check's verdict, as the engine decided it (``Check.passed``)."""
    return check.passed


def check_line(result: CandidateResult, check: Check) -> str:
    """``Check.describe()``: the engine's verdict and margin."""
    return check.describe()


def check_json(result: CandidateResult, check: Check) -> dict[str, Any]:
    return {
        "name": check.name,
        "value": finite_or_none(check.value),
        "limit": finite_or_none(check.limit),
        "unit": check.unit,
        "margin": finite_or_none(check.margin),
        "required": float(check.required),
        "passed": check_passed(result, check),
        "reason": check.undefined_reason,
    }


def result_json(result: CandidateResult, front: str | None = None) -> dict[str, Any]:
    """The JSON object of one pair, keys in a fixed order, SI units (``drive`` after
    ``motor`` where the design has drives; ``front`` after ``feasible`` when given: where
    the pair stands on the trade-off front, ``knee``, ``front`` or '')."""
    return {
        "motor": result.motor,
        **({"drive": result.drive} if result.drive is not None else {}),
        "law": result.law,
        "spec": result.spec,
        "params": {name: float(value) for name, value in result.params.items()},
        "feasible": bool(result.feasible),
        **({"front": front} if front is not None else {}),
        "duration": finite_or_none(result.duration),
        "peak_torque": finite_or_none(result.peak_torque),
        "rms_torque": finite_or_none(result.rms_torque),
        "max_speed": finite_or_none(result.max_speed),
        **{f"margin_{name}": finite_or_none(summary_margin(result, name))
           for name in MARGINS},
        "limiting": result.limiting,
        "reason": result.reason,
        "price": finite_or_none(result.price),
        "mass": finite_or_none(result.mass),
        "rated_power": finite_or_none(result.rated_power),
        "ratio": finite_or_none(result.ratio),
        "gearbox": result.gearbox,
        "load_speed": finite_or_none(result.load_speed),
        "load_torque": finite_or_none(result.load_torque),
        "checks": [check_json(result, check) for check in result.checks],
    }


def result_csv_cells(rank: int, result: CandidateResult, envelope: str = "",
                     front: str = "") -> tuple[str, ...]:
    """CSV cells at full precision (SI), in the order of CSV_HEADERS (``front``: the
    pair's place on the trade-off front, ``knee``, ``front`` or '')."""
    return (
        str(rank), result.motor, result.law, result.spec,
        "true" if result.feasible else "false",
        full_or_empty(result.duration), full_or_empty(result.peak_torque),
        full_or_empty(result.rms_torque), full_or_empty(result.max_speed),
        *(full_or_empty(summary_margin(result, name)) for name in MARGINS),
        result.limiting or "", result.reason,
        full_or_empty(result.price), full_or_empty(result.mass),
        full_or_empty(result.ratio), result.gearbox or "", envelope, front,
    )


def percent(fraction: float | None) -> str:
    """A margin in % with one decimal: '12.5', 'n/a' when missing or not finite.

    A negative margin beyond the checks' tolerance (a failing one) shows enough decimals
    to be visibly negative ('-0.0001'); one within it reads '0.0'.
    """
    if fraction is None:
        return NOT_AVAILABLE
    return margin_percent(fraction, 1, failed=fraction < -TOLERANCE)


def display_spec(result: CandidateResult) -> str:
    """The law spec for a table: a parameter chosen by the solver (full precision in JSON
    and CSV) shown to 4 significant digits."""
    if is_data_spec(result.spec):
        return data_law_label(result.spec)
    texts = {k: format_parameter(v) for k, v in result.params.items()}
    if all(len(t) <= 8 for t in texts.values()):
        return result.spec
    args = ", ".join(f"{k}={t if len(t) <= 8 else f'{result.params[k]:.4g}'}"
                     for k, t in texts.items())
    return f"{result.law}({args})"


def result_display_cells(rank: int, result: CandidateResult, *, ratio: str | None = None,
                         with_drive: bool = False) -> tuple[str, ...]:
    """Cells for a table: rank, motor, law, feasible, T [ms], torques, rpm, margins [%].

    ``ratio``: the transmission's cell after the law (when it varies by pair: the free
    stage's ratio as listed, sizer.report.transmission_text); with ``with_drive`` the
    drive follows the motor.
    """
    ratio_cell = () if ratio is None else (ratio,)
    drive = (result.drive or "",) if with_drive else ()
    return (
        str(rank), result.motor, *drive, display_spec(result), *ratio_cell,
        "yes" if result.feasible else "no",
        short_or_na(result.duration, 1000.0), short_or_na(result.peak_torque),
        short_or_na(result.rms_torque), short_or_na(result.max_speed, RPM_PER_RAD_S),
        *(percent(summary_margin(result, name)) for name in MARGINS),
        result.limiting or "",
    )
