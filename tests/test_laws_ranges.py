"""Laws over their whole parameter range: peaks wherever they are, stable formulas near
the ends of the ranges, and the rules for ``auto`` (issue 9).

Reference values come from closed forms derived by hand, from sympy/mpmath computations
in the test (other formulas, high precision) or from dense sampling in the natural
variable of the law, never from the code's own output.
"""

from __future__ import annotations

import functools
import math

import mpmath as mp
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import optimize

from sizer.errors import UserError
from sizer.io.schema.law_schema import check_law_spec
from sizer.laws import LAW_FAMILIES, make_law
from sizer.laws.coefficients import COEFFICIENT_NAMES, jumps
from sizer.laws.seven_segments import MIN_SHARE, SHARE_NAMES, SevenSegmentLaw
from sizer.laws.trigonometric import Elliptic

PI = math.pi

# ----------------------------------------------------- modified cycloidal (sec. 3.9)

_theta, _kappa = sp.symbols("theta kappa", real=True)
_tau_of_theta = _theta / (2 * sp.pi) - _kappa * sp.sin(_theta) / (2 * sp.pi)  # eq. 3.53
_q_of_theta = _theta / (2 * sp.pi) - sp.sin(_theta) / (2 * sp.pi)  # eq. 3.52


@functools.cache  # sympy's simplify takes a second: at first use, not at collection
def _parametric_derivatives(order: int):
    """d^k q/d tau^k as functions of theta (chain rule through tau(theta)), by sympy."""
    out, current = [], _q_of_theta
    for _ in range(order):
        current = sp.simplify(sp.diff(current, _theta) / sp.diff(_tau_of_theta, _theta))
        out.append(sp.lambdify((_theta, _kappa), current, "numpy"))
    return out


@functools.cache  # the same peak is the reference for both coefficient sets below
def _mc_peak(kappa: float, order: int) -> float:
    """max over theta of |d^k q/d tau^k|: dense theta samples refined by bounded Brent.

    In theta the profile varies on scales >= sqrt(1 - |kappa|) (0.1 rad at |kappa| = 0.99),
    so 200001 samples resolve every peak."""
    f = _parametric_derivatives(3)[order - 1]
    theta = np.linspace(0.0, 2 * PI, 200001)
    values = np.abs(f(theta, kappa) + 0 * theta)
    k = int(np.argmax(values))
    lo, hi = theta[max(k - 1, 0)], theta[min(k + 1, len(theta) - 1)]
    res = optimize.minimize_scalar(lambda t: -abs(float(f(t, kappa))), bounds=(lo, hi),
                                   method="bounded", options={"xatol": 1e-13})
    return max(float(values[k]), -float(res.fun))


@pytest.mark.parametrize("kappa", [-0.99, -0.95, -0.9, -0.6, -0.3, 0.0, 0.134, 0.5, 0.9, 0.99])
def test_modified_cycloidal_peaks_against_sympy(kappa):
    law = make_law(f"modified_cycloidal(kappa={kappa})")
    for coefficients in (law.coefficients, law.numerical_coefficients):
        for order, name in ((1, "C_v"), (2, "C_a"), (3, "C_j")):
            assert getattr(coefficients, name) == pytest.approx(_mc_peak(kappa, order), rel=1e-9)


@pytest.mark.parametrize("kappa", [-0.99, -0.95, -0.8, -0.5])
def test_modified_cycloidal_jerk_peaks_at_midpoint_for_strongly_negative_kappa(kappa):
    # At theta = pi (tau = 1/2): c = -1, g = 1 + kappa, j = 4 pi^2 (1 - kappa)(-1 - kappa)/g^5;
    # the peak sits exactly on a grid point, where the next derivative is 0 up to rounding.
    expected = 4 * PI**2 * (1 - kappa) / (1 + kappa) ** 4
    law = make_law(f"modified_cycloidal(kappa={kappa})")
    assert law.numerical_coefficients.C_j == pytest.approx(expected, rel=1e-12)
    assert law.coefficients.C_j == pytest.approx(expected, rel=1e-12)


def test_wildt_kappa_gives_the_books_minimum_acceleration():
    # sec. 3.9: kappa = 1 - sqrt(3)/2 minimizes q''_max, printed 5.88 h/T^2 (truncated:
    # 5.888253, see errata); the sympy peaks on either side are larger
    wildt = 1 - math.sqrt(3) / 2
    law = make_law(f"modified_cycloidal(kappa={wildt!r})")
    assert math.floor(law.coefficients.C_a * 100) / 100 == 5.88
    assert law.coefficients.C_a == pytest.approx(5.888253, abs=5e-7)
    assert _mc_peak(wildt - 1e-3, 2) > _mc_peak(wildt, 2) < _mc_peak(wildt + 1e-3, 2)


# ----------------------------------------------------------- elliptic (sec. 2.2.3)

def _elliptic_book(n: float, order: int, x):
    """The book's form (eq. 2.23, a = (n^2 - 1)/n^2) differentiated by mpmath at 60 digits."""
    with mp.workdps(60):
        a = (mp.mpf(n) ** 2 - 1) / mp.mpf(n) ** 2

        def q(tau):
            y = mp.pi * tau
            return (1 - mp.cos(y) / mp.sqrt(1 - a * mp.sin(y) ** 2)) / 2

        return mp.diff(q, mp.mpf(x), order)


def _elliptic_acceleration_peak(n: float) -> float:
    """max |q''| on [0, 1/2] (symmetric law): tau = 0 and the sign changes of the jerk
    on samples graded toward tau = 1/2 (the peak is within about 1/n of it), by Ridder."""
    with mp.workdps(40):
        best = abs(_elliptic_book(n, 2, 0))
        taus = [0.5 - float(t) for t in np.geomspace(1e-7, 0.5, 240)][::-1]
        jerk = [_elliptic_book(n, 3, t) for t in taus]
        for k in range(len(taus) - 1):
            (t0, j0), (t1, j1) = (taus[k], jerk[k]), (taus[k + 1], jerk[k + 1])
            if j0 * j1 < 0:
                root = mp.findroot(lambda t: _elliptic_book(n, 3, t), (t0, t1), solver="illinois",
                                   verify=False)
                best = max(best, abs(_elliptic_book(n, 2, root)))
        return float(best)


@pytest.mark.parametrize("n", [1.0, 1.05, 1.0863, 1.5, 2.0, 10.0, 1e3])
def test_elliptic_coefficients_against_high_precision(n):
    law = make_law(f"elliptic(n={n!r})")
    c, numeric = law.coefficients, law.numerical_coefficients
    # the velocity peaks at tau = 1/2 where D = 1/n^2: pi n/2
    assert c.C_v == pytest.approx(PI * n / 2, rel=1e-12)
    # acceleration: the larger of tau = 0 and the roots of the jerk, found by mpmath
    assert c.C_a == pytest.approx(_elliptic_acceleration_peak(n), rel=1e-9)
    # jerk at tau = 1/2 (x = pi/2, w = 0): pi^3 (3 - 2/n^2) n^3 / 2, the peak for n >= 2
    if n >= 2:
        assert c.C_j == pytest.approx(PI**3 * (3 - 2 / n**2) * n**3 / 2, rel=1e-9)
    for name in COEFFICIENT_NAMES:
        assert getattr(c, name) == pytest.approx(getattr(numeric, name), rel=1e-9)


@pytest.mark.parametrize("n", [2.0, 50.0, 1e3])
def test_elliptic_derivatives_are_free_of_cancellation(n):
    law = make_law(f"elliptic(n={n!r})")
    for x in (0.5, 0.5 - 0.1 / n, 0.5 - 1.0 / n, 0.1):
        for order in (1, 2, 3, 4):
            exact = float(_elliptic_book(n, order, x))
            got = float(law.piece_derivative(0, np.array([x]), order)[0])
            assert got == pytest.approx(exact, rel=1e-9, abs=1e-12 * n ** (order + 1))


def test_elliptic_auto_range_holds_every_optimum():
    # C_a falls from pi^2/2 at n = 1 to its minimum near n = 1.0863 (where the end value
    # pi^2/(2 n^2) meets the interior peak), then every coefficient grows with n.
    ns = np.concatenate((np.linspace(1.0, 2.0, 41), np.geomspace(2.0, 1e3, 30)[1:]))
    table = np.array([[getattr(Elliptic(n=float(n)).coefficients, k) for k in COEFFICIENT_NAMES]
                      for n in ns])
    above = ns >= 1.09
    assert np.all(np.diff(table[above], axis=0) > 0.0)
    c_v, c_v_rms, c_a_rms = table[:, 0], table[:, 3], table[:, 4]
    assert np.all(np.diff(c_v) > 0) and np.all(np.diff(c_v_rms) > 0)
    assert np.all(np.diff(c_a_rms) > 0)
    best = ns[np.argmin(table[:, 1])]
    assert 1.06 < best < 1.12
    assert Elliptic.parameters[0].auto_range == (1.0, 2.0)


# -------------------------------------------------------- every family, every range

def _log_toward(draw, low: float, high: float) -> float:
    """A value of [low, high], often within decades of either end."""
    where = draw(st.sampled_from(["low", "high", "any"]))
    if where == "any":
        return draw(st.floats(low, high))
    span = high - low
    offset = span * 10.0 ** -draw(st.floats(0.0, 9.0))
    return min(max(low + offset if where == "low" else high - offset, low), high)


def _seven_segment_shares(draw) -> dict[str, float]:
    """Shares of sec. 3.10.2/3.11 laws: seven weights (some zero) normalized to a sum of
    1, shares below MIN_SHARE dropped, both phases present; segment 4 takes the rest."""
    weights = [draw(st.sampled_from([0.0, 1.0])) * _log_toward(draw, 1e-3, 1.0)
               for _ in range(7)]
    weights[1] = weights[1] or 0.5  # an acceleration and a deceleration phase
    weights[5] = weights[5] or 0.5
    total = sum(weights)
    shares = [w / total if w / total >= 2 * MIN_SHARE else 0.0 for w in weights]
    return dict(zip(SHARE_NAMES, shares[:3] + shares[4:], strict=True))


@st.composite
def any_law(draw):
    family = draw(st.sampled_from(sorted(LAW_FAMILIES)))
    cls = LAW_FAMILIES[family]
    args = {}
    if issubclass(cls, SevenSegmentLaw):  # joint shares: a point of the simplex
        args = _seven_segment_shares(draw)
    for p in cls.parameters:
        if p.name in args:
            continue
        if p.integer:
            values = [v for v in range(int(p.low), int(p.high) + 1) if not p.odd or v % 2]
            args[p.name] = float(draw(st.sampled_from(values)))
        else:
            args[p.name] = _log_toward(draw, p.low, p.high)
    return cls(**args)


ENDS = [
    "trapezoidal(alpha=1e-6)", "trapezoidal(alpha=1e-5)", "trapezoidal(alpha=1/2)",
    "double_s(alpha=1/2, beta=0.0005)", "double_s(alpha=1e-6, beta=1e-6)",
    "double_s(alpha=1e-6, beta=1/2)", "double_s(alpha=1/2, beta=1e-6)",
    "double_s(alpha=1/2, beta=1/2)", "elliptic(n=1)", "elliptic(n=1.0000001)",
    "elliptic(n=1000)", "modified_cycloidal(kappa=-0.99)", "modified_cycloidal(kappa=0.99)",
    "exponential(sigma=1, lam=0.15)", "exponential(sigma=1, lam=5)",
    "exponential(sigma=100, lam=0.15)", "exponential(sigma=100, lam=5)",
    *(f"polynomial({d})" for d in range(3, 22, 2)),
]


def _check_law(law):
    c, numeric = law.coefficients, law.numerical_coefficients
    values = c.as_dict()
    assert all(math.isfinite(v) for v in values.values()), values
    assert all(v > 0.0 for k, v in values.items() if k != "C_j"), values
    assert c.C_j >= 0.0
    assert c.C_v >= 1.0 - 1e-12 and c.C_a >= 4.0 - 1e-9
    assert c.C_v_rms >= 1.0 - 1e-12  # the RMS of a velocity whose mean is 1
    assert c.C_v >= c.C_v_rms * (1 - 1e-12) and c.C_a >= c.C_a_rms * (1 - 1e-12)
    for name in COEFFICIENT_NAMES:
        assert getattr(c, name) == pytest.approx(getattr(numeric, name), rel=1e-9, abs=1e-300)
    # no sample exceeds a peak (dense sampling in tau, graded toward ends and the middle)
    graded = 10.0 ** -np.linspace(1, 13, 97)
    tau = np.unique(np.concatenate((np.linspace(0, 1, 100001), graded, 1 - graded,
                                    0.5 - graded, 0.5 + graded)))
    for order, name in ((1, "C_v"), (2, "C_a")):
        sampled = np.abs(law.derivative(tau, order)).max()
        assert sampled <= getattr(c, name) * (1 + 1e-12)


@pytest.mark.parametrize("spec", ENDS)
def test_coefficients_at_the_ends_of_the_ranges(spec):
    _check_law(make_law(spec))


@settings(max_examples=80, deadline=None)
@given(any_law())
def test_coefficients_over_the_whole_ranges(law):
    _check_law(law)


def test_exponential_normalization_against_mpmath():
    # v_c = 1/int_0^1 exp(-sigma x^2/(1 - x^2)^lam) dx, at 30 digits on graded panels
    for sigma, lam in ((1, 0.15), (7.1, 0.2), (100, 5), (2, 0.61)):
        with mp.workdps(30):
            def f(x, sigma=sigma, lam=lam):
                return mp.exp(-sigma * x**2 / (1 - x**2) ** lam) if x < 1 else mp.mpf(0)
            edges = [0] + [1 - mp.mpf(10) ** -k for k in range(1, 25)] + [1]
            v_c = float(1 / mp.quad(f, edges))
        law = make_law(f"exponential(sigma={sigma}, lam={lam})")
        assert law.coefficients.C_v == pytest.approx(v_c, rel=1e-12)


def test_steep_double_s_has_exact_one_sided_values_at_mirrored_breakpoints():
    # 1 - (1 - b) != b in floating point; the mirrored piece must still start at rest
    # acceleration-wise (no spurious jump) and the law is C^2
    law = make_law("double_s(alpha=1e-4, beta=1e-4)")
    assert jumps(law, 2) == []
    assert law.coefficients.jerk_bounded


# --------------------------------------------------------------- auto on parameters

def test_every_parameter_has_a_finite_auto_range_or_a_refusal():
    for family in LAW_FAMILIES.values():
        for p in family.parameters:
            span = p.auto_range
            if span is None:
                message = p.auto_refusal(family.law_id)
                assert message.startswith(f"{family.law_id}: {p.name}=auto is not supported")
                assert "\n" not in message
                continue
            low, high = span
            assert math.isfinite(low) and math.isfinite(high) and low < high
            assert p.low <= low and high <= p.high
            for value in (low, high):  # the ends are admissible unless open ends of the range
                if not ((value == p.low and p.low_open) or (value == p.high and p.high_open)):
                    p.validate(family.law_id, value)


def test_polynomial_degree_auto_is_refused_with_what_to_write():
    with pytest.raises(ValueError) as error:
        check_law_spec("polynomial(degree=auto)")
    assert "degree=auto" in str(error.value) and "poly3, poly5, poly7" in str(error.value)
    with pytest.raises(ValueError, match="degree=auto"):
        check_law_spec("polynomial(auto)")


@pytest.mark.parametrize("spec", ["elliptic(n=auto)", "trapezoidal(alpha=auto)",
                                  "double_s(alpha=auto, beta=auto)", "modified_cycloidal(auto)",
                                  "exponential(sigma=auto, lam=0.2)"])
def test_auto_is_accepted_where_a_finite_range_is_declared(spec):
    assert check_law_spec(spec) == spec


def test_make_law_still_refuses_auto():
    with pytest.raises(UserError, match="auto"):
        make_law("elliptic(n=auto)")
