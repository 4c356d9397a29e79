"""A tolerance on the load's mode (issue 39: "a mode frequency measured after the fact"):
``natural_frequency: 25 Hz +- 10 %`` (or ``load.natural_frequency`` / ``load.damping_ratio``
in ``tolerances:``) moves the residual vibration only.

Reference: each corner written as its own design (the mode's frequency and damping ratio
replaced) and sized on its own; the robust worst case is the worst over them (the
residual is not monotone in the frequency: the corners are the builds sized, as for any
input), and the sensitivity to the frequency is the central difference of two separate
sizings.
"""

from __future__ import annotations

import itertools
from dataclasses import replace

import pytest
from bad_input_cases import EXAMPLES, edited

from sizer import api
from sizer.model.tolerance import Tolerance
from sizer.robust import robust_sizing

DESIGN = "indexing-table-vibration.yaml"
MOTORS = str(EXAMPLES / "catalogs" / "example-servo.yaml")
CORNER_F = (25.0 * (1.0 - 0.1), 25.0 * (1.0 + 0.1))
CORNER_Z = (0.02 * (1.0 - 0.5), 0.02 * (1.0 + 0.5))
"""The corners' frequencies and damping ratios, as robust sizing computes them."""


def _design(tmp_path, **changes):
    path = tmp_path / "design.yaml"
    path.write_text(edited(DESIGN, set={"motors": MOTORS, **changes}), encoding="utf-8")
    design = api.load(path)
    return replace(design, motors=design.motors[2:], laws=design.laws[:2])


def _with_mode(design, frequency: float, ratio: float):
    elastic = replace(design.load.elastic, natural_frequency=frequency, damping_ratio=ratio)
    return replace(design, load=replace(design.load, elastic=elastic), tolerances=())


def test_the_inline_mode_tolerance_is_the_section_s(tmp_path):
    inline = _design(tmp_path, **{"load.natural_frequency": "25 Hz +- 10 %"})
    assert inline.tolerances == (Tolerance("load.natural_frequency", 0.1),)


def test_worst_duration_is_the_worst_over_the_mode_s_corners(tmp_path):
    design = replace(_design(tmp_path), tolerances=(
        Tolerance("load.natural_frequency", 0.1), Tolerance("load.damping_ratio", 0.5)))
    robust = robust_sizing(design, api.size(design))
    corners = {(f, z): {(r.motor, r.spec): r for r in api.size(_with_mode(design, f, z)).results}
               for f, z in itertools.product(CORNER_F, CORNER_Z)}
    for result in robust.results:
        key = (result.nominal.motor, result.nominal.spec)
        durations = [c[key].duration for c in corners.values()]
        assert result.duration is not None
        if all(d is not None for d in durations):
            assert result.duration.worst == pytest.approx(max(durations), rel=1e-12)
        residual = [c[key].margin("residual_vibration") for c in corners.values()]
        assert result.worst["residual_vibration"] == pytest.approx(min(residual), abs=1e-12)


def test_the_sensitivity_to_the_mode_frequency(tmp_path):
    from sizer.sensitivity import STEP, sensitivity

    design = _design(tmp_path)
    found = sensitivity(design, "HG-KN73J", "cycloidal")
    row = next(i for i in found.inputs if i.name == "load.natural_frequency")
    assert row.value == 25.0 and row.unit == "Hz"
    fixed = replace(design, motors=tuple(m for m in design.motors if m.id == "HG-KN73J"),
                    laws=(design.laws[0],))
    low, high = (api.size(_with_mode(fixed, 25.0 * f, 0.02)).results[0]
                 for f in (1.0 - STEP, 1.0 + STEP))
    assert row.slopes["residual_vibration"].central == pytest.approx(
        (high.margin("residual_vibration") - low.margin("residual_vibration")) / (2 * STEP),
        rel=1e-9, abs=1e-12)


@pytest.mark.parametrize(("laws", "sizings"), [(slice(0, 2), 1), (slice(2, 4), 4)])
def test_builds_of_the_mode_are_rows_unless_a_law_is_shaped_for_it(tmp_path, monkeypatch,
                                                                   laws, sizings):
    """The mode's corners are rows of one sizing (each row's residual by its build's mode);
    a law shaped for the load's mode at each duration is shaped again at each build, so
    its builds are sizings of their own (four corners: four sizings)."""
    from engine_calls import counted_sizings

    design = _design(tmp_path)
    laws_given = api.load(EXAMPLES / DESIGN).laws[laws]
    design = replace(design, motors=design.motors[1:], laws=laws_given, tolerances=(
        Tolerance("load.natural_frequency", 0.1), Tolerance("load.damping_ratio", 0.5)))
    nominal = api.size(design)
    robust, count = counted_sizings(monkeypatch, lambda: robust_sizing(design, nominal))
    assert count == sizings
    corners = [{(r.motor, r.law): r for r in api.size(_with_mode(design, f, z)).results}
               for f, z in itertools.product(CORNER_F, CORNER_Z)]
    # a shaped law by its family, shaped at each build: its T_min iteration stops at a
    # relative 1e-9 (sizer.sizing.choices.RTOL) whose step depends on the motors sized
    # with it, and the shaped law's residual there is ~1e-9 of the limit
    tolerance = 1e-12 if sizings == 1 else 1e-8
    for result in robust.results:
        key = (result.nominal.motor, result.nominal.law)
        residual = [c[key].margin("residual_vibration") for c in corners]
        assert result.worst["residual_vibration"] == pytest.approx(min(residual),
                                                                   abs=tolerance)
