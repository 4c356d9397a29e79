"""Law choices read once at the input boundary (sizer.laws.choice.LawChoice)."""

from __future__ import annotations

import pickle
from fractions import Fraction
from pathlib import Path

import pytest

from sizer.errors import UserError
from sizer.io import load_design
from sizer.laws import LawChoice, law_choice, make_law
from sizer.laws.data_law import DataLaw
from sizer.laws.piecewise_polynomial import DoubleS, Trapezoidal
from sizer.laws.polynomial import Polynomial
from sizer.laws.trigonometric import Cycloidal
from sizer.model.cycle import Move
from sizer.model.domain import Design, Load, Task

EXAMPLES = Path(__file__).parent.parent / "examples"
SPLINE = "{kind: cubic_spline, points: [[0, 0], [0.5, 0.4], [1, 1]]}"
OPEN_SHAPED = "{kind: shaped, law: cycloidal, shaper: zv}"


def test_plain_spec() -> None:
    choice = law_choice("cycloidal")
    assert (choice.text, choice.family, choice.values) == ("cycloidal", Cycloidal, ())
    assert choice.auto == () and choice.fixed == {}
    assert choice.is_fixed and not choice.open_shaped
    assert choice.law is make_law("cycloidal")
    assert str(choice) == "cycloidal"


def test_alias_and_fraction() -> None:
    poly5 = law_choice("poly5")
    assert poly5.family is Polynomial and poly5.fixed == {"degree": Fraction(5)}
    trapezoid = law_choice("trapezoidal(alpha=1/3)")
    assert trapezoid.text == "trapezoidal(alpha=1/3)"
    assert trapezoid.family is Trapezoidal
    assert trapezoid.fixed == {"alpha": Fraction(1, 3)}  # exact, not 0.333...
    assert trapezoid.law.params["alpha"] == pytest.approx(1.0 / 3.0, rel=1e-15)


def test_auto_parameters() -> None:
    choice = law_choice("double_s(beta=1/4, alpha=auto)")
    assert choice.family is DoubleS
    assert choice.auto == ("alpha",)  # in the family's order
    assert choice.fixed == {"beta": Fraction(1, 4)}
    assert not choice.is_fixed
    assert dict(choice.values) == {"alpha": "auto", "beta": Fraction(1, 4)}
    with pytest.raises(UserError, match="auto"):
        _ = choice.law


def test_data_specs() -> None:
    spline = law_choice(SPLINE)
    assert spline.text == SPLINE  # already the canonical text
    assert issubclass(spline.family, DataLaw) and spline.family.law_id == "cubic_spline"
    assert spline.is_fixed and isinstance(spline.law, DataLaw)
    shaped = law_choice(OPEN_SHAPED)
    assert shaped.open_shaped and not shaped.is_fixed
    assert shaped.family.law_id == "shaped"


def test_parsed_once_and_passed_through() -> None:
    choice = law_choice("harmonic")
    assert law_choice("harmonic") is choice
    assert law_choice(choice) is choice


@pytest.mark.parametrize("spec", ["poly7", "double_s(alpha=auto, beta=auto)", SPLINE,
                                  OPEN_SHAPED])
def test_pickle_round_trip(spec: str) -> None:
    choice = law_choice(spec)
    again = pickle.loads(pickle.dumps(choice))
    assert isinstance(again, LawChoice)
    assert again == choice and hash(again) == hash(choice)


def test_design_reads_texts() -> None:
    design = Design(Task(1.0), Load(1e-3), laws=("cycloidal", law_choice("poly5")),
                    chosen_law="poly5")
    assert all(isinstance(c, LawChoice) for c in design.laws)
    assert [c.text for c in design.laws] == ["cycloidal", "poly5"]
    assert design.chosen_law == law_choice("poly5")
    assert Move(1.0, law="poly7").law == law_choice("poly7")


def test_io_reads_choices_and_locates_a_bad_spec(tmp_path) -> None:
    text = (EXAMPLES / "book" / "ex6_1-6_2.yaml").read_text()
    design = load_design(EXAMPLES / "book" / "ex6_1-6_2.yaml")
    assert [c.text for c in design.laws] == ["cycloidal",
                                             "trapezoidal(alpha=0.12732200375003505)"]
    assert all(isinstance(c, LawChoice) for c in design.laws)
    path = tmp_path / "design.yaml"
    path.write_text(text.replace("  - cycloidal\n", "  - sinusoid\n"))
    with pytest.raises(UserError) as error:
        load_design(path)
    line = text.splitlines().index("  - cycloidal") + 1
    assert (error.value.line, error.value.field) == (line, "laws[0]")
    assert "unknown law 'sinusoid'" in error.value.message


def test_known_by_its_text() -> None:
    choice = law_choice("trapezoidal(alpha=1/3)")
    assert choice == "trapezoidal(alpha=1/3)" and hash(choice) == hash(choice.text)
    assert choice != "trapezoidal(alpha=0.25)" and choice != law_choice("cycloidal")
    assert "trapezoidal(alpha=1/3)" in {choice}
