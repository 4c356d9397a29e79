"""Independent references shared by tests: Ruckig's time-optimal duration and printed figures."""

from __future__ import annotations

from ruckig import InputParameter, Result, Ruckig, Trajectory


def ruckig_duration(h: float, v: float, a: float, j: float) -> float:
    """Ruckig's minimal duration of a 1-DOF rest-to-rest move of h under v, a, j limits."""
    inp = InputParameter(1)
    inp.current_position, inp.target_position = [0.0], [h]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [v], [a], [j]
    trajectory = Trajectory(1)
    assert Ruckig(1).calculate(inp, trajectory) == Result.Working
    return trajectory.duration


def printed(value: float, shown: float, last_digit: float) -> None:
    """``value`` rounds to the printed ``shown`` (last printed digit worth ``last_digit``);
    a value exactly half way (J_C = 0.3375e-4, printed 0.338e-4) passes up to rounding."""
    assert abs(value - shown) <= 0.5 * last_digit * (1 + 1e-9), (value, shown)
