"""Cam tables (issue 13): the spline fit of samples and its report (sample_fit)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.interpolate import make_interp_spline

from sizer.errors import UserError
from sizer.laws.multipoint.sample_fit import build_cam_table_samples, fit_samples

TAU = np.linspace(0.0, 1.0, 201)
CYCLOIDAL = TAU - np.sin(2.0 * np.pi * TAU) / (2.0 * np.pi)
DENSE = np.linspace(0.0, 1.0, 200_001)


def _rms(values: np.ndarray) -> float:
    """sqrt of the integral over [0, 1] of values^2 on DENSE (trapezoid rule)."""
    return math.sqrt(np.trapezoid(values ** 2, DENSE))


@pytest.mark.parametrize("order", [5, 6, 7, 8, 9, 10])
def test_cycloidal_table_gives_back_the_cycloidal_coefficients(order: int) -> None:
    curve = fit_samples(TAU, CYCLOIDAL, order=order).curve
    v, a = curve(DENSE, 1), curve(DENSE, 2)
    assert np.max(np.abs(v)) == pytest.approx(2.0, abs=1e-4)                  # C_v
    assert np.max(np.abs(a)) == pytest.approx(2.0 * np.pi, abs=1e-4)          # C_a
    assert _rms(v) == pytest.approx(math.sqrt(1.5), abs=1e-4)                 # C_v_rms
    assert _rms(a) == pytest.approx(math.sqrt(2.0) * np.pi, abs=1e-4)         # C_a_rms


def test_report_gives_the_rms_of_velocity_acceleration_and_jerk() -> None:
    fit = fit_samples(TAU, CYCLOIDAL)
    # closed forms: v = 1 - cos(2 pi t), a = 2 pi sin, j = 4 pi^2 cos
    assert fit.derivative_rms == pytest.approx(
        (math.sqrt(1.5), math.sqrt(2.0) * np.pi, 4.0 * np.pi ** 2 / math.sqrt(2.0)),
        rel=1e-5)


def test_default_is_a_quintic_c4_curve_over_the_samples() -> None:
    fit = fit_samples(TAU, CYCLOIDAL)
    assert fit.order == 6 and fit.degree == 5 and fit.curve.c.shape[0] == 6
    curve = fit.curve
    assert curve.x[0] == 0.0 and curve.x[-1] == 1.0 and np.all(np.diff(curve.x) > 0)
    inner = curve.x[1:-1]
    eps = 1e-9
    for nu in range(5):  # C4: derivatives 0..4 continuous across every breakpoint
        jump = np.abs(curve(inner + eps, nu) - curve(inner - eps, nu))
        assert np.max(jump) < 1e-4 * (1 + np.max(np.abs(curve(inner, nu))))
    assert np.all(curve(TAU, 6) == 0.0)  # beyond the degree


@pytest.mark.parametrize("order", [2, 3, 4, 5, 6, 7, 8, 9, 10])
def test_interpolation_has_zero_residual(order: int) -> None:
    rng = np.random.default_rng(3)
    x = np.cumsum(rng.uniform(0.5, 1.5, 40))
    q = rng.standard_normal(40)
    fit = fit_samples(x, q, order=order)
    # random data make a wildly oscillating interpolant of high degree: rounding grows
    assert fit.max_residual < 1e-10 and fit.rms_residual < 1e-10
    assert np.max(np.abs(fit.curve(x) - q)) < 1e-10


def test_clean_samples_have_negligible_derivative_noise() -> None:
    fit = fit_samples(TAU, CYCLOIDAL)
    assert fit.noise_sigma < 1e-10
    assert max(fit.noise_rms) < 1e-3 and max(fit.noise_peak) < 1e-2


def test_derivative_noise_is_positive_and_grows_with_the_noise_amplitude() -> None:
    rng = np.random.default_rng(7)
    unit = rng.standard_normal(TAU.size)
    reports = [fit_samples(TAU, CYCLOIDAL + amplitude * unit)
               for amplitude in (1e-7, 1e-6, 1e-5)]
    for small, large in itertools.pairwise(reports):
        assert small.noise_sigma < large.noise_sigma
        for k in range(3):
            assert 0.0 < small.noise_rms[k] < large.noise_rms[k]
            assert 0.0 < small.noise_peak[k] < large.noise_peak[k]
    # the noise estimate is near the noise added (a median of 195 pseudo-residuals)
    assert reports[1].noise_sigma == pytest.approx(1e-6 * np.std(unit), rel=0.3)


def test_derivative_noise_matches_the_deviation_the_noise_causes() -> None:
    """Independent: interpolate noisy copies with scipy directly and measure how far
    their derivatives are from those of the clean interpolant."""
    sigma = 1e-6
    rng = np.random.default_rng(11)
    clean = make_interp_spline(TAU, CYCLOIDAL, k=5)
    grid = np.linspace(0.0, 1.0, 20_001)
    deviation = np.zeros(3)
    reported = np.zeros(3)
    draws = 8
    for _ in range(draws):
        noisy = CYCLOIDAL + sigma * rng.standard_normal(TAU.size)
        spline = make_interp_spline(TAU, noisy, k=5)
        deviation += [_rms_on(grid, spline(grid, k) - clean(grid, k)) ** 2 for k in (1, 2, 3)]
        fit = fit_samples(TAU, noisy)  # relative to the noisy fit's own RMS: undo it
        reported += (np.array(fit.noise_rms) * np.array(fit.derivative_rms)) ** 2
    assert np.sqrt(reported / draws) == pytest.approx(np.sqrt(deviation / draws), rel=0.15)


def _rms_on(grid: np.ndarray, values: np.ndarray) -> float:
    return math.sqrt(np.trapezoid(values ** 2, grid) / (grid[-1] - grid[0]))


def test_smoothing_meets_its_rms_residual_with_fewer_pieces_and_less_noise() -> None:
    rng = np.random.default_rng(5)
    noisy = CYCLOIDAL + 1e-4 * rng.standard_normal(TAU.size)
    exact = fit_samples(TAU, noisy)
    smooth = fit_samples(TAU, noisy, smoothing=1e-4)
    assert smooth.rms_residual == pytest.approx(1e-4, rel=1e-2)
    assert len(smooth.curve.x) < len(exact.curve.x) / 10
    for k in range(3):
        assert smooth.noise_rms[k] < exact.noise_rms[k] / 10
    # and the smoothed curve is near the law itself
    assert np.max(np.abs(smooth.curve(DENSE, 1) - (1 - np.cos(2 * np.pi * DENSE)))) < 0.02


@pytest.mark.parametrize("order", [4, 6, 7])
def test_periodic_fit_repeats_its_derivatives(order: int) -> None:
    q = np.cos(2 * np.pi * TAU) + 0.3 * np.sin(4 * np.pi * TAU) ** 3
    q[-1] = q[0]
    fit = fit_samples(TAU, q, order=order, periodic=True)
    assert fit.max_residual < 1e-12
    ends = np.array([0.0, 1.0])
    for nu in range(order - 1):  # C^(k-1) across the period
        values = fit.curve(ends, nu)
        assert values[0] == pytest.approx(values[1], rel=1e-7, abs=1e-9)


def test_periodic_table_may_rise_by_a_stroke_per_period() -> None:
    # a rotary knife: one turn per cycle, 30 % faster than the mean at the cut
    # q = 2 pi tau + 0.3 sin(2 pi tau): v = 2 pi (1 + 0.3 cos 2 pi tau) repeats, q does not
    q = 2 * np.pi * TAU + 0.3 * np.sin(2 * np.pi * TAU)
    fit = fit_samples(TAU, q, order=6, periodic=True)
    assert fit.max_residual < 1e-12
    ends = np.array([0.0, 1.0])
    assert np.diff(fit.curve(ends))[0] == pytest.approx(2 * np.pi, rel=1e-12)
    for nu in range(1, 5):  # C4 across the period
        values = fit.curve(ends, nu)
        assert values[0] == pytest.approx(values[1], rel=1e-7, abs=1e-7)
    v = 2 * np.pi * (1 + 0.3 * np.cos(2 * np.pi * DENSE))
    assert np.max(np.abs(fit.curve(DENSE, 1) - v)) < 1e-6


def test_too_few_samples_for_the_order() -> None:
    with pytest.raises(UserError, match="order 6 needs at least 6 samples, got 5") as caught:
        fit_samples(TAU[:5], CYCLOIDAL[:5])
    assert caught.value.field == "order"
    with pytest.raises(UserError, match=r"needs at least 5 samples \(periodic\), got 4"):
        fit_samples(np.arange(4.0), np.array([0.0, 1.0, 2.0, 0.0]), order=4, periodic=True)


def test_x_not_increasing_names_the_sample() -> None:
    x = np.array([0.0, 0.1, 0.2, 0.2, 0.4, 0.5, 0.6])
    with pytest.raises(UserError, match=r"sample 3 has x = 0.2 after x = 0.2") as caught:
        fit_samples(x, x ** 2)
    assert caught.value.field == "x"


@pytest.mark.parametrize("bad", [math.nan, math.inf])
def test_non_finite_samples_are_refused(bad: float) -> None:
    q = CYCLOIDAL.copy()
    q[17] = bad
    with pytest.raises(UserError, match="sample 17 has q") as caught:
        fit_samples(TAU, q)
    assert caught.value.field == "q"


def test_fields_choose_the_fit() -> None:
    fit = build_cam_table_samples({"kind": "cam_table", "order": 4, "periodic": False},
                                  TAU, CYCLOIDAL)
    assert fit.order == 4 and fit.curve.c.shape[0] == 4 and not fit.periodic
    smooth = build_cam_table_samples({"smoothing": 1e-3}, TAU, CYCLOIDAL)
    assert smooth.smoothing == 1e-3
    plain = build_cam_table_samples({"smoothing": 0}, TAU, CYCLOIDAL)
    assert plain.smoothing is None and plain.max_residual < 1e-12


@pytest.mark.parametrize(("fields", "field", "message"), [
    ({"order": 1}, "order", "between 2 and 10"),
    ({"order": 11}, "order", "between 2 and 10"),
    ({"order": 4.5}, "order", "must be an integer"),
    ({"smoothing": -1e-3}, "smoothing", "must be in"),
    ({"smoothing": "a lot"}, "smoothing", "must be a number"),
    ({"periodic": "yes"}, "periodic", "true or false"),
])
def test_bad_fields(fields: dict, field: str, message: str) -> None:
    with pytest.raises(UserError, match=message) as caught:
        build_cam_table_samples(fields, TAU, CYCLOIDAL)
    assert caught.value.field == field
