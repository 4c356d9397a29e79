"""The file writer (sizer.report.output): atomic, through symbolic links, mode kept,
leftovers of killed runs cleaned, nothing changed on failure; and a real kill -9."""

from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

from sizer.errors import UserError
from sizer.report.output import (
    check_output_not_input,
    remove_stale_temporaries,
    same_file,
    temporary_name,
    write_bytes_atomically,
    write_text_atomically,
)

ROOT = Path(__file__).resolve().parents[1]


def leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if ".sizer-" in p.name)


def dead_pid() -> int:
    """The pid of a process that has exited (and been reaped)."""
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait(timeout=60)
    return process.pid


def test_new_file_gets_the_umask_mode_and_no_leftover(tmp_path: Path) -> None:
    target = tmp_path / "out.csv"
    write_text_atomically(target, "a,b\n")
    assert target.read_text() == "a,b\n"
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~umask
    assert leftovers(tmp_path) == []


def test_replacing_keeps_the_mode_of_the_old_file(tmp_path: Path) -> None:
    target = tmp_path / "out.csv"
    target.write_text("old")
    target.chmod(0o640)
    write_text_atomically(target, "new")
    assert target.read_text() == "new"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640


def test_a_symbolic_link_is_written_through_and_stays_a_link(tmp_path: Path) -> None:
    real = tmp_path / "data" / "real.csv"
    real.parent.mkdir()
    real.write_text("old")
    real.chmod(0o600)
    link = tmp_path / "link.csv"
    link.symlink_to(Path("data") / "real.csv")
    written = write_bytes_atomically(link, b"new")
    assert link.is_symlink() and os.readlink(link) == str(Path("data") / "real.csv")
    assert real.read_bytes() == b"new" and written == real.resolve()
    assert stat.S_IMODE(real.stat().st_mode) == 0o600
    assert leftovers(tmp_path) == [] and leftovers(real.parent) == []


def test_a_chain_of_links_is_followed_to_the_last_file(tmp_path: Path) -> None:
    real = tmp_path / "real.csv"
    real.write_text("old")
    (tmp_path / "one.csv").symlink_to("real.csv")
    (tmp_path / "two.csv").symlink_to("one.csv")
    write_text_atomically(tmp_path / "two.csv", "new")
    assert real.read_text() == "new"
    assert (tmp_path / "one.csv").is_symlink() and (tmp_path / "two.csv").is_symlink()


@pytest.mark.parametrize(("make", "words"), [
    (lambda p: p.symlink_to(p.parent / "nowhere.csv"), ("symbolic link", "does not exist")),
    (lambda p: p.symlink_to(p.parent), ("symbolic link", "folder")),
    (lambda p: p.mkdir(), ("is a folder",)),
], ids=["dangling-link", "link-to-folder", "folder"])
def test_targets_that_are_not_files_are_user_errors(tmp_path: Path, make, words) -> None:
    target = tmp_path / "out.csv"
    make(target)
    before = sorted(os.listdir(tmp_path))
    with pytest.raises(UserError) as caught:
        write_text_atomically(target, "x")
    assert caught.value.field == "--output" and caught.value.file == str(target)
    for word in words:
        assert word in str(caught.value)
    assert sorted(os.listdir(tmp_path)) == before


def test_a_missing_folder_is_a_user_error(tmp_path: Path) -> None:
    with pytest.raises(UserError, match="does not exist"):
        write_text_atomically(tmp_path / "missing" / "out.csv", "x")
    assert not (tmp_path / "missing").exists()


@pytest.mark.skipif(os.geteuid() == 0, reason="root may write in any folder")
def test_an_unwritable_folder_is_a_user_error(tmp_path: Path) -> None:
    folder = tmp_path / "locked"
    folder.mkdir()
    (folder / "out.csv").write_text("old")
    folder.chmod(0o500)
    try:
        with pytest.raises(UserError, match="not writable"):
            write_text_atomically(folder / "out.csv", "new")
        assert (folder / "out.csv").read_text() == "old"
    finally:
        folder.chmod(0o700)


def test_a_refused_temporary_file_is_a_user_error(tmp_path: Path, monkeypatch) -> None:
    """As in a folder the user may not write in (simulated: the tests may run as root)."""
    target = tmp_path / "out.csv"
    target.write_text("old")
    real_open = os.open

    def refuse(path, flags, *args, **kwargs):
        if ".sizer-" in str(path):
            raise PermissionError(13, "Permission denied")
        return real_open(path, flags, *args, **kwargs)

    monkeypatch.setattr(os, "open", refuse)
    with pytest.raises(UserError, match=r"Permission denied.*not writable") as caught:
        write_text_atomically(target, "new")
    assert caught.value.field == "--output"
    assert target.read_text() == "old" and leftovers(tmp_path) == []


def test_a_failed_rename_leaves_the_old_file_and_no_temporary(tmp_path: Path,
                                                            monkeypatch) -> None:
    target = tmp_path / "out.csv"
    target.write_bytes(b"old contents")

    def no_room(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", no_room)
    with pytest.raises(UserError, match="No space left"):
        write_bytes_atomically(target, b"new" * 1000)
    assert target.read_bytes() == b"old contents"
    assert leftovers(tmp_path) == []


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path: Path,
                                                           monkeypatch) -> None:
    target = tmp_path / "out.csv"
    target.write_bytes(b"old contents")

    def disk_error(fd: int) -> None:
        raise OSError(5, "Input/output error")

    monkeypatch.setattr(os, "fsync", disk_error)
    with pytest.raises(UserError, match="Input/output error"):
        write_bytes_atomically(target, b"new")
    assert target.read_bytes() == b"old contents"
    assert leftovers(tmp_path) == []


def test_leftovers_of_dead_processes_are_removed_others_kept(tmp_path: Path) -> None:
    target = tmp_path / "out.csv"
    dead = tmp_path / temporary_name("out.csv", dead_pid())
    mine = tmp_path / temporary_name("out.csv", os.getpid())  # an earlier process's pid
    live = tmp_path / temporary_name("out.csv", os.getppid())  # a live writer
    other = tmp_path / temporary_name("other.csv", dead_pid())  # another target's
    unrelated = tmp_path / ".out.csv.sizer-notapid.tmp"
    for path in (dead, mine, live, other, unrelated):
        path.write_text("partial")
    write_text_atomically(target, "new")
    assert target.read_text() == "new"
    assert not dead.exists() and not mine.exists()
    assert live.exists() and other.exists() and unrelated.exists()


def test_a_leftover_folder_of_the_same_name_is_not_removed(tmp_path: Path) -> None:
    odd = tmp_path / temporary_name("out.csv", dead_pid())
    odd.mkdir()
    assert remove_stale_temporaries(tmp_path / "out.csv") == []
    assert odd.is_dir()


def test_same_file_sees_hard_and_symbolic_links(tmp_path: Path) -> None:
    design = tmp_path / "design.yaml"
    design.write_text("x")
    (tmp_path / "hard.yaml").hardlink_to(design)
    (tmp_path / "soft.yaml").symlink_to(design)
    assert same_file(tmp_path / "hard.yaml", design)
    assert same_file(tmp_path / "soft.yaml", design)
    assert same_file(tmp_path / "sub" / ".." / "design.yaml", design)
    assert not same_file(tmp_path / "new.csv", design)
    with pytest.raises(UserError, match="same file as the input"):
        check_output_not_input(tmp_path / "hard.yaml", [design])
    check_output_not_input(tmp_path / "new.csv", [design])  # no error


# --------------------------------------------------------------- kill -9 during a write
SAMPLES = "120000"
"""Samples of the law table: about 11 MB of CSV, written in 1 MiB chunks."""


def _command(target: Path) -> list[str]:
    return [sys.executable, "-m", "sizer", "law", "cycloidal", "--displacement", "1",
            "--duration", "1", "--samples", SAMPLES, "--format", "csv", "-o", str(target)]


def _kill_while_writing(target: Path) -> tuple[bool, Path]:
    """Start a run, kill -9 it as soon as its temporary file holds some bytes; (caught,
    temporary)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    process = subprocess.Popen(_command(target), cwd=target.parent, env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    temporary = target.parent / temporary_name(target.name, process.pid)
    deadline = time.monotonic() + 120
    caught = False
    while time.monotonic() < deadline:
        if temporary.exists():
            try:  # the first bytes in it, then kill (a part written, the rest not)
                while temporary.stat().st_size == 0 and process.poll() is None:
                    pass
            except FileNotFoundError:  # renamed already: the kill comes after the write
                pass
            process.send_signal(signal.SIGKILL)
            caught = True
            break
        if process.poll() is not None:
            break
        # the run starts for a second or more before it creates the temporary file: spinning
        # through that took a core from the run and from the other tests; writing and syncing
        # ~11 MB takes several ms (30-40 ms on a disk), far longer than this pause
        time.sleep(0.0005)
    else:
        process.kill()
    process.communicate(timeout=60)
    return caught, temporary


def test_kill_9_during_a_large_write_leaves_the_old_file_or_the_new(tmp_path: Path) -> None:
    """The target is always the old file (byte-identical) or the complete new one, never a
    part; the next run removes the killed run's temporary file."""
    target = tmp_path / "big.csv"
    old = b"old,file\n1,2\n"
    target.write_bytes(old)
    states, temporaries = [], []
    for _ in range(3):
        caught, temporary = _kill_while_writing(target)
        states.append(target.read_bytes())
        if caught:
            temporaries.append(temporary)
    assert temporaries, "no run was caught while writing"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    subprocess.run(_command(target), cwd=tmp_path, env=env, check=True, timeout=300,
                   capture_output=True)
    new = target.read_bytes()
    assert new.startswith(b"t [s],q [rad]") and new.count(b"\n") == int(SAMPLES) + 1
    for state in states:
        assert state in (old, new), f"partial file of {len(state)} bytes"
    assert leftovers(tmp_path) == [], "the next run left the killed run's temporaries"


def test_kill_9_without_an_old_file_leaves_none_or_the_new(tmp_path: Path) -> None:
    target = tmp_path / "big.csv"
    caught, _ = _kill_while_writing(target)
    if caught:
        assert not target.exists() or target.read_bytes().count(b"\n") == int(SAMPLES) + 1
    else:  # the run finished before it was seen: the whole file
        assert target.read_bytes().count(b"\n") == int(SAMPLES) + 1
