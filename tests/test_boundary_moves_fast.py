"""The faster exact moves between boundary speeds (issue 34).

- The roots in (0, 1) of rows of polynomials (sizer.sizing.move._unit_roots: safeguarded
  Newton steps in the derivative's brackets) are the roots the polynomials were built
  from, to 1e-9 (closed form: products of known linear factors and of quadratics with
  no real root; the products' coefficients are rounded).
- The peaks of the flying saw's moves between boundary speeds (polynomial_move, with
  its peak-ratio sub-pieces left out where they cannot exceed the ratio found) against
  an independent dense sampling of the same moves (SegmentCycle.pieces: the load's
  motion on samples, the torque through the drive's chain): never below it, and above
  by no more than the sampling's error (first order in the spacing where the torque
  jumps or the limit has a corner).
- The bound's grid read in slices from below (BOUND_CHUNKS) gives the bound of the whole
  grid read at once, to the bit.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sizer.io.loader import load_design
from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.model.cycle import Move
from sizer.sizing import cycle as cycle_module
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.cycle import SegmentCycle
from sizer.sizing.move import _most, _unit_roots

SAW = Path(__file__).resolve().parents[1] / "examples" / "flying-saw.yaml"


def _product(factors: list[np.ndarray]) -> np.ndarray:
    out = np.array([1.0])
    for f in factors:
        out = np.convolve(out, f)
    return out


@pytest.mark.parametrize("seed", range(8))
def test_unit_roots_are_the_roots_the_polynomials_were_built_from(seed):
    rng = np.random.default_rng(seed)
    rows, expected = [], []
    for _ in range(60):
        count = rng.integers(1, 6)
        # separated roots inside (0, 1); factors (u - r) in ascending powers: (-r, 1)
        roots = np.sort(rng.uniform(0.05, 0.95, count))
        if count > 1 and np.diff(roots).min() < 0.02:
            roots = np.linspace(0.1, 0.9, count)
        factors = [np.array([-r, 1.0]) for r in roots]
        if rng.random() < 0.5:  # a quadratic with no real root: (u - a)^2 + b^2
            a, b = rng.uniform(-1.0, 2.0), rng.uniform(0.1, 1.0)
            factors.append(np.array([a * a + b * b, -2.0 * a, 1.0]))
        if rng.random() < 0.3:  # a real root outside [0, 1]
            factors.append(np.array([-rng.uniform(1.2, 3.0), 1.0]))
        rows.append(rng.uniform(0.5, 20.0) * rng.choice([-1.0, 1.0]) * _product(factors))
        expected.append(roots)
    width = max(len(r) for r in rows)
    c = np.array([np.concatenate((r, np.zeros(width - len(r)))) for r in rows])
    found = _unit_roots(c)
    for got, want in zip(found, expected, strict=True):
        got = np.sort(got[np.isfinite(got)])
        assert len(got) == len(want)
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)  # the products' rounding


def test_unit_roots_where_solves_only_the_rows_asked_for():
    c = np.array([[-0.25, 1.0], [-0.5, 1.0], [-0.75, 1.0]])
    where = np.array([True, False, True])
    got = _unit_roots(c, where)
    np.testing.assert_allclose(got[where, 0], [0.25, 0.75], rtol=0, atol=1e-15)
    assert np.isnan(got[1, 0])


def test_most_is_the_largest_and_smallest_entry_of_the_last_axis():
    a = np.random.default_rng(3).normal(size=(7, 5, 6))
    np.testing.assert_array_equal(_most(a), a.max(axis=-1))
    np.testing.assert_array_equal(_most(a, np.minimum), a.min(axis=-1))


def _saw(spec: str):
    design = load_design(SAW)
    assert design.cycle is not None
    motors = MotorArrays.of(design.motors, design.limits.envelope)
    calc = SegmentCycle(design.cycle, make_law(spec), Drive(design.load, design.transmission),
                        motors, design.limits.thermal_speed)
    return design, calc


@pytest.mark.parametrize("spec", ["poly5", "trapezoidal(alpha=1/3)",
                                  "double_s(alpha=1/3, beta=1/4)"])
@pytest.mark.parametrize("scale", [0.2, 0.6, 2.0])
def test_boundary_move_peaks_match_a_dense_sampling(spec, scale):
    design, calc = _saw(spec)
    n = len(calc.motors)
    s = np.full(n, scale)
    figures = calc.figures(s)
    pieces = calc.pieces(s, samples=40001)
    for k, segment in enumerate(design.cycle.segments):
        if not isinstance(segment, Move) or segment.rest_to_rest:
            continue
        exact, sampled = figures[k], pieces[k]
        torque = np.abs(sampled.torque).max(axis=1)
        speed = np.abs(sampled.motor_speed).max(axis=1)
        limit = calc.motors.intermittent.limit_clipped(np.abs(sampled.motor_speed))
        with np.errstate(divide="ignore"):
            ratio = (np.abs(sampled.torque) / limit).max(axis=1)
        # never below a sample; above by no more than the samples' spacing allows (the
        # torque jumps where the speed changes sign, the limit has corners: first order)
        assert np.all(exact.peak_torque >= torque * (1.0 - 1e-12))
        np.testing.assert_allclose(exact.peak_torque, torque, rtol=1e-3)
        assert np.all(exact.max_speed >= speed * (1.0 - 1e-12))
        np.testing.assert_allclose(exact.max_speed, speed, rtol=1e-8)
        assert np.all(exact.peak_ratio >= ratio * (1.0 - 1e-12))
        np.testing.assert_allclose(exact.peak_ratio, ratio, rtol=1e-3)


def test_the_bound_read_in_slices_equals_the_whole_grid(monkeypatch):
    design, calc = _saw("poly5")
    start = calc.initial_guess()
    boundary = [i for i, s in enumerate(design.cycle.segments)
                if isinstance(s, Move) and not s.rest_to_rest]
    sliced = [calc._boundary_bound(i, design.limits, start) for i in boundary]
    span = 2 * cycle_module.BOUND_SPAN + 1
    monkeypatch.setattr(cycle_module, "BOUND_CHUNKS", ((0, span),))
    whole = [calc._boundary_bound(i, design.limits, start) for i in boundary]
    for a, b in zip(sliced, whole, strict=True):
        np.testing.assert_array_equal(a, b)
    assert any(np.any(a > 0.0) for a in sliced)  # some bound found
