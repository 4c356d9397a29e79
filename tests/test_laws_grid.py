"""Pieces are never evaluated outside their interval (issue 9): on the sizing grid, at
refinement points a rounding error outside a piece, and at mirrored breakpoints, the
normalized speed and acceleration stay within the law's exact C_v and C_a.

C_v and C_a of the trapezoid and double S are the book's closed forms (sec. 6.2.1):
C_v = 1/(1 - alpha), C_a = 1/(alpha (1 - alpha)(1 - beta)).
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from sizer.laws import make_law
from sizer.sizing.move import PieceEvaluator, law_grid, piecewise

STEEP = [
    ("double_s(alpha=1/2, beta=0.0005)", 0.5, 0.0005),
    ("double_s(alpha=1/3, beta=0.0005)", 1 / 3, 0.0005),
    ("double_s(alpha=1e-6, beta=1e-6)", 1e-6, 1e-6),
    ("double_s(alpha=1/2, beta=1/2)", 0.5, 0.5),
    ("trapezoidal(alpha=1e-6)", 1e-6, 0.0),
    ("trapezoidal(alpha=1/2)", 0.5, 0.0),
]


def _exact(alpha: float, beta: float) -> tuple[float, float]:
    return 1 / (1 - alpha), 1 / (alpha * (1 - alpha) * (1 - beta))


def _near_ends(law, ulps: int = 8) -> tuple[np.ndarray, np.ndarray]:
    """For every piece: points up to ``ulps`` ulps outside and inside both of its ends."""
    taus, pieces = [], []
    for index, piece in enumerate(law.pieces):
        for end in (piece.start, piece.end):
            x = np.array([end])
            for _ in range(ulps):
                taus += [x.copy(), 2 * end - x]
                x = np.nextafter(x, np.inf)
            x = np.array([end])
            for _ in range(ulps):
                taus.append(x.copy())
                x = np.nextafter(x, -np.inf)
            pieces += [index] * 3 * ulps
    return np.concatenate(taus), np.array(pieces)


@pytest.mark.parametrize(("spec", "alpha", "beta"), STEEP)
def test_piece_evaluations_near_the_ends_never_exceed_the_peaks(spec, alpha, beta):
    law = make_law(spec)
    c_v, c_a = _exact(alpha, beta)
    tau, piece = _near_ends(law)
    at = PieceEvaluator(law, piece)
    assert np.abs(at(tau, 1)).max() <= c_v * (1 + 1e-14)
    assert np.abs(at(tau, 2)).max() <= c_a * (1 + 1e-14)
    assert np.abs(piecewise(law, tau, piece, 2)).max() <= c_a * (1 + 1e-14)
    for index in range(len(law.pieces)):
        mine = piece == index
        values = law.piece_derivative(index, tau[mine], 2)
        assert np.abs(values).max() <= c_a * (1 + 1e-14)
        # outside its interval a piece reads its end's one-sided value
        p = law.pieces[index]
        outside = tau[mine][(tau[mine] < p.start) | (tau[mine] > p.end)]
        clamped = np.clip(outside, p.start, p.end)
        assert np.array_equal(law.piece_derivative(index, outside, 2),
                              law.piece_derivative(index, clamped, 2))


@pytest.mark.parametrize(("spec", "alpha", "beta"), STEEP)
def test_law_grid_stays_within_the_peaks_and_reaches_them(spec, alpha, beta):
    law = make_law(spec)
    c_v, c_a = _exact(alpha, beta)
    grid = law_grid(law)
    for values, bound in ((grid.velocity, c_v), (grid.end_velocity, c_v),
                          (grid.acceleration, c_a), (grid.end_acceleration, c_a)):
        assert np.abs(values).max() <= bound * (1 + 1e-14)
    # the one-sided end values reach the exact peaks (plateaus of v and a)
    assert np.abs(grid.end_velocity).max() == pytest.approx(c_v, rel=1e-12)
    assert np.abs(grid.end_acceleration).max() == pytest.approx(c_a, rel=1e-9)


@pytest.mark.parametrize(("spec", "alpha", "beta"), STEEP)
def test_golden_refinement_points_stay_within_the_peaks(spec, alpha, beta):
    # the engine refines a peak between neighbouring grid samples of one interval; points
    # computed as lo + r*(hi - lo) may round past the interval's ends
    law = make_law(spec)
    c_v, c_a = _exact(alpha, beta)
    grid = law_grid(law)
    r = np.linspace(-1e-12, 1 + 1e-12, 257)
    tau = grid.left[:, None] + r * (grid.right - grid.left)[:, None]
    piece = np.broadcast_to(grid.piece[:, None], tau.shape)
    at = PieceEvaluator(law, piece)
    assert np.abs(at(tau, 1)).max() <= c_v * (1 + 1e-14)
    assert np.abs(at(tau, 2)).max() <= c_a * (1 + 1e-14)


@pytest.mark.parametrize("spec", ["double_s(alpha=1/2, beta=0.0005)",
                                  "double_s(alpha=1e-6, beta=1e-6)", "trapezoidal(alpha=1e-6)"])
def test_mirrored_breakpoints_have_mirrored_one_sided_values(spec):
    law = make_law(spec)
    n = len(law.pieces)
    for index in range(n // 2):
        left, right = law.pieces[index], law.pieces[n - 1 - index]
        for order in (1, 2):
            sign = -((-1.0) ** order)
            a = law.piece_derivative(index, np.array([left.start, left.end]), order)
            b = law.piece_derivative(n - 1 - index, np.array([right.end, right.start]), order)
            assert np.array_equal(b, sign * a)


def _elliptic_rms_book(n: float) -> tuple[float, float]:
    """C_v_rms, C_a_rms from the book's velocity and acceleration (sec. 2.2.3), by mpmath
    at 30 digits on [0, 1/2] split toward 1/2 (the law is symmetric)."""
    with mp.workdps(30):
        a = (mp.mpf(n) ** 2 - 1) / mp.mpf(n) ** 2

        def v(t):
            x = mp.pi * t
            return mp.pi / 2 * mp.sin(x) / (n**2 * mp.sqrt((1 - a * mp.sin(x) ** 2) ** 3))

        def acc(t):
            x = mp.pi * t
            s2 = mp.sin(x) ** 2
            return (mp.pi**2 / 2 * mp.cos(x) * (1 + 2 * a * s2)
                    / (n**2 * mp.sqrt((1 - a * s2) ** 5)))

        edges = [0] + [mp.mpf(1) / 2 - mp.mpf(10) ** -k for k in range(1, 12)] + [mp.mpf(1) / 2]
        return tuple(float(mp.sqrt(2 * mp.quad(lambda t, f=f: f(t) ** 2, edges)))
                     for f in (v, acc))


def test_grid_is_graded_toward_fine_points():
    # elliptic n = 1000: the profile lives within ~1/n of tau = 1/2; the engine's grid
    # must integrate v_N^2 and a_N^2 there as the book's formulas do
    law = make_law("elliptic(n=1000)")
    grid = law_grid(law)
    c_v_rms, c_a_rms = _elliptic_rms_book(1000.0)
    assert np.sqrt((grid.weights * grid.velocity**2).sum()) == pytest.approx(c_v_rms, rel=1e-9)
    assert np.sqrt((grid.weights * grid.acceleration**2).sum()) == pytest.approx(c_a_rms,
                                                                                 rel=1e-9)
    assert law.coefficients.C_v_rms == pytest.approx(c_v_rms, rel=1e-9)
    assert law.coefficients.C_a_rms == pytest.approx(c_a_rms, rel=1e-9)


@pytest.mark.parametrize("alpha", [1e-6, 1e-3, 1 / 3, 1 / 2])
def test_grid_nodes_are_evaluated_on_their_own_piece(alpha):
    # trapezoid: a_N = +C_a on the first piece, 0 on the cruise, -C_a on the last; no node
    # of a piece's interval may read its neighbour's value
    law = make_law(f"trapezoidal(alpha={alpha!r})")
    _, c_a = _exact(alpha, 0.0)
    grid = law_grid(law)
    first, last = grid.piece == 0, grid.piece == len(law.pieces) - 1
    assert np.allclose(grid.acceleration[first], c_a, rtol=1e-12, atol=0)
    assert np.allclose(grid.acceleration[last], -c_a, rtol=1e-12, atol=0)
    middle = ~(first | last)
    assert np.all(grid.acceleration[middle] == 0.0)
