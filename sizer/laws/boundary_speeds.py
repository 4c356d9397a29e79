"""Motion laws between non-null boundary speeds, as a basis linear in the speeds.

A move of a machine cycle goes h (signed) in T from speed v0 to speed v1. Normalized,
q_N(u), u = t/T in [0, 1], has q_N(0) = 0, q_N(1) = 1, q_N'(0) = s0 = v0*T/h and
q_N'(1) = s1 = v1*T/h. For the families below, with their phase shares (fractions of T)
fixed, the shape is linear in (s0, s1) on fixed breakpoints:

    q_N(u) = B_h(u) + s0*B_0(u) + s1*B_1(u)

- trapezoid (book sec. 3.2.7, eqs. 3.13a-c): T_a = alpha*T, T_d = alpha_d*T, the cruise
  speed v_v = (h - (v0*T_a + v1*T_d)/2)/(T - T_a/2 - T_d/2) from the displacement;
  constant acceleration is the trapezoid with alpha = alpha_d = 1/2 (sec. 2.1.2);
- double S (sec. 3.4, eqs. 3.30a-g; assigned phase durations as in sec. 3.4.6):
  T_a = alpha*T, T_j1 = beta*T_a, T_d = alpha_d*T, T_j2 = beta_d*T_d, null boundary
  accelerations; the cruise speed is the trapezoid's (each phase covers
  (v_v + v_k)*T_phase/2);
- polynomials of degree 2m + 1 = 3, 5, 7 (sec. 2.1.4-2.1.6) with the boundary speeds and
  null boundary derivatives of orders 2..m.

Polynomials of degree 5 and 7 also meet given boundary accelerations a0, a1 (sec. 2.1.5:
the quintic with q, q', q'' given at both ends, eq. 2.5; sec. 2.1.6 with null boundary
jerks), normalized r0 = a0*T^2/h, r1 = a1*T^2/h, with two more basis functions:

    q_N(u) = B_h(u) + s0*B_0(u) + s1*B_1(u) + r0*B_a0(u) + r1*B_a1(u)

(``BoundaryBasis.meets_accelerations``). The other families cannot: the trapezoid's end
accelerations are those of its ramps, the double S starts and ends at a = 0, the cubic has
no freedom left.

Each basis function is a piecewise polynomial on the same breaks, kept as coefficients of
ascending powers of (u - breaks[p]); a candidate's shape is one linear combination of
them (``BoundaryBasis.combine``), so law work is done once per canonical spec.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache

import numpy as np

from sizer.errors import UserError
from sizer.laws.base import LAW_CACHE_SIZE, MotionLaw, Parameter
from sizer.laws.piecewise_polynomial import (
    MIN_FRACTION,
    ConstantAcceleration,
    DoubleS,
    Trapezoidal,
)
from sizer.laws.polynomial import Polynomial
from sizer.laws.registry import resolve
from sizer.laws.spec import AUTO

BOUNDARY_DEGREES = (3, 5, 7)
"""Polynomial degrees with a boundary-speed form (the book's sec. 2.1.4-2.1.6)."""

BASIS_NAMES = ("h", "s0", "s1")
"""The basis functions in order: displacement, start speed, end speed."""

ACCELERATION_DEGREES = (5, 7)
"""Polynomial degrees that also meet boundary accelerations (sec. 2.1.5-2.1.6)."""

ACCELERATION_BASIS_NAMES = ("r0", "r1")
"""The basis functions of ``BoundaryBasis.acceleration_coefficients``: start and end
acceleration."""


@dataclass(frozen=True, eq=False)
class BoundaryBasis:
    """The boundary-speed form of a law: q_N = B_h + s0*B_0 + s1*B_1 on fixed breaks.

    ``coefficients[b, p, k]`` is the coefficient of (u - breaks[p])^k of basis b
    (B_h, B_0, B_1) on piece p, u in [breaks[p], breaks[p + 1]]. ``continuity`` is the
    class C^k of the move joined to neighbours whose derivatives of order 2 and higher
    vanish at the joins (dwells, runs, other such moves): position and velocity always
    match; k >= 2 when the acceleration is continuous inside and null at both ends for
    every (s0, s1) -- the rest-to-rest law's class.

    ``acceleration_coefficients[b, p, k]``: the same for B_a0, B_a1 (q_N''(0) = 1,
    resp. q_N''(1) = 1, every other boundary condition null) on the same breaks, for the
    families that meet boundary accelerations (polynomials of degree 5 and 7); None for
    the others. ``continuity`` and ``jerk_bounded`` are those of r0 = r1 = 0: with non-zero
    boundary accelerations the move's acceleration is continuous inside, and it steps at a
    join where the neighbour's differs (a jerk impulse there).
    """

    spec: str
    breaks: np.ndarray
    coefficients: np.ndarray
    continuity: int
    acceleration_coefficients: np.ndarray | None = None

    @property
    def pieces(self) -> int:
        return self.coefficients.shape[1]

    @property
    def degree(self) -> int:
        return self.coefficients.shape[2] - 1

    @property
    def jerk_bounded(self) -> bool:
        """True when the acceleration is continuous inside and null at both ends, for
        every (s0, s1): no jerk impulse in the move nor at its joins to such neighbours."""
        return self.continuity >= 2

    @property
    def acceleration_zero_at_ends(self) -> bool:
        """q_N''(0) = q_N''(1) = 0 for every (s0, s1) (double S, degrees 5 and 7)."""
        return self.continuity >= 2

    @property
    def meets_accelerations(self) -> bool:
        """True when non-zero boundary accelerations r0, r1 can be given to
        :meth:`combine` (polynomials of degree 5 and 7, sec. 2.1.5-2.1.6)."""
        return self.acceleration_coefficients is not None

    def derivative_basis(self, order: int) -> np.ndarray:
        """(3, P, d + 1 - order) coefficients of the order-th derivative of each basis
        function, in powers of (u - breaks[p]) (order 0: ``coefficients``)."""
        return _derivative_coefficients(self.coefficients, order)

    def acceleration_basis(self, order: int) -> np.ndarray:
        """(2, P, d + 1 - order) coefficients of the order-th derivative of B_a0, B_a1;
        ValueError for a form that does not meet boundary accelerations."""
        if self.acceleration_coefficients is None:
            raise ValueError(f"{self.spec}: {_CANNOT}")
        return _derivative_coefficients(self.acceleration_coefficients, order)

    def combine(self, s0: np.ndarray | float, s1: np.ndarray | float,
                order: int = 0, *, r0: np.ndarray | float | None = None,
                r1: np.ndarray | float | None = None) -> np.ndarray:
        """(n, P, d + 1 - order) piece coefficients of the order-th derivative of the
        shapes of n moves of normalized boundary speeds s0, s1 (arrays of shape (n,)).

        ``r0``, ``r1``: normalized boundary accelerations a0*T^2/h, a1*T^2/h (arrays (n,);
        None: 0), only where ``meets_accelerations``: a form that does not meet them takes
        None or zeros only (ValueError otherwise)."""
        s0, s1 = np.broadcast_arrays(np.atleast_1d(np.asarray(s0, dtype=float)),
                                     np.atleast_1d(np.asarray(s1, dtype=float)))
        basis = self.derivative_basis(order)
        out = basis[0] + s0[:, None, None] * basis[1] + s1[:, None, None] * basis[2]
        if r0 is None and r1 is None:
            return out
        r0, r1, _ = np.broadcast_arrays(
            np.atleast_1d(np.asarray(0.0 if r0 is None else r0, dtype=float)),
            np.atleast_1d(np.asarray(0.0 if r1 is None else r1, dtype=float)), s0)
        if self.acceleration_coefficients is None:
            if np.any(r0) or np.any(r1):
                raise ValueError(f"{self.spec}: {_CANNOT}")
            return out
        extra = self.acceleration_basis(order)
        return out + r0[:, None, None] * extra[0] + r1[:, None, None] * extra[1]

    def derivative(self, u: np.ndarray | float, order: int = 0,
                   s0: np.ndarray | float = 0.0, s1: np.ndarray | float = 0.0, *,
                   r0: np.ndarray | float | None = None,
                   r1: np.ndarray | float | None = None) -> np.ndarray:
        """The order-th derivative of q_N at u for each of n moves: shape (n, len(u)).

        u is clamped to [0, 1]; at an interior break the piece on the right is used and
        u = 1 belongs to the last piece (as sizer.laws.MotionLaw.derivative). ``r0``,
        ``r1`` as in :meth:`combine`."""
        u = np.clip(np.atleast_1d(np.asarray(u, dtype=float)), 0.0, 1.0)
        index = np.clip(np.searchsorted(self.breaks, u, side="right") - 1, 0, self.pieces - 1)
        x = u - self.breaks[index]
        coefficients = self.combine(s0, s1, order, r0=r0, r1=r1)[:, index, :]  # (n, m, k)
        out = np.zeros(coefficients.shape[:2])
        for k in range(coefficients.shape[2] - 1, -1, -1):  # Horner over the powers
            out = out * x + coefficients[:, :, k]
        return out


_CANNOT = ("this law cannot start or end at a non-zero acceleration; polynomials of "
           "degree 5 and 7 can")


def has_boundary_form(spec: str | MotionLaw) -> bool:
    """True when the law of the spec has a boundary-speed form (:func:`boundary_form`)."""
    return boundary_form(spec) is not None


def meets_accelerations(spec: str | MotionLaw) -> bool:
    """True when the law of the spec has a form that also meets non-zero boundary
    accelerations (polynomials of degree 5 and 7; :attr:`BoundaryBasis.meets_accelerations`)."""
    form = boundary_form(spec)
    return form is not None and form.meets_accelerations


def boundary_form(spec: str | MotionLaw) -> BoundaryBasis | None:
    """The boundary-speed form of a law spec, or None when its family has none.

    Trapezoidal, constant acceleration, double S and polynomials of degree 3, 5, 7 have
    one; every other family (cycloidal, harmonic, modified_*, ...) has not. The spec is
    read and validated as a law spec (UserError for a bad one, or for ``auto``: the
    shares must be numbers); forms are built once per canonical spec.

    The trapezoid's and the double S's phase shares alpha, alpha_d range over
    [1e-6, 1 - 1e-6] with alpha + alpha_d <= 1 here (between non-null speeds one phase
    may take most of the move, e.g. the book's Example 3.6); a sum within 1e-12 of 1 is
    taken as 1 (no cruise). The registry's rest-to-rest laws keep each share in
    [1e-6, 1/2], where every pair fits; a spec inside those ranges has the law's
    canonical spec.
    """
    if isinstance(spec, MotionLaw):
        family, params = type(spec), dict(spec.params)
    else:
        family, values = resolve(spec)
        if any(value == AUTO for value in values.values()):
            raise UserError(f"{family.law_id}: a move between boundary speeds needs its "
                            f"shape parameters as numbers, not 'auto'")
        params = _boundary_params(family, {k: float(v) for k, v in values.items()})
    if family not in (ConstantAcceleration, Trapezoidal, DoubleS, Polynomial):
        return None
    return _form(family.law_id, family.canonical_spec(params), tuple(params.items()))


SUM_TOLERANCE = 1e-12
"""alpha + alpha_d above 1 by at most this is rounding: alpha_d becomes 1 - alpha."""

_WIDE_SHARES = {
    name: Parameter(name, None, MIN_FRACTION, 1.0 - MIN_FRACTION)
    for name in ("alpha", "alpha_d")
}
_DECELERATION_OF = {"alpha_d": "alpha", "beta_d": "beta"}


def _boundary_params(family: type[MotionLaw], given: dict[str, float]) -> dict[str, float]:
    """The canonical parameters of a boundary-speed spec: the law's own, except that the
    trapezoid's and double S's alpha and alpha_d may exceed 1/2 (their sum at most 1)."""
    if family not in (Trapezoidal, DoubleS):
        return family.canonical_params(given)
    wide = {k: _WIDE_SHARES[k].validate(family.law_id, v) for k, v in given.items()
            if k in _WIDE_SHARES}
    narrow = family.canonical_params({k: v for k, v in given.items() if k not in wide})
    values: dict[str, float] = {}
    for name in (p.name for p in family.parameters):  # a share before its deceleration's
        value = wide.get(name, narrow.get(name))
        # a deceleration share the symmetric law's canonical parameters leave out: its own
        values[name] = values[_DECELERATION_OF[name]] if value is None else value
    total = values["alpha"] + values["alpha_d"]
    if total > 1.0 + SUM_TOLERANCE:
        raise UserError(f"{family.law_id}: alpha + alpha_d = {total:.6g} is more than 1: the "
                        f"acceleration and deceleration phases do not fit in the move; "
                        f"valid: alpha, alpha_d in [1e-06, 1) with alpha + alpha_d <= 1")
    if total > 1.0:
        values["alpha_d"] = 1.0 - values["alpha"]
    for dependent, source in _DECELERATION_OF.items():  # the symmetric law's spec
        if dependent in values and (dependent not in given or values[dependent] == values[source]):
            del values[dependent]
    return values


@lru_cache(maxsize=LAW_CACHE_SIZE)
def _form(law_id: str, spec: str,
          values: tuple[tuple[str, float], ...]) -> BoundaryBasis | None:
    """Keyed by the canonical spec (the values ride along to build the form)."""
    params = dict(values)
    if law_id == ConstantAcceleration.law_id:
        return _trapezoid(spec, 0.5, 0.5)
    if law_id == Trapezoidal.law_id:
        return _trapezoid(spec, params["alpha"], params.get("alpha_d", params["alpha"]))
    if law_id == DoubleS.law_id:
        return _double_s(spec, params["alpha"], params["beta"],
                         params.get("alpha_d", params["alpha"]),
                         params.get("beta_d", params["beta"]))
    if law_id == Polynomial.law_id and int(params["degree"]) in BOUNDARY_DEGREES:
        return _polynomial(spec, int(params["degree"]))
    return None


# ------------------------------------------------------------ constant-jerk families

def _cruise_speed(alpha: float, alpha_d: float) -> np.ndarray:
    """v_v/(h/T) of each basis (h, s0, s1): (1 - (s0*alpha + s1*alpha_d)/2)/(1 - (alpha
    + alpha_d)/2), sec. 3.2.7 (and 3.4: each phase covers (v_v + v_k)*T_phase/2)."""
    return np.array([1.0, -alpha / 2.0, -alpha_d / 2.0]) / (1.0 - (alpha + alpha_d) / 2.0)


ROUNDING_WIDTH = 4.0 * float(np.finfo(float).eps)
"""Pieces at most this wide are rounding (e.g. 1 - alpha_d vs alpha when alpha + alpha_d
= 1); real ones are at least MIN_FRACTION^2 = 1e-12 wide."""

BASIS_S0 = np.array([0.0, 1.0, 0.0])
BASIS_S1 = np.array([0.0, 0.0, 1.0])


def _constant_jerk_basis(spec: str, breaks: list[float], accelerations: list[np.ndarray],
                         jerks: list[np.ndarray], continuity: int) -> BoundaryBasis:
    """Integrate each basis function exactly from q = 0, q' = s0 over the pieces.

    ``accelerations[p]`` and ``jerks[p]`` are the (3,) basis values of the acceleration at
    the start of piece p and of its constant jerk; pieces of zero width are dropped."""
    breaks = list(np.maximum.accumulate(breaks))  # 1 - alpha_d an ulp below alpha: no cruise
    q, v = np.zeros(3), BASIS_S0.copy()
    rows, kept = [], [breaks[0]]
    for p in range(len(breaks) - 1):
        width = breaks[p + 1] - breaks[p]
        if width <= ROUNDING_WIDTH:
            continue
        a, j = accelerations[p], jerks[p]
        rows.append(np.stack([q, v, a / 2.0, j / 6.0], axis=-1))
        q, v = (q + v * width + a * width**2 / 2.0 + j * width**3 / 6.0,
                v + a * width + j * width**2 / 2.0)
        kept.append(breaks[p + 1])
    coefficients = np.stack(rows, axis=1)  # (3, P, 4)
    if not np.any(coefficients[:, :, 3]):
        coefficients = coefficients[:, :, :3]
    return _frozen(spec, np.array(kept), coefficients, continuity)


def _trapezoid(spec: str, alpha: float, alpha_d: float) -> BoundaryBasis:
    """Eqs. (3.13a-c) normalized: acceleration (v_v - s0)/alpha, deceleration
    (v_v - s1)/alpha_d, breaks 0, alpha, 1 - alpha_d, 1."""
    v_v = _cruise_speed(alpha, alpha_d)
    zero = np.zeros(3)
    return _constant_jerk_basis(
        spec, [0.0, alpha, 1.0 - alpha_d, 1.0],
        [(v_v - BASIS_S0) / alpha, zero, -(v_v - BASIS_S1) / alpha_d], [zero] * 3, 1)


def _double_s(spec: str, alpha: float, beta: float, alpha_d: float,
              beta_d: float) -> BoundaryBasis:
    """Eqs. (3.30a-g) normalized: a_lim_a = (v_v - s0)/(alpha (1 - beta)) reached after
    T_j1 = beta*alpha, a_lim_d = -(v_v - s1)/(alpha_d (1 - beta_d)), T_j2 = beta_d*alpha_d."""
    v_v = _cruise_speed(alpha, alpha_d)
    acc = (v_v - BASIS_S0) / (alpha * (1.0 - beta))
    dec = (v_v - BASIS_S1) / (alpha_d * (1.0 - beta_d))
    t_j1, t_j2 = beta * alpha, beta_d * alpha_d
    zero = np.zeros(3)
    breaks = [0.0, t_j1, alpha - t_j1, alpha, 1.0 - alpha_d, 1.0 - alpha_d + t_j2,
              1.0 - t_j2, 1.0]
    return _constant_jerk_basis(
        spec, breaks, [zero, acc, acc, zero, zero, -dec, -dec],
        [acc / t_j1, zero, -acc / t_j1, zero, -dec / t_j2, zero, dec / t_j2], 2)


# ------------------------------------------------------------------- polynomials

def _polynomial(spec: str, degree: int) -> BoundaryBasis:
    """Degree 2m + 1 with q(0) = 0, q(1) = 1, q'(0) = s0, q'(1) = s1 and null derivatives
    of orders 2..m at both ends (eqs. 2.2, 2.5 and sec. 2.1.6 with a0 = a1 = j0 = j1 = 0);
    for degrees 5 and 7 also B_a0, B_a1 with q''(0) = 1, resp. q''(1) = 1 and every
    other condition null (eq. 2.5 and sec. 2.1.6 with a0, a1 given, j0 = j1 = 0).
    Solved exactly in rationals: c_0..c_m follow from u = 0, the others from u = 1."""
    m = (degree - 1) // 2
    rows = [  # (q(0), q'(0), q(1), q'(1)) of B_h, B_0, B_1
        _hermite(degree, m, [q0, v0] + [0] * (m - 1), [q1, v1] + [0] * (m - 1))
        for q0, v0, q1, v1 in ((0, 0, 1, 0), (0, 1, 0, 0), (0, 0, 0, 1))]
    coefficients = np.array(rows)[:, None, :]  # (3, 1, degree + 1)
    extra = None
    if degree in ACCELERATION_DEGREES:
        zeros = [0] * (m + 1)
        start, end = list(zeros), list(zeros)
        start[2] = end[2] = 1
        extra = np.array([_hermite(degree, m, start, zeros),
                          _hermite(degree, m, zeros, end)])[:, None, :]  # (2, 1, degree + 1)
    return _frozen(spec, np.array([0.0, 1.0]), coefficients, m, extra)


def _hermite(degree: int, m: int, start: list[int], end: list[int]) -> list[float]:
    """Coefficients c_0..c_degree of the polynomial with q^(k)(0) = start[k] and
    q^(k)(1) = end[k], k = 0..m (degree = 2m + 1), exact in rationals."""
    low = [Fraction(start[k], math.factorial(k)) for k in range(m + 1)]  # c_k = q^(k)(0)/k!
    rows = [[Fraction(math.perm(j, k)) for j in range(m + 1, degree + 1)] for k in range(m + 1)]
    # u = 1: sum_j c_j j!/(j - k)! = end[k], less the low part's derivatives there
    rhs = [Fraction(end[k]) - sum(low[j] * math.perm(j, k) for j in range(k, m + 1))
           for k in range(m + 1)]
    return [float(c) for c in low + _solve_exact(rows, rhs)]


def _solve_exact(matrix: list[list[Fraction]], rhs: list[Fraction]) -> list[Fraction]:
    """Gauss-Jordan elimination in rationals (the small Hermite systems are exact)."""
    n = len(rhs)
    rows = [[*row, b] for row, b in zip(matrix, rhs, strict=True)]
    for col in range(n):
        pivot = next(r for r in range(col, n) if rows[r][col] != 0)
        rows[col], rows[pivot] = rows[pivot], rows[col]
        for r in range(n):
            if r != col and rows[r][col] != 0:
                factor = rows[r][col] / rows[col][col]
                rows[r] = [x - factor * y for x, y in zip(rows[r], rows[col], strict=True)]
    return [rows[k][n] / rows[k][k] for k in range(n)]


# ------------------------------------------------------------------------ helpers

def _frozen(spec: str, breaks: np.ndarray, coefficients: np.ndarray,
            continuity: int, acceleration_coefficients: np.ndarray | None = None
            ) -> BoundaryBasis:
    breaks = np.asarray(breaks, dtype=float)
    coefficients = np.ascontiguousarray(coefficients, dtype=float)
    breaks.setflags(write=False)
    coefficients.setflags(write=False)
    if acceleration_coefficients is not None:
        acceleration_coefficients = np.ascontiguousarray(acceleration_coefficients,
                                                         dtype=float)
        acceleration_coefficients.setflags(write=False)
    return BoundaryBasis(spec, breaks, coefficients, continuity, acceleration_coefficients)


def _derivative_coefficients(coefficients: np.ndarray, order: int) -> np.ndarray:
    """Coefficients of the order-th derivative along the last axis (ascending powers)."""
    if order < 0:
        raise ValueError(f"derivative order {order} < 0")
    degree = coefficients.shape[-1] - 1
    if order > degree:
        return np.zeros((*coefficients.shape[:-1], 1))
    powers = np.arange(order, degree + 1)
    factors = np.array([math.perm(int(k), order) for k in powers], dtype=float)
    return coefficients[..., order:] * factors
