"""maxon's EC motors with their windings (issue 35): the printed speed-torque line at the
nominal voltage against the electrical envelope's block model from the printed k_t, R and
voltage (sizer.envelope.electrical).

Every compared number is printed in the catalog (maxon's pages as saved in 2019): the
stall torque and the no-load speed are the two ends of maxon's line; the no-load current
is in each row's notes."""

from __future__ import annotations

import re

import pytest
import yaml

from sizer.catalog_tools import validate_catalogs
from sizer.envelope.electrical import Winding
from sizer.io import NOT_DEFAULT_CATALOGS, bundled_catalogs, load_catalog
from sizer.model.domain import figure_provenance

PATH = bundled_catalogs()["maxon-ec"]
MOTORS = load_catalog(PATH)
RAW = {row["id"]: row for row in yaml.safe_load(PATH.read_text(encoding="utf-8"))["motors"]}
LOSSY = {"maxon-EC-max16-5W-283828", "maxon-EC9.2flat-0.5W-624163",
         "maxon-EC14flat-1.5W-236679"}
"""The smallest motors, whose no-load current's drop in the terminal resistance moves the
no-load speed by more than 5 % (by 8.8 %, 11.3 % and 13.7 %)."""


def _no_load_current(motor_id: str) -> float:
    found = re.search(r"no-load current ([\d.]+) (mA|A)", RAW[motor_id]["notes"])
    assert found is not None, motor_id
    return float(found.group(1)) * (1e-3 if found.group(2) == "mA" else 1.0)


def test_the_catalog_is_clean_graded_priced_and_not_a_default():
    report = validate_catalogs([str(PATH)])
    assert report.findings == [] and report.motors == len(MOTORS) == 56
    for motor in MOTORS:
        grades = {p.grade for p in figure_provenance(motor).values() if p is not None}
        assert grades == {"B"}, motor.id
        assert motor.price is not None and motor.price > 0
        assert motor.commutation == "block" and motor.poles is not None
    assert "maxon-ec" in NOT_DEFAULT_CATALOGS  # peaks are stall torques: with a drive


@pytest.mark.parametrize("motor", MOTORS, ids=[m.id for m in MOTORS])
def test_the_block_model_gives_maxons_line(motor):
    """Stall torque k_t U / R within 1 % of the printed one (at most 0.62 % off); the
    no-load speed U / k_t within 5 % but for LOSSY, and within 2.5 % of the printed one
    for every motor once the no-load current's drop R I_0 is taken from U."""
    winding = Winding.of(motor)
    assert winding is not None and winding.block
    (_, stall), (no_load, _) = motor.intermittent_curve
    U, R, k_t = winding.bus_voltage, winding.resistance, winding.torque_constant
    assert k_t * U / R == pytest.approx(stall, rel=0.01)
    assert winding.no_load_speed() == pytest.approx(no_load, rel=0.15)
    if motor.id not in LOSSY:
        assert winding.no_load_speed() == pytest.approx(no_load, rel=0.05)
    assert (U - R * _no_load_current(motor.id)) / k_t == pytest.approx(no_load, rel=0.025)
