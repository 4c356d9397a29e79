"""The trapezoidal trajectory through a sequence of points (book sec. 3.2.4; issue 13)."""

from __future__ import annotations

import numpy as np
import pytest

from sizer.errors import UserError
from sizer.laws.multipoint.via_trapezoid import (
    acceleration_times_from_acceleration,
    build_via_trapezoid,
    via_trapezoid,
)

POINTS = [[0.0, 0.0], [2.0, 10.0], [4.0, 30.0], [6.0, 20.0], [7.0, 25.0], [10.0, 0.0]]


def trapezoid(t: np.ndarray, t0: float, T: float, Ta: float, h: float) -> np.ndarray:
    """Eq. (3.4) from q0 = 0 to q1 = h over [t0, t0 + T], 0 before, h after."""
    v = h / (T - Ta)
    u = np.clip(t - t0, 0.0, T)
    return np.where(u < Ta, v / (2 * Ta) * u ** 2,
                    np.where(u < T - Ta, v * (u - Ta / 2), h - v / (2 * Ta) * (T - u) ** 2))


def superposed(t: np.ndarray, points: list[list[float]], Ta: np.ndarray,
               overlaps: np.ndarray) -> np.ndarray:
    """Sec. 3.2.4 literally: the segments' trapezoids added, segment k + 1 started
    overlaps[k] before segment k ends."""
    times, q = np.array(points).T
    out = np.full_like(t, q[0])
    start = times[0]
    for k in range(len(q) - 1):
        T = times[k + 1] - times[k]
        out += trapezoid(t, start, T, Ta[k], q[k + 1] - q[k])
        if k < len(overlaps):
            start += T - overlaps[k]
    return out


def test_example_3_2_single_segment() -> None:
    """q0 = 0, q1 = 30, t0 = 0, t1 = 4, T_a = 1: v_v = 10 (printed) and a = v_v / T_a."""
    curve = build_via_trapezoid({"kind": "via_trapezoid", "points": [[0, 0], [4, 30]],
                                 "acceleration_time": 1})
    assert curve.x.tolist() == [0.0, 1.0, 3.0, 4.0]
    assert curve(np.array([0.5, 2.0, 3.5]), 1) == pytest.approx([5.0, 10.0, 5.0])
    assert curve(np.array([0.5, 2.0, 3.5]), 2) == pytest.approx([10.0, 0.0, -10.0])
    t = np.linspace(0.0, 4.0, 401)
    assert curve(t) == pytest.approx(trapezoid(t, 0.0, 4.0, 1.0, 30.0), abs=1e-12)


def test_eq_3_6_acceleration_gives_the_acceleration_period() -> None:
    """a_a = 10 on Example 3.2: T_a = (a T - sqrt(a^2 T^2 - 4 a h)) / 2a = 1."""
    Ta = acceleration_times_from_acceleration(np.array([0.0, 30.0]), np.array([4.0]), 10.0)
    assert Ta == pytest.approx([1.0])
    curve = build_via_trapezoid({"points": [[0, 0], [4, 30]], "acceleration": 10})
    assert curve.x.tolist() == pytest.approx([0.0, 1.0, 3.0, 4.0])
    # and (3.5), a_a T_a^2 - a_a (t1 - t0) T_a + (q1 - q0) = 0, for another move
    q, T, a = np.array([2.0, -5.0]), np.array([3.0]), 4.0
    Ta = acceleration_times_from_acceleration(q, T, a)[0]
    assert a * Ta ** 2 - a * T[0] * Ta + 7.0 == pytest.approx(0.0, abs=1e-12)
    assert 0.0 < Ta < T[0] / 2


def test_eq_3_7_minimum_acceleration_gives_the_parabolic_trajectory() -> None:
    h, T = 30.0, 4.0
    curve = build_via_trapezoid({"points": [[0, 0], [T, h]], "acceleration": 4 * h / T ** 2})
    assert curve.x.tolist() == pytest.approx([0.0, 2.0, 4.0])  # T_a = T / 2
    with pytest.raises(UserError, match=r"4 \|h\| / T\^2 = 7.5, eq. \(3.7\)") as caught:
        build_via_trapezoid({"points": [[0, 0], [T, h]], "acceleration": 7.0})
    assert caught.value.field == "acceleration"


def test_default_is_the_book_choice_t_a_one_third() -> None:
    """T_a = T/3: v_v = 3h / 2T, a_a = 9h / 2T^2 (sec. 3.2)."""
    h, T = 12.0, 3.0
    curve = build_via_trapezoid({"times": [1.0, 1.0 + T], "positions": [5.0, 5.0 + h]})
    assert curve.x.tolist() == pytest.approx([1.0, 2.0, 3.0, 4.0])
    assert curve(np.array([2.5]), 1)[0] == pytest.approx(3 * h / (2 * T))
    assert curve(np.array([1.5]), 2)[0] == pytest.approx(9 * h / (2 * T ** 2))


def test_null_intermediate_velocities_pass_through_every_point() -> None:
    """Fig. 3.5 (a): the trapezoids one after the other stop at every via-point."""
    curve = build_via_trapezoid({"points": POINTS, "acceleration_time": 0.4,
                                 "blend": False})
    t, q = np.array(POINTS).T
    assert curve.x[0] == 0.0 and curve.x[-1] == 10.0
    assert curve(t) == pytest.approx(q, abs=1e-12)
    assert curve(t, 1) == pytest.approx(np.zeros_like(t), abs=1e-12)


def test_blends_are_the_superposition_of_the_segments() -> None:
    """Fig. 3.5 (b): segment k + 1 starts T_a before segment k ends and the profiles add;
    the motion is shorter by T_a per interior point."""
    Ta = 0.4
    curve = build_via_trapezoid({"points": POINTS, "acceleration_time": Ta})
    n = len(POINTS) - 1
    assert curve.x[0] == 0.0
    assert curve.x[-1] == pytest.approx(10.0 - (n - 1) * Ta)
    t = np.linspace(curve.x[0], curve.x[-1], 5001)
    expected = superposed(t, POINTS, np.full(n, Ta), np.full(n - 1, Ta))
    assert curve(t) == pytest.approx(expected, abs=1e-12)
    ends = np.array([curve.x[0], curve.x[-1]])
    assert curve(ends) == pytest.approx([0.0, 0.0], abs=1e-12)  # q_0 ... q_n = 0
    assert curve(ends, 1) == pytest.approx([0.0, 0.0], abs=1e-12)  # at rest


def test_blends_near_the_via_points_and_linear_tracts_through_them() -> None:
    """Equal T_a: the blend at q_k is centred at tau_k, with the constant acceleration
    (v_k+1 - v_k) / T_a; the linear tracts join (tau_k-1, q_k-1) to (tau_k, q_k); at
    tau_k the trajectory is at q_k + (v_k+1 - v_k) T_a / 8, not at q_k."""
    Ta = 0.4
    curve = build_via_trapezoid({"points": POINTS, "acceleration_time": Ta})
    times, q = np.array(POINTS).T
    T = np.diff(times)
    v = np.concatenate(([0.0], np.diff(q) / (T - Ta), [0.0]))  # rest before and after
    tau = times[0] + Ta / 2 + np.concatenate(([0.0], np.cumsum(T - Ta)))
    for k in range(len(q)):
        inside = tau[k] + np.array([-0.45, -0.1, 0.2, 0.45]) * Ta
        assert curve(inside, 2) == pytest.approx(np.full(4, (v[k + 1] - v[k]) / Ta))
        assert curve(np.array([tau[k]]))[0] == pytest.approx(q[k] + (v[k + 1] - v[k]) * Ta / 8)
    for k in range(1, len(q)):
        line = np.linspace(tau[k - 1] + Ta / 2, tau[k] - Ta / 2, 7)
        assert curve(line) == pytest.approx(q[k - 1] + v[k] * (line - tau[k - 1]))
        assert curve(line, 1) == pytest.approx(np.full(7, v[k]))
    # the corner at the peak q_2 = 30 is cut: the trajectory stays below it
    dense = np.linspace(curve.x[0], curve.x[-1], 20001)
    assert np.max(curve(dense)) < 30.0 - 0.01


def test_velocity_is_continuous_and_acceleration_piecewise_constant() -> None:
    curve = build_via_trapezoid({"points": POINTS, "acceleration": 60.0})
    inner = curve.x[1:-1]
    eps = 1e-9
    assert curve(inner + eps) == pytest.approx(curve(inner - eps), abs=1e-6)
    assert curve(inner + eps, 1) == pytest.approx(curve(inner - eps, 1), abs=1e-6)
    assert curve.c.shape[0] == 3  # degree 2
    assert np.all(curve(np.linspace(0, curve.x[-1], 101), 3) == 0.0)


def test_unequal_acceleration_periods_overlap_by_the_shorter() -> None:
    """a_a given: each T_a,k from (3.6); the overlap T'_a,k = min(T_a,k, T_a,k+1)."""
    a = 60.0
    times, q = np.array(POINTS).T
    T, h = np.diff(times), np.abs(np.diff(q))
    Ta = (a * T - np.sqrt(a * a * T * T - 4 * a * h)) / (2 * a)  # eq. (3.6)
    curve = build_via_trapezoid({"points": POINTS, "acceleration": a})
    overlaps = np.minimum(Ta[:-1], Ta[1:])
    assert curve.x[-1] == pytest.approx(10.0 - overlaps.sum())
    t = np.linspace(0.0, curve.x[-1], 5001)
    assert curve(t) == pytest.approx(superposed(t, POINTS, Ta, overlaps), abs=1e-10)
    # every segment accelerates at +-a_a; in an overlap the two accelerations add
    accelerations = np.unique(np.round(curve.c[0] * 2, 9))
    assert set(np.abs(accelerations)) <= {0.0, a, 2 * a}


def test_a_dwell_between_equal_points_is_kept() -> None:
    points = [[0, 0], [1, 1], [2, 1], [3, 0]]
    curve = build_via_trapezoid({"points": points, "acceleration_time": 0.25})
    assert curve.x[-1] == pytest.approx(3.0)  # no overlap with the dwell
    dwell = np.linspace(1.0, 2.0, 11)
    assert curve(dwell) == pytest.approx(np.ones(11)) and np.all(curve(dwell, 1) == 0.0)


def test_plain_function_matches_the_builder() -> None:
    times, q = np.array(POINTS).T
    curve = via_trapezoid(times, q, np.full(len(q) - 1, 0.4), blend=True)
    built = build_via_trapezoid({"points": POINTS, "acceleration_time": 0.4})
    assert np.array_equal(curve.x, built.x) and np.array_equal(curve.c, built.c)


@pytest.mark.parametrize(("fields", "field", "message"), [
    ({"points": POINTS, "acceleration_time": 0.6}, "acceleration_time",
     r"T_a = 0.6 of segment 4 \(points 3 to 4\) exceeds half its duration T/2 = 0.5"),
    ({"points": POINTS, "acceleration_time": [0.1, 0.1]}, "acceleration_time",
     "must have 5 numbers"),
    ({"points": POINTS, "acceleration_time": [0.1, 0.1, -1, 0.1, 0.1]},
     "acceleration_time[2]", "must be positive"),
    ({"points": POINTS, "acceleration_time": 0}, "acceleration_time", "must be positive"),
    ({"points": POINTS, "acceleration_time": 0.1, "acceleration": 10}, "acceleration",
     "not both"),
    ({"points": POINTS, "acceleration": 19.9}, "acceleration", r"segment 2 \(points 1 to 2\)"),
    ({"points": POINTS, "blend": "yes"}, "blend", "true or false"),
    ({"points": POINTS, "velocity": 3}, "velocity", "no field"),
    ({"points": [[0, 0], [1, 1], [1, 2]]}, "points[2]", "times must increase"),
    ({"points": [[0, 0]]}, "points", "at least 2 points"),
])
def test_bad_fields(fields: dict, field: str, message: str) -> None:
    with pytest.raises(UserError, match=message) as caught:
        build_via_trapezoid(fields)
    assert caught.value.field == field
