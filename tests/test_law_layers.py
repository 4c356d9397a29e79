"""The laws' layers point one way: pieces <- analyses <- base <- families <- registry;
a law unpickles as the very object its spec gives (its analyses computed once)."""

from __future__ import annotations

import ast
import pickle
from pathlib import Path

import pytest

from sizer.laws import make_law
from sizer.laws.data_spec import data_spec_text

LAWS = Path(__file__).resolve().parents[1] / "sizer" / "laws"

BELOW_BASE = ("pieces", "piece_table", "piece_forms", "quadrature", "coefficients", "linear_peaks")
"""The modules a law's analyses live in: they know a law only as sizer.laws.pieces.LawShape."""


def _imported(module: str) -> set[str]:
    """Every sizer module a file imports, in functions and under TYPE_CHECKING too."""
    tree = ast.parse((LAWS / f"{module}.py").read_text())
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
            names.update(f"{node.module}.{alias.name}" for alias in node.names)
    return {name for name in names if name.startswith("sizer")}


@pytest.mark.parametrize("module", BELOW_BASE)
def test_the_analyses_do_not_import_the_law_class_or_the_registry(module: str) -> None:
    above = {"sizer.laws", "sizer.laws.base", "sizer.laws.registry", "sizer.laws.data_law"}
    assert not _imported(module) & above


def test_the_base_does_not_import_the_registry_or_a_family() -> None:
    imported = _imported("base")
    assert not any(name.startswith("sizer.laws.registry") for name in imported)
    assert {name.rpartition(".")[0] or name for name in imported} <= {
        "sizer", "sizer.errors", "sizer.laws", *(f"sizer.laws.{m}" for m in BELOW_BASE)}


@pytest.mark.parametrize("spec", [
    "double_s(beta=0.25, alpha=1/3)", "poly5", "trapezoidal(alpha=0.2, alpha_d=0.3)",
    data_spec_text({"kind": "cubic_spline", "points": [[0, 0], [0.4, 0.7], [1, 1]]}),
    data_spec_text({"kind": "shaped", "law": "harmonic", "shaper": "zvd", "f_T": 4.0}),
])
def test_a_law_unpickles_as_the_cached_object(spec: str) -> None:
    law = make_law(spec)
    assert pickle.loads(pickle.dumps(law)) is law
