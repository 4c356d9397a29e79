"""The classic polynomial spline of order k through via-points (slides, seed 002).

A spline of order k is made of N - 1 polynomials of degree k - 1,
S_j = F_j + E_j (t - t_j) + D_j (t - t_j)^2 + ... (ascending powers, the column order of
the slides' matrix), joined at the interior via-points with continuous derivatives up to
k - 2. Its k (N - 1) coefficients are fixed by (N - 2)(k - 1) continuity conditions, N
positions and k - 2 more conditions chosen by the user ("problema inverso": the count of
unknowns says how many boundary conditions are needed): velocity, acceleration, jerk,
snap at the ends, at interior times, or cyclic (book eq. 4.45).

scipy has no solver for this system (make_interp_spline takes end derivatives only in
the B-form and not at interior times, CubicSpline only cubics), so it is written here as
the slides write it and solved with one checked dense solve. The same checked solve
(``solve_conditions``) serves the B-spline and NURBS systems.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError
from sizer.laws.multipoint import fields as F

if TYPE_CHECKING:
    from scipy.interpolate import PPoly

Condition = tuple[float, int, float, str]
"""(time, derivative order, value, label naming the field, e.g. ``"end.jerk"``)."""

Label = tuple[str | None, str]
"""(field the row comes from or None for a structural row, text naming the row)."""

SINGULAR_RCOND = 1e-11
"""A system whose reciprocal condition number (rows scaled to unit max norm, LAPACK's
1-norm estimate) is below this is refused as singular."""

MAX_NAMING_SVD = 1500
"""Above this many unknowns a refused system names all the user's conditions instead of
finding the dependent ones by an SVD (seconds)."""

USER_FIELDS = ("start", "end", "conditions", "periodic")


def end_conditions(t0: float, tn: float, start: Mapping[int, float] | None = None,
                   end: Mapping[int, float] | None = None) -> list[Condition]:
    """The ``start`` and ``end`` mappings {order: value} as conditions at t_0 and t_n."""
    out: list[Condition] = []
    for key, where, given in (("start", t0, start), ("end", tn, end)):
        for order, value in sorted((given or {}).items()):
            out.append((where, order, value, f"{key}.{_name(order)}"))
    return out


def _name(order: int) -> str:
    return next((n for n, k in F.ORDER_NAMES.items() if k == order), f"derivative {order}")


def derivative_row(k: int, dt: float, r: int) -> np.ndarray:
    """d^r/dt^r of the monomials 1, dt, ..., dt^(k-1): the slides' S, V, A, J rows."""
    row = np.zeros(k)
    for m in range(r, k):
        row[m] = math.perm(m, r) * dt ** (m - r)
    return row


def classic_system(t: np.ndarray, q: np.ndarray, k: int,
                   conditions: Sequence[Condition] = (), periodic: Sequence[int] = ()
                   ) -> tuple[np.ndarray, np.ndarray, list[Label]]:
    """The slides' linear system on the coefficients, in their block order: continuity at
    the interior points (derivatives 0..k-2), interior positions s_j(t_j) = H_j (left
    piece), start and end positions, then the conditions and the cyclic rows.

    Unknown j*k + m is the coefficient of (t - t_j)^m of piece j (F_j, E_j, ... A_j).
    """
    t = np.asarray(t, dtype=float)
    n_pieces = len(t) - 1
    h = np.diff(t)
    n = k * n_pieces
    rows: list[np.ndarray] = []
    rhs: list[float] = []
    labels: list[Label] = []

    def add(entries: dict[int, np.ndarray], value: float, label: Label) -> None:
        row = np.zeros(n)
        for piece, part in entries.items():
            row[piece * k:(piece + 1) * k] += part
        rows.append(row)
        rhs.append(value)
        labels.append(label)

    for i in range(1, n_pieces):
        for r in range(k - 1):
            add({i - 1: derivative_row(k, h[i - 1], r), i: -derivative_row(k, 0.0, r)}, 0.0,
                (None, f"continuity of derivative {r} at t = {t[i]:g}"))
    for i in range(1, n_pieces):
        add({i - 1: derivative_row(k, h[i - 1], 0)}, float(q[i]), ("points", f"points[{i}]"))
    add({0: derivative_row(k, 0.0, 0)}, float(q[0]), ("points", "points[0]"))
    add({n_pieces - 1: derivative_row(k, h[-1], 0)}, float(q[-1]),
        ("points", f"points[{n_pieces}]"))
    for when, r, value, label in conditions:
        j = min(int(np.searchsorted(t, when, side="right")) - 1, n_pieces - 1)
        add({j: derivative_row(k, when - t[j], r)}, value, (label.split(".")[0].split("[")[0],
                                                            label))
    for r in periodic:
        add({0: derivative_row(k, 0.0, r), n_pieces - 1: -derivative_row(k, h[-1], r)}, 0.0,
            ("periodic", f"periodic.{_name(r)}"))
    return np.array(rows).reshape(len(rows), n), np.array(rhs), labels


def solve_conditions(A: np.ndarray, b: np.ndarray, labels: Sequence[Label],
                     fallback: str, column_scale: np.ndarray | None = None) -> np.ndarray:
    """Solve the square system A x = b, or UserError naming the conditions that make it
    singular (the rows in the left null space: dependent or contradictory).

    The unknowns are x = column_scale * y (e.g. the coefficients of (t - t_j)^m as those
    of ((t - t_j)/h_j)^m, which are all of the same size), the rows are scaled to unit
    max norm; LAPACK's LU with its condition estimate (getrf, gecon) is the rank test,
    and only a refused system pays for an SVD to find the rows at fault (numpy's solve
    would not say which they are).
    """
    from scipy.linalg import lapack

    column = np.ones(A.shape[1]) if column_scale is None else np.asarray(column_scale)
    As = A * column
    scale = np.max(np.abs(As), axis=1)
    scale[scale == 0.0] = 1.0
    As = As / scale[:, None]
    lu, piv, info = lapack.dgetrf(As)
    rcond = 0.0
    if info == 0:
        rcond, _ = lapack.dgecon(lu, float(np.max(np.sum(np.abs(As), axis=0))))
    if info != 0 or not rcond > SINGULAR_RCOND:
        raise _singular(As, labels, fallback)
    y, _ = lapack.dgetrs(lu, piv, b / scale)
    return y * column


def _singular(As: np.ndarray, labels: Sequence[Label], fallback: str) -> UserError:
    """The UserError of a singular system, naming the rows of its left null space (the
    user's conditions first, then the via-points)."""
    named = [lab for lab in labels if lab[0] is not None]
    if len(As) <= MAX_NAMING_SVD:
        U, s, _ = np.linalg.svd(As)
        weak = s <= max(SINGULAR_RCOND * s[0], s[-1])
        weight = np.max(np.abs(U[:, weak]), axis=1)
        involved = np.flatnonzero(weight > 1e-6 * weight.max())
        named = [labels[i] for i in involved.tolist() if labels[i][0] is not None]
    user = [lab for lab in named if lab[0] in USER_FIELDS]
    field = user[0][0] if user else fallback
    texts = [lab[1] for lab in user + [lab for lab in named if lab not in user]]
    listed = ", ".join(texts[:8]) + (", ..." if len(texts) > 8 else "")
    return UserError(f"the conditions make the system singular (dependent or "
                     f"contradictory): {listed}; change or drop one of them", field=field)


def check_count(needed: int, given: Sequence[Label], what: str) -> None:
    """UserError unless the conditions beyond the via-points are exactly ``needed``."""
    if len(given) == needed:
        return
    listed = ", ".join(lab[1] for lab in given) or "none"
    if len(given) < needed:
        raise UserError(f"{what} needs {needed} conditions (start, end, conditions, "
                        f"periodic), got {len(given)} ({listed}): add "
                        f"{needed - len(given)}", field="end")
    raise UserError(f"{what} needs {needed} conditions (start, end, conditions, periodic), "
                    f"got {len(given)} ({listed}): {len(given) - needed} too many",
                    field=str(given[-1][0]))


def check_conditions(t0: float, tn: float, conditions: Sequence[Condition],
                     highest: int) -> None:
    """Each condition inside [t_0, t_n] and of order at most ``highest``."""
    for when, r, _, label in conditions:
        if not t0 <= when <= tn:
            raise UserError(f"t = {when:g} is outside the via-points' interval "
                            f"[{t0:g}, {tn:g}]", field=label.rsplit(".", 1)[0])
        if r > highest:
            raise UserError(f"the spline's derivative {r} is not defined there (at most "
                            f"{highest})", field=label)


def poly_spline(t: np.ndarray, q: np.ndarray, order: int,
                start: Mapping[int, float] | None = None,
                end: Mapping[int, float] | None = None,
                conditions: Sequence[Condition] = (), periodic: Sequence[int] = ()
                ) -> PPoly:
    """The classic spline of order k (slides): pieces of degree k - 1 through (t_j, q_j),
    C^(k-2) at the interior points, with exactly k - 2 conditions (start/end mappings
    {order: value}, interior ``conditions`` (t, order, value, label), cyclic orders).

    Solved in the normalized time u = (t - t_0)/T (a condition of order r scales by
    T^r) so that the system's conditioning does not depend on the time unit, and for
    the coefficients of each piece's own ((u - u_j)/h_j)^m, so that it does not grow
    with the number of pieces.
    """
    from scipy.interpolate import PPoly

    t = np.asarray(t, dtype=float)
    q = np.asarray(q, dtype=float)
    k = int(order)
    every = end_conditions(float(t[0]), float(t[-1]), start, end) + list(conditions)
    check_conditions(float(t[0]), float(t[-1]), every, k - 1)
    for when, r, _, label in every:
        if r > k - 2 and np.any(np.isclose(when, t[1:-1], rtol=0.0,
                                           atol=1e-12 * (t[-1] - t[0]))):
            raise UserError(f"the order-{k} spline is only C^{k - 2} at the via-point "
                            f"t = {when:g}: its derivative {r} jumps there", field=label)
    given = [(label.split(".")[0].split("[")[0], label) for *_, label in every]
    given += [("periodic", f"periodic.{_name(r)}") for r in periodic]
    check_count(k - 2, given, f"order {k} through {len(t)} points")
    T = float(t[-1] - t[0])
    u = (t - t[0]) / T
    scaled = [((w - t[0]) / T, r, v * T ** r, lab) for w, r, v, lab in every]
    A, b, labels = classic_system(u, q, k, scaled, periodic)
    local = (np.diff(u)[:, None] ** -np.arange(k, dtype=float)).ravel()
    a = solve_conditions(A, b, labels, "points", local).reshape(len(t) - 1, k)
    c = (a / T ** np.arange(k)).T[::-1]
    return PPoly(np.ascontiguousarray(c), t)


POLY_SPLINE_FIELDS = ("points", "times", "positions", "order", "degree", "start", "end",
                      "conditions", "periodic")


def build_poly_spline(fields: Mapping[str, Any]) -> PPoly:
    """kind ``poly_spline``: the slides' classic spline of order k through via-points."""
    F.refuse_unknown(fields, POLY_SPLINE_FIELDS, "poly_spline")
    k = F.order_of(fields)
    t, q = F.points(fields, minimum=2)
    return poly_spline(t, q, k, F.conditions(fields, "start"), F.conditions(fields, "end"),
                       F.timed_conditions(fields), F.periodic(fields))
