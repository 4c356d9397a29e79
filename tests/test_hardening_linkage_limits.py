"""What a design through a linkage states and sizing would not check is refused, located:
the residual vibration of the load's mode is not computed through a linkage (its output
does not follow the law), so a ``limits.residual_vibration`` (or a load mode) there is a
user error at its line instead of a limit skipped in silence.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from bad_input_cases import EXAMPLES, Case, run_case


def _line_of(text: str, key: str) -> int:
    """The 1-based line of the first ``key:`` in a YAML text (an independent look-up)."""
    return next(i for i, line in enumerate(text.splitlines(), 1)
                if line.strip().startswith(f"{key}:"))


LINKAGES = ["press-slider-crank.yaml", "press-slider-crank-cycle.yaml",
            "four-bar-coupler.yaml", "four-bar-rocker-driven.yaml"]


def _with_mode(example: str, limit: bool) -> str:
    data = yaml.safe_load((EXAMPLES / example).read_text(encoding="utf-8"))
    data["load"].update(natural_frequency="25 Hz", damping_ratio=0.02)
    if limit:
        unit = "mm" if "slider" in example else "arcsec"
        data.setdefault("limits", {})["residual_vibration"] = f"0.1 {unit}"
    return yaml.safe_dump(data, sort_keys=False)


def _cases() -> list[Case]:
    cases = []
    for example in LINKAGES:
        if not (EXAMPLES / example).exists():
            continue
        with_limit = _with_mode(example, True)
        line = _line_of(with_limit, "residual_vibration")
        for command in ("size", "check", "segments"):
            cases.append(Case(f"{example}-limit-{command}", args=(command, "{design}"),
                              design=with_limit,
                              words=(f"design.yaml:{line}", "limits.residual_vibration",
                                     "not computed through a linkage")))
        mode_only = _with_mode(example, False)
        cases.append(Case(f"{example}-mode", design=mode_only,
                          words=(f"design.yaml:{_line_of(mode_only, 'natural_frequency')}",
                                 "load.natural_frequency", "not computed through a linkage")))
    return cases


@pytest.mark.parametrize("case", _cases(), ids=str)
def test_a_vibration_limit_through_a_linkage_is_refused(case: Case, tmp_path: Path) -> None:
    run_case(case, tmp_path)


def test_the_same_limit_without_a_linkage_is_checked(tmp_path: Path) -> None:
    from cli_run import run_cli

    result = run_cli("size", str(EXAMPLES / "indexing-table-vibration.yaml"), "--all",
                     "--format", "csv")
    assert result.returncode == 0, result.stderr
    assert "residual_vibration" in result.stdout.splitlines()[0]
