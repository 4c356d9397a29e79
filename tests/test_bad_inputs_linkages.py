"""Bad values of the fields of a linkage stage, ``slider_crank`` and ``four_bar`` (issue
32), rule by rule: non-finite, wrong type, wrong unit, missing, unknown key, a boolean for
a number, and a linkage in a cycle. Each is answered by one ``error:`` line naming the
file, the LINE of the field (found by composing the YAML, tests/bad_input_lines.py) and
its path, exit code 2.

tests/test_bad_inputs_fields.py holds one case per field (mostly its range) and the rules
between fields; the cases here are the rules it does not exercise.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from bad_input_cases import Case, assert_well_formed, edited, run_case
from bad_input_lines import at

PRESS = "press-slider-crank.yaml"
"""transmission[1] a slider-crank (law on the output, from the top dead centre)."""
FLAP = "four-bar-coupler.yaml"
"""transmission[1] a four-bar crank-rocker, the coupler's angle the output."""
CYCLE = "press-slider-crank-cycle.yaml"
"""The press on a cycle of segments."""
T = "transmission[1]"
SC, FB = "transmission[slider_crank]", "transmission[four_bar]"
NAN, INF = float("nan"), float("inf")
FINITE = "not a finite number"


def bad(id: str, base: str, key: str, value: Any, words: tuple[str, ...], field: str,
        delete: bool = False, where: str | None = None) -> Case:
    """``transmission[1].key`` of ``base`` set to ``value`` (or deleted): the message
    names the file, the line and the field (``where``, default the key's path)."""
    path = f"{T}.{key}"
    text = edited(base, set={} if delete else {path: value},
                  delete=(path,) if delete else ())
    return Case(id, design=text, words=(*at(text, where or path), *words), fields=(field,))


SLIDER_CRANK = [
    bad("slider-crank-radius-nan", PRESS, "crank_radius", NAN, (FINITE,),
        f"{SC}.crank_radius"),
    bad("slider-crank-radius-an-angle", PRESS, "crank_radius", "10 deg",
        ("expected a length",), f"{SC}.crank_radius"),
    bad("slider-crank-radius-missing", PRESS, "crank_radius", None,
        ("required field is missing", f"{T}.crank_radius"), f"{SC}.crank_radius",
        delete=True, where=T),
    bad("slider-crank-rod-inf", PRESS, "rod_length", INF, (FINITE,), f"{SC}.rod_length"),
    bad("slider-crank-rod-a-list", PRESS, "rod_length", [1, 2], ("expected a length",),
        f"{SC}.rod_length"),
    bad("slider-crank-rod-missing", PRESS, "rod_length", None,
        ("required field is missing", f"{T}.rod_length"), f"{SC}.rod_length",
        delete=True, where=T),
    bad("slider-crank-offset-nan", PRESS, "offset", NAN, (FINITE,), f"{SC}.offset"),
    bad("slider-crank-offset-a-mass", PRESS, "offset", "1 kg", ("expected a length",),
        f"{SC}.offset"),
    bad("slider-crank-start-angle-nan", PRESS, "start_angle", NAN, (FINITE,),
        f"{SC}.start_angle"),
    bad("slider-crank-start-angle-huge", PRESS, "start_angle", "1e300 rad", ("rad",),
        f"{SC}.start_angle"),
    bad("slider-crank-crank-inertia-inf", PRESS, "crank_inertia", INF, (FINITE,),
        f"{SC}.crank_inertia"),
    bad("slider-crank-crank-inertia-a-mass", PRESS, "crank_inertia", "1 kg",
        ("expected an inertia",), f"{SC}.crank_inertia"),
    bad("slider-crank-rod-mass-nan", PRESS, "rod_mass_at_crank", NAN, (FINITE,),
        f"{SC}.rod_mass_at_crank"),
    bad("slider-crank-rod-mass-an-inertia", PRESS, "rod_mass_at_slider", "1 kg*m^2",
        ("expected a mass",), f"{SC}.rod_mass_at_slider"),
    bad("slider-crank-law-on-a-bool", PRESS, "law_on", True, ("crank", "output"),
        f"{SC}.law_on"),
    bad("slider-crank-direction-a-number", PRESS, "direction", 1, ("positive", "negative"),
        f"{SC}.direction"),
    bad("slider-crank-output-a-list", PRESS, "output", ["slider_position"],
        ("slider_position", "rod_angle"), f"{SC}.output"),
    bad("slider-crank-unknown-key", PRESS, "stroke", "100 mm",
        ("unknown field 'stroke'", "crank_radius"), f"{SC}.type"),
    bad("slider-crank-type-misspelt", PRESS, "type", "slidercrank", ("slider_crank",),
        f"{SC}.type"),
]

FOUR_BAR = [
    bad("four-bar-crank-nan", FLAP, "crank", NAN, (FINITE,), f"{FB}.crank"),
    bad("four-bar-crank-missing", FLAP, "crank", None,
        ("required field is missing", f"{T}.crank"), f"{FB}.crank", delete=True, where=T),
    bad("four-bar-coupler-an-angle", FLAP, "coupler", "10 deg", ("expected a length",),
        f"{FB}.coupler"),
    bad("four-bar-rocker-inf", FLAP, "rocker", INF, (FINITE,), f"{FB}.rocker"),
    bad("four-bar-ground-a-list", FLAP, "ground", [175], ("expected a length",),
        f"{FB}.ground"),
    bad("four-bar-ground-missing", FLAP, "ground", None,
        ("required field is missing", f"{T}.ground"), f"{FB}.ground", delete=True, where=T),
    bad("four-bar-branch-a-bool", FLAP, "branch", True, ("1 or -1", "True"), f"{FB}.branch"),
    bad("four-bar-branch-nan", FLAP, "branch", NAN, (FINITE,), f"{FB}.branch"),
    bad("four-bar-branch-a-word", FLAP, "branch", "open", ("1 or -1",), f"{FB}.branch"),
    bad("four-bar-start-angle-a-length", FLAP, "start_angle", "10 mm",
        ("expected an angle",), f"{FB}.start_angle"),
    bad("four-bar-start-angle-nan", FLAP, "start_angle", NAN, (FINITE,),
        f"{FB}.start_angle"),
    bad("four-bar-coupler-mass-nan", FLAP, "coupler_mass_at_crank", NAN, (FINITE,),
        f"{FB}.coupler_mass_at_crank"),
    bad("four-bar-coupler-mass-a-force", FLAP, "coupler_mass_at_rocker", "10 N",
        ("expected a mass",), f"{FB}.coupler_mass_at_rocker"),
    bad("four-bar-crank-inertia-nan", FLAP, "crank_inertia", NAN, (FINITE,),
        f"{FB}.crank_inertia"),
    bad("four-bar-driven-link-a-number", FLAP, "driven_link", 1, ("crank", "rocker"),
        f"{FB}.driven_link"),
    bad("four-bar-output-unknown", FLAP, "output", "ground_angle",
        ("rocker_angle", "coupler_angle"), f"{FB}.output"),
    bad("four-bar-law-on-unknown", FLAP, "law_on", "rocker", ("crank", "output"),
        f"{FB}.law_on"),
    bad("four-bar-direction-a-bool", FLAP, "direction", False, ("positive", "negative"),
        f"{FB}.direction"),
    bad("four-bar-name-nan", FLAP, "name", NAN, (FINITE,), f"{FB}.name"),
    bad("four-bar-unknown-key", FLAP, "length", "1 m", ("unknown field 'length'",),
        f"{FB}.type"),
]

IN_A_CYCLE = [
    bad("cycle-slider-crank-radius-nan", CYCLE, "crank_radius", NAN, (FINITE,),
        f"{SC}.crank_radius"),
    bad("cycle-slider-crank-offset-a-list", CYCLE, "offset", [1], ("expected a length",),
        f"{SC}.offset"),
]

OVERSHOOT = edited(PRESS, set={"laws": ["polynomial_4_3_4(h_l=0, h_s=0)"]})
"""The press from the end of its range (a dead point) with a 4-3-4 polynomial whose position
dips below zero (h_l = h_s = 0: q_N down to -0.0176): the stroke is inside the range, the
law's own excursion is not; the message is placed at the law's line."""

LAW_PAST_THE_RANGE = [
    Case("slider-crank-law-overshoots-the-range", design=OVERSHOOT,
         words=(*at(OVERSHOOT, "laws"), "polynomial_4_3_4", "0.148242 m", "0.00176 m below",
                "the end 0.15 m", "overshoots its stroke"), fields=("laws",)),
]

CASES = [*SLIDER_CRANK, *FOUR_BAR, *IN_A_CYCLE, *LAW_PAST_THE_RANGE]


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_linkage_field(case: Case, tmp_path: Path) -> None:
    run_case(case, tmp_path)


def test_case_ids_are_unique_and_fields_are_the_models() -> None:
    assert_well_formed(CASES)


def test_a_branch_of_one_as_a_number_is_still_read() -> None:
    """1 and -1 (also written 1.0) stay valid: only a YAML boolean is refused."""
    from sizer.io.schema.transmission_inputs import FourBarInput

    links = {"type": "four_bar", "crank": 0.075, "coupler": 0.175, "rocker": 0.1,
             "ground": 0.175}
    assert FourBarInput.model_validate({**links, "branch": -1}).branch == -1
    assert FourBarInput.model_validate({**links, "branch": 1.0}).branch == 1
