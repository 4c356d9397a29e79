"""Laws are objects parsed once: cached by canonical spec, their work done once."""

from __future__ import annotations

import subprocess
import sys
from fractions import Fraction

import pytest

import sizer.laws.coefficients as coefficients_module
from sizer.errors import UserError
from sizer.laws import law_of, make_law, resolve
from sizer.laws.piecewise_polynomial import DoubleS, Trapezoidal


def test_spellings_of_one_law_are_one_object():
    law = make_law("double_s(alpha=1/3,beta=1/4)")
    assert make_law("double_s(beta=0.25, alpha=1/3)") is law
    assert make_law("double_s") is law
    assert make_law("double_s(0.3333333333333333, 0.25)") is law
    assert law_of(DoubleS, {"beta": 0.25}) is law
    assert make_law(law) is law
    assert make_law("poly5") is make_law("polynomial(degree=5)") is make_law("polynomial")


def test_different_laws_are_different_objects():
    assert make_law("double_s(alpha=1/3, beta=1/5)") is not make_law("double_s")
    assert make_law("double_s(alpha=1/3, beta=1/5)") != make_law("double_s")
    assert make_law("poly7") != make_law("poly5")


def test_laws_hash_and_compare_by_canonical_spec():
    built = Trapezoidal(alpha=0.25)  # outside the cache
    cached = make_law("trapezoidal(alpha=1/4)")
    assert built is not cached
    assert built == cached and hash(built) == hash(cached)
    assert {built: 1}[cached] == 1
    assert built.spec == "trapezoidal(alpha=1/4)"
    assert built != Trapezoidal(alpha=0.3)


def test_parameters_of_a_shared_law_cannot_be_changed():
    law = make_law("trapezoidal(alpha=1/3)")
    with pytest.raises(TypeError):
        law.params["alpha"] = 0.1  # type: ignore[index]
    assert law.params["alpha"] == 1 / 3


def test_coefficients_are_computed_once_per_law(monkeypatch):
    calls = []
    original = coefficients_module.compute_coefficients

    def counted(law, use_closed_form=True):
        calls.append(law.spec)
        return original(law, use_closed_form)

    monkeypatch.setattr(coefficients_module, "compute_coefficients", counted)
    spec = "trapezoidal(alpha=0.123456789)"  # not built by any other test
    first = make_law(spec).coefficients
    again = make_law("trapezoidal(0.123456789)").coefficients
    assert again is first
    assert law_of(Trapezoidal, {"alpha": 0.123456789}).coefficients is first
    assert calls == [spec]


def test_grids_and_tables_are_built_once_per_law():
    law = make_law("cycloidal")
    assert law.quadrature is make_law("cycloidal").quadrature
    assert law.linear_peaks is make_law("cycloidal").linear_peaks


def test_resolve_gives_the_caller_its_own_arguments():
    family, values = resolve("double_s(alpha=1/3)")
    assert family is DoubleS
    values["alpha"] = "changed"
    assert resolve("double_s(alpha=1/3)")[1] == {"alpha": Fraction(1, 3)}


def test_user_errors_are_raised_on_every_call():
    for _ in range(2):
        with pytest.raises(UserError, match="unknown law"):
            make_law("no_such_law")
        with pytest.raises(UserError, match="out of range"):
            make_law("trapezoidal(alpha=0.7)")
        with pytest.raises(UserError, match="auto"):
            make_law("trapezoidal(alpha=auto)")


def test_importing_the_laws_does_not_import_scipy():
    code = ("import sys, sizer.laws; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'scipy'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "[]"
