"""Constant accelerations joined by blends: the seven-segment laws of sec. 3.10.2 and 3.11.

The acceleration of the normalized move (T = 1, h = 1) is split into seven segments of
shares T1..T7 (Fig. 3.48, 3.52): +a1 reached through blend 1, held over T2, left through
blend 3; zero over T4; -a2 reached through blend 5, held over T6, left through blend 7.
A blend is a quarter sine ("cycloidal" in sec. 3.11, the sinusoidal blends of 3.10.2)
or a linear ramp (the "cubic" position of sec. 3.11). a1 and a2 follow from the final
velocity 0 and position 1 (the book's 2x2 system, sec. 3.10.2, or eq. 3.56 reduced to
its two unknowns a1, a2: the k_ij are the segment-start states integrated here).
Segments of zero share are absent; the parameters are seg_k = T_k/T, and segment 4
takes the rest, 1 - (the others).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import replace
from functools import cached_property

from sizer.errors import UserError
from sizer.laws.base import MotionLaw, Parameter, format_parameter
from sizer.laws.pieces import Piece, trig_poly_piece

PI = math.pi

SINE, LINEAR, CONSTANT = "sine", "linear", "constant"

MIN_SHARE = 1e-6
"""Smallest non-zero segment share: the blends' jerk a*pi/(2 T_k) stays finite."""

SHARE_NAMES = ("seg1", "seg2", "seg3", "seg5", "seg6", "seg7")

NO_AUTO_SHARES = "the segment shares are given, not searched: write a number"


def share_parameter(name: str, default: float, what: str) -> Parameter:
    return Parameter(name, default, 0.0, 1.0,
                     description=f"{what} over duration; 0 (absent) or at least 1e-6",
                     no_auto=NO_AUTO_SHARES)


def segment_end(kind: str, rising: bool, T: float, A: float, q0: float, v0: float
                ) -> tuple[float, float]:
    """(q, v) at the end of a segment of acceleration level A entered at (q0, v0)."""
    c = 2.0 * T / PI
    if kind == CONSTANT:
        return q0 + v0 * T + A * T * T / 2.0, v0 + A * T
    if kind == SINE:
        dq = A * c * (T - c) if rising else A * c * c
        return q0 + v0 * T + dq, v0 + A * c
    dq = A * T * T / 6.0 if rising else A * T * T / 3.0
    return q0 + v0 * T + dq, v0 + A * T / 2.0


def segment_piece(kind: str, rising: bool, start: float, T: float, A: float,
                  q0: float, v0: float) -> Piece:
    """The exact piece of one segment (the book's segment formulas, sec. 3.10.2, 3.11)."""
    end = start + T
    if kind == CONSTANT:
        return trig_poly_piece(start, end, (q0, v0, A / 2.0), origin=start)
    if kind == LINEAR:
        poly = (q0, v0, 0.0, A / (6.0 * T)) if rising else (q0, v0, A / 2.0, -A / (6.0 * T))
        return trig_poly_piece(start, end, poly, origin=start)
    c = 2.0 * T / PI
    w = 1.0 / c
    if rising:  # a = A sin(w u): q = q0 + v0 u + A c (u - c sin(w u))
        return trig_poly_piece(start, end, (q0, v0 + A * c), [(-A * c * c, w, -w * start)],
                               origin=start)
    # a = A cos(w u): q = q0 + v0 u + A c^2 (1 - cos(w u)); -cos x = sin(x - pi/2)
    return trig_poly_piece(start, end, (q0 + A * c * c, v0),
                           [(A * c * c, w, -w * start - PI / 2.0)], origin=start)


def velocity_square_integral(kind: str, rising: bool, T: float, A: float, v0: float
                             ) -> float:
    """int over the segment of v^2, v = v0 + A g(u): v0^2 T + 2 v0 A int g + A^2 int g^2."""
    c = 2.0 * T / PI
    if kind == CONSTANT:
        ig, ig2 = T * T / 2.0, T**3 / 3.0
    elif kind == SINE:
        ig, ig2 = (c * (T - c), c * c * (1.5 * T - 2.0 * c)) if rising else (c * c, c * c * T / 2.0)
    else:
        ig, ig2 = (T * T / 6.0, T**3 / 20.0) if rising else (T * T / 3.0, 2.0 * T**3 / 15.0)
    return v0 * v0 * T + 2.0 * v0 * A * ig + A * A * ig2


class SevenSegmentLaw(MotionLaw):
    """A rest-to-rest law of seven acceleration segments (sec. 3.10.2, 3.11).

    Subclasses declare the share parameters and :meth:`blend_kinds` (the kinds of the
    blends 1, 3, 5, 7)."""

    max_order = 32

    def blend_kinds(self) -> tuple[str, str, str, str]:
        raise NotImplementedError

    @classmethod
    def canonical_params(cls, params: Mapping[str, float]) -> dict[str, float]:
        values = super().canonical_params(params)
        shares = [values[k] for k in SHARE_NAMES]
        for name, share in zip(SHARE_NAMES, shares, strict=True):
            if 0.0 < share < MIN_SHARE:
                raise UserError(f"{cls.law_id}: parameter {name}={format_parameter(share)} "
                                f"is out of range; valid: {name} = 0 or at least 1e-6")
        text = ", ".join(f"{k}={format_parameter(values[k])}" for k in SHARE_NAMES)
        if sum(shares) > 1.0 + 1e-12:
            raise UserError(f"{cls.law_id}: the segment shares ({text}) add up to more "
                            f"than 1; segment 4 takes 1 - (the others), which must be >= 0")
        if sum(shares[:3]) == 0.0 or sum(shares[3:]) == 0.0:
            raise UserError(f"{cls.law_id}: ({text}): seg1 + seg2 + seg3 and "
                            f"seg5 + seg6 + seg7 must both be positive (an acceleration and a "
                            f"deceleration phase)")
        return values

    def _shape(self) -> list[tuple[str, bool, float, int]]:
        """(kind, rising, share, sign of the level: +a1, 0 or -a2) of the seven segments."""
        k1, k3, k5, k7 = self.blend_kinds()
        p = self.params
        t4 = max(0.0, 1.0 - sum(p[k] for k in SHARE_NAMES))
        return [(k1, True, p["seg1"], 1), (CONSTANT, False, p["seg2"], 1),
                (k3, False, p["seg3"], 1), (CONSTANT, False, t4, 0), (k5, True, p["seg5"], -1),
                (CONSTANT, False, p["seg6"], -1), (k7, False, p["seg7"], -1)]

    @cached_property
    def levels(self) -> tuple[float, float]:
        """(a1, a2): the peak acceleration and deceleration (a_2, a_6 of sec. 3.10.2),
        from v(1) = 0 and q(1) = 1, both linear in them."""
        ends = []
        for side in (1, -1):  # the final (q, v) with a1 = 1, a2 = 0 and then a1 = 0, a2 = 1
            q = v = 0.0
            for kind, rising, share, sign in self._shape():
                q, v = segment_end(kind, rising, share, float(sign) if sign == side else 0.0,
                                   q, v)
            ends.append((q, v))
        (qa, va), (qb, vb) = ends
        det = qa * vb - qb * va
        return vb / det, -va / det  # a1 va + a2 vb = 0 and a1 qa + a2 qb = 1

    def segments(self) -> list[tuple[str, bool, float, float]]:
        """(kind, rising, share, acceleration level) of the seven segments."""
        a1, a2 = self.levels
        values = {1: a1, 0: 0.0, -1: -a2}
        return [(kind, rising, share, values[sign]) for kind, rising, share, sign
                in self._shape()]

    def _build(self):
        pieces, t, q, v = [], 0.0, 0.0, 0.0
        edges = [0.0]  # the acceleration at each side of every join, rest at both ends
        for kind, rising, share, level in self.segments():
            if share <= 0.0:
                continue
            pieces.append(segment_piece(kind, rising, t, share, level, q, v))
            q, v = segment_end(kind, rising, share, level, q, v)
            t += share
            start = 0.0 if kind != CONSTANT and rising else level
            end = 0.0 if kind != CONSTANT and not rising else level
            edges += [start, end]
        edges.append(0.0)
        pieces[-1] = replace(pieces[-1], end=1.0)
        steps = any(abs(edges[i] - edges[i + 1]) > 1e-12 * max(self.levels)
                    for i in range(0, len(edges), 2))
        return pieces, 1 if steps else 2

    def closed_form_coefficients(self) -> dict[str, float]:
        """C_v = v at the end of segment 3; C_a = max(a1, a2); C_j the steepest blend
        (A pi/(2 T_k) for a sine, A/T_k for a ramp); int a^2 and int v^2 segment by
        segment (sine: A^2 T/2, ramp: A^2 T/3, constant: A^2 T)."""
        v, v2, a2sum, jerk, c_v = 0.0, 0.0, 0.0, 0.0, 0.0
        for kind, rising, share, level in self.segments():
            if share <= 0.0:
                continue
            v2 += velocity_square_integral(kind, rising, share, level, v)
            v = segment_end(kind, rising, share, level, 0.0, v)[1]
            c_v = max(c_v, v)
            weight = {CONSTANT: 1.0, SINE: 0.5, LINEAR: 1.0 / 3.0}[kind]
            a2sum += weight * level * level * share
            if kind == SINE:
                jerk = max(jerk, abs(level) * PI / (2.0 * share))
            elif kind == LINEAR:
                jerk = max(jerk, abs(level) / share)
        return {"C_v": c_v, "C_a": max(self.levels), "C_j": jerk,
                "C_v_rms": math.sqrt(v2), "C_a_rms": math.sqrt(a2sum)}


def shares_parameters(defaults: Sequence[float]) -> tuple[Parameter, ...]:
    """seg1, seg2, seg3, seg5, seg6, seg7: the shares T_k/T with their defaults
    (segment 4 is the rest of the duration)."""
    what = ("blend 1 (0 -> a1)", "constant acceleration a1", "blend 3 (a1 -> 0)",
            "blend 5 (0 -> -a2)", "constant deceleration a2", "blend 7 (-a2 -> 0)")
    return tuple(share_parameter(n, d, w) for n, d, w in zip(SHARE_NAMES, defaults, what,
                                                            strict=True))
