"""The open shaped law's search for T (sizer.sizing.choices.evaluate_shaped) keeps a
candidate's row from an earlier round where its T did not move (issue 34): every row must
be what its own law, the law shaped at its final T, gives the candidate sized alone."""

from __future__ import annotations

from dataclasses import replace

from test_shaped_sizing import design

from sizer.io import load_design
from sizer.sizing.engine import size_design


def test_every_row_is_its_own_law_sized_alone(tmp_path):
    design(tmp_path, "{kind: shaped, law: cycloidal, shaper: zv}")
    # the whole example catalog: its motors' T settle in different rounds
    loaded = load_design(tmp_path / "d.yaml")
    results = size_design(loaded).results
    assert sum(r.feasible for r in results) >= 3
    for r in results:
        (again,) = size_design(replace(loaded, laws=(r.spec,),
                                       motors=(r.motor_object,))).results
        assert again.feasible == r.feasible
        if r.feasible:
            assert (again.duration, again.peak_torque, again.rms_torque) == (
                r.duration, r.peak_torque, r.rms_torque)
