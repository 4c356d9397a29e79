"""The search of `auto` shape parameters (sizer.sizing.choices.search_1d) on functions
whose optimum the test knows, its count of evaluations, and several laws sized as the
rows of one model (sizer.laws.row_laws.RowLaws) against each law sized alone."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from sizer.laws.base import Parameter
from sizer.laws.piecewise_polynomial import Trapezoidal
from sizer.model import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing.candidates import Candidates, MotorArrays
from sizer.sizing.choices import TOLERANCE, _law_rows, score_law, search_1d
from tests.dense_shapes import assert_no_slower_than_fixed

ALPHA = Parameter("alpha", None, 0.0, 0.5)


class Counted:
    """-f(x, which) at the rows ``which`` (their own points x, nan: not asked) as
    (rows, 1) scores (search_1d's RowScore), counting the evaluations asked for."""

    def __init__(self, f):
        self.f, self.asked = f, 0

    def __call__(self, x: np.ndarray, which: np.ndarray) -> np.ndarray:
        self.asked += int(np.count_nonzero(~np.isnan(x)))
        with np.errstate(invalid="ignore"):
            return -self.f(x, which)[:, None]


def v_shape(optimum: np.ndarray):
    """max of a falling and a rising curve crossing at ``optimum`` (a kink, as where two
    checks' durations cross): slopes -3 and about +0.7 there."""
    return lambda x, w: np.maximum(1.0 + 3.0 * (optimum[w] - x),
                                   1.0 + 0.7 * (x - optimum[w]) + 0.5 * (x - optimum[w]) ** 2)


@pytest.mark.parametrize("optimum", [0.3123456789, 0.0871, 0.4444444])
def test_a_crossing_of_two_bounds_is_found_to_the_tolerance_in_few_steps(optimum):
    n = 3
    where = np.full(n, optimum)
    score = Counted(v_shape(where))
    best, scores = search_1d(score, ALPHA, (1e-3, 0.5), n, 1)
    assert np.all(np.abs(best - optimum) <= 2 * TOLERANCE[1])
    assert np.allclose(-scores[:, 0], 1.0, rtol=0, atol=1e-11)
    # 13 grid points, then a few steps each: golden section alone takes about 55
    assert score.asked <= n * 30


def test_a_smooth_minimum_ends_where_the_scores_agree_to_flat():
    centre = np.array([1 / 3, 0.25, 0.1])
    score = Counted(lambda x, w: 2.0 + 5.0 * (x - centre[w]) ** 2)
    best, scores = search_1d(score, ALPHA, (1e-3, 0.5), 3, 1)
    # the value is known to rounding: the point to about sqrt(1e-13 * 2 / 5)
    assert np.all(np.abs(best - centre) < 1e-6)
    assert np.allclose(-scores[:, 0], 2.0, rtol=1e-13)
    assert score.asked <= 3 * 40


def test_an_optimum_at_an_end_of_the_range_is_settled_beside_it():
    score = Counted(lambda x, w: np.where(w == 0, 1.0 / x, 1.0 + x))
    best, _ = search_1d(score, ALPHA, (0.01, 0.5), 2, 1)
    assert best[0] == 0.5 and best[1] == 0.01
    assert score.asked == 2 * (13 + 1)  # the grid, then one point beside each end


def test_a_best_end_whose_slope_does_not_show_beside_it_is_searched_inside():
    """The grid's best point at the end of the range, the optimum just inside the last
    interval and so shallow that the point tol/2 beside the end ties with it: the search
    goes on inside (it settled at the end, 0.0066 away, before)."""
    centre = 0.4934
    score = Counted(lambda x, w: 1.0 + 1e-3 * (x - centre) ** 2)
    best, scores = search_1d(score, ALPHA, (1e-3, 0.5), 1, 1)
    assert abs(best[0] - centre) < 1e-4
    assert -scores[0, 0] <= 1.0 + 1e-12


def test_a_jump_to_the_optimum_is_approached_from_its_side():
    """T_min may jump where a check's window opens: the search still closes on the jump."""
    edge = 0.2948625330448

    def f(x, which):
        return np.where(x < edge, 1.5, 1.0 + (x - edge))

    best, scores = search_1d(Counted(f), ALPHA, (1e-3, 0.5), 1, 1)
    assert edge <= best[0] <= edge + 2 * TOLERANCE[1]
    assert -scores[0, 0] == pytest.approx(1.0, abs=1e-11)


def test_ties_on_the_first_score_are_decided_by_the_next():
    """A given duration: the smallest margin may not depend on the shape (the inertia
    ratio), then the next one decides, and the steps read that one."""
    optimum = np.array([0.3, 0.1234567])
    second = v_shape(optimum)
    asked = []

    def score(x, which):
        asked.append(int(np.count_nonzero(~np.isnan(x))))
        with np.errstate(invalid="ignore"):
            return np.stack([np.where(np.isnan(x), np.nan, 0.25), -second(x, which)], axis=1)

    best, _ = search_1d(score, ALPHA, (1e-3, 0.5), 2, 1)
    assert np.all(np.abs(best - optimum) <= 2 * TOLERANCE[1])
    assert sum(asked) <= 2 * 30


def test_two_parameters_nested_with_an_outer_steps_values_as_rows():
    """The nested search of two parameters (choices._nested): the inner searches of the
    outer grid's values run as one search over motors x values; each motor's optimum of
    a known bowl (a kink in alpha, a smooth minimum in beta) is found to TOLERANCE[2]."""
    from sizer.sizing.choices import _nested

    centre = np.array([[0.31, 0.22], [0.12, 0.41], [0.45, 0.05]])
    calls = []

    def score_rows(points, rows):
        a, b = points
        calls.append(len(rows))
        with np.errstate(invalid="ignore"):
            value = (1.0 + 2.0 * np.abs(a - centre[rows, 0])
                     + 3.0 * (b - centre[rows, 1]) ** 2)
        return -np.where(np.isnan(a) | np.isnan(b), np.inf, value)[:, None]

    beta = Parameter("beta", None, 0.0, 0.5)
    best, scores = _nested(score_rows, [ALPHA, beta], [(1e-3, 0.5), (1e-3, 0.5)],
                           np.arange(3), 2, ())
    assert np.all(np.abs(best[0] - centre[:, 0]) <= 2e-4)
    assert np.all(np.abs(best[1] - centre[:, 1]) <= 1e-3)
    assert np.allclose(-scores[:, 0], 1.0, atol=1e-6)
    assert calls[0] == 7 * 7 * 3  # the outer grid's inner grids: one call


MOTORS = tuple(Motor(f"m{i}", inertia=2e-5 * t**1.3, continuous_torque=t, peak_torque=3 * t,
                     rated_speed=3000 * math.pi / 30)
               for i, t in enumerate((0.4, 1.1, 2.5, 6.0)))


def efficiency_design(motors=MOTORS, spec="trapezoidal(alpha=auto)", seed=None) -> Design:
    """A searched case: a gearbox of efficiency 0.9 (power flow: no closed form)."""
    rng = np.random.default_rng(seed)
    inertia, friction = (0.35, 0.5) if seed is None else (rng.uniform(0.05, 0.6),
                                                          rng.uniform(0.0, 0.8))
    dwell = 0.15 if seed is None else rng.uniform(0.0, 0.4)
    return Design(Task(math.pi / 2, None, dwell=dwell, return_move=True),
                  Load(inertia, friction=friction),
                  Transmission((Stage("gearbox", 10.0, 0.9, 1.2e-4),)), laws=(spec,),
                  motors=motors, limits=Limits(torque_margin=0.1))


@pytest.mark.parametrize("duration", [None, 0.45])
@pytest.mark.parametrize("chunk", [None, 3])
def test_several_laws_as_rows_of_one_model_give_each_laws_own_answer(duration, chunk,
                                                                     monkeypatch):
    """T_min in minimize mode, the sorted slacks at a given duration; in one model or in
    chunks of rows (``chunk``: the engine's chunk size made small), each law's own scores
    bit for bit."""
    from sizer.sizing import choices

    if chunk is not None:
        monkeypatch.setattr(choices, "candidates_per_chunk", lambda samples: chunk)
    design = efficiency_design()
    design = replace(design, task=replace(design.task, duration=duration))
    candidates = Candidates.single(MotorArrays.of(design.motors), design.load,
                                   design.transmission)
    laws = [Trapezoidal(alpha=a) for a in (0.11, 0.25, 1 / 3, 0.47)]
    part = np.array([2, 0, 3, 1, 1, 2, 0, 3])
    rows = candidates.take(np.arange(8) % 4)
    together = _law_rows(laws, part, design, rows)
    assert together is not None
    assert together.shape[1] == (1 if duration is None else len(together[0]))
    for k, law in enumerate(laws):
        mine = np.flatnonzero(part == k)
        alone = score_law(law, design, rows.take(mine))
        assert np.array_equal(together[mine], alone)  # the same numbers, bit for bit
    assert np.isfinite(together).all()
    if duration is not None:
        assert together.shape[1] > 1 and (np.diff(together, axis=1) >= 0.0).all()


@pytest.mark.parametrize("efficiency", [0.9, 1.0])
@pytest.mark.parametrize("duration, residual", [
    (None, None), (0.6, None),
    # a load with a mode: its residual vibration reported, then limited (binding for some)
    (None, math.inf), (0.6, math.inf), (None, 2e-5), (0.6, 2e-5)])
def test_each_candidates_own_law_sized_as_rows_of_one_model_is_each_law_alone(
        duration, residual, efficiency, monkeypatch):
    """sizer.sizing.engine.evaluate_laws (the laws of auto shapes, one per motor, and of
    shaped laws, one per duration): as the rows of one model of their laws (the closed
    forms with the friction as a constant torque through an ideal gearbox, the search
    through an efficient one), the residual vibration a later limit over its rows
    (sizer.sizing.vibration_check.ResidualRows), and law by law, every figure and check
    the same bit for bit."""
    from sizer.sizing import engine
    from sizer.vibration.elastic_load import ElasticLoad

    design = replace(efficiency_design(), task=Task(math.pi / 2, duration, dwell=0.15,
                                                    return_move=True))
    gearbox = replace(design.transmission.stages[0], efficiency=efficiency)
    design = replace(design, transmission=Transmission((gearbox,)))
    if residual is not None:
        design = replace(design, load=replace(design.load, elastic=ElasticLoad(25.0, 0.02)),
                         limits=replace(design.limits, residual_vibration=None
                                        if math.isinf(residual) else residual))
    candidates = Candidates.single(MotorArrays.of(design.motors), design.load,
                                   design.transmission)
    laws = [Trapezoidal(alpha=a) for a in (0.2, 1 / 3, 0.45)]
    group = np.array([2, 0, 1, 0])
    assert engine._law_rows(design, laws, group, candidates) is not None
    together = engine.evaluate_laws(design, laws, group, candidates)
    monkeypatch.setattr(engine, "_law_rows", lambda *args: None)
    alone = engine.evaluate_laws(design, laws, group, candidates)
    assert [together.laws[i] for i in together.law] == [laws[k] for k in group]
    assert [alone.laws[i] for i in alone.law] == [laws[k] for k in group]
    assert np.array_equal(together.feasible, alone.feasible)
    for name, values in alone.figures.items():
        assert np.array_equal(together.figures[name], values, equal_nan=True), name
    for mine, theirs in zip(together.checks, alone.checks, strict=True):
        assert mine.name == theirs.name
        assert np.array_equal(mine.value, theirs.value, equal_nan=True)
        assert np.array_equal(mine.slack, theirs.slack, equal_nan=True)
    if residual is not None:
        assert np.isfinite(together.figures["residual_vibration"]).all()
    if residual is not None and math.isfinite(residual):
        check = next(c for c in together.checks if c.name == "residual_vibration")
        binding = np.abs(check.value - residual) <= 1e-9 * residual
        assert binding.any() if duration is None else (~check.passed).any()


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_searched_optimum_is_no_slower_than_a_dense_grid_of_fixed_shapes(seed):
    """Random designs through a gearbox of efficiency 0.9 with damping (no closed form: the
    engine scores every point, sizer.sizing.optimal_shapes.trusted_phase_model leaves the
    damped case to it): the auto trapezoid's T_min against the engine's T_min of 97 fixed
    trapezoids."""
    design = efficiency_design(MOTORS[1:3], seed=seed)
    design = replace(design, load=replace(design.load, damping=0.01))
    grid = np.linspace(0.02, 0.5, 97).tolist()
    assert_no_slower_than_fixed(design, [f"trapezoidal(alpha={a!r})" for a in grid], 1e-12)
