"""The envelope rule from the design file and the command line, stated in the outputs."""

from __future__ import annotations

import json
import math

from cli_run import assert_user_error, run_cli

from sizer.io import load_design

# A Yaskawa axis run above the rated speed of its motors: a direct-drive trapezoid 1/3
# whose top speed is 4000 rpm (h = 4000 rpm x 0.1 s / 1.5), 0.1 s move and 0.3 s dwell.
AXIS = f"""\
name: fast axis, 4000 rpm
task: {{displacement: {4000 * 2 * math.pi / 60 * 0.1 / 1.5!r} rad, duration: 0.1 s, dwell: 0.3 s}}
load: {{inertia: 1.0e-4 kg*m^2}}
laws: [trapezoidal(alpha=1/3)]
motors: [yaskawa-sgm7j, yaskawa-sgm7a, yaskawa-sgm7g, yaskawa-sgmah, yaskawa-sgmsh]
check: {{motor: SGM7J-04A, law: trapezoidal(alpha=1/3)}}
"""


def _write(tmp_path, extra=""):
    path = tmp_path / "axis.yaml"
    path.write_text(AXIS + extra)
    return path


def _feasible(stdout):
    data = json.loads(stdout)
    rule = data["design"]["limits"]["envelope"]
    notes = data["design"]["notes"]
    assert [n for n in notes if n.startswith(f"envelope {rule}:")], (rule, notes)
    return {r["motor"] for r in data["results"] if r["feasible"]}, notes


def test_the_design_file_chooses_the_rule(tmp_path):
    assert load_design(_write(tmp_path)).limits.envelope == "electrical"
    for rule in ("book", "linear", "linear_intermittent", "electrical"):
        design = load_design(_write(tmp_path, f"limits: {{envelope: {rule}}}\n"))
        assert design.limits.envelope == rule


def test_an_unknown_rule_is_a_user_error_at_its_line(tmp_path):
    path = _write(tmp_path, "limits:\n  torque_margin: 10 %\n  envelope: flat\n")
    result = run_cli("size", str(path))
    line = assert_user_error(result, "axis.yaml:9", "limits.envelope", "'book'", "'flat'")
    assert "linear_intermittent" in line


def test_31_yaskawa_motors_none_feasible_with_book_some_with_linear(tmp_path):
    path = _write(tmp_path)
    assert len(load_design(path).motors) == 31
    linear, notes = _feasible(run_cli("size", str(path), "--format", "json").stdout)
    assert "SGM7J-04A" in linear
    # the default, electrical: these motors give no winding data, so as linear
    assert any(n.startswith("envelope electrical:") for n in notes)
    # the SGM7G's maximum speed is 3000 rpm: no rule lets it run at 4000 rpm
    assert not any(m.startswith("SGM7G") for m in linear)
    book, notes = _feasible(run_cli("size", str(path), "--format", "json",
                                    "--envelope", "book").stdout)
    assert book == set()
    assert any(n.startswith("envelope book:") and "rectangular" in n for n in notes)
    # the design file's choice, overridden by the option
    book_file = _write(tmp_path, "limits: {envelope: book}\n")
    assert _feasible(run_cli("size", str(book_file), "--format", "json").stdout)[0] == set()
    assert _feasible(run_cli("size", str(book_file), "--format", "json",
                             "--envelope", "linear").stdout)[0] == linear


def test_check_states_the_rule_and_follows_the_option(tmp_path):
    path = _write(tmp_path)
    passed = run_cli("check", str(path))
    assert passed.returncode == 0, passed.stdout
    assert "note: envelope electrical:" in passed.stdout
    failed = run_cli("check", str(path), "--envelope", "book")
    assert failed.returncode == 1
    assert "note: envelope book:" in failed.stdout
    assert "speed: 418.879 rad/s against 314.159 rad/s" in failed.stdout


def test_table_and_markdown_carry_the_note(tmp_path):
    path = _write(tmp_path)
    for fmt in ("table", "md"):
        out = run_cli("size", str(path), "--format", fmt, "--envelope",
                      "linear_intermittent").stdout
        assert "envelope linear_intermittent:" in out, fmt


def test_the_schema_knows_the_rules(tmp_path):
    import jsonschema
    import yaml

    from sizer.io import design_schema

    schema = design_schema()
    ok = yaml.safe_load(_write(tmp_path, "limits: {envelope: linear_intermittent}\n").read_text())
    jsonschema.validate(ok, schema)
    bad = yaml.safe_load(_write(tmp_path, "limits: {envelope: flat}\n").read_text())
    try:
        jsonschema.validate(bad, schema)
    except jsonschema.ValidationError as error:
        assert "flat" in error.message
    else:
        raise AssertionError("the schema accepted envelope: flat")
