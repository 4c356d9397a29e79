"""Where text goes: stdout, or a file replaced atomically."""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

from sizer.errors import UserError


def write_text_atomically(path: Path | str, text: str) -> None:
    """Write UTF-8 text to a temporary file beside ``path``, then rename it over ``path``.

    A reader never sees a half-written file; on failure the old file is left untouched.
    """
    write_bytes_atomically(Path(path), text.encode("utf-8"))


def write_bytes_atomically(path: Path, data: bytes) -> None:
    """Write to a temporary file beside ``path``, then rename it over ``path``."""
    directory = path.parent if str(path.parent) else Path(".")
    fd, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
        os.chmod(temporary, _file_mode(path))
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def _file_mode(path: Path) -> int:
    """The permissions the file keeps (if it exists) or would get from open() (umask)."""
    try:
        return path.stat().st_mode & 0o7777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def emit(text: str, output: Path | None) -> None:
    """Write text to ``output`` (atomically) or, when it is None, to stdout."""
    if output is None:
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    try:
        write_text_atomically(output, text)
    except OSError as error:
        reason = error.strerror or str(error)
        raise UserError(f"cannot write the output file: {reason}", file=str(output)) from error


def stdout_is_terminal() -> bool:
    """True when stdout is an interactive terminal (rich tables), False for pipes and files."""
    try:
        return sys.stdout.isatty()
    except (AttributeError, ValueError):
        return False
