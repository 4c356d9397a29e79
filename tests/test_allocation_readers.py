"""What reads a cycle's split reads each motor's own (``share: {optimize: ...}``, issue
39): the residual vibration check at that motor's durations, and `sizer plan` refuses a
split that needs a motor.

The reference: each motor's split written as a design of fixed durations (no share rule)
and sized alone; its residual vibration must equal the optimized design's for that motor.
"""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
from test_allocation import BIG, LOSSY, MOTOR, _design, _durations

from sizer import api
from sizer.errors import UserError


def _residual(design: dict, motor: str) -> float:
    result = api.size(copy.deepcopy(design))
    return next(r.residual_vibration for r in result.results
                if r.motor == motor and r.spec == "cycloidal")

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
MODE = {"natural_frequency": "9 Hz", "damping_ratio": 0.03}


def test_the_residual_vibration_is_each_motors_own_split() -> None:
    optimal = _design({"optimize": "rms"}, {**LOSSY, **MODE}, [MOTOR, BIG], efficiency=0.85)
    splits = _durations(optimal)
    assert not np.allclose(splits[0], splits[1], rtol=1e-6)  # each motor its own split
    residuals = []
    for row, motor in enumerate(("m1", "m2")):
        own = _design(None, {**LOSSY, **MODE}, [MOTOR, BIG], durations=splits[row],
                      efficiency=0.85)
        expected = _residual(own, motor)
        got = _residual(optimal, motor)
        assert got == pytest.approx(expected, rel=1e-9)
        residuals.append(got)
    assert residuals[0] != pytest.approx(residuals[1], rel=1e-6)  # the splits matter


def test_a_plan_refuses_a_split_chosen_per_motor() -> None:
    design = _design({"optimize": "rms"}, {"inertia": "0.02 kg*m^2"}, [],
                     extra={"limits": {"max_speed": "2 rad/s", "max_acceleration":
                                       "20 rad/s^2"}})
    with pytest.raises(UserError, match="share rule") as caught:
        api.plan(copy.deepcopy(design))
    assert caught.value.field == "cycle.share"


@pytest.mark.parametrize("row, motor", [(0, "m1"), (1, "m2")])
def test_the_cam_export_of_a_cycle_writes_the_motors_own_split(tmp_path, row, motor) -> None:
    """`sizer cam` of the whole cycle: each move's span in the certificate is the pair's
    own duration (the engine's split for that motor), the dwells as written."""
    import json

    import yaml
    from cli_run import run_cli

    design = _design({"optimize": "rms"}, LOSSY, [MOTOR, BIG], efficiency=0.85)
    path = tmp_path / "d.yaml"
    path.write_text(yaml.safe_dump(design))
    certificate = tmp_path / "c.json"
    done = run_cli("cam", str(path), "--to", "csv", "--motor", motor, "--law", "cycloidal",
                   "-o", str(tmp_path / "o.csv"), "--certificate", str(certificate))
    assert done.returncode == 0, done.stderr
    spans = [s["span"] for s in json.loads(certificate.read_text())["segments"]]
    expected = _durations(design)[row]
    np.testing.assert_allclose([spans[0], spans[2], spans[3]], expected, rtol=1e-12)
    assert spans[1] == pytest.approx(0.2) and spans[4] == pytest.approx(0.1)


def test_a_linkage_cycle_refuses_a_split_chosen_per_motor(tmp_path) -> None:
    """The linkage cycle engine reads one rule's weights: the rule is refused, exit 2."""
    import yaml
    from cli_run import assert_user_error, run_cli

    design = yaml.safe_load((EXAMPLES / "press-slider-crank-cycle.yaml").read_text())
    design["cycle"]["segments"][3]["dwell"]["duration"] = "0.2 s"
    design["cycle"]["segments"][0]["move"].pop("duration")
    design["cycle"].update({"share": {"optimize": "rms"}, "cycle_time": "1.2 s"})
    design["motors"] = [MOTOR]
    path = tmp_path / "press.yaml"
    path.write_text(yaml.safe_dump(design))
    assert_user_error(run_cli("size", str(path)), "cycle.share", "one rule")
