"""Motors with drives (issue 16): the drive's currents cap the motor's torques through k_t
(or the torque-current curve), the checks drive_peak_current / drive_rms_current name the
drive, and the motor x drive candidates are evaluated at once as one by one.

Numbers come from closed forms (a cycloidal move: a_max = 2 pi h / T^2, sec. 2.2.2 of the
book; the purely inertial T_min = sqrt(2 pi h J / tau)) and from the published
figures of the Siemens 1FT7044-AK7 (23 N*m at 30 A, 15 N*m with its recommended Motor
Module of 18 A).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from sizer.errors import UserError
from sizer.io.loader import load_design_data
from sizer.model.domain import Motor, ServoDrive
from sizer.sizing.candidates import MotorArrays, clip_region
from sizer.sizing.engine import size_design
from sizer.sizing.results import record

FT7_INERTIA = 5.43e-4
"""1FT7044-AK7 rotor inertia, kg*m^2 (its catalog)."""


def ft7_design(drives: list[str] | None, peak: float = 20.0) -> dict:
    """A cycloidal move whose peak torque is ``peak`` N*m at the 1FT7 (total inertia
    0.01 kg*m^2, a_max = 100 peak), with a long dwell so that the RMS torque is small."""
    a_max = peak / 0.01
    duration = 0.2
    h = a_max * duration**2 / (2.0 * math.pi)
    design = {"name": "1ft7", "task": {"displacement": f"{h!r} rad", "duration": "0.2 s",
                                       "dwell": "3 s"},
              "load": {"inertia": f"{0.01 - FT7_INERTIA!r} kg*m^2"}, "laws": ["cycloidal"],
              "motors": ["siemens-1ft7"]}
    if drives is not None:
        design["drives"] = drives
    return design


def only(result):
    assert len(result.results) == 1
    return result.results[0]


def test_the_1ft7_passes_alone_and_fails_with_its_recommended_module():
    alone = only(size_design(load_design_data(ft7_design(None))))
    paired = only(size_design(load_design_data(ft7_design(["siemens-s120"]))))
    assert alone.drive is None and paired.drive == "S120-MM-9A"
    assert alone.peak_torque == pytest.approx(20.0, rel=1e-9)
    assert alone.check("peak").value == pytest.approx(20.0 / 23.0, rel=1e-9)  # Mmax 23 N*m
    assert alone.feasible and alone.check("peak").passed
    assert not paired.feasible and not paired.check("peak").passed
    assert paired.check("peak").value == pytest.approx(20.0 / 15.0, rel=1e-9)  # 15 N*m at 18 A
    check = paired.check("drive_peak_current")
    # the current of 20 N*m on the published curve: between (18 A, 15 N*m), (30 A, 23 N*m)
    assert check.value == pytest.approx(18.0 + (20.0 - 15.0) * 12.0 / 8.0, rel=1e-12)
    assert check.limit == 18.0 and check.unit == "A" and not check.passed
    assert paired.limiting == "drive_peak_current"
    assert "drive_peak_current" in paired.reason


def test_the_1ft7_module_caps_the_peak_at_15_nm():
    design = load_design_data(ft7_design(["siemens-s120"]))
    arrays = MotorArrays.of(design.motors, design.limits.envelope, design.drives)
    assert arrays.intermittent.torques.max() == pytest.approx(15.0, rel=1e-12)
    alone = MotorArrays.of(design.motors, design.limits.envelope)
    assert alone.intermittent.torques.max() == 23.0
    below = only(size_design(load_design_data(ft7_design(["siemens-s120"], peak=14.0))))
    assert below.feasible and below.check("drive_peak_current").passed


BOOK_MOTOR = {"id": "M", "inertia": 0, "continuous_torque": "8 N*m", "peak_torque": "20 N*m",
              "rated_speed": "10 rad/s", "torque_constant": "2 N*m/Arms"}
"""The book's motor of Examples 6.1-6.2 with a torque constant of 2 N*m/A."""


def book_design(tmp_path, drives: list[dict], motors: list[dict] | None = None,
                **task) -> dict:
    """Examples 6.1-6.2 (h = 15 rad in T = 3 s, J = 1, B = 0.3) with the given drives."""
    catalog = {"catalog": "drives", "source": "test", "drives": drives}
    import yaml

    (tmp_path / "drives.yaml").write_text(yaml.safe_dump(catalog), encoding="utf-8")
    return {"task": {"displacement": "15 rad", "duration": "3 s", **task},
            "load": {"inertia": "1 kg*m^2", "damping": "0.3 N*m*s/rad"},
            "laws": ["cycloidal"], "motors": motors or [BOOK_MOTOR], "drives": ["drives.yaml"]}


def test_a_motor_that_passes_alone_fails_with_a_weak_drive(tmp_path):
    weak = {"id": "weak", "continuous_current": "4 A", "peak_current": "4 A", "motors": ["M"]}
    design = book_design(tmp_path, [weak])
    alone = only(size_design(load_design_data({**design, "drives": None}, base=tmp_path)))
    paired = only(size_design(load_design_data(design, base=tmp_path)))
    assert alone.feasible and paired.drive == "weak" and not paired.feasible
    assert paired.limiting == "drive_peak_current"
    check = paired.check("drive_peak_current")
    assert check.value == pytest.approx(alone.peak_torque / 2.0, rel=1e-12)  # tau / k_t
    assert check.limit == 4.0
    rms = paired.check("drive_rms_current")
    assert rms.value == pytest.approx(alone.rms_torque / 2.0, rel=1e-12) and rms.limit == 4.0
    assert paired.check("peak").value == pytest.approx(alone.peak_torque / 8.0, rel=1e-9)


def test_a_strong_drive_changes_nothing_but_adds_its_checks(tmp_path):
    strong = {"id": "strong", "continuous_current": "5 A", "peak_current": "12 A"}  # by rule
    design = book_design(tmp_path, [strong])
    alone = only(size_design(load_design_data({**design, "drives": None}, base=tmp_path)))
    paired = only(size_design(load_design_data(design, base=tmp_path)))
    assert paired.drive == "strong" and paired.feasible == alone.feasible
    for check in alone.checks:
        assert paired.check(check.name).value == check.value
        assert paired.check(check.name).limit == check.limit
    assert record(paired)["drive"] == "strong" and "drive" not in record(alone)


def test_the_drive_current_margin_applies_to_the_drive_checks(tmp_path):
    strong = {"id": "strong", "continuous_current": "5 A", "peak_current": "12 A"}
    design = book_design(tmp_path, [strong])
    result = only(size_design(load_design_data(
        {**design, "limits": {"drive_current_margin": 0.5}}, base=tmp_path)))
    check = result.check("drive_peak_current")
    assert check.required == 0.5
    assert check.passed == (1.0 - check.value / 12.0 >= 0.5)


def test_minimize_with_a_drive_is_the_closed_form_at_the_drive_torque(tmp_path):
    # purely inertial, rectangles: T_min = sqrt(2 pi h J / tau) with tau = k_t I_peak
    motor = {"id": "M", "inertia": 0, "continuous_torque": "8 N*m", "peak_torque": "20 N*m",
             "rated_speed": "100 rad/s", "torque_constant": "2 N*m/A"}
    drive = {"id": "d", "continuous_current": "4.5 A", "peak_current": "4.5 A"}
    design = book_design(tmp_path, [drive], [motor], duration="minimize")
    design["task"]["displacement"] = "1 rad"
    design["load"] = {"inertia": "1 kg*m^2"}
    design["limits"] = {"envelope": "book"}
    result = only(size_design(load_design_data(design, base=tmp_path)))
    alone = only(size_design(load_design_data({**design, "drives": None}, base=tmp_path)))
    assert result.duration == pytest.approx(math.sqrt(2.0 * math.pi / 9.0), rel=1e-7)
    # alone, the RMS binds first: tau_rms = J a_max / sqrt(2) = 8 N*m (no dwell)
    assert alone.duration == pytest.approx(math.sqrt(2.0 * math.pi / (8.0 * math.sqrt(2.0))),
                                           rel=1e-7)
    assert alone.limiting == "rms" and result.limiting == "drive_peak_current"


def _motor(id: str, tau_c: float, tau_p: float, kt: float | None, curve=None) -> Motor:
    return Motor(id=id, inertia=1e-4, continuous_torque=tau_c, peak_torque=tau_p,
                 rated_speed=300.0, max_speed=600.0, torque_constant=kt,
                 intermittent_curve=curve)


MOTORS = (_motor("A", 1.0, 3.0, 0.5), _motor("B", 2.0, 6.0, 0.8),
          _motor("C", 0.5, 1.5, None),
          _motor("D", 1.0, 4.0, 0.4, ((0.0, 4.0), (300.0, 4.0), (600.0, 1.0))))
DRIVES = (ServoDrive("small", 2.0, 4.0), ServoDrive("large", 4.0, 12.0),
          ServoDrive("listed", 1.0, 2.0, motors=("C", "D")))


def test_pairs_by_list_and_by_rule():
    arrays = MotorArrays.of(MOTORS, "linear", ())
    with pytest.raises(UserError, match="torque_constant"):
        replace(arrays).with_drives(DRIVES)  # C is listed but has no k_t
    motors = MOTORS[:2] + MOTORS[3:]
    paired = MotorArrays.of(motors, "linear", DRIVES)
    got = [(paired.catalog[m].id, DRIVES[d].id) for m, d in
           zip(paired.index, paired.drive, strict=True)]
    # by rule: the continuous current covers tau_c / k_t (A: 2 A, B: 2.5 A, D: 2.5 A)
    assert got == [("A", "small"), ("A", "large"), ("B", "large"), ("D", "large"),
                   ("D", "listed")]


def test_vectorized_pairing_equals_one_pair_at_a_time(tmp_path):
    motors = [{"id": "A", "inertia": "1e-4 kg*m^2", "continuous_torque": "1 N*m",
               "peak_torque": "3 N*m", "rated_speed": "3000 rpm", "max_speed": "6000 rpm",
               "torque_constant": "0.5 N*m/A", "source": "test"},
              {"id": "B", "inertia": "3e-4 kg*m^2", "continuous_torque": "2 N*m",
               "peak_torque": "6 N*m", "rated_speed": "3000 rpm", "max_speed": "6000 rpm",
               "torque_constant": "0.8 N*m/A", "source": "test",
               "torque_current_curve": [["0 A", "0 N*m"], ["2.5 A", "2 N*m"],
                                        ["9 A", "6 N*m"]]}]
    drives = [{"id": "small", "continuous_current": "2 A", "peak_current": "4 A"},
              {"id": "large", "continuous_current": "4 A", "peak_current": "12 A"},
              {"id": "listed", "continuous_current": "1 A", "peak_current": "2 A",
               "motors": ["B"]}]
    design = book_design(tmp_path, drives, motors)
    design["task"] = {"displacement": "20 rad", "duration": "0.3 s", "dwell": "0.2 s"}
    design["load"] = {"inertia": "2e-3 kg*m^2"}
    together = size_design(load_design_data(design, base=tmp_path))
    rows = {(r.motor, r.drive): r for r in together.results}
    assert set(rows) == {("A", "small"), ("A", "large"), ("B", "large"), ("B", "listed")}
    for (motor, drive), row in rows.items():
        one = book_design(tmp_path / "..", [d for d in drives if d["id"] == drive],
                          [m for m in motors if m["id"] == motor])
        single = only(size_design(load_design_data({**one, "task": design["task"],
                                                    "load": design["load"]},
                                                   base=tmp_path / "..")))
        assert single.drive == drive and single.feasible == row.feasible
        assert single.limiting == row.limiting
        for check in row.checks:
            assert single.check(check.name).value == pytest.approx(check.value, rel=1e-12)
            assert single.check(check.name).limit == pytest.approx(check.limit, rel=1e-12)


def test_clipped_regions_are_the_minimum_of_region_and_cap():
    arrays = MotorArrays.of(MOTORS[:2] + MOTORS[3:], "linear")
    caps = np.array([2.0, 7.0, 2.5])
    clipped = clip_region(arrays.intermittent, caps)
    speeds = np.linspace(0.0, 600.0, 4001)
    grid = np.broadcast_to(speeds, (3, speeds.size))
    expected = np.minimum(arrays.intermittent.limit(grid), caps[:, None])
    assert np.allclose(clipped.limit(grid), expected, rtol=1e-12, atol=1e-12)


def test_drives_with_a_listed_ratio_pair_with_every_option(tmp_path):
    # a free ratio (3 or 5) and two drives: each (motor, drive) gets its best ratio; the
    # drive's checks read the torque at the motor through k_t = 2 N*m/A
    drives = [{"id": "weak", "continuous_current": "0.5 A", "peak_current": "0.6 A",
               "motors": ["M"]},
              {"id": "strong", "continuous_current": "4 A", "peak_current": "10 A",
               "motors": ["M"]}]
    design = book_design(tmp_path, drives)
    design["transmission"] = {"type": "gearbox", "ratio": [3, 5]}
    design["task"] = {"displacement": "3 rad", "duration": "3 s"}
    design["load"] = {"inertia": "4 kg*m^2", "damping": "0.3 N*m*s/rad"}
    result = size_design(load_design_data(design, base=tmp_path))
    rows = {r.drive: r for r in result.results}
    assert set(rows) == {"weak", "strong"}
    for row in rows.values():
        assert row.ratio in (3.0, 5.0)
        assert row.check("drive_peak_current").value == pytest.approx(row.peak_torque / 2.0,
                                                                      rel=1e-12)
        assert row.check("drive_rms_current").value == pytest.approx(row.rms_torque / 2.0,
                                                                     rel=1e-12)
    assert rows["strong"].feasible and not rows["weak"].feasible
    assert rows["weak"].limiting == "drive_peak_current"
