"""The law's one integration scheme (sizer.laws.quadrature): fixed Gauss-Legendre nodes
per piece, exact on polynomial pieces, to 1e-14 on the others; checked against the
closed-form RMS coefficients (book sec. 6.2, Table 6.2) and scipy's adaptive quad."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from scipy import integrate

from sizer.laws import DEFAULT_LAW_SPECS, make_law
from sizer.laws.coefficients import rms

VARIANTS = ("trapezoidal(alpha=0.1)", "double_s(alpha=0.2, beta=0.5)", "polynomial(21)",
            "elliptic(n=30)", "modified_cycloidal(kappa=-0.5)",
            "exponential(sigma=3, lam=0.5)", "exponential(sigma=2, lam=0.61)")
SPECS = (*DEFAULT_LAW_SPECS, *VARIANTS)


@pytest.mark.parametrize("spec", SPECS)
def test_rms_against_closed_forms(spec):
    law = make_law(spec)
    known = law.closed_form_coefficients()
    for name, order in (("C_v_rms", 1), ("C_a_rms", 2)):
        if name in known:
            assert rms(law, order) == pytest.approx(known[name], rel=1e-14)


def adaptive_square_integral(law, order: int) -> float:
    """int_0^1 (q_N^(order))^2 by scipy's adaptive quad, piece by piece."""
    total = 0.0
    for index, piece in enumerate(law.pieces):
        points = [x for x in law.fine_points() if piece.start < x < piece.end] or None

        def square(x: float, index: int = index) -> float:
            return float(law.piece_derivative(index, np.array([x]), order)[0]) ** 2

        value, _ = integrate.quad(square, piece.start, piece.end, epsabs=0.0, epsrel=1e-13,
                                  limit=2000, points=points)
        total += value
    return total


@pytest.mark.parametrize("spec", SPECS)
def test_square_integrals_against_adaptive_quadrature(spec):
    law = make_law(spec)
    rule = law.quadrature
    for order in (1, 2):
        fixed = rule.integral(rule.values(law, order) ** 2)
        assert fixed == pytest.approx(adaptive_square_integral(law, order), rel=1e-13)


@pytest.mark.parametrize("degree", [3, 5, 7, 11, 21])
def test_polynomial_pieces_are_integrated_exactly(degree):
    """int q_N^2 of the polynomial law: sum over Bernstein terms, in exact fractions."""
    law = make_law(f"polynomial({degree})")
    m = (degree - 1) // 2
    n = degree
    # q_N = sum_{k>m} B_{k,n}; int B_{i,n} B_{k,n} = C(n,i) C(n,k) / (C(2n, i+k) (2n+1))
    exact = sum(Fraction(math.comb(n, i) * math.comb(n, k), math.comb(2 * n, i + k) * (2 * n + 1))
                for i in range(m + 1, n + 1) for k in range(m + 1, n + 1))
    rule = law.quadrature
    assert len(rule.tau) == degree + 1
    assert rule.integral(rule.values(law, 0) ** 2) == pytest.approx(float(exact), rel=1e-14)


@pytest.mark.parametrize("spec", SPECS)
def test_rule_covers_each_piece(spec):
    law = make_law(spec)
    rule = law.quadrature
    assert rule.integral(np.ones_like(rule.tau)) == pytest.approx(1.0, rel=1e-14)
    for index, piece in enumerate(law.pieces):
        part = slice(rule.bounds[index], rule.bounds[index + 1])
        assert np.all(rule.piece[part] == index)
        assert np.all((rule.tau[part] > piece.start) & (rule.tau[part] < piece.end))
        assert rule.weight[part].sum() == pytest.approx(piece.end - piece.start, rel=1e-13)
    # a constant-jerk piece of the double S: 4 nodes integrate its cubic's square exactly
    if law.law_id == "double_s":
        assert all(rule.bounds[i + 1] - rule.bounds[i] == 4 for i in range(len(law.pieces)))
