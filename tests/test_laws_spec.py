"""The law spec grammar and the registry's messages."""

from __future__ import annotations

from fractions import Fraction

import pytest

from sizer.errors import UserError
from sizer.laws import AUTO, LAW_FAMILIES, known_law_ids, make_law, parse_law_spec, resolve


def test_parse_plain_and_keyword_and_positional():
    assert parse_law_spec("cycloidal").name == "cycloidal"
    spec = parse_law_spec(" double_s( alpha = 1/3 , beta=0.25 ) ")
    assert spec.args == (("alpha", Fraction(1, 3)), ("beta", Fraction(1, 4)))
    assert parse_law_spec("polynomial(7)").args == ((None, Fraction(7)),)
    assert parse_law_spec("exponential(sigma=7.1e0, lam=2e-1)").args[1] == ("lam", Fraction(1, 5))
    assert parse_law_spec("trapezoidal(alpha=auto)").args == (("alpha", AUTO),)
    assert parse_law_spec("cycloidal()").args == ()


def test_fractions_are_exact():
    law = make_law("trapezoidal(alpha=1/3)")
    assert law.params["alpha"] == 1 / 3
    assert law.spec == "trapezoidal(alpha=1/3)"


@pytest.mark.parametrize("text", [
    "", "(", "trapezoidal(alpha=1/3", "trapezoidal alpha", "trapezoidal(alpha=)",
    "trapezoidal(alpha=1/0)", "trapezoidal(alpha=__import__('os'))", "trapezoidal(alpha=1+1)",
    "double_s(alpha=1/3;beta=1/4)",
])
def test_malformed_specs_are_user_errors(text):
    with pytest.raises(UserError):
        make_law(text)


def test_unknown_law_lists_known_ids():
    with pytest.raises(UserError) as error:
        make_law("cycloid")
    for law_id in ("cycloidal", "double_s", "poly5", "modified_trapezoidal"):
        assert law_id in str(error.value)


@pytest.mark.parametrize(("text", "needle"), [
    ("trapezoidal(alpha=0.7)", "alpha [1e-06, 1/2]"),
    ("trapezoidal(alpha=0)", "alpha [1e-06, 1/2]"),
    ("double_s(alpha=1/3, beta=0.6)", "beta [1e-06, 1/2]"),
    ("polynomial(4)", "odd integer in [3, 21]"),
    ("polynomial(23)", "odd integer in [3, 21]"),
    ("elliptic(n=0.5)", "n [1, 1000]"),
    ("elliptic(n=1e300)", "n [1, 1000]"),
    ("modified_cycloidal(kappa=1)", "kappa [-0.99, 0.99]"),
    ("exponential(sigma=0.5)", "sigma [1, 100]"),
    ("exponential(lam=0.1)", "lam [0.15, 5]"),
    ("trapezoidal(beta=1/3)", "parameters: alpha"),
    ("cycloidal(1)", "too many arguments"),
    ("trapezoidal(1/3, alpha=1/4)", "given twice"),
    ("trapezoidal(alpha=auto)", "auto"),
])
def test_out_of_range_parameters_name_the_range(text, needle):
    with pytest.raises(UserError) as error:
        make_law(text)
    assert needle in str(error.value)


def test_auto_is_resolved_but_not_built():
    family, values = resolve("double_s(alpha=auto, beta=1/4)")
    assert family is LAW_FAMILIES["double_s"]
    assert values == {"alpha": AUTO, "beta": Fraction(1, 4)}


def test_aliases():
    assert make_law("poly5").spec == "polynomial(degree=5)"
    assert make_law("triangular").spec == "constant_acceleration"
    assert {"poly3", "poly5", "poly7", "triangular"} <= set(known_law_ids())


@pytest.mark.parametrize("law_id", sorted(LAW_FAMILIES))
def test_canonical_spec_round_trips(law_id):
    law = make_law(law_id)
    again = make_law(law.spec)
    assert again.spec == law.spec
    assert again.params == law.params
