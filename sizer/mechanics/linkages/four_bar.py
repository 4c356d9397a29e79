"""The four-bar crank-rocker (seed 003, Figure 2, Table 2 and its section 6 experiment).

Links as in the paper's Figure 2 and Table 2: l1 the crank (driven by the motor), l2 the
coupler, l3 the rocker (the output), l4 the ground. Its angles: q1 the crank, q2 the
coupler, q3 the rocker; q3 has its dead points when crank and coupler are in line
(q1 = q2, and folded q2 = q1 + pi).

Conventions (they reproduce the paper's experiment, l = 0.075, 0.175, 0.100, 0.175 m
at its dead point q1 = 0.318 rad, q3 = 2.246 rad): the crank pivot O2 is the origin and
the rocker pivot O4 is at (l4, 0). theta = q1 is the crank angle from O2->O4,
counter-clockwise; its pin is A = l1 (cos theta, sin theta). q2 (phi) is the coupler's
angle, counter-clockwise from the same axis, B - A = l2 (cos phi, sin phi). The output
s = q3 is the rocker's angle at O4 from O4->O2, positive clockwise, i.e. the
quadrilateral's inner angle at O4: the rocker pin is B = (l4 - l3 cos s, l3 sin s). The
loop closure is then

    l1 cos q1 + l2 cos q2 + l3 cos q3 - l4 = 0,   l1 sin q1 + l2 sin q2 - l3 sin q3 = 0,

i.e. l1 e^{i q1} + l2 e^{i q2} + l3 e^{-i q3} = l4 (the paper does not print its
phi(q); this is the one its numbers fit).

Branch +1 (open, the paper's assembly) has B on the left of the line A->O4, branch -1
(crossed) on its right; the crossed one is the open one mirrored in the ground line:
s_-1(theta) = -s_+1(-theta). For a Grashof crank-rocker (crank the shortest, s + l < p + q)
the rocker never lines up with the ground, so s stays in (0, pi) on branch +1 and in
(-pi, 0) on branch -1 and no wrap-around occurs.

Derivatives in theta are exact: the closure differentiated k times (Faa di Bruno, the
complete Bell polynomials B_k of the angles' derivatives) is linear in q2^(k), q3^(k)
with the same 2x2 matrix at every order, solved per sample by Cramer's rule:
q3^(k) = Re(r_k e^{-i q2}) / (l3 sin(q2 + q3)), q2^(k) = Re(r_k e^{i q3}) / (l2 sin(q2 + q3)),
with r_k the known terms. sin(q2 + q3) = 0 (coupler and rocker in line) never occurs in a
Grashof crank-rocker.

The output coordinate (``coordinate``) may be the rocker's angle q3 (the default), the
coupler's angle q2, or the crank's own angle q1 (for a four-bar driven from its rocker,
whose load turns with the crank: sizer.mechanics.linkages.of_stage reads the linkage in
the other direction, the motor's coordinate and the load's both as functions of q1).
q2 has its extremes where dq2/dq1 = -l1 sin(q1 + q3) / (l2 sin(q2 + q3)) = 0: the crank
parallel to the rocker, e^{i q1} = +-e^{-i q3}. Then B = l4 - c e^{i q1} with
c = l1 + l3 or l1 - l3 and |B - A| = l2 gives cos q1 = (l4^2 + c^2 - l2^2) / (2 l4 c)
(:meth:`FourBar.dead_points`). The coupler does not turn fully in a crank-rocker, so its
angle is read on the branch cut opposite the middle of its swing (continuous).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, replace

import numpy as np

from sizer.errors import UserError
from sizer.mechanics.linkages import MAX_ORDER, outside_range

COORDINATES = ("rocker_angle", "coupler_angle", "crank_angle")
"""The output coordinates a four-bar gives (its ``coordinate`` field)."""

_LINKS = ("crank", "coupler", "rocker", "ground")


@dataclass(frozen=True)
class FourBar:
    """A four-bar crank-rocker: link lengths (m), assembly ``branch`` (+1 open, -1 crossed).

    ``coordinate`` names the output: "rocker_angle" (s = q3, rad), "coupler_angle"
    (s = q2) or "crank_angle" (s = q1, the identity; module docstring).
    """

    crank: float
    coupler: float
    rocker: float
    ground: float
    branch: int = 1
    coordinate: str = "rocker_angle"
    output_linear: bool = False

    def __post_init__(self) -> None:
        lengths = {name: getattr(self, name) for name in _LINKS}
        for name, value in lengths.items():
            if not (isinstance(value, numbers.Real) and not isinstance(value, bool)
                    and math.isfinite(value) and float(value) > 0.0):
                raise UserError(f"must be a positive length, got {value!r} m", field=name)
        if isinstance(self.branch, bool) or self.branch not in (1, -1):
            raise UserError(f"must be +1 (open) or -1 (crossed), got {self.branch!r}",
                            field="branch")
        if self.coordinate not in COORDINATES:
            raise UserError(f"must be one of {', '.join(COORDINATES)}, got "
                            f"{self.coordinate!r}", field="coordinate")
        described = ", ".join(f"{name} {value:g} m" for name, value in lengths.items())
        longest = max(lengths, key=lengths.__getitem__)
        others = sum(lengths.values()) - lengths[longest]
        if not lengths[longest] < others:
            raise UserError(f"the four-bar cannot close: the {longest} ({lengths[longest]:g} m)"
                            f" is not shorter than the other three links together "
                            f"({others:g} m) ({described})", field=longest)
        shorter = [name for name in _LINKS[1:] if lengths[name] <= self.crank]
        if shorter:
            verb = "is" if len(shorter) == 1 else "are"
            raise UserError(f"the crank cannot turn fully: it must be the shortest link, but "
                            f"the {' and the '.join(shorter)} {verb} not longer ({described})",
                            field="crank")
        rest = sum(lengths.values()) - lengths[longest] - self.crank
        if not self.crank + lengths[longest] < rest * (1.0 - 1e-12):
            raise UserError(f"the crank cannot turn fully: the shortest plus the longest link "
                            f"({self.crank:g} + {lengths[longest]:g} m) must be less than the "
                            f"other two ({rest:g} m) (Grashof crank-rocker; {described})",
                            field="crank")

    def output(self, theta: np.ndarray, order: int = 0) -> np.ndarray:
        """d^order s / d theta^order at the crank angles theta, s the ``coordinate``."""
        if not 0 <= order <= MAX_ORDER:
            raise ValueError(f"order {order} not in 0..{MAX_ORDER}")
        theta = np.asarray(theta, dtype=float)
        if self.coordinate == "crank_angle":
            return theta.copy() if order == 0 else np.full(theta.shape, float(order == 1))
        if self.coordinate == "coupler_angle":
            return self.coupler_angle(theta, order)
        phi, s = self._angles(theta)
        if order == 0:
            return s
        return self._derivatives(theta, phi, s, order)[1][order]

    def rocker_angle(self, theta: np.ndarray, order: int = 0) -> np.ndarray:
        """d^order q3 / d theta^order, whatever the output coordinate."""
        return replace(self, coordinate="rocker_angle").output(theta, order)

    def coupler_angle(self, theta: np.ndarray, order: int = 0) -> np.ndarray:
        """d^order q2 / d theta^order (q2 continuous over the coupler's swing)."""
        if not 0 <= order <= MAX_ORDER:
            raise ValueError(f"order {order} not in 0..{MAX_ORDER}")
        theta = np.asarray(theta, dtype=float)
        phi, s = self._angles(theta)
        if order == 0:
            centre = self._coupler_centre()
            return centre + _wrapped(phi - centre)
        return self._derivatives(theta, phi, s, order)[0][order]

    def input_of(self, s: np.ndarray, half: int) -> np.ndarray:
        """theta in [-pi, pi) on the half-turn where ds/dtheta has the sign of ``half``.

        For the rocker angle: s fixes B; the crank pin A is where the circles |A| = l1 and
        |B - A| = l2 meet: theta = delta - branch * half * acos((b^2 + l1^2 - l2^2) /
        (2 l1 b)), delta and b the direction and length of O2->B. For the coupler angle:
        w = l2 e^{i q2} - l4 and |l1 e^{i theta} + w| = l3 give theta = arg(w) +-
        acos((l3^2 - l1^2 - |w|^2) / (2 l1 |w|)), the root where dq2/dtheta has the sign
        of ``half`` (both roots are on the assembly's branch: a Grashof crank-rocker's
        coupler takes each angle of its swing twice per turn on each branch).
        """
        s = np.asarray(s, dtype=float)
        if self.coordinate == "crank_angle":
            return s.copy()
        low, high = self.output_range()
        value = outside_range(s, low, high)
        if value is not None:
            name = self.coordinate.replace("_", " ")
            raise UserError(f"the {name} {value:g} rad is outside its swing "
                            f"[{low:g}, {high:g}] rad", field="output")
        s = np.clip(s, low, high)
        l1, l2, l3, l4 = self.crank, self.coupler, self.rocker, self.ground
        if self.coordinate == "coupler_angle":
            w = l2 * np.exp(1j * s) - l4
            b = np.abs(w)
            c = np.clip((l3 * l3 - l1 * l1 - b * b) / (2.0 * l1 * b), -1.0, 1.0)
            roots = [_wrapped(np.angle(w) + sign * np.arccos(c)) for sign in (1.0, -1.0)]
            slopes = [self.coupler_angle(r, 1) for r in roots]
            return np.where(half * slopes[0] >= half * slopes[1], roots[0], roots[1])
        bx = l4 - l3 * np.cos(s)
        by = l3 * np.sin(s)
        b = np.hypot(bx, by)
        c = np.clip((b * b + l1 * l1 - l2 * l2) / (2.0 * l1 * b), -1.0, 1.0)
        return _wrapped(np.arctan2(by, bx) - self.branch * half * np.arccos(c))

    def dead_points(self) -> np.ndarray:
        """The crank angles where ds/dtheta = 0, [at the largest s, at the least].

        Rocker angle: crank and coupler in line, extended (|O2 B| = l2 + l1) and folded
        (|O2 B| = l2 - l1), B at the law of cosines' angle from the ground line. Coupler
        angle: crank parallel to rocker (module docstring). Crank angle: none."""
        if self.coordinate == "crank_angle":
            return np.empty(0)
        if self.coordinate == "coupler_angle":
            return self._coupler_dead_points()
        l1, l2, l3, l4 = self.crank, self.coupler, self.rocker, self.ground
        extended = _cosine_angle(l1 + l2, l4, l3)
        folded = _cosine_angle(l2 - l1, l4, l3) - math.pi
        if self.branch == 1:
            return _wrapped(np.array([extended, folded]))
        return _wrapped(np.array([-folded, -extended]))

    def output_range(self) -> tuple[float, float]:
        """The output's swing over a turn of the crank (the values at the dead points;
        unbounded for the crank angle)."""
        if self.coordinate == "crank_angle":
            return -math.inf, math.inf
        if self.coordinate == "coupler_angle":
            values = self.coupler_angle(self._coupler_dead_points())
            return float(values[1]), float(values[0])
        l1, l2, l3, l4 = self.crank, self.coupler, self.rocker, self.ground
        extended = _cosine_angle(l4, l3, l1 + l2)
        folded = _cosine_angle(l4, l3, l2 - l1)
        if self.branch == 1:
            return folded, extended
        return -extended, -folded

    def _coupler_dead_points(self) -> np.ndarray:
        """[theta at the largest coupler angle, at the least] (module docstring): of the
        closed form's candidates, those where the assembly's crank and rocker are
        parallel."""
        l1, l2, l3, l4 = self.crank, self.coupler, self.rocker, self.ground
        found = []
        for c in (l1 + l3, l1 - l3):
            cosine = (l4 * l4 + c * c - l2 * l2) / (2.0 * l4 * c)
            if abs(cosine) > 1.0 + 1e-12:
                continue
            angle = math.acos(min(1.0, max(-1.0, cosine)))
            for theta in (angle, -angle):
                s = float(self.rocker_angle(np.array([theta]))[0])
                if abs(math.sin(theta + s)) < 1e-9:
                    found.append(theta)
        phi, _ = self._angles(np.asarray(found, dtype=float))
        if len(found) != 2:  # unreachable for a Grashof crank-rocker
            raise ValueError(f"found {len(found)} coupler dead points")
        first, second = (float(x) for x in found)
        # the largest coupler angle: where q2'' < 0
        curvature = self._derivatives(np.array([first]), phi[:1],
                                      self.rocker_angle(np.array([first])), 2)[0][2]
        if float(curvature[0]) > 0.0:
            first, second = second, first
        return _wrapped(np.array([first, second]))

    def _coupler_centre(self) -> float:
        """The middle of the coupler's swing (its branch cut is opposite): the coupler
        does not turn fully, so its angle unwrapped over a turn of the crank spans less
        than a turn."""
        phi, _ = self._angles(np.linspace(-math.pi, math.pi, 65))
        phi = np.unwrap(phi)
        return float(_wrapped(np.array([0.5 * (phi.max() + phi.min())]))[0])

    def _angles(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The coupler and rocker angles (q2, q3) from the circles about A and O4."""
        l1, l2, l3, l4 = self.crank, self.coupler, self.rocker, self.ground
        ax, ay = l1 * np.cos(theta), l1 * np.sin(theta)
        dx, dy = l4 - ax, -ay
        d = np.hypot(dx, dy)
        ex, ey = dx / d, dy / d
        a = (d * d + l2 * l2 - l3 * l3) / (2.0 * d)
        h = self.branch * np.sqrt(np.maximum(l2 * l2 - a * a, 0.0))
        bx = ax + a * ex - h * ey
        by = ay + a * ey + h * ex
        return np.arctan2(by - ay, bx - ax), np.arctan2(by, l4 - bx)

    def _derivatives(self, theta: np.ndarray, phi: np.ndarray, s: np.ndarray,
                     order: int) -> tuple[list[np.ndarray], list[np.ndarray]]:
        """[q2^(k)], [q3^(k)] for k = 0..order, the closure differentiated k times."""
        l1, l2, l3 = self.crank, self.coupler, self.rocker
        e_phi, e_s = np.exp(1j * phi), np.exp(-1j * s)
        sin_gamma = np.sin(phi + s)
        dphi, ds = [phi], [s]
        for k in range(1, order + 1):
            # d^k e^{i q2} = e^{i q2} B_k(i q2', ..., i q2^(k)); the top term i q2^(k) is
            # the unknown, the rest (_bell_rest) is known from the lower orders.
            known = (l1 * (1j ** k) * np.exp(1j * theta)
                     + l2 * e_phi * _bell_rest([1j * x for x in dphi[1:]], k)
                     + l3 * e_s * _bell_rest([-1j * x for x in ds[1:]], k))
            # l2 e^{i q2} i q2^(k) - l3 e^{-i q3} i q3^(k) + known = 0
            ds.append(np.real(known * np.conj(e_phi)) / (l3 * sin_gamma))
            dphi.append(np.real(known * np.conj(e_s)) / (l2 * sin_gamma))
        return dphi, ds


def paper_four_bar() -> FourBar:
    """The paper's test bed (seed 003, Table 2): l1 = 0.075, l2 = 0.175, l3 = 0.100,
    l4 = 0.175 m, the open assembly; its dead point q1 = 0.318, q3 = 2.246 rad (sec. 6)."""
    return FourBar(crank=0.075, coupler=0.175, rocker=0.100, ground=0.175, branch=1)


def _bell_rest(x: list[np.ndarray], k: int) -> np.ndarray | float:
    """The complete Bell polynomial B_k(x1, ..., xk) without its xk term (k = 1..4),
    from the known x1..x(k-1) (``x`` holds them; a k-th entry, if any, is ignored)."""
    if k == 1:
        return 0.0
    x1 = x[0]
    if k == 2:
        return x1 * x1
    x2 = x[1]
    if k == 3:
        return x1 ** 3 + 3.0 * x1 * x2
    x3 = x[2]
    return x1 ** 4 + 6.0 * x1 * x1 * x2 + 4.0 * x1 * x3 + 3.0 * x2 * x2


def _cosine_angle(a: float, b: float, opposite: float) -> float:
    """The angle between sides a and b of a triangle, facing the side ``opposite``."""
    c = (a * a + b * b - opposite * opposite) / (2.0 * a * b)
    return math.acos(min(1.0, max(-1.0, c)))


def _wrapped(theta: np.ndarray) -> np.ndarray:
    """theta in [-pi, pi)."""
    return (theta + np.pi) % (2.0 * np.pi) - np.pi
