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

from sizer.laws.base import MotionLaw
from sizer.laws.quadrature import gauss_legendre
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


def polynomial_increment(acceleration, breaks: np.ndarray, duration: np.ndarray,
                         load: ElasticLoad) -> np.ndarray:
    """The H a move of unit displacement leaves from rest, for moves whose normalized
    acceleration differs per candidate (a move between boundary speeds: its shape depends
    on v T / h): (1 / T) int_0^1 a_N(u) exp(lambda T (1 - u)) du. ``acceleration(u)`` gives
    a_N at the nodes u for every candidate, (n, len(u)); ``breaks`` are its pieces' ends.
    Composite Gauss-Legendre on the pieces, cut so that a part's phase stays below
    PHASE_STEP (exact to rounding for polynomial pieces times the exponential)."""
    T = np.asarray(duration, dtype=float)
    s = eigenvalue(load) * T
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
    values = acceleration(u)  # (n, nodes)
    kernel = np.exp(s.reshape(-1, 1) * (1.0 - u))  # decays: Re(lambda) <= 0
    return ((values * kernel) @ weight).reshape(s.shape) / T
