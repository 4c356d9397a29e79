"""``sizer diff`` (issue 39, design diffs): the diff equals two separate sizings compared
field by field; a pair that passed and fails exits 1; identical designs give an empty
diff; git revisions of one file are read without touching the work tree; user errors
exit 2. Small designs (the book's Examples 6.1-6.3), a few sizings in all."""

from __future__ import annotations

import copy
import csv
import io
import json
import math
import shutil
import subprocess
from pathlib import Path

import pytest
import yaml

import sizer.api as api
from sizer.cli.app import run
from sizer.sizing.design_diff import PairKey, PairStatus, design_changes, diff_sizings

BOOK = Path(__file__).resolve().parents[1] / "examples" / "book"
EX61 = BOOK / "ex6_1-6_2.yaml"
EX63 = BOOK / "ex6_3.yaml"


def _data(path: Path) -> dict:
    return yaml.safe_load(path.read_text())


def _changed_ex61() -> dict:
    """Example 6.1 with 20 % more inertia, the trapezoid replaced by poly5."""
    data = copy.deepcopy(_data(EX61))
    data["load"]["inertia"] = "1.2 kg*m^2"
    data["laws"] = ["cycloidal", "poly5"]
    del data["check"]
    return data


def _write(tmp_path: Path, name: str, data: dict) -> Path:
    path = tmp_path / name
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


def _by_pair(result) -> dict[tuple[str, str], object]:
    return {(r.motor, r.spec): r for r in result.results}


def _fields(r, checks) -> dict[str, object]:
    """A result's compared figures read from the CandidateResult itself."""
    known = r.duration is not None
    out = {"spec": r.spec, "feasible": r.feasible, "duration": r.duration,
           "peak_torque": r.peak_torque, "rms_torque": r.rms_torque,
           "max_speed": r.max_speed, "load_speed": r.load_speed,
           "load_torque": r.load_torque, "ratio": r.ratio, "gearbox": r.gearbox,
           "limiting": r.limiting, "price": r.price, "mass": r.mass,
           "rated_power": r.rated_power}
    for name in checks:
        margin = r.margin(name)
        out[f"margin_{name}"] = margin if known else None
    out["limiting_margin"] = r.margin(r.limiting) if known else None
    return out


def test_the_diff_equals_two_separate_runs_compared_field_by_field():
    before, after_data = _data(EX61), _changed_ex61()
    a = api.size(EX61)
    b = api.size(after_data, catalogs=())
    diff = diff_sizings(a, b, design=design_changes(before, after_data))
    checks = tuple(dict.fromkeys((*a.check_names(), *b.check_names())))
    rows_a, rows_b = _by_pair(a), _by_pair(b)
    assert {(p.key.motor, p.key.law) for p in diff.pairs} == set(rows_a) | set(rows_b)
    records = diff.to_records()
    for p in diff.pairs:
        pair = (p.key.motor, p.key.law)
        ra, rb = rows_a.get(pair), rows_b.get(pair)
        fa = None if ra is None else _fields(ra, checks)
        fb = None if rb is None else _fields(rb, checks)
        for side, expected in ((p.before, fa), (p.after, fb)):
            if expected is None:
                assert side is None
                continue
            for name, value in expected.items():
                assert side[name] == value, (pair, name)
        if fa is None or fb is None:
            assert p.status is (PairStatus.ADDED if fa is None else PairStatus.REMOVED)
            continue
        differ = {n for n in fa if fa[n] != fb[n]}
        assert {c.field for c in p.changes} == differ, pair
        mine = [r for r in records if (r["motor"], r["law"]) == pair]
        assert {r["field"] for r in mine} == differ
        for r in mine:
            assert (r["before"], r["after"]) == (fa[r["field"]], fb[r["field"]])
            if isinstance(fa[r["field"]], float) and isinstance(fb[r["field"]], float):
                assert r["change"] == fb[r["field"]] - fa[r["field"]]
        if ra.feasible and not rb.feasible:
            assert p.status is PairStatus.REGRESSED
        elif rb.feasible and not ra.feasible:
            assert p.status is PairStatus.IMPROVED
        else:
            assert p.status is (PairStatus.CHANGED if differ else PairStatus.UNCHANGED)
    # the trapezoid's three pairs removed, poly5's three added
    assert sum(p.status is PairStatus.REMOVED for p in diff.pairs) == 3
    assert sum(p.status is PairStatus.ADDED for p in diff.pairs) == 3
    # Example 6.2: cycloidal on ex6_1 passes with an RMS torque of 7.6293 N*m < 8 N*m;
    # with J = 1.2 it needs more than tau_c: a regression limited by the RMS check
    regressed = {p.key for p in diff.regressions}
    assert PairKey("ex6_1", "", "cycloidal") in regressed
    cyc = diff.pair(PairKey("ex6_1", "", "cycloidal"))
    assert cyc is not None and cyc.after is not None and cyc.after["limiting"] == "rms"
    # the RMS torque of tau = J a + B v (the cross term integrates to 0 over a rest-to-rest
    # move): sqrt((J C_a_rms h/T^2)^2 + (B C_v_rms h/T)^2), cycloidal C_a_rms = pi sqrt 2,
    # C_v_rms = sqrt(3/2); h = 15 rad, T = 3 s, B = 0.3 N*m*s/rad, J = 1 then 1.2 kg*m^2
    rms = cyc.change("rms_torque")
    assert rms is not None
    for inertia, value in ((1.0, rms.before), (1.2, rms.after)):
        expected = math.hypot(inertia * math.pi * math.sqrt(2) * 15 / 9,
                              0.3 * math.sqrt(1.5) * 15 / 3)
        assert value == pytest.approx(expected, rel=1e-9)
    assert [c.field for c in diff.design] == ["load.inertia", "laws", "check"]


def test_minimize_mode_diff_holds_t_min_before_and_after():
    """Example 6.3: T_min = sqrt(C_a_rms h J_t / tau_c), C_a_rms = pi^2 / (2 sqrt 2) for
    the harmonic law (the RMS bound wins), with J_t = 0.25 and then 0.3 kg*m^2."""
    after = _data(EX63)
    after["load"]["inertia"] = "0.3 kg*m^2"
    diff = diff_sizings(api.size(EX63, motors=["ex6_3"]), api.size(after, motors=["ex6_3"]))
    (pair,) = diff.pairs
    assert pair.status is PairStatus.CHANGED
    c_a_rms = math.pi ** 2 / (2 * math.sqrt(2))
    duration = pair.change("duration")
    assert duration is not None
    assert duration.before == pytest.approx(math.sqrt(c_a_rms * 0.6 * 0.25 / 14), rel=1e-6)
    assert duration.after == pytest.approx(math.sqrt(c_a_rms * 0.6 * 0.3 / 14), rel=1e-6)
    assert pair.before["limiting"] == pair.after["limiting"] == "rms"


def test_identical_designs_give_an_empty_diff_and_exit_0(capsys):
    assert run(["diff", str(EX61), str(EX61), "--format", "json"]) == 0
    document = json.loads(capsys.readouterr().out)
    assert document["regression"] is False
    assert document["design_changes"] == []
    assert {p["status"] for p in document["pairs"]} == {"unchanged"}
    assert all(p["changes"] == [] for p in document["pairs"])
    assert run(["diff", str(EX61), str(EX61), "--format", "csv"]) == 0
    assert capsys.readouterr().out == "motor,drive,law,status,field,before,after,change\n"
    assert run(["diff", str(EX61), str(EX61)]) == 0
    assert "no change" in capsys.readouterr().out


def test_a_passing_pair_that_fails_exits_1_in_every_format(tmp_path, capsys):
    after = _write(tmp_path, "after.yaml", _changed_ex61())
    outputs = {}
    for fmt in ("table", "md", "json", "csv"):
        assert run(["diff", str(EX61), str(after), "--format", fmt]) == 1, fmt
        outputs[fmt] = capsys.readouterr().out
    rows = list(csv.DictReader(io.StringIO(outputs["csv"])))
    feasible = [r for r in rows if r["field"] == "feasible" and r["status"] == "regressed"]
    assert {(r["motor"], r["law"]) for r in feasible} == {("ex6_1", "cycloidal")}
    assert (feasible[0]["before"], feasible[0]["after"]) == ("true", "false")
    md = outputs["md"]
    assert md.startswith("### sizer diff")
    assert md.index("regression") < md.index("| pair | status | field |")
    assert "`load.inertia`" in md
    document = json.loads(outputs["json"])
    assert document["format"] == "sizer.diff/1" and document["regression"] is True
    assert document["summary"]["regressed"] == 1
    # the same inputs give the same bytes
    for fmt in ("json", "csv"):
        assert run(["diff", str(EX61), str(after), "--format", fmt]) == 1
        assert capsys.readouterr().out == outputs[fmt]
    # the other way round the pair becomes feasible: no regression
    assert run(["diff", str(after), str(EX61), "--format", "csv"]) == 0
    assert ",improved,feasible,false,true," in capsys.readouterr().out


def _git(repo: Path, *args: str) -> str:
    return subprocess.run(["git", "-C", str(repo), "-c", "user.name=t", "-c",
                           "user.email=t@example.com", *args], check=True,
                          capture_output=True, text=True).stdout


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_git_revisions_of_one_file(tmp_path, capsys, monkeypatch):
    repo = tmp_path / "repo"
    (repo / "designs").mkdir(parents=True)
    (repo / "catalogs").mkdir()
    shutil.copy(Path(api.__file__).parent / "catalogs" / "book-examples.yaml",
                repo / "catalogs" / "book.yaml")
    data = _data(EX61)
    data["motors"] = "../catalogs/book.yaml"  # relative to the design's folder
    design = _write(repo / "designs", "axis.yaml", data)
    _git(repo, "init", "-q")
    _git(repo, "add", ".")
    _git(repo, "commit", "-qm", "one")
    data["load"]["inertia"] = "1.2 kg*m^2"
    _write(repo / "designs", "axis.yaml", data)
    index = (repo / ".git" / "index").read_bytes()
    status = _git(repo, "status", "--porcelain")
    text = design.read_text()
    monkeypatch.chdir(repo / "designs")
    # HEAD's file against the work tree's: the cycloidal pair of ex6_1 regresses
    assert run(["diff", "axis.yaml", "--rev", "HEAD", "--format", "json"]) == 1
    document = json.loads(capsys.readouterr().out)
    assert document["a"]["file"] == "HEAD:axis.yaml" and document["b"]["file"] == "axis.yaml"
    assert document["design_changes"] == [
        {"field": "load.inertia", "before": "1 kg*m^2", "after": "1.2 kg*m^2"}]
    # the same as the two files compared directly
    old = _write(tmp_path, "old.yaml", {**_data(EX61), "motors": "book-examples"})
    assert run(["diff", str(old), str(design), "--format", "csv"]) == 1
    direct = capsys.readouterr().out
    assert run(["diff", "axis.yaml", "--rev", "HEAD", "--format", "csv"]) == 1
    assert capsys.readouterr().out == direct
    # nothing in the work tree or the index changed
    assert design.read_text() == text
    assert _git(repo, "status", "--porcelain") == status
    assert (repo / ".git" / "index").read_bytes() == index
    # a catalog the revision's design reads is the work tree's: a warning when it differs
    catalog = repo / "catalogs" / "book.yaml"
    catalog.write_text(catalog.read_text() + "# edited\n")
    assert run(["diff", "axis.yaml", "--rev", "HEAD", "--format", "csv"]) == 1
    captured = capsys.readouterr()
    assert captured.out == direct
    assert captured.err.startswith("warning: HEAD:axis.yaml: catalogs/book.yaml differs")
    # two revisions
    _git(repo, "commit", "-qam", "two")
    assert run(["diff", "axis.yaml", "--rev", "HEAD~1", "--rev", "HEAD", "-f", "csv"]) == 1
    assert capsys.readouterr().out == direct
    assert run(["diff", "axis.yaml", "--rev", "HEAD", "--rev", "HEAD~1", "-f", "csv"]) == 0
    assert ",improved,feasible,false,true," in capsys.readouterr().out


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_a_revision_read_changes_nothing(tmp_path, capsys):
    repo = tmp_path / "r"
    repo.mkdir()
    design = _write(repo, "d.yaml", {**_data(EX63)})
    _git(repo, "init", "-q")
    _git(repo, "add", ".")
    _git(repo, "commit", "-qm", "one")
    design.write_text(design.read_text().replace("0.25 kg*m^2", "0.3 kg*m^2"))
    before = {p: p.read_bytes() for p in repo.rglob("*") if p.is_file()}
    assert run(["diff", str(design), "--rev", "HEAD", "-f", "csv"]) == 0
    assert ",changed,duration," in capsys.readouterr().out
    assert {p: p.read_bytes() for p in repo.rglob("*") if p.is_file()} == before


@pytest.mark.parametrize(("args", "words"), [
    (["{a}"], "give two design files"),
    (["{a}", "{missing}"], "not found"),
    (["{a}", "{a}", "--rev", "HEAD"], "--rev"),
    (["{a}", "--rev", "HEAD", "--rev", "HEAD", "--rev", "HEAD"], "at most twice"),
    (["{outside}", "--rev", "HEAD"], "not in a git work tree"),
    (["{a}", "{a}", "--law", "nonsense"], "--law"),
    (["{a}", "{a}", "--rank-by", "nonsense"], "--rank-by"),
    (["{a}", "{a}", "--motor", "nonsense"], "--motor"),
    (["{a}", "{a}", "--output", "{a}"], "--output"),
    (["{a}", "{a}", "--format", "xml"], "--format"),
    (["{a}", "--rev", "-p"], "not a revision"),
    (["{machine}", "{a}"], "machine file"),
    (["{a}", "{plan}"], "planned, not sized"),
])
def test_user_errors_exit_2(tmp_path, capsys, args, words):
    outside = _write(tmp_path, "outside.yaml", _data(EX61))
    a = _write(tmp_path, "a.yaml", _data(EX61))
    machine = _write(tmp_path, "machine.yaml", {"axes": {"x": {"design": "a.yaml"}}})
    plan = _write(tmp_path, "plan.yaml", {
        **{k: v for k, v in _data(EX61).items() if k != "check"}, "motors": [],
        "limits": {"max_speed": "10 rad/s"}})
    names = {"a": a, "missing": tmp_path / "missing.yaml", "outside": outside,
             "machine": machine, "plan": plan}
    argv = ["diff", *(x.format(**names) for x in args)]
    assert run(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and words in err and "Traceback" not in err
    assert a.read_text() == yaml.safe_dump(_data(EX61), sort_keys=False)


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_a_revision_with_catalog_options_is_sized_as_a_file(tmp_path, capsys, monkeypatch):
    """--catalog adds its motors to a revision's design as the loader adds them to a file:
    a design naming no motors gets only those (not the bundled catalogs); the same diff as
    the two files compared directly with the option."""
    repo = tmp_path / "repo"
    repo.mkdir()
    data = _data(EX61)
    data.pop("motors", None)
    design = _write(repo, "axis.yaml", data)
    _git(repo, "init", "-q")
    _git(repo, "add", ".")
    _git(repo, "commit", "-qm", "one")
    old = _write(tmp_path, "old.yaml", data)
    data["load"]["inertia"] = "1.2 kg*m^2"
    _write(repo, "axis.yaml", data)
    monkeypatch.chdir(repo)
    assert run(["diff", str(old), str(design), "--catalog", "book-examples", "-f", "json"]) == 1
    direct = json.loads(capsys.readouterr().out)
    from sizer.io.loader import load_catalog

    book = {m.id for m in load_catalog("book-examples")}
    assert direct["pairs"] and {p["motor"] for p in direct["pairs"]} <= book
    assert run(["diff", "axis.yaml", "--rev", "HEAD", "--catalog", "book-examples",
                "-f", "json"]) == 1
    revision = json.loads(capsys.readouterr().out)
    assert revision["pairs"] == direct["pairs"]
    # a plan's design (no motors, the load's limits, no load) with --catalog is sized
    # against the catalog, so it needs its load, in a revision as in a file
    plan = {k: v for k, v in data.items() if k != "load"}
    plan["limits"] = {"max_speed": "30 rad/s"}
    _write(repo, "axis.yaml", plan)
    _git(repo, "commit", "-qam", "plan")
    code = run(["diff", "axis.yaml", "--rev", "HEAD~1", "--rev", "HEAD", "--catalog",
                "book-examples"])
    assert code == 2 and "load.inertia" in capsys.readouterr().err
