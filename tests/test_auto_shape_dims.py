"""`auto` on three shape parameters at once (fifteen_segments: alpha, beta, gamma): the
search's optimum against a dense grid of the test's own eq. (6.2) closed form."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy import optimize

from sizer.laws import LAW_FAMILIES
from sizer.model import Design, Limits, Load, Motor, Task
from sizer.sizing import size_design

MOTOR = Motor("m", inertia=1e-3, continuous_torque=4.0, peak_torque=12.0, rated_speed=3.0)
J_T = 1.0 + MOTOR.inertia
JERK = 400.0
FIFTEEN = LAW_FAMILIES["fifteen_segments"]
DWELL = 0.5


def t_min(law) -> float:
    """eq. (6.2), h = 1, direct drive: the largest of the speed, peak, RMS and jerk bounds
    from the law's coefficients (sec. 6.2.1)."""
    c = law.coefficients
    scale = c.C_a_rms * J_T / MOTOR.continuous_torque
    rms = optimize.brentq(lambda T: T**3 * (T + DWELL) - scale**2, 1e-9, 10 * math.sqrt(scale),
                          xtol=1e-15, rtol=1e-15)
    return max(c.C_v / MOTOR.rated_speed, math.sqrt(c.C_a * J_T / MOTOR.peak_torque), rms,
               (c.C_j / JERK) ** (1 / 3))


def design(spec: str) -> Design:
    return Design(Task(1.0, None, dwell=DWELL), Load(1.0), laws=(spec,), motors=(MOTOR,),
                  limits=Limits(max_jerk=JERK))


def test_the_closed_form_is_the_engines_duration():
    spec = "fifteen_segments(alpha=0.25, beta=0.2, gamma=0.15)"
    r = size_design(design(spec)).results[0]
    law = FIFTEEN(alpha=0.25, beta=0.2, gamma=0.15)
    assert r.duration == pytest.approx(t_min(law), rel=1e-9)


def test_three_auto_parameters_size_and_beat_a_dense_grid():
    r = size_design(design("fifteen_segments(alpha=auto, beta=auto, gamma=auto)")).results[0]
    assert r.feasible and r.law == "fifteen_segments"
    grid = np.linspace(0.01, 0.49, 11)
    brute = min(t_min(FIFTEEN(alpha=a, beta=b, gamma=g))
                for a, b, g in itertools.product(grid, grid, grid))
    assert r.duration <= brute * (1 + 1e-12)
    chosen = FIFTEEN(**r.params)
    assert r.duration == pytest.approx(t_min(chosen), rel=1e-9)
