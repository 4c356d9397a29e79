"""The shape of the package (issue 33): no import circle among sizer's modules, counting
the imports inside functions; the core imports no surface; the file schema apart from the
SI domain; sizer/sizing in a few modules. Read from the source with ast, nothing imported."""

from __future__ import annotations

import ast
import functools
from collections.abc import Iterator
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "sizer"
CORE = ("laws", "mechanics", "sizing", "vibration", "energy", "thermal", "envelope",
        "numerics", "model", "export")
"""Packages of the core: pure numpy, no printing, files, CLI or plotting."""
SURFACE = ("sizer.cli", "sizer.report", "typer", "rich", "matplotlib", "click")
MAX_SIZING_MODULES = 20


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def _runtime_nodes(tree: ast.AST) -> Iterator[ast.AST]:
    """The nodes of ``tree`` outside the bodies of ``if TYPE_CHECKING:`` (their ``else:``
    included): one walk, not a walk to mark the skipped nodes and a second to read them."""
    stack = [tree]
    while stack:
        node = stack.pop()
        yield node
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            stack.append(node.test)
            stack.extend(node.orelse)
        else:
            stack.extend(ast.iter_child_nodes(node))


@functools.cache
def _runtime_imports(path: Path, name: str) -> frozenset[str]:
    """Every module named by an import that runs (in a function too; not under
    ``if TYPE_CHECKING:``). Cached: the circle test and the core tests read the same files."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    names: set[str] = set()
    for node in _runtime_nodes(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            names.add(module)
            names.update(f"{module}.{alias.name}" for alias in node.names)
    return frozenset(names)


def _own(module: str) -> str | None:
    """The sizer module an imported name belongs to (a name inside a module: the module)."""
    while module and module not in MODULES:
        module = module.rpartition(".")[0]
    return module or None


def _graph() -> dict[str, set[str]]:
    graph: dict[str, set[str]] = {}
    for name, path in MODULES.items():
        targets = {_own(m) for m in _runtime_imports(path, name) if m.startswith("sizer")}
        edges = {t for t in targets if t is not None and t != name}
        # importing a.b.c runs the packages a and a.b first
        for target in list(edges):
            parts = target.split(".")
            edges.update(".".join(parts[:i]) for i in range(1, len(parts))
                         if not name.startswith(".".join(parts[:i]) + ".")
                         and ".".join(parts[:i]) != name)
        graph[name] = edges
    return graph


def _circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    top = stack.pop()
                    on_stack.discard(top)
                    component.append(top)
                    if top == node:
                        break
                if len(component) > 1:
                    found.append(sorted(component))
    return found


def test_the_circle_finder_finds_a_circle():
    """The finder itself: a -> b -> c -> a is one circle, d on its own is none."""
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set()}
    assert _circles(graph) == [["a", "b", "c"]]


def test_no_import_circle_among_sizer_modules():
    circles = _circles(_graph())
    assert not circles, "import circles:\n" + "\n".join(" ".join(c) for c in circles)


@pytest.mark.parametrize("package", CORE)
def test_the_core_imports_no_surface(package):
    """sizer's core is pure numpy: no CLI, report, terminal or plotting import."""
    bad = []
    for name, path in MODULES.items():
        if not name.startswith(f"sizer.{package}"):
            continue
        for imported in _runtime_imports(path, name):
            if imported.startswith(SURFACE):
                bad.append(f"{name} imports {imported}")
    assert not bad, "\n".join(bad)


def test_sizing_is_a_few_modules():
    """sizer/sizing in at most MAX_SIZING_MODULES modules (issue 33), each named by the
    question it answers."""
    modules = sorted(p.stem for p in (PACKAGE / "sizing").glob("*.py") if p.stem != "__init__")
    assert len(modules) <= MAX_SIZING_MODULES, modules
