"""The pieces as data (sizer.laws.piece_forms) give each piece's own value bit for bit.

The reference is each piece's closure (Piece.evaluate after Piece.clamp, the path
MotionLaw.piece_derivative takes): independent arithmetic the table must reproduce, on
every multi-piece law of the registry, every derivative order it evaluates, points inside
its pieces, at their ends and outside them (clamped to one-sided values)."""

from __future__ import annotations

import numpy as np
import pytest

from sizer.laws.linear_peaks import piece_values
from sizer.laws.piece_forms import PieceForms
from sizer.laws.pieces import trig_poly_piece
from sizer.laws.registry import make_law

MULTI_PIECE = (
    "constant_acceleration", "trapezoidal(alpha=1/3)", "trapezoidal(alpha=0.05)",
    "trapezoidal(alpha=0.5)", "double_s(alpha=1/3, beta=1/4)",
    "double_s(alpha=0.1, beta=0.45)", "modified_trapezoidal", "modified_sinusoidal",
    "fifteen_segments(alpha=0.3, beta=0.2, gamma=0.25)", "polynomial_blends",
    "cycloidal_blends", "cycloidal_blend_acceleration", "cubic_blend_acceleration",
    "polynomial_4_3_4", "circular_blends",
)


def _points(law, rng) -> tuple[np.ndarray, np.ndarray]:
    """Per piece: random points inside, its ends, its ends' neighbours (one ulp) and
    points outside it (a clamped read)."""
    taus, pieces = [], []
    for i, p in enumerate(law.pieces):
        inside = rng.uniform(p.start, p.end, 40)
        ends = np.array([p.start, p.end, np.nextafter(p.start, -1.0), np.nextafter(p.end, 2.0),
                         np.nextafter(p.start, 2.0), np.nextafter(p.end, -1.0),
                         p.start - 0.3, p.end + 0.3, 0.0, 1.0, 0.5])
        taus.append(np.concatenate([inside, ends]))
        pieces.append(np.full(len(inside) + len(ends), i))
    order = rng.permutation(sum(len(t) for t in taus))  # pieces mixed
    return np.concatenate(taus)[order], np.concatenate(pieces)[order]


def _closure(law, tau: np.ndarray, piece: np.ndarray, order: int) -> np.ndarray:
    out = np.empty(len(tau))
    for i in range(len(law.pieces)):
        rows = piece == i
        out[rows] = law.piece_derivative(i, tau[rows], order)
    return out


@pytest.mark.parametrize("spec", MULTI_PIECE)
def test_every_order_bit_for_bit(spec: str) -> None:
    law = make_law(spec)
    forms = law.piece_forms()
    if forms is None:  # a family whose pieces are not polynomials plus sines
        assert any(p.form is None and p.mirror_of is None for p in law.pieces)
        return
    tau, piece = _points(law, np.random.default_rng(7))
    orders = tuple(range(law.max_order + 1))
    values = forms.values(piece, tau, orders)
    for order, got in zip(orders, values, strict=True):
        expected = _closure(law, tau, piece, order)
        assert np.array_equal(got, expected), (spec, order)
    # what the analyses call: the grouped values and the law's own derivative
    grouped = piece_values(law, tau, piece, (1, 2, 3))
    for order, got in zip((1, 2, 3), grouped, strict=True):
        assert np.array_equal(got, _closure(law, tau, piece, order))
    grid = np.linspace(-0.1, 1.1, 1201)
    for order in range(min(law.max_order, 4) + 1):
        index = np.clip(np.searchsorted(law.breakpoints[:-1], grid, side="right") - 1, 0,
                        len(law.pieces) - 1)
        inside = (grid >= 0.0) & (grid <= 1.0)
        expected = np.zeros_like(grid)
        expected[grid > 1.0] = 1.0 if order == 0 else 0.0
        expected[inside] = _closure(law, grid[inside], index[inside], order)
        assert np.array_equal(law.derivative(grid, order), expected), (spec, order)


def test_the_table_covers_the_book_laws_of_several_pieces() -> None:
    for spec in ("trapezoidal(alpha=1/3)", "double_s(alpha=1/3, beta=1/4)",
                 "modified_trapezoidal", "modified_sinusoidal", "constant_acceleration"):
        assert make_law(spec).piece_forms() is not None, spec
    assert make_law("cycloidal").piece_forms() is None  # one piece: its own closure


def test_a_piece_without_a_form_has_no_table() -> None:
    from sizer.laws.pieces import Piece

    plain = Piece(0.5, 1.0, lambda tau, order: np.zeros(np.shape(tau)))
    assert PieceForms.of([trig_poly_piece(0.0, 0.5, (0.0, 1.0)), plain]) is None


def test_padding_adds_exact_zeros() -> None:
    """A piece of degree 1 beside one of degree 5 and one with two sines: each still reads
    its own closure's value (the padded coefficients and amplitudes add exact zeros)."""
    pieces = [trig_poly_piece(0.0, 0.3, (0.1, -0.7)),
              trig_poly_piece(0.3, 0.6, (1e-3, 2.0, -3.0, 4.0, -5.0, 6.0), origin=0.3),
              trig_poly_piece(0.6, 1.0, (0.5,), [(0.2, 7.0, 0.1), (-0.3, 3.0, -1.2)],
                              origin=0.6)]
    forms = PieceForms.of(pieces)
    assert forms is not None
    rng = np.random.default_rng(3)
    tau = rng.uniform(-0.2, 1.2, 500)
    piece = rng.integers(0, 3, 500)
    for order, got in enumerate(forms.values(piece, tau, range(7))):
        expected = np.empty(500)
        for i, p in enumerate(pieces):
            rows = piece == i
            expected[rows] = p.evaluate(p.clamp(tau[rows]), order)
        assert np.array_equal(got, expected), order


@pytest.mark.parametrize("spec", MULTI_PIECE)
def test_the_linear_peaks_samples_are_the_pieces_own(spec: str) -> None:
    """The (v_N, a_N) samples a law's linear peaks are built on: every piece in one pass
    gives each piece's samples, constant-acceleration pieces cut to their ends, the same
    values bit for bit."""
    from sizer.laws.linear_peaks import _law_samples, _piece_samples

    law = make_law(spec)
    columns = [_piece_samples(law, index) for index in range(len(law.pieces))]
    expected = [np.concatenate(parts) for parts in zip(*columns, strict=True)]
    for got, want in zip(_law_samples(law), expected, strict=True):
        assert got.dtype == want.dtype and np.array_equal(got, want), spec


@pytest.mark.parametrize("spec", MULTI_PIECE)
def test_the_laws_tables_are_the_same_from_the_forms(spec: str, monkeypatch) -> None:
    """The law's grid (edges, nodes and their values), its quadrature values, its one-sided
    limits at the breakpoints and a piecewise evaluation read through the forms are those
    of the pieces one by one (the forms switched off for the reference), bit for bit."""
    from sizer.laws.coefficients import one_sided_limits
    from sizer.laws.quadrature import quadrature_rule
    from sizer.sizing.move import PieceEvaluator, law_grid

    law = make_law(spec)
    if law.piece_forms() is None:
        return
    rng = np.random.default_rng(11)
    tau, piece = _points(law, rng)
    rule = quadrature_rule(law)

    def tables():
        grid = law_grid.__wrapped__(law)
        arrays = [getattr(grid, name) for name in vars(grid) if name != "law"]
        values = [rule.values(law, k) for k in range(law.max_order + 1)]
        limits = [one_sided_limits(law, k) for k in range(law.max_order + 1)]
        evaluated = PieceEvaluator(law, piece).orders(tau, (0, 1, 2, 3))
        return arrays, values, limits, evaluated

    with_forms = tables()
    monkeypatch.setattr(type(law), "piece_forms", lambda self: None)
    reference = tables()
    for got, want in zip(with_forms[0] + with_forms[1] + list(with_forms[3]),
                         reference[0] + reference[1] + list(reference[3]), strict=True):
        assert np.array_equal(np.asarray(got), np.asarray(want)), spec
    assert with_forms[2] == reference[2], spec


def _bits(x: np.ndarray) -> np.ndarray:
    """The array's bits (floats as int64: a signed zero differs), to compare exactly."""
    return x.view(np.int64) if x.dtype == np.float64 else x


def test_several_laws_samples_in_one_pass_are_each_laws_own():
    """sizer.laws.linear_peaks.samples_together (the hull samples of a search step's laws,
    their pieces numbered across the laws) against each law's own samples, bit for bit;
    sizer.laws.base.build_linear_peaks gives each law the hull it builds alone."""
    from sizer.laws.base import build_linear_peaks
    from sizer.laws.linear_peaks import LinearPeaks, _law_samples, samples_together

    specs = ("trapezoidal(alpha=0.2)", "double_s(alpha=0.3, beta=0.15)",
             "fifteen_segments(alpha=0.3, beta=0.2, gamma=0.25)", "modified_sinusoidal",
             "modified_trapezoidal", "double_s(alpha=1e-6, beta=1e-6)",
             "trapezoidal(alpha=0.45, alpha_d=0.3)")
    laws = [make_law(spec) for spec in specs]
    assert all(law.piece_forms() is not None for law in laws)
    for law, together in zip(laws, samples_together(laws), strict=True):
        for mine, alone in zip(together, _law_samples(law), strict=True):
            assert mine.dtype == alone.dtype
            assert np.array_equal(_bits(mine), _bits(alone)), law.spec
    fresh = [type(law)(**dict(law.params)) for law in [*laws, make_law("poly5")]]
    built = fresh[0].linear_peaks  # built already: kept
    build_linear_peaks(fresh)
    assert fresh[0].linear_peaks is built
    for law in fresh[1:-1]:
        assert "linear_peaks" in law.__dict__
        alone = LinearPeaks(law)
        assert np.array_equal(law.linear_peaks.hull, alone.hull)
        assert np.array_equal(_bits(law.linear_peaks._angles), _bits(alone._angles))
    assert "linear_peaks" not in fresh[-1].__dict__  # one piece: built on first use
