"""Bounded reading of user files: regular files only, a size limit, UTF-8 text.

``read_user_text(path, limit=MAX_CATALOG_BYTES)`` refuses, without blocking, what is not a
regular file (a FIFO, a device like /dev/zero, a directory, a socket), reads at most
``limit + 1`` bytes, and decodes UTF-8 (a BOM is accepted). Every refusal is a UserError
naming the file: too big (its size and the limit), not UTF-8 (the line), NUL bytes (binary or
UTF-16), missing, unreadable, a name too long.

Every file opened is remembered by its identity (``st_dev``, ``st_ino``) for the rest of
the process (:mod:`sizer.files_read`), so that no output is written over an input
(sizer.report.output.write_bytes_atomically refuses it).
"""

from __future__ import annotations

import errno
import os
import stat
from pathlib import Path

from sizer.errors import UserError
from sizer.files_read import record_file_read
from sizer.input_limits import MAX_CATALOG_BYTES, MIB

_KINDS = (
    (stat.S_ISDIR, "a directory"),
    (stat.S_ISFIFO, "a named pipe (FIFO)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)

_BOMS = (
    (b"\xff\xfe\x00\x00", "UTF-32"), (b"\x00\x00\xfe\xff", "UTF-32"),
    (b"\xff\xfe", "UTF-16"), (b"\xfe\xff", "UTF-16"),
)


def _size(count: int) -> str:
    return f"{count / MIB:.1f} MiB" if count >= MIB else f"{count} bytes"


def _kind(mode: int) -> str | None:
    """What a non-regular file is, or None for a regular file."""
    for test, name in _KINDS:
        if test(mode):
            return name
    return None if stat.S_ISREG(mode) else "not a regular file"


def _refuse(mode: int, file: str, what: str) -> None:
    kind = _kind(mode)
    if kind is not None:
        raise UserError(f"is {kind}, not a {what} file (only regular files are read)",
                        file=file)


def _os_error(error: OSError, file: str) -> UserError:
    if error.errno == errno.ENOENT:
        return UserError("file not found", file=file)
    if error.errno in (errno.EACCES, errno.EPERM):
        return UserError("permission denied (cannot read the file)", file=file)
    if error.errno == errno.ENAMETOOLONG:
        return UserError("the file name is too long", file=file)
    if error.errno == errno.EISDIR:
        return UserError("is a directory, not a file", file=file)
    return UserError(f"cannot read: {error.strerror or error}", file=file)


def read_user_bytes(path: str | Path, *, limit: int = MAX_CATALOG_BYTES,
                    what: str = "YAML") -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes; UserError otherwise."""
    file = str(path)
    if "\x00" in file:
        raise UserError("the file name contains a NUL character", file=file.replace("\x00", "\\0"))
    try:
        _refuse(os.stat(file).st_mode, file, what)  # before open: a FIFO must not block
        fd = os.open(file, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0)
                     | getattr(os, "O_NOCTTY", 0))
    except OSError as error:
        raise _os_error(error, file) from None
    try:
        info = os.fstat(fd)  # the file opened may not be the one stat()ed
        _refuse(info.st_mode, file, what)
        record_file_read(info, file)
        if info.st_size > limit:
            raise _too_big(file, info.st_size, limit)
        chunks, total = [], 0
        while total <= limit:
            chunk = os.read(fd, min(limit + 1 - total, MIB))
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
    except OSError as error:
        raise _os_error(error, file) from None
    finally:
        os.close(fd)
    if total > limit:
        raise _too_big(file, None, limit)
    return b"".join(chunks)


def _too_big(file: str, size: int | None, limit: int) -> UserError:
    given = f"{_size(size)}" if size is not None else f"more than {_size(limit)}"
    return UserError(f"the file is too big: {given}, the limit is {_size(limit)} "
                     f"(see docs/input-files.md)", file=file)


def decode_text(raw: bytes, file: str, *, encoding: str = "utf-8") -> str:
    """UTF-8 text of ``raw`` (BOM accepted); UserError with the line otherwise."""
    utf8 = encoding.lower().replace("_", "-") in ("utf-8", "utf8")
    if utf8:
        for bom, name in _BOMS:
            if raw.startswith(bom):
                raise UserError(f"is {name} text, not UTF-8: save it as UTF-8", file=file)
        nul = raw.find(b"\x00")
        if nul >= 0:
            raise UserError("contains NUL bytes: a binary file or UTF-16 text, not UTF-8 "
                            "text", file=file, line=raw.count(b"\n", 0, nul) + 1)
    try:
        return raw.decode("utf-8-sig" if utf8 else encoding)
    except UnicodeDecodeError as error:
        line = raw.count(b"\n", 0, error.start) + 1
        byte = raw[error.start:error.start + 1].hex()
        raise UserError(f"not {'UTF-8' if utf8 else encoding} text (byte 0x{byte}): save it "
                        f"as UTF-8", file=file, line=line) from None


def read_user_text(path: str | Path, *, limit: int = MAX_CATALOG_BYTES,
                   what: str = "YAML") -> str:
    """The UTF-8 text of a regular file of at most ``limit`` bytes."""
    return decode_text(read_user_bytes(path, limit=limit, what=what), str(path))
