"""The project's one root finder (sizer.numerics.roots.bracketed_root) and its use by the laws'
coefficient peaks: roots against closed forms, peaks at the closed-form stationary points,
and no scipy behind the laws' coefficients."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from sizer.laws import make_law
from sizer.laws.coefficients import peak
from sizer.numerics.roots import bracketed_root

ROOT = Path(__file__).resolve().parents[1]


def test_all_brackets_at_once_reach_the_roots_of_a_cosine():
    # cos(x) has its roots at (k + 1/2) pi; one bracket around each, of uneven widths
    k = np.arange(40)
    roots = (k + 0.5) * math.pi
    lo, hi = roots - 0.3 - 0.01 * k, roots + 0.1 + 0.02 * k
    found = bracketed_root(np.cos, lo, hi, np.cos(lo), np.cos(hi))
    np.testing.assert_allclose(found, roots, rtol=1e-15, atol=0)  # a few ulps


def test_elementwise_mode_and_final_brackets():
    # x^3 = c per element: roots c^(1/3); with bracket=True the ends keep their signs
    c = np.array([0.5, 2.0, 27.0, 1e3])
    lo, hi = np.zeros(4), np.full(4, 11.0)

    def f(x, c):
        return x**3 - c

    found = bracketed_root(f, lo, hi, -c, 11.0**3 - c, args=(c,))
    np.testing.assert_allclose(found, np.cbrt(c), rtol=1e-15)
    a, b = bracketed_root(lambda x: x**3 - c, lo, hi, -c, 11.0**3 - c, bracket=True)
    assert np.all(a**3 - c <= 0.0) and np.all(b**3 - c >= 0.0)
    np.testing.assert_allclose(b - a, 0.0, atol=1e-14)


def test_the_engine_imports_the_same_root_finder():
    from sizer.sizing.shortest_duration import bracketed_root as engine_root

    assert engine_root is bracketed_root


@pytest.mark.parametrize("near", [1e-3, 1e-7, 1e-11])
def test_a_bracket_with_one_end_near_the_root_closes_in_few_evaluations(near):
    """The excess of an RMS crossing with a dwell, 3x + log(e^x + d) - log(c^3 (c + d))
    in x = log T (root log c), from an end ``near`` the root and one a unit past it (the
    ends' values 1e3-1e11 apart): the Illinois method took 31 and 20 evaluations for the
    first two, halving the far end's value once a step."""
    c, d = np.array([0.3, 1.7, 40.0]), 0.2
    root = np.log(c)
    lo, hi = root - near, root + 1.0
    count = [0]

    def f(x, c):
        count[0] += 1
        return 3.0 * x + np.log(np.exp(x) + d) - 3.0 * np.log(c) - np.log(c + d)

    f_lo, f_hi = f(lo, c), f(hi, c)
    found = bracketed_root(f, lo, hi, f_lo, f_hi, xtol=1e-15, args=(c,))
    np.testing.assert_allclose(found, root, rtol=0, atol=4e-15)
    assert count[0] - 2 <= 8


@pytest.mark.parametrize(("spec", "order", "taus", "value"), [
    # cycloidal: a_N = 2 pi sin(2 pi tau), peaks at tau = 1/4, 3/4
    ("cycloidal", 2, (0.25, 0.75), 2 * math.pi),
    # 3-4-5: a_N = 60 t (1 - t)(1 - 2t), a_N' = 0 at t = (3 -+ sqrt 3)/6, |a_N| = 10 sqrt(3)/3
    ("poly5", 2, ((3 - math.sqrt(3)) / 6, (3 + math.sqrt(3)) / 6), 10 * math.sqrt(3) / 3),
    # 4-5-6-7: a_N = 420 t^2 (1 - t)^2 (1 - 2t), a_N' = 0 at t = (5 -+ sqrt 5)/10, where
    # t (1 - t) = 1/5 and |1 - 2t| = sqrt(5)/5: |a_N| = 84 sqrt(5)/25
    ("poly7", 2, ((5 - math.sqrt(5)) / 10, (5 + math.sqrt(5)) / 10), 84 * math.sqrt(5) / 25),
])
def test_peaks_sit_on_the_roots_of_the_next_derivative(spec, order, taus, value):
    law = make_law(spec)
    found, tau = peak(law, order)
    assert found == pytest.approx(value, rel=2e-15)
    assert min(abs(tau - t) for t in taus) < 1e-12


def test_the_laws_coefficients_need_no_scipy():
    script = ("import sys\n"
              "from sizer.laws import DEFAULT_LAW_SPECS, make_law\n"
              "for spec in (*DEFAULT_LAW_SPECS, 'elliptic(n=1000)', 'polynomial(21)'):\n"
              "    make_law(spec).numerical_coefficients\n"
              "print(sorted(m for m in sys.modules if m.split('.')[0] == 'scipy'))\n")
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            timeout=120, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "[]"
