"""``sizer report``: report.md links only to files that exist, holds the ranking table and
the checks of the best candidates, and is deterministic."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

pytest.importorskip("matplotlib")

from sizer.cli import report_command
from sizer.errors import UserError
from sizer.io import load_design
from sizer.report.candidate_row import check_line
from sizer.report.design_report import (
    LAWS_FIGURE,
    REPORT_FILE,
    DesignReport,
    display_check,
    md,
    write_report,
)
from sizer.report.markdown_table import render_markdown_table
from sizer.report.sizing_table import SizingDocument
from sizer.sizing import size_design

DESIGN = """\
name: Book 6.1
task: {displacement: 15 rad, duration: 3 s}
load: {inertia: 1 kg*m^2, damping: 0.3 N*m*s/rad}
transmission: {type: direct}
laws: [cycloidal, "trapezoidal(alpha=0.12732200375003505)", harmonic, poly5]
motors: book-examples
"""

GEARED = """\
name: Geared, with a return
task: {displacement: 90 deg, duration: 0.3 s, dwell: 0.1 s, return: true}
load: {inertia: 0.02 kg*m^2, damping: 0.01 N*m*s/rad, friction: 0.2 N*m}
transmission:
  - {type: gearbox, ratio: 5, efficiency: 0.9, inertia: 0.2 kg*cm^2, name: planetary}
laws: [cycloidal, "trapezoidal(alpha=auto)"]
limits: {torque_margin: 10 %, inertia_ratio: 20}
motors:
  - id: small
    inertia: 0.1 kg*cm^2
    continuous_torque: 0.1 N*m
    peak_torque: 0.3 N*m
    rated_speed: 3000 rpm
  - id: big
    inertia: 1 kg*cm^2
    continuous_torque: 1.0 N*m
    peak_torque: 3 N*m
    rated_speed: 3000 rpm
    part_number: BIG-1
    source: a test catalog
"""

DPI = 30
SAMPLES = 21
LINK = re.compile(r"\]\(([^)]+)\)")


def links(text: str) -> list[str]:
    return LINK.findall(text)


@pytest.fixture(scope="module")
def book(tmp_path_factory):
    path = tmp_path_factory.mktemp("book") / "book.yaml"
    path.write_text(DESIGN)
    design = load_design(path)
    return design, size_design(design)


@pytest.fixture(scope="module")
def written(tmp_path_factory, book):
    design, sizing = book
    directory = tmp_path_factory.mktemp("report") / "out"
    paths = write_report(design, sizing, directory, dpi=DPI, samples=SAMPLES,
                         source="book.yaml")
    return directory, paths


def test_report_links_only_to_files_that_exist(written):
    directory, paths = written
    text = (directory / REPORT_FILE).read_text()
    targets = links(text)
    assert LAWS_FIGURE in targets
    assert sum(t.startswith("speed-torque-") for t in targets) == 3
    for target in targets:
        assert not Path(target).is_absolute() and "/" not in target
        assert (directory / target).is_file(), target
        assert (directory / target).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in paths) == sorted([REPORT_FILE, *targets])
    assert sorted(p.name for p in directory.iterdir()) == sorted(p.name for p in paths)


def test_report_contains_the_ranking_table(written, book):
    design, sizing = book
    directory, _ = written
    text = (directory / REPORT_FILE).read_text()
    table = md(render_markdown_table(SizingDocument(sizing, design, top=5).table()))
    assert table in text
    assert text.count("\n| 1 | ") == 1
    rows = table.splitlines()[2:]
    assert len(rows) == min(5, len(sizing.feasible))
    infeasible = len(sizing.results) - len(sizing.feasible)
    assert f"- {infeasible} infeasible pairs not shown" in text
    assert f"{len(sizing.feasible)} of {len(sizing.results)} motor/law pairs are feasible" \
        in text


def test_report_sections_and_checks(written, book):
    _, sizing = book
    text = (written[0] / REPORT_FILE).read_text()
    headings = [line for line in text.splitlines() if line.startswith("#")]
    assert headings[0] == "# Sizing report: Book 6.1"
    for section in ("## Task", "## Load", "## Transmission", "## Limits", "## Motors",
                    "## Motion laws", "## Ranking", "## Best candidates"):
        assert section in headings
    best = sizing.feasible[:3]
    for rank, result in enumerate(best, start=1):
        assert f"### {rank}. {result.motor} with {result.spec}" in headings
        for check in result.checks:
            # speeds in rpm in the report (issue 36), as display_check converts them
            assert f"- {md(check_line(result, display_check(check)))}" in text
    # the coefficient table of the laws considered
    for spec in ("cycloidal", "harmonic", "polynomial(degree=5)"):
        assert f"\n| {spec} | " in text
    assert "15 rad (859.44 deg)" in text
    assert "Direct drive" in text
    assert "0.3 N\\*m\\*s/rad" in text  # '*' escaped: not read as emphasis


def test_report_is_deterministic(tmp_path, written, book):
    design, sizing = book
    first = DesignReport(design, sizing, source="book.yaml").markdown()
    again = DesignReport(design, size_design(design), source="book.yaml").markdown()
    assert first == again == (written[0] / REPORT_FILE).read_text()
    second = tmp_path / "again"
    write_report(design, sizing, second, dpi=DPI, samples=SAMPLES, source="book.yaml")
    for name in ("report.md", "laws.png", "speed-torque-1.png"):
        assert (second / name).read_bytes() == (written[0] / name).read_bytes()


def test_top_and_best_options(tmp_path, book):
    design, sizing = book
    report = DesignReport(design, sizing, top=2, best=1)
    text = report.markdown()
    assert len(report.candidates) == 1
    assert report.figures == [LAWS_FIGURE, "speed-torque-1.png"]
    assert text.count("\n### ") == 1
    more = len(sizing.feasible) - 2
    assert f"- {more} more feasible pairs not shown." in text
    assert "The best feasible pair." in text


def test_report_of_a_geared_design_with_auto_shapes(tmp_path):
    path = tmp_path / "geared.yaml"
    path.write_text(GEARED)
    design = load_design(path)
    sizing = size_design(design)
    directory = tmp_path / "geared"
    write_report(design, sizing, directory, dpi=DPI, samples=SAMPLES)
    text = (directory / REPORT_FILE).read_text()
    for target in links(text):
        assert (directory / target).is_file()
    assert "| 1 | gearbox | planetary | 5 | 0.9 | 2e-05 |" in text
    assert "move, dwell, move back, dwell" in text
    # the auto shape chosen for the pairs shown is in the coefficient table
    chosen = {r.spec for r in sizing.results if r.law == "trapezoidal"}
    assert any(f"\n| {spec} | " in text for spec in chosen)
    assert "trapezoidal(alpha=auto): the shape is chosen for each motor" in text
    assert "| big | 0.0001 | 1 | 3 | 3000 |" in text
    assert "- big: a test catalog" in text


def test_report_when_no_pair_is_feasible(tmp_path):
    path = tmp_path / "heavy.yaml"
    path.write_text(DESIGN.replace("inertia: 1 kg*m^2", "inertia: 100 kg*m^2"))
    design = load_design(path)
    sizing = size_design(design)
    assert not sizing.feasible
    directory = tmp_path / "heavy"
    write_report(design, sizing, directory, dpi=DPI, samples=SAMPLES, best=2)
    text = (directory / REPORT_FILE).read_text()
    assert "no feasible motor/law pair" in text
    assert "## Closest candidates (none is feasible)" in text
    assert "Verdict: not feasible:" in text
    assert text.count("\n### ") == 2
    for target in links(text):
        assert (directory / target).is_file()


def test_report_in_minimize_mode_without_duration_has_no_figure(tmp_path):
    path = tmp_path / "hopeless.yaml"
    path.write_text(DESIGN.replace("duration: 3 s", "duration: minimize")
                    .replace("inertia: 1 kg*m^2", "inertia: 1 kg*m^2, torque: 50 N*m"))
    design = load_design(path)
    sizing = size_design(design)
    assert all(r.duration is None for r in sizing.results)
    directory = tmp_path / "hopeless"
    write_report(design, sizing, directory, dpi=DPI, samples=SAMPLES)
    text = (directory / REPORT_FILE).read_text()
    assert "No figure: the pair has no feasible duration." in text
    assert [t for t in links(text) if t.startswith("speed-torque")] == []
    assert "minimized for each pair (T_min)" in text


def test_report_command(tmp_path):
    path = tmp_path / "design.yaml"
    path.write_text(DESIGN)
    application = typer.Typer()
    report_command.register(application)
    application.command("unused")(lambda: None)  # keep 'report' a subcommand
    out = tmp_path / "out"
    result = CliRunner().invoke(application, [
        "report", str(path), "-o", str(out), "--top", "3", "--best", "1", "--dpi", "30",
        "--motor", "ex6_1"])
    assert result.exit_code == 0, result.output
    assert result.output.strip() == f"{out / REPORT_FILE}: report with 2 figures"
    text = (out / REPORT_FILE).read_text()
    assert "Design file: `design.yaml`" in text and str(tmp_path) not in text
    assert "1 motor considered" in text
    bad = CliRunner().invoke(application, ["report", str(path), "-o", str(out),
                                           "--rank-by", "colour"])
    assert isinstance(bad.exception, UserError)
    assert "--rank-by: unknown key 'colour'" in str(bad.exception)
