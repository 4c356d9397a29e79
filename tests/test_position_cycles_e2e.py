"""Design files with loads of the position in a cycle, sized end to end (issue 38): a task
with a return move and a ``cycle:`` of segments through sizer.size and the CLI, against
the independent evaluation of tests/test_position_cycles.py. Needs the engine to size them
(sizer.sizing.engine.cycle_model and sizer.sizing.samples._position call
sizer.sizing.linkage_move.position_model)."""

from __future__ import annotations

import math

import pytest
from bad_input_cases import edited
from cli_run import run_cli as run
from position_reference import ROTOR_GEAR, falling
from test_position_cycles import ARM, Independent

TABLE_POINTS = [["0 deg", "0 N*m"], ["50 deg", "1 N*m"], ["100 deg", "0 N*m"]]


def _design(tmp_path, set_: dict, delete: tuple[str, ...] = ()):
    text = edited("book/ex6_1-6_2.yaml", set={
        "load": {"inertia": "0.05 kg*m^2", "damping": "0.01 N*m*s/rad", "friction": "0.2 N*m",
                 "gravity": {"mass": "2 kg", "radius": "250 mm", "offset": "-30 deg"}},
        "transmission": {"type": "gearbox", "ratio": 5, "efficiency": 1.0,
                         "inertia": f"{ROTOR_GEAR} kg*m^2"},
        "laws": ["cycloidal"], **set_}, delete=delete)
    path = tmp_path / "arm.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_a_return_move_sized_end_to_end(tmp_path):
    import sizer

    h, T, dwell = math.pi / 2, 0.45, 0.3
    path = _design(tmp_path, {"task": {"displacement": "90 deg", "duration": f"{T} s",
                                       "dwell": f"{dwell} s", "return": True}})
    motor = falling(1)
    row = sizer.size(path, motors=[motor]).results[0]
    ref = Independent(ARM, [("move", h, T, "cycloidal"), ("dwell", dwell),
                            ("move", -h, T, "cycloidal"), ("dwell", dwell)], 1.0)
    assert row.duration == pytest.approx(T, rel=1e-15)  # each move's T, as any task
    assert row.peak_torque == pytest.approx(ref.peak(motor.inertia), rel=1e-9)
    assert row.rms_torque == pytest.approx(ref.rms(motor.inertia), rel=1e-9)


def test_a_cycle_sized_end_to_end(tmp_path):
    import sizer

    segments = [("move", math.radians(60.0), 0.3, "cycloidal"), ("dwell", 0.2),
                ("move", math.radians(40.0), 0.25, "cycloidal"), ("dwell", 0.1),
                ("move", -math.radians(100.0), 0.3, "cycloidal"), ("dwell", 0.2)]
    cycle = [{"move": {"displacement": f"{math.degrees(s[1])!r} deg",
                       "duration": f"{s[2]} s", "name": f"s{i}"}} if s[0] == "move"
             else {"dwell": {"duration": f"{s[1]} s", "name": f"s{i}"}}
             for i, s in enumerate(segments)]
    path = _design(tmp_path, {"cycle": {"closed": True, "segments": cycle}}, ("task",))
    motor = falling(1)
    row = sizer.size(path, motors=[motor]).results[0]
    ref = Independent(ARM, segments, 1.0)
    assert row.duration == pytest.approx(1.35, rel=1e-15)  # the cycle time
    assert row.peak_torque == pytest.approx(ref.peak(motor.inertia), rel=1e-9)
    assert row.rms_torque == pytest.approx(ref.rms(motor.inertia), rel=1e-9)


def test_a_cycle_with_a_table_in_the_cli(tmp_path):
    path = _design(tmp_path, {
        "load": {"inertia": "0.12 kg*m^2", "friction": "0.4 N*m",
                 "gravity": {"mass": "3 kg", "radius": "200 mm", "offset": "-30 deg"},
                 "torque_table": {"points": TABLE_POINTS}},
        "transmission": {"type": "gearbox", "ratio": 10, "efficiency": "90 %"},
        "motors": ["mitsubishi-hg-kn"], "laws": ["cycloidal", "poly5"],
        "cycle": {"closed": True, "segments": [
            {"move": {"displacement": "60 deg", "duration": "0.3 s", "name": "up"}},
            {"dwell": {"duration": "0.2 s", "name": "hold"}},
            {"move": {"displacement": "40 deg", "name": "higher"}},
            {"dwell": {"duration": "0.1 s", "name": "place"}},
            {"move": {"displacement": "-100 deg", "name": "down"}},
            {"dwell": {"duration": "0.2 s", "name": "rest"}}]}}, ("task", "check"))
    for args in (("size", str(path)), ("segments", str(path)),
                 ("plot", str(path), "-o", str(tmp_path / "p.png"))):
        out = run(*args)
        assert out.returncode == 0, out.stderr
        assert "Traceback" not in out.stderr and "Warning" not in out.stderr
    assert "down" in run("segments", str(path)).stdout
