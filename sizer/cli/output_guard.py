"""``--output`` checked before any work: a writable file that is none of the inputs.

Every command with ``-o`` calls :func:`check_output` with the inputs it knows from its
arguments (the design file, ``--catalog`` files, the CSV it imports) before reading
anything, and again with the files a design load read (``Design.files``: the catalogs
and gearbox catalogs the design names) before computing. Both also refuse any file this
process has read (:mod:`sizer.files_read`: a cam table a law read, the axis files of a
machine...), so a command that builds its laws calls :func:`check_output` once more, after
building them and before computing. Nothing is written then; and the writer itself
(sizer.report.output.write_bytes_atomically) refuses a file read, whatever was checked.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from sizer.report.output import check_output_not_input, real_target


def existing_files(references: Iterable[Path | str | None]) -> list[Path]:
    """The references that name existing files (a bundled catalog's name is not one)."""
    found = []
    for reference in references:
        if reference is None:
            continue
        path = Path(reference).expanduser()
        try:
            if path.is_file():
                found.append(path)
        except OSError:
            continue
    return found


def check_output(output: Path | None, inputs: Iterable[Path | str | None] = (),
                 field: str = "--output") -> None:
    """UserError (naming ``field`` and the input) when ``output`` cannot be written (a
    folder, a missing folder, a dangling link) or is one of the ``inputs``."""
    if output is None:
        return
    real_target(output, field)
    check_output_not_input(output, existing_files(inputs), field)


def check_outputs(outputs: Iterable[Path], inputs: Iterable[Path | str | None],
                  field: str = "--output") -> None:
    """:func:`check_output_not_input` for several output files (a report's folder)."""
    files = existing_files(inputs)
    for output in outputs:
        check_output_not_input(output, files, field)
