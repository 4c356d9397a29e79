"""The cam targets whose controller interpolates C1 or smoother (issue 37): the file carries
positions, velocities and accelerations and runs as a quintic Hermite, certified by
sizer.export.hermite_certificate; their torques are re-computed on the exported profile
(sizer.export.resized). Kept apart from sizer.export.targets, whose point tables are
linear (their certificate and tests assume it)."""

from __future__ import annotations

from sizer.export import codesys_xyva
from sizer.export.targets import Target

QUINTIC_HERMITE = "quintic_hermite"

SMOOTH_TARGETS: dict[str, Target] = {t.name: t for t in (
    Target("codesys-xyva", "CODESYS SoftMotion XYVA cam table (SMC_CAMXYVA X,Y,V,A)",
           codesys_xyva.MAX_ELEMENTS, QUINTIC_HERMITE, codesys_xyva.SOURCE,
           codesys_xyva.write),
)}
