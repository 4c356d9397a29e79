"""A result row holds the motor, law and drive objects once; ids and figures are read from
them (sizer.sizing.results, issue 33)."""

from __future__ import annotations

from dataclasses import fields

from sizer.laws import make_law
from sizer.model.domain import Motor, ServoDrive, Stage, Transmission
from sizer.sizing import CandidateResult, Check
from sizer.sizing.results import OPTIONAL_FIGURES, record

MOTOR = Motor("m-400", 2e-5, 1.3, 3.9, 300.0, price=250.0, mass=1.2)
DRIVE = ServoDrive("d-2A", 2.0, 6.0)


def row(**given) -> CandidateResult:
    return CandidateResult(MOTOR, make_law("trapezoidal(alpha=1/4)"), True, 0.2, 1.0, 0.5,
                           100.0, (Check("peak", 1.0, 3.9, "N*m", 1 - 1.0 / 3.9),), "peak",
                           **given)


def test_ids_and_motor_figures_are_read_from_the_objects() -> None:
    r = row(drive_object=DRIVE)
    assert (r.motor, r.law, r.spec, r.drive) == ("m-400", "trapezoidal",
                                                 "trapezoidal(alpha=1/4)", "d-2A")
    assert dict(r.params) == {"alpha": 0.25}
    assert (r.price, r.mass, r.continuous_torque, r.rotor_inertia) == (250.0, 1.2, 1.3, 2e-5)
    assert r.rated_power == 1.3 * 300.0  # tau_c * v_n
    assert row().drive is None
    assert row().ratio == 1.0  # direct drive
    assert row(transmission=Transmission((Stage(ratio=5.0), Stage(ratio=2.0)))).ratio == 10.0


def test_no_field_repeats_an_object() -> None:
    names = {f.name for f in fields(CandidateResult)}
    assert not names & {"motor", "law", "spec", "params", "drive", "price", "mass", "ratio",
                        "rated_power", "continuous_torque", "rotor_inertia", *OPTIONAL_FIGURES}


def test_check_figures_are_read_from_one_mapping() -> None:
    r = row(figures={"winding_rise": 12.5, "stage_ratio": 3.0})
    assert r.winding_rise == 12.5
    assert all(getattr(row(), name) is None for name in OPTIONAL_FIGURES)
    assert all(getattr(row(figures={name: 2.0}), name) == 2.0 for name in OPTIONAL_FIGURES)


def test_a_record_puts_the_drive_after_the_motor_and_the_figures_before_params() -> None:
    out = record(row(drive_object=DRIVE, figures={"braking_power": 4.0, "stage_ratio": 3.0}))
    keys = list(out)
    assert keys[:3] == ["motor", "drive", "law"]
    assert keys[-4:] == ["braking_power", "params", "stage_ratio", "checks"]
    assert out["rated_power"] == 390.0 and out["price"] == 250.0
