"""Holding brakes (issue 16): a brake variant's holding torque against the torque that
holds a constant load at rest, and its inertia added to the rotor's.

References: the static torque tau_l / (k eta) of a gearbox holding the load (counted as
driving, as the dwell's holding torque), and the same motor written without brake fields
and with the brake's inertia in its own.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from sizer.model.domain import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing.engine import size_design


def motor(id: str, **fields: float) -> Motor:
    return Motor(id=id, inertia=1e-4, continuous_torque=2.0, peak_torque=6.0,
                 rated_speed=300.0, **fields)


def design(*motors: Motor, torque: float = 8.0) -> Design:
    return Design(task=Task(displacement=1.0, duration=0.4, dwell=0.3),
                  load=Load(inertia=0.05, torque=torque),
                  transmission=Transmission((Stage("gearbox", ratio=10.0, efficiency=0.9),)),
                  laws=("cycloidal",), motors=motors, limits=Limits(torque_margin=0.1))


def test_a_weak_brake_fails_the_holding_check_and_names_it():
    strong = motor("strong", brake_holding_torque=1.5)
    weak = motor("weak", brake_holding_torque=0.9)
    results = {r.motor: r for r in size_design(design(strong, weak)).results}
    hold = 8.0 / (10.0 * 0.9)  # 0.889 N*m at the motor, counted as driving
    check = results["weak"].check("holding_brake")
    assert check.value == pytest.approx(hold, rel=1e-12)
    assert check.limit == 0.9 and not check.passed  # 1.2 % margin against 10 % required
    assert not results["weak"].feasible and results["weak"].limiting == "holding_brake"
    assert results["strong"].check("holding_brake").passed
    assert results["strong"].feasible


def test_no_brake_or_nothing_held_means_no_check():
    plain = size_design(design(motor("plain"))).results[0]
    assert plain.check("holding_brake") is None
    free = size_design(design(motor("braked", brake_holding_torque=1.0), torque=0.0))
    assert free.results[0].check("holding_brake") is None


def test_the_brake_inertia_is_sized_with_the_rotor():
    braked = motor("m", brake_holding_torque=5.0, brake_inertia=0.3e-4)
    alone = replace(motor("m"), inertia=1.3e-4)
    a = size_design(design(braked)).results[0]
    b = size_design(design(alone)).results[0]
    assert a.peak_torque == b.peak_torque and a.rms_torque == b.rms_torque
    assert a.peak_torque > size_design(design(motor("m"))).results[0].peak_torque
