"""No import circles between the modules of src/crashlite (issue 32).

The test parses every module with ``ast`` (nothing is imported), builds the
module import graph -- module-level *and* function-level imports, relative
imports resolved, ``from pkg import sub`` counted as an import of the
submodule ``pkg.sub`` -- and fails on any cycle, naming each one as a chain
of modules.

A package's ``__init__`` is a node like any other (``crashlite.model`` is
``model/__init__.py``).  Python imports a submodule's parent packages
implicitly; those implicit edges are not counted, only the import statements
written in the code.
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
ROOT_PACKAGE = "crashlite"


def _module_names() -> dict[str, Path]:
    """Dotted module name -> file, for every module under src/crashlite."""
    modules: dict[str, Path] = {}
    for path in sorted((SRC / ROOT_PACKAGE).rglob("*.py")):
        parts = list(path.relative_to(SRC).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        modules[".".join(parts)] = path
    return modules


def _resolve_relative(module: str, is_package: bool, level: int, name: str | None) -> str:
    base = module.split(".")
    if not is_package:
        base = base[:-1]
    if level > 1:
        base = base[: len(base) - (level - 1)]
    return ".".join(base + ([name] if name else []))


def import_graph() -> dict[str, set[str]]:
    """module -> the crashlite modules its import statements name."""
    modules = _module_names()
    graph: dict[str, set[str]] = {name: set() for name in modules}
    for module, path in modules.items():
        is_package = path.name == "__init__.py"
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            targets: list[str] = []
            if isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = _resolve_relative(module, is_package, node.level, node.module)
                else:
                    base = node.module or ""
                for alias in node.names:
                    sub = f"{base}.{alias.name}"
                    targets.append(sub if sub in modules else base)
            for target in targets:
                # ``import a.b.c`` where only ``a.b`` is ours: the longest known prefix
                while target and target not in modules:
                    target = target.rpartition(".")[0]
                if target and target != module:
                    graph[module].add(target)
    return graph


def find_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module, each as
    one cycle through it (a chain of modules, first == last)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components: list[list[str]] = []
    counter = 0

    def strongconnect(v: str) -> None:  # Tarjan, iterative enough for ~200 modules
        nonlocal counter
        index[v] = low[v] = counter
        counter += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                strongconnect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                components.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            strongconnect(v)

    cycles = []
    for component in components:
        members = set(component)
        # shortest cycle through the component's first module (BFS back to it)
        start = component[0]
        parents: dict[str, str] = {}
        frontier = [start]
        found = None
        while frontier and found is None:
            nxt = []
            for v in frontier:
                for w in sorted(graph[v] & members):
                    if w == start:
                        found = v
                        break
                    if w not in parents:
                        parents[w] = v
                        nxt.append(w)
                if found is not None:
                    break
            frontier = nxt
        chain = [start]
        v = found
        while v is not None and v != start:
            chain.append(v)
            v = parents.get(v)
        chain = [start] + list(reversed(chain[1:])) + [start]
        cycles.append(chain if len(component) == len(chain) - 1 else chain + [f"(component: {', '.join(component)})"])
    return cycles


def test_graph_sees_the_package():
    graph = import_graph()
    assert "crashlite.keyword" in graph
    assert "crashlite.solver.setup" in graph
    # relative and absolute imports are both resolved
    assert any(edges for edges in graph.values())


def test_no_import_cycles():
    cycles = find_cycles(import_graph())
    assert not cycles, "import cycles between modules:\n" + "\n".join(" -> ".join(c) for c in cycles)
