"""End to end: the files in examples/ through the CLI, and the book's numbers (ch. 6).

Where the book prints a figure that follows from a misprint the right value is pinned
(docs/errata.md): Example 6.2 trapezoid RMS 7.7297 (printed 7.7104), Example 6.3
T_min 0.1934 (printed 0.1924), Example 6.4 trapezoid 1/3 T_min 0.9584 (printed 0.9582).
Most runs call ``sizer.cli.app.main`` in this process; the README's first command runs
as a real process from the repository root, as in a fresh clone.
"""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from cli_run import run_cli as run

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
BOOK = EXAMPLES / "book"
REFERENCE = ROOT.parent / "shared" / "reference" / "motor-data.md"




def results(design: Path, motor: str) -> dict[str, dict]:
    """The JSON results of the book's motor, by law spec."""
    out = run("size", str(design), "--motor", motor, "--all", "--format", "json")
    assert out.returncode == 0, out.stderr
    return {r["spec"]: r for r in json.loads(out.stdout)["results"]}


# ------------------------------------------------------------------ the book
def test_examples_6_1_and_6_2() -> None:
    by_spec = results(BOOK / "ex6_1-6_2.yaml", "ex6_1")
    cycloidal = by_spec["cycloidal"]
    trapezoid = by_spec["trapezoidal(alpha=0.12732200375003505)"]
    assert cycloidal["feasible"] and trapezoid["feasible"]
    assert cycloidal["max_speed"] == pytest.approx(10.0, rel=1e-12)  # 2 h / T, at v_n
    assert round(trapezoid["max_speed"], 4) == 5.7295
    assert round(cycloidal["rms_torque"], 4) == 7.6293  # as printed
    assert round(trapezoid["rms_torque"], 4) == 7.7297  # printed 7.7104 (errata)
    # a_max = 15 rad/s^2 for the trapezoid, as the example asks
    alpha = trapezoid["params"]["alpha"]
    assert 15.0 / (alpha * (1 - alpha) * 3.0**2) == pytest.approx(15.0, rel=1e-12)


def test_example_6_3() -> None:
    harmonic = results(BOOK / "ex6_3.yaml", "ex6_3")["harmonic"]
    assert harmonic["limiting"] == "rms"
    assert round(harmonic["duration"], 4) == 0.1934  # printed 0.1924 (errata)
    assert harmonic["duration"] == pytest.approx(
        math.sqrt(math.pi**2 / (2 * math.sqrt(2)) * 0.6 * 0.25 / 14), rel=1e-9)
    variant = results(BOOK / "ex6_3-vmax4.yaml", "ex6_3_vmax4")["harmonic"]
    assert variant["limiting"] == "speed"
    assert round(variant["duration"], 4) == 0.2356
    assert variant["duration"] == pytest.approx(math.pi / 2 * 0.6 / 4, rel=1e-9)


def test_example_6_4() -> None:
    by_spec = results(BOOK / "ex6_4.yaml", "ex6_4")
    assert by_spec["trapezoidal(alpha=1/2)"]["duration"] == pytest.approx(1.0, rel=1e-9)
    third = by_spec["trapezoidal(alpha=1/3)"]
    assert third["limiting"] == "rms"
    assert round(third["duration"], 4) == 0.9584  # printed 0.9582 (errata)


def test_example_6_5() -> None:
    by_spec = results(BOOK / "ex6_5.yaml", "ex6_4")
    half = by_spec["double_s(alpha=1/2, beta=1/4)"]
    assert half["limiting"] == "rms" and round(half["duration"], 4) == 1.0434
    assert by_spec["double_s(alpha=1/3, beta=1/4)"]["duration"] == pytest.approx(1.0,
                                                                                 rel=1e-9)


# ------------------------------------------------------------------ all the examples
DESIGNS = sorted([*EXAMPLES.glob("*.yaml"), *BOOK.glob("*.yaml")])


def test_every_design_with_a_check_passes_it() -> None:
    with_check = [p for p in DESIGNS if "check" in yaml.safe_load(p.read_text())]
    assert len(with_check) >= 6
    result = run("check", *map(str, with_check))
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.count("\nPASS: ") + result.stdout.startswith("PASS: ") == \
        len(with_check)


def test_fastest_indexing_table_has_a_feasible_pair() -> None:
    data = json.loads(run("size", str(EXAMPLES / "indexing-table-fastest.yaml"),
                          "--top", "3", "-f", "json").stdout)
    assert data["design"]["mode"] == "minimize" and len(data["results"]) == 3
    durations = [r["duration"] for r in data["results"]]
    assert durations == sorted(durations) and all(0 < t < 0.25 for t in durations)


def test_readme_command_runs_from_the_repository_root() -> None:
    readme = (ROOT / "README.md").read_text().splitlines()
    assert readme[1] == ("python -m pip install . && python -m sizer size "
                         "examples/indexing-table.yaml")
    command = readme[1].split(" && ")[1].split()
    result = subprocess.run([sys.executable, *command[1:]], cwd=ROOT, capture_output=True,
                            text=True, timeout=120, check=False)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].startswith("Indexing table, 90 deg in 0.25 s: h = 1.5708 rad in "
                               "T = 250 ms; 12 of 24 motor/law pairs feasible")
    assert any("HG-KN43J" in line and "modified_sinusoidal" in line for line in lines)


def readme_transcripts() -> list[tuple[list[str], str]]:
    """The ``$ sizer ...`` commands shown in code blocks of the README and of the docs its
    reference moved to, with the output under each."""
    files = ("README.md", "docs/commands.md", "docs/machine-cycles.md", "docs/vibration.md")
    transcripts: list[tuple[list[str], list[str]]] = []
    current: list[str] | None = None
    inside = False
    lines = [line for name in files for line in (ROOT / name).read_text().splitlines()]
    for line in lines:
        if line.startswith("```"):
            inside, current = not inside, None
        elif inside and line.startswith("$ sizer "):
            current = []
            transcripts.append((line[len("$ sizer "):].split(), current))
        elif current is not None:
            current.append(line)
    return [(args, "".join(out + "\n" for out in lines)) for args, lines in transcripts]


def test_readme_transcripts_are_the_real_output(monkeypatch: pytest.MonkeyPatch) -> None:
    """The tutorial's outputs are what the commands print (regenerate them if not)."""
    transcripts = readme_transcripts()
    assert len(transcripts) >= 4
    monkeypatch.chdir(ROOT)
    for args, shown in transcripts:
        if "--output" not in args:
            assert run(*args).stdout == shown, " ".join(args)


def test_examples_readme_lists_every_example_file() -> None:
    listing = (EXAMPLES / "README.md").read_text()
    files = [p for p in EXAMPLES.rglob("*") if p.is_file() and p.name != "README.md"]
    assert files
    for path in files:
        assert f"`{path.relative_to(EXAMPLES).as_posix()}`" in listing


def test_ci_examples_run_sizer_check() -> None:
    workflow = yaml.safe_load((EXAMPLES / "ci" / "sizer-check.yml").read_text())
    steps = workflow["jobs"]["check"]["steps"]
    assert any(s.get("run", "").startswith("sizer check ") for s in steps)
    assert any("pip install" in s.get("run", "") for s in steps)
    hooks = yaml.safe_load((EXAMPLES / "ci" / "pre-commit-hooks.yaml").read_text())
    assert hooks[0]["id"] == "sizer-check" and hooks[0]["entry"] == "sizer check"
    config = yaml.safe_load((EXAMPLES / "ci" / "pre-commit-config.yaml").read_text())
    assert config["repos"][0]["hooks"][0]["entry"] == "sizer check"


# ------------------------------------------------------------------ the motor catalog
def test_example_catalog_cites_a_source_for_every_motor() -> None:
    from sizer.io import load_catalog

    motors = load_catalog(EXAMPLES / "catalogs" / "example-servo.yaml")
    assert len(motors) == 4
    for motor in motors:
        assert motor.source and "https://" in motor.source
        assert motor.price is None and motor.mass is None  # not in the source: absent
        assert motor.continuous_curve is None and motor.intermittent_curve is None


@pytest.mark.skipif(not REFERENCE.is_file(), reason="the motor-data notes are not here")
def test_example_catalog_figures_are_copied_from_the_reference() -> None:
    """Each HG-KN figure is the one printed in the research notes, unit included."""
    rows = {}
    for line in REFERENCE.read_text().splitlines():
        match = re.match(r"\| (HG-KN\d+)\(B\)J \|", line)
        if match:
            rows[match.group(1) + "J"] = [cell.strip() for cell in line.strip("|").split("|")]
    catalog = yaml.safe_load((EXAMPLES / "catalogs" / "example-servo.yaml").read_text())
    assert sorted(rows) == sorted(m["id"] for m in catalog["motors"])
    for motor in catalog["motors"]:
        row = rows[motor["id"]]
        assert motor["continuous_torque"] == f"{row[2]} N*m"
        assert motor["peak_torque"] == f"{row[3]} N*m"
        assert motor["rated_speed"] == f"{row[4]} rev/min"
        assert motor["max_speed"] == f"{row[5].split()[0]} rev/min"
        assert motor["inertia"] == f"{row[9]}e-4 kg*m^2"
