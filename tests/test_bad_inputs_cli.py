"""Bad inputs of the command line (issue 10): options, outputs onto inputs, unwritable
outputs, unknown commands, control characters from files.

Every case gets the answer of ``bad_input_cases.run_case`` (exit code, words, one error
line, no traceback, inputs unchanged); :class:`CliCase` adds links made before the run and
raw texts that must never reach the terminal.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import pytest
from bad_input_cases import EXAMPLES, Case, edited, run_case

SERVO = (EXAMPLES / "catalogs" / "example-servo.yaml").read_text(encoding="utf-8")
EX63 = edited("book/ex6_3.yaml")
INDEXING = edited("indexing-table.yaml")
GEARBOXES = edited("indexing-table-gearboxes.yaml")
LAW = ("law", "cycloidal", "--displacement", "90 deg", "--duration", "0.2 s")
CSV = "Model,Tc\nA1,0.3\n"
ESC = "\x1b"
RLO = "\u202e"


@dataclass(frozen=True)
class CliCase(Case):
    """A Case with links made in its folder first and texts that must not be printed."""

    links: tuple[tuple[str, str, str], ...] = ()
    """(kind, name, target): kind 'hard' or 'symbolic'; target relative to the folder."""
    absent: tuple[str, ...] = ()
    """Raw texts (control characters) that must appear neither on stdout nor on stderr."""


def evil_catalog(motor_id: str) -> str:
    """The example catalog with its first motor renamed (YAML escapes keep it one line)."""
    escaped = motor_id.encode("unicode_escape").decode("ascii").replace('"', '\\"')
    return SERVO.replace("id: HG-KN13J", f'id: "{escaped}"', 1)


EVIL_ID = f"EVIL{ESC}[31mRED{RLO}X\r\x07\b"
EVIL_CATALOG = evil_catalog(EVIL_ID)
EVIL_DESIGN = edited("indexing-table.yaml", set={
    "name": f"Table{ESC}]0;owned\x07 {RLO}eman",
    "motors": "motors.yaml", "check.motor": EVIL_ID,
    "laws": ["modified_sinusoidal"]})
RAW = (ESC, RLO, "\x07", "\b", "\r")

CASES = [
    # ---------------------------------------------------------------- options: values
    Case("size-rank-by-unknown", args=("size", "{design}", "--rank-by", "bogus"), design=EX63,
         words=("--rank-by", "unknown key 'bogus'", "choose one of", "size", "duration",
                "margin", "price", "power")),
    Case("report-rank-by-unknown",
         args=("report", "{design}", "--rank-by", "speed", "-o", "{tmp}/report"), design=EX63,
         words=("--rank-by", "'speed'", "choose one of", "margin")),
    Case("size-top-zero", args=("size", "{design}", "--top", "0"), design=EX63,
         words=("--top", "greater than or equal to 1")),
    Case("size-top-not-a-number", args=("size", "{design}", "-n", "five"), design=EX63,
         words=("--top", "valid integer")),
    Case("report-best-too-many", args=("report", "{design}", "--best", "99", "-o", "{tmp}/r"),
         design=EX63, words=("--best", "50")),
    Case("size-format-unknown", args=("size", "{design}", "--format", "xlsx"), design=EX63,
         words=("--format", "xlsx", "table", "csv", "md", "json")),
    Case("check-format-md", args=("check", "{design}", "--format", "md"), design=EX63,
         words=("--format", "table", "json")),
    Case("laws-format-unknown", args=("laws", "-f", "html"), words=("--format", "html")),
    Case("size-envelope-unknown", args=("size", "{design}", "--envelope", "curvy"),
         design=EX63, words=("--envelope", "curvy", "book", "linear")),
    Case("check-envelope-unknown", args=("check", "{design}", "--envelope", "x"), design=EX63,
         words=("--envelope", "linear_intermittent")),
    Case("size-motor-unknown", args=("size", "{design}", "--motor", "NOPE-1"), design=EX63,
         words=("--motor", "NOPE-1", "loaded motors")),
    Case("law-samples-one", args=(*LAW, "--samples", "1"), words=("--samples", "between 2")),
    Case("law-duration-zero", args=("law", "cycloidal", "--displacement", "1",
                                    "--duration", "0 s"), words=("--duration", "positive")),
    Case("plot-speed-unit-unknown",
         args=("plot", "{design}", "--speed-unit", "furlong/s", "-o", "{tmp}/p.png"),
         design=EX63, words=("--speed-unit", "rpm", "rad/s", "furlong")),
    Case("plot-output-suffix", args=("plot", "{design}", "-o", "{tmp}/p.txt"), design=EX63,
         words=("--output", ".txt", "png", "svg")),
    Case("plot-dpi-too-low", args=("plot", "{design}", "--dpi", "5", "-o", "{tmp}/p.png"),
         design=EX63, words=("--dpi", "10")),
    Case("plot-law-size-malformed",
         args=("plot-law", "cycloidal", "--size", "big", "-o", "{tmp}/l.png"),
         words=("--size", "8x6")),
    Case("import-delimiter-two-chars",
         args=("catalog", "import", "{tmp}/m.csv", "--map", "Model=id", "--delimiter", ";;"),
         extra_files={"m.csv": CSV}, words=("--delimiter", "one character")),
    Case("laws-law-unknown", args=("laws", "--law", "bogus"),
         words=("--law", "unknown law 'bogus'", "cycloidal")),
    Case("plot-law-option-malformed-before-loading",
         args=("plot", "{design}", "--law", "poly5(", "-o", "{tmp}/p.png"), design="task: [\n",
         words=("--law", "poly5(")),
    Case("plot-motor-unknown-names-the-option",
         args=("plot", "{design}", "--motor", "NOPE", "-o", "{tmp}/p.png"), design=EX63,
         words=("--motor", "NOPE", "loaded motors: ex6_1")),
    Case("law-spec-malformed", args=("law", "cycloidal(", "--displacement", "1",
                                     "--duration", "1"), words=("SPEC", "cycloidal(")),
    Case("plot-law-spec-unknown", args=("plot-law", "cycloid", "-o", "{tmp}/l.png"),
         words=("SPEC", "cycloid")),
    Case("import-encoding-unknown",
         args=("catalog", "import", "{tmp}/m.csv", "--map", "Model=id", "--encoding", "klingon"),
         extra_files={"m.csv": CSV}, words=("--encoding", "klingon", "utf-8")),
    Case("size-catalog-missing-before-loading",
         args=("size", "{design}", "--catalog", "{tmp}/none.yaml"), design="task: [\n",
         words=("--catalog", "none.yaml", "not found")),
    Case("check-catalog-unknown-once-for-all-files",
         args=("check", "{design}", "{design}", "--catalog", "nosuch"), design=EX63,
         words=("--catalog", "nosuch", "bundled catalogs")),
    Case("catalog-show-catalog-unknown", args=("catalog", "show", "X", "-c", "nosuch"),
         words=("--catalog", "nosuch")),
    # ------------------------------------------------- options: names, commands, arguments
    Case("size-unknown-option", args=("size", "{design}", "--bogus"), design=EX63,
         words=("no such option", "--bogus")),
    Case("root-unknown-option", args=("--verbose", "laws"), words=("no such option",
                                                                   "--verbose")),
    Case("unknown-command", args=("sise", "{design}"), design=EX63,
         words=("no such command", "sise", "sizer --help")),
    Case("catalog-unknown-command", args=("catalog", "remove", "x"),
         words=("no such command", "remove", "sizer catalog --help")),
    Case("size-missing-design", args=("size",), words=("missing argument", "DESIGN.yaml")),
    Case("law-missing-duration", args=("law", "cycloidal", "--displacement", "1"),
         words=("missing option", "--duration")),
    Case("import-missing-map", args=("catalog", "import", "{tmp}/m.csv"),
         extra_files={"m.csv": CSV}, words=("missing option", "--map")),
    Case("schema-unknown", args=("schema", "motors"), words=("motors", "design", "catalog",
                                                              "gearboxes")),
    # ------------------------------------------------------ --output onto an input file
    Case("size-output-is-the-design", args=("size", "{design}", "-o", "{design}"),
         design=EX63, words=("--output", "design.yaml", "input", "another output file")),
    Case("size-output-is-a-catalog-the-design-names",
         args=("size", "{design}", "-f", "csv", "-o", "{tmp}/catalogs/example-servo.yaml"),
         design=INDEXING, words=("--output", "example-servo.yaml", "input")),
    Case("size-output-is-the-gearbox-catalog",
         args=("size", "{design}", "-o", "{tmp}/catalogs/example-gearboxes.yaml"),
         design=GEARBOXES, words=("--output", "example-gearboxes.yaml", "input")),
    Case("size-output-is-the-added-catalog",
         args=("size", "{design}", "--catalog", "{catalog}", "-o", "{catalog}"),
         design=EX63, catalog=SERVO, words=("--output", "motors.yaml", "input")),
    Case("size-output-names-the-added-catalog-another-way",
         args=("size", "{design}", "-c", "{tmp}/motors.yaml", "-o",
               "{tmp}/catalogs/../motors.yaml"),
         design=EX63, catalog=SERVO, words=("--output", "same file as the input")),
    Case("report-folder-holds-an-input",
         args=("report", "{design}", "-c", "{tmp}/laws.png", "-o", "{tmp}"), design=EX63,
         extra_files={"laws.png": SERVO}, words=("--output", "laws.png", "input")),
    Case("report-folder-holds-the-design-as-report-md",
         args=("report", "{tmp}/report.md", "-o", "{tmp}"),
         extra_files={"report.md": EX63}, words=("--output", "report.md", "input")),
    Case("plot-output-is-a-catalog",
         args=("plot", "{design}", "-c", "{tmp}/m.png", "-o", "{tmp}/m.png"), design=EX63,
         extra_files={"m.png": SERVO}, words=("--output", "m.png", "input")),
    Case("import-output-is-the-csv",
         args=("catalog", "import", "{tmp}/m.csv", "--map", "Model=id", "-o", "{tmp}/m.csv"),
         extra_files={"m.csv": CSV}, words=("--output", "m.csv", "input")),
    Case("catalog-list-output-is-the-catalog",
         args=("catalog", "list", "{catalog}", "-o", "{catalog}"), catalog=SERVO,
         words=("--output", "motors.yaml", "input")),
    Case("catalog-show-output-is-the-catalog",
         args=("catalog", "show", "HG-KN43J", "-c", "{catalog}", "-o", "{catalog}"),
         catalog=SERVO, words=("--output", "motors.yaml", "input")),
    CliCase("size-output-is-a-hard-link-to-the-design",
            args=("size", "{design}", "-o", "{tmp}/hard.yaml"), design=EX63,
            links=(("hard", "hard.yaml", "design.yaml"),),
            words=("--output", "hard.yaml", "same file as the input", "design.yaml")),
    CliCase("size-output-is-a-symlink-to-the-design",
            args=("size", "{design}", "-f", "csv", "-o", "{tmp}/out.csv"), design=EX63,
            links=(("symbolic", "out.csv", "design.yaml"),),
            words=("--output", "out.csv", "same file as the input")),
    CliCase("size-output-is-a-symlink-to-a-named-catalog",
            args=("size", "{design}", "-o", "{tmp}/out.csv"), design=INDEXING,
            links=(("symbolic", "out.csv", "catalogs/example-servo.yaml"),),
            words=("--output", "out.csv", "example-servo.yaml")),
    CliCase("laws-output-is-a-hard-link-to-a-catalog-added",
            args=("plot", "{design}", "-c", "{catalog}", "-o", "{tmp}/h.png"), design=EX63,
            catalog=SERVO, links=(("hard", "h.png", "motors.yaml"),),
            words=("--output", "h.png", "motors.yaml")),
    # ------------------------------------------------------ outputs that cannot be written
    Case("size-output-is-a-folder", args=("size", "{design}", "-o", "{tmp}/catalogs"),
         design=EX63, words=("--output", "directory")),
    Case("laws-output-folder-missing", args=("laws", "-o", "{tmp}/missing/laws.md"),
         words=("--output", "missing", "does not exist")),
    Case("schema-output-folder-missing",
         args=("schema", "design", "-o", "{tmp}/no/such/dir/s.json"),
         words=("--output", "does not exist")),
    Case("law-output-folder-is-a-file", args=(*LAW, "-o", "{tmp}/m.csv/x.csv"),
         extra_files={"m.csv": CSV}, words=("--output", "not a folder")),
    Case("report-output-is-a-file", args=("report", "{design}", "-o", "{tmp}/m.csv"),
         design=EX63, extra_files={"m.csv": CSV}, words=("--output", "m.csv")),
    Case("plot-law-output-folder-missing",
         args=("plot-law", "cycloidal", "-o", "{tmp}/missing/l.png"),
         words=("--output", "does not exist")),
    CliCase("laws-output-dangling-symlink", args=("laws", "-o", "{tmp}/gone.csv"),
            links=(("symbolic", "gone.csv", "nowhere/none.csv"),),
            words=("--output", "gone.csv", "symbolic link", "does not exist")),
    CliCase("laws-output-symlink-to-a-folder", args=("laws", "-o", "{tmp}/dir.csv"),
            links=(("symbolic", "dir.csv", "catalogs"),),
            words=("--output", "dir.csv", "directory")),
    # ---------------------------------------- control characters from files, escaped
    CliCase("control-characters-in-an-unknown-motor",
            args=("size", "{design}", "--motor", f"X{ESC}[2J"), design=EX63,
            words=("--motor", "X\\x1b[2J"), absent=RAW),
    CliCase("control-characters-in-loaded-motor-ids",
            args=("size", "{design}", "--motor", "NOPE"), design=EVIL_DESIGN,
            catalog=EVIL_CATALOG, words=("--motor", "EVIL\\x1b[31mRED\\u202eX\\r\\x07\\x08"),
            absent=RAW),
    CliCase("control-characters-in-a-law-spec",
            args=("size", "{design}"),
            design=edited("book/ex6_3.yaml", set={"laws": [f"harm{ESC}[8monic"]},
                          delete=("check",)),
            words=("laws", "harm\\x1b[8monic"), absent=RAW),
    CliCase("control-characters-in-a-file-name",
            args=("size", "{tmp}/de\x1bsign\u202e.yaml"), design="task: [\n",
            links=(("symbolic", "de\x1bsign\u202e.yaml", "design.yaml"),),
            words=("de\\x1bsign\\u202e.yaml",), absent=(ESC, RLO)),
    CliCase("control-characters-in-the-check-report", exit_code=1,
            args=("check", "{design}"), design=EVIL_DESIGN, catalog=EVIL_CATALOG,
            absent=RAW),
    CliCase("control-characters-in-the-sizing-table", exit_code=0,
            args=("size", "{design}", "--all"), design=EVIL_DESIGN, catalog=EVIL_CATALOG,
            absent=RAW),
    CliCase("control-characters-in-markdown", exit_code=0,
            args=("size", "{design}", "--all", "-f", "md"), design=EVIL_DESIGN,
            catalog=EVIL_CATALOG, absent=RAW),
    CliCase("control-characters-in-a-catalog-listing", exit_code=0,
            args=("catalog", "list", "{catalog}"), catalog=EVIL_CATALOG, absent=RAW),
    CliCase("control-characters-in-a-motor-shown", exit_code=0,
            args=("catalog", "show", EVIL_ID, "-c", "{catalog}"), catalog=EVIL_CATALOG,
            absent=RAW),
]


def make_links(case: Case, folder: Path) -> None:
    """The links of a CliCase; a hard link's target is written first (the case's design or
    catalog, which case_files rewrites in place, keeping the link)."""
    for kind, name, target in getattr(case, "links", ()):
        path, real = folder / name, folder / target
        if kind == "hard":
            if not real.exists():
                real.write_text(case.design if target == "design.yaml" else case.catalog or "",
                                encoding="utf-8")
            path.hardlink_to(real)
        else:
            path.symlink_to(os.path.relpath(real, path.parent))


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_input(case: Case, tmp_path: Path) -> None:
    make_links(case, tmp_path)
    result = run_case(case, tmp_path)
    for raw in getattr(case, "absent", ()):
        assert raw not in result.stdout and raw not in result.stderr, repr(raw)
    for kind, name, _ in getattr(case, "links", ()):
        if kind == "symbolic":
            assert (tmp_path / name).is_symlink(), f"{name} is no longer a link"


def test_the_cases_are_many_and_distinct() -> None:
    assert len(CASES) >= 35
    assert len({c.id for c in CASES}) == len(CASES)


def test_every_rank_key_is_in_the_help() -> None:
    """The --rank-by help text and the error list the keys of RankKey (no key forgotten)."""
    from cli_run import run_cli

    from sizer.sizing.ranking import RANK_ALIASES, RankKey

    text = " ".join(run_cli("size", "--help").stdout.split())
    for key in (*(k.value for k in RankKey), *RANK_ALIASES):
        assert key in text


def test_csv_and_json_keep_the_exact_names(tmp_path: Path) -> None:
    """Control characters stay as they are in CSV (quoted where needed) and JSON."""
    import csv
    import json

    from cli_run import run_cli

    catalog = tmp_path / "motors.yaml"
    catalog.write_text(EVIL_CATALOG, encoding="utf-8")
    result = run_cli("catalog", "list", str(catalog), "-f", "csv", "-o", str(tmp_path / "m.csv"))
    assert result.returncode == 0, result.stderr
    with open(tmp_path / "m.csv", newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    assert rows[1][0] == EVIL_ID and len(rows) == 5 and len({len(r) for r in rows}) == 1
    listed = json.loads(run_cli("catalog", "list", str(catalog), "-f", "json").stdout)
    assert [m["id"] for m in listed["motors"]].count(EVIL_ID) == 1


@pytest.mark.parametrize(("raw", "shown"), [
    ("a\x1b[2Jb", "a\\x1b[2Jb"), ("x\ry", "x\\ry"), ("bell\x07", "bell\\x07"),
    ("back\bspace", "back\\x08space"), ("nul\x00", "nul\\x00"), ("del\x7f", "del\\x7f"),
    ("c1\x9b31m", "c1\\x9b31m"), ("\u202egnp.exe", "\\u202egnp.exe"),
    ("zero\u200bwidth", "zero\\u200bwidth"), ("iso\u2066late", "iso\\u2066late"),
    ("tab\there", "tab\\there"), ("two\nlines", "two\\nlines"),
    ("HG-KN43J µ Ω ü 中", "HG-KN43J µ Ω ü 中"),
], ids=repr)
def test_printable_escapes_terminal_controls_only(raw: str, shown: str) -> None:
    from sizer.report.printable import printable

    assert printable(raw) == shown
    assert printable(printable(raw)) == printable(raw)  # escaping twice changes nothing
    assert printable("one\ntwo\x1b", keep_newlines=True) == "one\ntwo\\x1b"


def test_the_rich_table_shows_names_escaped() -> None:
    """On a terminal (rich, with its own colour codes) the names' controls are escaped."""
    import io

    from rich.console import Console

    from sizer.report.rich_table import print_rich_table
    from sizer.report.table import Column, make_table

    buffer = io.StringIO()
    console = Console(file=buffer, force_terminal=True, width=120, highlight=False)
    table = make_table([Column("id", "left"), Column(f"x{ESC}", "right")],
                       [[EVIL_ID, "1"]], title=f"T{RLO}itle\x07")
    print_rich_table(table, console=console)
    text = buffer.getvalue()
    for raw in (RLO, "\x07", "\b", "\r", f"{ESC}[31mRED"):
        assert raw not in text, repr(raw)
    assert "EVIL\\x1b[31mRED\\u202eX\\r\\x07\\x08" in text and "T\\u202eitle\\x07" in text
