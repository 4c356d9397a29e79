"""The exact peak ratio of moves that leave the speed-torque region (sizer.sizing.cycle
CycleCalculator._leaving_ratio, from LinearPeaks.maximum_within and
ratio_maximum_within) against an independent computation: the ratio sampled densely
along the move, with the points where the speed crosses the region's end found by
scipy's brentq added to the samples (the ratio has a kink there).

Tolerance: 400,000 samples over tau in [0, 1] (plus the crossings) fall short of a smooth
maximum by at most (1/400,000)^2/8 * max|f''|, under 1e-10 relative for these moves (the
largest gap seen, 8e-11, shrinks to 2e-13 with ten times the samples: second order, the
exact value is the maximum). So the exact value must not be below the sampled one (to
rounding) and not above it by more than 1e-9 relative.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from sizer.laws import make_law
from sizer.laws.linear_peaks import piece_values
from sizer.mechanics import Drive
from sizer.model.domain import Load, Motor, Stage, Task, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.move import CycleCalculator, MoveScales

LAWS = ("cycloidal", "poly5", "trapezoidal(alpha=1/3)", "modified_sinusoidal",
        "double_s(alpha=1/3, beta=1/4)")
SAMPLES = 400_000


_GRIDS: dict[str, tuple[np.ndarray, np.ndarray]] = {}
_SCANS: dict[str, np.ndarray] = {}


def dense_curve(law, extra=()):
    """(v_N, a_N) on a uniform grid of each piece, one-sided at its ends, plus the points
    ``extra`` (tau values); in no particular order (the tests take maxima). The grid's
    values are computed once a law (pointwise, the same values), the extras each call."""
    if law.spec not in _GRIDS:
        taus, pieces = [], []
        for index, piece in enumerate(law.pieces):
            count = max(int(SAMPLES * (piece.end - piece.start)), 2)
            taus.append(np.linspace(piece.start, piece.end, count + 1))
            pieces.append(np.full(count + 1, index))
        _GRIDS[law.spec] = piece_values(law, np.concatenate(taus), np.concatenate(pieces),
                                        (1, 2))
    v, a = _GRIDS[law.spec]
    inside = [(t, index) for index, piece in enumerate(law.pieces) for t in extra
              if piece.start <= t <= piece.end]
    if not inside:
        return v, a
    tau, piece = (np.array(x) for x in zip(*inside, strict=True))
    v_extra, a_extra = piece_values(law, tau, piece, (1, 2))
    return np.concatenate((v, v_extra)), np.concatenate((a, a_extra))


def crossings(law, level):
    """Every tau where v_N = level (brentq between sign changes of a fine scan; the scan's
    v_N computed once a law)."""
    grid = np.linspace(0.0, 1.0, 20_001)
    if law.spec not in _SCANS:
        _SCANS[law.spec] = law.derivative(grid, 1)
    v = _SCANS[law.spec] - level
    found = []
    for i in np.flatnonzero(np.sign(v[:-1]) * np.sign(v[1:]) < 0):
        found.append(brentq(lambda t: float(law.derivative(np.array([t]), 1)[0]) - level,
                            grid[i], grid[i + 1], xtol=1e-15, rtol=1e-15))
    return found


@pytest.mark.parametrize("name", LAWS)
@pytest.mark.parametrize("side", (1.0, -1.0))
def test_maximum_within_a_speed_band_equals_dense_sampling(name, side):
    law = make_law(name)
    peaks = law.linear_peaks
    rng = np.random.default_rng(len(name) + int(side > 0))
    C_v = law.coefficients.C_v
    bounds = rng.uniform(0.05, 0.98, 6) * C_v
    p = rng.normal(size=6)
    q = rng.normal(size=6) * 5.0
    found = peaks.maximum_within(p, q, peaks.band(bounds, side))
    for i, u in enumerate(bounds):
        v, a = dense_curve(law, crossings(law, u))
        inside = side * (v - u) <= 1e-12
        sampled = np.max(p[i] * a[inside] + q[i] * v[inside])
        scale = abs(p[i]) * np.max(np.abs(a)) + abs(q[i]) * C_v
        assert found.value[i] >= sampled - 1e-12 * scale
        assert found.value[i] <= sampled + 1e-9 * scale
        # the value is the law's at the point reported, and that point is in the band
        v_at, a_at = piece_values(law, found.tau[i], found.piece[i], (1, 2))
        assert p[i] * a_at + q[i] * v_at == pytest.approx(found.value[i], rel=1e-12,
                                                           abs=1e-12 * scale)
        assert side * (v_at - u) <= 1e-12 * C_v


@pytest.mark.parametrize("name", LAWS)
def test_ratio_maximum_within_equals_dense_sampling(name):
    law = make_law(name)
    peaks = law.linear_peaks
    rng = np.random.default_rng(7 + len(name))
    C_v = law.coefficients.C_v
    u = rng.uniform(0.3, 0.95, 5) * C_v
    p, q, c = rng.normal(size=5), rng.normal(size=5) * 3.0, rng.normal(size=5)
    alpha = rng.uniform(2.0, 4.0, 5)
    rate = -rng.uniform(0.2, 0.9, 5) * alpha / C_v  # falling lines, positive up to C_v
    found = peaks.ratio_maximum_within(p, q, c, alpha, rate, peaks.band(u, 1.0))
    for i in range(5):
        v, a = dense_curve(law, crossings(law, u[i]))
        inside = v <= u[i] + 1e-12
        sampled = np.max((p[i] * a + q[i] * v + c[i])[inside]
                         / (alpha[i] + rate[i] * v[inside]))
        assert found.value[i] >= sampled - 1e-12 * abs(sampled)
        assert found.value[i] <= sampled + 1e-9 * abs(sampled)


def concave_curve(rng: np.random.Generator, shape: int, peak: float, top: float,
                  end: float):
    """A concave peak region ending at (top, end): flat to a knee then falling (shape 0),
    falling from standstill (1), or flat, then two falling segments, the second
    steeper (2)."""
    knee = top * float(rng.uniform(0.3, 0.8))
    if shape == 0:
        return ((0.0, peak), (knee, peak), (top, end))
    if shape == 1:
        return ((0.0, peak), (top, end))
    middle = 0.5 * (knee + top)
    # on the chord's upper side: the slopes fall, the curve is concave
    at_middle = end + (peak - end) * 0.5 + (peak - end) * float(rng.uniform(0.05, 0.45))
    return ((0.0, peak), (knee, peak), (middle, min(at_middle, peak)), (top, end))


def leaving_case(rng: np.random.Generator, efficiency: float):
    """A gearbox axis and motors whose peak region is concave and ends at a positive
    torque at v_max (:func:`concave_curve`), so the limit is the minimum of its lines."""
    stage = Stage("gearbox", float(rng.uniform(3.0, 10.0)), efficiency, 0.0)
    load = Load(float(rng.uniform(0.01, 0.2)), damping=float(rng.uniform(0.0, 0.1)),
                friction=float(rng.uniform(0.0, 1.0)), torque=float(rng.uniform(-2.0, 2.0)))
    motors = []
    for i in range(6):
        peak = float(rng.uniform(2.0, 8.0))
        top = float(rng.uniform(300.0, 500.0))
        end = peak * float(rng.uniform(0.2, 0.7))
        curve = concave_curve(rng, i % 3, peak, top, end)
        motors.append(Motor(f"m{i}", float(10 ** rng.uniform(-5, -3.5)), peak / 3.0, peak,
                            curve[1][0], max_speed=top, intermittent_curve=curve,
                            continuous_curve=((0.0, peak / 3.0), (top, peak / 4.0))))
    return Drive(load, Transmission((stage,))), MotorArrays.of(tuple(motors), "book")


def dense_ratio(calculator: CycleCalculator, law, scales: MoveScales, row: int) -> float:
    """max over the move of |tau| / tau_int(min(|speed|, v_max)) for one candidate, on the
    dense samples plus the crossings of v_max."""
    region = calculator.motors.intermittent
    speed_scale = float(np.broadcast_to(calculator.drive.ratio * scales.vel,
                                        (len(calculator.motors),))[row])
    top = float(region.max_speed[row])
    v, a = dense_curve(law, crossings(law, top / speed_scale))
    index = np.array([row])
    motor, _ = calculator.channels(a[None], v[None], scales, index)
    speed = np.minimum(np.abs(speed_scale * v), top)
    limit = region.take(index).limit(speed[None])
    return float(np.max(np.abs(motor[0]) / limit[0]))


@pytest.mark.parametrize("seed", range(10))
def test_peak_ratio_of_moves_leaving_the_region_equals_dense_sampling(seed):
    rng = np.random.default_rng(100 + seed)
    drive, motors = leaving_case(rng, efficiency=(1.0, 0.85)[seed % 2])
    law = make_law(LAWS[seed % len(LAWS)])
    calculator = CycleCalculator(None, Task(1.0, 0.5, 0.1, return_move=True), drive, motors,
                                 law=law)
    K = float(np.ravel(drive.ratio)[0])
    C_v = law.coefficients.C_v
    # durations at which every move's peak speed is 1.1 to 2 times the region's end
    factor = rng.uniform(1.1, 2.0, len(motors))
    T = K * C_v / (factor * motors.intermittent.max_speed)
    for direction in (1.0, -1.0):
        scales = MoveScales(1.0 / T / T, 1.0 / T, direction)
        (_, ratio, _, _), exact, _ = calculator._exact_peaks(scales)
        assert exact.all()  # no candidate left to the grid search
        for row in range(len(motors)):
            sampled = dense_ratio(calculator, law, scales, row)
            assert ratio[row] >= sampled * (1.0 - 1e-12)
            assert ratio[row] <= sampled * (1.0 + 1e-9)


def test_a_region_ending_at_zero_torque_gives_an_infinite_ratio():
    """Past a region that ends at zero torque the clipped limit is zero: a move that
    leaves it with any torque there has an infinite peak ratio (as the grid search
    says)."""
    stage = Stage("gearbox", 5.0, 0.9, 0.0)
    drive = Drive(Load(0.05, damping=0.02, friction=0.3, torque=0.5), Transmission((stage,)))
    motors = MotorArrays.of((Motor("zero", 1e-4, 1.0, 3.0, 200.0, max_speed=400.0,
                                   intermittent_curve=((0.0, 3.0), (200.0, 3.0),
                                                       (400.0, 0.0))),), "book")
    law = make_law("cycloidal")
    calculator = CycleCalculator(None, Task(1.0, 0.5, 0.1, return_move=True), drive, motors,
                                 law=law)
    T = np.array([5.0 * 2.0 / (1.5 * 400.0)])  # peak speed 1.5 times the end
    for direction in (1.0, -1.0):
        scales = MoveScales(1.0 / T / T, 1.0 / T, direction)
        (_, ratio, _, _), exact, _ = calculator._exact_peaks(scales)
        assert exact.all()
        assert ratio[0] == np.inf
        grid = calculator._sampled_peaks([scales], ratio_only=True)[0][1]
        assert grid[0] == np.inf


def test_empty_bands_and_floors():
    """A part of the move with no point gives -inf (and leaves a floor as it is); a floor
    above the part's maximum is returned as it is, one below it gives the maximum."""
    law = make_law("cycloidal")
    peaks = law.linear_peaks
    C_v = law.coefficients.C_v
    empty = peaks.band(np.array([1.5 * C_v, 2.0 * C_v]), -1.0)  # v_N >= 1.5 C_v: nowhere
    below_zero = peaks.band(np.array([-0.5]), 1.0)  # v_N <= -0.5: nowhere
    assert np.all(peaks.maximum_within([1.0, 1.0], [1.0, 1.0], empty).value == -np.inf)
    assert peaks.maximum_within([1.0], [1.0], below_zero).value[0] == -np.inf
    got = peaks.ratio_maximum_within(1.0, 1.0, 0.0, 2.0, -0.1, below_zero, floor=[0.25])
    assert got.value[0] == 0.25
    band = peaks.band(np.array([0.8 * C_v, 0.8 * C_v]), 1.0)
    free = peaks.ratio_maximum_within(np.ones(2), np.ones(2), np.zeros(2), np.full(2, 2.0),
                                      np.full(2, -0.1), band)
    top = free.value[0]
    floored = peaks.ratio_maximum_within(np.ones(2), np.ones(2), np.zeros(2), np.full(2, 2.0),
                                         np.full(2, -0.1), band, floor=[top + 1.0, top - 1.0])
    assert floored.value[0] == top + 1.0
    assert floored.value[1] == pytest.approx(top, rel=1e-15)


@pytest.mark.parametrize("name", LAWS)
def test_peak_ratio_on_regions_not_flat_at_standstill(name):
    """Moves inside a region that falls from standstill (its first line not flat) or rises
    before it falls: the ratio against the first line counts too (it is not the torque
    peak over the standstill torque there)."""
    stage = Stage("gearbox", 5.0, 0.9, 0.0)
    drive = Drive(Load(0.05, damping=0.02, friction=0.3, torque=0.5), Transmission((stage,)))
    motors = MotorArrays.of((
        Motor("falling", 1e-4, 1.0, 3.0, 400.0, max_speed=400.0,
              intermittent_curve=((0.0, 3.0), (400.0, 1.0))),
        Motor("rising", 1e-4, 1.0, 3.0, 400.0, max_speed=400.0,
              intermittent_curve=((0.0, 2.0), (100.0, 3.0), (400.0, 1.0)))), "book")
    law = make_law(name)
    calculator = CycleCalculator(None, Task(1.0, 0.5, 0.1, return_move=True), drive, motors,
                                 law=law)
    T = np.full(2, 5.0 * law.coefficients.C_v / (0.9 * 400.0))  # peak speed 0.9 of the end
    for direction in (1.0, -1.0):
        scales = MoveScales(1.0 / T / T, 1.0 / T, direction)
        (_, ratio, _, _), exact, _ = calculator._exact_peaks(scales)
        assert exact.all()
        for row in range(2):
            sampled = dense_ratio(calculator, law, scales, row)
            assert ratio[row] >= sampled * (1.0 - 1e-12)
            assert ratio[row] <= sampled * (1.0 + 1e-9)
