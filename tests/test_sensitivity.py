"""sizer sensitivity (issue 39): slopes against separate sizings, closed forms, kinks."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import pytest

from sizer import api
from sizer.cli.app import run
from sizer.sensitivity import STEP, T_MIN, sensitivity

ROOT = Path(__file__).resolve().parents[1]
INDEXING = ROOT / "examples" / "indexing-table.yaml"
EX61 = ROOT / "examples" / "book" / "ex6_1-6_2.yaml"
EX63 = ROOT / "examples" / "book" / "ex6_3.yaml"


def _margins(result):
    return {str(c.name): c.margin for c in result.checks}


def _one(design, motor, law):
    """A separate sizing of one pair of ``design``."""
    return api.size(design, motors=[motor], laws=[law]).results[0]


def _central(low, high, h=STEP):
    a, b = _margins(low), _margins(high)
    return {k: (b[k] - a[k]) / (2 * h) for k in a}


def _check(row, expected):
    for name, value in expected.items():
        assert row.slopes[name].central == pytest.approx(value, rel=1e-6, abs=1e-9), name


@pytest.fixture(scope="module")
def indexing():
    design = api.load(INDEXING)
    return design, sensitivity(design)


def test_load_and_transmission_against_separate_sizings(indexing):
    design, s = indexing
    motor, law = s.result.motor, s.result.spec
    rows = {r.name: r for r in s.inputs}
    h = STEP
    load = design.load
    expected = _central(
        _one(replace(design, load=replace(load, inertia=load.inertia * (1 - h))), motor, law),
        _one(replace(design, load=replace(load, inertia=load.inertia * (1 + h))), motor, law))
    _check(rows["load.inertia"], expected)
    stage = design.transmission.stages[0]

    def with_ratio(f):
        return replace(design, transmission=replace(
            design.transmission, stages=(replace(stage, ratio=stage.ratio * f),)))

    _check(rows["transmission.ratio"],
           _central(_one(with_ratio(1 - h), motor, law), _one(with_ratio(1 + h), motor, law)))


def test_motor_rows_against_separate_sizings(indexing):
    design, s = indexing
    rows = {r.name: r for r in s.inputs}
    base = next(m for m in design.motors if m.id == s.result.motor)
    for name in ("continuous_torque", "peak_torque", "inertia"):
        value = getattr(base, name)
        low, high = (_one(replace(design, motors=(replace(base, **{name: value * f}),)),
                          base.id, s.result.spec) for f in (1 - STEP, 1 + STEP))
        _check(rows[f"motor.{name}"], _central(low, high))
    influence = [max(abs(v.central) for v in r.slopes.values()) for r in s.inputs]
    assert influence == sorted(influence, reverse=True)


def test_rms_margin_closed_form_example_6_1():
    # cycloidal, h = 15 rad, T = 3 s, J = 1, B = 0.3, tau_c = 8 (B&M ex. 6.1-6.2):
    # rms^2 = J^2 <a^2> + B^2 <v^2> (the cross term integrates to 0 rest to rest),
    # <a^2> = (2 pi h / T^2)^2 / 2, <v^2> = 3/2 (h / T)^2; margin = 1 - rms / tau_c, so
    # d margin / d ln J = -J^2 <a^2> / (rms tau_c).
    h, T, J, B, tau_c = 15.0, 3.0, 1.0, 0.3, 8.0
    a2 = (2 * math.pi * h / T**2) ** 2 / 2
    v2 = 1.5 * (h / T) ** 2
    rms = math.sqrt(J**2 * a2 + B**2 * v2)
    s = sensitivity(api.load(EX61), "ex6_1", "cycloidal")
    rows = {r.name: r for r in s.inputs}
    assert rows["load.inertia"].slopes["rms"].central == pytest.approx(
        -J**2 * a2 / (rms * tau_c), rel=1e-6)
    assert rows["load.damping"].slopes["rms"].central == pytest.approx(
        -B**2 * v2 / (rms * tau_c), rel=1e-6)
    assert rows["motor.continuous_torque"].slopes["rms"].central == pytest.approx(
        rms / tau_c, rel=1e-6)


def test_t_min_closed_form_example_6_3():
    # T_min = sqrt(C h J / tau_c) (the RMS bound, eq. 6.2), C = pi^2 / (2 sqrt 2):
    # d T_min / d ln J = T_min / 2, d T_min / d ln tau_c = -T_min / 2
    C = math.pi**2 / (2 * math.sqrt(2))
    t_min = math.sqrt(C * 0.6 * 0.25 / 14.0)
    s = sensitivity(api.load(EX63))
    assert s.minimize and T_MIN in s.quantities
    rows = {r.name: r for r in s.inputs}
    assert rows["load.inertia"].slopes[T_MIN].central == pytest.approx(t_min / 2, rel=1e-6)
    assert rows["task.displacement"].slopes[T_MIN].central == pytest.approx(t_min / 2,
                                                                             rel=1e-6)
    assert rows["motor.continuous_torque"].slopes[T_MIN].central == pytest.approx(
        -t_min / 2, rel=1e-6)
    assert not any(r.kinked for r in s.inputs)


def test_kink_where_the_limiting_bound_changes():
    # ex. 6.3 with the rated speed where the speed bound meets the RMS bound: the harmonic
    # law's peak speed pi h / (2 T) equals v_n at T_rms. Below it the speed bound wins,
    # T_min = pi h / (2 v_n): d T_min / d ln v_n = -T_min on the left, 0 on the right.
    C = math.pi**2 / (2 * math.sqrt(2))
    t_rms = math.sqrt(C * 0.6 * 0.25 / 14.0)
    design = api.load(EX63)
    motor = next(m for m in design.motors if m.id == "ex6_3")
    crossing = replace(motor, rated_speed=math.pi * 0.6 / (2 * t_rms))
    design = replace(design, motors=(crossing,))
    s = sensitivity(design)
    row = next(r for r in s.inputs if r.name == "motor.rated_speed")
    slope = row.slopes[T_MIN]
    assert slope.kink and row.kinked
    assert slope.minus == pytest.approx(-t_rms, rel=1e-4)
    assert slope.plus == pytest.approx(0.0, abs=1e-6)


def _cli(args, capsys):
    code = run(args)
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_cli_formats(capsys):
    code, out, _ = _cli(["sensitivity", str(EX63), "--format", "json"], capsys)
    assert code == 0
    data = json.loads(out)
    assert data["motor"] == "ex6_3" and data["minimize"] is True
    first = data["inputs"][0]
    assert {"input", "value", "unit", "d_T_min/d_ln_x"} <= set(first)
    code, out, _ = _cli(["sensitivity", str(EX61), "--format", "md"], capsys)
    assert code == 0 and "| load.inertia |" in out
    code, out, _ = _cli(["sensitivity", str(EX61), "--format", "csv"], capsys)
    assert code == 0 and out.startswith("input,value,unit")


def test_cli_user_errors(capsys, tmp_path):
    code, _, err = _cli(["sensitivity", str(EX63), "--motor", "nope"], capsys)
    assert code == 2 and "--motor" in err and "nope" in err
    code, _, err = _cli(["sensitivity", str(EX63), "--law", "nope"], capsys)
    assert code == 2 and "--law" in err
    design = tmp_path / "infeasible.yaml"
    design.write_text(
        "task: {displacement: 0.6 rad, duration: minimize}\n"
        "load: {inertia: 0.25 kg*m^2, torque: 20 N*m}\n"
        "transmission: {type: direct}\nlaws: [harmonic]\nmotors: book-examples\n")
    code, _, err = _cli(["sensitivity", str(design), "--motor", "ex6_3", "--law",
                         "harmonic"], capsys)
    assert code == 2 and "no feasible duration" in err and "Traceback" not in err


def test_cycle_segment_duration_moves_t_min_as_separate_sizings():
    # indexing-duty-cycle.yaml: two free indexes and two fixed dwells, minimized
    design = api.load(ROOT / "examples" / "indexing-duty-cycle.yaml")
    s = sensitivity(design, "HG-KN73J", "cycloidal")
    row = next(r for r in s.inputs if r.name == "press.duration")
    cycle = design.machine_cycle
    index = next(i for i, seg in enumerate(cycle.segments) if seg.name == "press")

    def t_min(factor):
        segments = list(cycle.segments)
        segments[index] = replace(segments[index], duration=segments[index].duration * factor)
        changed = replace(design, machine_cycle=replace(cycle, segments=tuple(segments)))
        return _one(changed, "HG-KN73J", "cycloidal").duration

    expected = (t_min(1 + STEP) - t_min(1 - STEP)) / (2 * STEP)
    assert row.slopes[T_MIN].central == pytest.approx(expected, rel=1e-6)


def test_kinked_records_give_both_one_sided_values(capsys):
    code, out, _ = _cli(["sensitivity", str(ROOT / "examples" / "vendor-ballscrew.yaml"),
                         "--format", "json"], capsys)
    assert code == 0
    rows = {r["input"]: r for r in json.loads(out)["inputs"]}
    kinked = rows["task.duration"]
    assert kinked["kink"] is True
    assert kinked["d_peak/d_ln_x_minus"] != pytest.approx(kinked["d_peak/d_ln_x_plus"])
    assert kinked["d_peak/d_ln_x"] == pytest.approx(
        (kinked["d_peak/d_ln_x_minus"] + kinked["d_peak/d_ln_x_plus"]) / 2)
