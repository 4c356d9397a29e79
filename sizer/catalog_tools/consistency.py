"""Does a motor's data agree with itself? The consistency checks of ``sizer catalog
validate`` (issue 35), each within a stated tolerance; what they find is a warning.

- k_t and k_e agree: a sinusoidal winding has k_t = sqrt(3) k_e (k_e the RMS line-to-line
  back-EMF per rad/s), a block-commutated one k_t = k_e;
- k_t x continuous_current = continuous_torque;
- k_t x peak_current >= peak_torque (above, the winding saturates: only a peak torque
  beyond k_t x peak_current is flagged);
- a printed continuous curve passes through the rated point: it reaches the rated speed,
  and its torque there reaches the continuous torque (unless the continuous torque is the
  curve's standstill torque: :func:`stall_convention`);
- the intermittent region holds the continuous one, both completed by the ``linear`` rule
  (sizer.envelope), by more than 3 % of the continuous torque nowhere.

Not checked: rated power = rated torque x rated speed (see :data:`NOT_CHECKED`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from sizer.envelope import continuous_region, intermittent_region
from sizer.model.domain import Curve, Motor

TOLERANCE = 0.03
"""3 %, issue 35's tolerance: printed figures of 2 to 3 significant digits round by at
most 0.5 % to 2.5 % each, so a larger disagreement is a mistake in the data (a unit, a
column, a convention), not rounding."""

TEMPERATURE_TOLERANCE = 0.15
"""15 % where the two figures are printed at different temperatures: k_t x a current
against a torque, and k_t against k_e. Makers print k_e (and often k_t) for a cold winding
and the rated torque, or k_t, for a warm one: the magnets of a winding 100 K warmer give
about 10 % less (NdFeB, -0.1 %/K), and the torque at a current is k_t (I - I_0), I_0 the
no-load (friction) current. Printed data of the bundled catalogs differ by up to 14.3 %
(Yaskawa SGM7G-13A: 0.891 N*m/A x 10.7 A against 8.34 N*m; Siemens 1FT7044-AK7: k_T
0.88 N*m/A hot against sqrt(3) k_E = 0.943 N*m/A cold; maxon EC: up to 11.8 %). The
conventions this check is for are larger: a peak for an RMS figure is sqrt(2) (41 %),
a phase for a line-to-line one sqrt(3) (73 %)."""

NOT_CHECKED = ("rated power = rated torque x rated speed: not checked, a catalog motor "
               "has no rated power field",)
"""The consistency checks of issue 35 that cannot run, and why."""

RPM_PER_RAD_S = 30.0 / math.pi

Found = list[tuple[tuple[Any, ...], str]]


@dataclass(frozen=True)
class ConsistencyCheck:
    """One check: its name, what it checks, and its findings in a motor (path, message)."""

    name: str
    checks: str
    find: Callable[[Motor], Found]


def _percent(ratio: float) -> str:
    return f"{abs(ratio - 1.0):.1%}"


def _rpm(speed: float) -> str:
    return f"{speed * RPM_PER_RAD_S:.5g} rpm"


def _torque_constants(m: Motor) -> Found:
    k_t, k_e = m.torque_constant, m.back_emf_constant
    if k_t is None or k_e is None:
        return []
    block = m.commutation == "block"
    expected = k_e if block else math.sqrt(3.0) * k_e
    if abs(k_t / expected - 1.0) <= TEMPERATURE_TOLERANCE:
        return []
    rule = "k_t = k_e" if block else "k_t = sqrt(3) k_e"
    return [(("back_emf_constant",),
             f"torque_constant {k_t:.4g} N*m/A and back_emf_constant {k_e:.4g} V*s/rad "
             f"disagree by {_percent(k_t / expected)}: a {m.commutation} winding has {rule} "
             f"= {expected:.4g} N*m/A (tolerance {TEMPERATURE_TOLERANCE:.0%})")]


def _continuous_current(m: Motor) -> Found:
    k_t, current = m.torque_constant, m.continuous_current
    if k_t is None or current is None:
        return []
    torque = k_t * current
    if abs(torque / m.continuous_torque - 1.0) <= TEMPERATURE_TOLERANCE:
        return []
    return [(("continuous_current",),
             f"torque_constant x continuous_current = {torque:.4g} N*m differs from the "
             f"continuous torque {m.continuous_torque:.4g} N*m by "
             f"{_percent(torque / m.continuous_torque)} (tolerance {TEMPERATURE_TOLERANCE:.0%})")]


def _peak_current(m: Motor) -> Found:
    k_t, current = m.torque_constant, m.peak_current
    if k_t is None or current is None:
        return []
    torque = k_t * current
    if m.peak_torque <= torque * (1.0 + TOLERANCE):
        return []
    return [(("peak_torque",),
             f"the peak torque {m.peak_torque:.4g} N*m exceeds torque_constant x "
             f"peak_current = {torque:.4g} N*m by {_percent(m.peak_torque / torque)} "
             f"(saturation only lowers it; tolerance {TOLERANCE:.0%})")]


def torque_at(curve: Curve, speed: float) -> float | None:
    """The piecewise linear torque of ``curve`` at ``speed``; None beyond its speeds."""
    if speed < curve[0][0] or speed > curve[-1][0]:
        return None
    for (s0, t0), (s1, t1) in itertools.pairwise(curve):
        if s0 <= speed <= s1:
            return t0 if s1 == s0 else t0 + (t1 - t0) * (speed - s0) / (s1 - s0)
    return curve[-1][1]


def stall_convention(m: Motor, curve: Curve) -> bool:
    """The continuous torque is the curve's standstill torque (M_0, as Siemens and
    Mitsubishi print it): the curve starts at 0 rpm within :data:`TOLERANCE` of it and
    falls from there to the rated torque, which no field states."""
    return curve[0][0] == 0.0 and abs(curve[0][1] / m.continuous_torque - 1.0) <= TOLERANCE


def _rated_point(m: Motor) -> Found:
    curve = m.continuous_curve
    if not curve or len(curve) < 2:
        return []
    torque = torque_at(curve, min(m.rated_speed, curve[-1][0]))
    if curve[-1][0] < m.rated_speed * (1.0 - TOLERANCE) or torque is None:
        return [(("continuous_curve",),
                 f"the continuous curve ({_rpm(curve[0][0])} to {_rpm(curve[-1][0])}) does "
                 f"not reach the rated speed {_rpm(m.rated_speed)} (tolerance "
                 f"{TOLERANCE:.0%})")]
    if torque >= m.continuous_torque * (1.0 - TOLERANCE) or stall_convention(m, curve):
        return []
    return [(("continuous_curve",),
             f"the continuous curve gives {torque:.4g} N*m at the rated speed "
             f"{_rpm(m.rated_speed)}, {_percent(torque / m.continuous_torque)} below the "
             f"continuous torque {m.continuous_torque:.4g} N*m (tolerance {TOLERANCE:.0%})")]


def _regions_nested(m: Motor) -> Found:
    continuous = continuous_region(m, "linear")
    intermittent = intermittent_region(m, "linear")
    top = min(continuous[-1][0], intermittent[-1][0])
    speeds = sorted({s for s, _ in (*continuous, *intermittent) if s <= top})
    allowed = TOLERANCE * m.continuous_torque  # relative to a torque that is not 0
    for speed in speeds:
        low, high = torque_at(continuous, speed), torque_at(intermittent, speed)
        if low is not None and high is not None and low - high > allowed:
            at = "continuous_curve" if m.continuous_curve else "continuous_torque"
            return [((at,), f"under the linear envelope rule the continuous region "
                            f"({low:.4g} N*m) is above the intermittent one ({high:.4g} "
                            f"N*m) at {_rpm(speed)} (tolerance {TOLERANCE:.0%})")]
    return []


CHECKS: tuple[ConsistencyCheck, ...] = (
    ConsistencyCheck("torque_constants", "k_t = sqrt(3) k_e (sinusoidal) or k_e (block)",
                     _torque_constants),
    ConsistencyCheck("continuous_current", "k_t x continuous_current = continuous_torque",
                     _continuous_current),
    ConsistencyCheck("peak_current", "peak_torque <= k_t x peak_current", _peak_current),
    ConsistencyCheck("rated_point", "the continuous curve reaches the continuous torque at "
                     "the rated speed", _rated_point),
    ConsistencyCheck("regions_nested_linear", "the intermittent region holds the continuous "
                     "one (linear rule)", _regions_nested),
)
"""Every consistency check, in the order of its findings."""


def inconsistencies(motor: Motor) -> Found:
    """The findings of every check of :data:`CHECKS` in ``motor`` (path, message)."""
    return [found for check in CHECKS for found in check.find(motor)]
