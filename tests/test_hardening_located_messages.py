"""Issue 32: messages located at the field at fault (file, line and field), or at the
command-line option, for the faults helper-E found: an empty ``motors:`` list, pydantic's
``too_long``, a linkage's ``start_angle``, a bundled drive catalog naming motors that are
not loaded, and an auto law given with ``sizer plot --law`` on a cycle design."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from bad_input_cases import Case, edited, run_case
from bad_input_lines import at, line_of
from cli_run import assert_user_error, run_cli
from pydantic import Field
from test_bad_inputs_catalogs import DRIVE, MOTOR_KT

from sizer.errors import UserError
from sizer.io.schema.inputs_base import Strict
from sizer.io.validation import validate
from sizer.io.yaml_source import parse_yaml

MOTORS = yaml.safe_dump({"motors": [MOTOR_KT]}, sort_keys=False)
DRIVES = yaml.safe_dump({"catalog": "Acme drives", "drives": [DRIVE]}, sort_keys=False)
PRESS = "press-slider-crank.yaml"


def test_an_empty_motors_list_is_refused_at_its_line(tmp_path: Path) -> None:
    text = edited("book/ex6_1-6_2.yaml", set={"motors": []}, delete=("check",))
    run_case(Case("motors-empty", design=text,
                  words=(*at(text, "motors"), "no motors to size")), tmp_path)


def test_an_empty_motors_list_with_a_catalog_option_is_sized(tmp_path: Path) -> None:
    text = edited("book/ex6_1-6_2.yaml", set={"motors": []}, delete=("check",))
    result = run_case(Case("motors-empty-and-catalog",
                           args=("size", "{design}", "-c", "{catalog}", "--all"),
                           design=text, catalog=MOTORS, exit_code=0), tmp_path)
    assert "M1" in result.stdout  # sized (no pair feasible is a result), not refused


class _Few(Strict):
    items: list[int] = Field(max_length=2)


def test_too_many_items_read_as_at_most_n() -> None:
    text = "items:\n  - 1\n  - 2\n  - 3\n"
    with pytest.raises(UserError) as caught:
        validate(_Few, parse_yaml(text, "few.yaml"))
    assert str(caught.value) == "few.yaml:1: items: at most 2 items, got 3"


def test_a_start_angle_off_the_stroke_is_named(tmp_path: Path) -> None:
    """The crank at 90 deg puts the slider mid-stroke: 100 mm of the 100 mm stroke
    (2 x 50 mm crank) cannot start there; start_angle is at fault, not the displacement."""
    text = edited(PRESS, set={"transmission[1].start_angle": "90 deg"})
    run_case(Case("start-angle", design=text,
                  words=(*at(text, "transmission[1].start_angle"), "task.displacement",
                         "start_angle 90 deg", "change start_angle")), tmp_path)


def test_a_displacement_longer_than_the_stroke_is_blamed_on_itself(tmp_path: Path) -> None:
    """150 mm > the 100 mm stroke: no start angle helps."""
    text = edited(PRESS, set={"transmission[1].start_angle": "90 deg",
                              "task.displacement": "150 mm"})
    result = run_case(Case("displacement", design=text,
                           words=(*at(text, "task.displacement"),)), tmp_path)
    assert "start_angle" not in result.stderr


def test_a_bundled_drive_catalog_naming_other_motors_is_not_paired(tmp_path: Path) -> None:
    """siemens-s120 names 1FT7 motors, none loaded: its drive is not paired, no error; the
    design's own drive D1 pairs with M1."""
    text = edited("book/ex6_1-6_2.yaml", set={"motors": "motors.yaml",
                                              "drives": ["drives.yaml", "siemens-s120"]},
                  delete=("check",))
    (tmp_path / "design.yaml").write_text(text, encoding="utf-8")
    (tmp_path / "motors.yaml").write_text(MOTORS, encoding="utf-8")
    (tmp_path / "drives.yaml").write_text(DRIVES, encoding="utf-8")
    result = run_cli("size", str(tmp_path / "design.yaml"), "--all")
    assert result.returncode in (0, 1), result.stderr
    assert "D1" in result.stdout and "S120" not in result.stdout


def test_a_users_drive_naming_an_unloaded_motor_is_still_refused(tmp_path: Path) -> None:
    drives = yaml.safe_dump({"drives": [{**DRIVE, "motors": ["M9"]}]}, sort_keys=False)
    text = edited("book/ex6_1-6_2.yaml", set={"motors": "motors.yaml",
                                              "drives": ["drives.yaml"]}, delete=("check",))
    run_case(Case("drive-unloaded-motor", design=text,
                  extra_files={"motors.yaml": MOTORS, "drives.yaml": drives},
                  words=(f"drives.yaml:{line_of(drives, 'drives[0].motors[0]')}:",
                         "no loaded motor is 'M9'")), tmp_path)


def test_plot_blames_the_law_option_not_the_designs_laws(tmp_path: Path) -> None:
    """An auto shape is refused for a cycle design: the law came from --law."""
    design = Path(__file__).parents[1] / "examples" / "indexing-duty-cycle.yaml"
    result = run_cli("plot", str(design), "-o", str(tmp_path / "p.png"),
                     "--law", "trapezoidal(alpha=auto)")
    line = assert_user_error(result, "error: --law:", "auto")
    assert " laws:" not in line
    assert not (tmp_path / "p.png").exists()
