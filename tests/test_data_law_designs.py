"""Laws defined by data end to end: design files, the task shorthand, cycles, the CLI.

Expected numbers are closed forms (the cycloidal and poly5 coefficients, a rotary cam's
speeds) or the conditions the user wrote, never the code's own output."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import yaml
from cli_run import assert_user_error, run_cli

from sizer.api import size
from sizer.errors import UserError
from sizer.laws import make_law, resolve
from sizer.laws.data_law import DataLaw

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"

SLIDES = {"kind": "poly_spline", "order": 6,
          "points": [[0, 0], [0.3, 0.15], [0.55, 0.8], [1, 1]],
          "start": {"velocity": 0, "acceleration": 0}, "end": {"velocity": 0, "jerk": 0}}

KINDS = [
    {"kind": "cubic_spline", "points": [[0, 0], [0.3, 0.2], [0.7, 0.8], [1, 1]]},
    {"kind": "cubic_spline", "times": "auto", "positions": [0, 0.2, 0.8, 1]},
    {"kind": "smoothing_spline", "mu": 0.5,
     "points": [[0, 0], [0.3, 0.25], [0.5, 0.4], [0.7, 0.8], [1, 1]]},
    SLIDES,
    {**SLIDES, "kind": "bspline"},
    {**SLIDES, "kind": "nurbs", "weights": [1, 1, 2, 1, 1, 1, 1, 1]},
    {"kind": "via_trapezoid", "points": [[0, 0], [1, 0.5], [2, 0.6], [3, 1]]},
]


def _flow(fields: dict) -> str:
    return yaml.safe_dump(fields, default_flow_style=True, width=10_000).strip()


@pytest.mark.parametrize("fields", KINDS, ids=lambda f: f["kind"])
def test_every_kind_is_a_law_that_meets_its_points(fields: dict) -> None:
    law = make_law(_flow(fields))
    assert isinstance(law, DataLaw) and law.law_id == fields["kind"]
    assert make_law(law.spec) is law  # the canonical spec reads back to the same law
    assert resolve(law.spec)[0].law_id == fields["kind"] and resolve(law.spec)[1] == {}
    assert law.position(0.0) == 0.0 and float(law.position(1.0)) == pytest.approx(1.0)
    assert law.rest_to_rest
    c = law.coefficients
    assert all(math.isfinite(v) and v > 0 for v in (c.C_v, c.C_a, c.C_v_rms, c.C_a_rms))
    # C_v is at least the mean speed 1 and C_a_rms at least that of the best law (2 sqrt 3)
    assert c.C_v >= 1.0 - 1e-12 and c.C_a_rms >= 2 * math.sqrt(3) - 1e-9
    if fields["kind"] in ("cubic_spline", "poly_spline", "bspline", "nurbs") \
            and "points" in fields:
        t, q = np.array(fields["points"], dtype=float).T
        assert law.position(t / t[-1]) == pytest.approx(q / q[-1], abs=1e-9)


def test_slides_example_is_one_law_as_poly_spline_and_bspline() -> None:
    a, b = make_law(_flow(SLIDES)), make_law(_flow({**SLIDES, "kind": "bspline"}))
    tau = np.linspace(0, 1, 2001)
    for order in range(4):
        assert a.derivative(tau, order) == pytest.approx(b.derivative(tau, order), abs=1e-8)
    assert a.continuity == 1  # v = a = 0 at the start, but a(1) != 0 steps to rest
    assert float(a.velocity(0.0)) == 0 and abs(float(a.acceleration(0.0))) < 1e-9
    assert abs(float(a.jerk(1.0))) < 1e-7


def test_cam_table_of_the_cycloidal_law_gives_back_its_coefficients(tmp_path: Path) -> None:
    table = tmp_path / "cycloidal.csv"
    result = run_cli("law", "cycloidal", "--displacement", "90 deg", "--duration", "0.2 s",
                     "--samples", "201", "--format", "csv", "--output", str(table))
    assert result.returncode == 0, result.stderr
    law = make_law(_flow({"kind": "cam_table", "file": str(table)}))
    c = law.coefficients
    assert c.C_v == pytest.approx(2.0, abs=1e-4)
    assert c.C_a == pytest.approx(2 * math.pi, abs=1e-4)
    assert c.C_j == pytest.approx(4 * math.pi**2, abs=1e-2)
    assert c.C_v_rms == pytest.approx(math.sqrt(1.5), abs=1e-4)
    assert c.C_a_rms == pytest.approx(math.sqrt(2) * math.pi, abs=1e-4)
    # the header's units give the law its size: 90 deg in 0.2 s, and `sizer law` reads
    # it back without --displacement and --duration
    assert law.scale.displacement == pytest.approx(math.pi / 2, rel=1e-12)
    assert law.scale.span == pytest.approx(0.2, rel=1e-12) and not law.scale.master
    again = run_cli("law", law.spec, "--samples", "5", "--format", "json")
    document = json.loads(again.stdout)
    assert document["duration"] == pytest.approx(0.2) and "fit" in document
    assert document["v"][2] == pytest.approx(2.0 * (math.pi / 2) / 0.2, rel=1e-4)
    assert "noise the fit puts in" in again.stderr


def _design(**changes: object) -> dict:
    design = {"task": {"displacement": "60 mm", "duration": "0.4 s", "dwell": "0.2 s"},
              "load": {"mass": "6 kg", "friction": "15 N"},
              "transmission": {"type": "ball_screw", "lead": "10 mm", "diameter": "16 mm",
                               "length": "300 mm", "efficiency": 0.9},
              "laws": ["poly5"], "motors": ["yaskawa-sgm7j"]}
    design.update(changes)
    return design


def test_a_data_law_polynomial_of_degree_5_sizes_as_poly5() -> None:
    # the slides' spline with the points of poly5 itself and its end conditions is poly5
    tau = [0.0, 0.25, 0.5, 0.75, 1.0]
    poly5 = {"kind": "poly_spline", "order": 6,
             "points": [[t, 10 * t**3 - 15 * t**4 + 6 * t**5] for t in tau],
             "start": {"velocity": 0, "acceleration": 0},
             "end": {"velocity": 0, "acceleration": 0}}
    records = size(_design(laws=["poly5", poly5], task={"displacement": "60 mm",
                                                        "duration": "minimize"})).to_records()
    by_motor: dict[str, dict[str, float]] = {}
    for r in records:
        by_motor.setdefault(r["motor"], {})[r["law"]] = r["duration"]
    assert by_motor
    for durations in by_motor.values():
        assert durations["poly_spline"] == pytest.approx(durations["polynomial"], rel=1e-7)


def test_design_errors_point_at_the_field_inside_the_law(tmp_path: Path) -> None:
    design = tmp_path / "bad.yaml"
    text = yaml.safe_dump(_design(laws=["poly5"]), sort_keys=False).replace(
        "laws:\n- poly5\n", "laws:\n- kind: cubic_spline\n  points:\n  - [0, 0]\n"
        "  - [0.5, 0.3]\n  - [0.5, 1]\n")
    design.write_text(text)
    line = text.splitlines().index("  - [0.5, 1]") + 1
    assert_user_error(run_cli("size", str(design)), f"bad.yaml:{line}: laws[0].points[2]",
                      "times must increase")


def test_a_cam_table_with_a_header_and_no_rows_is_a_located_error(tmp_path: Path) -> None:
    (tmp_path / "cam.csv").write_text("t [s],q [mm]\n")
    design = tmp_path / "cam.yaml"
    design.write_text(yaml.safe_dump(_design(laws=[{"kind": "cam_table",
                                                    "file": "cam.csv"}])))
    assert_user_error(run_cli("size", str(design)), "cam.csv:1", "header but no rows")


PERIODIC = {"kind": "cubic_spline", "periodic": True,
            "points": [[0, 0], [0.25, 0.4], [0.5, 0.1], [0.75, -0.2], [1, 0]]}


def test_a_periodic_law_is_one_period_of_the_task() -> None:
    with pytest.raises(UserError, match="needs dwell 0"):
        size(_design(laws=[PERIODIC]))
    task = {"displacement": "60 mm", "duration": "0.4 s", "dwell": 0}
    records = size(_design(laws=[PERIODIC], task=task)).to_records()
    assert records and all(r["law"] == "cubic_spline" for r in records)
    open_ends = {**PERIODIC, "periodic": False, "start": {"velocity": 1}}
    with pytest.raises(UserError, match="ends do not join"):
        size(_design(laws=[open_ends], task=task))


def test_a_law_whose_ends_move_is_not_a_move_of_a_cycle() -> None:
    cycle = {"segments": [{"move": {"displacement": "60 mm", "duration": "0.4 s",
                                    "law": PERIODIC}},
                          {"dwell": {"duration": "0.2 s"}}]}
    design = _design(cycle=cycle)
    del design["task"]
    with pytest.raises(UserError, match="must start and end at rest"):
        size(design)


def test_a_rest_to_rest_data_law_drives_a_move_of_a_cycle() -> None:
    cycle = {"segments": [{"move": {"displacement": "60 mm", "duration": "0.4 s",
                                    "law": SLIDES}},
                          {"dwell": {"duration": "0.2 s"}},
                          {"move": {"displacement": "-60 mm", "duration": "0.4 s",
                                    "law": "poly5"}}]}
    design = _design(cycle=cycle)
    del design["task"]
    assert any(r["feasible"] for r in size(design).to_records())


def test_master_speed_gives_the_duration_of_a_cam_on_a_master_axis(tmp_path: Path) -> None:
    # a rotary cam: q = theta + 0.3 sin(theta) (rad), one turn per master turn
    theta = np.linspace(0.0, 360.0, 73)
    q = theta + np.degrees(0.3 * np.sin(np.radians(theta)))
    rows = "\n".join(f"{a:.10g},{b:.10g}" for a, b in zip(theta, q, strict=True))
    (tmp_path / "knife.csv").write_text("theta [deg],knife [deg]\n" + rows + "\n")
    law = {"kind": "cam_table", "file": "knife.csv", "periodic": True}
    design = _design(task={"master_speed": "120 rpm", "dwell": 0},  # no displacement
                     laws=[law], load={"inertia": "0.06 kg*m^2"},
                     transmission={"type": "belt", "ratio": 4}, motors=["mitsubishi-hg-kn"])
    (tmp_path / "knife.yaml").write_text(yaml.safe_dump(design))
    records = size(tmp_path / "knife.yaml").to_records()
    assert records[0]["duration"] == pytest.approx(0.5, rel=1e-12)  # 360 deg at 120 rpm
    # the knife's top speed: (1 + 0.3) turn per master turn, at the motor x 4
    assert records[0]["max_speed"] == pytest.approx(1.3 * 4 * 4 * math.pi, rel=1e-6)


@pytest.mark.parametrize(("fields", "fragment"), [
    ({"kind": "cubic_spline", "points": [[0, 0]]}, "at least 2"),
    ({"kind": "poly_spline", "order": 6, "points": [[0, 0], [1, 1]]}, "end"),
    ({"kind": "cubic_spline", "points": [[0, 0], [1, 1]], "colour": "red"}, "no field"),
    ({"kind": "wave"}, "unknown kind"),
])
def test_bad_laws_on_the_command_line_exit_2(fields: dict, fragment: str) -> None:
    assert_user_error(run_cli("laws", "--law", _flow(fields)), fragment)


def test_plot_law_draws_a_data_law(tmp_path: Path) -> None:
    output = tmp_path / "law.png"
    result = run_cli("plot-law", _flow(SLIDES), "cycloidal", "-o", str(output))
    assert result.returncode == 0, result.stderr
    assert output.stat().st_size > 1000


def test_the_examples_run() -> None:
    for name in ("pusher-via-points.yaml", "rotary-knife.yaml"):
        result = run_cli("size", str(EXAMPLES / name))
        assert result.returncode == 0, result.stderr
