"""Writing results: atomic file replacement and stdout (sizer.report.output)."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest

from sizer.errors import UserError
from sizer.report.output import emit, write_text_atomically


def test_write_creates_and_replaces_without_leftovers(tmp_path: Path) -> None:
    target = tmp_path / "out.csv"
    write_text_atomically(target, "a\n")
    write_text_atomically(target, "b\nc\n")
    assert target.read_bytes() == b"b\nc\n"
    assert os.listdir(tmp_path) == ["out.csv"]


def test_write_keeps_newlines_and_utf8(tmp_path: Path) -> None:
    target = tmp_path / "t.txt"
    write_text_atomically(target, "C∞\n")
    assert target.read_bytes() == "C∞\n".encode()


def test_new_file_is_readable_like_an_ordinary_file(tmp_path: Path) -> None:
    target = tmp_path / "new.json"
    write_text_atomically(target, "{}\n")
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~umask


def test_existing_file_keeps_its_permissions(tmp_path: Path) -> None:
    target = tmp_path / "old.json"
    target.write_text("old")
    target.chmod(0o640)
    write_text_atomically(target, "new")
    assert stat.S_IMODE(target.stat().st_mode) == 0o640


def test_emit_to_stdout(capsys: pytest.CaptureFixture[str]) -> None:
    emit("hello\n", None)
    assert capsys.readouterr().out == "hello\n"


def test_emit_to_a_missing_directory_is_a_user_error(tmp_path: Path) -> None:
    target = tmp_path / "missing" / "out.csv"
    with pytest.raises(UserError) as caught:
        emit("x", target)
    assert caught.value.file == str(target)
    assert not (tmp_path / "missing").exists()
