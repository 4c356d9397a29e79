"""The bundled drive catalog maxon-escon (issue 16): maxon ESCON controllers for the maxon
EC 45 flat 30 W motors.

The currents are typed from the manufacturer's pages, not from the YAML:
- ESCON Module 50/5 (438725), Hardware Reference rel9051, sec. 2.1 Technical Data, p. 2-9,
  "Output current Icont/Imax (<20 s) 5 A/15 A",
  https://www.easymanua.ls/maxon/escon-50-5/manual?p=9
- ESCON 50/5 (409510), Hardware Reference rel5536, sec. 3.2 Determination of Power Supply,
  p. 3-12, "continuous max. 5 A", "short-time (acceleration, <20 s) max. 15 A",
  https://www.manualshelf.com/manual/maxon-motor/409510/1-datasheet-english/page-12.html
The motors' torque constants are typed from the maxon catalog page (May 2012) the motor
catalog cites: 25.5 mNm/A (200142, 12 V), 51 mNm/A (339281, 24 V), 70.6 mNm/A (339282, 36 V).
Torques and currents of the sizing come from closed forms (a cycloidal move:
a_max = 2 pi h / T^2, sec. 2.2.2 of the book; torque = J a_max without friction).
"""

from __future__ import annotations

import fnmatch
import math

import numpy as np
import pytest

from sizer.io import load_catalog
from sizer.io.loader import (
    bundled_catalogs,
    bundled_drive_catalogs,
    load_design_data,
    read_drive_catalog,
    read_yaml,
)
from sizer.io.schema.inputs import DriveCatalogFile
from sizer.sizing.candidates import CurrentCurves, MotorArrays
from sizer.sizing.engine import size_design

PRINTED = {"ESCON-Module-50-5": ("438725", 5.0, 15.0), "ESCON-50-5": ("409510", 5.0, 15.0)}
"""id: (part number, Icont A, Imax A), as printed (see the module docstring)."""

K_T = {"EC45flat-30W-200142": 25.5e-3, "EC45flat-30W-339281": 51e-3,
       "EC45flat-30W-339282": 70.6e-3}
"""The Hall-sensor EC 45 flat 30 W motors and their printed torque constants, N*m/A."""

SENSORLESS = ("EC45flat-30W-200189", "EC45flat-30W-339283", "EC45flat-30W-339284")

MOTOR_INERTIA = 92.5e-7
"""EC 45 flat 30 W rotor inertia, 92.5 g*cm^2 (its catalog page)."""


def drives():
    path = bundled_drive_catalogs()["maxon-escon"]
    return {d.drive.id: d.drive for d in read_drive_catalog(path)}


def all_motors():
    return [m for name in bundled_catalogs() for m in load_catalog(name)]


def test_the_file_validates_as_a_drive_catalog():
    path = bundled_drive_catalogs()["maxon-escon"]
    catalog = DriveCatalogFile.model_validate(read_yaml(path).data)
    assert [d.id for d in catalog.drives] == list(PRINTED)
    assert catalog.manufacturer == "maxon"
    text = path.read_text(encoding="utf-8")
    assert "grade B" in text.split("catalog:")[0]  # the header records the trust grade
    for drive in drives().values():
        assert drive.source and "https://" in drive.source


def test_the_currents_are_the_printed_ones():
    got = drives()
    assert set(got) == set(PRINTED)
    for drive_id, (part, continuous, peak) in PRINTED.items():
        drive = got[drive_id]
        assert drive.part_number == part
        assert drive.continuous_current == continuous
        assert drive.peak_current == peak
        assert drive.manufacturer == "maxon"
        # nothing but the currents was printed as a drive rating the schema takes
        assert drive.dc_bus_voltage is None and drive.max_bus_voltage is None
        assert drive.bus_capacitance is None and drive.braking_resistor_power is None


def test_every_pattern_matches_a_bundled_motor():
    ids = [m.id for m in all_motors()]
    for drive in drives().values():
        assert drive.motors, drive.id
        for pattern in drive.motors:
            assert fnmatch.filter(ids, pattern), (drive.id, pattern)
        matched = {i for p in drive.motors for i in fnmatch.filter(ids, p)}
        assert matched == set(K_T)
        assert not matched & set(SENSORLESS)


def test_the_motors_torque_constants_are_the_printed_ones():
    motors = {m.id: m for m in load_catalog("maxon-ec45-flat")}
    for motor_id, k_t in K_T.items():
        assert motors[motor_id].torque_constant == pytest.approx(k_t, rel=1e-12)


def test_the_drive_torque_is_k_t_times_the_printed_current():
    motors = {m.id: m for m in load_catalog("maxon-ec45-flat")}
    chosen = [motors[i] for i in K_T]
    curves = CurrentCurves.of(chosen)
    k_t = np.array(list(K_T.values()))
    assert curves.torque(np.full(3, 15.0)) == pytest.approx(k_t * 15.0, rel=1e-12)
    assert curves.torque(np.full(3, 5.0)) == pytest.approx(k_t * 5.0, rel=1e-12)
    # 200142 with the ESCON Module 50/5: 0.0255 N*m/A x 15 A = 0.3825 N*m, above the
    # motor's stall torque of 241 mN*m; 5 A give 0.1275 N*m, above its 55.5 mN*m nominal
    # torque: the controller caps neither region, the motor's own limits stay.
    escon = drives()["ESCON-Module-50-5"]
    motor = motors["EC45flat-30W-200142"]
    paired = MotorArrays.of([motor], "linear", [escon])
    alone = MotorArrays.of([motor], "linear")
    assert len(paired) == 1
    assert paired.intermittent.torques.max() == pytest.approx(0.241, rel=1e-12)
    assert alone.intermittent.torques.max() == pytest.approx(0.241, rel=1e-12)
    assert paired.continuous.torques.max() == pytest.approx(0.0555, rel=1e-12)
    assert 0.0255 * 15.0 > 0.241 and 0.0255 * 5.0 > 0.0555


def test_a_design_pairs_each_hall_motor_with_both_controllers():
    # cycloidal move: J = 1e-4 kg*m^2 in all, a_max = 1000 rad/s^2, so 0.1 N*m at the peak
    inertia, a_max, duration = 1e-4, 1000.0, 0.2
    h = a_max * duration**2 / (2.0 * math.pi)
    design = {"name": "ec45", "task": {"displacement": f"{h!r} rad",
                                      "duration": f"{duration!r} s", "dwell": "3 s"},
              "load": {"inertia": f"{inertia - MOTOR_INERTIA!r} kg*m^2"},
              "laws": ["cycloidal"], "motors": ["maxon-ec45-flat"], "drives": ["maxon-escon"]}
    result = size_design(load_design_data(design))
    rows = {(r.motor, r.drive): r for r in result.results}
    assert set(rows) == {(m, d) for m in K_T for d in PRINTED}
    for (motor_id, _), row in rows.items():
        assert row.peak_torque == pytest.approx(inertia * a_max, rel=1e-6)
        check = row.check("drive_peak_current")
        assert check.limit == 15.0 and check.unit == "A" and check.passed
        assert check.value == pytest.approx(inertia * a_max / K_T[motor_id], rel=1e-6)
        assert row.check("drive_rms_current").limit == 5.0
