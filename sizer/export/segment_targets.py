"""The segment-exact cam targets (issue 37): the controller names the law, so the file
carries the law itself (a function type per segment), not a point table. Written by
sizer.cli.cam_segment_exact and certified by re-evaluating the target's own definition
of each function type (sizer.export.twincat_mc3.exact_errors). Kept apart from
sizer.export.targets, whose point tables are linear (their certificate and tests assume
it)."""

from __future__ import annotations

from sizer.export import twincat_mc3
from sizer.export.sampling import MAX_POINTS
from sizer.export.targets import Target

SEGMENT_EXACT = "segment-exact"

SEGMENT_TARGETS: dict[str, Target] = {t.name: t for t in (
    Target("twincat-mc3", "TwinCAT 3 MC3 motion functions (IEC 61131-3)", MAX_POINTS,
           SEGMENT_EXACT,
           "segment-exact: the law's own EMotionFunctionType (infosys.beckhoff.com "
           "TF55xx TC3 MC3: MotionFunctionPoint, EMotionFunctionType, MC_CAM_REF)",
           twincat_mc3.not_a_table),
)}
