"""A law whose acceleration is linear on every piece (sizer.laws.linear_peaks.
linear_acceleration: the trapezoid, the double S, constant acceleration) reads its least
and largest a_N and its least v_N from its pieces, with the floats its linear peaks give
from their samples and hull; the engine then peaks a torque affine in the acceleration
(an ideal drive with friction, a constant load) on flat regions without building the
hull, and its answers are those the hull gives, bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.laws import make_law
from sizer.laws.linear_peaks import LinearPeaks, linear_acceleration
from sizer.laws.piecewise_polynomial import DoubleS, Trapezoidal
from sizer.model import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing import size_design


def _laws(seed: int) -> list:
    rng = np.random.default_rng(seed)
    out = [make_law("constant_acceleration")]
    for _ in range(6):
        a, d = rng.uniform(1e-3, 0.5, 2)
        b, e = rng.uniform(1e-3, 0.5, 2)
        out += [Trapezoidal(alpha=a), Trapezoidal(alpha=a, alpha_d=d), DoubleS(alpha=a, beta=b),
                DoubleS(alpha=a, beta=b, alpha_d=d, beta_d=e)]
    return out


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_extremes_are_the_linear_peaks_own(seed: int) -> None:
    rng = np.random.default_rng(seed)
    for law in _laws(seed):
        found = linear_acceleration(law)
        assert found is not None, law.spec
        hull = LinearPeaks(law)
        assert found.highest == float(hull.maximum(1.0, 0.0).value)
        assert found.lowest == float(hull.minimum(1.0, 0.0).value)
        assert found.slowest == pytest.approx(float(hull.minimum(0.0, 1.0).value), abs=1e-15)
        p = rng.normal(size=200) * 10.0 ** rng.uniform(-3, 3, 200)
        p[:3] = (0.0, -0.0, 1.0)
        ours = np.where(p >= 0.0, p * found.highest, p * found.lowest)
        assert np.array_equal(ours, hull.maximum(p, np.zeros_like(p)).value)


def test_the_extremes_of_a_trapezoid_are_its_closed_forms() -> None:
    """Book sec. 3.2, 6.2.1: a_max = 1/(alpha (1 - alpha)) on [0, alpha], v_N >= 0."""
    alpha = 0.2
    found = linear_acceleration(Trapezoidal(alpha=alpha))
    assert found is not None
    assert found.highest == pytest.approx(1.0 / (alpha * (1.0 - alpha)), rel=1e-15)
    assert found.lowest == pytest.approx(-1.0 / (alpha * (1.0 - alpha)), rel=1e-15)
    assert found.slowest == 0.0


def test_laws_with_other_pieces_have_none() -> None:
    for spec in ("cycloidal", "poly5", "modified_sinusoidal", "harmonic",
                 "fifteen_segments(alpha=0.3, beta=0.2, gamma=0.25)"):
        law = make_law(spec)
        assert linear_acceleration(law) is None and law.linear_acceleration is None


def _design(spec: str, rows: bool, efficiency: float = 1.0) -> Design:
    """A gearbox (ideal, or lossy: a torque of two functions of the acceleration, one
    per power flow, and a belt after it), friction and a constant load, rectangular
    regions."""
    motors = tuple(Motor(f"m{i}", inertia=2e-5 * t**1.3, continuous_torque=t,
                         peak_torque=3 * t, rated_speed=3000 * math.pi / 30)
                   for i, t in enumerate(np.geomspace(0.2, 20.0, 9)))
    laws = (spec, "trapezoidal(alpha=0.25)", "double_s(alpha=0.3, beta=0.2)") if rows \
        else (spec,)
    return Design(Task(math.pi / 2, None, dwell=0.1, return_move=True),
                  Load(0.3, friction=0.4, torque=-0.2),
                  Transmission((Stage("gearbox", 8.0, efficiency, 1e-4),)
                               + ((Stage("belt", 1.5, 0.93, 2e-5),) if efficiency < 1.0
                                  else ())), laws=laws, motors=motors,
                  limits=Limits(torque_margin=0.1))


@pytest.mark.parametrize("rows", [False, True])
@pytest.mark.parametrize("efficiency", [1.0, 0.85])
def test_sizing_reads_no_hull_and_gives_the_hulls_answers(rows: bool, efficiency: float
                                                          ) -> None:
    """The same design sized with the laws' hulls (the extremes withheld: every law
    answers None) and without: the same records; without, no hull was built."""
    spec = "double_s(alpha=0.21, beta=0.17)"
    design = _design(spec, rows, efficiency)
    laws = [make_law(s) for s in design.laws]
    for law in laws:
        law.__dict__.pop("linear_peaks", None)
    fast = size_design(design).to_records()
    assert all("linear_peaks" not in law.__dict__ for law in laws)
    for law in laws:
        law.__dict__["linear_acceleration"] = None  # the cached property's slot
        law.__dict__.pop("_moves_backwards", None)
    try:
        slow = size_design(design).to_records()
        assert all("linear_peaks" in law.__dict__ for law in laws)
    finally:
        for law in laws:
            law.__dict__.pop("linear_acceleration", None)
    assert fast == slow
