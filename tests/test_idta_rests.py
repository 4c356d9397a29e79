"""IDTA 02021 motion files with rests (issue 37, review of sizer/idta/read.py): a span where
the position holds is a dwell of the design, not samples of a periodic cam table. One move
gives ``task: {duration, dwell}``, several a ``cycle`` of moves (a cam table each) and dwells;
the cycle is read around its end. The motions are cycloids written here from their closed
form, h (tau - sin(2 pi tau) / (2 pi)), with 12 decimals as the template's example writes
them (a hold is the same number written again)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml

from sizer.errors import UserError
from sizer.idta.read import read_csv_design, read_motion_csv
from tests.cli_run import assert_user_error, run_cli

H = math.pi / 2
T = 0.4
STEP = 0.01


def _cycloid(tau: float) -> float:
    return H * (tau - math.sin(2 * math.pi * tau) / (2 * math.pi))


def _csv(samples: list[tuple[float, float]]) -> str:
    return "Time [s];AngularPosition [rad]\n" + "".join(
        f"{t:.2f};{q:.12f}\n" for t, q in samples)


def _move(start: float, q0: float, sign: float = 1.0, first: int = 0, last: int = 40
          ) -> list[tuple[float, float]]:
    """Samples k = first..last of a cycloidal move of sign * H from q0 starting at ``start``."""
    return [(start + k * STEP, q0 + sign * _cycloid(k * STEP / T)) for k in range(first, last + 1)]


def _hold(start: float, end: float, q: float) -> list[tuple[float, float]]:
    """The samples after ``start`` up to ``end`` at q."""
    count = round((end - start) / STEP)
    return [(start + k * STEP, q) for k in range(1, count + 1)]


def _quantity(text: str) -> float:
    return float(text.split()[0])


def _rows(text: str) -> list[tuple[float, float]]:
    lines = [ln for ln in text.splitlines() if ln and not ln.startswith("#")]
    return [(float(a), float(b)) for a, b in (ln.split(",") for ln in lines[1:])]


OUT_AND_BACK = _move(0.0, 0.0) + _hold(0.4, 0.6, H) + _move(0.6, H, -1.0, 1) + _hold(1.0, 1.3, 0)


def test_moves_between_rests_are_a_cycle_of_moves_and_dwells():
    result = read_csv_design(_csv(OUT_AND_BACK), source="m.csv", cam_file="m.csv")
    assert "task" not in result.design and "laws" not in result.design
    segments = result.design["cycle"]["segments"]
    assert [next(iter(s)) for s in segments] == ["move", "dwell", "move", "dwell"]
    out, back = segments[0]["move"], segments[2]["move"]
    assert out["law"] == {"kind": "cam_table", "file": "m-1.csv"}
    assert back["law"] == {"kind": "cam_table", "file": "m-2.csv"}
    assert _quantity(out["displacement"]) == float(f"{H:.12f}")
    assert _quantity(back["displacement"]) == -float(f"{H:.12f}")
    assert back["displacement"].endswith(" rad")
    # differences of the file's times to 15 digits: 0.2 s, not 0.6 - 0.4 = 0.19999999999999996
    assert out["duration"] == back["duration"] == "0.4 s"
    assert segments[1]["dwell"] == {"duration": "0.2 s"}
    assert segments[3]["dwell"] == {"duration": "0.3 s"}
    assert [name for name, _ in result.cams] == ["m-1.csv", "m-2.csv"]
    first, second = (_rows(text) for _, text in result.cams)
    assert len(first) == len(second) == 41
    assert first[0] == (0.0, 0.0) and first[-1] == (0.4, float(f"{H:.12f}"))
    assert second[0] == (0.6, float(f"{H:.12f}")) and second[-1] == (1.0, 0.0)
    assert any("are the design's dwells, its 2 moves a cycle" in n for n in result.notes)


def test_a_rest_before_the_move_ends_the_cycle():
    samples = [(0.0, 0.0), *_hold(0.0, 0.2, 0.0), *_move(0.2, 0.0, first=1)]
    result = read_csv_design(_csv(samples), source="m.csv", cam_file="m.csv")
    assert result.design["task"] == {"duration": "0.4 s", "dwell": "0.2 s"}
    assert result.design["laws"] == [{"kind": "cam_table", "file": "m.csv"}]
    rows = _rows(result.cam_csv)
    assert len(rows) == 41 and rows[0] == (0.2, 0.0)
    assert any("before its first move" in n for n in result.notes)


def test_a_move_across_the_end_of_the_cycle_is_one_move():
    """The table starts in the second half of an index and ends in the first half of the next
    (an indexing axis: H more per cycle of 0.8 s): one move of 0.4 s from 0.6 s."""
    tail = [(k * STEP, _cycloid((k + 20) * STEP / T) - H) for k in range(21)]
    head = [(0.6 + k * STEP, _cycloid(k * STEP / T)) for k in range(1, 21)]
    samples = [*tail, *_hold(0.2, 0.6, 0.0), *head]
    result = read_csv_design(_csv(samples), source="m.csv", cam_file="m.csv")
    assert result.design["task"] == {"duration": "0.4 s", "dwell": "0.4 s"}
    rows = _rows(result.cam_csv)
    assert len(rows) == 41
    for t, q in rows:
        assert q == pytest.approx(_cycloid((t - 0.6) / T), abs=2e-12)
    assert [t for t, _ in rows] == sorted(t for t, _ in rows)
    assert any("one move across the cycle's end" in n for n in result.notes)


def test_a_move_back_to_its_start_keeps_the_periodic_table():
    """Out and back with no rest between, then a rest: a move of displacement 0 is no move
    of a sizer cycle, so the rest stays in one periodic table (as before)."""
    samples = [*_move(0.0, 0.0), *_move(0.4, H, -1.0, 1), *_hold(0.8, 1.0, 0.0)]
    result = read_csv_design(_csv(samples), source="m.csv", cam_file="m.csv")
    assert result.design["laws"] == [{"kind": "cam_table", "file": "m.csv", "periodic": True}]
    assert result.design["task"]["dwell"] == "0 s"
    assert len(_rows(result.cam_csv)) == len(samples)
    assert any("returns to its start" in n for n in result.notes)


def test_a_motion_that_never_moves_is_refused():
    with pytest.raises(UserError, match="holds one position throughout"):
        read_csv_design(_csv([(0.0, 1.0), (0.5, 1.0), (1.0, 1.0)]), source="m.csv",
                        cam_file="m.csv")


def test_the_shared_csv_reader_keeps_the_template_rules_and_the_lines():
    """sizer.io.csv_rows reads the records: ';' only (a ',' is no separator, no decimal
    comma), a trailing ';' ignored, comment lines counted in the error's line."""
    table = read_motion_csv("# exported\nTime [s];Position [mm];\n0;0;\n1;2.5;\n",
                            source="m.csv")
    assert table.times == (0.0, 1.0) and table.positions == (0.0, 2.5)
    assert table.units == {"time": "s", "position": "mm"}
    with pytest.raises(UserError) as caught:
        read_motion_csv("# exported\nTime [s];Position [m]\n0;0\n1;2,5\n", source="m.csv")
    assert caught.value.line == 4 and caught.value.file == "m.csv"
    assert "Position: '2,5' is not a number (the decimal point is '.')" in caught.value.message
    with pytest.raises(UserError, match="'nan' is not a number"):
        read_motion_csv("Time [s];Position [m]\n0;0\n1;nan\n", source="m.csv")


def test_the_cycle_sizes_as_its_closed_form(tmp_path: Path):
    """The out-and-back cycle (no transmission, load inertia J_L only) sized: the peak torque
    is (J_m + J_L) 2 pi H / T^2; the RMS over the 1.3 s cycle of two cycloidal moves is
    (J_m + J_L) (2 pi H / T^2) sqrt(T / 1.3) (each move's mean square a_max^2 / 2)."""
    result = read_csv_design(_csv(OUT_AND_BACK), source="m.csv", cam_file="m.csv")
    for name, text in result.cams:
        (tmp_path / name).write_text(text, encoding="utf-8")
    design = {**result.design, "load": {"inertia": "0.5 kg*m^2"}, "motors": ["teco-jsma-p"]}
    path = tmp_path / "axis.yaml"
    path.write_text(yaml.safe_dump(design, sort_keys=False), encoding="utf-8")
    sized = run_cli("size", str(path), "--format", "json")
    assert sized.returncode == 0, sized.stderr
    import json

    top = next(r for r in json.loads(sized.stdout)["results"] if r["feasible"])
    motor = next(m for m in __import__("sizer").load(str(path)).motors if m.id == top["motor"])
    a_max = 2 * math.pi * H / T**2
    inertia = motor.inertia + 0.5
    assert top["peak_torque"] == pytest.approx(inertia * a_max, rel=2e-3)
    assert top["rms_torque"] == pytest.approx(inertia * a_max * math.sqrt(T / 1.3), rel=2e-3)


def test_idta_read_writes_a_cam_table_per_move_and_never_over_its_inputs(tmp_path: Path):
    import shutil

    source = tmp_path / "ob.csv"
    source.write_text(_csv(OUT_AND_BACK), encoding="utf-8")
    read = run_cli("idta", "read", str(source), "-o", str(tmp_path / "ob.yaml"))
    assert read.returncode == 0, read.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "ob-motion-1.csv", "ob-motion-2.csv", "ob.csv", "ob.yaml"]
    # a motion file of the submodel named like the cam table the output would write
    data = Path(__file__).parent / "data" / "idta"
    text = (data / "rotary-table.json").read_text(encoding="utf-8")
    assert text.count('"index-section.csv"') == 1
    (tmp_path / "axis.json").write_text(text.replace('"index-section.csv"', '"axis-motion.csv"'),
                                        encoding="utf-8")
    shutil.copy(data / "index-section.csv", tmp_path / "axis-motion.csv")
    before = (tmp_path / "axis-motion.csv").read_bytes()
    refused = run_cli("idta", "read", str(tmp_path / "axis.json"), "-o",
                      str(tmp_path / "axis.yaml"))
    assert_user_error(refused, "axis-motion.csv")
    assert (tmp_path / "axis-motion.csv").read_bytes() == before
    assert not (tmp_path / "axis.yaml").exists()
