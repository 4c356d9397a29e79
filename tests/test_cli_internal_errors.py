"""A bug in sizer is not a failed check: exit code 3, one line, the traceback on request;
``check`` goes on with the other files; Ctrl-C and a closed pipe end quietly."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from cli_run import run_cli

import sizer
from sizer.cli import app as app_module
from sizer.cli.exit_codes import ExitCode

ROOT = Path(__file__).resolve().parents[1]
EX63 = str(ROOT / "examples" / "book" / "ex6_3.yaml")
EX64 = str(ROOT / "examples" / "book" / "ex6_4.yaml")


def design_text(duration: str = "0.25 s") -> str:
    """Example 6.3 (T_min = 0.1934 s) with a given duration, named after its file."""
    text = Path(EX63).read_text(encoding="utf-8").replace("name: B&M Example 6.3\n", "")
    return text.replace("duration: minimize", f"duration: {duration}")


def crash(*args, **kwargs):
    raise ZeroDivisionError("float division by zero")


def internal_lines(stderr: str) -> list[str]:
    return [line for line in stderr.splitlines() if line.startswith("internal error")]


def assert_internal_error(result: subprocess.CompletedProcess[str], *words: str) -> str:
    assert result.returncode == 3, (result.stdout, result.stderr)
    assert "Traceback" not in result.stderr, result.stderr
    lines = internal_lines(result.stderr)
    assert len(lines) == 1 and len(result.stderr.splitlines()) == 1, result.stderr
    line = lines[0]
    for word in ("ZeroDivisionError: float division by zero", "this is a bug in sizer",
                 sizer.__version__, "please report it", "--debug", *words):
        assert word in line, line
    return line


@pytest.fixture(autouse=True)
def no_debug_env(monkeypatch) -> None:
    monkeypatch.delenv("SIZER_DEBUG", raising=False)


def test_a_crash_in_the_sizing_is_exit_code_3_and_one_line(monkeypatch) -> None:
    monkeypatch.setattr("sizer.sizing.size_design", crash)
    line = assert_internal_error(run_cli("size", EX63), "'sizer size'")
    assert "test_cli_internal_errors.py" not in line  # where in sizer, not in the test
    # the innermost frame of sizer: the API function the command calls (sizer.api.size)
    assert "(at sizer/api.py:" in line and " in size)" in line


def test_debug_option_shows_the_traceback(monkeypatch) -> None:
    monkeypatch.setattr("sizer.sizing.size_design", crash)
    result = run_cli("--debug", "size", EX63)
    assert result.returncode == 3
    assert "Traceback (most recent call last)" in result.stderr
    assert len(internal_lines(result.stderr)) == 1
    assert result.stderr.rstrip().splitlines()[-1].startswith("internal error")


@pytest.mark.parametrize("value", ["1", "yes"])
def test_sizer_debug_environment_shows_the_traceback(monkeypatch, value: str) -> None:
    monkeypatch.setattr("sizer.sizing.size_design", crash)
    monkeypatch.setenv("SIZER_DEBUG", value)
    result = run_cli("size", EX63)
    assert result.returncode == 3 and "Traceback" in result.stderr


def test_debug_does_not_stick_to_the_next_run(monkeypatch) -> None:
    monkeypatch.setattr("sizer.sizing.size_design", crash)
    run_cli("--debug", "size", EX63)
    assert_internal_error(run_cli("size", EX63))


def test_sizer_debug_0_is_off(monkeypatch) -> None:
    monkeypatch.setattr("sizer.sizing.size_design", crash)
    monkeypatch.setenv("SIZER_DEBUG", "0")
    assert_internal_error(run_cli("size", EX63))


def test_a_crash_while_writing_is_an_internal_error(monkeypatch, tmp_path: Path) -> None:
    monkeypatch.setattr("sizer.report.document.render_text", crash)
    assert_internal_error(run_cli("laws", "-o", str(tmp_path / "laws.txt")), "'sizer laws'")
    assert not (tmp_path / "laws.txt").exists()


def test_a_crash_in_a_catalog_subcommand_names_it(monkeypatch) -> None:
    monkeypatch.setattr("sizer.catalog_tools.catalog_summaries", crash)
    assert_internal_error(run_cli("catalog", "list"), "'sizer catalog list'")


def test_check_reports_the_crash_of_one_file_and_checks_the_others(monkeypatch,
                                                                   tmp_path: Path) -> None:
    import sizer.sizing

    real = sizer.sizing.check_design

    def crash_on_b(design):
        if design.name == "b":
            crash()
        return real(design)

    monkeypatch.setattr("sizer.sizing.check_design", crash_on_b)
    files = []
    for name in ("a", "b", "c"):
        path = tmp_path / f"{name}.yaml"
        path.write_text(design_text())
        files.append(str(path))
    result = run_cli("check", *files)
    assert result.returncode == 3, result.stderr
    lines = internal_lines(result.stderr)
    assert len(lines) == 1 and "b.yaml" in lines[0] and "a.yaml" not in lines[0]
    assert "Traceback" not in result.stderr
    assert result.stdout.count("PASS") + result.stdout.count("FAIL") == 2
    assert "check a" in result.stdout and "check c" in result.stdout


def test_check_exit_code_is_the_gravest(monkeypatch, tmp_path: Path) -> None:
    """3 if any internal error, else 2 if any invalid file, else 1 if any check failed."""
    good = tmp_path / "good.yaml"
    good.write_text(design_text("0.25 s"))
    failing = tmp_path / "failing.yaml"  # shorter than T_min = 0.1934 s
    failing.write_text(design_text("0.1 s"))
    invalid = tmp_path / "invalid.yaml"
    invalid.write_text("task: [\n")
    assert run_cli("check", str(good)).returncode == 0
    assert run_cli("check", str(good), str(failing)).returncode == 1
    assert run_cli("check", str(failing), str(invalid), str(good)).returncode == 2

    import sizer.sizing

    real = sizer.sizing.check_design
    monkeypatch.setattr("sizer.sizing.check_design",
                        lambda d: crash() if d.name == "good" else real(d))
    result = run_cli("check", str(invalid), str(good), str(failing))
    assert result.returncode == 3
    assert len([x for x in result.stderr.splitlines() if x.startswith("error:")]) == 1
    assert len(internal_lines(result.stderr)) == 1
    assert "FAIL" in result.stdout


def test_keyboard_interrupt_is_one_line_and_130(monkeypatch) -> None:
    def interrupt(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr("sizer.sizing.size_design", interrupt)
    result = run_cli("size", EX63)
    assert result.returncode == 130
    assert result.stderr == "interrupted\n"


def test_user_errors_are_still_exit_code_2() -> None:
    result = run_cli("size", str(ROOT / "missing.yaml"))
    assert result.returncode == 2 and result.stderr.startswith("error:")
    assert len(result.stderr.splitlines()) == 1


def test_exit_codes_are_documented_in_the_help() -> None:
    for args in (("--help",), ("check", "--help")):
        text = " ".join(run_cli(*args).stdout.split())
        assert "3" in text and "internal error" in text, text
    root = " ".join(run_cli("--help").stdout.split())
    assert "--debug" in root and "2 bad input" in root


def _subprocess(code: str, *args: str, env: dict[str, str] | None = None,
                ) -> subprocess.CompletedProcess[str]:
    environment = {**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}
    environment.pop("SIZER_DEBUG", None)
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True,
                          text=True, timeout=120, env=environment, cwd=ROOT)


PATCHED_MAIN = ("import sys, sizer.sizing\n"
                "def crash(*a, **k): raise ZeroDivisionError('float division by zero')\n"
                "sizer.sizing.size_design = crash\n"
                "from sizer.cli.app import main\n"
                "main(sys.argv[1:])\n")


def test_an_internal_error_in_a_real_process() -> None:
    assert_internal_error(_subprocess(PATCHED_MAIN, "size", EX64), "'sizer size'")
    debug = _subprocess(PATCHED_MAIN, "--debug", "size", EX64)
    assert debug.returncode == 3 and "Traceback" in debug.stderr


def test_typer_prints_no_traceback_box_of_its_own() -> None:
    """typer's pretty exceptions are off: with the hook installed a crash stays one line."""
    result = _subprocess(PATCHED_MAIN, "size", EX64)
    assert "╭" not in result.stderr and "Traceback" not in result.stderr


@pytest.mark.parametrize("args", [("laws",), ("laws", "--format", "csv"),
                                  ("schema", "design")], ids=" ".join)
def test_a_closed_pipe_prints_no_traceback(args: tuple[str, ...]) -> None:
    """Like ``sizer laws | head -0``: the reader is gone before sizer writes."""
    process = subprocess.Popen([sys.executable, "-m", "sizer", *args],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=ROOT,
                               env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert process.stdout is not None
    process.stdout.close()
    _, stderr = process.communicate(timeout=120)
    assert stderr == b"", stderr
    assert process.returncode == ExitCode.BROKEN_PIPE


def test_a_pipe_closed_while_writing_is_quiet(monkeypatch) -> None:
    class ClosedPipe:
        def write(self, text: str) -> int:
            raise BrokenPipeError(32, "Broken pipe")

        def flush(self) -> None:
            raise BrokenPipeError(32, "Broken pipe")

        def isatty(self) -> bool:
            return False

    monkeypatch.setattr(sys, "stdout", ClosedPipe())
    assert app_module.run(["laws"]) == ExitCode.BROKEN_PIPE


def test_help_imports_no_numerical_or_file_libraries() -> None:
    """``sizer --help`` stays quick: the error handling, escaping and output checks import
    nothing heavy (numpy, scipy, pint, yaml, pydantic, matplotlib) before a command runs."""
    code = ("import sys, io, contextlib\n"
            "from sizer.cli.app import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    try:\n"
            "        main(['--help'])\n"
            "    except SystemExit:\n"
            "        pass\n"
            "heavy = {'numpy', 'scipy', 'pint', 'yaml', 'pydantic', 'matplotlib'}\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] in heavy))\n")
    result = _subprocess(code)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "[]"
