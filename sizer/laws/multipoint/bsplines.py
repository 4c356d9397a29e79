"""B-spline trajectories through via-points with kinematic conditions (book sec. 4.5,
slides "B-Splines: Modalità operativa").

s(t) = sum_j p_j B_j^p(t) (eq. 4.41), degree p = k - 1 (the slides' order k). The control
points solve A p = c (eqs. 4.44, 4.46, 4.47): one row per via-point s(t_k) = q_k, one per
kinematic condition s^(i)(t) = v (at the ends or at chosen interior times) and one per
cyclic condition s^(i)(t_0) = s^(i)(t_n) (eq. 4.45). The knots are the user's, or the
book's (4.42) for an odd degree and (4.43) for an even one.

scipy.interpolate.BSpline gives the basis functions and their derivatives (its
make_interp_spline takes conditions only at the ends and not cyclic ones mixed with
kinematic ones, so the system is stacked here and solved with the checked solve of
:mod:`~sizer.laws.multipoint.poly_splines`). The result is a PPoly (PPoly.from_spline).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError
from sizer.laws.multipoint import fields as F
from sizer.laws.multipoint.poly_splines import (
    Condition,
    Label,
    check_conditions,
    check_count,
    end_conditions,
    solve_conditions,
)

if TYPE_CHECKING:
    from scipy.interpolate import BSpline, PPoly

Basis = Callable[[np.ndarray, int], np.ndarray]
"""basis(x, nu) -> matrix (len(x), number of control points) of nu-th derivatives."""

KNOT_RULES = ("points", "midpoints")
"""``knots: points`` is the book's eq. (4.42), ``knots: midpoints`` its eq. (4.43)."""


def basis_matrix(knots: np.ndarray, degree: int, x: np.ndarray, nu: int = 0) -> np.ndarray:
    """B_j^{p(nu)}(x) for every basis function j (columns): a BSpline whose coefficients
    are the identity (BSpline.design_matrix gives no derivatives)."""
    from scipy.interpolate import BSpline

    n = len(knots) - degree - 1
    x = np.atleast_1d(np.asarray(x, dtype=float))
    if nu > degree:
        return np.zeros((len(x), n))
    return BSpline(knots, np.eye(n), degree, extrapolate=True)(x, nu)


def default_knots(t: np.ndarray, degree: int, rule: str | None = None) -> np.ndarray:
    """The book's knots: (4.42) [t_0 x (p+1), t_1, ..., t_{n-1}, t_n x (p+1)] or (4.43)
    with the midpoints (t_{k-1} + t_k)/2 inside; by default (4.42) for an odd degree and
    (4.43) for an even one (sec. 4.5: "if p is odd, (4.42) is preferable")."""
    t = np.asarray(t, dtype=float)
    rule = rule or ("points" if degree % 2 else "midpoints")
    inner = t[1:-1] if rule == "points" else (t[:-1] + t[1:]) / 2.0
    return np.concatenate([np.full(degree + 1, t[0]), inner, np.full(degree + 1, t[-1])])


def check_knots(knots: np.ndarray, degree: int, field: str = "knots") -> np.ndarray:
    """Non-decreasing, at least 2 (p + 1), no interior knot repeated more than p times
    (the curve is C^(p - multiplicity) there) and a non-empty base interval."""
    k = degree + 1
    F.increasing(knots, field, strict=False)
    if len(knots) < 2 * k:
        raise UserError(f"order {k} (degree {degree}) needs at least {2 * k} knots, got "
                        f"{len(knots)}", field=field)
    lo, hi = knots[degree], knots[-k]
    if not hi > lo:
        raise UserError(f"the base interval [knots[{degree}], knots[{len(knots) - k}]] is "
                        f"empty", field=field)
    values, counts = np.unique(knots, return_counts=True)
    for value, count in zip(values, counts, strict=True):
        inside = lo < value < hi
        if count > (degree if inside else k):
            raise UserError(f"knot {value:g} is repeated {count} times: at most "
                            f"{degree if inside else k} {'inside' if inside else 'at an end'}"
                            f" for degree {degree}", field=field)
    return knots


def bspline_system(t: np.ndarray, q: np.ndarray, basis: Basis,
                   conditions: Sequence[Condition] = (), periodic: Sequence[int] = (),
                   ) -> tuple[np.ndarray, np.ndarray, list[Label]]:
    """Stack eq. (4.44) rows: the via-points, then the conditions, then the cyclic rows
    (4.45) B^(i)(t_0) - B^(i)(t_n)."""
    t = np.asarray(t, dtype=float)
    rows = [basis(t, 0)]
    rhs = [np.asarray(q, dtype=float)]
    labels: list[Label] = [("points", f"points[{i}]") for i in range(len(t))]
    for when, r, value, label in conditions:
        rows.append(basis(np.array([when]), r))
        rhs.append(np.array([value]))
        labels.append((label.split(".")[0].split("[")[0], label))
    for r in periodic:
        rows.append(basis(t[:1], r) - basis(t[-1:], r))
        rhs.append(np.zeros(1))
        labels.append(("periodic", f"periodic.{_name(r)}"))
    return np.vstack(rows), np.concatenate(rhs), labels


def _name(order: int) -> str:
    return next((n for n, k in F.ORDER_NAMES.items() if k == order), f"derivative {order}")


def solve_control_points(t: np.ndarray, q: np.ndarray, degree: int, knots: np.ndarray,
                         conditions: Sequence[Condition], periodic: Sequence[int],
                         basis_of: Callable[[np.ndarray], Basis], what: str,
                         knots_field: str = "knots") -> np.ndarray:
    """Control points meeting the via-points and the conditions, solved in the
    normalized time u = (t - t_0)/T: the basis functions do not change under an affine
    map of the knots, a condition of order r scales by T^r."""
    t = np.asarray(t, dtype=float)
    t0, tn = float(t[0]), float(t[-1])
    T = tn - t0
    tol = 1e-12 * T
    if abs(knots[degree] - t0) > tol or abs(knots[-degree - 1] - tn) > tol:
        raise UserError(f"the knots' base interval [knots[{degree}], "
                        f"knots[{len(knots) - degree - 1}]] = [{knots[degree]:g}, "
                        f"{knots[-degree - 1]:g}] must be the via-points' interval "
                        f"[{t0:g}, {tn:g}]", field=knots_field)
    check_conditions(t0, tn, conditions, degree)
    for when, r, _, label in conditions:
        multiplicity = int(np.sum(np.abs(knots - when) <= tol)) if t0 < when < tn else 0
        if r > degree - multiplicity:
            raise UserError(f"the spline is only C^{degree - multiplicity} at the knot "
                            f"t = {when:g} (repeated {multiplicity} times): its derivative "
                            f"{r} jumps there", field=label)
    n_ctrl = len(knots) - degree - 1
    given = [(label.split(".")[0].split("[")[0], label) for *_, label in conditions]
    given += [("periodic", f"periodic.{_name(r)}") for r in periodic]
    if n_ctrl < len(t):
        raise UserError(f"{what}: the {len(knots)} knots give {n_ctrl} control points, "
                        f"fewer than the {len(t)} via-points; add knots", field=knots_field)
    check_count(n_ctrl - len(t), given, f"{what} ({n_ctrl} control points, {len(t)} "
                                        f"via-points)")
    u = (t - t0) / T
    scaled = [((w - t0) / T, r, v * T ** r, lab) for w, r, v, lab in conditions]
    A, b, labels = bspline_system(u, q, basis_of((knots - t0) / T), scaled, periodic)
    return solve_conditions(A, b, labels, knots_field)


def interpolating_bspline(t: np.ndarray, q: np.ndarray, degree: int,
                          knots: np.ndarray | str | None = None,
                          start: Mapping[int, float] | None = None,
                          end: Mapping[int, float] | None = None,
                          conditions: Sequence[Condition] = (),
                          periodic: Sequence[int] = ()) -> BSpline:
    """Sec. 4.5: the B-spline of degree p through (t_k, q_k) meeting the conditions;
    ``knots`` an array, ``"points"`` (4.42), ``"midpoints"`` (4.43) or None (by parity)."""
    from scipy.interpolate import BSpline

    t = np.asarray(t, dtype=float)
    if knots is None or isinstance(knots, str):
        u = default_knots(t, degree, knots)
    else:
        u = check_knots(np.asarray(knots, dtype=float), degree)
    every = end_conditions(float(t[0]), float(t[-1]), start, end) + list(conditions)
    what = f"order {degree + 1} (degree {degree}) through {len(t)} points"
    P = solve_control_points(t, q, degree, u, every, periodic,
                             lambda knots_u: _bspline_basis(knots_u, degree), what)
    return BSpline(u, P, degree)


def _bspline_basis(knots: np.ndarray, degree: int) -> Basis:
    return lambda x, nu: basis_matrix(knots, degree, x, nu)


def ppoly_from_bspline(spline: BSpline) -> PPoly:
    """PPoly.from_spline restricted to the base interval, without the zero-length pieces
    of repeated knots (so that the breakpoints ``x`` increase strictly)."""
    from scipy.interpolate import PPoly

    p = PPoly.from_spline(spline)
    k = spline.k
    lo, hi = spline.t[k], spline.t[-k - 1]
    keep = (np.diff(p.x) > 0.0) & (p.x[:-1] >= lo) & (p.x[1:] <= hi)
    idx = np.flatnonzero(keep)
    x = np.append(p.x[idx], p.x[idx[-1] + 1])
    return PPoly(np.ascontiguousarray(p.c[:, idx]), x)


def direct_counts(knots: np.ndarray, degree: int, count: int, field: str) -> None:
    """UserError unless ``count`` (control points or weights) is len(knots) - order."""
    k = degree + 1
    if count < k and field == "control_points":
        raise UserError(f"order {k} needs at least {k} control points, got {count}",
                        field=field)
    if count != len(knots) - k:
        raise UserError(f"must have {len(knots) - k} numbers (one per control point: "
                        f"{len(knots)} knots - order {k}), got {count}", field=field)


BSPLINE_FIELDS = ("points", "times", "positions", "order", "degree", "knots", "start",
                  "end", "conditions", "periodic", "control_points")
_SOLVE_ONLY = ("points", "times", "positions", "start", "end", "conditions", "periodic")


def read_knots(fields: Mapping[str, Any], degree: int) -> np.ndarray | str | None:
    """``knots``: a list of numbers, ``points`` (4.42), ``midpoints`` (4.43) or absent."""
    raw = fields.get("knots")
    if raw is None:
        return None
    if isinstance(raw, str):
        if raw not in KNOT_RULES:
            raise UserError(f"must be a list of numbers or one of {', '.join(KNOT_RULES)} "
                            f"(book eqs. 4.42, 4.43), got {raw!r}", field="knots")
        return raw
    return check_knots(F.numbers(fields, "knots"), degree)


def read_direct(fields: Mapping[str, Any], kind: str) -> tuple[int, np.ndarray, np.ndarray]:
    """(degree, knots, control points) of a spline given by its control points."""
    for key in _SOLVE_ONLY:
        if key in fields:
            raise UserError(f"a {kind} given by control_points takes no {key} (it is not "
                            f"solved)", field=key)
    degree = F.order_of(fields) - 1
    if "knots" not in fields or isinstance(fields["knots"], str):
        raise UserError("control_points need the knots as a list of numbers",
                        field="knots")
    knots = check_knots(F.numbers(fields, "knots"), degree)
    P = F.numbers(fields, "control_points")
    direct_counts(knots, degree, len(P), "control_points")
    return degree, knots, P


def build_bspline(fields: Mapping[str, Any]) -> PPoly:
    """kind ``bspline``: sec. 4.5 / the slides, solved from via-points and conditions, or
    given by ``control_points`` and ``knots``."""
    from scipy.interpolate import BSpline

    F.refuse_unknown(fields, BSPLINE_FIELDS, "bspline")
    if "control_points" in fields:
        degree, given, P = read_direct(fields, "bspline")
        return ppoly_from_bspline(BSpline(given, P, degree))
    degree = F.order_of(fields) - 1
    knots = read_knots(fields, degree)
    t, q = F.points(fields, minimum=2)
    spline = interpolating_bspline(t, q, degree, knots, F.conditions(fields, "start"),
                                   F.conditions(fields, "end"), F.timed_conditions(fields),
                                   F.periodic(fields))
    return ppoly_from_bspline(spline)
