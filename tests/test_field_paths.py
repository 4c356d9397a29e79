"""A field's text and its path in the YAML (sizer.bounded_yaml.format_path and its inverse
parse_path), and a sizing's refusal placed at its field's line (sizer.io.loader.
at_its_line)."""

from __future__ import annotations

from pathlib import Path

import pytest

from sizer.bounded_yaml import format_path, parse_path
from sizer.errors import UserError
from sizer.io.loader import at_its_line


@pytest.mark.parametrize("path", [("laws",), ("motors", 3, "inertia"),
                                  ("transmission", 0, "start_angle"), ("task", "duration"),
                                  ("axes", 1, "laws", 0), ("a", 12, 0)])
def test_a_path_reads_back_from_its_text(path: tuple) -> None:
    assert parse_path(format_path(path)) == path


@pytest.mark.parametrize("text", ["--law", "", "motors[x]", "motors[3", "12 kg", "a..b",
                                  "motors[-1]", "laws[0]x"])
def test_other_texts_are_no_path(text: str) -> None:
    assert parse_path(text) is None


def test_a_refusal_is_placed_at_its_fields_line(tmp_path: Path) -> None:
    design = tmp_path / "d.yaml"
    design.write_text("task: {displacement: 1 rad, duration: 1 s}\n"
                      "load: {inertia: 0.1 kg*m^2}\n"
                      "transmission:\n  - {type: gearbox, ratio: 3}\n"
                      "laws: [cycloidal]\n", encoding="utf-8")
    placed = at_its_line(UserError("no", field="laws"), design)
    assert (placed.file, placed.line, placed.field) == (str(design), 5, "laws")
    assert at_its_line(UserError("no", field="transmission[0].ratio"), design).line == 4
    # a key the file lacks: its nearest ancestor, the document (line 1)
    assert at_its_line(UserError("no", field="motors"), design).line == 1
    assert at_its_line(UserError("no", field="--law"), design).line is None
    kept = at_its_line(UserError("no", file="c.yaml", line=9, field="laws"), design)
    assert (kept.file, kept.line) == ("c.yaml", 9)
