"""Laws sized in worker processes (sizer.sizing.law_processes): the same result as one
process, bit for bit; errors and progress come back; laws pickle as their spec."""

from __future__ import annotations

import pickle
import sys
from pathlib import Path

import numpy as np
import pytest

from sizer.errors import UserError
from sizer.laws import DEFAULT_LAW_SPECS, make_law
from sizer.laws.data_spec import data_spec_text
from sizer.sizing import size_design
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.engine import AUTO_WORK, tables_in_processes, usable_cpus, worker_count

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))
from cli_run import run_cli  # noqa: E402
from synthetic import book_problem, scale_problem  # noqa: E402

LAWS = ("cycloidal", "poly5", "double_s(alpha=1/3, beta=1/4)", "modified_sinusoidal")


@pytest.mark.parametrize("design", [
    scale_problem(16, laws=LAWS),
    book_problem(3, laws=("trapezoidal(alpha=auto)", "cycloidal"), ratios=(4.0, 9.0)),
], ids=["listed ratios", "an auto shape"])
def test_two_processes_give_the_one_process_result_bit_for_bit(design):
    alone, spread = size_design(design), size_design(design, workers=2)
    a, b = alone.table, spread.table
    for name in a.figures:
        assert np.array_equal(a.figures[name], b.figures[name], equal_nan=True), name
    for name in ("feasible", "motor", "stage_ratio"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    # laws and transmissions by value (the tables' tuples they index may differ)
    assert [a.laws[k].spec for k in a.law] == [b.laws[k].spec for k in b.law]
    assert [a.transmissions[k] for k in a.option] == [b.transmissions[k] for k in b.option]
    assert b.motors is design.motors or b.motors == design.motors
    rows = [(r.motor, r.spec, r.duration, r.feasible) for r in alone.results]
    assert rows == [(r.motor, r.spec, r.duration, r.feasible) for r in spread.results]
    assert any(r.feasible for r in alone.results)  # the comparison means something


def test_the_jobs_option_gives_the_same_output():
    example = str(ROOT / "examples" / "indexing-table-gearboxes.yaml")
    alone = run_cli("size", example, "--all", "--format", "json")
    spread = run_cli("size", example, "--all", "--format", "json", "--jobs", "2")
    assert alone.returncode == spread.returncode == 0, spread.stderr
    assert alone.stdout == spread.stdout
    refused = run_cli("size", example, "--jobs", "0")
    assert refused.returncode == 2 and "--jobs" in refused.stderr


def test_progress_counts_every_law_once_in_order():
    design = scale_problem(6, laws=LAWS[:3])
    seen: list[tuple[int, int]] = []
    size_design(design, progress=lambda done, total: seen.append((done, total)), workers=2)
    assert seen == [(0, 3), (1, 3), (2, 3), (3, 3)]


def test_a_workers_user_error_reaches_the_caller():
    design = scale_problem(4, laws=("cycloidal",))
    motors = MotorArrays.of(design.motors, design.limits.envelope, design.drives)
    with pytest.raises(UserError, match="no_such_law"):
        tables_in_processes(design, ["cycloidal", "no_such_law"], motors, 2)


def test_auto_uses_every_cpu_for_large_work_only():
    assert worker_count(None, 100, 20) == 1
    assert worker_count(None, AUTO_WORK, 1) == 1  # never more processes than laws
    assert worker_count(None, AUTO_WORK, 64) == min(usable_cpus(), 64)
    assert worker_count(3, 10, 2) == 2
    assert worker_count(1, 10**9, 20) == 1


@pytest.mark.parametrize("spec", [
    *DEFAULT_LAW_SPECS, "trapezoidal(alpha=0.3)",
    data_spec_text({"kind": "cubic_spline", "points": [[0, 0], [0.5, 0.5], [1, 1]]}),
    data_spec_text({"kind": "shaped", "law": "cycloidal", "shaper": "zv", "f_T": 3.0,
                    "damping_ratio": 0.02}),
])
def test_a_law_pickles_as_its_spec(spec):
    law = make_law(spec)
    again = pickle.loads(pickle.dumps(law))
    assert again == law and again.spec == law.spec
    tau = np.linspace(0.0, 1.0, 7)
    assert np.array_equal(again.derivative(tau, 2), law.derivative(tau, 2))


def test_the_jobs_option_sizes_a_machines_axes_in_processes(monkeypatch, tmp_path):
    """``sizer size MACHINE --jobs 2``: each axis's sizing in worker processes, the output
    the one process gives (a given master speed: one sizing per axis)."""
    import sizer.sizing.engine as processes

    text = (ROOT / "examples" / "machines" / "two-axis-packer.yaml").read_text()
    text = text.replace("master_speed: minimize", "master_speed: 30 rpm")
    text = text.replace("../catalogs/", str(ROOT / "examples" / "catalogs") + "/")
    machine = tmp_path / "packer.yaml"
    machine.write_text(text)
    alone = run_cli("size", str(machine), "--all", "--format", "json", "--jobs", "1")
    pools = []
    original = processes.tables_in_processes
    monkeypatch.setattr(processes, "tables_in_processes",
                        lambda *a, **k: pools.append(a[3]) or original(*a, **k))
    spread = run_cli("size", str(machine), "--all", "--format", "json", "--jobs", "2")
    assert alone.returncode == spread.returncode == 0, spread.stderr
    assert alone.stdout == spread.stdout
    assert pools == [2, 2]  # both axes, two processes each
