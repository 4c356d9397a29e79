"""A CODESYS SoftMotion XYVA cam table as text: one SMC_CAMXYVA element {dX, dY, dV, dA} a
line, 'X,Y,V,A', under a header naming the columns with their units and '#' comment lines
that say what it is. The controller runs an XYVA cam as a quintic Hermite between points.

Which CODESYS artefact: the content of an ``ARRAY [0..N-1] OF SMC_CAMXYVA`` (the cam
element array that MC_CAM_REF.pce points to, with byType XYVA) — its values, in the order
of the structure's members. The exact text of the IEC 61131-3 initialisation code that
the cam editor's "Display Generated Code" shows could not be confirmed from the
reference at hand (../shared/reference/controller-cams.md names the structure and the
editor command, not the code), so this writer does not produce it: the table is a
documented CSV that sizer reads back (``{kind: cam_table, file: F, interpolation:
quintic_hermite}``) and that a few lines of ST or a spreadsheet turn into the
initialiser. The limit of 128 elements is SM3_Basic's default gc_SMC_FILE_MAXCAMEL.
"""

from __future__ import annotations

from sizer.export.hermite_certificate import HermiteTable
from sizer.export.numbers import exact
from sizer.export.sampling import PointTable

MAX_ELEMENTS = 128
"""gc_SMC_FILE_MAXCAMEL: SM3_Basic's default largest number of cam elements."""


def header(table: HermiteTable) -> str:
    p = table.profile
    m, s = p.master_unit, p.slave_unit
    return f"X [{m}],Y [{s}],V [{s}/{m}],A [{s}/{m}^2]"


def write(table: HermiteTable | PointTable) -> str:
    """The file of an XYVA table (a PointTable, position only, is refused)."""
    if not isinstance(table, HermiteTable):
        raise TypeError("an XYVA cam needs a HermiteTable (positions, velocities and "
                        "accelerations)")
    rows = [",".join(exact(value) for value in row) for row in
            zip(table.master, table.slave, table.velocity, table.acceleration, strict=True)]
    comments = [
        "# CODESYS SoftMotion XYVA cam: ARRAY OF SMC_CAMXYVA {dX, dY, dV, dA}, "
        f"{table.points} elements",
        "# the controller interpolates a quintic Hermite between the points; "
        "sizer: {kind: cam_table, file: THIS, interpolation: quintic_hermite}",
    ]
    return "\n".join([*comments, header(table), *rows]) + "\n"


SOURCE = ("controller-cams.md line 45 (CODESYS SoftMotion SM3_Basic: byType XYVA, SMC_CAMXYVA "
          "{dX, dY, dV, dA}, 'XYVA at blend points gives quintic-Hermite reproduction'; the "
          "default limit gc_SMC_FILE_MAXCAMEL = 128 elements)")
