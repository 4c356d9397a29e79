"""Determinism: the same input gives byte-identical CSV and JSON (issue 10).

Whatever PYTHONHASHSEED, whatever the order of the keys in the YAML mappings, of the
motors in a catalog, of the catalogs, or of the laws in the design. The catalogs below
hold twins (motors with the same ratings under other ids), so the ranking's criteria leave
real ties and only the final total order (sizer.sizing.ranking.TIES: motor id, law spec,
ratio) decides them.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml
from cli_run import run_cli

from sizer.sizing.ranking import TIES_TEXT

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"

TWINS = [  # (id, inertia, tau_c, tau_p, v_n): b2 and b1 are twins, so are a9 and a10
    ("b2", 1e-3, 8.0, 20.0, 10.0),
    ("a9", 2e-3, 14.0, 30.0, 6.0),
    ("b1", 1e-3, 8.0, 20.0, 10.0),
    ("c0", 5e-4, 4.0, 8.0, 12.0),
    ("a10", 2e-3, 14.0, 30.0, 6.0),
]
LAWS = ["cycloidal", "harmonic", "poly5", "trapezoidal(alpha=1/3)",
        "double_s(alpha=1/3, beta=1/4)"]


def catalog_text(motors: list[tuple[str, float, float, float, float]], name: str) -> str:
    rows = [{"id": i, "inertia": j, "continuous_torque": c, "peak_torque": p,
             "rated_speed": v} for i, j, c, p, v in motors]
    return yaml.safe_dump({"catalog": name, "motors": rows}, sort_keys=False)


def design_data(mode: str) -> dict[str, Any]:
    """ex6_1-6_2 (a given duration) or ex6_3 (minimize), on the twin catalogs."""
    base = "ex6_1-6_2.yaml" if mode == "duration" else "ex6_3.yaml"
    data = yaml.safe_load((EXAMPLES / "book" / base).read_text(encoding="utf-8"))
    data["laws"] = list(LAWS)
    data["motors"] = ["one.yaml", "two.yaml"]
    data["load"]["friction"] = "0.5 N*m"  # not purely inertial: the search, not eq. 6.2
    del data["check"]
    return data


def reversed_keys(value: Any) -> Any:
    """The same data with every mapping's keys in reverse order (lists kept)."""
    if isinstance(value, dict):
        return {k: reversed_keys(value[k]) for k in reversed(list(value))}
    if isinstance(value, list):
        return [reversed_keys(v) for v in value]
    return value


def write(folder: Path, data: dict[str, Any], motors: list | None = None,
          name: str = "design.yaml") -> Path:
    motors = TWINS if motors is None else motors
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "one.yaml").write_text(catalog_text(motors[:3], "one"), encoding="utf-8")
    (folder / "two.yaml").write_text(catalog_text(motors[3:], "two"), encoding="utf-8")
    path = folder / name
    path.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    return path


def outputs(design: Path, *extra: str) -> dict[str, str]:
    """CSV and JSON of ``size --all``, run in this process."""
    out = {}
    for fmt in ("csv", "json"):
        result = run_cli("size", str(design), "--all", "-f", fmt, *extra)
        assert result.returncode in (0, 1), result.stderr
        out[fmt] = result.stdout
    return out


def ranked_pairs(json_text: str) -> list[tuple[str, str]]:
    return [(r["motor"], r["spec"]) for r in json.loads(json_text)["results"]]


@pytest.mark.parametrize("mode", ["duration", "minimize"])
def test_key_order_of_the_yaml_does_not_change_the_output(mode: str, tmp_path: Path) -> None:
    data = design_data(mode)
    first = outputs(write(tmp_path / "a", data))
    second = outputs(write(tmp_path / "b", reversed_keys(data)))
    assert list(reversed_keys(data)) != list(data)  # the keys really were reordered
    assert first == second


@pytest.mark.parametrize("mode", ["duration", "minimize"])
def test_motor_catalog_and_law_order_do_not_change_the_ranking(mode: str,
                                                               tmp_path: Path) -> None:
    data = design_data(mode)
    reference = outputs(write(tmp_path / "ref", data))
    # the motors permuted inside and across the two catalogs
    permuted = outputs(write(tmp_path / "perm", data, motors=TWINS[::-1]))
    # the catalogs listed in the other order
    swapped_data = {**data, "motors": data["motors"][::-1]}
    swapped = outputs(write(tmp_path / "swap", swapped_data))
    for other in (permuted, swapped):
        assert other["csv"] == reference["csv"]
        assert json.loads(other["json"])["results"] == json.loads(reference["json"])["results"]
    # the laws in another order: the same ranking (only the echo of the design differs)
    laws_data = {**data, "laws": LAWS[::-1]}
    laws = outputs(write(tmp_path / "laws", laws_data))
    assert laws["csv"] == reference["csv"]
    assert json.loads(laws["json"])["results"] == json.loads(reference["json"])["results"]


def test_catalogs_given_with_catalog_options_in_another_order(tmp_path: Path) -> None:
    data = {**design_data("duration"), "motors": []}
    design = write(tmp_path, data)
    one, two = str(tmp_path / "one.yaml"), str(tmp_path / "two.yaml")
    forward = outputs(design, "-c", one, "-c", two)
    backward = outputs(design, "-c", two, "-c", one)
    assert forward["csv"] == backward["csv"]
    assert json.loads(forward["json"])["results"] == json.loads(backward["json"])["results"]


def test_ties_are_broken_by_the_motor_id_then_the_law(tmp_path: Path) -> None:
    """Twins tie on every criterion of the rule: the id decides (a10 < a9 as text)."""
    out = outputs(write(tmp_path, design_data("duration")))
    pairs = ranked_pairs(out["json"])
    for first, second in (("a10", "a9"), ("b1", "b2")):
        specs = [s for m, s in pairs if m == first]
        assert len(specs) == len(LAWS)
        for spec in specs:
            assert pairs.index((first, spec)) == pairs.index((second, spec)) - 1
    assert TIES_TEXT == "motor id, law spec, ratio"


def test_the_rank_by_help_names_the_final_tie_break() -> None:
    from sizer.cli.size_command import RANK_HELP

    assert TIES_TEXT in RANK_HELP


def _run_with_seed(seed: str, *args: str) -> str:
    env = {**os.environ, "PYTHONHASHSEED": seed}
    result = subprocess.run([sys.executable, "-m", "sizer", *args], capture_output=True,
                            text=True, env=env, cwd=ROOT, timeout=120, check=False)
    assert result.returncode in (0, 1), result.stderr
    return result.stdout


def test_hash_seed_does_not_change_the_output(tmp_path: Path) -> None:
    design = str(write(tmp_path, design_data("minimize")))
    for fmt, seeds in (("json", ("0", "4242")), ("csv", ("1", "97"))):
        texts = {_run_with_seed(seed, "size", design, "--all", "-f", fmt) for seed in seeds}
        assert len(texts) == 1, fmt
