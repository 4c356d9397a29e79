"""A CODESYS SoftMotion ASCII cam table, as the cam editor's "Write Cam Data to ASCII
Table" (and "Read Cam Data from ASCII Table") handle it: N X/Y value pairs, the X range
split equidistantly, no other cam information (no header). One pair a line, X and Y
separated by a tab (the documentation does not spell the separator: an assumption).

Source: content.helpme-codesys.com, CODESYS SoftMotion, "Command: Write Cam Data to ASCII
Table"; the limit of 128 elements is SM3_Basic's default gc_SMC_FILE_MAXCAMEL (see
SMC_ReadCAM). Interpolated linearly with MC_CAM_REF.byInterpolationQuality = 1."""

from __future__ import annotations

from sizer.export.numbers import pairs
from sizer.export.sampling import PointTable

MAX_ELEMENTS = 128
"""gc_SMC_FILE_MAXCAMEL: SM3_Basic's default largest number of cam elements in a file."""


def write(table: PointTable) -> str:
    return "\n".join(pairs(table.master, table.slave, "\t")) + "\n"
