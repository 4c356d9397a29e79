"""``sizer catalog validate``'s consistency checks (issue 35): each fires on a crafted motor
and stays quiet on a consistent one (figures from closed forms); the grade mix."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import pytest
import yaml

from sizer.catalog_tools import validate_catalogs
from sizer.catalog_tools.consistency import (
    NOT_CHECKED,
    TEMPERATURE_TOLERANCE,
    TOLERANCE,
    inconsistencies,
)
from sizer.catalog_tools.grade_mix import grade_mix
from sizer.model.domain import Motor

RPM = math.pi / 30
K_T = 0.5
CONSISTENT = Motor(
    id="OK", inertia=1e-4, continuous_torque=K_T * 2.0, peak_torque=K_T * 6.0,
    rated_speed=3000 * RPM, max_speed=5000 * RPM, torque_constant=K_T,
    back_emf_constant=K_T / math.sqrt(3.0), continuous_current=2.0, peak_current=6.0,
    continuous_curve=((0.0, 1.0), (3000 * RPM, 1.0), (5000 * RPM, 0.6)))
"""k_e = k_t / sqrt(3), torques = k_t x currents, the curve flat up to the rated speed."""


def fields_of(motor: Motor) -> list[str]:
    return [path[0] for path, _ in inconsistencies(motor)]


def test_a_consistent_motor_has_no_finding() -> None:
    assert inconsistencies(CONSISTENT) == []
    block = replace(CONSISTENT, commutation="block", back_emf_constant=K_T)
    assert inconsistencies(block) == []


@pytest.mark.parametrize(("changes", "field", "words"), [
    ({"back_emf_constant": K_T / math.sqrt(3.0) * math.sqrt(2.0)}, "back_emf_constant",
     "sqrt(3) k_e"),  # a peak k_e read as an RMS one
    ({"commutation": "block"}, "back_emf_constant", "k_t = k_e"),
    ({"continuous_current": 2.0 * (1 + 2 * TEMPERATURE_TOLERANCE)}, "continuous_current",
     "torque_constant x continuous_current"),
    ({"peak_torque": K_T * 6.0 * (1 + 2 * TOLERANCE)}, "peak_torque", "saturation"),
    ({"continuous_curve": ((0.0, 1.0), (2000 * RPM, 1.0))}, "continuous_curve",
     "does not reach the rated speed"),
    ({"continuous_curve": ((0.0, 1.2), (3000 * RPM, 0.8))}, "continuous_curve",
     "at the rated speed 3000 rpm"),
    ({"intermittent_curve": ((0.0, 3.0), (3000 * RPM, 3.0), (5000 * RPM, 0.3))},
     "continuous_curve", "linear envelope rule"),
])
def test_each_check_fires_on_a_crafted_motor(changes: dict, field: str, words: str) -> None:
    found = inconsistencies(replace(CONSISTENT, **changes))
    assert [path[0] for path, _ in found] == [field], found
    assert words in found[0][1]


def test_the_checks_allow_their_tolerance() -> None:
    within = replace(CONSISTENT, back_emf_constant=K_T / math.sqrt(3.0) * (1 + TOLERANCE / 2),
                     continuous_current=2.0 * (1 + TEMPERATURE_TOLERANCE / 2),
                     peak_current=6.0 * 0.5)  # a saturating peak: k_t I_p above tau_p is fine
    assert fields_of(within) == ["peak_torque"]  # tau_p = 2 k_t I_p: too high
    saturating = replace(CONSISTENT, peak_current=6.0 * 1.5)
    assert inconsistencies(saturating) == []


def test_a_standstill_continuous_torque_is_not_a_rated_point() -> None:
    """Siemens and Mitsubishi print M_0 at standstill; the curve falls to the rated torque."""
    stall = replace(CONSISTENT, continuous_curve=((0.0, 1.0), (3000 * RPM, 0.7)))
    assert inconsistencies(stall) == []


def test_rated_power_is_said_not_checked() -> None:
    assert any("rated power" in text for text in NOT_CHECKED)


CATALOG = {
    "manufacturer": "ACME",
    "sources": {"ds": {"grade": "A", "text": "ACME catalog, p. 3, https://acme.example"},
                "calc": {"grade": "C", "text": "computed"}},
    "default_source": "ds",
    "motors": [
        {"id": "M1", "inertia": "1 kg*cm^2", "continuous_torque": "1 N*m",
         "peak_torque": "3 N*m", "rated_speed": "3000 rpm", "torque_constant": "0.5 N*m/A",
         "back_emf_constant": "0.35 V*s/rad", "figure_sources": {"back_emf_constant": "calc"},
         "notes": "not a figure"},
    ],
}


def test_validate_reports_findings_and_the_grade_mix(tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "m.yaml").write_text(yaml.safe_dump(CATALOG), encoding="utf-8")
    report = validate_catalogs(["m.yaml"])
    assert [(f.field, f.severity) for f in report.findings] == [
        ("motors[0].back_emf_constant", "warning")]  # 0.5 / 0.35 = 1.43, not sqrt(3)
    assert report.grades["m.yaml"].counts == {"A": 5, "B": 0, "C": 1, "D": 0, "ungraded": 0}
    assert report.total_grades.total == 6


def test_the_grade_mix_of_an_ungraded_file_and_of_gearboxes() -> None:
    plain = {"source": "x", "motors": [{"id": "A", "inertia": 1, "peak_torque": 2}]}
    assert grade_mix(plain).counts["ungraded"] == 2
    gearboxes = {"sources": {"g": {"grade": "B", "text": "t"}},
                 "gearboxes": [{"id": "G", "efficiency": 0.9, "figure_sources": {
                     "efficiency": "g"}, "ratios": [{"ratio": 3, "inertia": 1e-5}]}]}
    assert grade_mix(gearboxes).counts == {"A": 0, "B": 1, "C": 0, "D": 0, "ungraded": 2}


def test_the_cli_prints_the_grade_mix(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from sizer.cli.catalog_command import catalog_app

    path = tmp_path / "m.yaml"
    path.write_text(yaml.safe_dump(CATALOG), encoding="utf-8")
    result = CliRunner().invoke(catalog_app, ["validate", str(path)])
    assert result.exit_code == 1
    assert "A 5, B 0, C 1, D 0, ungraded 0 (6 figures)" in result.output
    assert "not checked: rated power" in result.output
