"""Which files has this process read? The identities of the user's input files.

:func:`sizer.io.files.read_user_bytes` (through which every user file is read) records
each file it opens by its identity (``st_dev``, ``st_ino``); the one writer of outputs
(:func:`sizer.report.output.write_bytes_atomically`) asks :func:`file_read_as` and refuses
to write over one of them, whatever the spelling of the path (``..``, a symbolic link, a
hard link). A neutral module (no sizer imports) so that both layers may use it.

A file is known by its device, inode and modification time: a long-lived process (a
notebook, the test suite) deletes files and makes new ones, and a new file may get the
inode of one read and deleted before; its modification time tells them apart.
"""

from __future__ import annotations

import os
from pathlib import Path

_READ: dict[tuple[int, int, int], str] = {}
"""(st_dev, st_ino, st_mtime_ns) of every file read in this process -> its path as first
given."""


def _identity(info: os.stat_result) -> tuple[int, int, int]:
    return info.st_dev, info.st_ino, info.st_mtime_ns


def record_file_read(info: os.stat_result, path: str) -> None:
    """Remember the file of ``info`` (an ``os.fstat`` of the opened file) as read."""
    _READ.setdefault(_identity(info), path)


def file_read_as(path: str | Path) -> str | None:
    """The path under which this process read the file ``path`` names (the same inode,
    unchanged since, whatever the spelling or link), or None when it read no such file."""
    try:
        info = os.stat(path)
    except (OSError, ValueError):
        return None
    return _READ.get(_identity(info))


def files_read() -> list[str]:
    """The paths (as first given) of the files this process read, in reading order."""
    return list(_READ.values())


def forget_files_read() -> None:
    """Start a new record (tests; a caller that knows no later write concerns them)."""
    _READ.clear()
