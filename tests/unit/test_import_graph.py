"""The package's import graph has no cycle and follows the layer order.

The graph is built from the source with ``ast``: every ``import`` and ``from
... import`` statement, at module level and inside functions or classes, of
every module under ``src/hollowbody``. Nodes are the top-level subpackages and
modules (``model``, ``solver``, ``errors``, ...), with ``io.keyword`` and
``io.results`` as nodes of their own. Imports inside one node are not edges, nor
are imports of the root package itself (``from hollowbody import tissues`` is an
edge to ``tissues``); the root ``__init__`` must import nothing, so importing
one layer never drags in another.
"""

from __future__ import annotations

import ast
from collections.abc import Iterable, Mapping
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"
PACKAGE = "hollowbody"

#: Layers from the bottom up: a node may import only nodes of earlier entries (the
#: nodes of one entry do not import each other unless listed in SIBLING_EDGES).
LAYERS: list[tuple[str, ...]] = [
    ("errors", "units", "source", "tissues"),
    ("mesh",),
    ("model",),
    ("io.keyword", "io.results"),
    ("build",),
    ("materials",),
    ("elements", "contact"),
    ("solver",),
    # engines: the hand-off to OpenRadioss / LS-DYNA reads decks (io.keyword, build) and
    # writes the solver's history columns; it sits beside api (neither imports the other)
    # so that scenarios, calibration and the command line can run on any engine.
    ("api", "engines"),
    ("hollow", "curves", "rating"),
    ("scenarios", "body"),
    ("calibrate", "validation"),
    ("report",),
    ("cli", "testing"),
    ("__main__",),
]
#: Allowed imports between nodes of the same layer.
SIBLING_EDGES: set[tuple[str, str]] = set()


def node_of(module: str) -> str | None:
    """Graph node of a dotted module name (None outside the package)."""
    parts = module.split(".")
    if parts[0] != PACKAGE:
        return None
    if len(parts) == 1:
        return PACKAGE
    if parts[1] == "io" and len(parts) > 2:
        return f"io.{parts[2]}"
    return parts[1]


def _module_name(path: Path, root: Path) -> tuple[str, str]:
    """(dotted module name, dotted package the module's relative imports start from)."""
    rel = path.relative_to(root).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
        return ".".join(parts), ".".join(parts)
    return ".".join(parts), ".".join(parts[:-1])


def _is_module(dotted: str, root: Path) -> bool:
    p = root.joinpath(*dotted.split("."))
    return p.with_suffix(".py").is_file() or (p / "__init__.py").is_file()


def imported_modules(tree: ast.AST, package: str, root: Path) -> Iterable[str]:
    """Dotted names of the modules every import statement of ``tree`` refers to."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            yield target
            for alias in node.names:  # ``from pkg import module``
                if _is_module(f"{target}.{alias.name}", root):
                    yield f"{target}.{alias.name}"


def import_graph(root: Path, package: str = PACKAGE) -> dict[str, dict[str, set[str]]]:
    """node -> {imported node -> set of importing files} for the package under ``root``."""
    graph: dict[str, dict[str, set[str]]] = {}
    for path in sorted((root / package).rglob("*.py")):
        module, pkg = _module_name(path, root)
        src = node_of(module)
        graph.setdefault(src, {})
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for target in imported_modules(tree, pkg, root):
            dst = node_of(target)
            if dst is not None and dst != src and dst != PACKAGE:
                graph[src].setdefault(dst, set()).add(str(path.relative_to(root)))
    return graph


def find_cycle(edges: Mapping[str, Iterable[str]]) -> list[str] | None:
    """One cycle of the directed graph as [a, b, ..., a], or None (depth-first search)."""
    colour: dict[str, int] = {}  # 1 on the current path, 2 done
    stack: list[str] = []

    def visit(n: str) -> list[str] | None:
        colour[n] = 1
        stack.append(n)
        for m in sorted(edges.get(n, ())):
            if colour.get(m) == 1:
                return stack[stack.index(m):] + [m]
            if m not in colour:
                found = visit(m)
                if found:
                    return found
        stack.pop()
        colour[n] = 2
        return None

    for n in sorted(edges):
        if n not in colour:
            found = visit(n)
            if found:
                return found
    return None


def cycle_message(graph: Mapping[str, Mapping[str, set[str]]], cycle: list[str]) -> str:
    steps = [f"{a} -> {b} (in {', '.join(sorted(graph[a][b]))})"
             for a, b in zip(cycle, cycle[1:])]
    return "import cycle " + " -> ".join(cycle) + ":\n  " + "\n  ".join(steps)


def layer_violations(graph: Mapping[str, Mapping[str, set[str]]]) -> list[str]:
    """Edges that go up or sideways in :data:`LAYERS` (and nodes no layer names)."""
    rank = {n: i for i, layer in enumerate(LAYERS) for n in layer}
    out = [f"{PACKAGE} (root __init__) -> {b}" for b in sorted(graph.get(PACKAGE, {}))]
    for a, targets in sorted(graph.items()):
        if a == PACKAGE:
            continue
        for b, files in sorted(targets.items()):
            if a not in rank or b not in rank:
                out.append(f"{a} -> {b}: node not in LAYERS")
            elif rank[b] >= rank[a] and (a, b) not in SIBLING_EDGES:
                out.append(f"{a} -> {b} (in {', '.join(sorted(files))})")
    return out


def test_find_cycle_detects_a_synthetic_cycle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": {"c"}, "d": {"a", "c"}}) is None
    assert find_cycle({"a": {"a"}}) == ["a", "a"]


def _write(root: Path, rel: str, text: str) -> None:
    p = root / rel
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text)


def test_graph_of_a_temporary_package_finds_function_level_and_relative_cycles(tmp_path):
    _write(tmp_path, f"{PACKAGE}/__init__.py", "")
    _write(tmp_path, f"{PACKAGE}/model/__init__.py", "")
    _write(tmp_path, f"{PACKAGE}/model/thing.py",
           "def f():\n    from hollowbody.io.keyword import reader\n")
    _write(tmp_path, f"{PACKAGE}/io/__init__.py", "")
    _write(tmp_path, f"{PACKAGE}/io/keyword/__init__.py", "")
    _write(tmp_path, f"{PACKAGE}/io/keyword/reader.py", "from ...model import thing\n")
    _write(tmp_path, f"{PACKAGE}/io/results/__init__.py", "from hollowbody import model\n")
    graph = import_graph(tmp_path)
    assert set(graph["model"]) == {"io.keyword"}
    assert set(graph["io.keyword"]) == {"model"}
    assert set(graph["io.results"]) == {"model"}
    cycle = find_cycle({a: set(b) for a, b in graph.items()})
    assert cycle is not None and set(cycle) == {"model", "io.keyword"}
    msg = cycle_message(graph, cycle)
    assert "hollowbody/model/thing.py" in msg and "hollowbody/io/keyword/reader.py" in msg
    assert layer_violations(graph) == [
        "model -> io.keyword (in hollowbody/model/thing.py)"]


def test_package_import_graph_has_no_cycle():
    graph = import_graph(SRC)
    assert {"model", "io.keyword", "io.results", "solver", "build"} <= set(graph)
    cycle = find_cycle({a: set(b) for a, b in graph.items()})
    if cycle:
        pytest.fail(cycle_message(graph, cycle))


def test_package_imports_follow_the_layers():
    graph = import_graph(SRC)
    bad = layer_violations(graph)
    assert not bad, "imports against the layer order:\n  " + "\n  ".join(bad)
