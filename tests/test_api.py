"""The Python interface (sizer.size / sizer.check / sizer.load): a path, a mapping and a
Design give the same results; results are plain data and hold the objects sized."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
import yaml
from cli_run import run_cli

import sizer
from sizer.errors import UserError
from sizer.model.domain import Design
from sizer.sizing import SizingResult

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "book" / "ex6_3.yaml"


def test_a_path_a_mapping_and_a_design_size_alike():
    from_path = sizer.size(EXAMPLE)
    data = yaml.safe_load(EXAMPLE.read_text())
    design = sizer.load(data, base=EXAMPLE.parent)
    assert isinstance(design, Design)
    from_mapping = sizer.size(design)
    assert isinstance(from_path, SizingResult)
    assert from_path.to_records() == from_mapping.to_records()
    assert sizer.size(sizer.load(EXAMPLE)).to_dict() == from_path.to_dict()


def test_records_are_json_ready_and_ranked_feasible_first():
    result = sizer.size(EXAMPLE)
    records = result.to_records()
    text = json.dumps(result.to_dict(), allow_nan=False)  # no NaN or inf anywhere
    assert json.loads(text)["candidates"] == records
    verdicts = [r["feasible"] for r in records]
    assert verdicts == sorted(verdicts, reverse=True)
    assert len(records) == len(result.results) == len(result.table)


def test_rows_hold_the_motor_and_law_objects_sized():
    result = sizer.size(EXAMPLE)
    row = result.results[0]
    assert row.motor_object is not None and row.motor_object.id == row.motor
    assert row.law_object is not None and row.law_object.spec == row.spec
    assert row.motor_object in sizer.load(EXAMPLE).motors


def test_a_bad_mapping_is_a_located_user_error():
    data = yaml.safe_load(EXAMPLE.read_text())
    data["task"]["duration"] = "-1 s"
    with pytest.raises(UserError) as error:
        sizer.load(data, base=EXAMPLE.parent)
    assert "task.duration" in str(error.value) and "<design>" in str(error.value)


def test_check_gives_the_named_pair():
    data = yaml.safe_load(EXAMPLE.read_text())
    first = sizer.size(EXAMPLE).results[0]
    data["check"] = {"motor": first.motor, "law": first.spec}
    checked = sizer.check(sizer.load(data, base=EXAMPLE.parent))
    assert checked.motor == first.motor and checked.feasible == first.feasible
    assert checked.duration == pytest.approx(first.duration, rel=1e-12)


# ------------------------------------------------- the CLI is built on the API (issue 11)
BOOK = ROOT / "examples" / "book" / "ex6_1-6_2.yaml"  # 3 motors x 2 laws, a check pair


def _cli_json(*args: str) -> dict:
    run = run_cli(*args, "--format", "json")
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


def _same_records(cli: list[dict], api: list[dict]) -> None:
    """Every field of every API record, as the CLI's JSON gives it, in the same order."""
    assert len(cli) == len(api) > 1
    for shown, record in zip(cli, api, strict=True):
        checks = record.pop("checks")
        assert {key: shown[key] for key in record} == record
        assert [{key: c[key] for key in check} for c, check in
                zip(shown["checks"], checks, strict=True)] == checks


def test_the_cli_size_result_is_the_api_result():
    cli = _cli_json("size", str(BOOK), "--all")
    result = sizer.size(BOOK)
    _same_records(cli["results"], result.to_records())
    assert cli["design"]["notes"] == list(result.notes)


def test_the_cli_options_are_the_api_parameters():
    cli = _cli_json("size", str(BOOK), "--all", "--motor", "ex6_3", "--motor", "ex6_1",
                    "--envelope", "book", "--rank-by", "margin")
    result = sizer.size(BOOK, motors=["ex6_1", "ex6_3"], envelope="book", rank_by="margin")
    assert {r.motor for r in result.results} == {"ex6_1", "ex6_3"}
    _same_records(cli["results"], result.to_records())
    assert cli["design"]["notes"] == list(result.notes)
    assert "rectangular regions up to the rated speed (sec. 6.1.1)" in result.notes[0]


def test_the_cli_check_result_is_the_api_result():
    cli = _cli_json("check", str(BOOK), "--envelope", "book")
    checked = sizer.check(BOOK, envelope="book")
    assert cli["passed"] is checked.feasible
    shown = cli["result"]
    assert (shown["motor"], shown["spec"], shown["duration"]) == (
        checked.motor, checked.spec, checked.duration)
    assert [c["name"] for c in shown["checks"]] == [c.name for c in checked.checks]
    assert [c["margin"] for c in shown["checks"]] == [c.margin for c in checked.checks]


def test_size_takes_a_path_a_dict_and_a_design_alike():
    from_path = sizer.size(BOOK).to_records()
    data = yaml.safe_load(BOOK.read_text())
    assert sizer.size(data).to_records() == from_path  # catalogs by bundled name
    assert sizer.size(str(BOOK)).to_records() == from_path
    design = sizer.load(BOOK)
    assert sizer.size(design).to_records() == from_path
    assert sizer.size(sizer.load(data)).to_dict() == sizer.size(design).to_dict()


def test_motors_as_objects_or_ids_and_laws_replace_the_designs():
    design = sizer.load(BOOK)
    motor = next(m for m in design.motors if m.id == "ex6_3")
    by_id = sizer.size(design, motors=["ex6_3"], laws=["poly5"]).to_records()
    by_object = sizer.size(design, motors=[motor], laws=["poly5"]).to_records()
    assert by_id == by_object
    assert [(r["motor"], r["spec"]) for r in by_id] == [("ex6_3", "polynomial(degree=5)")]


def test_progress_is_called_as_the_laws_are_sized(monkeypatch):
    # the book's laws are sized together as one axis: all done at once
    calls: list[tuple[int, int]] = []
    sizer.size(BOOK, progress=lambda done, total: calls.append((done, total)))
    laws = len(sizer.load(BOOK).laws)
    assert laws > 1 and calls == [(0, laws), (laws, laws)]
    calls.clear()  # law by law: after each
    monkeypatch.setattr("sizer.sizing.engine.law_axis", lambda *args: None)
    sizer.size(BOOK, progress=lambda done, total: calls.append((done, total)))
    assert calls == [(i, laws) for i in range(laws + 1)]


def test_parameter_mistakes_name_the_parameter():
    with pytest.raises(UserError) as error:
        sizer.size(ROOT / "missing.yaml", rank_by="speed")  # before the file is read
    assert error.value.field == "rank_by" and "choose one of size" in error.value.message
    with pytest.raises(UserError) as error:
        sizer.size(BOOK, motors=["nope"])
    assert error.value.field == "motors" and "loaded motors: ex6_1" in error.value.message
    with pytest.raises(UserError) as error:
        sizer.check(BOOK, envelope="square")
    assert error.value.field == "envelope"
    with pytest.raises(TypeError):
        sizer.size(sizer.load(BOOK), catalogs=["book-examples"])  # a Design has its motors
    with pytest.raises(TypeError):
        sizer.size(BOOK, motors="ex6_1")  # one string is not a list of ids


def test_the_notes_are_the_assumptions_of_the_sizing():
    from sizer import api

    design = sizer.load(BOOK)
    assert api.assumptions(design) == sizer.size(design).notes


@pytest.mark.parametrize("command,calls", [
    (["size", str(BOOK), "--top", "1"], ["load", "size"]),
    (["check", str(BOOK)], ["load", "check"]),
    (["report", str(BOOK), "--best", "0", "-o", "{tmp}/report"], ["load", "size"]),
    (["plot", str(BOOK), "--motor", "ex6_1", "-o", "{tmp}/plot.svg"], ["load", "size"]),
])
def test_the_commands_load_and_size_through_the_api(monkeypatch, tmp_path, command, calls):
    from sizer import api

    called: list[str] = []

    def spy(name: str):
        real = getattr(api, name)

        def call(*args, **kwargs):
            called.append(name)
            return real(*args, **kwargs)
        return call

    for name in ("load", "size", "check"):
        monkeypatch.setattr(api, name, spy(name))
    run = run_cli(*(part.format(tmp=tmp_path) for part in command))
    assert run.returncode == 0, run.stderr
    assert list(dict.fromkeys(called)) == calls  # the design loaded first, then sized


def test_the_readme_example_runs(monkeypatch, capsys):
    """The Python API section's code block, run from the repository root as it stands."""
    import re

    section = (ROOT / "docs" / "api-reference.md").read_text(encoding="utf-8")
    (code,) = re.findall(r"```python\n(.*?)```", section, re.S)
    monkeypatch.chdir(ROOT)
    exec(compile(code, "README.md", "exec"), {})
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("ex6_1 ") and lines[0].endswith(" True")
    assert lines[-3:] == ["0/2 laws", "2/2 laws", "True"]  # the two laws as one axis


def test_records_carry_the_energy_figures_of_designs_with_those_checks():
    """With a braking limit the records hold the energy returned per cycle, 1/2 J
    omega_max^2 with omega_max = 2 h / T (cycloidal, a lossless inertia), and the
    resistor's power, that over the cycle time T + dwell; without a limit, neither key."""
    design = {"task": {"displacement": "90 deg", "duration": "0.2 s", "dwell": "0.3 s"},
              "load": {"inertia": "0.02 kg*m^2"}, "laws": ["cycloidal"],
              "motors": [{"id": "m", "inertia": 0, "continuous_torque": 50,
                          "peak_torque": 100, "rated_speed": 1000}]}
    plain = sizer.size(design).to_records()[0]
    assert "regenerated_energy" not in plain and "braking_power" not in plain
    braked = sizer.size({**design, "limits": {"braking_resistor_power": "1000 W"}}
                        ).to_records()[0]
    stop = 0.5 * 0.02 * (2 * (math.pi / 2) / 0.2) ** 2
    assert braked["regenerated_energy"] == pytest.approx(stop, rel=1e-5)
    assert braked["braking_power"] == pytest.approx(braked["regenerated_energy"] / 0.5,
                                                    rel=1e-12)
