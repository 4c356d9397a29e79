"""Energy and heat over a cycle of segments (issue 16): the braking and heat checks of the
engine on cycles of moves, runs and dwells (sizer.sizing.segment_samples).

Numbers from closed forms: a lossless mass returns its kinetic energy 1/2 M v^2 at each
stop (M = m + J_m K^2, the rotor reflected to the load); and from an independent path:
the task shorthand written as a cycle of segments gives the figures of the task.
"""

from __future__ import annotations

import math

import pytest

from sizer import api

MOTOR = {"id": "m1", "inertia": "1e-4 kg*m^2", "continuous_torque": "2 N*m",
         "peak_torque": "6 N*m", "rated_speed": "3000 rpm"}
HEATED = {**MOTOR, "torque_constant": "0.5 N*m/A", "winding_resistance": "2 ohm",
          "thermal_time_constant": "2 s", "max_winding_temperature_rise": "100 K"}


def _records(design: dict) -> list[dict]:
    return api.size(design).to_records()


def test_a_lossless_flying_saw_returns_the_kinetic_energy_of_its_stops() -> None:
    """Accelerate 100 mm to 0.5 m/s in 0.4 s and stop from it over 100 mm in 0.4 s: a
    cubic between those speeds is a linear ramp of the speed (q = 2u - u^2), so each
    stop returns 1/2 M v^2 exactly; the return (cycloidal, 400 mm in 0.5 s) returns
    1/2 M (2 L / T)^2; the run at constant speed against 120 N returns nothing."""
    m, r, J_m = 20.0, 0.03, 1e-4
    design = {
        "name": "saw",
        "cycle": {"closed": True, "segments": [
            {"move": {"displacement": "100 mm", "end_speed": "0.5 m/s", "duration": "0.4 s"}},
            {"run": {"speed": "0.5 m/s", "duration": "0.4 s", "force": "120 N"}},
            {"move": {"displacement": "100 mm", "start_speed": "0.5 m/s",
                      "duration": "0.4 s"}},
            {"move": {"displacement": "-400 mm", "duration": "0.5 s",
                      "law": "cycloidal"}},
            {"dwell": {"duration": "0.3 s"}}]},
        "load": {"mass": f"{m} kg"},
        "transmission": {"type": "rack_pinion", "pitch_radius": f"{r * 1000} mm"},
        "laws": ["poly3"],
        "motors": [MOTOR],
        "limits": {"braking_resistor_power": "1000 W"},
    }
    result = _records(design)[0]
    M = m + J_m / r**2
    expected = 0.5 * M * 0.5**2 + 0.5 * M * (2 * 0.4 / 0.5) ** 2
    # the bus power is the piecewise-linear interpolant of 1001 samples per move: to 1e-5
    assert result["regenerated_energy"] == pytest.approx(expected, rel=1e-5)
    assert result["braking_power"] == pytest.approx(expected / 2.0, rel=1e-5)  # T_c = 2 s
    check = next(c for c in result["checks"] if c["name"] == "braking_resistor_power")
    assert check["limit"] == 1000.0 and check["passed"]


def _as_cycle(task: dict) -> dict:
    """The task's cycle with its first dwell split in two halves: the same motion, but not
    the task shorthand, so the engine sizes it as a cycle of segments."""
    T, h = task["duration"], task["displacement"]
    half = {"dwell": {"duration": f"{float(task['dwell'].split()[0]) / 2} s"}}
    return {"closed": True, "segments": [
        {"move": {"displacement": h, "duration": T}}, half, half,
        {"move": {"displacement": "-" + h, "duration": T}},
        {"dwell": {"duration": task["dwell"]}}]}


@pytest.mark.parametrize("load", [
    {"inertia": "0.02 kg*m^2"},
    {"inertia": "0.02 kg*m^2", "friction": "0.3 N*m", "damping": "0.01 N*m*s/rad"},
    {"inertia": "0.02 kg*m^2", "torque": "0.4 N*m"},
])
def test_the_task_as_a_cycle_of_segments_has_the_tasks_energy_and_heat(load: dict) -> None:
    task = {"displacement": "90 deg", "duration": "0.2 s", "dwell": "0.3 s", "return": True}
    base = {"load": load, "transmission": {"type": "gearbox", "ratio": 5, "efficiency": 0.9},
            "laws": ["cycloidal", "poly5"], "motors": [HEATED],
            "limits": {"braking_resistor_power": "50 W"}}
    by_task = _records({**base, "task": task})
    by_cycle = _records({**base, "cycle": _as_cycle(task)})
    assert len(by_task) == len(by_cycle) == 2
    for a, b in zip(sorted(by_task, key=lambda r: r["spec"]),
                    sorted(by_cycle, key=lambda r: r["spec"]), strict=True):
        for name in ("regenerated_energy", "braking_power", "winding_rise", "rms_torque"):
            assert b[name] == pytest.approx(a[name], rel=1e-9), name
        names = {c["name"] for c in b["checks"]}
        assert {"braking_resistor_power", "winding_temperature_rise"} <= names


def test_a_minimized_cycle_is_lengthened_until_the_resistor_copes() -> None:
    """The free moves' duration grows until the braking power meets the limit: at the
    answer the resistor's power equals the limit (the binding check), and the cycle is
    longer than without the limit. Lossless: each stop returns 1/2 J omega^2 with
    omega = 2 h / T (cycloidal), two stops per cycle."""
    design = {
        "cycle": {"closed": True, "segments": [
            {"move": {"displacement": "180 deg", "duration": "free"}},
            {"dwell": {"duration": "0.1 s"}}, {"dwell": {"duration": "0.1 s"}},
            {"move": {"displacement": "-180 deg", "duration": "free"}},
            {"dwell": {"duration": "0.2 s"}}]},
        "load": {"inertia": "0.05 kg*m^2"},
        "laws": ["cycloidal"], "motors": [{**MOTOR, "peak_torque": "60 N*m",
                                           "continuous_torque": "30 N*m"}],
    }
    free = _records(design)[0]
    limited = _records({**design, "limits": {"braking_resistor_power": "20 W"}})[0]
    assert limited["feasible"] and limited["duration"] > free["duration"]
    assert limited["braking_power"] == pytest.approx(20.0, rel=1e-6)
    assert limited["limiting"] == "braking_resistor_power"
    J = 0.05 + 1e-4
    T = (limited["duration"] - 0.4) / 2  # the duration of a cycle is its cycle time
    assert limited["regenerated_energy"] == pytest.approx(
        2 * 0.5 * J * (2 * math.pi / T) ** 2, rel=1e-5)
    assert limited["braking_power"] == pytest.approx(
        limited["regenerated_energy"] / limited["duration"], rel=1e-12)


def test_the_design_report_states_the_energy_figures() -> None:
    from sizer.report.design_report import DesignReport

    design = api.load({"task": {"displacement": "90 deg", "duration": "0.2 s",
                                "dwell": "0.3 s"},
                       "load": {"inertia": "0.02 kg*m^2"}, "laws": ["cycloidal"],
                       "motors": [HEATED], "limits": {"braking_resistor_power": "100 W"}})
    sizing = api.size(design)
    best = sizing.results[0]
    text = DesignReport(design, sizing, best=1).markdown()
    assert f"{best.regenerated_energy:.5g} J per cycle returned to the DC bus" in text
    assert f"{best.winding_rise:.5g} K winding temperature rise" in text


def test_the_power_figures_of_a_lossless_inertia() -> None:
    """Cycloidal, h in T then a dwell, J on a motor with k_t and R: the shaft power
    P = J h^2/T^3 v_N a_N peaks at u = 1/3 (cos 2 pi u = -1/2): 2 pi (3 sqrt 3 / 4)
    J h^2/T^3; the motoring half gives 1/2 J omega_max^2 per cycle, omega_max = 2 h/T;
    the copper loss is 3/2 R (tau_rms/k_t)^2 and, the mechanics lossless, the net energy
    per cycle is that loss over the cycle."""
    J, h, T, dwell, k_t, R = 0.02, math.pi / 2, 0.2, 0.3, 0.5, 2.0
    motor = {**HEATED, "inertia": 0}
    design = {"task": {"displacement": "90 deg", "duration": f"{T} s", "dwell": f"{dwell} s"},
              "load": {"inertia": f"{J} kg*m^2"}, "laws": ["cycloidal"], "motors": [motor],
              "limits": {"braking_resistor_power": "100 W"}}
    r = _records(design)[0]
    peak = 2 * math.pi * 3 * math.sqrt(3) / 4 * J * h**2 / T**3
    assert r["peak_power"] == pytest.approx(peak, rel=1e-5)
    assert r["mean_power"] == pytest.approx(0.5 * J * (2 * h / T) ** 2 / (T + dwell), rel=1e-5)
    copper = 1.5 * R * (r["rms_torque"] / k_t) ** 2
    assert r["copper_loss"] == pytest.approx(copper, rel=1e-5)
    assert r["cycle_energy"] == pytest.approx(copper * (T + dwell), rel=1e-5)
    without = _records({**design, "motors": [{**MOTOR, "inertia": 0}]})[0]
    assert without["peak_power"] == pytest.approx(peak, rel=1e-5)
    assert without.get("copper_loss") is None and without.get("cycle_energy") is None


def _crank(**task: object) -> dict:
    """A slider-crank turned by its crank (law on the crank) with a negligible slider mass:
    the crank's own inertia J_c behind a lossless 10:1 gearbox is the whole load."""
    return {"task": {"displacement": "180 deg", "duration": "0.3 s", "dwell": "0.2 s",
                     **task},
            "load": {"mass": "1e-6 kg"},
            "transmission": [{"type": "gearbox", "ratio": 10},
                             {"type": "slider_crank", "crank_radius": "50 mm",
                              "rod_length": "200 mm", "law_on": "crank",
                              "crank_inertia": "0.002 kg*m^2"}],
            "laws": ["cycloidal"],
            "motors": [{**MOTOR, "inertia": "1e-5 kg*m^2"}],
            "limits": {"braking_resistor_power": "1000 W"}}


@pytest.mark.parametrize(("task", "stops", "cycle_time"), [
    ({}, 1, 0.5), ({"return": True}, 2, 1.0)])
def test_a_crank_stopped_returns_its_kinetic_energy(task: dict, stops: int,
                                                    cycle_time: float) -> None:
    """Each stop of the crank (cycloidal, pi in 0.3 s: omega_max = 2 pi / 0.3) returns
    1/2 (J_c + J_m N^2) omega_max^2 (the slider's 1e-6 kg adds about 1e-6 of it); a move
    back is a second stop."""
    r = _records(_crank(**task))[0]
    stop = 0.5 * (0.002 + 1e-5 * 10**2) * (2 * math.pi / 0.3) ** 2
    assert r["duration"] == pytest.approx(0.3, rel=1e-12)
    assert r["regenerated_energy"] == pytest.approx(stops * stop, rel=2e-5)
    assert r["braking_power"] == pytest.approx(r["regenerated_energy"] / cycle_time,
                                               rel=1e-12)
    assert "braking_resistor_power" in [c["name"] for c in r["checks"]]
    assert "dead_point" in [c["name"] for c in r["checks"]]


def test_a_minimized_crank_is_lengthened_until_the_resistor_copes() -> None:
    free = _records(_crank(duration="minimize"))[0]
    limited = _records({**_crank(duration="minimize"),
                        "limits": {"braking_resistor_power": "1 W"}})[0]
    assert limited["feasible"] and limited["duration"] > free["duration"]
    assert limited["braking_power"] == pytest.approx(1.0, rel=1e-6)
    assert limited["checks"][0]["name"] == "dead_point"


def test_the_largest_stop_and_the_resistors_peak() -> None:
    """One stop per cycle of a lossless inertia (cycloidal, h in T): it returns
    1/2 J omega_max^2; with no capacitance the resistor takes it, its peak the largest
    regenerative power, which by the symmetry of the law equals the peak motoring power."""
    design = {"task": {"displacement": "90 deg", "duration": "0.2 s", "dwell": "0.3 s"},
              "load": {"inertia": "0.02 kg*m^2"}, "laws": ["cycloidal"],
              "motors": [{**MOTOR, "inertia": 0}],
              "limits": {"braking_resistor_power": "100 W"}}
    r = _records(design)[0]
    assert r["stop_energy"] == pytest.approx(0.5 * 0.02 * (math.pi / 0.2) ** 2, rel=1e-5)
    assert r["stop_energy"] == pytest.approx(r["regenerated_energy"], rel=1e-12)
    assert r["braking_peak_power"] == pytest.approx(r["peak_power"], rel=1e-9)
