"""The CLI on mutated example designs and catalogs: a clean answer every time (issue 10).

The cases and the invariants are those of ``tests/fuzz_cases.py`` (see its docstring); the seed
is fixed and the count modest (SIZER_FUZZ_EXAMPLES raises it). ``tools/fuzz_inputs.py`` runs
the same generator at 10,000 cases.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import pytest
from fuzz_cases import (
    BASES,
    NEW_KIND_BASES,
    FuzzInput,
    base_input,
    fuzz_inputs,
    option_inputs,
    run_input,
)
from hypothesis import HealthCheck, Phase, given, settings

COUNT = int(os.environ.get("SIZER_FUZZ_EXAMPLES", "0")) or None
FUZZ = dict(deadline=None, derandomize=True, database=None,
            phases=(Phase.explicit, Phase.generate),  # no shrinking: each run is a CLI call
            suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much,
                                   HealthCheck.data_too_large])
DESIGNS = [b for b in BASES if b.target == "design.yaml"]
CATALOGS = [b for b in BASES if b.target != "design.yaml"]


def _assert_clean(case: FuzzInput) -> None:
    with tempfile.TemporaryDirectory(prefix="sizer-fuzz-") as folder:
        outcome = run_input(case, Path(folder))
    assert not outcome.failures, (
        f"{case.describe()}\nfailures: {outcome.failures}\nexit code {outcome.returncode}, "
        f"{outcome.seconds:.2f} s\nstdout:\n{outcome.stdout[-1500:]}\n"
        f"stderr:\n{outcome.stderr[-3000:]}\nfiles:\n{case.files}")


@pytest.mark.parametrize("base", BASES + NEW_KIND_BASES, ids=lambda b: b.name)
def test_the_unmutated_bases_answer_cleanly(base):
    """The generator starts from valid inputs: each base's first two commands, unmutated
    (their speed is measured by tools/fuzz_inputs.py, not asserted here)."""
    for args in base.commands[:2]:
        case = base_input(base, args)
        with tempfile.TemporaryDirectory(prefix="sizer-fuzz-") as folder:
            outcome = run_input(case, Path(folder))
        assert outcome.returncode in (0, 1) and not outcome.failures, (args, outcome)


@settings(max_examples=COUNT or 70, **FUZZ)
@given(fuzz_inputs(DESIGNS))
def test_mutated_designs_answer_cleanly(case):
    _assert_clean(case)


@settings(max_examples=COUNT or 50, **FUZZ)
@given(fuzz_inputs(CATALOGS))
def test_mutated_catalogs_answer_cleanly(case):
    _assert_clean(case)


@settings(max_examples=COUNT or 60, **FUZZ)
@given(fuzz_inputs(NEW_KIND_BASES))
def test_mutated_cycles_linkages_data_laws_machines_and_drives_answer_cleanly(case):
    """The input kinds of issues 12-31 (issue 32): cycles, linkages, data laws and cam
    tables, vibration limits, machines and drive catalogs, through size, check, segments,
    vibration and law."""
    _assert_clean(case)


@settings(max_examples=COUNT or 40, **FUZZ)
@given(option_inputs())
def test_mutated_options_of_the_law_commands_answer_cleanly(case):
    """spectrum, law and laws with extreme, mis-united, glued or nasty option values."""
    _assert_clean(case)
