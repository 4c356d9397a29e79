"""A curve normalized into a motion law (sizer.laws.data_law) and its spec text.

The curves here are PPolys written by hand, so that every expected number is a closed
form of the polynomial, independent of the builders of sizer.laws.multipoint."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline, PPoly

from sizer.errors import UserError
from sizer.laws.data_law import DataLaw
from sizer.laws.data_spec import data_spec_text, is_data_spec, read_data_spec


def _poly5_curve(t0: float, duration: float, q0: float, h: float, pieces: int) -> PPoly:
    """q0 + h (10 u^3 - 15 u^4 + 6 u^5), u = (t - t0)/T, cut into ``pieces`` pieces."""
    x = np.linspace(t0, t0 + duration, pieces + 1)
    normalized = np.polynomial.Polynomial([0, 0, 0, 10, -15, 6])
    c = np.zeros((6, pieces))
    for i in range(pieces):
        # the polynomial in s = t - x_i: u = (x_i - t0 + s)/T
        local = normalized(np.polynomial.Polynomial([(x[i] - t0) / duration, 1 / duration]))
        c[:, i] = np.pad((h * local).coef, (0, 6 - len(local.coef)))[::-1]
        c[-1, i] += q0
    return PPoly(c, x)


@pytest.mark.parametrize("pieces", [1, 3])
def test_poly5_curve_in_user_units_has_the_poly5_coefficients(pieces: int) -> None:
    # q from 40 mm to 15 mm over t = 2 s .. 2.5 s: the normalized law is poly5 whatever
    # the units, the start, the sign of the displacement and the cuts
    law = DataLaw("x", _poly5_curve(2.0, 0.5, 40.0, -25.0, pieces))
    c = law.coefficients
    assert c.C_v == pytest.approx(15 / 8, rel=1e-12)
    assert c.C_a == pytest.approx(10 / math.sqrt(3), rel=1e-12)
    assert c.C_j == pytest.approx(60, rel=1e-12)
    assert c.C_v_rms == pytest.approx(math.sqrt(10 / 7), rel=1e-12)
    assert c.C_a_rms == pytest.approx(math.sqrt(120 / 7), rel=1e-12)
    assert law.continuity == 2
    assert law.rest_to_rest and law.end_position == 1.0
    assert all(p.degree == 5 for p in law.pieces)
    tau = np.linspace(0, 1, 11)
    u = tau
    assert law.position(tau) == pytest.approx(10 * u**3 - 15 * u**4 + 6 * u**5, abs=1e-13)


def test_a_curve_that_returns_is_normalized_by_its_excursion() -> None:
    # q = 3 + 16 t^2 (1 - t)^2 on [0, 1]: out by 1 at t = 1/2 and back
    q = np.polynomial.Polynomial([0, 0, 16, -32, 16])
    law = DataLaw("x", PPoly(_coefficients(2.0 * q, 3.0), [0.0, 1.0]))
    assert law.end_position == 0.0
    assert float(law.position(0.5)) == pytest.approx(1.0, abs=1e-14)
    assert float(law.position(2.0)) == 0.0  # at rest back at the start
    # v = 32 t (1 - t)(1 - 2t), largest at t = (3 - sqrt 3)/6: 16 sqrt(3)/9
    assert law.coefficients.C_v == pytest.approx(16 * math.sqrt(3) / 9, rel=1e-12)
    assert law.coefficients.C_a == pytest.approx(32, rel=1e-12)  # a = 32 (1 - 6t + 6t^2)


def _coefficients(p: np.polynomial.Polynomial, constant: float) -> np.ndarray:
    coef = p.coef.copy()
    coef[0] += constant
    return coef[::-1].reshape(-1, 1)


def test_periodic_spline_is_c2_across_the_wrap_and_moves_at_its_ends() -> None:
    # the book's Example 4.8 data (sec. 4.4.2), built here by scipy directly
    t = [0, 5, 7, 8, 10, 15, 18]
    q = [3, -2, -5, 0, 6, 12, 3]
    law = DataLaw("x", CubicSpline(t, q, bc_type="periodic"))
    assert not law.rest_to_rest and law.periodic
    assert law.continuity == 2  # a cubic spline's jerk jumps; q, v, a join at the wrap
    v0, v1 = law.end_speeds
    assert v0 == pytest.approx(v1, rel=1e-12)
    clamped = DataLaw("x", CubicSpline(t, [*q[:-1], 8], bc_type=((1, 0.0), (1, 0.0))))
    assert clamped.rest_to_rest and clamped.continuity == 1  # a jumps from rest at the ends


def test_a_curve_that_does_not_move_is_refused() -> None:
    with pytest.raises(UserError, match="does not move"):
        DataLaw("x", PPoly(np.array([[0.0], [2.0]]), [0.0, 1.0]))


def test_spec_text_is_canonical_and_reads_back() -> None:
    a = data_spec_text({"points": [[0, 0], [0.5, 1e-05], [1, 1.0]], "kind": "cubic_spline",
                        "start": {"velocity": 0.25}})
    b = data_spec_text({"kind": "cubic_spline", "start": {"velocity": 1 / 4},
                        "points": [[0.0, 0], [0.5, 0.00001], [1, 1]]})
    assert a == b == ("{kind: cubic_spline, points: [[0, 0], [0.5, 1.0e-05], [1, 1]], "
                      "start: {velocity: 0.25}}")
    assert is_data_spec(a) and not is_data_spec("cycloidal")
    back = read_data_spec(a)
    assert back["points"][1][1] == 1e-05 and back["start"]["velocity"] == 0.25
    assert data_spec_text(back) == a
    third = 1 / 3
    assert read_data_spec(data_spec_text({"kind": "bspline", "x": [third, "yes", "a b"]}))[
        "x"] == [third, "yes", "a b"]


@pytest.mark.parametrize(("fields", "message"), [
    ({"points": [[0, 0], [1, 1]]}, "needs a kind"),
    ({"kind": "spline", "points": []}, "unknown kind 'spline'"),
    ({"kind": "cubic_spline", "x": float("nan")}, "not a finite number"),
])
def test_bad_mappings_name_the_field(fields: dict, message: str) -> None:
    with pytest.raises(UserError, match=message):
        data_spec_text(fields)


def test_bad_spec_text_is_a_user_error() -> None:
    with pytest.raises(UserError, match="cannot read the law"):
        read_data_spec("{kind: cubic_spline, points: [[0, 0]")
