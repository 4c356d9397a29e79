"""Bad inputs of the reading layer (issue 10): what is not a regular file, files too big or
not UTF-8 text, YAML bombs and deep nesting, huge integers, non-finite numbers, and law specs
and unit texts that would make a parser work without bound. The limits are in
sizer.input_limits (documented in docs/input-files.md)."""

from __future__ import annotations

import contextlib
import os
import threading
from pathlib import Path

import pytest
from bad_input_cases import EXAMPLES, Case, assert_clean_answer, edited, run_case
from cli_run import run_cli

from sizer.input_limits import (
    MAX_CATALOG_BYTES,
    MAX_DESIGN_BYTES,
    MAX_INT_DIGITS,
    MAX_LAW_SPEC_CHARS,
    MAX_SCALAR_CHARS,
)
from sizer.io.loader import read_catalog

BASE = "book/ex6_3.yaml"
"""The fast base design: one harmonic law, one motor of book-examples."""
TEXT = (EXAMPLES / BASE).read_text(encoding="utf-8")
CATALOG = (EXAMPLES / "catalogs" / "example-servo.yaml").read_text(encoding="utf-8")


def _set(field: str, value: object) -> str:
    return edited(BASE, set={field: value})


def _law(spec: str) -> str:
    return edited(BASE, set={"laws": [spec], "check.law": spec})


def _bomb(levels: int = 9) -> str:
    """The billion laughs: level k holds 10 aliases of level k-1, 10^levels nodes in all."""
    lines = ['l0: &l0 ["lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol"]']
    for k in range(1, levels + 1):
        lines.append(f"l{k}: &l{k} [" + ", ".join([f"*l{k - 1}"] * 10) + "]")
    return "\n".join(lines) + "\n"


def _catalog_with(old: str, new: str) -> str:
    assert old in CATALOG
    return CATALOG.replace(old, new, 1)


HUGE = int("1" + "0" * (MAX_INT_DIGITS - 1))  # 400 digits: a Python int, beyond any float
OVER_FLOAT = 2 * 10**308  # 309 digits: few enough digits, still too large for a float
CSV = "Model,J,Tc,Tp,n\nA1,1.2,0.64,1.9,3000\n"
CSV_ARGS = ("catalog", "import", "{tmp}/motors.csv", "--map", "Model=id", "--map",
            "J=inertia:kg*cm^2", "--map", "Tc=continuous_torque:N*m", "--map",
            "Tp=peak_torque:N*m", "--map", "n=rated_speed:rpm", "--source", "test",
            "-o", "{tmp}/out.yaml")
GEARBOX_DESIGN = edited(BASE, set={"transmission": {"type": "gearbox", "catalog": "gears.yaml"}})

CASES = [
    # ---- not a regular file, not found
    Case("design-dev-zero", args=("size", "/dev/zero"),
         words=("/dev/zero", "character device", "only regular files")),
    Case("design-dev-urandom", args=("check", "/dev/urandom"),
         words=("/dev/urandom", "character device")),
    Case("catalog-option-dev-zero", design=TEXT,
         args=("size", "{design}", "--catalog", "/dev/zero"),
         words=("/dev/zero", "character device", "only regular files")),
    Case("catalog-entry-dev-zero", design=_set("motors", ["/dev/zero"]),
         words=("/dev/zero", "character device"), fields=("motors",)),
    Case("design-directory", args=("size", "{tmp}/catalogs"),
         words=("catalogs", "is a directory")),
    Case("design-missing", args=("size", "{tmp}/nowhere.yaml"),
         words=("nowhere.yaml", "file not found")),
    Case("design-name-too-long", args=("size", "{tmp}/" + "x" * 300 + ".yaml"),
         words=("xxxx", "too long")),
    Case("catalog-validate-dev-zero", args=("catalog", "validate", "/dev/zero"),
         words=("/dev/zero", "character device")),
    Case("gearbox-catalog-dev-zero", design=edited(BASE, set={
        "transmission": {"type": "gearbox", "catalog": "/dev/zero"}}),
         words=("/dev/zero", "character device"), fields=("transmission.catalog",)),
    Case("csv-import-dev-zero", args=(*CSV_ARGS[:2], "/dev/zero", *CSV_ARGS[3:]),
         words=("/dev/zero", "character device", "only regular files")),
    # ---- not UTF-8 text
    Case("design-binary-nul", args=("size", "{tmp}/bin.yaml"),
         extra_files={"bin.yaml": b"\x7fELF\x02\x01\x01\x00\x00\x00\xff\xfe" * 50},
         words=("bin.yaml:1", "NUL bytes", "not UTF-8")),
    Case("design-binary-no-nul", args=("size", "{tmp}/bin.yaml"),
         extra_files={"bin.yaml": b"name: x\n" + bytes(range(0x80, 0x100)) * 4},
         words=("bin.yaml:2", "not UTF-8", "0x80")),
    Case("design-utf16-bom", args=("size", "{tmp}/u16.yaml"),
         extra_files={"u16.yaml": TEXT.encode("utf-16")},
         words=("u16.yaml", "UTF-16", "save it as UTF-8")),
    Case("design-utf16-no-bom", args=("size", "{tmp}/u16.yaml"),
         extra_files={"u16.yaml": TEXT.encode("utf-16-le")},
         words=("u16.yaml:1", "NUL bytes", "UTF-16")),
    Case("design-latin1-line", args=("size", "{tmp}/l1.yaml"),
         extra_files={"l1.yaml": TEXT.replace("name: B&M", "name: Caf\xe9").encode("latin-1")},
         words=("l1.yaml:8", "not UTF-8", "0xe9")),
    Case("catalog-utf16", design=TEXT, args=("size", "{design}", "--catalog", "{tmp}/c.yaml"),
         extra_files={"c.yaml": CATALOG.encode("utf-16")}, words=("c.yaml", "UTF-16")),
    Case("csv-import-utf16", args=CSV_ARGS, extra_files={"motors.csv": CSV.encode("utf-16")},
         words=("motors.csv", "UTF-16", "--encoding")),
    Case("design-nul-in-middle", args=("size", "{tmp}/n.yaml"),
         extra_files={"n.yaml": TEXT.replace("task:", "task:\x00").encode()},
         words=("n.yaml:9", "NUL")),
    Case("design-control-character", design=TEXT + "note: ring\x07\n",
         words=("design.yaml:20", "unacceptable character")),
    # ---- YAML bounded work
    Case("design-billion-laughs", design=TEXT + _bomb(),
         words=("design.yaml:", "too many YAML nodes", "alias")),
    Case("catalog-billion-laughs", design=TEXT, args=("size", "{design}", "--catalog", "{catalog}"),
         catalog=CATALOG + _bomb(), words=("motors.yaml:", "too many YAML nodes")),
    Case("gearbox-catalog-billion-laughs", design=GEARBOX_DESIGN,
         extra_files={"gears.yaml": "gearboxes: []\n" + _bomb()},
         words=("gears.yaml:", "too many YAML nodes")),
    Case("design-deep-flow", design="name: " + "[" * 5000 + "]" * 5000 + "\n",
         words=("design.yaml:1", "nested too deeply", "100 levels")),
    Case("design-deep-block", design=TEXT + "".join(" " * i + f"k{i}:\n" for i in range(200)),
         words=("design.yaml:", "nested too deeply")),
    Case("design-long-name", design=_set("name", "x" * (MAX_SCALAR_CHARS + 1)),
         words=("design.yaml:", f"{MAX_SCALAR_CHARS + 1:,} characters", f"{MAX_SCALAR_CHARS:,}"),
         fields=("name",)),
    Case("design-recursive-alias", design=TEXT + "extra: &r [*r]\n",
         words=("design.yaml:20", "extra[0]", "recursive")),
    # ---- huge integers and non-finite numbers where they are written
    Case("ratio-400-digits", design=_set("transmission", {"type": "gearbox", "ratio": HUGE}),
         words=("design.yaml:", "transmission.ratio", "400 digits", "finite"),
         fields=("transmission.ratio",)),
    Case("inertia-beyond-float", design=_set("load.inertia", OVER_FLOAT),
         words=("design.yaml:6", "load.inertia", "309 digits", "too large", "finite"),
         fields=("load.inertia",)),
    Case("duration-5000-digits", design=TEXT.replace("duration: minimize",
                                                     "duration: 1" + "0" * 5000),
         words=("design.yaml:11", "task.duration", "5001 digits"), fields=("task.duration",)),
    Case("catalog-torque-huge-int", design=TEXT,
         args=("size", "{design}", "--catalog", "{catalog}"),
         catalog=_catalog_with("peak_torque: 0.95 N*m", f"peak_torque: {OVER_FLOAT}"),
         words=("motors.yaml:", "motors[0].peak_torque", "too large")),
    Case("inertia-dot-inf", design=TEXT.replace("inertia: 0.25 kg*m^2", "inertia: .inf"),
         words=("design.yaml:13", "load.inertia", "not a finite number"),
         fields=("load.inertia",)),
    Case("dwell-float-overflow", design=TEXT.replace("duration: minimize",
                                                     "duration: 0.2\n  dwell: 1.0e+999"),
         words=("design.yaml:12", "task.dwell", "not a finite number"), fields=("task.dwell",)),
    Case("margin-NaN-spelled", design=_set("limits", {"torque_margin": "NaN %"}),
         words=("design.yaml:", "limits.torque_margin", "finite"),
         fields=("limits.torque_margin",)),
    Case("catalog-speed-Infinity", design=TEXT, args=("size", "{design}", "--catalog", "{catalog}"),
         catalog=_catalog_with("max_speed: 5000 rev/min", "max_speed: Infinity rpm"),
         words=("motors.yaml:", "motors[0].max_speed", "not a finite number")),
    Case("torque-minus-inf", design=_set("load.torque", "-inf N*m"),
         words=("design.yaml:", "load.torque", "not a finite number"), fields=("load.torque",)),
    Case("duration-1e999-text", design=_set("task.duration", "1e999 s"),
         words=("design.yaml:", "task.duration", "finite"), fields=("task.duration",)),
    Case("duration-1e400-text", design=_set("task.duration", "1e400 s"),
         words=("design.yaml:", "task.duration", "finite"), fields=("task.duration",)),
    # ---- law specs
    Case("law-exponent-huge", design=_law("trapezoidal(alpha=1e999999999)"),
         words=("design.yaml:", "laws[0]", "out of range", "exponent of at most 400")),
    Case("law-fraction-huge", design=_law("trapezoidal(alpha=1/1" + "0" * 400 + ")"),
         words=("design.yaml:", "laws[0]", "at most 100 characters")),
    Case("law-beyond-float", design=_law("trapezoidal(alpha=1e400)"),
         words=("design.yaml:", "laws[0]", "beyond the float range", "finite number")),
    Case("law-fraction-beyond-float", args=("law", "trapezoidal(alpha=1e300/1e-300)",
                                            "--displacement", "1 rad", "--duration", "1 s"),
         words=("1e300/1e-300", "beyond the float range")),
    Case("law-nan", design=_law("trapezoidal(alpha=NaN)"),
         words=("design.yaml:", "laws[0]", "not a finite number", "1/3")),
    Case("law-minus-infinity", design=_law("trapezoidal(alpha=-Infinity)"),
         words=("design.yaml:", "laws[0]", "not a finite number")),
    Case("law-power-operator", design=_law("poly5(x=10**10**10)"),
         words=("design.yaml:", "laws[0]", "cannot read law spec")),
    Case("law-too-long", design=_law("trapezoidal(alpha=" + "1" * MAX_LAW_SPEC_CHARS + ")"),
         words=("design.yaml:", "laws[0]", f"the limit is {MAX_LAW_SPEC_CHARS}")),
    Case("law-unicode-digit", design=_law("trapezoidal(alpha=\u0661/3)"),
         words=("design.yaml:", "laws[0]", "cannot read law spec")),
    Case("law-nested-parentheses", design=_law("trapezoidal(" * 20 + ")" * 20),
         words=("design.yaml:", "laws[0]", "cannot read law spec")),
    Case("law-command-exponent", args=("law", "trapezoidal(alpha=1e999999999)",
                                       "--displacement", "1 rad", "--duration", "1 s"),
         words=("trapezoidal(alpha=1e999999999)", "exponent of at most 400")),
    # ---- unit texts before pint
    Case("unit-power-huge", design=_set("task.displacement", "1 m^99999999"),
         words=("design.yaml:", "task.displacement", "power", "at most 12")),
    Case("unit-power-float", design=_set("load.inertia", "1 kg*m**1e9"),
         words=("design.yaml:", "load.inertia"), fields=("load.inertia",)),
    Case("unit-tower-of-powers", design=_set("load.torque", "1 10**10**10*N*m"),
         words=("design.yaml:", "load.torque", "power must be a plain number")),
    Case("unit-caret-tower", design=_set("load.inertia", "1 9^9^9 kg*m^2"),
         words=("design.yaml:", "load.inertia", "power must be a plain number")),
    Case("unit-unicode-digits", design=_set("task.displacement", "\u0661\u0662 deg"),
         words=("design.yaml:", "task.displacement", "expected an angle")),
    Case("unit-text-long", design=_set("load.inertia", "1 " + "kg*" * 60 + "m^2"),
         words=("design.yaml:", "load.inertia", "characters")),
    Case("unit-offset-celsius", design=_set("load.inertia", "0.25 degC"),
         words=("design.yaml:", "load.inertia", "expected an inertia")),
    Case("unit-offset-fahrenheit-product", design=_set("load.torque", "1 degF*m"),
         words=("design.yaml:", "load.torque")),
    Case("unit-kelvin-speed", design=_set("task.displacement", "3 K"),
         words=("design.yaml:", "task.displacement", "expected an angle")),
    # ---- a well-formed file the reader must still accept
    Case("design-utf8-bom-accepted", design="\ufeff" + TEXT, exit_code=0),
]


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_input(case: Case, tmp_path: Path) -> None:
    run_case(case, tmp_path)


class _FifoGuard:
    """Unblocks a reader stuck on ``fifo`` after ``seconds`` (a hang is a failure, not a hang)."""

    def __init__(self, fifo: Path, seconds: float = 20.0) -> None:
        self.fifo, self.fired, self.done = fifo, False, threading.Event()
        self.thread = threading.Thread(target=self._run, args=(seconds,), daemon=True)

    def _run(self, seconds: float) -> None:
        if self.done.wait(seconds):
            return
        self.fired = True
        while not self.done.is_set():  # open for writing (and close): the reader sees EOF
            with contextlib.suppress(OSError):
                os.close(os.open(self.fifo, os.O_WRONLY | os.O_NONBLOCK))
            self.done.wait(0.05)

    def __enter__(self) -> _FifoGuard:
        self.thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.done.set()
        self.thread.join()
        assert not self.fired, "the command blocked on the FIFO"


FIFO_CASES = [
    Case("fifo-design", args=("size", "{tmp}/pipe.yaml"),
         words=("pipe.yaml", "named pipe (FIFO)", "only regular files")),
    Case("fifo-catalog-option", design=TEXT,
         args=("size", "{design}", "--catalog", "{tmp}/pipe.yaml"),
         words=("pipe.yaml", "named pipe (FIFO)")),
    Case("fifo-catalog-entry", design=_set("motors", ["pipe.yaml"]),
         words=("pipe.yaml", "named pipe (FIFO)"), fields=("motors",)),
    Case("fifo-gearbox-catalog", design=edited(BASE, set={
        "transmission": {"type": "gearbox", "catalog": "pipe.yaml"}}),
         words=("pipe.yaml", "named pipe (FIFO)"), fields=("transmission.catalog",)),
    Case("fifo-csv-import", args=(*CSV_ARGS[:2], "{tmp}/pipe.yaml", *CSV_ARGS[3:]),
         words=("pipe.yaml", "named pipe (FIFO)")),
]


@pytest.mark.parametrize("case", FIFO_CASES, ids=str)
def test_a_fifo_is_refused_without_blocking(case: Case, tmp_path: Path) -> None:
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    with _FifoGuard(fifo):
        run_case(case, tmp_path)


def test_a_50_mb_design_is_refused_by_its_size(tmp_path: Path) -> None:
    line = "# " + "padding " * 12 + "\n"
    (tmp_path / "huge.yaml").write_text(TEXT + line * (50_000_000 // len(line)), encoding="utf-8")
    assert (tmp_path / "huge.yaml").stat().st_size > 50_000_000
    run_case(Case("huge-design", args=("size", "{tmp}/huge.yaml")), tmp_path)
    result = run_cli("size", str(tmp_path / "huge.yaml"))
    assert "huge.yaml: the file is too big: 47.7 MiB, the limit is 1.0 MiB" in result.stderr


def test_a_design_just_over_the_limit_is_refused_and_one_at_it_is_read(tmp_path: Path) -> None:
    padding = MAX_DESIGN_BYTES - len(TEXT.encode())
    at_limit = TEXT + "#" * (padding - 1) + "\n"
    assert len(at_limit.encode()) == MAX_DESIGN_BYTES
    (tmp_path / "at.yaml").write_text(at_limit, encoding="utf-8")
    (tmp_path / "over.yaml").write_text(at_limit + "\n", encoding="utf-8")
    assert run_cli("size", str(tmp_path / "at.yaml")).returncode == 0
    run_case(Case("over", args=("size", "{tmp}/over.yaml"),
                  words=("over.yaml", "too big", "1.0 MiB")), tmp_path)


def test_a_catalog_over_its_limit_is_refused(tmp_path: Path) -> None:
    big = tmp_path / "big.yaml"
    with big.open("w", encoding="utf-8") as handle:
        handle.write(CATALOG)
        handle.write(("#" * 1023 + "\n") * (MAX_CATALOG_BYTES // 1024 + 1))
    run_case(Case("big-catalog", design=TEXT, args=("size", "{design}", "--catalog", str(big)),
                  words=("big.yaml", "too big", "32.0 MiB")), tmp_path)


def _catalog_of(count: int) -> str:
    """A catalog of ``count`` motors with units and a curve each, as a generator writes it.

    Most figures are bare SI numbers: every text with a unit costs a pint parse (issue 11).
    """
    lines = ["catalog: generated", "source: test", "motors:"]
    for index in range(count):
        lines += [f"  - id: M{index:05d}", f"    part_number: PN-{index:05d}",
                  f"    inertia: {0.1 + index * 1e-4:.4f} kg*cm^2",
                  "    continuous_torque: 1.3", "    peak_torque: 3.8",
                  "    rated_speed: 3000 rpm", "    max_speed: 523.6",
                  "    continuous_curve:"]
        lines += [f"      - {{speed: {s}, torque: {1.3 - s * 1e-3:.5f}}}"  # SI: pint is slow
                  for s in range(0, 501, 100)]
    return "\n".join(lines) + "\n"


def test_a_catalog_of_thousands_of_motors_loads(tmp_path: Path) -> None:
    path = tmp_path / "big.yaml"
    path.write_text(_catalog_of(4_000), encoding="utf-8")
    motors = read_catalog(path).motors
    assert len(motors) == 4_000
    assert motors[-1].id == "M03999"
    assert motors[-1].inertia == pytest.approx((0.1 + 3999e-4) * 1e-4)
    assert len(motors[0].continuous_curve) == 6


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads any file")
def test_a_design_without_read_permission(tmp_path: Path) -> None:
    (tmp_path / "secret.yaml").write_text(TEXT, encoding="utf-8")
    (tmp_path / "secret.yaml").chmod(0)
    result = run_cli("size", str(tmp_path / "secret.yaml"))  # run_case could not read it
    assert_clean_answer(result, 2, ("secret.yaml", "permission denied"))
