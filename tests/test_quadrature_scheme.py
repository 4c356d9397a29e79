"""One integration scheme (sizer.laws.quadrature) for the laws' RMS coefficients and the
engine's law grid (sizer.sizing.grid): both are exact on polynomial pieces and reach
machine precision on the others, checked against integrals known in closed form.

Over a rest-to-rest move int v_N = q_N(1) - q_N(0) = 1, int a_N = 0 and
int v_N a_N = [v_N^2 / 2] = 0 (book sec. 6.2); cycloidal: v_N = 1 - cos(2 pi tau),
a_N = 2 pi sin(2 pi tau), so int v_N^2 = 3/2 and int a_N^2 = 2 pi^2.
"""

from __future__ import annotations

import math

import pytest

from sizer.laws import DEFAULT_LAW_SPECS, make_law
from sizer.laws.quadrature import Resolution, law_intervals
from sizer.sizing.move import ENGINE_RESOLUTION, engine_intervals, grid_samples, law_grid

SPECS = (*DEFAULT_LAW_SPECS, "elliptic(n=1000)", "polynomial(21)",
         "exponential(sigma=2, lam=0.61)", "double_s(alpha=1e-6, beta=1e-6)")


@pytest.mark.parametrize("spec", SPECS)
def test_the_engine_grid_integrates_the_move_identities(spec):
    law = make_law(spec)
    g = law_grid(law)
    c = law.coefficients
    assert (g.weights * g.velocity).sum() == pytest.approx(1.0, rel=1e-14)
    assert abs((g.weights * g.acceleration).sum()) <= 1e-14 * c.C_a
    assert abs((g.weights * g.velocity * g.acceleration).sum()) <= 1e-14 * c.C_a * c.C_v
    assert g.weights.sum() == pytest.approx(1.0, rel=1e-14)


@pytest.mark.parametrize("spec", SPECS[:-1])
def test_the_engine_grid_and_the_laws_rule_agree(spec):
    # the same scheme at two resolutions: the same integrals of a mixed square (not the
    # double S with pieces 1e-12 wide at tau = 1e-6: one interval's nodes there round to
    # 1e-11 of the integral of a_N^2; its coefficients are the closed forms)
    law = make_law(spec)
    g = law_grid(law)
    rule = law.quadrature
    for p in (0.0, 0.3, -2.0):
        on_grid = (g.weights * (g.velocity + p * g.acceleration) ** 2).sum()
        on_rule = rule.integral((rule.values(law, 1) + p * rule.values(law, 2)) ** 2)
        assert on_grid == pytest.approx(on_rule, rel=1e-13)


def test_cycloidal_squares_on_the_engine_grid():
    g = law_grid(make_law("cycloidal"))
    assert (g.weights * g.velocity**2).sum() == pytest.approx(1.5, rel=2e-16)
    assert (g.weights * g.acceleration**2).sum() == pytest.approx(2 * math.pi**2, rel=4e-16)


@pytest.mark.parametrize("spec", ["trapezoidal(alpha=1/3)", "double_s(alpha=1/3, beta=1/4)",
                                  "poly5", "poly7", "constant_acceleration"])
def test_polynomial_pieces_get_their_exact_node_count_on_the_engine_grid(spec):
    # degree d: d + 1 nodes are exact for (q_N^(k))^2, k >= 0 (degree 2d <= 2(d + 1) - 1)
    law = make_law(spec)
    g = law_grid(law)
    assert g.nodes.shape[1] == max(p.degree for p in law.pieces) + 1
    intervals = [len(part.edges) - 1 for part in law_intervals(law, ENGINE_RESOLUTION)]
    assert g.size == sum(intervals) == ENGINE_RESOLUTION.polynomial_intervals * len(law.pieces)


@pytest.mark.parametrize("spec", ["poly5", "double_s(alpha=0.2, beta=0.5)"])
def test_one_interval_per_polynomial_piece_is_exact(spec):
    # the laws' own resolution: one interval per piece, the book's closed forms of C_a_rms
    law = make_law(spec)
    parts = law_intervals(law, Resolution(polynomial_intervals=1, lowest_order=1))
    assert all(len(part.edges) == 2 for part in parts)
    total = 0.0
    for part in parts:
        tau, weight = part.gauss()
        total += float((law.piece_derivative(part.index, tau, 2) ** 2 * weight).sum())
    assert math.sqrt(total) == pytest.approx(law.closed_form_coefficients()["C_a_rms"],
                                             rel=1e-14)


@pytest.mark.parametrize("spec", SPECS)
def test_grid_samples_counts_the_grid_from_its_intervals(spec):
    # the chunks' memory (sizer.sizing.engine.chunk_size) without the grid's values: the
    # nodes and both ends of every interval, as the grid built from them holds
    law = make_law(spec)
    g = law_grid(law)
    assert grid_samples(law) == g.nodes.size + 2 * g.size
    assert engine_intervals(law) is engine_intervals(law)  # computed once per law
