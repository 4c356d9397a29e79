"""The torque at the crank of a 1-DOF linkage by Lagrange (virtual work), issue 14.

The linkage maps the crank angle theta to its output s = f(theta) (a slider, m, or a
rocker angle, rad), with s' = ds/dtheta and s'' = d^2 s/dtheta^2 exact from
``Linkage.output``. The kinetic energy is (1/2) J(theta) theta_dot^2 with the equivalent
inertia at the crank

    J(theta) = J_0 + M s'(theta)^2,   J_0 = J_crank + m_pin r^2,   dJ/dtheta = 2 M s' s''

(M the output's mass or inertia plus its share of the connecting link, see
:class:`LinkageMasses`). Lagrange's equation with the generalized force of the output's
loads, Q = -s' (F + f sign(s_dot) + c s_dot), gives the torque the crank needs:

    tau = J(theta) theta_ddot + (1/2) dJ/dtheta theta_dot^2
          + s'(theta) (F + f sign(s_dot) + c s_dot),   s_dot = s' theta_dot.

The second term is the d(J_eq)/dq term: at constant crank speed it is the whole inertial
torque (M s' s'' omega^2). When the load is on another coordinate than the one the
connecting link's output end moves with (a rocker's angle, a slider's position), e.g.
the coupler's or the rod's angle, that end is the ``joint`` g(theta) and
J(theta) = J_0 + M s'^2 + M_j g'^2, dJ/dtheta = 2 (M s' s'' + M_j g' g''), with M the
load's inertia and M_j the link's mass at its output end (times the rocker's length
squared for a rocker). No gravity acts on the links (a vertical slider's weight goes
into the load F). Gears between the motor and the crank are the caller's: the motor
functions here take an ideal ratio (no loss) at most; efficiencies and the limits of a
gearbox stay with the transmission chain (sizer.mechanics.drive).

Time scaling (book sec. 5.2): a crank motion of fixed shape theta(u), u = t/T, has
theta_dot = theta'(u)/T and theta_ddot = theta''(u)/T^2, so
tau(u; T) = A(u)/T^2 + D(u)/T + B(u) with A the inertial part, D the damping part and B
the load and friction part, independent of T (:func:`time_scaling_parts`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sizer.errors import UserError
from sizer.mechanics.linkages import Linkage


@dataclass(frozen=True)
class LinkageMasses:
    """The masses of a linkage and the loads on its output (SI).

    - ``crank_inertia``: the crank's inertia about its axis (kg*m^2).
    - ``output_inertia``: the slider's mass (kg) or the rocker's inertia about its pivot
      (kg*m^2).
    - The connecting link (the slider-crank's rod, the four-bar's coupler) is modelled by
      two point masses at its ends: ``link_mass_at_crank`` sits on the crank pin and turns
      with the crank (it adds m r^2 to the crank's inertia, r the crank radius);
      ``link_mass_at_output`` moves with the output's joint (for a slider it adds to the
      slider's mass; for a rocker it adds m l_rocker^2 to its inertia). The link's own
      rotational inertia about its centre beyond this two-mass model is neglected.
    - ``load``: an external force on a slider (N) or torque on a rocker (N*m) with its
      sign: positive opposes a positive output motion (gravity along the slider...).
    - ``friction``: Coulomb friction on the output (N or N*m, a magnitude >= 0) opposing
      its speed (none while the output is at rest, e.g. at a dead point).
    - ``damping``: viscous damping on the output (N*s/m or N*m*s/rad, >= 0).
    - ``spring_rate``, ``spring_preload``: a spring on the output pushing against a
      positive output, with the force P + k s (a cam's follower held on the cam:
      sizer.mechanics.disc_cam; N/m and N, or on a rotary output N*m/rad and N*m).
    """

    crank_inertia: float = 0.0
    output_inertia: float = 0.0
    link_mass_at_crank: float = 0.0
    link_mass_at_output: float = 0.0
    load: float = 0.0
    friction: float = 0.0
    damping: float = 0.0
    spring_rate: float = 0.0
    spring_preload: float = 0.0

    def __post_init__(self) -> None:
        for name in ("crank_inertia", "output_inertia", "link_mass_at_crank",
                     "link_mass_at_output", "friction", "damping", "spring_rate"):
            value = getattr(self, name)
            if not _finite(value) or value < 0.0:
                raise UserError(f"must be a finite value >= 0, got {value!r}", field=name)
        if not _finite(self.load):
            raise UserError(f"must be a finite value, got {self.load!r}", field="load")


@dataclass(frozen=True)
class TorqueParts:
    """The crank torque of a fixed-shape motion split by its scaling in the duration T:
    tau(u; T) = inertial/T^2 + damping/T + steady (arrays over the samples u)."""

    inertial: np.ndarray
    """A(u) = J(theta) theta''(u) + (1/2) dJ/dtheta theta'(u)^2 (N*m*s^2)."""
    damping: np.ndarray
    """D(u) = c s'^2 theta'(u) (N*m*s)."""
    steady: np.ndarray
    """B(u) = s' (F + f sign(s' theta'(u))) (N*m), independent of T."""
    crank_acceleration: np.ndarray
    """theta''(u) (rad), for the motor's own inertia: J_m theta''(u)/T^2."""

    def crank_torque(self, duration: float | np.ndarray) -> np.ndarray:
        """tau at the crank for durations T (s); T of shape (candidates,) gives
        (candidates, samples)."""
        T = _leading(duration)
        return self.inertial / T**2 + self.damping / T + self.steady

    def motor_torque(self, duration: float | np.ndarray,
                     motor_inertia: float | np.ndarray = 0.0) -> np.ndarray:
        """J_m theta_ddot + tau for a motor on the crank (no gear), broadcasting T and J_m
        over a leading candidates axis."""
        T = _leading(duration)
        J_m = _leading(motor_inertia)
        return (self.inertial + J_m * self.crank_acceleration) / T**2 + self.damping / T \
            + self.steady


@dataclass(frozen=True)
class LinkageDynamics:
    """A linkage with its masses: the equivalent inertia at the crank and the torque.

    ``crank_radius`` is the distance of the crank pin (where ``link_mass_at_crank`` sits)
    from the crank's axis; by default the linkage's ``crank_radius`` attribute.
    ``rocker_length`` is the distance from the rocker's pivot to the coupler's joint
    (where ``link_mass_at_output`` sits), needed for a rocker when that mass is not zero;
    by default the linkage's ``rocker_length`` attribute if it has one.
    """

    linkage: Linkage
    masses: LinkageMasses
    crank_radius: float | None = None
    rocker_length: float | None = None
    joint: Linkage | None = None
    """The coordinate ``link_mass_at_output`` moves with, when not the output (module
    docstring); None: the output's."""

    def __post_init__(self) -> None:
        r = self.crank_radius
        if r is None:
            r = getattr(self.linkage, "crank_radius", None)
            if r is None and self.masses.link_mass_at_crank > 0.0:
                raise UserError("the crank radius is needed for the link's mass at the "
                                "crank pin", field="crank_radius")
            r = 0.0 if r is None else float(r)
            object.__setattr__(self, "crank_radius", r)
        if not _finite(r) or r < 0.0:
            raise UserError(f"must be a finite length >= 0, got {r!r} m", field="crank_radius")
        if not self._joint.output_linear:
            length = self.rocker_length
            if length is None:
                length = getattr(self.linkage, "rocker_length", None)
            if length is None and self.masses.link_mass_at_output > 0.0:
                raise UserError("the rocker length is needed for the link's mass at the "
                                "rocker", field="rocker_length")
            length = 0.0 if length is None else length
            if not _finite(length) or length < 0.0:
                raise UserError(f"must be a finite length >= 0, got {length!r} m",
                                field="rocker_length")
            object.__setattr__(self, "rocker_length", float(length))

    @property
    def _joint(self) -> Linkage:
        return self.linkage if self.joint is None else self.joint

    @property
    def joint_inertia(self) -> float:
        """M_j: the link's mass at its output end as an inertia on the joint's coordinate
        (kg, or kg*m^2 on a rocker); 0 when the joint is the output (it is then in M)."""
        if self.joint is None:
            return 0.0
        m = self.masses.link_mass_at_output
        return m if self.joint.output_linear else m * (self.rocker_length or 0.0) ** 2

    @property
    def crank_side_inertia(self) -> float:
        """J_0 = J_crank + m_pin r^2: what turns with the crank (kg*m^2)."""
        m = self.masses
        radius = self.crank_radius or 0.0  # never None: __post_init__ fills it in
        return m.crank_inertia + m.link_mass_at_crank * radius**2

    @property
    def output_side_inertia(self) -> float:
        """M: the slider's mass plus the link's mass at the slider (kg), or the rocker's
        inertia plus m l_rocker^2 (kg*m^2)."""
        m = self.masses
        if self.joint is not None:
            return m.output_inertia
        if self.linkage.output_linear:
            return m.output_inertia + m.link_mass_at_output
        return m.output_inertia + m.link_mass_at_output * (self.rocker_length or 0.0) ** 2

    def inertia(self, theta: np.ndarray) -> np.ndarray:
        """J(theta) = J_0 + M s'(theta)^2 (+ M_j g'^2) (kg*m^2)."""
        theta = np.asarray(theta, dtype=float)
        s1 = self.linkage.output(theta, 1)
        out = self.crank_side_inertia + self.output_side_inertia * s1**2
        if self.joint is not None:
            out = out + self.joint_inertia * self.joint.output(theta, 1) ** 2
        return out

    def inertia_derivative(self, theta: np.ndarray) -> np.ndarray:
        """dJ/dtheta = 2 M s' s'' (+ 2 M_j g' g'') (kg*m^2/rad)."""
        theta = np.asarray(theta, dtype=float)
        s1, s2 = self.linkage.output(theta, 1), self.linkage.output(theta, 2)
        out = 2.0 * self.output_side_inertia * s1 * s2
        if self.joint is not None:
            out = out + 2.0 * self.joint_inertia * self.joint.output(theta, 1) \
                * self.joint.output(theta, 2)
        return out

    def kinetic_energy(self, theta: np.ndarray, theta_dot: np.ndarray) -> np.ndarray:
        """(1/2) J(theta) theta_dot^2 (J)."""
        return 0.5 * self.inertia(theta) * np.asarray(theta_dot, dtype=float) ** 2

    def crank_torque(self, theta: np.ndarray, theta_dot: np.ndarray,
                     theta_ddot: np.ndarray) -> np.ndarray:
        """The torque the crank needs (N*m), module docstring; arrays broadcast."""
        parts = self._parts(theta, theta_dot, theta_ddot)
        return parts.inertial + parts.damping + parts.steady

    def motor_torque(self, theta: np.ndarray, theta_dot: np.ndarray, theta_ddot: np.ndarray,
                     motor_inertia: float | np.ndarray = 0.0,
                     ratio: float | np.ndarray = 1.0) -> np.ndarray:
        """The motor's torque J_m k theta_ddot + tau/k through an ideal ratio k (motor angle
        per crank angle, no loss; 1: the motor drives the crank directly). ``motor_inertia``
        is everything on the motor side (a gear's inertia reflected to the motor included);
        J_m and k of shape (candidates,) give (candidates, samples)."""
        J_m, k = _leading(motor_inertia), _leading(ratio)
        tau = self.crank_torque(theta, theta_dot, theta_ddot)
        return J_m * k * np.asarray(theta_ddot, dtype=float) + tau / k

    def time_scaling_parts(self, theta: np.ndarray, theta_prime: np.ndarray,
                           theta_second: np.ndarray) -> TorqueParts:
        """The parts A, D, B of tau(u; T) = A/T^2 + D/T + B for a crank motion theta(u) of
        fixed shape over u = t/T (book sec. 5.2), from theta(u), theta'(u), theta''(u)."""
        return self._parts(theta, theta_prime, theta_second)

    def _parts(self, theta, speed, acceleration) -> TorqueParts:
        theta = np.asarray(theta, dtype=float)
        speed = np.asarray(speed, dtype=float)
        acceleration = np.asarray(acceleration, dtype=float)
        s1, s2 = self.linkage.output(theta, 1), self.linkage.output(theta, 2)
        M = self.output_side_inertia
        J = self.crank_side_inertia + M * s1**2
        half_dj = M * s1 * s2
        if self.joint is not None:
            g1, g2 = self.joint.output(theta, 1), self.joint.output(theta, 2)
            J = J + self.joint_inertia * g1**2
            half_dj = half_dj + self.joint_inertia * g1 * g2
        inertial = J * acceleration + half_dj * speed**2
        out_speed = s1 * speed
        m = self.masses
        damping = m.damping * s1 * out_speed
        steady = s1 * (m.load + m.friction * np.sign(out_speed))
        if m.spring_rate or m.spring_preload:
            steady = steady + s1 * (m.spring_preload
                                    + m.spring_rate * self.linkage.output(theta, 0))
        inertial, damping, steady, acceleration = np.broadcast_arrays(
            inertial, damping, steady, acceleration)
        return TorqueParts(inertial, damping, steady, acceleration)


def _finite(value: object) -> bool:
    """A real number (not a bool, not NaN or infinite)."""
    return (isinstance(value, (int, float, np.integer, np.floating))
            and not isinstance(value, bool) and math.isfinite(value))


def _leading(value: float | np.ndarray) -> np.ndarray:
    """A scalar as is; an array of shape (candidates,) as (candidates, 1) to broadcast
    over the samples."""
    array = np.asarray(value, dtype=float)
    return array[..., None] if array.ndim else array
