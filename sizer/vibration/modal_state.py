"""The state of the load's mode as one complex number, carried exactly through a cycle.

For the mode of eq. 7.2 with eigenvalue lambda = omega_n (-delta + i sqrt(1 - delta^2)),
the response to an input acceleration y'' from rest is the convolution
H(t) = int_0^t exp(lambda (t - s)) y''(s) ds, and z = -Im(H) / omega_d,
z' = -Im(lambda H) / omega_d (the impulse response is Im(exp(lambda t)) / omega_d). So:

- at rest or at constant speed (a dwell, a run) H turns and decays: H exp(lambda d);
- a rest-to-rest move of h in T adds (h / T) exp(lambda T) F(lambda T), F the transform of
  the law's normalized acceleration (sizer.vibration.response.forced_end);
- the free vibration that follows has the amplitude |H| / omega_d (the envelope of z).

Every figure is exact to the rounding of the transform; vectorized over durations.
"""

from __future__ import annotations

import itertools

import numpy as np

from sizer.errors import UserError
from sizer.laws.base import MotionLaw
from sizer.laws.quadrature import gauss_legendre
from sizer.vibration import convolution as cv
from sizer.vibration import far_field as far
from sizer.vibration.elastic_load import ElasticLoad


def eigenvalue(load: ElasticLoad) -> complex:
    """lambda = omega_n (-delta + i sqrt(1 - delta^2)) [1/s]."""
    return complex(-load.damping_ratio * load.omega_n, load.omega_d)


def move_increment(law: MotionLaw, duration: np.ndarray, load: ElasticLoad) -> np.ndarray:
    """The H a rest-to-rest move of unit displacement in ``duration`` leaves from rest:
    (1 / T) int_0^1 a_N(tau) exp(lambda T (1 - tau)) dtau, per duration (complex)."""
    from sizer.vibration.response import forced_end  # the decaying form: no overflow

    T = np.asarray(duration, dtype=float)
    s = eigenvalue(load) * T
    return forced_end(law, s.ravel()).reshape(s.shape) / T


def free_turn(duration: np.ndarray, load: ElasticLoad) -> np.ndarray:
    """The factor exp(lambda d) of a rest or a run of duration d."""
    return np.exp(eigenvalue(load) * np.asarray(duration, dtype=float))


def amplitude(state: np.ndarray, load: ElasticLoad) -> np.ndarray:
    """The amplitude |H| / omega_d of the free vibration of a state."""
    return np.abs(state) / load.omega_d


NODES = 20
"""Gauss-Legendre nodes on each part of a polynomial move's integral."""

PHASE_STEP = 6.0
"""Largest |lambda T| * width of a part [rad] (as sizer.vibration.transform)."""

GAUSS_S_MAX = float(2 ** 20)
"""Largest |lambda T| integrated by Gauss-Legendre (its nodes grow with it)."""


def polynomial_increment(acceleration, breaks: np.ndarray, duration: np.ndarray,
                         load: ElasticLoad) -> np.ndarray:
    """The H a move of unit displacement leaves from rest, for moves whose normalized
    acceleration differs per candidate (a move between boundary speeds: its shape depends
    on v T / h): (1 / T) int_0^1 a_N(u) exp(lambda T (1 - u)) du. ``acceleration(u, rows)``
    gives a_N at the nodes u for those candidates, (len(rows), len(u)); ``breaks`` are its
    pieces' ends. For |lambda T| >= far_field.FAR_MIN the end series (exact for polynomial
    pieces, cost free of lambda T); else composite Gauss-Legendre on the pieces, cut so
    that a part's phase stays below PHASE_STEP (exact to rounding for polynomial pieces
    times the exponential), the candidates in groups of like |lambda T| and bounded
    memory."""
    T = np.asarray(duration, dtype=float)
    s = (eigenvalue(load) * T).ravel()
    out = np.zeros(s.shape, dtype=complex)
    rows = max(1, far.CHUNK // (far.POINTS * max(1, len(breaks))))
    done = np.zeros(s.shape, dtype=bool)
    for i in range(0, s.size, rows):  # fast modes: the end series, cost free of |s|
        part = slice(i, i + rows)
        big = np.flatnonzero(np.abs(s[part]) >= far.FAR_MIN)
        if big.size:
            index = np.arange(s.size)[part][big]
            def of_rows(u: np.ndarray, _i: np.ndarray = index) -> np.ndarray:
                return acceleration(u, _i)

            value, ok = far.polynomial_end_values(of_rows, breaks, s[index])
            out[index[ok]] = value[ok]
            done[index[ok]] = True
    if np.any(~done & (np.abs(s) > GAUSS_S_MAX)):
        raise UserError(f"f_n T up to {float(np.max(np.abs(s[~done]))) / (2 * np.pi):.4g} is "
                        f"beyond the {GAUSS_S_MAX / (2 * np.pi):.4g} a move between boundary "
                        "speeds is integrated to here: lower the natural frequency or the "
                        "duration", field="load.natural_frequency")
    for group, _cap in cv.grouped(s, 1):  # the rest: Gauss, by size of |s|
        group = group[~done[group]]
        if group.size:
            out[group] = _gauss_increment(
                lambda u, rows, _g=group: acceleration(u, _g[rows]), breaks, s[group])
    return out.reshape(T.shape) / T


def _gauss_increment(acceleration, breaks: np.ndarray, s: np.ndarray) -> np.ndarray:
    """int_0^1 a_N(u) e^{s (1 - u)} du by composite Gauss-Legendre, rows in blocks of
    bounded memory."""
    s_max = float(np.max(np.abs(s), initial=0.0))
    edges = [np.asarray(breaks, dtype=float)[:1]]
    for start, end in itertools.pairwise(breaks):
        cuts = max(1, int(np.ceil(s_max * (end - start) / PHASE_STEP)))
        edges.append(np.linspace(start, end, cuts + 1)[1:])
    fine = np.concatenate(edges)
    x, w = gauss_legendre(NODES)
    half = 0.5 * np.diff(fine)
    u = ((0.5 * (fine[:-1] + fine[1:]))[:, None] + half[:, None] * x).ravel()
    weight = (half[:, None] * w).ravel()
    out = np.empty(s.shape, dtype=complex)
    rows = max(1, cv.CHUNK // u.size)
    for i in range(0, s.size, rows):
        values = acceleration(u, np.arange(i, min(i + rows, s.size)))  # (rows, nodes)
        kernel = np.exp(s[i:i + rows, None] * (1.0 - u))  # decays: Re(lambda) <= 0
        out[i:i + rows] = (values * kernel) @ weight
    return out
