"""The later limits (residual vibration, braking resistor, winding rise) are settled in the
one search for the shortest duration (sizer.sizing.shortest_duration.settle).

- With both a residual-vibration limit and a braking limit, T_min is the smallest duration
  at which every check passes: every shorter duration tried at a given duration fails one.
- A candidate infeasible at every duration names the check that fails there (its inertia
  ratio, (J_L / N^2 + J_gear) / J_m, a closed form), not a check evaluated at no duration.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import yaml

import sizer.api as api

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "indexing-table-vibration.yaml"
CATALOG = EXAMPLE.parent / "catalogs" / "example-servo.yaml"
ARCSEC = math.pi / 180 / 3600


def _design(**task: object) -> dict:
    data = yaml.safe_load(EXAMPLE.read_text())
    data["motors"] = str(CATALOG)
    data["laws"] = ["cycloidal"]
    data["limits"]["braking_resistor_power"] = "0.5 W"
    data["task"].update(task)
    return data


def _sized(tmp_path: Path, name: str, **task: object):
    path = tmp_path / f"{name}.yaml"
    path.write_text(yaml.safe_dump(_design(**task)))
    return api.size(str(path), motors=["HG-KN73J"]).results[0]


def test_vibration_and_braking_settle_at_the_shortest_duration_passing_both(tmp_path):
    best = _sized(tmp_path, "minimize")
    assert best.feasible
    assert best.residual_vibration <= 20 * ARCSEC * (1 + 1e-9)
    braking = best.check("braking_resistor_power")
    assert braking.passed and braking.value <= 0.5 * (1 + 1e-9)
    # the mechanical T_min alone (no later limit) is shorter: the later limits moved it
    plain = _design()
    plain["limits"].pop("braking_resistor_power")
    plain["limits"].pop("residual_vibration")
    path = tmp_path / "plain.yaml"
    path.write_text(yaml.safe_dump(plain))
    mechanical = api.size(str(path), motors=["HG-KN73J"]).results[0].duration
    assert mechanical < best.duration
    # every shorter duration from the mechanical T_min up fails some check there
    for k, T in enumerate(np.linspace(mechanical, best.duration * (1 - 1e-6), 12)):
        at = _sized(tmp_path, f"at{k}", duration=f"{float(T)!r} s")
        assert not at.feasible, T
        assert at.limiting in ("residual_vibration", "braking_resistor_power")
    at = _sized(tmp_path, "at_best", duration=f"{best.duration * (1 + 1e-9)!r} s")
    assert at.feasible


def test_an_infeasible_candidate_names_the_check_failing_at_every_duration(tmp_path):
    data = yaml.safe_load(EXAMPLE.read_text())
    data["motors"] = str(CATALOG)
    path = tmp_path / "vibration.yaml"
    path.write_text(yaml.safe_dump(data))
    motors = {m.id: m for m in api.load(str(path)).motors}
    load, gearbox, ratio = 0.034, 0.3e-4, 10.0  # kg*m^2 (the example's figures)
    result = api.size(str(path))  # the feasible candidates moved up by the limit too
    assert sum(not row.feasible and row.law != "shaped" for row in result.results) == 6
    for row in result.results:
        if row.law == "shaped" or row.feasible:
            continue
        expected = (load / ratio**2 + gearbox) / motors[row.motor].inertia
        assert row.limiting == "inertia_ratio"
        assert row.check("inertia_ratio").value == pytest.approx(expected, rel=1e-12)
        assert all(c.value is not None and np.isfinite(c.value) for c in row.checks)


def test_a_limit_without_the_mode_it_needs_is_refused_not_skipped(tmp_path):
    """Built in code (sizer.io refuses it at its line), a residual-vibration limit on a
    load without a mode is an error, never a limit left unchecked."""
    from dataclasses import replace

    from sizer.errors import UserError

    data = yaml.safe_load(EXAMPLE.read_text())
    data["motors"] = str(CATALOG)
    path = tmp_path / "vibration.yaml"
    path.write_text(yaml.safe_dump(data))
    design = api.load(str(path))
    without_mode = replace(design, load=replace(design.load, elastic=None))
    with pytest.raises(UserError, match="residual_vibration limit needs the load's mode"):
        api.size(without_mode)


def test_a_winding_limit_on_motors_without_thermal_data_is_said(tmp_path):
    """The example catalog gives no thermal time constant: a winding-rise limit cannot be
    checked there, and the notes say so by motor (the RMS check stands for it)."""
    data = yaml.safe_load(EXAMPLE.read_text())
    data["motors"] = str(CATALOG)
    data["limits"]["winding_temperature_rise"] = "80 K"
    path = tmp_path / "hot.yaml"
    path.write_text(yaml.safe_dump(data))
    notes = api.size(str(path), motors=["HG-KN43J"]).notes
    said = [n for n in notes if "winding_temperature_rise is not checked" in n]
    assert len(said) == 1 and "HG-KN43J" in said[0]
