"""The builder of ``kind: cam_segments`` laws: a coefficient-segment file (sizer cam
--to siemens-tcpu) read back as the curve its segments make (sizer.laws.segment_table).

Reading the file is I/O, kept out of the core; a relative ``file`` is taken from the
working directory, as a cam table's is. ``span: [x0, x1]`` (master units of the file)
reads the segments between those X (each the X1 or X2 of a segment: the export writes
every segment end), normalized to their own stroke and duration, as a cam table's span
(sizer.io.cam_table_law).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from sizer.errors import UserError
from sizer.laws.multipoint import FittedCurve

MAX_SEGMENT_FILE_BYTES = 4_000_000


def build_cam_segments_law(fields: Mapping[str, Any]) -> FittedCurve:
    """The curve of the segment file ``fields['file']`` and the units its comments name."""
    from sizer.io.files import read_user_text
    from sizer.laws.segment_table import SegmentCurve, parse_segments

    extra = set(fields) - {"kind", "file", "span"}
    if extra:
        raise UserError(f"cam_segments reads only 'file' and 'span'; unknown field "
                        f"{sorted(extra)[0]!r}", field=sorted(extra)[0])
    file = fields.get("file")
    if not isinstance(file, str) or not file:
        raise UserError("cam_segments needs the segment file: {kind: cam_segments, "
                        "file: cam.txt}", field="file")
    read = parse_segments(read_user_text(file, limit=MAX_SEGMENT_FILE_BYTES,
                                         what="cam segment"), file)
    segments = read.segments
    if fields.get("span") is not None:
        import numpy as np

        from sizer.io.cam_table_law import span_rows

        ends = np.array([s.x1 for s in segments] + [segments[-1].x2])
        i0, i1 = span_rows(fields["span"], ends, file, "segment end")
        segments = segments[i0:i1]
    return FittedCurve(SegmentCurve(segments), {"segments": float(len(segments))},
                       (read.master_unit, read.slave_unit))
