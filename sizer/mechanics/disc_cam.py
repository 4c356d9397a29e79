"""A disc cam with a translating (offset) or oscillating roller follower as the last
transmission stage.

Slides 002 "Meccanismi a camma" and the textbook's sec. 1.3 describe the cam as a
transmission whose ratio is the follower's lift law: the follower's lift s(theta) over the
cam angle theta is the law chosen for it, and the cam's profile is made from it. The
closed forms of the geometry are Norton's (R. L. Norton, "Cam Design and Manufacturing
Handbook", 2nd ed., ch. 7, "Cam Size Determination", translating roller follower; the
same in Rothbart, "Cam Design Handbook", ch. 4):

Conventions. The cam turns counterclockwise by theta (rad) about the origin; the
follower's axis is parallel to y at x = e (the ``offset``) and the roller's centre, the
pitch point, moves along +y away from the cam's centre. ``base_radius`` R_b is the radius
of the base circle of the cam's actual profile (the smallest); the prime circle (the
pitch curve's smallest circle) has R_p = R_b + R_f, R_f the roller's radius. With
d = sqrt(R_p^2 - e^2) the pitch point in the fixed frame is P = (e, d + s), and in the
cam's frame the pitch curve is C(theta) = Rot(-theta) P (points: :func:`pitch_curve`).

- Pressure angle (Norton eq. 7.1, offset translating roller follower): the angle between
  the follower's axis and the common normal at the contact,

      phi = atan((s' - e) / (s + d)),  s' = ds/dtheta (m/rad).

  A positive offset lowers it on the rise (s' > 0) and raises it on the return.
- Radius of curvature of the pitch curve (Norton eq. 7.9 in the offset form; from
  C' = Rot(-theta) (R, s' - e), C'' = Rot(-theta) (2 s' - e, s'' - R), R = s + d):

      rho = ((R^2 + (s' - e)^2)^(3/2)) / (R (R - s'') + (s' - e)(2 s' - e)),

  positive where the pitch curve is convex (a circle of radius R: rho = R), negative
  where concave. The actual profile is the pitch curve offset inward by R_f; its radius
  is rho - R_f where convex, so the roller does not undercut the cam when
  rho > R_f at every convex point: min over the convex points of rho (the largest
  curvature kappa = 1/rho > 0) exceeds R_f. Concave points never undercut.
- Contact of a force-closed follower (a spring of rate k and preload P holds the roller
  on the cam): the force the cam pushes the follower with, along its axis, at a cam
  speed omega is N = M s'' omega^2 + c s' omega + f sign(s' omega) + F + P + k s (M the
  follower's and load's mass, F the load's force, positive pushing toward the cam). The
  follower stays on the cam while N > 0: the preload needed is
  max(-(N - P)) over the turn (:func:`needed_preload`).
- The torque at the cam shaft is tau = N s' (virtual work; the linkage path computes it
  as for any linkage: sizer.mechanics.linkages.dynamics).

If the cam turns clockwise, the same formulas hold with e negated.

Oscillating roller follower (slides 002, "seconda specie"; Norton ch. 7, the 45 deg
default limit): the pivot at (a, 0), the arm of length L at the angle psi = psi_0 + phi
(phi the swing, the lift law, rad) from the line to the cam's centre; the roller's
centre P = (a - L cos psi, L sin psi) moves along u = (sin psi, cos psi)
(:func:`oscillating_motion`). For any roller follower, the pitch curve's derivatives
relative to the cam are T = P' - J P and P'' - 2 J P' - P (turned by -theta), which give
the pressure angle atan((T . u) / (T . w)), w = (u_y, -u_x) (:func:`pressure_angle_of`)
and kappa = -(T x (P'' - 2 J P' - P)) / |T|^3 (:func:`curvature_of`); with
P = (e, d + s), u = (0, 1) they are the translating follower's closed forms above. Its
contact check and torque are the same with moments about the pivot (N*m; the load's
inertia, the follower's mass at the roller: m L^2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from sizer.errors import UserError
from sizer.laws import MotionLaw
from sizer.model.domain import LinkageStage
from sizer.numerics.arrays import sorted_unique

DEFAULT_PRESSURE_ANGLE = math.radians(30.0)
"""The pressure angle limit of a translating follower (Norton sec. 7.2: 30 deg)."""
CAM_SAMPLES = 7201
"""Cam angles over a turn where the geometry checks are read (with every piece's ends)."""
RADIUS_TOLERANCE = 1e-9
"""The auto base radius: the bisection stops when the bracket is this narrow (m)."""


@dataclass(frozen=True)
class LiftPiece:
    """One piece of the follower's lift over the cam angle: from ``start`` (rad) over
    ``angle`` (rad), from lift ``lift`` (m) by ``rise`` (m, negative a return; 0 a dwell)
    by the normalized ``law`` (None: a dwell)."""

    start: float
    angle: float
    lift: float
    rise: float
    law: MotionLaw | None


@dataclass(frozen=True)
class CamLift:
    """The follower's lift s(theta) over a whole turn of the cam (periodic in 2 pi), made
    of :class:`LiftPiece` s; the protocol of sizer.mechanics.linkages.Linkage (the
    follower's position is a length; its extremes are the lowest and highest lift)."""

    pieces: tuple[LiftPiece, ...]
    output_linear: bool = True

    def _index(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(piece index, cam angle in [0, 2 pi)) of each theta; a piece's end belongs
        to the next one."""
        phase = np.mod(theta, 2.0 * math.pi)
        starts = np.array([p.start for p in self.pieces])
        index = np.clip(np.searchsorted(starts, phase, side="right") - 1, 0,
                        len(self.pieces) - 1)
        return index, phase

    def output(self, theta: np.ndarray, order: int = 0) -> np.ndarray:
        """d^order s / d theta^order: h q^(order)(u) / beta^order, u the piece's
        normalized angle."""
        return self._orders(theta, (order,))[0]

    def _orders(self, theta: np.ndarray, orders: tuple[int, ...]) -> list[np.ndarray]:
        """:meth:`output` of each order, the angles sorted into pieces once."""
        theta = np.asarray(theta, dtype=float)
        index, phase = self._index(theta)
        out = [np.zeros(theta.shape) for _ in orders]
        for i in sorted_unique(index):
            piece = self.pieces[int(i)]
            mask = index == i
            u = np.clip((phase[mask] - piece.start) / piece.angle, 0.0, 1.0)
            for values, order in zip(out, orders, strict=True):
                if order == 0:
                    values[mask] = piece.lift
                if piece.law is None or order > piece.law.max_order:
                    continue
                values[mask] += piece.rise * piece.law.derivative(u, order) \
                    / piece.angle**order
        return out

    def input_of(self, s: np.ndarray, half: int) -> np.ndarray:
        raise UserError("a cam's follower follows the cam: the law is on the follower's "
                        "lift over the cam angle", field="law_on")

    def dead_points(self) -> np.ndarray:
        return np.empty(0)  # the cam turns at constant speed: no inverse kinematics

    def output_range(self) -> tuple[float, float]:
        lifts = [p.lift for p in self.pieces] + [p.lift + p.rise for p in self.pieces]
        return min(lifts), max(lifts)

    @cached_property
    def turn(self) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """The turn's angles (:meth:`angles`) and s, s', s'' there, computed once: every
        geometry of the cam reads them (the auto base radius bisects over dozens)."""
        theta = self.angles()
        s, s1, s2 = self._orders(theta, (0, 1, 2))
        return theta, (s, s1, s2)

    def outputs(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """s, s', s'' at the angles ``theta`` (the turn's, :attr:`turn`, kept)."""
        if theta is self.turn[0]:
            return self.turn[1]
        s, s1, s2 = self._orders(theta, (0, 1, 2))
        return s, s1, s2

    def angles(self, samples: int = CAM_SAMPLES) -> np.ndarray:
        """Cam angles over a turn: a uniform grid plus every piece's ends (approached
        from inside, where the law's derivatives may jump)."""
        ends = []
        for p in self.pieces:
            ends += [p.start, p.start + p.angle * (1.0 - 1e-12)]
        grid = np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False)
        return sorted_unique(np.concatenate((grid, ends)))


@dataclass(frozen=True)
class CamFigures:
    """What the cam's checks read (sizer.sizing.checks.cam_checks), made once per law by
    :func:`resolved`: the largest |pressure angle| (rad) and the cam angle where (rad);
    the pitch curve's smallest convex radius of curvature (m; inf: none) and where; the
    spring preload the contact needs (N; <= 0: none) and where."""

    max_pressure_angle: float
    pressure_angle_at: float
    min_convex_radius: float
    radius_at: float
    needed_preload: float
    preload_at: float


@dataclass(frozen=True)
class CamStage(LinkageStage):
    """A disc cam with a translating offset roller follower (module docstring): a
    LinkageStage of kind "disc_cam" whose output is the follower's lift. ``lengths`` is
    (R_b, e, R_f) (m; R_b None: ``auto``, resolved per law by :func:`resolved`);
    ``lift`` the follower's lift over the cam angle (set per law; None until then);
    ``speed`` the cam's constant speed omega (rad/s): one turn per machine cycle;
    ``pressure_angle`` the limit (rad); ``spring_preload`` (N, on the base circle) and
    ``spring_force_at_top`` (N, at the highest lift; None: the preload) of a
    force-closed follower (``force_closed``), whose ``spring_rate`` (N/m)
    :func:`resolved` sets; the follower's own mass is
    ``link_mass_at_output`` (kg), the cam's inertia ``crank_inertia``."""

    base_radius: float | None = None
    offset: float = 0.0
    roller_radius: float = 0.0
    speed: float = 0.0
    pressure_angle: float = DEFAULT_PRESSURE_ANGLE
    force_closed: bool = False
    spring_rate: float = 0.0
    spring_preload: float = 0.0
    spring_force_at_top: float | None = None
    arm: Arm | None = None
    """An oscillating roller follower's (pivot distance, arm length), m; None: a
    translating one (its lift in m; an oscillating one's in rad, its load rotary)."""
    lift: CamLift | None = field(default=None, compare=True)
    figures: CamFigures | None = field(default=None, compare=False)

    @property
    def output_linear(self) -> bool:
        return self.arm is None

    @property
    def prime_radius(self) -> float:
        """R_p = R_b + R_f (m); needs the base radius resolved."""
        assert self.base_radius is not None, "the base radius resolved (auto: resolved())"
        return self.base_radius + self.roller_radius


def cam_lift(segments: list[tuple[float, float, MotionLaw | None]]) -> CamLift:
    """The lift over a turn of a cam making one turn per machine cycle: ``segments`` are
    (displacement m, duration s, law; None a dwell), each taking the cam angle
    2 pi T_i / sum T. The lift starts at 0 and is measured from its lowest (the base
    circle): s >= 0. UserError (field "cycle") unless the follower comes back."""
    total = math.fsum(T for _, T, _ in segments)
    travel = math.fsum(h for h, _, _ in segments)
    scale = max((abs(h) for h, _, _ in segments), default=0.0)
    if not total > 0.0:
        raise UserError("a cam's cycle needs a positive duration", field="cycle")
    if abs(travel) > 1e-9 * max(scale, 1e-300):
        raise UserError(f"a cam's follower must come back where it started (one turn of "
                        f"the cam per cycle): the displacements sum to {travel:g} m",
                        field="cycle")
    pieces, start, lift = [], 0.0, 0.0
    for h, T, law in segments:
        angle = 2.0 * math.pi * T / total
        pieces.append(LiftPiece(start, angle, lift, h if law is not None else 0.0, law))
        start += angle
        lift += h if law is not None else 0.0
    low = min(min(p.lift, p.lift + p.rise) for p in pieces)
    return CamLift(tuple(LiftPiece(p.start, p.angle, p.lift - low, p.rise, p.law)
                         for p in pieces))


def pressure_angle(s: np.ndarray, s1: np.ndarray, prime_radius: float,
                   offset: float) -> np.ndarray:
    """phi = atan((s' - e) / (s + sqrt(R_p^2 - e^2))) (rad, signed; module docstring)."""
    d = math.sqrt(prime_radius**2 - offset**2)
    return np.arctan2(np.asarray(s1) - offset, np.asarray(s) + d)


def pitch_curvature(s: np.ndarray, s1: np.ndarray, s2: np.ndarray, prime_radius: float,
                    offset: float) -> np.ndarray:
    """kappa = 1 / rho of the pitch curve (1/m; > 0 convex; module docstring):
    (R (R - s'') + (s' - e)(2 s' - e)) / (R^2 + (s' - e)^2)^(3/2), R = s + d."""
    d = math.sqrt(prime_radius**2 - offset**2)
    R, v = np.asarray(s) + d, np.asarray(s1) - offset
    return (R * (R - np.asarray(s2)) + v * (2.0 * np.asarray(s1) - offset)) \
        / (R * R + v * v) ** 1.5


def pitch_curve(theta: np.ndarray, s: np.ndarray, prime_radius: float,
                offset: float) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) of the pitch curve in the cam's frame: Rot(-theta) (e, d + s)."""
    d = math.sqrt(prime_radius**2 - offset**2)
    c, n = np.cos(theta), np.sin(theta)
    y0 = d + np.asarray(s)
    return c * offset + n * y0, -n * offset + c * y0


def cam_profile(theta: np.ndarray, s: np.ndarray, s1: np.ndarray, prime_radius: float,
                offset: float, roller_radius: float) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) of the actual profile: the pitch curve moved by R_f along its inward
    normal, the direction (s' - e, -R) of the fixed frame (the tangent (R, s' - e)
    turned by -90 deg) turned by -theta."""
    x, y = pitch_curve(theta, s, prime_radius, offset)
    d = math.sqrt(prime_radius**2 - offset**2)
    R, v = np.asarray(s) + d, np.asarray(s1) - offset
    norm = np.hypot(R, v)
    nx, ny = v / norm, -R / norm  # fixed frame, toward the cam
    c, n = np.cos(theta), np.sin(theta)
    return x + roller_radius * (c * nx + n * ny), y + roller_radius * (-n * nx + c * ny)


Arm = tuple[float, float]
"""An oscillating follower's (pivot distance a, arm length L), m."""


def oscillating_motion(phi: np.ndarray, phi1: np.ndarray, phi2: np.ndarray,
                       prime_radius: float, arm: Arm) -> tuple[np.ndarray, ...]:
    """The roller's centre of an oscillating follower in the fixed frame and its first two
    derivatives in theta, and the direction it moves in (module docstring, oscillating):
    (P, P', P'', u), each of shape (2, n). The pivot is at (a, 0); the arm of length L
    makes the angle psi = psi_0 + phi with the line from the pivot to the cam's centre,
    P = (a - L cos psi, L sin psi), psi_0 where |P| = R_p (cos psi_0 = (a^2 + L^2 -
    R_p^2) / (2 a L)); u = (sin psi, cos psi), the roller's direction as psi grows."""
    a, L = arm
    psi = math.acos((a * a + L * L - prime_radius**2) / (2.0 * a * L)) + np.asarray(phi)
    c, n = np.cos(psi), np.sin(psi)
    p1, p2 = np.asarray(phi1), np.asarray(phi2)
    P = np.stack([a - L * c, L * n])
    P1 = L * p1 * np.stack([n, c])
    P2 = L * p2 * np.stack([n, c]) + L * p1 * p1 * np.stack([c, -n])
    return P, P1, P2, np.stack([n, c])


def pressure_angle_of(P: np.ndarray, P1: np.ndarray, u: np.ndarray) -> np.ndarray:
    """The pressure angle (rad, signed) of any roller follower whose roller centre is P(theta)
    (fixed frame), P' = dP/dtheta, moving along u: the pitch curve's tangent relative to
    the cam, T = P' - J P (J: +90 deg), and the normal (T_y, -T_x); the angle between the
    normal and u is atan((T . u) / (T . w)), w = (u_y, -u_x). A translating follower
    (P = (e, d + s), u = (0, 1)): atan((s' - e) / (s + d)), :func:`pressure_angle`."""
    tx, ty = P1[0] + P[1], P1[1] - P[0]
    return np.arctan((tx * u[0] + ty * u[1]) / (tx * u[1] - ty * u[0]))


def curvature_of(P: np.ndarray, P1: np.ndarray, P2: np.ndarray) -> np.ndarray:
    """kappa = 1 / rho (1/m; > 0 convex) of the pitch curve C = Rot(-theta) P of any
    follower: C' = Rot(-theta) T, C'' = Rot(-theta) (P'' - 2 J P' - P), kappa =
    -(T x C'') / |T|^3 (the curve turns clockwise as theta grows); a translating
    follower's is :func:`pitch_curvature`."""
    tx, ty = P1[0] + P[1], P1[1] - P[0]
    cx, cy = P2[0] + 2.0 * P1[1] - P[0], P2[1] - 2.0 * P1[0] - P[1]
    return -(tx * cy - ty * cx) / (tx * tx + ty * ty) ** 1.5


def _follower(lift: CamLift, theta: np.ndarray, prime_radius: float, offset: float,
              arm: Arm | None) -> tuple[np.ndarray, ...]:
    """(P, P', P'', u) of the follower at the cam angles: a translating one
    (P = (e, d + s)) or, with ``arm``, an oscillating one (:func:`oscillating_motion`)."""
    s, s1, s2 = lift.outputs(theta)
    if arm is not None:
        return oscillating_motion(s, s1, s2, prime_radius, arm)
    d = math.sqrt(prime_radius**2 - offset**2)
    zero = np.zeros(s.shape)
    return (np.stack([np.full(s.shape, offset), d + s]), np.stack([zero, s1]),
            np.stack([zero, s2]), np.stack([zero, zero + 1.0]))


def fits(prime_radius: float, offset: float, arm: Arm | None) -> bool:
    """Whether the prime circle reaches the follower: beyond the offset (translating),
    or between |a - L| and a + L (oscillating: the arm reaches it)."""
    if arm is None:
        return prime_radius > abs(offset)
    a, L = arm
    return abs(a - L) < prime_radius < a + L


@dataclass(frozen=True)
class CamGeometry:
    """The geometry checks' figures of a cam over a turn: the largest |pressure angle|
    (rad) and where (cam angle, rad); the smallest radius of curvature of the pitch curve
    where convex (m; inf: none) and where."""

    max_pressure_angle: float
    pressure_angle_at: float
    min_convex_radius: float
    radius_at: float


ZOOMS = 5
"""Rounds refining a maximum: each samples ZOOM_POINTS angles between the neighbours of the
largest sample so far, shrinking the bracket 50-fold (from the turn's grid step, 9e-4 rad,
to 3e-12 rad after 5: a smooth peak's value is then exact to rounding)."""
ZOOM_POINTS = 101


def refined_max(f, theta: np.ndarray) -> tuple[float, float]:
    """(max f, where) over a turn: the largest of f on the angles ``theta`` (sorted, in
    [0, 2 pi)), refined by :data:`ZOOMS` rounds of denser samples between the neighbours
    of the largest (exact for a smooth peak, to rounding; a peak at a jump of f, a
    piece's end, is the largest value on its side)."""
    values = f(theta)
    i = int(np.argmax(values))
    best, at = float(values[i]), float(theta[i])
    lo = float(theta[i - 1]) if i > 0 else float(theta[-1]) - 2.0 * math.pi
    hi = float(theta[i + 1]) if i + 1 < len(theta) else float(theta[0]) + 2.0 * math.pi
    for _ in range(ZOOMS):
        x = np.linspace(lo, hi, ZOOM_POINTS)
        v = f(x)
        j = int(np.argmax(v))
        if v[j] > best:
            best, at = float(v[j]), float(x[j] % (2.0 * math.pi))
        lo, hi = float(x[max(j - 1, 0)]), float(x[min(j + 1, ZOOM_POINTS - 1)])
    return best, at


def geometry(lift: CamLift, prime_radius: float, offset: float,
             arm: Arm | None = None) -> CamGeometry:
    """The figures of :class:`CamGeometry` over a turn (:meth:`CamLift.angles`, each
    maximum refined: :func:`refined_max`); ``arm``: an oscillating follower's."""
    theta = lift.turn[0]  # its s, s', s'' computed once for every geometry of the cam
    if arm is None:  # the translating follower's closed forms
        def phi(x: np.ndarray) -> np.ndarray:
            s, s1, _ = lift.outputs(x)
            return np.abs(pressure_angle(s, s1, prime_radius, offset))

        def kappa(x: np.ndarray) -> np.ndarray:
            return pitch_curvature(*lift.outputs(x), prime_radius, offset)
    else:
        def phi(x: np.ndarray) -> np.ndarray:
            P, P1, _, u = _follower(lift, x, prime_radius, offset, arm)
            return np.abs(pressure_angle_of(P, P1, u))

        def kappa(x: np.ndarray) -> np.ndarray:
            P, P1, P2, _ = _follower(lift, x, prime_radius, offset, arm)
            return curvature_of(P, P1, P2)

    top, i = refined_max(phi, theta)
    bend, j = refined_max(kappa, theta)
    rho = 1.0 / bend if bend > 0.0 else math.inf
    return CamGeometry(top, i, rho, j)


def geometry_passes(lift: CamLift, base_radius: float, offset: float, roller_radius: float,
                    limit: float, arm: Arm | None = None) -> bool:
    """The pressure angle within ``limit`` and the pitch curve's convex radius above the
    roller's (no undercut), at this base radius (False where the prime circle does not
    reach the follower: :func:`fits`)."""
    prime = base_radius + roller_radius
    if not fits(prime, offset, arm):
        return False
    g = geometry(lift, prime, offset, arm)
    return g.max_pressure_angle <= limit and g.min_convex_radius > roller_radius


def auto_base_radius(lift: CamLift, offset: float, roller_radius: float,
                     limit: float, arm: Arm | None = None) -> float:
    """The smallest base radius R_b (m) at which :func:`geometry_passes`, by doubling then
    bisection to RADIUS_TOLERANCE (the passing end of the bracket). Both checks tighten
    as R_b shrinks (phi's denominator s + d grows with R_b; so does the pitch curve); an
    oscillating follower's prime circle stays within the arm's reach, below a + L."""
    if arm is None:
        low = max(abs(offset) - roller_radius, 0.0)
        span = max(lift.output_range()[1], roller_radius, abs(offset), 1e-3)
        top = math.inf
    else:
        low = max(abs(arm[0] - arm[1]) - roller_radius, 0.0)
        top = arm[0] + arm[1] - roller_radius
        span = max(top - low, 0.0) / 2.0 ** 20
    high = min(low + span, top)
    for _ in range(60):
        if high < top and geometry_passes(lift, high, offset, roller_radius, limit, arm):
            break
        low, high = high, min(high + 2.0 * (high - low), top)
        if high >= top:
            high = top * (1.0 - 1e-12)
            if geometry_passes(lift, high, offset, roller_radius, limit, arm):
                break
            high = math.inf
            break
    if not math.isfinite(high) or not geometry_passes(lift, high, offset, roller_radius,
                                                      limit, arm):
        raise UserError("no base radius keeps the pressure angle and the curvature checks"
                        + ("" if arm is None else " within the arm's reach (pivot_distance "
                           "+ arm_length)"), field="base_radius")
    while high - low > RADIUS_TOLERANCE:
        middle = 0.5 * (low + high)
        if geometry_passes(lift, middle, offset, roller_radius, limit, arm):
            high = middle
        else:
            low = middle
    return high


def resolved(stage: CamStage, lift: CamLift, speed: float,
             load: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)) -> CamStage:
    """The stage with its lift, its speed (rad/s), its spring's rate (from its force at
    the top over the largest lift), its base radius (``auto``: :func:`auto_base_radius`)
    and its checks' figures (:class:`CamFigures`; ``load``: the follower's load's mass
    (the follower's own added here), force, friction and damping); UserError (field
    "base_radius") where the prime circle does not reach the axis."""
    from dataclasses import replace

    lift = replace(lift, output_linear=stage.arm is None)  # an arm's swing is an angle
    top = stage.spring_force_at_top
    rate = 0.0 if top is None else (top - stage.spring_preload) / lift.output_range()[1]

    radius = stage.base_radius
    if radius is None:
        radius = auto_base_radius(lift, stage.offset, stage.roller_radius,
                                  stage.pressure_angle, stage.arm)
    elif not fits(radius + stage.roller_radius, stage.offset, stage.arm):
        raise UserError(f"the prime circle (base radius + roller radius, "
                        f"{radius + stage.roller_radius:g} m) does not reach the follower "
                        f"(the offset, or the arm's reach)", field="base_radius")
    # lengths: the last is where the follower's own mass sits on a rotary output (the
    # roller, at the arm's length: sizer.mechanics.linkages.dynamics' rocker length)
    last = stage.roller_radius if stage.arm is None else stage.arm[1]
    out = replace(stage, base_radius=radius, lift=lift, speed=speed, spring_rate=rate,
                  lengths=(radius, stage.offset, last))
    g = geometry(lift, out.prime_radius, stage.offset, stage.arm)
    mass, force, friction, damping = load
    own = stage.link_mass_at_output * (1.0 if stage.arm is None else stage.arm[1] ** 2)
    preload, at = needed_preload(out, mass + own, force, friction, damping)
    return replace(out, figures=CamFigures(g.max_pressure_angle, g.pressure_angle_at,
                                           g.min_convex_radius, g.radius_at, preload, at))


def contact_force(stage: CamStage, mass: float, force: float, friction: float,
                  damping: float, theta: np.ndarray) -> np.ndarray:
    """N(theta) (N): the force the cam pushes the follower with at the constant speed
    (module docstring), the spring included."""
    assert stage.lift is not None
    w = stage.speed
    s, s1, s2 = stage.lift.outputs(theta)
    return (mass * s2 * w * w + damping * s1 * w + friction * np.sign(s1 * w) + force
            + stage.spring_preload + stage.spring_rate * s)


def needed_preload(stage: CamStage, mass: float, force: float, friction: float,
                   damping: float) -> tuple[float, float]:
    """(the smallest spring preload P keeping N >= 0 over the turn, N, the cam angle
    where it binds, rad): max over theta of P - N(theta)."""
    assert stage.lift is not None

    def gap(x: np.ndarray) -> np.ndarray:
        return stage.spring_preload - contact_force(stage, mass, force, friction, damping, x)

    return refined_max(gap, stage.lift.turn[0])


@dataclass(frozen=True)
class CamPoints:
    """The cam's profile as points in its own frame (m), at the cam angles ``theta``
    (rad): the pitch curve (the roller's centre) and the actual profile (what is cut)."""

    theta: np.ndarray
    pitch_x: np.ndarray
    pitch_y: np.ndarray
    profile_x: np.ndarray
    profile_y: np.ndarray


def profile_points(stage: CamStage, samples: int = 721) -> CamPoints:
    """The resolved cam's pitch curve and actual profile at ``samples`` cam angles over a
    turn (the last the first again: a closed outline)."""
    assert stage.lift is not None, "the cam resolved (resolved())"
    theta = np.linspace(0.0, 2.0 * math.pi, samples)
    if stage.arm is None:
        s, s1 = stage.lift.output(theta), stage.lift.output(theta, 1)
        px, py = pitch_curve(theta, s, stage.prime_radius, stage.offset)
        qx, qy = cam_profile(theta, s, s1, stage.prime_radius, stage.offset,
                             stage.roller_radius)
        return CamPoints(theta, px, py, qx, qy)
    P, P1, _, _ = _follower(stage.lift, theta, stage.prime_radius, stage.offset, stage.arm)
    tx, ty = P1[0] + P[1], P1[1] - P[0]
    norm = np.hypot(tx, ty)
    inward = np.stack([ty / norm, -tx / norm])  # the tangent turned by -90 deg
    c, n = np.cos(theta), np.sin(theta)
    q = P + stage.roller_radius * inward
    return CamPoints(theta, c * P[0] + n * P[1], -n * P[0] + c * P[1],
                     c * q[0] + n * q[1], -n * q[0] + c * q[1])


@dataclass(frozen=True)
class FollowerMotion:
    """The follower's motion over one turn of the resolved cam, at the cam angles
    ``theta`` (rad, increasing from 0 to 2 pi; each piece's ends twice, approached from
    inside, where a derivative may jump): its lift (m; an oscillating follower's swing,
    rad) and the lift's time derivatives at the cam's constant speed omega (book eq. 5.4
    with theta_dot constant: v = s' omega, a = s'' omega^2, j = s''' omega^3; m/s^k, or
    rad/s^k); ``speed`` is omega (rad/s)."""

    theta: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    jerk: np.ndarray
    speed: float


def follower_motion(stage: CamStage, samples: int = CAM_SAMPLES) -> FollowerMotion:
    """The resolved cam's :class:`FollowerMotion` on :meth:`CamLift.angles` (``samples``
    per turn plus every piece's ends) and the turn's end, 2 pi."""
    assert stage.lift is not None, "the cam resolved (resolved())"
    theta = np.append(stage.lift.angles(samples), 2.0 * math.pi)
    w = stage.speed
    s, s1, s2, s3 = (stage.lift.output(theta, k) for k in range(4))
    return FollowerMotion(theta, s, s1 * w, s2 * w * w, s3 * w**3, w)
