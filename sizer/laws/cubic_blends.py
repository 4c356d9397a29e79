"""Constant acceleration with cycloidal or cubic blends (book sec. 3.11, Fig. 3.52).

Each odd segment (1, 3, 5, 7) is a cubic blend (a linear acceleration ramp) or a
cycloidal one (a quarter sine), chosen by ``cubic1``, ``cubic3``, ``cubic5``, ``cubic7``
(1 cubic, 0 cycloidal). The book solves eq. (3.56) for a1, a2 and the sixteen k_ij;
here the k_ij are the segment-start states, integrated exactly, and a1, a2 come from
the final velocity 0 and position 1 (sizer.laws.seven_segments).
"""

from __future__ import annotations

from sizer.laws.base import Parameter
from sizer.laws.seven_segments import LINEAR, SINE, SevenSegmentLaw, shares_parameters

BLEND_NAMES = ("cubic1", "cubic3", "cubic5", "cubic7")


def _blend_flag(name: str) -> Parameter:
    return Parameter(name, 1, 0.0, 1.0, integer=True,
                     description=f"segment {name[-1]}: 1 cubic blend (linear acceleration), "
                                 f"0 cycloidal (quarter sine)",
                     no_auto="the blend kind is given: write 0 or 1")


class CubicBlendAcceleration(SevenSegmentLaw):
    """Constant acceleration with cubic (or cycloidal) blends, sec. 3.11.

    The defaults, shares (1/8, 1/4, 1/8, 0, 1/8, 1/4, 1/8) with cubic blends, are the
    trapezoidal acceleration of Fig. 3.54(a) (double_s(alpha=1/2, beta=1/4))."""

    law_id = "cubic_blend_acceleration"
    title = "Constant acceleration, cycloidal/cubic blends"
    parameters = (*shares_parameters((1 / 8, 1 / 4, 1 / 8, 1 / 8, 1 / 4, 1 / 8)),
                  *(_blend_flag(n) for n in BLEND_NAMES))

    def blend_kinds(self) -> tuple[str, str, str, str]:
        k1, k3, k5, k7 = (LINEAR if self.params[n] else SINE for n in BLEND_NAMES)
        return k1, k3, k5, k7
