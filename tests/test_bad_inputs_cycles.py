"""Bad values of the fields of a design's ``cycle:`` (issue 32), rule by rule: non-finite,
wrong type, wrong unit, out of range, empty, beyond the segment limit. Each is answered
by one ``error:`` line naming the file, the LINE of the field (found by composing the YAML,
tests/bad_input_lines.py) and the field's path, exit code 2.

tests/test_cycle_input.py holds one case per field (and the rules between fields); the
cases here are the rules it does not exercise. The largest accepted cycle,
MAX_CYCLE_SEGMENTS segments, is sized under a 2 GiB address-space limit.
"""

from __future__ import annotations

import resource
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml
from bad_input_cases import EXAMPLES, Case, assert_well_formed, edited, run_case
from bad_input_lines import at

from sizer.input_limits import MAX_CYCLE_SEGMENTS

R = "indexing-duty-cycle.yaml"
"""Rotary: segments[0] a free move, [1] a dwell, [2] a free move, [3] a dwell with a torque."""
L = "flying-saw.yaml"
"""Linear: segments[0] a move to the line speed, [1] a run, [2] [3] moves, [4] a dwell."""
S = "cycle.segments"
NAN, INF = float("nan"), float("inf")
FINITE = "not a finite number"


def bad(id: str, base: str, path: str, value: Any, words: tuple[str, ...], field: str,
        more: dict[str, Any] | None = None, delete: tuple[str, ...] = ()) -> Case:
    """``path`` of example ``base`` set to ``value``: the message names the file, the
    line and the field of ``path`` and holds ``words``."""
    text = edited(base, set={**(more or {}), path: value}, delete=delete)
    return Case(id, design=text, words=(*at(text, path), *words), fields=(field,))


M0, R1, D1 = f"{S}[0].move", f"{S}[1].run", f"{S}[1].dwell"
LM0, LD4 = f"{S}[0].move", f"{S}[4].dwell"
FM, FR, FD = "cycle.segments.move", "cycle.segments.run", "cycle.segments.dwell"
WEIGHTS = {"cycle.share": "weights"}

MOVES = [
    bad("move-displacement-nan", R, f"{M0}.displacement", NAN, (FINITE,), f"{FM}.displacement"),
    bad("move-displacement-a-list", R, f"{M0}.displacement", [1, 2], ("expected",),
        f"{FM}.displacement"),
    bad("move-displacement-a-mass", R, f"{M0}.displacement", "5 kg", ("expected an angle",),
        f"{FM}.displacement"),
    bad("move-displacement-empty", R, f"{M0}.displacement", "", ("expected",),
        f"{FM}.displacement"),
    bad("move-duration-nan", R, f"{M0}.duration", NAN, (FINITE,), f"{FM}.duration"),
    bad("move-duration-inf-text", R, f"{M0}.duration", "inf s", (FINITE,), f"{FM}.duration"),
    bad("move-duration-a-length", R, f"{M0}.duration", "5 m", ("expected a time",),
        f"{FM}.duration"),
    bad("move-duration-too-long", R, f"{M0}.duration", "1e7 s", ("[1e-6, 1e6] s",),
        f"{FM}.duration"),
    bad("move-law-a-number", R, f"{M0}.law", 5, ("expected a law spec",), f"{FM}.law"),
    bad("move-law-empty", R, f"{M0}.law", "", ("law spec",), f"{FM}.law"),
    bad("move-start-speed-nan", R, f"{M0}.start_speed", NAN, (FINITE,), f"{FM}.start_speed"),
    bad("move-start-speed-a-torque", R, f"{M0}.start_speed", "5 N*m",
        ("expected an angular speed", "rotary axis"), f"{FM}.start_speed"),
    bad("move-start-speed-out-of-range", R, f"{M0}.start_speed", "1e9 rad/s",
        ("rad/s",), f"{FM}.start_speed"),
    bad("move-end-speed-inf", R, f"{M0}.end_speed", INF, (FINITE,), f"{FM}.end_speed"),
    bad("move-end-speed-a-list", R, f"{M0}.end_speed", [1], ("expected",), f"{FM}.end_speed"),
    bad("move-start-acceleration-nan", R, f"{M0}.start_acceleration", NAN, (FINITE,),
        f"{FM}.start_acceleration"),
    bad("move-start-acceleration-a-list", R, f"{M0}.start_acceleration", [1, 2],
        ("expected",), f"{FM}.start_acceleration"),
    bad("move-end-acceleration-inf-text", R, f"{M0}.end_acceleration", "inf rad/s^2",
        (FINITE,), f"{FM}.end_acceleration"),
    bad("move-end-acceleration-a-speed", R, f"{M0}.end_acceleration", "5 rad/s",
        ("expected",), f"{FM}.end_acceleration"),
    bad("move-weight-nan", R, f"{M0}.weight", NAN, (FINITE,), f"{FM}.weight", WEIGHTS),
    bad("move-weight-a-mass", R, f"{M0}.weight", "5 kg", ("expected a ratio",),
        f"{FM}.weight", WEIGHTS),
    bad("move-weight-huge", R, f"{M0}.weight", 1e300, ("[1e-6, 1e6]",), f"{FM}.weight",
        WEIGHTS),
    bad("move-inertia-nan", R, f"{M0}.inertia", NAN, (FINITE,), f"{FM}.inertia"),
    bad("move-inertia-a-mass", R, f"{M0}.inertia", "5 kg", ("expected an inertia",),
        f"{FM}.inertia"),
    bad("move-inertia-huge", R, f"{M0}.inertia", "1e300 kg*m^2", ("kg*m^2",), f"{FM}.inertia"),
    bad("move-mass-nan", L, f"{LM0}.mass", NAN, (FINITE,), f"{FM}.mass"),
    bad("move-mass-a-force", L, f"{LM0}.mass", "5 N", ("expected a mass",), f"{FM}.mass"),
    bad("move-mass-negative", L, f"{LM0}.mass", "-1 kg", ("kg",), f"{FM}.mass"),
    bad("move-torque-inf", R, f"{M0}.torque", INF, (FINITE,), f"{FM}.torque"),
    bad("move-torque-a-mass", R, f"{M0}.torque", "5 kg", ("expected a torque",),
        f"{FM}.torque"),
    bad("move-force-nan", L, f"{LM0}.force", NAN, (FINITE,), f"{FM}.force"),
    bad("move-force-a-mass", L, f"{LM0}.force", "5 kg", ("expected a force",), f"{FM}.force"),
    bad("move-name-a-bool", R, f"{M0}.name", True, ("expected text",), f"{FM}.name"),
    bad("move-name-nan", R, f"{M0}.name", NAN, (FINITE,), f"{FM}.name"),
]

RUNS = [
    bad("run-speed-nan", L, f"{R1}.speed", NAN, (FINITE,), f"{FR}.speed"),
    bad("run-speed-a-list", L, f"{R1}.speed", [1, 2], ("expected",), f"{FR}.speed"),
    bad("run-speed-an-angular-speed", L, f"{R1}.speed", "30 rpm",
        ("expected a linear speed", "linear axis"), f"{FR}.speed"),
    bad("run-speed-out-of-range", L, f"{R1}.speed", "1e9 m/s", ("m/s",), f"{FR}.speed"),
    bad("run-duration-nan", L, f"{R1}.duration", NAN, (FINITE,), f"{FR}.duration"),
    bad("run-duration-a-length", L, f"{R1}.duration", "5 m", ("expected a time",),
        f"{FR}.duration"),
    bad("run-duration-negative", L, f"{R1}.duration", "-1 s", ("[1e-6, 1e6] s",),
        f"{FR}.duration"),
    bad("run-displacement-nan", L, f"{R1}.displacement", NAN, (FINITE,),
        f"{FR}.displacement", delete=(f"{R1}.duration",)),
    bad("run-displacement-an-angle", L, f"{R1}.displacement", "90 deg", ("linear axis",),
        f"{FR}.displacement", delete=(f"{R1}.duration",)),
    bad("run-displacement-huge", L, f"{R1}.displacement", "1e300 m", ("[1e-7, 1e4] m",),
        f"{FR}.displacement", delete=(f"{R1}.duration",)),
    bad("run-displacement-too-slow", L, f"{R1}.displacement", "9 km",
        ("gives a duration", "[1e-6, 1e6] s"), f"{FR}.displacement",
        {f"{R1}.speed": "1 mm/s", f"{S}[0].move.end_speed": "1 mm/s",
         f"{S}[2].move.start_speed": "1 mm/s"}, delete=(f"{R1}.duration",)),
    bad("run-mass-inf", L, f"{R1}.mass", INF, (FINITE,), f"{FR}.mass"),
    bad("run-mass-a-force", L, f"{R1}.mass", "5 N", ("expected a mass",), f"{FR}.mass"),
    bad("run-force-nan", L, f"{R1}.force", NAN, (FINITE,), f"{FR}.force"),
    bad("run-force-out-of-range", L, f"{R1}.force", "1e12 N", ("N",), f"{FR}.force"),
    bad("run-inertia-a-list", L, f"{R1}.inertia", [1], ("inertia",), f"{FR}.inertia"),
    bad("run-torque-nan", L, f"{R1}.torque", NAN, (FINITE,), f"{FR}.torque"),
    bad("run-name-a-bool", L, f"{R1}.name", False, ("expected text",), f"{FR}.name"),
    bad("run-name-empty", L, f"{R1}.name", "", ("empty",), f"{FR}.name"),
]

DWELLS = [
    bad("dwell-duration-nan", R, f"{D1}.duration", NAN, (FINITE,), f"{FD}.duration"),
    bad("dwell-duration-a-list", R, f"{D1}.duration", [1, 2], ("expected a time",),
        f"{FD}.duration"),
    bad("dwell-duration-an-angle", R, f"{D1}.duration", "90 deg", ("expected a time",),
        f"{FD}.duration"),
    bad("dwell-duration-negative", R, f"{D1}.duration", "-1 s", ("[1e-6, 1e6] s",),
        f"{FD}.duration"),
    bad("dwell-duration-null", R, f"{D1}.duration", None, ("duration",), f"{FD}.duration"),
    bad("dwell-weight-inf", R, f"{D1}.weight", INF, (FINITE,), f"{FD}.weight", WEIGHTS),
    bad("dwell-weight-zero", R, f"{D1}.weight", 0, ("[1e-6, 1e6]",), f"{FD}.weight", WEIGHTS),
    bad("dwell-torque-nan", R, f"{D1}.torque", NAN, (FINITE,), f"{FD}.torque"),
    bad("dwell-torque-a-force", R, f"{D1}.torque", "5 N", ("expected a torque",),
        f"{FD}.torque"),
    bad("dwell-torque-huge", R, f"{D1}.torque", "1e300 N*m", ("N*m",), f"{FD}.torque"),
    bad("dwell-force-nan", L, f"{LD4}.force", NAN, (FINITE,), f"{FD}.force"),
    bad("dwell-force-a-torque", L, f"{LD4}.force", "5 N*m", ("expected a force",),
        f"{FD}.force"),
    bad("dwell-name-a-list", R, f"{D1}.name", ["a"], ("expected text",), f"{FD}.name"),
]

CYCLE = [
    bad("share-a-list", R, "cycle.share", ["equal"], ("equal", "weights"), "cycle.share"),
    bad("share-a-bool", R, "cycle.share", True, ("equal", "weights"), "cycle.share"),
    bad("cycle-time-nan", R, "cycle.cycle_time", NAN, (FINITE,), "cycle.cycle_time"),
    bad("cycle-time-an-angle", R, "cycle.cycle_time", "90 deg", ("expected a time",),
        "cycle.cycle_time"),
    bad("cycle-time-huge", R, "cycle.cycle_time", 1e300, ("[1e-6, 1e6] s",),
        "cycle.cycle_time"),
    bad("rate-nan", R, "cycle.rate", NAN, (FINITE,), "cycle.rate"),
    bad("rate-a-list", R, "cycle.rate", [50], ("expected a rate",), "cycle.rate"),
    bad("rate-zero", R, "cycle.rate", "0 /min", ("1/s",), "cycle.rate"),
    bad("minimize-a-bool", R, "cycle.minimize", True, ("expected text",), "cycle.minimize"),
    bad("minimize-empty", R, "cycle.minimize", "", ("empty",), "cycle.minimize"),
    bad("closed-nan", R, "cycle.closed", NAN, (FINITE,), "cycle.closed"),
    bad("closed-a-number", R, "cycle.closed", 1, ("true or false",), "cycle.closed"),
    bad("segments-null", R, S, None, ("expected a list",), "cycle.segments"),
    bad("segments-a-number", R, S, 3, ("expected a list",), "cycle.segments"),
    bad("segment-empty-mapping", R, f"{S}[1]", {}, ("exactly one kind",), "cycle.segments"),
    bad("segments-over-the-limit", R, S,
        [{"move": {"displacement": "1 deg", "duration": "0.1 s"}}] * (MAX_CYCLE_SEGMENTS + 1),
        (f"{MAX_CYCLE_SEGMENTS + 1} segments", f"the limit is {MAX_CYCLE_SEGMENTS}",
         "MAX_CYCLE_SEGMENTS"), "cycle.segments"),
]

CASES = [*MOVES, *RUNS, *DWELLS, *CYCLE]


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_cycle_field(case: Case, tmp_path: Path) -> None:
    run_case(case, tmp_path)


def test_case_ids_are_unique_and_fields_are_the_models() -> None:
    assert_well_formed(CASES)


def test_over_the_limit_is_refused_before_the_segments_are_read(tmp_path: Path) -> None:
    """200,000 nodes of segments (the design's node limit) are refused by their count,
    not read one by one: the message names the count, whatever the items hold."""
    from cli_run import run_cli

    data = yaml.safe_load((EXAMPLES / R).read_text(encoding="utf-8"))
    data["cycle"]["segments"] = [{"wait": 1}] * 60_000
    path = tmp_path / "design.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    result = run_cli("size", str(path))
    assert result.returncode == 2
    assert "a cycle of 60000 segments: the limit is" in result.stderr
    assert "wait" not in result.stderr


# ------------------------------------------------------------- the largest accepted cycle

GIB = 1024**3

_UNDER_LIMIT = """
import resource, sys
resource.setrlimit(resource.RLIMIT_AS, ({limit}, {limit}))
from sizer.cli.app import main
main(sys.argv[1:])
"""


def largest_cycle(n: int) -> dict[str, Any]:
    """examples/indexing-duty-cycle.yaml with ``n`` segments (moves of 10 deg in 0.1 s and
    dwells of 0.05 s, the first move free: the cycle is minimized), one law."""
    data = yaml.safe_load((EXAMPLES / R).read_text(encoding="utf-8"))
    segments: list[dict[str, Any]] = []
    for i in range(n // 2):
        segments.append({"move": {"displacement": "10 deg",
                                  "duration": "free" if i == 0 else "0.1 s"}})
        segments.append({"dwell": {"duration": "0.05 s"}})
    data["cycle"] = {"segments": segments}
    data["laws"] = ["poly5"]
    data["motors"] = str(EXAMPLES / "catalogs" / "example-servo.yaml")
    return data


@pytest.mark.skipif(not hasattr(resource, "RLIMIT_AS"), reason="needs RLIMIT_AS")
def test_a_large_cycle_is_sized_under_2_gib(tmp_path: Path) -> None:
    """A cycle of 100 segments is sized in a process whose address space is limited to
    2 GiB (the largest, MAX_CYCLE_SEGMENTS, takes longer than a test should: its command
    and figures are in benchmarks/README.md)."""
    path = tmp_path / "design.yaml"
    path.write_text(yaml.safe_dump(largest_cycle(100), sort_keys=False), encoding="utf-8")
    result = subprocess.run([sys.executable, "-c", _UNDER_LIMIT.format(limit=2 * GIB),
                             "size", str(path), "-j", "1"],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr[-2000:]
    assert "a cycle of 100 segments" in result.stdout
    assert "MemoryError" not in result.stderr and "Traceback" not in result.stderr


# ------------------------------------------------------------ the `segments` command's options

DUTY = edited(R)


def option(id: str, args: tuple[str, ...], words: tuple[str, ...]) -> Case:
    """``sizer segments DESIGN ARGS``: the message names the option (no file line: the
    mistake is on the command line)."""
    return Case(id, args=("segments", "{design}", *args), design=DUTY, words=words)


OPTIONS = [
    option("segments-law-empty", ("--law", ""), ("--law", "cannot read law spec")),
    option("segments-law-auto-on-a-cycle", ("--law", "trapezoidal(alpha=auto)"),
           ("--law", "auto", "cycle of segments")),
    option("segments-law-unknown", ("--law", "sinusoid"), ("--law", "unknown law")),
    option("segments-law-nan", ("--law", "trapezoidal(alpha=nan)"), ("--law", "finite")),
    option("segments-law-too-long", ("--law", "x" * 600), ("--law", "the limit is 500")),
    option("segments-motor-unknown", ("--motor", "NOPE"), ("--motor", "unknown motor")),
    option("segments-motor-empty", ("--motor", ""), ("--motor", "unknown motor")),
    option("segments-format-unknown", ("-f", "xml"), ("--format", "xml")),
    option("segments-envelope-unknown", ("--envelope", "round"), ("--envelope", "round")),
    option("segments-catalog-missing", ("--catalog", "{tmp}/none.yaml"),
           ("--catalog", "none.yaml", "not found")),
    option("segments-output-a-folder", ("-o", "{tmp}"), ("--output", "directory")),
    option("segments-output-the-design", ("-o", "{design}"), ("--output", "is an input")),
]


@pytest.mark.parametrize("case", OPTIONS, ids=str)
def test_bad_segments_option(case: Case, tmp_path: Path) -> None:
    run_case(case, tmp_path)
