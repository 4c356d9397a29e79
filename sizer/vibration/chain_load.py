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
from sizer.vibration.response import (
    ModalModel,
    MoveVibration,
    Segment,
    checked_move,
    cycle_response,
    modal_move,
)


def _positive(values: Sequence[float], name: str, allow_zero: bool = False) -> np.ndarray:
    out = np.asarray(values, dtype=float)
    good = np.isfinite(out) & ((out >= 0.0) if allow_zero else (out > 0.0))
    if out.ndim != 1 or out.size == 0 or not good.all():
        kind = "non-negative" if allow_zero else "positive"
        raise UserError(f"{name} must be a list of {kind} numbers, not {list(out.ravel())}",
                        field=f"load.{name}")
    return out


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
    def modes(self) -> ModalModel:
        """Eigen-decomposition of A: eigenvalues ``lam`` (2n,), input weights ``beta`` =
        V^-1 B, output weights ``c`` = [1 .. 1, 0 .. 0] V, ``vectors`` V (UserError when A
        has no basis of eigenvectors, e.g. a critically damped mode)."""
        A, B = self.state_matrices()
        lam, V = np.linalg.eig(A)
        if not np.all(np.isfinite(V)) or np.linalg.cond(V) > 1e10:
            raise UserError("the chain has a (nearly) critically damped mode: its state "
                            "matrix has no basis of eigenvectors", field="load.dampings")
        n = self.size
        beta = np.linalg.solve(V, B.astype(complex))
        out = np.concatenate([np.ones(n), np.zeros(n)])
        return ModalModel(lam, beta, out @ V, V)

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


def chain_move_response(law: MotionLaw | str, duration: float, displacement: float,
                        chain: ChainLoad, times: np.ndarray,
                        initial: Sequence[float] | None = None) -> np.ndarray:
    """The state [z_1 .. z_n, z_1' .. z_n'] at the given times [s] of a move starting at
    t = 0, shape times.shape + (2n,): exact during the move, free vibration after it;
    times before 0 read the initial state (rest by default). x_n - y = z.sum(-1)[..., :n]."""
    return modal_move(law, duration, displacement, chain.modes, times, initial)


def chain_vibration(law: MotionLaw | str, duration: float, displacement: float,
                    chain: ChainLoad, initial: Sequence[float] | None = None
                    ) -> MoveVibration:
    """Residual and peak tracking error of the last mass through one move (sec. 7.2):
    ``residual`` = sum_j |C_j eta_j| at the move's end (the sum of the modes' envelopes
    of x_n - y after it, a bound on |x_n - y| from then on; for one mode, the 1-DOF
    residual amplitude), ``peak_error`` = max |x_n - y| during the move, ``end_state`` =
    [z, z'] at the end."""
    T, h = checked_move(duration, displacement)
    return cycle_response([Segment(law, 0.0, T, h)], chain, initial=initial).moves[0]
