"""A 1-DOF mechanism at a dead point of its independent coordinate (seed 003, sec. 4).

The mechanism has n dependent coordinates q^d and one independent coordinate q^i, tied
by n constraint equations phi(q) = 0 (eq. 1). At a dead point of q^i, det(phi_q^d) = 0
and q_dot^i = 0 whatever q_dot^d is; the inverse kinematics (eqs. 5, 14) is 0/0. The
paper resolves it by l'Hopital's rule; these are its results as plain functions of the
arrays the caller evaluates at the dead point, in the paper's symbols:

- ``phi_d``: phi_q^d (n x n, eq. 6); ``phi_i``: phi_q^i (n, eq. 7);
- ``dphi_d[k]``: d(phi_q^d)/dq_k (n x n x n);
- ``d2phi_d[k, l]``: d^2(phi_q^d)/dq_k dq_l (n x n x n x n);
- ``dphi_i_d``: (phi_q^i)^d, column k = d(phi_q^i)/dq_k (n x n, eq. 37);
- ``dphi_d_i``: d(phi_q^d)/dq^i (n x n).

``sign`` (+1 or -1) picks the root: the velocities q_dot^d = sign * m * sqrt(...) (eq. 27
gives the + root; the mechanism passes the dead point one way or the other).

In 1-DOF form (q^d = theta, q^i = s, phi = s - f(theta), n = 1): m = 1, k = -f'',
S = -3 f'', R = -f'''/f'', so eq. 27 is theta_dot^2 = s_ddot / f'', eq. 49 is
theta_ddot = (s_dddot / theta_dot - f''' s_ddot / f'') / (3 f'') and eq. 60 is
theta_ddot^2 = s_ddddot / (3 f'') (see :mod:`inverse_motion`).

Corrections to the printed text (docs/errata.md, "Dead points"): eq. 50's last term is
adj(phi_q^d) sum_k d(phi_q^d)/dq_k m_k (the adjugate is needed, as eq. 47 and the
slider-crank's eq. 51 show); eqs. 49 and 53-54 contain the jerk of q^i, eq. 60 and
61-62 its fourth derivative.
"""

from __future__ import annotations

import numpy as np


def adjugate(a: np.ndarray) -> np.ndarray:
    """adj(A): the transposed cofactor matrix, from the minors (defined for a singular
    A, unlike det(A) A^-1; works on complex arrays for :func:`d_adjugate`)."""
    a = np.asarray(a)
    n = a.shape[0]
    if n == 1:
        return np.ones_like(a)
    cof = np.empty_like(a)
    for i in range(n):
        for j in range(n):
            minor = np.delete(np.delete(a, i, axis=0), j, axis=1)
            cof[i, j] = (-1) ** (i + j) * np.linalg.det(minor)
    return cof.T


def d_adjugate(a: np.ndarray, da: np.ndarray) -> np.ndarray:
    """The derivative of adj(A) along dA. The adjugate's entries are polynomials with
    real coefficients in those of A, so the complex step Im adj(A + i h dA) / h is exact
    to O(h^2) with no cancellation (numpy has no adjugate derivative)."""
    h = 1e-30
    return np.imag(adjugate(np.asarray(a, dtype=complex) + 1j * h * np.asarray(da))) / h


def m_vector(phi_d: np.ndarray, phi_i: np.ndarray) -> np.ndarray:
    """m = adj(phi_q^d) phi_q^i (eq. 22)."""
    return adjugate(np.asarray(phi_d, dtype=float)) @ np.asarray(phi_i, dtype=float)


def k_vector(phi_d: np.ndarray, dphi_d: np.ndarray) -> np.ndarray:
    """k = d det(phi_q^d) / dq^d (eq. 23), by Jacobi's formula k_j = tr(adj(phi_q^d)
    d(phi_q^d)/dq_j)."""
    adj = adjugate(np.asarray(phi_d, dtype=float))
    return np.array([np.trace(adj @ d) for d in np.asarray(dphi_d, dtype=float)])


def velocities(m: np.ndarray, k: np.ndarray, qi_dd: float, sign: int = 1) -> np.ndarray:
    """q_dot^d = sign m sqrt(-q_ddot^i / (k m)) (eqs. 24-27). ValueError when q_ddot^i
    has the sign the geometry forbids (the radicand negative)."""
    m = np.asarray(m, dtype=float)
    radicand = -qi_dd / float(np.dot(k, m))
    if radicand < 0.0:
        raise ValueError("q_ddot^i has the wrong sign for this dead point")
    return sign * m * np.sqrt(radicand)


def s_matrix(phi_d: np.ndarray, dphi_d: np.ndarray, m: np.ndarray,
             k: np.ndarray) -> np.ndarray:
    """S = k m I + adj(phi_q^d) [d(phi_q^d)/dq_1 m ... d(phi_q^d)/dq_n m]
    + adj(phi_q^d) sum_k d(phi_q^d)/dq_k m_k (eq. 50, with the adjugate on its last
    term as eq. 47 has it)."""
    phi_d = np.asarray(phi_d, dtype=float)
    dphi_d = np.asarray(dphi_d, dtype=float)
    m = np.asarray(m, dtype=float)
    n = m.size
    adj = adjugate(phi_d)
    columns = np.column_stack([dphi_d[j] @ m for j in range(n)])
    weighted = np.einsum("kij,k->ij", dphi_d, m)
    return float(np.dot(k, m)) * np.eye(n) + adj @ columns + adj @ weighted


def r_vector(phi_d: np.ndarray, phi_i: np.ndarray, dphi_d: np.ndarray,
             d2phi_d: np.ndarray, dphi_i_d: np.ndarray, dphi_d_i: np.ndarray,
             m: np.ndarray, k: np.ndarray) -> np.ndarray:
    """R (eq. 48): sum_k d adj(phi_q^d)/dq_k m_k [phi_q^i - (1/km) sum_k d(phi_q^d)/dq_k
    m_k m] + adj(phi_q^d) [2 (phi_q^i)^d - (1/km) sum_lk d^2(phi_q^d)/dq_k dq_l m_k m_l
    + d(phi_q^d)/dq^i] m."""
    phi_d = np.asarray(phi_d, dtype=float)
    dphi_d = np.asarray(dphi_d, dtype=float)
    m = np.asarray(m, dtype=float)
    km = float(np.dot(k, m))
    adj = adjugate(phi_d)
    weighted = np.einsum("kij,k->ij", dphi_d, m)
    d_adj = d_adjugate(phi_d, weighted)  # sum_k d adj / dq_k m_k
    second = np.einsum("klij,k,l->ij", np.asarray(d2phi_d, dtype=float), m, m)
    first = d_adj @ (np.asarray(phi_i, dtype=float) - weighted @ m / km)
    bracket = 2.0 * np.asarray(dphi_i_d, dtype=float) - second / km \
        + np.asarray(dphi_d_i, dtype=float)
    return first + adj @ bracket @ m


def accelerations(s: np.ndarray, r: np.ndarray, m: np.ndarray, k: np.ndarray,
                  qi_dd: float, qi_ddd: float, sign: int = 1) -> np.ndarray:
    """q_ddot^d = -S^-1 [sign sqrt(k m / -q_ddot^i) m q_dddot^i + R q_ddot^i] for
    q_ddot^i != 0 (eq. 49, sec. 4.2.1; the jerk q_dddot^i, and ``sign`` that of the
    velocities, since sqrt(k m / -q_ddot^i) m is m^2 / q_dot^d)."""
    m = np.asarray(m, dtype=float)
    km = float(np.dot(k, m))
    rhs = sign * np.sqrt(km / -qi_dd) * m * qi_ddd + np.asarray(r, dtype=float) * qi_dd
    return -np.linalg.solve(np.asarray(s, dtype=float), rhs)


def accelerations_at_rest(phi_d: np.ndarray, dphi_d: np.ndarray, m: np.ndarray,
                          k: np.ndarray, qi_dddd: float, sign: int = 1) -> np.ndarray:
    """q_ddot^d for q_ddot^i = q_dddot^i = 0 (then q_dot^d = 0), eq. 60:
    q_ddot_j = sign sqrt(-m_j^3 q^i'''' / (m_j k m + 2 a_j* sum_k d(phi_q^d)/dq_k m_k m))
    with a_j* row j of adj(phi_q^d) and q^i'''' the fourth time derivative (the crank
    comes to rest at the dead point; ``sign`` is that of q_ddot^d / m). The root's sign
    is that of m_j, for q_ddot_j / q_ddot_k = m_j / m_k (eq. 58)."""
    m = np.asarray(m, dtype=float)
    adj = adjugate(np.asarray(phi_d, dtype=float))
    weighted = np.einsum("kij,k->ij", np.asarray(dphi_d, dtype=float), m)
    denominator = m * float(np.dot(k, m)) + 2.0 * adj @ weighted @ m
    out = np.zeros_like(m)
    moving = m != 0.0
    radicand = -(m[moving] ** 3) * qi_dddd / denominator[moving]
    if np.any(radicand < 0.0):
        raise ValueError("the fourth derivative of q^i has the wrong sign for this dead point")
    out[moving] = sign * np.sign(m[moving]) * np.sqrt(radicand)
    return out
