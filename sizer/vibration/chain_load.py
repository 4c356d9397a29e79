"""The n-DOF chain load of sec. 7.1.2 and its exact response to a law (sec. 7.2).

Masses m_1 .. m_n in a chain, m_1 tied to the input y by (k_1, d_1), m_i to m_{i-1} by
(k_i, d_i). In z_1 = x_1 - y, z_i = x_i - x_{i-1}: M z'' + D z' + K z = -m y'' (eq. 7.3),
state x = [z, z'], x' = A x + B y'' (eq. 7.4). A = V Lambda V^-1 (complex modes, over-
damped ones real): each mode eta_j = (V^-1 x)_j obeys eta_j' = lambda_j eta_j + beta_j y'',
beta = V^-1 B, answered exactly by sizer.vibration.convolution at s = lambda_j T. The output
is the last mass's error x_n - y = z_1 + ... + z_n = sum_j C_j eta_j, C = [1 .. 1, 0 .. 0] V.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from sizer.errors import UserError
from sizer.laws.base import MotionLaw
from sizer.vibration import convolution as cv
from sizer.vibration.response import (
    TRACK_SAMPLES,
    TRACK_STEP,
    _law,
    forced_end,
    peak_output,
)


def _positive(values: Sequence[float], name: str, allow_zero: bool = False) -> np.ndarray:
    out = np.asarray(values, dtype=float)
    good = np.isfinite(out) & ((out >= 0.0) if allow_zero else (out > 0.0))
    if out.ndim != 1 or out.size == 0 or not good.all():
        kind = "non-negative" if allow_zero else "positive"
        raise UserError(f"{name} must be a list of {kind} numbers, not {list(out.ravel())}",
                        field=f"load.{name}")
    return out


@dataclass(frozen=True)
class ChainModes:
    """The eigen-decomposition of A: eigenvalues ``lam`` (2n,), input weights ``beta`` =
    V^-1 B and output weights ``c`` = [1 .. 1, 0 .. 0] V."""

    lam: np.ndarray
    beta: np.ndarray
    c: np.ndarray
    vectors: np.ndarray


@dataclass(frozen=True, eq=False)
class ChainLoad:
    """The chain of Fig. 7.2: masses, dampings and stiffnesses of its n elements."""

    masses: tuple[float, ...]
    dampings: tuple[float, ...]
    stiffnesses: tuple[float, ...]

    def __post_init__(self) -> None:
        m = _positive(self.masses, "masses")
        d = _positive(self.dampings, "dampings", allow_zero=True)
        k = _positive(self.stiffnesses, "stiffnesses")
        if not (m.size == d.size == k.size):
            raise UserError(f"masses, dampings and stiffnesses must have one value each per "
                            f"element (got {m.size}, {d.size}, {k.size})", field="load")

    @property
    def size(self) -> int:
        return len(self.masses)

    def matrices(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """M, D, K and m of eq. 7.3."""
        m = np.asarray(self.masses, dtype=float)
        n = m.size
        M = np.tril(np.repeat(m[:, None], n, axis=1))

        def coupling(values: Sequence[float]) -> np.ndarray:
            v = np.asarray(values, dtype=float)
            return np.diag(v) - np.diag(v[1:], 1)

        return M, coupling(self.dampings), coupling(self.stiffnesses), m

    def state_matrices(self) -> tuple[np.ndarray, np.ndarray]:
        """A and B of eq. 7.4 (state [z, z'], input y'')."""
        M, D, K, m = self.matrices()
        n = m.size
        solved = np.linalg.solve(M, np.column_stack([K, D, m]))
        Minv_K, Minv_D, Minv_m = solved[:, :n], solved[:, n:2 * n], solved[:, 2 * n]
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv_K, -Minv_D]])
        B = np.concatenate([np.zeros(n), -Minv_m])
        return A, B

    @cached_property
    def modes(self) -> ChainModes:
        """Eigen-decomposition of A (UserError when A has no basis of eigenvectors, e.g. a
        critically damped mode)."""
        A, B = self.state_matrices()
        lam, V = np.linalg.eig(A)
        if not np.all(np.isfinite(V)) or np.linalg.cond(V) > 1e10:
            raise UserError("the chain has a (nearly) critically damped mode: its state "
                            "matrix has no basis of eigenvectors", field="load.dampings")
        n = self.size
        beta = np.linalg.solve(V, B.astype(complex))
        out = np.concatenate([np.ones(n), np.zeros(n)])
        return ChainModes(lam, beta, out @ V, V)

    def natural_frequencies(self) -> np.ndarray:
        """|lambda| / 2 pi [Hz] of the under-damped modes, one a conjugate pair, ascending."""
        lam = self.modes.lam
        pairs = lam[lam.imag > 0.0]
        return np.sort(np.abs(pairs)) / (2.0 * math.pi)

    def damping_ratios(self) -> np.ndarray:
        """-Re lambda / |lambda| of the under-damped modes, in the order of
        :meth:`natural_frequencies`."""
        lam = self.modes.lam
        pairs = lam[lam.imag > 0.0]
        pairs = pairs[np.argsort(np.abs(pairs))]
        return -pairs.real / np.abs(pairs)


def _move(duration: float, displacement: float) -> tuple[float, float]:
    T, h = float(duration), float(displacement)
    if not (math.isfinite(T) and T > 0.0):
        raise UserError(f"duration must be positive, not {T:g} s", field="duration")
    if not math.isfinite(h):
        raise UserError(f"displacement must be finite, not {h:g}", field="displacement")
    return T, h


def _initial(chain: ChainLoad, state: Sequence[float] | None) -> np.ndarray:
    """Modal coordinates V^-1 x of a state [z, z'] (rest by default)."""
    if state is None:
        return np.zeros(2 * chain.size, dtype=complex)
    x = np.asarray(state, dtype=float)
    if x.shape != (2 * chain.size,) or not np.all(np.isfinite(x)):
        raise UserError(f"initial state must be {2 * chain.size} finite numbers [z, z']",
                        field="initial")
    return np.linalg.solve(chain.modes.vectors, x.astype(complex))


def chain_move_response(law: MotionLaw | str, duration: float, displacement: float,
                        chain: ChainLoad, times: np.ndarray,
                        initial: Sequence[float] | None = None) -> np.ndarray:
    """The state [z_1 .. z_n, z_1' .. z_n'] at the given times [s] of a move starting at
    t = 0, shape times.shape + (2n,): exact during the move, free vibration after it;
    times before 0 read the initial state (rest by default). x_n - y = z.sum(-1)[..., :n]."""
    T, h = _move(duration, displacement)
    the_law = _law(law)
    modes = chain.modes
    eta0 = _initial(chain, initial)
    t = np.asarray(times, dtype=float).ravel()
    tau = np.clip(t / T, 0.0, 1.0)
    s = modes.lam * T
    grid = cv.law_grid(the_law, float(cv.s_cap_of(np.array([np.max(np.abs(s))]))[0]),
                       TRACK_STEP, TRACK_SAMPLES)
    at_edges = cv.edge_values(grid, s)  # (modes, K + 1)
    count = s.size
    s_rows = np.tile(s, tau.size)
    tau_rows = np.repeat(tau, count)
    row = np.tile(np.arange(count), tau.size)
    forced = cv.values_at(grid, s_rows, at_edges, tau_rows, row).reshape(tau.size, count)
    eta = np.exp(np.multiply.outer(tau, s)) * eta0 + (h / T) * modes.beta * forced
    after = t > T
    eta[after] *= np.exp(np.multiply.outer(t[after] - T, modes.lam))
    x = (eta @ modes.vectors.T).real
    before = t < 0.0
    x[before] = 0.0 if initial is None else np.asarray(initial, dtype=float)
    return x.reshape((*np.shape(times), 2 * chain.size))


@dataclass(frozen=True)
class ChainVibration:
    """One move of a chain load: ``residual`` = sum_j |C_j eta_j| at the move's end (the
    sum of the modes' envelopes of x_n - y after it, a bound on |x_n - y| from then on;
    for one mode, the 1-DOF residual amplitude); ``peak_error`` = max |x_n - y| during
    the move; ``end_state`` = [z, z'] at the end."""

    residual: float
    peak_error: float
    end_state: tuple[float, ...]


def chain_vibration(law: MotionLaw | str, duration: float, displacement: float,
                    chain: ChainLoad, initial: Sequence[float] | None = None
                    ) -> ChainVibration:
    """Residual and peak tracking error of the last mass through one move (sec. 7.2)."""
    T, h = _move(duration, displacement)
    the_law = _law(law)
    modes = chain.modes
    eta0 = _initial(chain, initial)
    s = modes.lam * T
    eta = np.exp(s) * eta0 + (h / T) * modes.beta * forced_end(the_law, s)
    peak = peak_output(the_law, s[None, :], modes.c[None, :], eta0[None, :],
                       ((h / T) * modes.beta)[None, :])[0]
    state = (modes.vectors @ eta).real
    return ChainVibration(float(np.sum(np.abs(modes.c * eta))), float(peak),
                          tuple(float(v) for v in state))
