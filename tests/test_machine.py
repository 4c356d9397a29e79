"""Several axes on one master (book sec. 5.3): the slowest axis sets the master speed.

The numbers come from closed forms: the book's v_c = min over the axes of
v_max,k / |q_k'|max and sqrt(a_max,k / |q_k''|max) (sec. 5.3) for axes limited by their
load limits only; the RMS bound of eq. (6.2) with a dwell that scales with the machine
cycle, T^3 (T + d) = (J h C_a,rms / tau_c)^2 with T = f T_c, d = g T_c; and for the bus,
the kinetic energy 1/2 J omega^2 a pure inertia returns per stop (eq. 6.1 integrated), or
an independent dense sampling of the closed-form powers.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml
from cli_run import run_cli

from sizer import api
from sizer.errors import UserError

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "machines" / "two-axis-packer.yaml"

BIG = {"id": "big", "inertia": 1e-9, "continuous_torque": 1e4, "peak_torque": 1e5,
       "rated_speed": 1e5}
"""A motor that never limits: the axes are held by their load limits only."""


def axis(name: str, move: str, *, law: str = "cycloidal", h: str = "90 deg",
         motors: list[dict[str, Any]] | None = None, start: str = "0 deg",
         **extra: Any) -> dict[str, Any]:
    task = {"displacement": h, "move": move, **extra.pop("task", {})}
    return {"name": name, "start": start, "task": task,
            "load": extra.pop("load", {"inertia": 0.01}), "laws": [law],
            "motors": motors if motors is not None else [BIG], **extra}


def machine(*axes: dict[str, Any], **master: Any) -> dict[str, Any]:
    return {"name": "m", "machine": {"cycle": "360 deg", **master}, "axes": list(axes)}


# ------------------------------------------------------------------ the master speed
def test_the_slowest_axis_sets_the_master_speed_as_the_book_says() -> None:
    """Sec. 5.3: v_c = min(v_max1/|q1'|max, sqrt(a_max1/|q1''|max), v_max2/..., ...)."""
    h1, m1 = math.radians(90), math.radians(120)   # cycloidal: q' 2h/m, q'' 2 pi h/m^2
    h2, m2 = math.radians(60), math.radians(90)    # poly5: q' 15/8 h/m, q'' 10/sqrt(3) h/m^2
    v1, a1, v2, a2 = 20.0, 400.0, 9.0, 150.0
    data = machine(
        axis("cam1", "120 deg", h="90 deg", limits={"max_speed": v1, "max_acceleration": a1}),
        axis("cam2", "90 deg", law="poly5", h="60 deg", start="200 deg",
             limits={"max_speed": v2, "max_acceleration": a2}),
        master_speed="minimize")
    v_c = min(v1 / (2 * h1 / m1), math.sqrt(a1 / (2 * math.pi * h1 / m1**2)),
              v2 / (15 / 8 * h2 / m2), math.sqrt(a2 / (10 / math.sqrt(3) * h2 / m2**2)))
    result = api.size_machine(data)
    assert result.master_speed == pytest.approx(v_c, rel=1e-9)
    assert result.cycle_time == pytest.approx(2 * math.pi / v_c, rel=1e-9)
    slowest = ("cam1" if min(v1 / (2 * h1 / m1), math.sqrt(a1 / (2 * math.pi * h1 / m1**2)))
               == v_c else "cam2")
    assert result.limiting_axis == slowest and result.feasible
    by_name = {a.name: a for a in result.axes}
    assert by_name["cam2"].phase == pytest.approx(math.radians(200) / v_c, rel=1e-12)
    assert by_name["cam1"].move_time == pytest.approx(m1 / v_c, rel=1e-9)


def test_a_dwell_that_scales_with_the_cycle_gives_the_rms_closed_form() -> None:
    """One RMS-limited axis: T^3 (T + d) = (J h C_a,rms / tau_c)^2, T = f T_c, d = g T_c,
    so T_c = sqrt(J h C / tau_c) / (f^3 (f + g))^(1/4) (cycloidal: C_a,rms = sqrt(2) pi)."""
    J_m, J_l, tau_c, h = 1e-4, 0.02, 2.0, math.pi / 2
    motor = {"id": "m1", "inertia": J_m, "continuous_torque": tau_c, "peak_torque": 1e3,
             "rated_speed": 1e4}
    data = machine(axis("table", "100 deg", h="90 deg", motors=[motor],
                        load={"inertia": J_l}), master_speed="minimize")
    f, g = 100 / 360, 260 / 360
    scale = (J_m + J_l) * h * math.sqrt(2) * math.pi / tau_c
    expected = math.sqrt(scale) / (f**3 * (f + g)) ** 0.25
    result = api.size_machine(data)
    assert result.cycle_time == pytest.approx(expected, rel=1e-9)
    chosen = result.axes[0].chosen
    assert chosen is not None and chosen.limiting == "rms"
    assert chosen.rms_torque == pytest.approx(tau_c, rel=1e-8)


def test_a_load_held_in_the_dwell_enters_the_rms_closed_form() -> None:
    """A constant load torque held during the dwell: RMS^2 = ((J h C/T^2)^2 + tau_l^2) T
    + tau_l^2 d over (T + d) with the move's torque J a + tau_l (mean of a is zero):
    T_c solves (J h C / T^2)^2 f + tau_l^2 (f + g) = tau_c^2 (f + g), T = f T_c."""
    J, tau_c, tau_l, h = 0.01, 1.0, 0.6, math.pi / 2
    motor = {"id": "m1", "inertia": 0.0, "continuous_torque": tau_c, "peak_torque": 1e3,
             "rated_speed": 1e4}
    data = machine(axis("lift", "90 deg", h="90 deg", motors=[motor],
                        load={"inertia": J, "torque": tau_l}), master_speed="minimize")
    f, g = 0.25, 0.75
    C = math.sqrt(2) * math.pi
    # (J h C)^2 / (f T_c)^4 * f = (tau_c^2 - tau_l^2) (f + g)
    T_c = ((J * h * C) ** 2 * f / ((tau_c**2 - tau_l**2) * (f + g))) ** 0.25 / f
    result = api.size_machine(data)
    assert result.cycle_time == pytest.approx(T_c, rel=1e-9)


def test_a_given_master_speed_gives_each_axis_its_durations() -> None:
    data = machine(axis("a", "120 deg"), axis("b", "90 deg", start="90 deg",
                                               task={"return": True}),
                   master_speed="60 rpm")
    result = api.size_machine(data)
    T_c = 1.0
    assert result.cycle_time == pytest.approx(T_c, rel=1e-12) and not result.minimize
    a, b = result.axes
    assert a.move_time == pytest.approx(T_c / 3, rel=1e-12)
    assert a.dwell_time == pytest.approx(2 * T_c / 3, rel=1e-12)
    assert b.move_time == pytest.approx(T_c / 4, rel=1e-12)
    assert b.dwell_time == pytest.approx(T_c / 4, rel=1e-12)  # (360 - 2 x 90) / 2
    assert b.phase == pytest.approx(T_c / 4, rel=1e-12)
    assert a.sizing.results[0].duration == pytest.approx(T_c / 3, rel=1e-12)
    assert a.fastest_cycle_time is None  # searched only with minimize


def test_cycle_time_is_the_master_speed_in_other_words() -> None:
    by_speed = api.size_machine(machine(axis("a", "120 deg"), master_speed="30 rpm"))
    by_time = api.size_machine(machine(axis("a", "120 deg"), cycle_time="2 s"))
    assert by_time.master_speed == pytest.approx(by_speed.master_speed, rel=1e-12)


def test_an_axis_no_master_speed_suits_makes_the_machine_infeasible() -> None:
    weak = {"id": "weak", "inertia": 1e-5, "continuous_torque": 0.1, "peak_torque": 0.3,
            "rated_speed": 300}
    data = machine(axis("a", "120 deg"),
                   axis("lift", "90 deg", motors=[weak], load={"inertia": 0.01, "torque": 0.5}),
                   master_speed="minimize")
    result = api.size_machine(data)
    assert not result.feasible and "lift" in result.reason
    assert result.axes[1].chosen is None and result.axes[1].fastest_cycle_time is None


# ------------------------------------------------------------------ the shared bus
def _inertia_axis(name: str, start: str) -> dict[str, Any]:
    return axis(name, "90 deg", h="180 deg", start=start, load={"inertia": 0.05})


def test_stops_apart_return_each_axis_kinetic_energy() -> None:
    """Lossless inertias (motor inertia 0): each stop returns 1/2 J omega_max^2 with
    omega_max = 2 h / T (cycloidal); apart in the cycle, the bus gets both."""
    motor = {**BIG, "inertia": 0.0}
    data = machine({**_inertia_axis("a", "0 deg"), "motors": [motor]},
                   {**_inertia_axis("b", "180 deg"), "motors": [motor]},
                   master_speed="60 rpm")
    result = api.size_machine(data)
    T = 0.25
    omega = 2 * math.pi / T
    stop = 0.5 * 0.05 * omega**2
    bus = result.bus
    assert bus is not None
    assert bus.regenerated_energy == pytest.approx(2 * stop, rel=1e-5)
    assert bus.motoring_energy == pytest.approx(2 * stop, rel=1e-5)
    assert bus.worst_stop_energy == pytest.approx(stop, rel=1e-5)
    assert bus.resistor_power == pytest.approx(2 * stop / 1.0, rel=1e-5)  # no capacitance
    assert bus.separate_resistor_power == pytest.approx(bus.resistor_power, rel=1e-9)


def test_overlapping_axes_feed_each_other_on_the_bus() -> None:
    """b starts as a is halfway: a's braking feeds b's acceleration. The energy the sum
    returns, from a dense sampling of the closed-form powers P = J omega alpha."""
    motor = {**BIG, "inertia": 0.0}
    data = machine({**_inertia_axis("a", "0 deg"), "motors": [motor]},
                   {**_inertia_axis("b", "45 deg"), "motors": [motor]},
                   master_speed="60 rpm", )
    data["bus"] = {"capacitance": "1000 uF", "voltage": "560 V", "braking_threshold": "600 V"}
    result = api.size_machine(data)
    J, h, T = 0.05, math.pi, 0.25
    t = np.linspace(0.0, 1.0, 2_000_001)

    def power(t0: float) -> np.ndarray:
        u = np.clip((t - t0) / T, 0.0, 1.0)
        inside = (t >= t0) & (t <= t0 + T)
        omega = h / T * (1 - np.cos(2 * np.pi * u))
        alpha = h / T**2 * 2 * np.pi * np.sin(2 * np.pi * u)
        return np.where(inside, J * omega * alpha, 0.0)

    total = power(0.0) + power(0.125)
    returned = np.trapezoid(np.maximum(-total, 0.0), t)
    bus = result.bus
    assert bus is not None
    assert bus.regenerated_energy == pytest.approx(returned, rel=1e-4)
    stop = 0.5 * J * (2 * h / T) ** 2
    assert bus.regenerated_energy < 2 * stop * 0.99  # shared: less than the two stops
    assert bus.absorbable_energy == pytest.approx(0.5 * 1e-3 * (600**2 - 560**2), rel=1e-12)
    # each run of negative power is a stop; the capacitors take E_C of each
    negative = np.maximum(-total, 0.0)
    edges = np.flatnonzero(np.diff((total < 0).astype(int)))
    runs = np.split(np.arange(t.size), edges + 1)
    stops = [np.trapezoid(negative[r], t[r]) for r in runs if (total[r] < 0).any()]
    assert len(stops) >= 2
    resistor = sum(max(e - bus.absorbable_energy, 0.0) for e in stops)
    assert bus.worst_stop_energy == pytest.approx(max(stops), rel=1e-4)
    assert bus.resistor_energy == pytest.approx(resistor, rel=1e-3, abs=1e-9)
    assert bus.separate_resistor_power == pytest.approx(2 * stop, rel=1e-5)


def test_a_bus_resistor_limit_is_a_machine_verdict() -> None:
    motor = {**BIG, "inertia": 0.0}
    data = machine({**_inertia_axis("a", "0 deg"), "motors": [motor]},
                   master_speed="60 rpm")
    data["bus"] = {"braking_resistor_power": "10 W"}
    result = api.size_machine(data)
    assert not result.feasible and result.reason.startswith("bus:")
    assert result.axes[0].chosen is not None


# ------------------------------------------------------------------ input errors
@pytest.mark.parametrize(("edit", "field", "words"), [
    (lambda d: d["axes"][0]["task"].update(move="400 deg"), "axes[0].task.move", "do not fit"),
    (lambda d: d["axes"][0]["task"].update(dwell="100 deg"), "axes[0].task.dwell", "add up"),
    (lambda d: d["axes"][1].update(name="a"), "axes[1].name", "twice"),
    (lambda d: d["axes"][0].update(start="360 deg"), "axes[0].start", "below"),
    (lambda d: d["axes"][0].update(cycle={"segments": []}), "axes[0].cycle", "task"),
    (lambda d: d["machine"].update(cycle_time="1 s"), "machine.master_speed", "one of"),
    (lambda d: d["axes"][1]["load"].update(inertia="-1 kg*m^2"), "axes[1].load.inertia", ""),
    (lambda d: d["axes"][1].update(laws=["no_such_law"]), "axes[1].laws[0]", ""),
])
def test_bad_machines_are_located(edit, field: str, words: str, tmp_path: Path) -> None:
    data = machine(axis("a", "120 deg"), axis("b", "90 deg"), master_speed="60 rpm")
    edit(data)
    with pytest.raises(UserError) as caught:
        api.load_machine(data)
    assert caught.value.field == field and words in caught.value.message
    assert caught.value.line is not None


def test_the_cli_sizes_the_example_machine() -> None:
    out = run_cli("size", str(EXAMPLE), "--format", "json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["format"] == "sizer.machine/1" and data["feasible"] is True
    assert [a["name"] for a in data["axes"]] == ["table", "pusher"]
    assert data["machine"]["limiting_axis"] in ("table", "pusher")
    assert data["bus"]["absorbable_energy"] == pytest.approx(
        0.5 * 1100e-6 * (375**2 - 325**2), rel=1e-12)
    again = run_cli("size", str(EXAMPLE), "--format", "json")
    assert again.stdout == out.stdout  # deterministic
    csv = run_cli("size", str(EXAMPLE), "--format", "csv").stdout.splitlines()
    assert csv[0].startswith("axis,") and {line.split(",")[0] for line in csv[1:]} == \
        {"table", "pusher"}
    text = run_cli("size", str(EXAMPLE)).stdout
    assert "set by" in text and "machine: feasible" in text


def test_the_cli_refuses_design_options_on_a_machine(tmp_path: Path) -> None:
    out = run_cli("size", str(EXAMPLE), "--motor", "HG-KN43J")
    assert out.returncode == 2 and "--motor" in out.stderr
    assert "Traceback" not in out.stderr
    bad = tmp_path / "bad.yaml"
    bad.write_text(EXAMPLE.read_text().replace("move: 150 deg", "move: 500 deg"))
    out = run_cli("size", str(bad))
    assert out.returncode == 2 and "axes[0].task.move" in out.stderr
    assert f"{bad}:" in out.stderr and "Traceback" not in out.stderr


def test_the_report_of_a_machine_links_each_axis_report(tmp_path: Path) -> None:
    out = run_cli("report", str(EXAMPLE), "-o", str(tmp_path / "r"), "--best", "1")
    assert out.returncode == 0, out.stderr
    text = (tmp_path / "r" / "report.md").read_text()
    assert text.startswith("# Two-axis packer: 2 axes") and "(bus.png)" in text
    for folder in ("1-table", "2-pusher"):
        assert f"]({folder}/report.md)" in text
        assert (tmp_path / "r" / folder / "report.md").read_text().startswith("# ")
    assert (tmp_path / "r" / "bus.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    again = tmp_path / "again"
    assert run_cli("report", str(EXAMPLE), "-o", str(again), "--best", "1").returncode == 0
    assert (again / "report.md").read_text() == text  # deterministic


def test_the_bus_figure_draws_the_summed_power() -> None:
    from sizer.report.plots.bus_power import GID_POWER, bus_figure

    result = api.size_machine(EXAMPLE)
    assert result.bus is not None
    figure = bus_figure(result.bus)
    lines = [a for ax in figure.axes for a in ax.get_lines() if a.get_gid() == GID_POWER]
    assert len(lines) == 1
    np.testing.assert_array_equal(lines[0].get_ydata(), result.bus.power)


def test_sizer_check_passes_a_feasible_machine_and_fails_a_too_fast_one(tmp_path: Path) -> None:
    out = run_cli("check", str(EXAMPLE))
    assert out.returncode == 0 and "\nPASS: machine Two-axis packer" in out.stdout
    fast = tmp_path / "fast.yaml"
    catalog = (ROOT / "examples" / "catalogs" / "example-servo.yaml").as_posix()
    fast.write_text(EXAMPLE.read_text().replace("master_speed: minimize", "master_speed: 1000 rpm")
                    .replace("../catalogs/example-servo.yaml", catalog))
    out = run_cli("check", str(fast), "--format", "json")
    assert out.returncode == 1, out.stderr
    data = json.loads(out.stdout)
    assert data["passed"] is False and data["reason"].startswith("axis ")
    text = run_cli("check", str(fast)).stdout
    assert "FAIL: machine Two-axis packer: axis" in text


@pytest.mark.parametrize("command", [["plot", "-o", "{tmp}/x.png"], ["segments"],
                                     ["vibration"]])
def test_commands_for_design_files_say_a_machine_file_is_not_one(command, tmp_path) -> None:
    args = [a.format(tmp=tmp_path) for a in command]
    out = run_cli(args[0], str(EXAMPLE), *args[1:])
    assert out.returncode == 2 and "a machine file (axes:)" in out.stderr
    assert "Traceback" not in out.stderr and not (tmp_path / "x.png").exists()


def test_a_machine_no_axis_can_run_says_why_without_a_number_it_has_not(tmp_path) -> None:
    weak = {"id": "weak", "inertia": 1e-5, "continuous_torque": 0.1, "peak_torque": 0.3,
            "rated_speed": 300}
    held = {"inertia": 0.01, "torque": 0.5}
    data = machine(axis("a", "120 deg", motors=[weak], load=held),
                   axis("b", "90 deg", motors=[weak], load=held), master_speed="minimize")
    result = api.size_machine(data)
    assert result.cycle_time is None and not result.feasible and result.bus is None
    assert all(a.move_time is None and a.chosen is None for a in result.axes)
    path = tmp_path / "m.yaml"
    path.write_text(yaml.safe_dump(data))
    for fmt in ("table", "json", "csv", "md"):
        out = run_cli("size", str(path), "--all", "--format", fmt)
        assert out.returncode == 0, out.stderr
        assert "nan" not in out.stdout.lower().replace("infeasible", "")
    assert "no master speed suits every axis" in run_cli("size", str(path)).stdout


def test_a_mapping_that_is_not_yaml_data_is_a_user_error() -> None:
    data = machine(axis("a", "120 deg"), master_speed="60 rpm")
    data["axes"][0]["load"] = {"inertia": object()}
    with pytest.raises(UserError, match="cannot be written as YAML"):
        api.load_machine(data)
