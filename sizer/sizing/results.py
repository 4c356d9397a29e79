"""Results of sizing: plain data that reports format (no computation there)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from sizer.model.domain import Motor, ServoDrive, Transmission
from sizer.sizing.checks import TOLERANCE

if TYPE_CHECKING:
    from collections.abc import Sequence

    from sizer.laws import MotionLaw
    from sizer.sizing.table import CandidateTable

NOT_AVAILABLE = "n/a"
"""The text of a figure that does not exist (an unbounded requirement, no feasible
duration); the reason goes with it (Check.undefined_reason, CandidateResult.reason)."""

UNBOUNDED_WHY = {"jerk": "the law has jerk impulses",
                 "inertia_ratio": "the motor's inertia is 0",
                 "peak": "the move needs torque at a speed where the intermittent region "
                         "gives none"}
"""Why a check's value can be infinite, by check name."""


def margin_percent(margin: float, decimals: int = 2, *, failed: bool = False,
                   required: float = 0.0) -> str:
    """A margin in % with ``decimals`` decimals ('12.50').

    A failing margin gets as many more decimals as it takes to show it below the required
    one (visibly negative for required 0: '-0.0001', never '-0.00'); a passing margin never
    shows a minus sign on zero.
    """
    if not math.isfinite(margin):
        return NOT_AVAILABLE
    value = 100.0 * margin
    text = f"{value:.{decimals}f}"
    if failed:
        while float(text) >= 100.0 * required and decimals < 20:
            decimals += 1
            text = f"{value:.{decimals}f}"
    elif float(text) == 0.0:
        text = text.lstrip("-")
    return text


@dataclass(frozen=True, slots=True)
class Check:
    """One limit checked for a candidate. margin = 1 - value/limit (capability left unused).

    The check passes when margin >= required - TOLERANCE (sizer.sizing.checks: the one
    tolerance of every verdict, so that a requirement equal to its rating passes).
    """

    name: str
    value: float
    limit: float
    unit: str
    margin: float
    required: float = 0.0
    note: str = ""
    """Why it fails when the numbers do not say it (sizer.sizing.checks.CheckArrays)."""

    @property
    def slack(self) -> float:
        return self.margin - self.required

    @property
    def passed(self) -> bool:
        return self.slack >= -TOLERANCE

    @property
    def undefined_reason(self) -> str | None:
        """Why the value or margin is no finite number (None when both are finite)."""
        if math.isfinite(self.value) and math.isfinite(self.margin):
            return None
        if math.isnan(self.value) or math.isnan(self.margin):
            return f"{self.name}: not computable for this candidate"
        if math.isfinite(self.value) and self.limit == 0.0:
            unit = f" {self.unit}" if self.unit else ""
            return (f"{self.name}: {self.value:.6g}{unit} needed where the motor gives none "
                    f"(margin unbounded)")
        why = UNBOUNDED_WHY.get(self.name, "beyond the range of a float")
        return f"{self.name}: unbounded ({why})"

    def describe(self) -> str:
        """One line: which limit, the values, and by how much it passes or fails."""
        unit = f" {self.unit}" if self.unit else ""
        if self.note and not self.passed:
            return f"{self.name}: {self.note} (FAILS)"
        undefined = self.undefined_reason
        if undefined is not None:
            verdict = "ok" if self.passed else "FAILS"
            return f"{undefined} against {self.limit:.6g}{unit} ({verdict})"
        verdict = "ok" if self.passed else "FAILS"
        need = f", {self.required:.0%} required" if self.required else ""
        margin = margin_percent(self.margin, failed=not self.passed, required=self.required)
        return (f"{self.name}: {self.value:.6g}{unit} against {self.limit:.6g}{unit}, "
                f"margin {margin}%{need} ({verdict})")


@dataclass(frozen=True, slots=True)
class CandidateResult:
    """A motor with a law: its duration, requirements at the motor shaft and checks.

    ``ratio`` is the total transmission ratio K (motor speed over load speed: rad/rad, or
    rad/m on a linear axis), ``gearbox`` the catalog gearbox chosen if any; ``load_speed``
    and ``load_torque`` are the peak speed and peak torque (force on a linear axis) at the
    load. ``transmission`` is the one the result was computed with (the design's, or with
    the chosen ratio or catalog gearbox in place). ``rated_power`` (tau_c*v_n, W),
    ``continuous_torque`` (N*m) and ``rotor_inertia`` (kg*m^2) are the motor's, for ranking
    by size.
    """

    motor: str
    law: str
    spec: str
    params: dict[str, float]
    feasible: bool
    duration: float | None
    peak_torque: float | None
    rms_torque: float | None
    max_speed: float | None
    checks: tuple[Check, ...]
    limiting: str | None
    reason: str = ""
    price: float | None = None
    mass: float | None = None
    ratio: float = 1.0
    gearbox: str | None = None
    load_speed: float | None = None
    load_torque: float | None = None
    residual_vibration: float | None = None
    """The largest residual vibration of the moves at the load (m or rad), where the
    design gives the load's mode (sizer.sizing.vibration_check); None otherwise."""
    regenerated_energy: float | None = None
    """J per machine cycle returned to the DC bus, where the design has a braking check
    (sizer.sizing.energy_check); None otherwise."""
    braking_power: float | None = None
    """W: the braking resistor's continuous power, with the braking check; None otherwise."""
    winding_rise: float | None = None
    """K: the winding temperature rise of the heat check that applies (the thermal model's
    periodic peak, or the RMS-equivalent rise); None where the motor has no heat check."""
    peak_power: float | None = None
    """W: the largest motoring power at the motor shaft (tau*omega > 0), where the design
    has a braking or heat check; None otherwise. So are the next three."""
    mean_power: float | None = None
    """W: the motoring shaft power's mean over the machine cycle."""
    copper_loss: float | None = None
    """W: the mean copper loss, 3/2 R (tau/k_t)^2 (None where the motor lacks k_t or R)."""
    cycle_energy: float | None = None
    """J: the net energy drawn from the DC bus per machine cycle (motoring minus
    regenerated, copper included; None where the motor lacks k_t or R)."""
    stop_energy: float | None = None
    """J: what the largest stop returns to the bus, with the braking check."""
    braking_peak_power: float | None = None
    """W: the braking resistor's peak power (0 when the capacitors take every stop), with
    the braking check."""
    transmission: Transmission | None = None
    rated_power: float | None = None
    continuous_torque: float | None = None
    rotor_inertia: float | None = None
    extra: dict[str, float] = field(default_factory=dict)
    motor_object: Motor | None = field(default=None, compare=False, repr=False)
    """The motor itself (the catalog's object), so that no report looks it up by id."""
    law_object: MotionLaw | None = field(default=None, compare=False, repr=False)
    """The law itself, parsed once (its ``spec`` is the canonical text)."""
    drive: str | None = None
    """The id of the candidate's drive (amplifier), where the design has drives."""
    drive_object: ServoDrive | None = field(default=None, compare=False, repr=False)
    """The drive itself (the catalog's object)."""

    def check(self, name: str) -> Check | None:
        return next((c for c in self.checks if c.name == name), None)

    def margin(self, name: str) -> float | None:
        found = self.check(name)
        return None if found is None else found.margin

    @property
    def worst_slack(self) -> float:
        """The smallest margin beyond the required one, over all checks (ranking key)."""
        return min((c.slack for c in self.checks), default=math.inf)

    @property
    def slacks(self) -> tuple[float, ...]:
        """All slacks, smallest first: ties on the worst are broken by the next ones."""
        return tuple(sorted(c.slack for c in self.checks))


@dataclass(frozen=True)
class SizingResult:
    """All candidates of a design, ranked, with what the run assumed."""

    mode: str  # a sizer.sizing.table.Mode ("duration" or "minimize")
    results: Sequence[CandidateResult]
    """Ranked, best first (rows built when read: sizer.sizing.table.Rows)."""
    design_name: str = ""
    notes: tuple[str, ...] = ()
    table: CandidateTable | None = field(default=None, compare=False, repr=False)
    """The same candidates as arrays, in table order (None for hand-made results)."""

    @property
    def feasible(self) -> tuple[CandidateResult, ...]:
        if self.table is not None:  # ranked feasible first: a prefix of the rows
            return tuple(self.results[: int(np.count_nonzero(self.table.feasible))])
        return tuple(r for r in self.results if r.feasible)

    def to_records(self) -> list[dict[str, object]]:
        """One plain dict per candidate, ranked (JSON-ready numbers; None where unknown)."""
        from sizer.sizing.records import record

        return [record(r) for r in self.results]

    def to_dict(self) -> dict[str, object]:
        """The whole result as plain data: mode, design name, notes and the records."""
        return {"design": self.design_name, "mode": str(self.mode),
                "notes": list(self.notes), "candidates": self.to_records()}
