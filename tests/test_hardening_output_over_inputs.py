"""No command writes over a file it reads (issue 32): every input kind, every output option.

The inputs: a design, its motor catalog, gearbox catalog, drive catalog and cam table; a
machine file and the files its axes name; a CSV to import. Each is named as an output by
the same path, a symbolic link, a ``..`` spelling and a hard link. Every run must end in one
``error:`` line (exit code 2) naming the refusal, with every input's bytes unchanged.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

import pytest

from sizer.errors import UserError
from sizer.files_read import file_read_as
from sizer.io.files import read_user_bytes
from sizer.report.output import write_bytes_atomically
from tests.cli_run import run_cli

ROOT = Path(__file__).resolve().parents[1]
REFUSAL = "never writes over its inputs"

MOTORS = """catalog: test motors
source: test
motors:
  - id: M1
    inertia: 0.5 kg*cm^2
    continuous_torque: 1.3 N*m
    peak_torque: 3.8 N*m
    rated_speed: 3000 rpm
    max_speed: 5000 rpm
    torque_constant: 0.6 N*m/A
"""
DRIVES = """catalog: test drives
source: test
drives:
  - {id: D1, continuous_current: 5 A, peak_current: 15 A}
"""
GEARBOXES = """catalog: test gearboxes
source: test
gearboxes:
  - id: G1
    efficiency: 95 %
    max_input_speed: 6000 rpm
    rated_output_torque: 30 N*m
    peak_output_torque: 60 N*m
    ratios:
      - {ratio: 10, inertia: 0.1 kg*cm^2}
"""


def _cam_csv() -> str:
    """The poly5 rise 10 t^3 - 15 t^4 + 6 t^5 at 21 points (normalized: no units in the
    header); the default quintic spline fits it exactly, at rest at both ends."""
    rows = [f"{t!r},{10 * t**3 - 15 * t**4 + 6 * t**5!r}" for t in (i / 20 for i in range(21))]
    return "# a poly5 cam\nt,q\n" + "\n".join(rows) + "\n"


def _design(files: dict[str, Path]) -> str:
    return f"""name: guard
task: {{displacement: 90 deg, duration: 0.25 s, dwell: 0.35 s}}
load: {{inertia: 0.034 kg*m^2, natural_frequency: 25 Hz, damping_ratio: 0.02}}
transmission: {{type: gearbox, catalog: {files['gearboxes']}}}
laws:
  - cycloidal
  - {{kind: cam_table, file: {files['cam']}}}
motors: {files['motors']}
drives: [{files['drives']}]
"""


def _machine(files: dict[str, Path]) -> str:
    return f"""name: guard machine
machine: {{cycle: 360 deg, master_speed: 60 rpm}}
axes:
  - name: table
    task: {{displacement: 90 deg, move: 150 deg}}
    load: {{inertia: 0.034 kg*m^2}}
    transmission: {{type: gearbox, ratio: 10}}
    laws: [cycloidal, {{kind: cam_table, file: {files['cam']}}}]
    motors: {files['motors']}
"""


def workspace(folder: Path, suffix: str = "") -> dict[str, Path]:
    """The input files in ``folder`` (absolute paths; ``suffix`` appended to every name, so
    that a figure output, which must end in .png, can be spelled as an input's own path)."""
    files = {name: folder / "in" / f"{stem}{suffix}" for name, stem in (
        ("motors", "motors.yaml"), ("drives", "drives.yaml"),
        ("gearboxes", "gearboxes.yaml"), ("cam", "cam.csv"), ("design", "design.yaml"),
        ("machine", "machine.yaml"), ("import", "vendor.csv"))}
    files["design"].parent.mkdir(parents=True)
    texts = {"motors": MOTORS, "drives": DRIVES, "gearboxes": GEARBOXES, "cam": _cam_csv(),
             "design": _design(files), "machine": _machine(files),
             "import": "Model,J (kgcm2),Tc,Tp,n\nM1,0.5,1.3,3.8,3000\n"}
    for name, text in texts.items():
        files[name].write_text(text, encoding="utf-8")
    return files


def spelled(folder: Path, target: Path, spelling: str, suffix: str) -> Path:
    """An output path naming ``target``: itself, a symbolic link, ``..``, a hard link."""
    links = folder / "links"
    links.mkdir(exist_ok=True)
    if spelling == "same":
        return target
    if spelling == "dotdot":
        (target.parent / "sub").mkdir(exist_ok=True)
        return target.parent / "sub" / ".." / target.name
    link = links / f"{spelling}{suffix or target.suffix}"
    if spelling == "symlink":
        link.symlink_to(target)
    else:
        os.link(target, link)
    return link


SPELLINGS = ("same", "symlink", "dotdot", "hardlink")
DESIGN_KINDS = ("design", "motors", "gearboxes", "drives", "cam")
IMPORT_MAPS = ("--map", "Model=id", "--map", "J (kgcm2)=inertia:kg*cm^2",
               "--map", "Tc=continuous_torque:N*m", "--map", "Tp=peak_torque:N*m",
               "--map", "n=rated_speed:rpm", "--source", "test")

# (name, figure output?, the command's arguments given the files and the output path)
Command = tuple[str, bool, Callable[[dict[str, Path], str], list[str]]]
DESIGN_COMMANDS: list[Command] = [
    ("size", False, lambda f, o: ["size", str(f["design"]), "-f", "csv", "-o", o]),
    ("segments", False, lambda f, o: ["segments", str(f["design"]), "-o", o]),
    ("vibration", False, lambda f, o: ["vibration", str(f["design"]), "-o", o]),
    ("vibration-plot", True, lambda f, o: ["vibration", str(f["design"]), "--plot", o]),
    ("plot", True, lambda f, o: ["plot", str(f["design"]), "-o", o]),
]
LAW_COMMANDS: list[Command] = [
    ("law", False, lambda f, o: ["law", _cam_spec(f), "--displacement", "1",
                                 "--duration", "1", "-o", o]),
    ("laws", False, lambda f, o: ["laws", "--law", _cam_spec(f), "-f", "json", "-o", o]),
    ("spectrum", False, lambda f, o: ["spectrum", _cam_spec(f), "-o", o]),
    ("spectrum-plot", True, lambda f, o: ["spectrum", _cam_spec(f), "--plot", o]),
    ("plot-law", True, lambda f, o: ["plot-law", _cam_spec(f), "-o", o]),
]


def _cam_spec(files: dict[str, Path]) -> str:
    return f"{{kind: cam_table, file: {files['cam']}}}"


def assert_refused(folder: Path, args: list[str], *fragments: str) -> None:
    """Exit code 2, one error line naming the refusal, every input's bytes unchanged."""
    before = {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()}
    result = run_cli(*args)
    assert result.returncode == 2, (result.stdout, result.stderr)
    assert "Traceback" not in result.stderr
    errors = [line for line in result.stderr.splitlines() if line.startswith("error:")]
    assert len(errors) == 1, result.stderr
    for fragment in (REFUSAL, *fragments):
        assert fragment in errors[0], errors[0]
    after = {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()}
    assert after == before


@pytest.mark.parametrize("spelling", SPELLINGS)
@pytest.mark.parametrize("kind", DESIGN_KINDS)
@pytest.mark.parametrize("command", DESIGN_COMMANDS, ids=[c[0] for c in DESIGN_COMMANDS])
def test_design_commands_refuse_every_input(tmp_path: Path, command: Command, kind: str,
                                            spelling: str) -> None:
    name, figure, make = command
    suffix = ".png" if figure else ""
    files = workspace(tmp_path, suffix)
    output = spelled(tmp_path, files[kind], spelling, suffix)
    field = "--plot" if name.endswith("-plot") else "--output"
    assert_refused(tmp_path, make(files, str(output)), field)


@pytest.mark.parametrize("spelling", SPELLINGS)
def test_size_as_json_refuses_the_cam_table(tmp_path: Path, spelling: str) -> None:
    files = workspace(tmp_path)
    output = spelled(tmp_path, files["cam"], spelling, "")
    assert_refused(tmp_path, ["size", str(files["design"]), "-f", "json", "-o", str(output)])


@pytest.mark.parametrize("spelling", SPELLINGS)
@pytest.mark.parametrize("command", LAW_COMMANDS, ids=[c[0] for c in LAW_COMMANDS])
def test_law_commands_refuse_the_cam_table(tmp_path: Path, command: Command,
                                           spelling: str) -> None:
    name, figure, make = command
    suffix = ".png" if figure else ""
    files = workspace(tmp_path, suffix)
    output = spelled(tmp_path, files["cam"], spelling, suffix)
    field = "--plot" if name.endswith("-plot") else "--output"
    assert_refused(tmp_path, make(files, str(output)), field)


@pytest.mark.parametrize("spelling", SPELLINGS)
@pytest.mark.parametrize("kind", ("machine", "motors", "cam"))
def test_size_of_a_machine_refuses_the_machine_and_its_axis_files(
        tmp_path: Path, kind: str, spelling: str) -> None:
    files = workspace(tmp_path)
    output = spelled(tmp_path, files[kind], spelling, "")
    assert_refused(tmp_path, ["size", str(files["machine"]), "-f", "csv", "-o", str(output)])


def _report_folder(tmp_path: Path, files: dict[str, Path], kind: str, spelling: str) -> Path:
    """A report folder whose report.md is the input ``kind``, spelled ``spelling``."""
    folder = tmp_path / "report"
    folder.mkdir()
    target = folder / "report.md"
    if spelling == "symlink":
        target.symlink_to(files[kind])
    elif spelling == "hardlink":
        os.link(files[kind], target)
    else:  # the input itself lives in the report folder
        files[kind].rename(target)
        files[kind].symlink_to(target)  # the other inputs still name it by its old path
    return folder / "sub" / ".." if spelling == "dotdot" else folder


@pytest.mark.parametrize("spelling", SPELLINGS)
@pytest.mark.parametrize("kind", (*DESIGN_KINDS, "machine"))
def test_report_refuses_to_write_its_files_over_an_input(tmp_path: Path, kind: str,
                                                         spelling: str) -> None:
    files = workspace(tmp_path)
    folder = _report_folder(tmp_path, files, kind, spelling)
    if spelling == "dotdot":
        (tmp_path / "report" / "sub").mkdir()
    given = files["machine" if kind == "machine" else "design"]
    assert_refused(tmp_path, ["report", str(given), "-o", str(folder)])


@pytest.mark.parametrize("spelling", SPELLINGS)
def test_catalog_import_refuses_its_csv(tmp_path: Path, spelling: str) -> None:
    files = workspace(tmp_path)
    output = spelled(tmp_path, files["import"], spelling, "")
    assert_refused(tmp_path, ["catalog", "import", str(files["import"]), *IMPORT_MAPS,
                              "-o", str(output)])


@pytest.mark.parametrize("spelling", SPELLINGS)
def test_catalog_list_and_show_refuse_the_catalog(tmp_path: Path, spelling: str) -> None:
    files = workspace(tmp_path)
    output = spelled(tmp_path, files["motors"], spelling, "")
    assert_refused(tmp_path, ["catalog", "list", str(files["motors"]), "-o", str(output)])
    assert_refused(tmp_path, ["catalog", "show", "M1", "--catalog", str(files["motors"]),
                              "-o", str(output)])


def test_the_writer_refuses_any_file_read_in_this_process(tmp_path: Path) -> None:
    """The last line of defence: whatever a command checked, the writer refuses a file
    the bounded reader read, through every spelling, naming the option given."""
    read = tmp_path / "read.csv"
    read.write_bytes(b"0,0\n1,1\n")
    read_user_bytes(read)
    assert file_read_as(tmp_path / "." / "read.csv") == str(read)
    for spelling in SPELLINGS:
        output = spelled(tmp_path, read, spelling, ".png")
        with pytest.raises(UserError, match=REFUSAL) as caught:
            write_bytes_atomically(output, b"new", field="--plot")
        assert caught.value.field == "--plot" and caught.value.file == str(output)
        assert read.read_bytes() == b"0,0\n1,1\n"
    other = tmp_path / "other.csv"
    other.write_bytes(b"old")  # never read: replaced as usual
    write_bytes_atomically(other, b"new")
    assert other.read_bytes() == b"new"


def test_a_new_file_on_the_inode_of_one_read_and_deleted_is_not_an_input(
        tmp_path: Path) -> None:
    """A long-lived process deletes files and makes new ones; a new file may reuse the
    inode of one read before (forced here with os.utime: same inode, another time)."""
    read = tmp_path / "read.csv"
    read.write_bytes(b"0,0\n1,1\n")
    read_user_bytes(read)
    assert file_read_as(read) == str(read)
    info = os.stat(read)
    os.utime(read, ns=(info.st_atime_ns, info.st_mtime_ns + 10**9))
    assert file_read_as(read) is None
