"""The time instants of a spline (book sec. 4.4.6): the distributions (4.37), the ``auto``
times (lowest peak or RMS acceleration for a given duration), the book's minimum-time
iteration (4.39) on Example 4.15, and the bad inputs of the times fields."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize
from test_cubic_splines import assert_c2

from sizer.errors import UserError
from sizer.laws.multipoint import cubic_splines as cs
from sizer.laws.multipoint import cubic_splines as kt

Q_4_14 = np.array([0.0, 2, 12, 5, 12, -10, -11, -4, 6, 9])
Q_4_15 = np.array([0.0, 2, 12, 5])


def test_distributions_4_37():
    np.testing.assert_allclose(kt.distributed_times(Q_4_15, "equal"), [0, 1 / 3, 2 / 3, 1])
    np.testing.assert_allclose(kt.distributed_times(Q_4_15, "chord", 19.0), [0, 2, 12, 19])
    d = np.sqrt([2.0, 10.0, 7.0])
    np.testing.assert_allclose(kt.distributed_times(Q_4_15, "centripetal", 2.0),
                               2 * np.concatenate([[0], np.cumsum(d)]) / d.sum())


def test_chord_times_need_distinct_consecutive_positions():
    with pytest.raises(UserError) as caught:
        kt.distributed_times(np.array([0.0, 1, 1, 2]), "chord")
    assert caught.value.field == "times"
    assert "positions[2] = positions[1]" in caught.value.message


def test_exact_measures_against_samples():
    t = kt.distributed_times(Q_4_14, "centripetal", 3.0)
    pp = cs.velocity_acceleration_spline(t, Q_4_14, 0, 0, 0, 0)
    x = np.linspace(0.0, 3.0, 300001)
    a = pp(x, 2)
    # the acceleration is piecewise linear: its peak is at a breakpoint
    assert kt.peak_acceleration(pp) == pytest.approx(np.max(np.abs(pp(pp.x, 2))), rel=1e-12)
    assert kt.peak_acceleration(pp) >= np.max(np.abs(a))
    h = x[1] - x[0]
    integral = h / 3 * (a[0] ** 2 + a[-1] ** 2 + 4 * np.sum(a[1:-1:2] ** 2)
                        + 2 * np.sum(a[2:-1:2] ** 2))  # Simpson; exact up to the kinks
    assert kt.rms_acceleration(pp) == pytest.approx(math.sqrt(integral / 3.0), rel=1e-6)


CONDITIONS = [
    (Q_4_14, {}),                                              # clamped, v = 0
    (Q_4_14, {"v0": 0.0, "vn": 0.0, "a0": 0.0, "an": 0.0}),    # sec. 4.4.4, Example 4.14
    (np.array([0.0, 3, 1, 4, 0]), {"periodic": True}),
    (np.array([0.0, 1, 3, 2, 5]), {"natural": True}),
]


@pytest.mark.parametrize("objective", kt.OBJECTIVES)
@pytest.mark.parametrize(("q", "conditions"), CONDITIONS)
def test_auto_times_are_a_local_optimum(q, conditions, objective):
    measure = kt.MEASURES[objective]
    duration = 2.0
    t = kt.optimal_times(q, duration, objective, **conditions)
    assert t[0] == 0.0 and t[-1] == duration and np.all(np.diff(t) > 0)
    best = measure(cs.cubic_spline(t, q, **conditions))
    equal = measure(cs.cubic_spline(kt.distributed_times(q, "equal", duration), q,
                                    **conditions))
    assert best <= equal * (1 + 1e-12)
    pp = cs.cubic_spline(t, q, **conditions)
    np.testing.assert_allclose(pp(t), q, rtol=0, atol=1e-9)
    assert_c2(pp)
    step = 1e-3 * duration
    for k in range(1, len(t) - 1):
        for sign in (-1.0, 1.0):
            moved = t.copy()
            moved[k] += sign * step
            other = measure(cs.cubic_spline(moved, q, **conditions))
            assert other >= best * (1 - 1e-9), (k, sign, other, best)


def test_auto_times_are_deterministic():
    first = kt.optimal_times(Q_4_14, 1.0, "peak_acceleration")
    np.testing.assert_array_equal(first, kt.optimal_times(Q_4_14, 1.0, "peak_acceleration"))


# ---------------------------------------------------------------- Example 4.15

def interval_peaks(T: np.ndarray) -> np.ndarray:
    """(max |v|, max |a|) on each interval of the clamped spline through Q_4_15, from
    dense samples (independent of the code's exact peaks)."""
    t = np.concatenate([[0.0], np.cumsum(T)])
    pp = cs.clamped_spline(t, Q_4_15)
    out = []
    for k in range(len(T)):
        x = np.linspace(t[k], t[k + 1], 20001)
        out.append([np.max(np.abs(pp(x, 1))), np.max(np.abs(pp(x, 2)))])
    return np.array(out)


def test_example_4_15_minimum_duration():
    t = kt.minimum_duration_times(Q_4_15, kt.distributed_times(Q_4_15, "chord"),
                                  {1: 3.0, 2: 2.0})
    T = np.diff(t)
    peaks = interval_peaks(T)
    # the fixed point of (4.39): every interval reaches a limit and none exceeds one
    reach = np.maximum(peaks[:, 0] / 3.0, np.sqrt(peaks[:, 1] / 2.0))
    np.testing.assert_allclose(reach, 1.0, rtol=0, atol=1e-6)
    # the nonlinear problem (4.38) solved directly gives the same duration

    def limits(T):
        x = np.concatenate([[0.0], np.cumsum(T)])
        pp = cs.clamped_spline(x, Q_4_15)
        s = np.linspace(0.0, 1.0, 401)
        v = [np.max(np.abs(pp(x[k] + s * T[k], 1))) for k in range(3)]
        a = [np.max(np.abs(pp(x[k] + s * T[k], 2))) for k in range(3)]
        return np.concatenate([3.0 - np.array(v), 2.0 - np.array(a)])
    direct = minimize(lambda T: T.sum(), [1.5, 4.5, 4.5], method="SLSQP",
                      constraints=[{"type": "ineq", "fun": limits}],
                      bounds=[(0.1, 20)] * 3, options={"ftol": 1e-12})
    assert direct.x.sum() == pytest.approx(T.sum(), rel=1e-5)
    # printed T = 10.5818 from T_k = 1.5551, 4.4500, 4.5767 (erratum): those intervals
    # exceed a_max = 2 in the last one; the fixed point is 1.5549, 4.4451, 4.5826
    np.testing.assert_allclose([*T, T.sum()], [1.5549, 4.4451, 4.5826, 10.5826], rtol=0,
                               atol=1e-4)
    book = interval_peaks(np.array([1.5551, 4.4500, 4.5767]))
    assert book[2, 1] > 2.002


def agrees_4(value: float, text: str) -> bool:
    return abs(value - float(text)) < 1e-4


# ---------------------------------------------------------------- the builder's fields

def test_builder_time_words():
    pp = cs.build_cubic_spline({"times": "equal", "positions": Q_4_15.tolist(),
                                "duration": 3})
    np.testing.assert_allclose(pp.x, [0, 1, 2, 3])
    pp = cs.build_cubic_spline({"times": "chord", "positions": Q_4_15.tolist(),
                                "duration": 19})
    np.testing.assert_allclose(pp.x, [0, 2, 12, 19])
    fields = {"times": "auto", "positions": Q_4_14.tolist(), "minimize": "rms_acceleration",
              "start": {"velocity": 0, "acceleration": 0},
              "end": {"velocity": 0, "acceleration": 0}}
    pp = cs.build_cubic_spline(fields)
    t = kt.optimal_times(Q_4_14, 1.0, "rms_acceleration", v0=0.0, vn=0.0, a0=0.0, an=0.0)
    np.testing.assert_allclose(pp(t), Q_4_14, rtol=0, atol=1e-9)
    pp = cs.build_cubic_spline({"positions": Q_4_15.tolist(), "minimize": "duration",
                                "limits": {"velocity": 3, "acceleration": 2}})
    assert agrees_4(pp.x[-1], "10.5826")


POSITIONS = {"positions": [0, 1, 3]}
BAD = [
    ({**POSITIONS, "times": "even"}, "times", "unknown time distribution 'even'"),
    ({"times": [0, 1, 2], **POSITIONS, "duration": 2}, "duration", "listed times"),
    ({**POSITIONS, "times": "equal", "duration": -1}, "duration", "must be positive"),
    ({**POSITIONS, "times": "equal", "minimize": "peak_acceleration"}, "minimize",
     "use times: auto"),
    ({**POSITIONS, "times": "auto", "minimize": "jerk"}, "minimize", "unknown objective"),
    ({**POSITIONS, "times": "equal", "limits": {"velocity": 1}}, "limits",
     "minimize: duration"),
    ({**POSITIONS, "minimize": "duration"}, "limits", "needs limits"),
    ({**POSITIONS, "minimize": "duration", "limits": {"velocity": 0}}, "limits.velocity",
     "must be positive"),
    ({**POSITIONS, "minimize": "duration", "limits": {"velocity": 1}, "duration": 2},
     "duration", "remove duration"),
    ({**POSITIONS, "times": "auto", "minimize": "duration", "limits": {"velocity": 1}},
     "times", "only start the book's iteration"),
    ({**POSITIONS, "times": "equal", "start": {"velocity": 0, "acceleration": 0},
      "end": {"velocity": 0, "acceleration": 0}, "extra_times": [0.1, 0.9]},
     "extra_times", "midpoints"),
    ({"points": [[0, 0], [1, 1]], "times": "equal"}, "points", "not both"),
]


@pytest.mark.parametrize(("fields", "field", "text"), BAD)
def test_bad_input_names_the_field(fields, field, text):
    with pytest.raises(UserError) as caught:
        cs.build_cubic_spline(fields)
    assert caught.value.field == field
    assert text in caught.value.message
