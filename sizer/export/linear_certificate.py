"""The true largest errors of a linearly interpolated point table against its law.

A controller that interpolates the table (x_i, y_i) linearly runs L(x) = y_i + s_i (x -
x_i) on [x_i, x_{i+1}], with the chord slope s_i = (y_{i+1} - y_i) / (x_{i+1} - x_i). Its
position is continuous, its velocity is the chord slope (a step at each point) and its
acceleration is a train of impulses (the velocity steps): a linear table certifies
position and velocity only.

The maxima are found, not sampled:

- the table's intervals are cut into cells at the law's breakpoints, at a few
  subdivisions, and at the zeros of the law's acceleration (each found by a bracketed
  root of y'' on a cell where it changes sign); on each cell the law is one smooth piece
  and its velocity y' is monotone;
- velocity error |y'(x) - s_i|: its largest on a cell is at one of the cell's ends
  (one-sided values of the cell's piece), since y' is monotone on it;
- position error |y(x) - L(x)|: its derivative y'(x) - s_i is monotone on a cell, so it
  has at most one interior extremum per cell, at the root of y'(x) = s_i (bracketed by a
  sign change, found by scipy's elementwise Chandrupatla root finder); the others are the
  cell ends.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sizer.export.extremes import bracketed_roots
from sizer.export.profile import CamProfile
from sizer.numerics.arrays import sorted_unique

SUBDIVISIONS = 4
"""Cells per table interval before the cuts at breakpoints and acceleration zeros."""


@dataclass(frozen=True)
class LinearErrors:
    """The largest errors of a linear table against its law (in the file's units).

    ``position`` in the slave unit, at master ``position_at``; ``velocity`` in slave unit
    per master unit, at ``velocity_at``; ``velocity_step`` the largest step of the chord
    slope at a point (the size of the largest acceleration impulse), the law's own
    velocity at the ends counted."""

    position: float
    position_at: float
    velocity: float
    velocity_at: float
    velocity_step: float


def linear_errors(profile: CamProfile, x: np.ndarray, y: np.ndarray) -> LinearErrors:
    """The certificate of the table (x, y) (x increasing, from 0 to the span)."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if x.ndim != 1 or x.shape != y.shape or len(x) < 2 or not np.all(np.diff(x) > 0):
        raise ValueError("a table needs at least 2 points with increasing master values")
    slope = np.diff(y) / np.diff(x)
    # cells: the intervals cut at subdivisions and the law's breakpoints
    fractions = np.arange(1, SUBDIVISIONS) / SUBDIVISIONS
    inner = (x[:-1, None] + np.diff(x)[:, None] * fractions[None, :]).ravel()
    breaks = profile.breakpoints
    breaks = breaks[(breaks > x[0]) & (breaks < x[-1])]
    edges = sorted_unique(np.concatenate([x, inner, breaks]))
    # ... and at the zeros of the law's acceleration
    a, b, piece = _cells(profile, edges)
    acc_a = profile.derivative(a, 2, piece)
    acc_b = profile.derivative(b, 2, piece)
    change = acc_a * acc_b < 0.0
    if change.any():
        roots = bracketed_roots(lambda t, p: profile.derivative(t, 2, p),
                       a[change], b[change], piece[change])
        edges = sorted_unique(np.concatenate([edges, roots]))
        a, b, piece = _cells(profile, edges)
    interval = np.clip(np.searchsorted(x, 0.5 * (a + b), side="right") - 1, 0, len(slope) - 1)
    s = slope[interval]

    # velocity: the cell ends, one-sided
    va = np.abs(profile.derivative(a, 1, piece) - s)
    vb = np.abs(profile.derivative(b, 1, piece) - s)
    ends = np.concatenate([a, b])
    verr = np.concatenate([va, vb])
    k = int(np.argmax(verr))
    velocity, velocity_at = float(verr[k]), float(ends[k])

    # position: the cell ends and the root of y' = s inside a cell
    def error(t: np.ndarray, p: np.ndarray, i: np.ndarray) -> np.ndarray:
        return np.abs(profile.derivative(t, 0, p) - (y[i] + slope[i] * (t - x[i])))

    candidates = [ends]
    errors = [np.concatenate([error(a, piece, interval), error(b, piece, interval)])]
    fa = profile.derivative(a, 1, piece) - s
    fb = profile.derivative(b, 1, piece) - s
    change = fa * fb < 0.0
    if change.any():
        def chord(t: np.ndarray, p: np.ndarray, sl: np.ndarray) -> np.ndarray:
            return profile.derivative(t, 1, p) - sl

        roots = bracketed_roots(chord, a[change], b[change], piece[change], s[change])
        candidates.append(roots)
        errors.append(error(roots, piece[change], interval[change]))
    where, err = np.concatenate(candidates), np.concatenate(errors)
    k = int(np.argmax(err))

    law_ends = profile.derivative(np.array([x[0], x[-1]]), 1)
    chords = np.concatenate([[law_ends[0]], slope, [law_ends[1]]])
    return LinearErrors(position=float(err[k]), position_at=float(where[k]),
                        velocity=velocity, velocity_at=velocity_at,
                        velocity_step=float(np.max(np.abs(np.diff(chords)))))


def _cells(profile: CamProfile, edges: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The cells between consecutive edges and the law piece of each."""
    a, b = edges[:-1], edges[1:]
    keep = b > a
    a, b = a[keep], b[keep]
    return a, b, profile.piece_of(0.5 * (a + b))
