"""A law defined by data and written as YAML text is composed under the limits of a design
file: an alias bomb in ``--law '{kind: ...}'``, in a design's laws (a mapping or a text)
or in a machine file's is refused at once, naming ``--law`` or the file, line and field,
instead of expanding (hours and gigabytes) while the canonical text is written.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from pathlib import Path

import pytest
from bad_input_cases import EXAMPLES, ROOT, Case, run_case

LEVELS = 7  # 10**7 leaves once expanded: far beyond MAX_DESIGN_NODES (2e5)


def _nodes_bomb() -> str:
    """{kind: cubic_spline, ..., a0: &a0 [0 x10], a1: &a1 [*a0 x10], ..., positions: *a6}"""
    levels = ["a0: &a0 [0,0,0,0,0,0,0,0,0,0]"] + [
        f"a{i}: &a{i} [" + ",".join([f"*a{i - 1}"] * 10) + "]" for i in range(1, LEVELS)]
    return ("{kind: cubic_spline, times: auto, " + ", ".join(levels)
            + f", positions: *a{LEVELS - 1}}}")


def _chars_bomb(length: int = 20_000, repeats: int = 2_000) -> str:
    """Few nodes, a long value repeated: 4e7 characters once written out."""
    return (f'{{kind: cubic_spline, name: &s "{"x" * length}", points: [[0, 0], [1, 1]], '
            f'extra: [{",".join(["*s"] * repeats)}]}}')


SELF = "{kind: cubic_spline, points: &p [[0, 0], *p, [1, 1]]}"


def _run_limited(*args: str) -> subprocess.CompletedProcess[str]:
    """``sizer ARGS`` in a subprocess with 2 GB of address space and 60 s: a bomb that
    expands fails the test instead of the machine."""

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))

    environment = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "sizer", *args], capture_output=True,
                          text=True, timeout=60, preexec_fn=limit, env=environment, cwd=ROOT)


@pytest.mark.parametrize("spec,words", [
    (_nodes_bomb(), ("too many YAML nodes", "alias bomb")),
    (_chars_bomb(), ("once its YAML aliases are expanded", "200,000")),
])
def test_a_bomb_in_the_law_option_is_refused_at_once(spec: str, words: tuple[str, ...]) -> None:
    result = _run_limited("laws", "--law", spec)
    assert result.returncode == 2, result.stderr[-2000:]
    (line,) = [x for x in result.stderr.splitlines() if x.startswith("error:")]
    assert line.startswith("error: --law: ")
    for word in words:
        assert word in line
    assert "Traceback" not in result.stderr


def _with_law(example: str, marker: str, law: str) -> str:
    text = (EXAMPLES / example).read_text(encoding="utf-8")
    i = text.rindex(marker)
    return text[:i] + marker.replace("cycloidal", f"cycloidal, {law}", 1) + text[i + len(marker):]


PUSHER_LAWS = "  - cycloidal\n"
PUSHER_LINE = 1 + (EXAMPLES / "pusher-via-points.yaml").read_text().splitlines().index(
    "  - cycloidal")


def _pusher(law: str) -> str:
    text = (EXAMPLES / "pusher-via-points.yaml").read_text(encoding="utf-8")
    return text.replace(PUSHER_LAWS, f"  - cycloidal\n  - {law}\n")


MACHINE_LAWS = '    laws: [cycloidal, modified_sinusoidal, "trapezoidal(alpha=1/3)"]\n'
MACHINE = EXAMPLES / "machines/two-axis-packer.yaml"
MACHINE_LINE = 1 + MACHINE.read_text().splitlines().index(MACHINE_LAWS.rstrip("\n"), 40)


def _machine(law: str) -> str:
    text = MACHINE.read_text(encoding="utf-8")
    i = text.rindex(MACHINE_LAWS)
    return text[:i] + f"    laws: [cycloidal, {law}]\n" + text[i + len(MACHINE_LAWS):]


def _quoted(spec: str) -> str:
    return '"' + spec.replace('"', '\\"') + '"'


LAW_INDEX = 4  # the pusher's laws: 4 data laws, then cycloidal, then the bomb

CASES = [
    Case("design-mapping-nodes", design=_pusher(_nodes_bomb()),
         words=(f"design.yaml:{PUSHER_LINE + 1}", f"laws[{LAW_INDEX + 1}].", "alias bomb")),
    Case("design-text-nodes", design=_pusher(_quoted(_nodes_bomb())),
         words=(f"design.yaml:{PUSHER_LINE + 1}", f"laws[{LAW_INDEX + 1}]:", "alias bomb")),
    Case("design-mapping-chars", design=_pusher(_chars_bomb()),
         words=(f"design.yaml:{PUSHER_LINE + 1}", f"laws[{LAW_INDEX + 1}]",
                "once its YAML aliases are expanded")),
    Case("design-self", design=_pusher(SELF),
         words=(f"design.yaml:{PUSHER_LINE + 1}", f"laws[{LAW_INDEX + 1}]",
                "recursive YAML alias")),
    Case("machine-mapping-nodes", design=_machine(_nodes_bomb()),
         words=(f"design.yaml:{MACHINE_LINE}", "axes[1].laws[1].", "alias bomb")),
    Case("machine-text-nodes", design=_machine(_quoted(_nodes_bomb())),
         words=(f"design.yaml:{MACHINE_LINE}", "axes[1].laws[1]:", "alias bomb")),
    Case("machine-mapping-chars", design=_machine(_chars_bomb()),
         words=(f"design.yaml:{MACHINE_LINE}", "axes[1].laws[1]",
                "once its YAML aliases are expanded")),
]


@pytest.mark.parametrize("case", CASES, ids=str)
def test_a_bomb_in_a_file_is_refused_at_its_law(case: Case, tmp_path: Path) -> None:
    run_case(case, tmp_path)


def test_a_law_that_holds_itself_is_a_user_error() -> None:
    result = _run_limited("laws", "--law", SELF)
    assert result.returncode == 2, result.stderr[-2000:]
    assert "error: --law: " in result.stderr and "recursive YAML alias" in result.stderr


def test_a_law_with_an_anchor_within_the_limits_still_reads() -> None:
    spec = "{kind: cubic_spline, times: auto, positions: &p [0, 0.2, 0.7, 1], name: ok}"
    result = _run_limited("laws", "--law", spec)
    assert result.returncode == 0, result.stderr
    assert "ok" in result.stdout
