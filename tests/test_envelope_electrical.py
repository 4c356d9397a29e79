"""The electrical envelope (issue 35): the intermittent region a winding's supply allows.

Every number comes from the circuit's closed form or from an independent root finder
(scipy's brentq on the voltage equation), never from the module's own output."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from sizer.envelope import continuous_region, intermittent_region
from sizer.envelope.electrical import TOLERANCE, Winding
from sizer.model.domain import Motor

RPM = math.pi / 30.0

# an AC servo of round figures: k_t 0.6 N*m/A, R 2 ohm and L 8 mH phase to phase, 8 poles,
# on a 320 V DC link; peak 4 N*m, rated 1.3 N*m at 3000 rpm, 6000 rpm at most
SERVO = Motor(id="servo", inertia=1e-4, continuous_torque=1.3, peak_torque=4.0,
              rated_speed=3000 * RPM, max_speed=6000 * RPM, torque_constant=0.6,
              winding_resistance=2.0, winding_inductance=8e-3, poles=8, dc_bus_voltage=320.0)


def _voltage_excess(motor: Motor, speed: float, current: float) -> float:
    """|V_phase|^2 - V_max^2 of the per-phase circuit (RMS phasors, i_d = 0)."""
    e = motor.torque_constant / math.sqrt(3.0) / math.sqrt(3.0) * speed  # k_e/sqrt3 * w
    r, x = motor.winding_resistance / 2.0, motor.poles / 2 * speed * motor.winding_inductance / 2
    return (e + r * current) ** 2 + (x * current) ** 2 - (motor.dc_bus_voltage ** 2) / 6.0


def test_the_constants_follow_by_power_balance():
    w = Winding.of(SERVO)
    assert w is not None and w.back_emf_constant == pytest.approx(0.6 / math.sqrt(3.0), rel=1e-15)
    only_ke = Winding.of(Motor(**{**SERVO.__dict__, "torque_constant": None,
                                  "back_emf_constant": 0.3}))
    assert only_ke is not None and only_ke.torque_constant == pytest.approx(0.3 * math.sqrt(3.0))
    block = Winding.of(Motor(**{**SERVO.__dict__, "commutation": "block"}))
    assert block is not None and block.back_emf_constant == 0.6
    for missing in ("winding_resistance", "dc_bus_voltage"):
        assert Winding.of(Motor(**{**SERVO.__dict__, missing: None})) is None


def test_the_current_solves_the_voltage_equation():
    w = Winding.of(SERVO)
    assert w is not None
    # the no-load speed: E = V, k_e w / sqrt(3) = 320 / sqrt(6)
    w0 = (320.0 / math.sqrt(6.0)) / (0.6 / 3.0)
    assert w.no_load_speed() == pytest.approx(w0, rel=1e-14)
    for speed in (0.0, 100.0, 400.0, 600.0, 0.999 * w0):
        expected = brentq(lambda i, s=speed: _voltage_excess(SERVO, s, i), 0.0, 1e3,
                          xtol=1e-14, rtol=1e-14)
        assert w.current(np.array([speed]))[0] == pytest.approx(expected, rel=1e-10)
    assert w.current(np.array([w0, 1.1 * w0])).tolist() == [0.0, 0.0]


def test_without_inductance_the_line_of_a_resistive_circuit():
    motor = Motor(**{**SERVO.__dict__, "winding_inductance": None})
    w = Winding.of(motor)
    assert w is not None and not w.inductive
    speeds = np.array([0.0, 200.0, 500.0])
    expected = (320.0 / math.sqrt(6.0) - 0.2 * speeds) / 1.0  # (V - E) / R_ph
    assert w.current(speeds) == pytest.approx(expected, rel=1e-14)


def test_block_commutation_is_maxons_straight_line():
    """U = R I + k_e w at the terminals: stall torque k_t U / R, no-load speed U / k_t."""
    motor = Motor(id="ec", inertia=1e-6, continuous_torque=0.05, peak_torque=1.0,
                  rated_speed=3000 * RPM, torque_constant=0.0255, winding_resistance=1.2,
                  dc_bus_voltage=12.0, commutation="block")
    curve = intermittent_region(motor, "electrical")
    stall = 0.0255 * 12.0 / 1.2
    assert curve[0] == (0.0, pytest.approx(stall, rel=1e-14))
    assert curve[-1] == (pytest.approx(12.0 / 0.0255, rel=1e-14), 0.0)
    assert len(curve) == 2 or all(
        t == pytest.approx(stall * (1 - s / curve[-1][0]), rel=1e-12, abs=1e-15)
        for s, t in curve)


def test_the_region_follows_the_torque_within_its_tolerance():
    w = Winding.of(SERVO)
    assert w is not None
    curve = intermittent_region(SERVO, "electrical")
    speeds, torques = (np.array(c) for c in zip(*curve, strict=True))
    assert curve[0] == (0.0, 4.0) and np.all(np.diff(speeds) > 0.0)
    assert speeds[-1] == pytest.approx(6000 * RPM)  # max_speed before the no-load speed
    # the corner: the peak current 4 / 0.6 A just available there (brentq on the speed)
    corner = brentq(lambda s: _voltage_excess(SERVO, s, 4.0 / 0.6), 0.0, 1e3, xtol=1e-12)
    assert speeds[1] == pytest.approx(corner, rel=1e-9)
    dense = np.linspace(0.0, speeds[-1], 20001)
    exact = np.array([min(4.0, 0.6 * brentq(lambda i, s=s: _voltage_excess(SERVO, s, i),
                                            0.0, 1e3, xtol=1e-13))
                      for s in dense[::50]])
    assert np.max(np.abs(np.interp(dense[::50], speeds, torques) - exact)) <= 1.01 * \
        TOLERANCE * 4.0


def test_the_peak_current_caps_the_region():
    capped = Motor(**{**SERVO.__dict__, "peak_current": 5.0})  # 3 N*m < 4 N*m peak torque
    assert intermittent_region(capped, "electrical")[0] == (0.0, 3.0)


def test_a_low_supply_ends_the_region_at_its_no_load_speed():
    low = Motor(**{**SERVO.__dict__, "dc_bus_voltage": 200.0})
    curve = intermittent_region(low, "electrical")
    assert curve[-1] == (pytest.approx((200.0 / math.sqrt(6.0)) / 0.2, rel=1e-14), 0.0)
    # the continuous region: linear's, under the intermittent one
    continuous = continuous_region(low, "electrical")
    speeds = np.linspace(0.0, continuous[-1][0], 1001)
    under = np.interp(speeds, *zip(*curve, strict=True))
    assert np.all(np.interp(speeds, *zip(*continuous, strict=True)) <= under + 1e-12)
    assert continuous[:2] == ((0.0, 1.3), (3000 * RPM, 1.3))


def test_printed_curves_win_and_motors_without_data_are_linear():
    printed = ((0.0, 4.0), (400.0, 3.0), (600.0, 1.0))
    motor = Motor(**{**SERVO.__dict__, "intermittent_curve": printed})
    assert intermittent_region(motor, "electrical") == printed
    plain = Motor(**{**SERVO.__dict__, "dc_bus_voltage": None})
    for region in (intermittent_region, continuous_region):
        assert region(plain, "electrical") == region(plain, "linear")


def test_a_supply_voltage_is_read_as_its_rectified_peak(tmp_path):
    from sizer.io import load_catalog

    path = tmp_path / "m.yaml"
    path.write_text("motors:\n  - {id: A, inertia: 1 kg*cm^2, continuous_torque: 1 N*m,\n"
                    "     peak_torque: 3 N*m, rated_speed: 3000 rpm, torque_constant: 0.6 N*m/A,\n"
                    "     winding_resistance: 2 ohm, supply_voltage: 230 V,\n"
                    "     back_emf_constant: 36.3 V/krpm, poles: 8}\n")
    motor = load_catalog(path)[0]
    assert motor.dc_bus_voltage == pytest.approx(230.0 * math.sqrt(2.0), rel=1e-15)
    assert motor.back_emf_constant == pytest.approx(36.3 / (1000.0 * RPM), rel=1e-15)
    assert motor.poles == 8 and motor.commutation == "sinusoidal"


def test_a_drive_with_its_dc_link_supplies_the_motor():
    """Paired with a drive that gives its DC link, the motor's voltage limit is at that
    link (its own bus only without one); the drive's currents still clip the region."""
    from sizer.model.domain import ServoDrive
    from sizer.sizing.candidates import MotorArrays

    motor = Motor(**{**SERVO.__dict__, "dc_bus_voltage": None, "max_speed": None})
    drives = (ServoDrive(id="low", continuous_current=3.0, peak_current=10.0,
                         dc_bus_voltage=200.0, motors=("servo",)),
              ServoDrive(id="none", continuous_current=3.0, peak_current=10.0,
                         motors=("servo",)))
    arrays = MotorArrays.of([motor], "electrical", drives)
    ends = arrays.intermittent.max_speed
    by_drive = dict(zip(arrays.drive.tolist(), ends.tolist(), strict=True))
    # on 200 V: the no-load speed (200 / sqrt 6) / (k_e / sqrt 3)
    assert by_drive[0] == pytest.approx((200.0 / math.sqrt(6.0)) / 0.2, rel=1e-12)
    # without a DC link anywhere: linear's rectangle up to the rated speed
    assert by_drive[1] == pytest.approx(3000 * RPM, rel=1e-15)


# WITTENSTEIN alpha premo motors on 320 V DC (premo SP/TP/XP Line operating manual, Rev. 02,
# Table 16, read from a mirror: ../shared/reference/motor-data.md sec. 6): stator code ->
# (torque constant N*m/A rms, printed no-load speed rpm)
PREMO_320V = {"1C": (0.35, 10530), "2C": (0.39, 9330), "1D": (0.41, 8855),
              "2D": (0.52, 7023), "1F": (0.51, 7166), "3F": (0.54, 6908)}


@pytest.mark.parametrize("code", sorted(PREMO_320V))
def test_the_no_load_speed_matches_premo_within_5_percent(code):
    """The model's no-load speed on 320 V (space-vector modulation, k_e = k_t / sqrt 3)
    against the printed one: within 5 % (issue 35's goal). The model's is 0.3 % to 3.1 %
    higher: the manual does not say at which magnet temperature it gives k_t and n0, and
    a k_t read hot (weaker magnets) gives a higher n0 than a cold motor reaches."""
    k_t, printed = PREMO_320V[code]
    winding = Winding(k_t, k_t / math.sqrt(3.0), 1.0, 0.0, None, 320.0, False)
    model = winding.no_load_speed() / RPM
    assert model == pytest.approx(printed, rel=0.05)


def test_the_disagreement_with_a_printed_point():
    """Relative in torque, or in speed at zero torque (sizer's tools/catalog_goals.py)."""
    from sizer.envelope.electrical import disagreement

    w = Winding(0.0255, 0.0255, 1.2, 0.0, None, 12.0, True)  # block: U = R I + k_e w
    stall = 0.0255 * 12.0 / 1.2
    assert disagreement(w, 0.0, stall / 1.02) == pytest.approx(0.02, rel=1e-12)
    assert disagreement(w, 12.0 / 0.0255 / 1.05, 0.0) == pytest.approx(0.05, rel=1e-12)


def test_a_printed_line_holds_at_its_own_supply_only():
    """maxon's line is printed at the nominal voltage: on a drive's other DC link the
    winding's model replaces it (capped at the printed peak); on the same, it stays."""
    from sizer.model.domain import ServoDrive
    from sizer.sizing.candidates import MotorArrays

    k_t, R, U = 0.0255, 1.2, 24.0
    line = ((0.0, 0.5), (U / k_t * 0.98, 0.0))  # printed: a little below the ideal line
    motor = Motor(id="ec", inertia=1e-6, continuous_torque=0.05, peak_torque=0.5,
                  rated_speed=3000 * RPM, torque_constant=k_t, winding_resistance=R,
                  dc_bus_voltage=U, commutation="block", intermittent_curve=line)
    drives = tuple(ServoDrive(id=f"d{v:g}", continuous_current=5.0, peak_current=100.0,
                              dc_bus_voltage=v, motors=("ec",)) for v in (24.0, 48.0))
    arrays = MotorArrays.of([motor], "electrical", drives)
    ends = dict(zip(arrays.drive.tolist(), arrays.intermittent.max_speed.tolist(),
                    strict=True))
    assert ends[0] == pytest.approx(line[-1][0], rel=1e-15)  # its own supply: as printed
    assert ends[1] == pytest.approx(48.0 / k_t, rel=1e-12)  # 48 V: the model's no-load
