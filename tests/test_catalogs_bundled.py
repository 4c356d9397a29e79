"""The bundled catalogs of real motors: clean, sourced, copied from the datasheets, usable.

The figures are checked against the research notes (../shared/reference/motor-data.md)
where that file is present: every number of a motor's ratings must appear, as written, on
its row of the notes, so no figure was invented, rounded or converted on the way.
"""

from __future__ import annotations

import itertools
import re
import tomllib
from collections import Counter
from importlib import resources
from pathlib import Path

import pytest
import yaml

from sizer.catalog_tools import validate_catalogs
from sizer.errors import UserError
from sizer.io import (
    NOT_DEFAULT_CATALOGS,
    bundled_catalogs,
    default_catalogs,
    load_catalog,
    load_design,
)
from sizer.sizing import size_design

ROOT = Path(__file__).resolve().parent.parent
REFERENCE = next((folder / "shared" / "reference" / "motor-data.md" for folder in ROOT.parents
                  if (folder / "shared" / "reference" / "motor-data.md").is_file()),
                 ROOT.parent / "shared" / "reference" / "motor-data.md")
REAL = sorted(set(bundled_catalogs()) - NOT_DEFAULT_CATALOGS)
RPM = 2 * 3.141592653589793 / 60


def real_motors():
    return [m for name in REAL for m in load_catalog(name)]


def raw_motors():
    """(catalog name, motor mapping as written) of every real motor."""
    out = []
    for name in REAL:
        data = yaml.safe_load(bundled_catalogs()[name].read_text(encoding="utf-8"))
        out += [(name, motor) for motor in data["motors"]]
    return out


# ------------------------------------------------------------------ clean and sourced


def test_every_bundled_catalog_validates_with_no_findings():
    report = validate_catalogs(list(bundled_catalogs().values()))
    assert report.unreadable == []
    assert [str(f) for f in report.findings] == []
    assert report.exit_code == 0
    assert len(report.files) == len(bundled_catalogs())


def test_at_least_40_real_motors_from_at_least_4_manufacturers():
    motors = real_motors()
    assert len(motors) >= 40
    makers = Counter(m.manufacturer for m in motors)
    assert len(makers) >= 4, makers
    assert None not in makers


def test_ids_are_unique_across_all_bundled_catalogs():
    ids = [m.id for name in bundled_catalogs() for m in load_catalog(name)]
    assert len(ids) == len(set(ids))


def test_every_motor_has_a_source_with_a_web_address_and_a_trust_grade():
    for motor in real_motors():
        assert motor.source and re.search(r"https?://\S+", motor.source), motor.id
    for name, raw in raw_motors():
        assert re.match(r"grade [AB]\b", raw.get("notes", "")), (name, raw["id"])


def test_real_motors_have_a_rotor_inertia_and_consistent_ratings():
    for motor in real_motors():
        assert motor.inertia > 0, motor.id
        assert motor.peak_torque >= motor.continuous_torque, motor.id
        assert motor.max_speed is None or motor.max_speed >= motor.rated_speed, motor.id


def test_quantities_are_written_with_their_units():
    """Datasheet figures keep a unit in the file; no bare SI number sneaks in."""
    fields = ("inertia", "continuous_torque", "peak_torque", "rated_speed", "max_speed",
              "mass")
    for name, raw in raw_motors():
        for key in fields:
            if key in raw:
                assert isinstance(raw[key], str) and " " in raw[key], (name, raw["id"], key)
        for key in ("continuous_curve", "intermittent_curve"):
            for point in raw.get(key, ()):
                assert all(isinstance(v, str) and " " in v for v in point), (name, key)


def test_curves_where_the_datasheets_give_points():
    by_id = {m.id: m for m in real_motors()}
    assert by_id["1FT7044-AK7"].continuous_curve is not None
    assert by_id["HC52"].continuous_curve is not None
    assert by_id["EC45flat-30W-339281"].intermittent_curve is not None
    # written out so that no envelope rule extends it to the mechanical 9000 rpm
    assert _flat(by_id["1FT7044-AK7"].intermittent_curve) == pytest.approx(
        [0.0, 23.0, 6000 * RPM, 23.0])
    # corner figures only (the curves are drawn, not printed): no invented curve, the
    # design's envelope rule completes the regions
    for motor_id in ("SGM7J-02A", "SGM7A-15A", "SGM7G-03A", "SGMAH-01A", "SGMSH-10AA",
                     "HG-KN43J", "JSMA-PMC10"):
        assert by_id[motor_id].continuous_curve is None, motor_id
        assert by_id[motor_id].intermittent_curve is None, motor_id


def _flat(curve):
    return [value for point in curve for value in point]


def test_every_bundled_curve_falls_with_speed_from_standstill():
    for motor in real_motors():
        for curve in (motor.continuous_curve, motor.intermittent_curve):
            if curve is None:
                continue
            speeds, torques = zip(*curve, strict=True)
            assert speeds[0] == 0.0, motor.id
            assert all(b > a for a, b in itertools.pairwise(speeds)), motor.id
            assert all(b <= a for a, b in itertools.pairwise(torques)), motor.id
        if motor.continuous_curve and motor.intermittent_curve:
            assert motor.continuous_curve[0][1] <= motor.intermittent_curve[0][1], motor.id


def _cell_number(cells: dict[str, str], heading: str) -> float:
    matches = [c for h, c in cells.items() if h.lower().startswith(heading.lower())]
    assert matches, (heading, list(cells))
    return float(re.match(r"\d+(?:\.\d+)?", matches[0].replace(",", "")).group(0))


@pytest.mark.skipif(not REFERENCE.is_file(), reason="the motor-data notes are not here")
def test_curve_points_are_the_notes_figures():
    """Each curve point is a figure of the notes' table, in the column that defines it."""
    checked = 0
    for catalog, raw in raw_motors():
        motor = {m.id: m for m in load_catalog(catalog)}[raw["id"]]
        if catalog == "maxon-ec45-flat":  # the line at nominal voltage: stall -> no-load
            cells = _table_cells(str(raw["part_number"]))
            expected = ((0.0, _cell_number(cells, "Stall torque") * 1e-3),
                        (_cell_number(cells, "No-load speed") * RPM, 0.0))
            assert _flat(motor.intermittent_curve) == pytest.approx(_flat(expected)), raw["id"]
            checked += 1
        elif catalog == "mitsubishi-hc":  # S1: stall torque at 0, rated torque at rated speed
            cells = _table_cells(raw["id"])
            expected = ((0.0, _cell_number(cells, "Stall torque")),
                        (_cell_number(cells, "Rated speed") * RPM,
                         _cell_number(cells, "Rated torque")))
            assert _flat(motor.continuous_curve) == pytest.approx(_flat(expected)), raw["id"]
            checked += 1
    siemens = {m.id: m for m in load_catalog("siemens-1ft7")}["1FT7044-AK7"]
    section = REFERENCE.read_text(encoding="utf-8").split("## 3. Siemens")[1].split("## 4.")[0]
    for fragment in ("| Rated speed nr | 6,000 rpm |", "| Rated torque (100 K) | 2 Nm |",
                     "/ 5 Nm |", "| 23 Nm / 30 A |"):
        assert fragment in section, fragment
    assert _flat(siemens.continuous_curve) == pytest.approx([0.0, 5.0, 6000 * RPM, 2.0])
    assert _flat(siemens.intermittent_curve) == pytest.approx([0.0, 23.0, 6000 * RPM, 23.0])
    assert checked == 6 + 8


def test_a_known_figure_in_si():
    motor = {m.id: m for m in load_catalog("yaskawa-sgm7j")}["SGM7J-02A"]
    assert motor.inertia == pytest.approx(0.263e-4)
    assert motor.continuous_torque == pytest.approx(0.637)
    assert motor.peak_torque == pytest.approx(2.23)
    assert motor.rated_speed == pytest.approx(3000 * 2 * 3.141592653589793 / 60)
    assert motor.manufacturer == "Yaskawa"


# ------------------------------------------------------------------ copied from the notes


def _numbers(text: str) -> set[str]:
    """The numbers of a line as written, thousands separators dropped ('6,000' -> '6000')."""
    text = re.sub(r"(?<=\d),(?=\d{3}\b)", "", text)
    return set(re.findall(r"\d+(?:\.\d+)?", text))


def _reference_rows() -> dict[str, str]:
    """Motor name (as in the catalogs) -> the text of its row (or section) in the notes."""
    text = REFERENCE.read_text(encoding="utf-8")
    rows: dict[str, str] = {}
    for line in text.splitlines():
        if not line.startswith("| "):
            continue
        first = line.strip("|").split("|")[0].strip()
        name = re.sub(r"\s*\((200 V|Hall|sensorless)\)$", "", first)
        name = name.replace("(B)J", "J")
        rows.setdefault(name, line)
    section = text.split("## 3. Siemens")[1].split("## 4.")[0]
    rows["1FT7044-AK7"] = section
    return rows


def _name_in_notes(catalog: str, raw: dict) -> str:
    if catalog == "maxon-ec45-flat":
        return str(raw["part_number"])
    return str(raw["id"])


@pytest.mark.skipif(not REFERENCE.is_file(), reason="the motor-data notes are not here")
def test_every_figure_is_on_the_motors_row_of_the_reference_notes():
    rows = _reference_rows()
    fields = ("inertia", "continuous_torque", "peak_torque", "rated_speed", "max_speed",
              "mass")
    checked = 0
    for catalog, raw in raw_motors():
        name = _name_in_notes(catalog, raw)
        assert name in rows, f"{catalog}: {name} has no row in the notes"
        on_row = _numbers(rows[name])
        texts = [raw[k] for k in fields if k in raw]
        for key in ("continuous_curve", "intermittent_curve"):
            texts += [v for point in raw.get(key, ()) for v in point]
        for text in texts:
            number = text.split()[0]
            value = number.split("e")[0]  # '0.263e-4 kg*m^2': the notes print 0.263 x10^-4
            if float(value) == 0:
                continue  # standstill and zero-torque ends of curves
            assert value in on_row, f"{catalog}: {raw['id']}: {text!r} not on its row"
            checked += 1
    assert checked > 300


SERVO_COLUMNS = {"continuous_torque": "Rated torque", "peak_torque": "Inst.",
                 "rated_speed": "Rated speed", "max_speed": "Max speed",
                 "inertia": "Rotor inertia"}
COLUMNS = {
    "yaskawa-sgm7j": SERVO_COLUMNS,
    "yaskawa-sgm7a": SERVO_COLUMNS,
    "yaskawa-sgm7g": SERVO_COLUMNS,
    "yaskawa-sgmah": SERVO_COLUMNS,
    "yaskawa-sgmsh": SERVO_COLUMNS,
    "mitsubishi-hg-kn": {**SERVO_COLUMNS, "peak_torque": "Max torque",
                         "inertia": "Moment of inertia"},
    "mitsubishi-hc-r": {**SERVO_COLUMNS, "peak_torque": "Max torque", "inertia": "J ("},
    "mitsubishi-hc": {**SERVO_COLUMNS, "continuous_torque": "Stall torque",
                      "peak_torque": "Max torque", "inertia": "J ("},
    "teco-jsma-p": {**SERVO_COLUMNS, "peak_torque": "Max torque", "mass": "Weight"},
    "maxon-ec45-flat": {"continuous_torque": "Nominal torque", "peak_torque": "Stall torque",
                        "rated_speed": "Nominal speed", "inertia": "Rotor inertia"},
}
"""Catalog -> field -> the start of the notes' column heading that holds the figure."""


def _table_cells(name: str) -> dict[str, str]:
    """Column heading -> cell of the notes' table row of motor ``name``."""
    lines = REFERENCE.read_text(encoding="utf-8").splitlines()
    for index, line in enumerate(lines):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        first = re.sub(r"\s*\((200 V|Hall|sensorless)\)$", "", cells[0]).replace("(B)J", "J")
        if line.startswith("| ") and first == name:
            head = index
            while not lines[head - 1].startswith("|---"):
                head -= 1
            headings = [c.strip() for c in lines[head - 2].strip().strip("|").split("|")]
            return dict(zip(headings, cells, strict=True))
    raise AssertionError(f"{name} not in the notes")


@pytest.mark.skipif(not REFERENCE.is_file(), reason="the motor-data notes are not here")
def test_each_rating_comes_from_its_own_column_of_the_notes():
    """Not only on the row: the rated torque from the rated-torque column, and so on."""
    checked = 0
    for catalog, raw in raw_motors():
        columns = COLUMNS.get(catalog)
        if columns is None:
            continue  # the Siemens motor: a field/value table, checked by the test above
        cells = _table_cells(_name_in_notes(catalog, raw))
        for key, heading in columns.items():
            matches = [h for h in cells if h.lower().startswith(heading.lower())]
            assert matches, (catalog, key, heading, list(cells))
            cell = cells[matches[0]].replace(",", "")
            first = re.match(r"\d+(?:\.\d+)?", cell)
            assert first, (catalog, raw["id"], key, cell)
            assert raw[key].split()[0].split("e")[0] == first.group(0), (catalog, raw["id"], key)
            checked += 1
    assert checked >= 4 * 60


@pytest.mark.skipif(not REFERENCE.is_file(), reason="the motor-data notes are not here")
def test_no_grade_d_or_left_out_series_shipped():
    ids = {m.id for m in real_motors()}
    for left_out in ("SGM7G-30A", "SGM7G-44A", "AM8011-wByz", "AM3011-wB00", "AS1010-0000",
                     "YM070-210-M001-RH", "NEO", "X6-8", "353297"):
        assert not any(left_out in motor_id for motor_id in ids)


# ------------------------------------------------------------------ package data, defaults


def test_package_data_includes_the_catalogs():
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    globs = pyproject["tool"]["setuptools"]["package-data"]["sizer"]
    assert "catalogs/*.yaml" in globs
    # every bundled file, drives and gearboxes too, is installed with the package
    catalogs = ROOT / "sizer" / "catalogs"
    for path in catalogs.rglob("*.yaml"):
        relative = path.relative_to(ROOT / "sizer").as_posix()
        # setuptools' globs: '*' stays within one folder
        assert any(re.fullmatch(re.escape(glob).replace(r"\*", "[^/]*"), relative)
                   for glob in globs), relative
    folder = resources.files("sizer").joinpath("catalogs")
    names = sorted(p.name for p in folder.iterdir() if p.name.endswith(".yaml"))
    assert names == sorted(f"{n}.yaml" for n in bundled_catalogs())
    for path in bundled_catalogs().values():
        assert path.parent.name == "catalogs" and path.parent.parent.name == "sizer"


def test_the_default_set_is_every_real_catalog():
    assert sorted(default_catalogs()) == REAL
    assert "book-examples" not in default_catalogs()
    assert "book-examples" in bundled_catalogs()


# ------------------------------------------------------------------ end to end sizing

ROTARY_TABLE = """\
name: rotary table, 90 deg in 0.3 s
task: {displacement: 90 deg, duration: 0.3 s, dwell: 0.3 s}
load: {inertia: 0.05 kg*m^2, friction: 0.5 N*m}
transmission: {type: gearbox, ratio: 10, efficiency: 0.95}
laws: [cycloidal, modified_sinusoidal, trapezoidal(alpha=1/3)]
limits: {torque_margin: 10 %, inertia_ratio: 10}
"""


def test_a_design_without_motors_is_sized_against_the_bundled_real_motors(tmp_path):
    path = tmp_path / "table.yaml"
    path.write_text(ROTARY_TABLE)
    design = load_design(path, default_motors=True)
    real_ids = {m.id for m in real_motors()}
    assert {m.id for m in design.motors} == real_ids
    result = size_design(design)
    feasible = [r.feasible for r in result.results]
    assert any(feasible) and not all(feasible)
    assert feasible == sorted(feasible, reverse=True)  # feasible pairs first
    winners = {r.motor for r in result.results if r.feasible}
    assert winners <= real_ids
    # a 200 W motor cannot drive 0.05 kg*m^2 through 10:1 in 0.3 s; a 1.5 kW one can
    assert "SGM7J-02A" not in winners and "SGM7A-15A" in winners
    assert {m.split("-")[0] for m in winners} >= {"SGM7A", "JSMA"}


def test_the_default_set_is_opt_in_and_yields_to_named_catalogs(tmp_path):
    path = tmp_path / "table.yaml"
    path.write_text(ROTARY_TABLE)
    assert load_design(path).motors == ()  # without default_motors, as before
    only = load_design(path, extra_catalogs=["siemens-1ft7"], default_motors=True)
    assert [m.id for m in only.motors] == ["1FT7044-AK7"]
    path.write_text(ROTARY_TABLE + "motors: []\n")  # no bundled motors in its place:
    with pytest.raises(UserError, match="no motors to size") as refused:  # refused at its line
        load_design(path, default_motors=True)
    assert refused.value.line == ROTARY_TABLE.count("\n") + 1
    assert refused.value.field == "motors"
    path.write_text(ROTARY_TABLE + "motors: teco-jsma-p\n")
    assert len(load_design(path, default_motors=True).motors) == 9
