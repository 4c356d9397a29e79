"""The coefficient-segment cam target (issue 37): a Siemens Technology CPU's cam segments
Y = A0 + A1 X + ... + A6 X^6 + B0 sin(B1 X + B2) (MC_CamSectorAdd, Type 0 = polynomial).
Written by sizer.cli.cam_coefficients, certified by sizer.export.coefficient_segments;
kept apart from sizer.export.targets, whose point tables are linear."""

from __future__ import annotations

from sizer.export.coefficient_segments import MAX_SEGMENTS
from sizer.export.targets import Target

COEFFICIENT_SEGMENTS = "coefficient-segments"
SOURCE = ("Siemens 'CPU 317T: Technology Functions' A5E00251798-03, FB 438 "
          "MC_CamSectorAdd, p. 6-181 (polynomial data block: Type, Reserve, X1, Y1, X2, Y2, "
          "A0..A6, B0..B2) and p. 6-189 (segment borders); X absolute and B1 in rad per "
          "master unit inferred (docs/cam-coefficients.md)")


def not_a_table(table: object) -> str:
    """The point-table writer slot of the registry: this target writes segments."""
    raise TypeError("siemens-tcpu writes coefficient segments, not a point table")


COEFFICIENT_TARGETS: dict[str, Target] = {t.name: t for t in (
    Target("siemens-tcpu", "Siemens Technology CPU cam segments (MC_CamSectorAdd, "
           "polynomial + sine)", MAX_SEGMENTS, COEFFICIENT_SEGMENTS, SOURCE, not_a_table),
)}
