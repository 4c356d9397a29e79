"""Where text goes: stdout, or a file replaced atomically, never over one of the inputs.

Writing a file (:func:`write_bytes_atomically`):

- The bytes go to a temporary file ``.<name>.sizer-<pid>.tmp`` in the target's folder
  (created exclusively, mode 0600 while written), are flushed and fsync'ed, get the mode of
  the file they replace (or the umask's default), and are renamed over the target with
  ``os.replace``; the folder is fsync'ed too. A reader, or a run killed at any moment,
  sees the old file or the new one, never a part of it.
- A target that is a symbolic link is written through: the real file (the link's final
  target) is replaced, beside itself, and the link stays a link. A dangling link, a link
  to a folder, a folder, a missing folder or one we may not write in is a UserError.
- Leftovers: a run killed while writing leaves its temporary file. Before writing, every
  ``.<name>.sizer-<pid>.tmp`` beside the target whose process ``<pid>`` no longer exists,
  or is this process (which writes one file at a time, so such a file is from an earlier
  process of the same pid), is removed. A temporary of a live process of another pid is
  left alone (it may be a concurrent writer).

Inputs are protected twice: :func:`check_output_not_input` (before any work) refuses an
output that names one of the command's input files, and :func:`write_bytes_atomically`
refuses a target that is a file this process read (:mod:`sizer.files_read`: the same
inode, whatever the spelling, symbolic or hard link). Nothing is written then.
"""

from __future__ import annotations

import errno
import os
import re
import stat
import sys
from collections.abc import Iterable
from pathlib import Path

from sizer.errors import UserError
from sizer.files_read import file_read_as
from sizer.report.printable import printable

TEMPORARY_SUFFIX = ".tmp"
CHUNK = 1 << 20
"""Bytes per write call."""


def temporary_name(name: str, pid: int) -> str:
    """The temporary file of a write of ``name`` by process ``pid``."""
    return f".{name}.sizer-{pid}{TEMPORARY_SUFFIX}"


def _temporary_pattern(name: str) -> re.Pattern[str]:
    return re.compile(re.escape(f".{name}.sizer-") + r"(\d+)" + re.escape(TEMPORARY_SUFFIX))


def _process_exists(pid: int) -> bool:
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # someone else's live process
        return True
    except OSError:
        return True
    return True


def remove_stale_temporaries(target: Path) -> list[Path]:
    """Remove the leftovers of killed writes of ``target`` (see the module docstring)."""
    pattern = _temporary_pattern(target.name)
    removed: list[Path] = []
    try:
        names = os.listdir(target.parent)
    except OSError:
        return removed
    for name in names:
        match = pattern.fullmatch(name)
        if match is None:
            continue
        pid = int(match.group(1))
        if pid != os.getpid() and _process_exists(pid):
            continue
        leftover = target.parent / name
        try:
            if stat.S_ISREG(os.lstat(leftover).st_mode):
                leftover.unlink()
                removed.append(leftover)
        except OSError:
            continue
    return removed


def real_target(path: Path, field: str = "--output") -> Path:
    """The file a write of ``path`` replaces: ``path`` itself, or the final target of a
    symbolic link. UserError for a folder, a dangling link, a missing or unusable folder."""
    def fail(message: str) -> UserError:
        return UserError(message, file=str(path), field=field)

    if path.is_symlink():
        target = Path(os.path.realpath(path))
        if not target.exists():
            raise fail(f"a symbolic link to {target}, which does not exist; not writing "
                       f"through a dangling link")
        if target.is_dir():
            raise fail(f"a symbolic link to the folder {target}; name a file")
        path = target
    if path.is_dir():
        raise fail("is a folder; name a file")
    if path.exists() and not path.is_file():
        raise fail("not a regular file (a device or a pipe?); name a file")
    folder = path.parent
    if not folder.is_dir():
        what = "is not a folder" if folder.exists() else "does not exist"
        raise fail(f"cannot write it: the folder {folder} {what}")
    return path


def write_text_atomically(path: Path | str, text: str, field: str = "--output") -> None:
    """Write UTF-8 text atomically (see the module docstring)."""
    write_bytes_atomically(Path(path), text.encode("utf-8"), field=field)


def write_bytes_atomically(path: Path | str, data: bytes, field: str = "--output") -> Path:
    """Write ``data`` to ``path`` atomically, through a symbolic link; returns the file
    replaced. UserError when the target cannot be written (nothing changed then)."""
    path = Path(path)
    target = real_target(path, field)
    refuse_file_read(path, field)
    remove_stale_temporaries(target)
    temporary = target.parent / temporary_name(target.name, os.getpid())
    mode = _file_mode(target)
    try:
        fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_TRUNC, 0o600)
    except OSError as error:
        raise _write_error(path, error, field) from None
    try:
        with os.fdopen(fd, "wb") as handle:
            view = memoryview(data)
            for start in range(0, len(view), CHUNK):
                handle.write(view[start:start + CHUNK])
            handle.flush()
            os.fsync(handle.fileno())
        os.chmod(temporary, mode)
        os.replace(temporary, target)
    except BaseException as error:
        Path(temporary).unlink(missing_ok=True)
        if isinstance(error, OSError):
            raise _write_error(path, error, field) from None
        raise
    _fsync_folder(target.parent)
    return target


def _write_error(path: Path, error: OSError, field: str) -> UserError:
    reason = error.strerror or str(error)
    if error.errno in (errno.EACCES, errno.EPERM, errno.EROFS):
        reason += f" (the folder {path.parent} is not writable)"
    return UserError(f"cannot write it: {reason}", file=str(path), field=field)


def _fsync_folder(folder: Path) -> None:
    """Make the rename durable (best effort: not every system can open a folder)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def _file_mode(path: Path) -> int:
    """The permissions the file keeps (if it exists) or would get from open() (umask)."""
    try:
        return path.stat().st_mode & 0o7777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def same_file(a: Path | str, b: Path | str) -> bool:
    """True when ``a`` and ``b`` are one file: equal resolved paths, or one inode (hard
    links, symbolic links)."""
    if not os.path.exists(b):
        return False
    try:
        if os.path.realpath(a) == os.path.realpath(b):
            return True
        return os.path.samefile(a, b)
    except (OSError, ValueError):
        return False


def _input_error(output: Path | str, given: Path | str, field: str) -> UserError:
    which = ("is an input" if str(output) == str(given) else
             f"is the same file as the input {given}")
    return UserError(f"{which} of this command; a command never writes over its inputs: "
                     f"name another output file", file=str(output), field=field)


def refuse_file_read(output: Path | str, field: str = "--output") -> None:
    """UserError when ``output`` names a file this process read (sizer.io.files)."""
    given = file_read_as(output)
    if given is not None:
        raise _input_error(output, given, field)


def check_output_not_input(output: Path | str | None, inputs: Iterable[Path | str],
                           field: str = "--output") -> None:
    """UserError when ``output`` is one of the ``inputs`` (or a link to one) or a file
    this process has read: a command never writes over a file it reads."""
    if output is None:
        return
    for given in inputs:
        if same_file(output, given):
            raise _input_error(output, given, field)
    refuse_file_read(output, field)


def emit(text: str, output: Path | None, *, escape: bool = False) -> None:
    """Write text to ``output`` (atomically) or, when it is None, to stdout.

    With ``escape`` (human-readable formats: plain tables, Markdown, check reports)
    terminal control characters are escaped, newlines kept (:mod:`sizer.report.printable`).
    """
    if escape:
        text = printable(text, keep_newlines=True)
    if output is None:
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    write_text_atomically(output, text)


def stdout_is_terminal() -> bool:
    """True when stdout is an interactive terminal (rich tables), False for pipes and files."""
    try:
        return sys.stdout.isatty()
    except (AttributeError, ValueError):
        return False
