"""Bad inputs, numbers: extreme but accepted values and figures that do not exist (issue 10).

Every case reaches the core (no user error): exit 0 or 1 with clean outputs in every format,
no warning, no ``nan``/``inf`` printed (run_case), JSON that is valid JSON (NaN and
Infinity refused), and where a figure does not exist ``n/a`` with the reason (no feasible
duration because friction or a constant load exceeds the peak torque, an unbounded jerk or
inertia ratio).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml
from bad_input_cases import Case, edited, run_case

EX61 = "book/ex6_1-6_2.yaml"  # h = 15 rad in T = 3 s
EX63 = "book/ex6_3.yaml"  # h = 0.6 rad, duration: minimize
VENDOR = "vendor-ballscrew.yaml"  # a linear axis: gear + ball screw


def motors(*rows: tuple[str, float, float, float, float]) -> str:
    """A catalog of (id, inertia, tau_c, tau_p, v_n) motors, SI."""
    return yaml.safe_dump({"catalog": "extreme", "motors": [
        {"id": i, "inertia": j, "continuous_torque": c, "peak_torque": p, "rated_speed": v}
        for i, j, c, p, v in rows]}, sort_keys=False)


def on_catalog(example: str, **changes: object) -> str:
    """An example sized on the case's catalog (motors.yaml), checking motor m0."""
    return edited(example, set={"motors": "motors.yaml", "check.motor": "m0", **changes})


def size(fmt: str) -> tuple[str, ...]:
    return ("size", "{design}", "--all", "-f", fmt)


def check(fmt: str = "table") -> tuple[str, ...]:
    return ("check", "{design}", "-f", fmt)


FRICTION = {"load.friction": "100 N*m"}  # above every book motor's peak torque (<= 30)
NO_DURATION = ("no duration is feasible",)

CASES = [
    # durations at the ends of the plausible range
    Case("duration-1us-table", size("table"), design=edited(EX61, set={"task.duration": "1e-6 s"}),
         exit_code=0, fields=("task.duration",)),
    Case("duration-1us-json", size("json"), design=edited(EX61, set={"task.duration": "1e-6 s"}),
         exit_code=0, fields=("task.duration",)),
    Case("duration-1us-check", check(), design=edited(EX61, set={"task.duration": "1e-6 s"}),
         exit_code=1, fields=("task.duration",)),
    Case("duration-1e6s-csv", size("csv"), design=edited(EX61, set={"task.duration": "1e6 s"}),
         exit_code=0, fields=("task.duration",)),
    Case("duration-1e6s-md", size("md"), design=edited(EX61, set={"task.duration": "1e6 s"}),
         exit_code=0, fields=("task.duration",)),
    Case("dwell-1e6s-return-json", size("json"),
         design=edited(EX63, set={"task.dwell": "1e6 s", "task.return": True}),
         exit_code=0, fields=("task.dwell", "task.return")),
    Case("dwell-1us-return-csv", size("csv"),
         design=edited(EX63, set={"task.dwell": "1e-6 s", "task.return": True}),
         exit_code=0, fields=("task.dwell",)),
    # displacements
    Case("displacement-1e6rad-check-json", check("json"),
         design=edited(EX61, set={"task.displacement": "1e6 rad"}), exit_code=1,
         fields=("task.displacement",)),
    Case("displacement-1e-6rad-minimize-table", size("table"),
         design=edited(EX63, set={"task.displacement": "1e-6 rad"}), exit_code=0,
         fields=("task.displacement",)),
    # load inertias, damping
    Case("inertia-1e-12-minimize-json", size("json"),
         design=edited(EX63, set={"load.inertia": "1e-12 kg*m^2"}), exit_code=0,
         fields=("load.inertia",)),
    Case("inertia-1e6-minimize-md", size("md"),
         design=edited(EX63, set={"load.inertia": "1e6 kg*m^2"}), exit_code=0,
         fields=("load.inertia",)),
    Case("inertia-1e6-check", check(), design=edited(EX61, set={"load.inertia": "1e6 kg*m^2"}),
         exit_code=1, fields=("load.inertia",)),
    Case("damping-1e6-minimize-table", size("table"),
         design=edited(EX63, set={"load.damping": "1e6 N*m*s/rad"}), exit_code=0,
         fields=("load.damping",)),
    # T_min does not exist: friction or a constant load above the peak torque
    Case("friction-above-peak-table", size("table"), design=edited(EX63, set=FRICTION),
         exit_code=0, fields=("load.friction",)),
    Case("friction-above-peak-md", size("md"), design=edited(EX63, set=FRICTION),
         exit_code=0, fields=("load.friction",)),
    Case("friction-above-peak-csv", size("csv"), design=edited(EX63, set=FRICTION),
         exit_code=0, fields=("load.friction",)),
    Case("friction-above-peak-json", size("json"), design=edited(EX63, set=FRICTION),
         exit_code=0, fields=("load.friction",)),
    Case("friction-above-peak-check", check(), design=edited(EX63, set=FRICTION),
         exit_code=1, fields=("load.friction",)),
    Case("friction-above-peak-check-json", check("json"), design=edited(EX63, set=FRICTION),
         exit_code=1, fields=("load.friction",)),
    Case("friction-above-peak-plot", ("plot", "{design}", "-o", "{tmp}/p.png"),
         design=edited(EX63, set=FRICTION), exit_code=2,
         words=("no law with a feasible duration", "design.yaml"), fields=("load.friction",)),
    Case("friction-1e6-fixed-duration-check", check(),
         design=edited(EX61, set={"load.friction": "1e6 N*m"}), exit_code=1,
         fields=("load.friction",)),
    Case("torque-above-peak-minimize-json", size("json"),
         design=edited(EX63, set={"load.torque": "1e4 N*m", "task.dwell": "0.1 s"}),
         exit_code=0, fields=("load.torque",)),
    # transmissions
    Case("ratio-1e-3-json", size("json"),
         design=edited(EX61, set={"transmission": {"type": "gearbox", "ratio": 1e-3}}),
         exit_code=0, fields=("transmission.ratio",)),
    Case("ratio-1e5-minimize-table", size("table"),
         design=edited(EX63, set={"transmission": {"type": "gearbox", "ratio": 1e5}}),
         exit_code=0, fields=("transmission.ratio",)),
    Case("ratio-1e5-efficiency-0.01-md", size("md"),
         design=edited(EX63, set={"transmission": {"type": "gearbox", "ratio": 1e5,
                                                   "efficiency": 0.01}}),
         exit_code=0, fields=("transmission.ratio", "transmission.efficiency")),
    Case("efficiency-0.01-check-json", check("json"),
         design=edited(EX61, set={"transmission": {"type": "gearbox", "ratio": 1,
                                                   "efficiency": 0.01}}),
         exit_code=1, fields=("transmission.efficiency",)),
    Case("ballscrew-efficiency-0.01-csv", size("csv"),
         design=edited(VENDOR, set={"transmission[1].efficiency": 0.01}), exit_code=0,
         fields=("transmission[1].efficiency",)),
    Case("ballscrew-mass-1e-6kg-json", size("json"),
         design=edited(VENDOR, set={"load.mass": "1e-6 kg", "load.friction": "0 N"}),
         exit_code=0, fields=("load.mass",)),
    # motors at the edges
    Case("motor-rated-speed-1e-3-minimize-json", size("json"),
         design=on_catalog(EX63), catalog=motors(("m0", 0.0, 14.0, 30.0, 1e-3)),
         exit_code=0, fields=("motors[0].rated_speed",)),
    Case("motor-peak-equals-continuous-check", check(),
         design=on_catalog(EX63), catalog=motors(("m0", 0.0, 30.0, 30.0, 6.0)),
         exit_code=0, fields=("motors[0].peak_torque",)),
    Case("motor-tiny-torques-table", size("table"),
         design=on_catalog(EX63), catalog=motors(("m0", 1e-12, 1e-6, 2e-6, 6.0)),
         exit_code=0, fields=("motors[0].continuous_torque",)),
    Case("motor-rotor-inertia-1000-check-json", check("json"),
         design=on_catalog(EX61), catalog=motors(("m0", 1e3, 14.0, 30.0, 6.0)),
         exit_code=1, fields=("motors[0].inertia",)),
    # zero-ish load: only the speed bound is left
    Case("nearly-no-load-minimize-csv", size("csv"),
         design=on_catalog(EX63, **{"load.inertia": "1e-12 kg*m^2"}),
         catalog=motors(("m0", 0.0, 14.0, 30.0, 6.0)), exit_code=0, fields=("load.inertia",)),
    # unbounded requirements: n/a with the reason
    Case("inertia-ratio-rotor-0-check", check(),
         design=edited(EX61, set={"limits": {"inertia_ratio": 10}}), exit_code=1,
         fields=("limits.inertia_ratio",)),
    Case("inertia-ratio-rotor-0-json", check("json"),
         design=edited(EX61, set={"limits": {"inertia_ratio": 10}}), exit_code=1,
         fields=("limits.inertia_ratio",)),
    Case("jerk-limit-trapezoid-json", size("json"),
         design=edited(EX61, set={"limits": {"max_jerk": "1e6 rad/s^3"},
                                  "laws": ["trapezoidal(alpha=1/3)", "cycloidal"]}),
         exit_code=0, fields=("limits.max_jerk",)),
    Case("jerk-limit-trapezoid-table", size("table"),
         design=edited(EX61, set={"limits": {"max_jerk": "1e6 rad/s^3"},
                                  "laws": ["trapezoidal(alpha=1/3)", "cycloidal"]}),
         exit_code=0, fields=("limits.max_jerk",)),
    # law, laws, plot and report of extreme moves
    Case("law-1e6rad-in-1us-json",
         ("law", "cycloidal", "--displacement", "1e6 rad", "--duration", "1e-6 s", "-f", "json",
          "-n", "11"), exit_code=0),
    Case("law-1e6s-csv",
         ("law", "poly5", "--displacement", "1e-6 rad", "--duration", "1e6 s", "-f", "csv",
          "-n", "11"), exit_code=0),
    Case("laws-md", ("laws", "--law", "cycloidal", "--law", "double_s(alpha=1/2, beta=1/2)",
                     "-f", "md"), exit_code=0),
    Case("plot-ratio-1e5", ("plot", "{design}", "--acceleration", "-o", "{tmp}/p.png"),
         design=edited(EX63, set={"transmission": {"type": "gearbox", "ratio": 1e5}}),
         exit_code=0, fields=("transmission.ratio",)),
    Case("plot-duration-1us", ("plot", "{design}", "-o", "{tmp}/p.png"),
         design=edited(EX61, set={"task.duration": "1e-6 s"}), exit_code=0,
         fields=("task.duration",)),
    Case("plot-law-1us", ("plot-law", "cycloidal", "--displacement", "1e6 rad",
                          "--duration", "1e-6 s", "-o", "{tmp}/p.png"), exit_code=0),
    Case("report-inertia-1e6", ("report", "{design}", "-o", "{tmp}/report", "--best", "1"),
         design=edited(EX63, set={"load.inertia": "1e6 kg*m^2"}), exit_code=0,
         fields=("load.inertia",)),
    Case("report-friction-above-peak", ("report", "{design}", "-o", "{tmp}/report"),
         design=edited(EX63, set=FRICTION), exit_code=0, fields=("load.friction",)),
]


STDOUT_WORDS: dict[str, tuple[str, ...]] = {
    "duration-1us-check": ("FAIL", "speed: 3e+07 rad/s against 10 rad/s"),
    "inertia-1e6-check": ("FAIL",),
    "friction-above-peak-check": (*NO_DURATION, "rms: 100 N*m against 14 N*m"),
    "friction-above-peak-check-json": NO_DURATION,
    "friction-1e6-fixed-duration-check": ("FAIL", "peak"),
    "inertia-ratio-rotor-0-check": ("inertia_ratio: unbounded", "inertia is 0"),
    "inertia-ratio-rotor-0-json": ("inertia_ratio: unbounded (the motor's inertia is 0)",),
    "jerk-limit-trapezoid-table": ("jerk: unbounded (the law has jerk impulses)",),
    "motor-rated-speed-1e-3-minimize-json": ("speed",),
}
"""Words the answer on stdout must hold (a check's verdict, a reason beside an n/a)."""


def _refuse(constant: str) -> float:
    raise ValueError(f"{constant} in JSON output")


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_input(case: Case, tmp_path: Path) -> None:
    result = run_case(case, tmp_path)
    for word in STDOUT_WORDS.get(case.id, ()):
        assert word in result.stdout, f"{word!r} not in stdout\n{result.stdout[-3000:]}"
    if "json" in case.args and result.returncode in (0, 1):
        json.loads(result.stdout, parse_constant=_refuse)
    report = tmp_path / "report" / "report.md"
    if case.args[0] == "report":
        text = report.read_text(encoding="utf-8")
        assert "nan" not in text.lower().split() and " inf " not in text
    if "friction-above-peak" in case.id and case.args[0] == "size":
        assert "no duration is feasible" in result.stdout
        if "json" in case.args:
            rows = json.loads(result.stdout)["results"]
            assert all(r["duration"] is None and r["reason"] for r in rows)
        if case.args[-1] in ("table", "md"):
            assert "n/a" in result.stdout and "no operating point" in result.stdout


def test_unbounded_checks_are_null_with_a_reason(tmp_path: Path) -> None:
    """The inertia ratio over a rotor inertia of 0 and the jerk of a trapezoid: no number
    (null), the reason beside it, and the row's reason names it."""
    case = next(c for c in CASES if c.id == "jerk-limit-trapezoid-json")
    rows = json.loads(run_case(case, tmp_path).stdout)["results"]
    trapezoid = next(r for r in rows if r["law"] == "trapezoidal")
    jerk = next(c for c in trapezoid["checks"] if c["name"] == "jerk")
    assert jerk["value"] is None and jerk["margin"] is None and not jerk["passed"]
    assert "jerk impulses" in jerk["reason"]
    cycloidal = next(r for r in rows if r["law"] == "cycloidal")
    assert all(c["reason"] is None for c in cycloidal["checks"])


def test_enough_cases() -> None:
    assert len(CASES) >= 30
    assert len({c.id for c in CASES}) == len(CASES)
