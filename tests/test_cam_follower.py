"""A disc cam with a translating offset roller follower as the last transmission stage
(issue 38, "Mechanical cams as a transmission"; docs/disc-cams.md).

Every expected number is computed here: the lift by its closed forms (cycloidal and
harmonic rises written out), the pitch curve by rotating the follower's roller centre into
the cam's frame, its tangent and curvature by 5-point finite differences, the pressure
angle from the tangent, the torque as F ds/dtheta, the RMS by scipy's adaptive quadrature,
never from sizer's own formulas.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import yaml
from bad_input_cases import Case
from bad_input_cases import run_case as run
from scipy.integrate import quad
from scipy.optimize import minimize_scalar

from sizer.api import load, size
from sizer.laws import make_law
from sizer.mechanics.disc_cam import (
    RADIUS_TOLERANCE,
    cam_lift,
    geometry_passes,
    pitch_curvature,
    pressure_angle,
)

H = 0.02
"""The follower's lift (m)."""
RISE, TOP, BACK, BOTTOM = 0.1, 0.05, 0.1, 0.05
"""The cycle's durations (s): rise, dwell at the top, return, dwell at the bottom."""
CYCLE = RISE + TOP + BACK + BOTTOM
OMEGA = 2.0 * math.pi / CYCLE
BETA = 2.0 * math.pi * RISE / CYCLE
"""The cam angle of the rise and of the return (rad)."""
DWELL = 2.0 * math.pi * TOP / CYCLE
MOTOR = {"id": "m1", "inertia": "1 kg*cm^2", "continuous_torque": "50 N*m",
         "peak_torque": "150 N*m", "rated_speed": "3000 rpm"}
N, ETA = 5.0, 0.95
MASS, FOLLOWER, FORCE = 2.0, 0.5, 50.0
PRELOAD, TOP_FORCE = 100.0, 140.0
RATE = (TOP_FORCE - PRELOAD) / H


def _cam(**fields: object) -> dict:
    cam = {"type": "disc_cam", "base_radius": "40 mm", "roller_radius": "10 mm",
           "offset": "5 mm", "follower_mass": f"{FOLLOWER} kg", "cam_inertia": "0.001 kg*m^2",
           "spring_preload": f"{PRELOAD} N", "spring_force_at_top": f"{TOP_FORCE} N"}
    cam.update(fields)
    return {k: v for k, v in cam.items() if v is not None}


def _design(cam: dict | None = None, law: str = "cycloidal", **changes: object) -> dict:
    design = {
        "name": "disc cam",
        "cycle": {"segments": [
            {"move": {"displacement": f"{H * 1e3} mm", "duration": f"{RISE} s", "name": "rise"}},
            {"dwell": {"duration": f"{TOP} s", "name": "top"}},
            {"move": {"displacement": f"{-H * 1e3} mm", "duration": f"{BACK} s",
                      "name": "return"}},
            {"dwell": {"duration": f"{BOTTOM} s", "name": "bottom"}}]},
        "load": {"mass": f"{MASS} kg", "force": f"{FORCE} N"},
        "transmission": [{"type": "gearbox", "ratio": N, "efficiency": f"{ETA * 100} %"},
                         _cam() if cam is None else cam],
        "laws": [law], "motors": [MOTOR]}
    design.update(changes)
    return {k: v for k, v in design.items() if v is not None}


# ------------------------------------------------------------ the lift, written out
def _cycloidal(x: np.ndarray, k: int) -> np.ndarray:
    """d^k/dx^k of x - sin(2 pi x)/(2 pi)."""
    w = 2.0 * np.pi
    return [x - np.sin(w * x) / w, 1.0 - np.cos(w * x), w * np.sin(w * x),
            w * w * np.cos(w * x)][k]


def _harmonic(x: np.ndarray, k: int) -> np.ndarray:
    """d^k/dx^k of (1 - cos(pi x))/2."""
    p = np.pi
    return [(1.0 - np.cos(p * x)) / 2.0, p * np.sin(p * x) / 2.0, p * p * np.cos(p * x) / 2.0,
            -p**3 * np.sin(p * x) / 2.0][k]


def _lift(theta: np.ndarray, k: int = 0, shape=_cycloidal, beta: float = BETA,
          dwell: float = DWELL) -> np.ndarray:
    """d^k s/dtheta^k of the cycle's lift: rise over beta, dwell, return over beta, dwell."""
    theta = np.mod(np.asarray(theta, dtype=float), 2.0 * np.pi)
    out = np.zeros(theta.shape)
    rise = theta < beta
    top = (theta >= beta) & (theta < beta + dwell)
    back = (theta >= beta + dwell) & (theta < 2 * beta + dwell)
    out[rise] = H * shape(theta[rise] / beta, k) / beta**k
    out[back] = -H * shape((theta[back] - beta - dwell) / beta, k) / beta**k
    if k == 0:
        out[top] = H
        out[back] += H
    return out


def _pitch_point(theta: float, rp: float, e: float, s) -> np.ndarray:
    """The roller's centre in the cam's frame: (e, d + s) of the fixed frame, the cam
    turned counterclockwise by theta, so the point turned by -theta."""
    d = math.sqrt(rp * rp - e * e)
    p = np.array([e, d + float(s(theta))])
    c, n = math.cos(theta), math.sin(theta)
    return np.array([[c, n], [-n, c]]) @ p


def _derivatives(theta: float, rp: float, e: float, s, step: float = 1e-3):
    """The pitch curve's first and second derivatives in theta by 5-point differences."""
    f = [_pitch_point(theta + k * step, rp, e, s) for k in (-2, -1, 0, 1, 2)]
    d1 = (f[0] - 8 * f[1] + 8 * f[3] - f[4]) / (12 * step)
    d2 = (-f[0] + 16 * f[1] - 30 * f[2] + 16 * f[3] - f[4]) / (12 * step * step)
    return d1, d2


@pytest.mark.parametrize("shape", [_cycloidal, _harmonic], ids=["cycloidal", "harmonic"])
@pytest.mark.parametrize("e", [0.0, 0.008, -0.006])
def test_pressure_angle_and_curvature_against_the_pitch_curve(shape, e):
    rp = 0.04
    angles = np.concatenate((np.linspace(0.02, BETA - 0.02, 9),
                             np.linspace(BETA + DWELL + 0.02, 2 * BETA + DWELL - 0.02, 9)))
    for theta in angles:
        def s(x, shape=shape):
            return _lift(np.array([x]), 0, shape)[0]
        d1, d2 = _derivatives(theta, rp, e, s)
        c, n = math.cos(theta), math.sin(theta)
        tangent = np.array([[c, -n], [n, c]]) @ d1  # back to the fixed frame
        # the normal is the tangent turned by 90 deg; its angle to the follower's axis (y)
        # is the tangent's to x
        phi_numeric = math.atan2(tangent[1], tangent[0])
        # the curve turns clockwise with theta: a convex point has a negative cross product
        kappa_numeric = -(d1[0] * d2[1] - d1[1] * d2[0]) / np.hypot(*d1) ** 3
        z = np.array([theta])
        s0, s1, s2 = (_lift(z, k, shape) for k in range(3))
        assert pressure_angle(s0, s1, rp, e)[0] == pytest.approx(phi_numeric, abs=1e-9)
        assert pitch_curvature(s0, s1, s2, rp, e)[0] == pytest.approx(kappa_numeric, rel=1e-6)


def test_the_lift_is_the_cycle_over_a_turn():
    law = make_law("cycloidal")
    lift = cam_lift([(H, RISE, law), (0.0, TOP, None), (-H, BACK, law), (0.0, BOTTOM, None)])
    theta = np.linspace(0.0, 2 * np.pi, 2001)[:-1]
    ends = np.array([BETA, BETA + DWELL, 2 * BETA + DWELL])
    # at a piece's end the jerk jumps (cycloidal: from 0 to (2 pi)^2 h / beta^3): apart
    theta = theta[np.min(np.abs(theta[:, None] - ends), axis=1) > 1e-9]
    for k in range(4):
        expected = _lift(theta, k)
        assert np.allclose(lift.output(theta, k), expected, rtol=1e-12,
                           atol=1e-12 * np.max(np.abs(expected)))


def test_a_cam_whose_follower_does_not_come_back_is_refused():
    law = make_law("cycloidal")
    with pytest.raises(Exception, match="come back"):
        cam_lift([(H, RISE, law), (0.0, TOP, None)])


# ------------------------------------------------------------ the base radius
def _smallest_prime_radius(limit: float) -> float:
    """In line (e = 0), phi <= limit where s' / (s + R_p) <= tan(limit): R_p >= s'/tan - s,
    the largest over the rise (the return mirrors it), by bounded minimization."""
    t = math.tan(limit)

    def need(theta: float) -> float:
        z = np.array([theta])
        return -(float(_lift(z, 1)[0]) / t - float(_lift(z)[0]))

    found = minimize_scalar(need, bounds=(0.0, BETA), method="bounded",
                            options={"xatol": 1e-12})
    return -found.fun


def test_auto_base_radius_is_the_smallest_that_passes():
    roller, limit = 0.002, math.radians(30.0)
    design = _design(_cam(base_radius="auto", roller_radius=f"{roller * 1e3} mm", offset=0))
    (result,) = size(design).results
    checks = {c.name: c for c in result.checks}
    # the pressure angle binds: the smallest prime radius is the in-line closed form
    expected = _smallest_prime_radius(limit) - roller
    loaded = load(design)
    from sizer.sizing.linkage_move import cam_design

    cam = cam_design(loaded, make_law("cycloidal")).transmission.linkage
    assert cam.base_radius == pytest.approx(expected, abs=2 * RADIUS_TOLERANCE)
    assert checks["pressure_angle"].passed and checks["cam_curvature"].passed
    assert checks["pressure_angle"].margin == pytest.approx(0.0, abs=1e-5)
    # one step below fails, at the radius itself it passes
    assert geometry_passes(cam.lift, cam.base_radius, 0.0, roller, limit)
    assert not geometry_passes(cam.lift, cam.base_radius - 1e-6, 0.0, roller, limit)


def test_auto_base_radius_bound_by_the_curvature():
    # a big roller: the pitch curve's convex radius binds before the pressure angle
    roller, limit = 0.03, math.radians(60.0)
    design = _design(_cam(base_radius="auto", roller_radius=f"{roller * 1e3} mm", offset=0,
                          pressure_angle="60 deg"))
    from sizer.sizing.linkage_move import cam_design

    cam = cam_design(load(design), make_law("cycloidal")).transmission.linkage
    assert geometry_passes(cam.lift, cam.base_radius, 0.0, roller, limit)
    assert not geometry_passes(cam.lift, cam.base_radius - 1e-6, 0.0, roller, limit)
    # the smallest convex radius, found here by dense sampling, is the roller's there
    rp = cam.base_radius + roller
    theta = np.linspace(0, 2 * np.pi, 400_001)
    kappa = pitch_curvature(_lift(theta), _lift(theta, 1), _lift(theta, 2), rp, 0.0)
    assert 1 / kappa.max() == pytest.approx(roller, abs=2 * RADIUS_TOLERANCE)


# ------------------------------------------------------------ the torque through the cam
def _motor_torque(theta: np.ndarray) -> np.ndarray:
    """F ds/dtheta at the cam, F the follower's inertia, load and spring, through the
    gearbox with its efficiency in the power flow's direction (the cam at constant speed:
    no inertia of the cam, the gear or the rotor acts)."""
    s, s1, s2 = (_lift(theta, k) for k in range(3))
    force = (MASS + FOLLOWER) * s2 * OMEGA**2 + FORCE + PRELOAD + RATE * s
    tau = s1 * force
    return np.where(tau >= 0.0, tau / (N * ETA), tau * ETA / N)


def _peak(f) -> float:
    """max over a turn of f (vectorized) by a grid and a bounded minimization."""
    grid = np.linspace(0.0, 2 * np.pi, 20001)
    i = int(np.argmax(f(grid)))
    found = minimize_scalar(lambda x: -float(f(np.array([x]))[0]),
                            bounds=(grid[max(i - 1, 0)], grid[min(i + 1, 20000)]),
                            method="bounded", options={"xatol": 1e-12})
    return max(-found.fun, float(f(grid)[i]))


def test_motor_torque_through_the_cam_is_force_times_ds_dtheta():
    from sizer.sizing.linkage_move import result_calculator

    design = load(_design())
    calc = result_calculator(design, design.motors[0], make_law("cycloidal"))
    pieces = calc.pieces(np.array([calc.given_scale()]))
    theta = np.concatenate([p.theta for p in pieces])
    torque = np.concatenate([p.torque[0] for p in pieces])
    expected = _motor_torque(theta)
    assert np.allclose(torque, expected, rtol=1e-9, atol=1e-9 * np.max(np.abs(expected)))
    speed = np.concatenate([p.motor_speed[0] for p in pieces])
    assert np.allclose(speed, N * OMEGA, rtol=1e-12)  # dwells too: the cam turns on


def test_peak_and_rms_torque_through_the_cam():
    (result,) = size(_design()).results
    breaks = [BETA, BETA + DWELL, 2 * BETA + DWELL]
    square, _ = quad(lambda x: float(_motor_torque(np.array([x]))[0]) ** 2, 0.0, 2 * np.pi,
                     points=breaks, limit=400, epsabs=0.0, epsrel=1e-13)
    assert result.rms_torque == pytest.approx(math.sqrt(square / (2 * np.pi)), rel=1e-9)
    assert result.peak_torque == pytest.approx(_peak(lambda x: np.abs(_motor_torque(x))),
                                               rel=1e-9)
    assert result.max_speed == pytest.approx(N * OMEGA, rel=1e-12)


# ------------------------------------------------------------ the follower's contact
def test_a_separating_follower_fails_cam_contact_with_its_margin():
    # 4x faster: the follower's deceleration over the top of the rise exceeds what the
    # spring and the load push it back with
    fast = _design(_cam(spring_preload="20 N", spring_force_at_top="60 N"), load={
        "mass": f"{MASS} kg", "force": "0 N"})
    for segment in fast["cycle"]["segments"]:
        (body,) = segment.values()
        body["duration"] = f"{float(body['duration'].split()[0]) / 4} s"
    (result,) = size(fast).results
    check = {c.name: c for c in result.checks}["cam_contact"]
    omega = 4 * OMEGA
    rate = 40.0 / H

    def gap(theta: float) -> float:  # the preload needed at theta: P - N(theta)
        z = np.array([theta])
        return -((MASS + FOLLOWER) * _lift(z, 2)[0] * omega**2 + rate * _lift(z)[0])

    found = minimize_scalar(lambda x: -gap(x), bounds=(BETA / 2, BETA), method="bounded",
                            options={"xatol": 1e-12})
    needed = -found.fun
    assert needed > 20.0
    assert not check.passed and not result.feasible
    assert check.value == pytest.approx(needed, rel=1e-9)
    assert check.limit == pytest.approx(20.0)
    assert check.margin == pytest.approx(1.0 - needed / 20.0, rel=1e-9)
    # with the preload it needs the follower stays on the cam
    fast["transmission"][1].update(spring_preload=f"{needed * 1.001} N",
                                   spring_force_at_top=f"{needed * 1.001 + 40.0} N")
    (again,) = size(fast).results
    assert {c.name: c for c in again.checks}["cam_contact"].passed


def test_a_form_closed_cam_has_no_contact_check():
    (result,) = size(_design(_cam(spring_preload=None, spring_force_at_top=None))).results
    names = [c.name for c in result.checks]
    assert "pressure_angle" in names and "cam_curvature" in names
    assert "cam_contact" not in names


def test_pressure_angle_over_its_limit_fails():
    (result,) = size(_design(_cam(base_radius="5 mm", roller_radius="2 mm", offset=0))).results
    check = {c.name: c for c in result.checks}["pressure_angle"]
    # in line: phi = atan(s' / (s + R_p)), its largest by bounded minimization
    rp = 0.007

    def minus_phi(x: float) -> float:
        z = np.array([x])
        return -math.atan(float(_lift(z, 1)[0]) / (float(_lift(z)[0]) + rp))

    found = minimize_scalar(minus_phi, bounds=(0.0, BETA), method="bounded",
                            options={"xatol": 1e-12})
    assert check.value == pytest.approx(-found.fun, rel=1e-9)
    assert not check.passed and not result.feasible
    assert check.margin == pytest.approx(1.0 + found.fun / math.radians(30.0), rel=1e-9)


# ------------------------------------------------------------ end to end, bad inputs
def test_sizer_size_a_disc_cam(tmp_path):
    from cli_run import run_cli

    path = tmp_path / "cam.yaml"
    path.write_text(yaml.safe_dump(_design()), encoding="utf-8")
    out = run_cli("size", str(path), "--all", "--format", "json")
    assert out.returncode == 0, out.stderr
    import json

    (result,) = json.loads(out.stdout)["results"]
    names = [c["name"] for c in result["checks"]]
    assert {"pressure_angle", "cam_curvature", "cam_contact"} <= set(names)


D = "design.yaml:"
CAM = "transmission[1]"
F = "transmission[disc_cam]"


def _text(cam: dict | None = None, **changes: object) -> str:
    return yaml.safe_dump(_design(cam, **changes), sort_keys=False)


def _case(id: str, cam: dict, words: tuple[str, ...], fields: tuple[str, ...] = (),
          **changes: object) -> Case:
    return Case(id, design=_text(cam, **changes), words=(D, *words), fields=fields)


FIELD_CASES = [
    _case("cam-type-unknown", _cam(type="barrel_cam"), (f"{CAM}", "disc_cam"), (f"{F}.type",)),
    _case("cam-follower-flat", _cam(follower="flat_face"), (f"{CAM}.follower",
                                                             "translating_roller"),
          (f"{F}.follower",)),
    _case("cam-base-radius-a-word", _cam(base_radius="big"), (f"{CAM}.base_radius",),
          (f"{F}.base_radius",)),
    _case("cam-base-radius-inside-the-offset", _cam(base_radius="2 mm", roller_radius="1 mm",
                                                    offset="5 mm"),
          (f"{CAM}.base_radius", "larger than the offset")),
    _case("cam-roller-radius-20-m", _cam(roller_radius="20 m"),
          (f"{CAM}.roller_radius", "[1e-4, 10] m"), (f"{F}.roller_radius",)),
    _case("cam-offset-an-angle", _cam(offset="5 deg"), (f"{CAM}.offset",), (f"{F}.offset",)),
    _case("cam-pressure-angle-90-deg", _cam(pressure_angle="90 deg"),
          (f"{CAM}.pressure_angle", "[0.001, 1.5] rad"), (f"{F}.pressure_angle",)),
    _case("cam-follower-mass-negative", _cam(follower_mass="-1 kg"),
          (f"{CAM}.follower_mass", "[1e-6, 1e4] kg"), (f"{F}.follower_mass",)),
    _case("cam-inertia-huge", _cam(cam_inertia="1e4 kg*m^2"),
          (f"{CAM}.cam_inertia", "[1e-12, 1000] kg*m^2"), (f"{F}.cam_inertia",)),
    _case("cam-spring-preload-a-length", _cam(spring_preload="5 mm"),
          (f"{CAM}.spring_preload",), (f"{F}.spring_preload",)),
    _case("cam-spring-top-below-preload", _cam(spring_force_at_top="50 N"),
          (f"{CAM}.spring_force_at_top", "at least its preload"), (f"{F}.spring_force_at_top",)),
    _case("cam-spring-top-without-preload", _cam(spring_preload=None),
          (f"{CAM}.spring_force_at_top", "needs its preload")),
    _case("cam-name-a-list", _cam(name=[1]), (f"{CAM}.name", "expected text"), (f"{F}.name",)),
    _case("cam-not-last", None, ("transmission[0].type", "must be the last stage"),
          transmission=[_cam(), {"type": "rack_pinion", "pitch_radius": "20 mm"}]),
    _case("cam-task-without-return", None, ("task", "return"),
          cycle=None, task={"displacement": "20 mm", "duration": "0.1 s", "dwell": "0.1 s"}),
    _case("cam-follower-not-back", None, ("cycle", "sum to 0.01 m"), cycle={"segments": [
        {"move": {"displacement": "20 mm", "duration": "0.1 s"}},
        {"move": {"displacement": "-10 mm", "duration": "0.1 s"}}]}),
    _case("cam-free-duration", None, ("cycle.segments[1]", "own duration"), cycle={
        "segments": [{"move": {"displacement": "20 mm", "duration": "0.1 s"}},
                     {"move": {"displacement": "-20 mm"}}]}),
]
"""The disc cam's fields' bad values and its cycle's: each one located message (for
tests/test_bad_inputs_fields.py's walk over every field: it needs these ``fields``)."""


@pytest.mark.parametrize("case", FIELD_CASES, ids=str)
def test_bad_cam_field(case, tmp_path):
    run(case, tmp_path)


def test_profile_points_are_the_roller_s_envelope():
    from sizer.mechanics.disc_cam import profile_points
    from sizer.sizing.linkage_move import cam_design

    cam = cam_design(load(_design()), make_law("cycloidal")).transmission.linkage
    points = profile_points(cam, 121)
    rp, e, roller = 0.05, 0.005, 0.01
    # the pitch curve: the roller's centre (e, d + s) of the fixed frame in the cam's
    for theta, x, y in zip(points.theta, points.pitch_x, points.pitch_y, strict=True):
        assert np.allclose([x, y], _pitch_point(theta, rp, e, lambda z: _lift(np.array([z]))[0]),
                           atol=1e-15)
    # each profile point is a roller's radius from the pitch curve, and no point of the
    # (densely sampled) pitch curve is nearer: the roller touches the profile there
    t = np.linspace(0, 2 * np.pi, 20001)
    d = math.sqrt(rp * rp - e * e)
    # [[cos, sin], [-sin, cos]] (e, d + s), as _pitch_point, for every angle at once
    rotated = np.stack([np.cos(t) * e + np.sin(t) * (d + _lift(t)),
                        -np.sin(t) * e + np.cos(t) * (d + _lift(t))], axis=1)
    assert np.allclose(rotated[::1000], [_pitch_point(x, rp, e, lambda z: _lift(np.array([z]))[0])
                                         for x in t[::1000]], atol=1e-15)
    dense = rotated
    profile = np.stack([points.profile_x, points.profile_y], axis=1)
    nearest = np.min(np.linalg.norm(profile[:, None, :] - dense[None, :, :], axis=2), axis=1)
    assert np.allclose(nearest, roller, rtol=1e-6)
    own = np.hypot(points.profile_x - points.pitch_x, points.profile_y - points.pitch_y)
    assert np.allclose(own, roller, rtol=1e-12)


def test_undercut_fails_cam_curvature_with_its_margin():
    # the rise and the return in 20 ms each (24 deg of cam), 130 ms dwells: a 5 mm roller
    # on a 15 mm base circle, in line, is sharper than the pitch curve over the top
    roller, rp = 0.005, 0.02
    design = _design(_cam(base_radius="15 mm", roller_radius="5 mm", offset=0,
                          pressure_angle="80 deg"))
    for segment, duration in zip(design["cycle"]["segments"], (0.02, 0.13, 0.02, 0.13),
                                 strict=True):
        (body,) = segment.values()
        body["duration"] = f"{duration} s"
    (result,) = size(design).results
    check = {c.name: c for c in result.checks}["cam_curvature"]
    beta, dwell = 2 * np.pi * 0.02 / 0.3, 2 * np.pi * 0.13 / 0.3

    def s(z: float) -> float:
        return float(_lift(np.array([z]), beta=beta, dwell=dwell)[0])

    def kappa(theta: float) -> float:  # 1/rho of the pitch curve by 5-point differences
        d1, d2 = _derivatives(theta, rp, 0.0, s, 1e-4)
        return -(d1[0] * d2[1] - d1[1] * d2[0]) / np.hypot(*d1) ** 3

    grid = np.linspace(0.001, beta - 0.001, 801)  # the rise (the return mirrors it)
    start = grid[int(np.argmax([kappa(x) for x in grid]))]
    found = minimize_scalar(lambda x: -kappa(x), bounds=(start - 0.002, start + 0.002),
                            method="bounded", options={"xatol": 1e-10})
    rho = -1.0 / found.fun
    assert rho < roller
    assert not check.passed and not result.feasible
    assert check.value == roller
    assert check.limit == pytest.approx(rho, rel=1e-6)
    assert check.margin == pytest.approx(1.0 - roller / rho, rel=1e-6)


def test_a_task_with_its_return_is_the_cam_s_cycle():
    # the task shorthand: rise, dwell, return, dwell; a single stage given as a mapping
    task = {"displacement": f"{H * 1e3} mm", "duration": f"{RISE} s", "dwell": f"{TOP} s",
            "return": True}
    cam = _design(_cam(), cycle=None, task=task)
    cam["transmission"] = _cam()
    (result,) = size(cam).results
    def tau(theta: np.ndarray) -> np.ndarray:  # no gearbox: the cam on the motor's shaft
        s, s1, s2 = (_lift(theta, k) for k in range(3))
        return np.abs(s1 * ((MASS + FOLLOWER) * s2 * OMEGA**2 + FORCE + PRELOAD + RATE * s))

    assert result.peak_torque == pytest.approx(_peak(tau), rel=1e-9)
    assert result.max_speed == pytest.approx(OMEGA, rel=1e-12)


# ------------------------------------------------------------ an oscillating follower
PIVOT, ARM = 0.1, 0.08
"""The oscillating follower's pivot at (PIVOT, 0) from the cam's centre, its arm (m)."""
SWING = math.radians(20.0)


def _swing(theta: np.ndarray, k: int = 0) -> np.ndarray:
    """The arm's swing: the cycle's lift shape with an angle SWING for H."""
    return _lift(theta, k) * SWING / H


def _roller(theta: float, rp: float) -> np.ndarray:
    """The oscillating roller's centre in the cam's frame: the pivot at (PIVOT, 0), the arm
    at psi_0 + swing from the line to the cam's centre, psi_0 where the roller is on the
    prime circle (the law of cosines), turned by -theta."""
    psi = math.acos((PIVOT**2 + ARM**2 - rp**2) / (2 * PIVOT * ARM)) + \
        float(_swing(np.array([theta]))[0])
    p = np.array([PIVOT - ARM * math.cos(psi), ARM * math.sin(psi)])
    c, n = math.cos(theta), math.sin(theta)
    return np.array([[c, n], [-n, c]]) @ p, p - np.array([PIVOT, 0.0])


@pytest.mark.parametrize("theta", [0.3, 1.0, 1.6, 2.5, 3.3, 3.9, 4.6, 5.6])
def test_oscillating_pressure_angle_and_curvature_against_the_pitch_curve(theta):
    from sizer.mechanics.disc_cam import curvature_of, oscillating_motion, pressure_angle_of

    rp = 0.035
    step = 1e-3
    f = [_roller(theta + k * step, rp)[0] for k in (-2, -1, 0, 1, 2)]
    d1 = (f[0] - 8 * f[1] + 8 * f[3] - f[4]) / (12 * step)
    d2 = (-f[0] + 16 * f[1] - 30 * f[2] + 16 * f[3] - f[4]) / (12 * step * step)
    c, n = math.cos(theta), math.sin(theta)
    tangent = np.array([[c, -n], [n, c]]) @ d1  # in the fixed frame
    normal = np.array([tangent[1], -tangent[0]]) / np.hypot(*tangent)
    arm = _roller(theta, rp)[1]
    moving = np.array([arm[1], -arm[0]]) / np.hypot(*arm)  # perpendicular to the arm
    expected_phi = math.acos(min(abs(float(normal @ moving)), 1.0))
    expected_kappa = -(d1[0] * d2[1] - d1[1] * d2[0]) / np.hypot(*d1) ** 3
    z = np.array([theta])
    P, P1, P2, u = oscillating_motion(_swing(z), _swing(z, 1), _swing(z, 2), rp, (PIVOT, ARM))
    assert abs(pressure_angle_of(P, P1, u)[0]) == pytest.approx(expected_phi, abs=1e-9)
    assert curvature_of(P, P1, P2)[0] == pytest.approx(expected_kappa, rel=1e-6)


def _oscillating(**fields: object) -> dict:
    cam = {"type": "disc_cam", "follower": "oscillating_roller", "base_radius": "25 mm",
           "roller_radius": "10 mm", "pivot_distance": f"{PIVOT * 1e3} mm",
           "arm_length": f"{ARM * 1e3} mm", "follower_mass": "0.3 kg",
           "spring_torque_preload": "2 N*m", "spring_torque_at_top": "3 N*m"}
    cam.update(fields)
    design = _design({k: v for k, v in cam.items() if v is not None},
                     load={"inertia": "0.002 kg*m^2", "torque": "1 N*m"})
    for segment in design["cycle"]["segments"]:
        (body,) = segment.values()
        if "displacement" in body:
            body["displacement"] = f"{math.copysign(20.0, float(body['displacement'][:-3]))} deg"
    return design


def test_motor_torque_through_an_oscillating_follower():
    (result,) = size(_oscillating()).results
    inertia = 0.002 + 0.3 * ARM**2  # the load's and the follower's mass at the roller
    rate = (3.0 - 2.0) / SWING

    def motor(theta: np.ndarray) -> np.ndarray:
        p, p1, p2 = (_swing(theta, k) for k in range(3))
        tau = p1 * (inertia * p2 * OMEGA**2 + 1.0 + 2.0 + rate * p)
        return np.where(tau >= 0.0, tau / (N * ETA), tau * ETA / N)

    assert result.peak_torque == pytest.approx(_peak(lambda x: np.abs(motor(x))), rel=1e-9)
    square, _ = quad(lambda x: float(motor(np.array([x]))[0]) ** 2, 0.0, 2 * np.pi,
                     points=[BETA, BETA + DWELL, 2 * BETA + DWELL], limit=400, epsabs=0.0,
                     epsrel=1e-13)
    assert result.rms_torque == pytest.approx(math.sqrt(square / (2 * np.pi)), rel=1e-9)
    checks = {c.name: c for c in result.checks}
    assert checks["pressure_angle"].limit == pytest.approx(math.radians(45.0))


def test_oscillating_auto_base_radius_is_the_smallest_that_passes():
    from sizer.sizing.linkage_move import cam_design

    design = _oscillating(base_radius="auto")
    cam = cam_design(load(design), make_law("cycloidal")).transmission.linkage
    limit, roller = math.radians(45.0), 0.01
    assert geometry_passes(cam.lift, cam.base_radius, 0.0, roller, limit, (PIVOT, ARM))
    assert not geometry_passes(cam.lift, cam.base_radius - 1e-6, 0.0, roller, limit,
                               (PIVOT, ARM))
    (result,) = size(design).results
    check = {c.name: c for c in result.checks}["pressure_angle"]
    assert check.passed and check.margin == pytest.approx(0.0, abs=1e-6)


OSC = "transmission[1]"
OSCILLATING_CASES = [
    Case("cam-pivot-distance-20-m", design=yaml.safe_dump(_oscillating(
        pivot_distance="20 m")), words=(D, f"{OSC}.pivot_distance", "[1e-4, 10] m"),
        fields=(f"{F}.pivot_distance",)),
    Case("cam-arm-length-a-torque", design=yaml.safe_dump(_oscillating(
        arm_length="5 N*m")), words=(D, f"{OSC}.arm_length"), fields=(f"{F}.arm_length",)),
    Case("cam-arm-missing", design=yaml.safe_dump(_oscillating(arm_length=None)),
         words=(D, f"{OSC}.follower", "arm_length")),
    Case("cam-arm-on-a-translating-follower", design=_text(_cam(arm_length="80 mm")),
         words=(D, f"{OSC}.arm_length", "oscillating")),
    Case("cam-arm-out-of-reach", design=yaml.safe_dump(_oscillating(
        base_radius="200 mm")), words=(D, f"{OSC}.base_radius", "the arm reaches it")),
    Case("cam-spring-torque-negative", design=yaml.safe_dump(_oscillating(
        spring_torque_preload="-2 N*m")), words=(D, f"{OSC}.spring_torque_preload",
                                                 "[1e-9, 1e6] N*m"),
         fields=(f"{F}.spring_torque_preload",)),
    Case("cam-spring-torque-top-below", design=yaml.safe_dump(_oscillating(
        spring_torque_at_top="1 N*m")), words=(D, f"{OSC}.spring_torque_at_top",
                                               "at least its preload"),
         fields=(f"{F}.spring_torque_at_top",)),
    Case("cam-spring-force-on-an-arm", design=yaml.safe_dump(_oscillating(
        spring_preload="20 N")), words=(D, f"{OSC}.spring_preload", "spring_torque_preload")),
    Case("cam-oscillating-lift-a-length", design=yaml.safe_dump(_design(_oscillating()[
        "transmission"][1], load={"inertia": "0.002 kg*m^2"})),
        words=(D, "cycle", "an angle")),
]
"""An oscillating follower's fields and its cycle, bad."""
FIELD_CASES += OSCILLATING_CASES


@pytest.mark.parametrize("case", OSCILLATING_CASES, ids=str)
def test_bad_oscillating_field(case, tmp_path):
    run(case, tmp_path)


def test_oscillating_profile_points_are_the_roller_s_envelope():
    from sizer.mechanics.disc_cam import profile_points
    from sizer.sizing.linkage_move import cam_design

    cam = cam_design(load(_oscillating()), make_law("cycloidal")).transmission.linkage
    rp, roller = 0.035, 0.01
    points = profile_points(cam, 91)
    for theta, x, y in zip(points.theta, points.pitch_x, points.pitch_y, strict=True):
        assert np.allclose([x, y], _roller(theta, rp)[0], atol=1e-15)
    dense = np.array([_roller(t, rp)[0] for t in np.linspace(0, 2 * np.pi, 20001)])
    profile = np.stack([points.profile_x, points.profile_y], axis=1)
    nearest = np.min(np.linalg.norm(profile[:, None, :] - dense[None, :, :], axis=2), axis=1)
    assert np.allclose(nearest, roller, rtol=1e-6)
