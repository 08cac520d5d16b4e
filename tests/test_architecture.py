"""The shape of the code: no import circle, no module too long to read, problems
laid out as the registry's docstring says."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from mdcalc.problems import PROBLEMS

PACKAGE = Path(__file__).resolve().parent.parent / "mdcalc"
#: A module longer than this is split into a package whose files show its parts.
MAX_LINES = 700


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def modules() -> dict[str, Path]:
    return {module_name(path): path for path in sorted(PACKAGE.rglob("*.py"))}


def imports_of(name: str, path: Path, known: set[str]) -> set[str]:
    """The mdcalc modules ``path`` imports anywhere in it (module level or inside a
    function: a deferred import closes a circle just the same), TYPE_CHECKING
    blocks excepted (they never run)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    skipped: set[int] = set()
    for node in ast.walk(tree):
        test = node.test if isinstance(node, ast.If) else None
        if test is not None and "TYPE_CHECKING" in ast.unparse(test):
            skipped.update(id(inner) for inner in ast.walk(node) if inner is not node)
    found: set[str] = set()
    for node in ast.walk(tree):
        if id(node) in skipped:
            continue
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*anchor, base] if base else anchor)
            for alias in node.names:
                child = f"{base}.{alias.name}"
                found.add(child if child in known else base)
    return {module for module in found if module in known and module != name}


def import_graph() -> dict[str, set[str]]:
    known = modules()
    return {name: imports_of(name, path, set(known)) for name, path in known.items()}


def find_circle(graph: dict[str, set[str]]) -> list[str] | None:
    """A circle of imports, or None (depth-first search, colouring nodes)."""
    state: dict[str, int] = {}  # 1 on the current path, 2 done
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for target in sorted(graph[node]):
            if state.get(target) == 1:
                return [*path[path.index(target) :], target]
            if target not in state and (circle := visit(target)) is not None:
                return circle
        path.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state and (circle := visit(node)) is not None:
            return circle
    return None


def test_the_import_graph_has_no_circle():
    assert find_circle(import_graph()) is None, " -> ".join(find_circle(import_graph()) or [])


def test_the_circle_finder_finds_a_circle():
    # The guard above can fail: a deferred import back is a circle.
    graph = import_graph()
    graph["mdcalc.pool"] = graph["mdcalc.pool"] | {"mdcalc.check"}
    circle = find_circle(graph)
    assert circle is not None and circle[0] == circle[-1], circle
    assert {"mdcalc.check", "mdcalc.pool"} <= set(circle), circle


def test_deferred_and_relative_imports_are_seen(tmp_path):
    source = tmp_path / "mdcalc" / "problems" / "demo" / "report.py"
    source.parent.mkdir(parents=True)
    source.write_text(
        "from typing import TYPE_CHECKING\n"
        "from .case import Case\n"
        "if TYPE_CHECKING:\n"
        "    from mdcalc.plot import Chart\n"
        "def f():\n"
        "    from mdcalc import methods\n",
        encoding="utf-8",
    )
    known = {"mdcalc.problems.demo.case", "mdcalc.methods", "mdcalc.plot", "mdcalc"}
    assert imports_of("mdcalc.problems.demo.report", source, known) == {
        "mdcalc.problems.demo.case",
        "mdcalc.methods",
    }


@pytest.mark.parametrize("name", sorted(modules()))
def test_no_module_is_too_long_to_read(name):
    lines = len(modules()[name].read_text(encoding="utf-8").splitlines())
    assert lines <= MAX_LINES, f"{name}: {lines} lines; split it into a package of its parts"


@pytest.mark.parametrize("name", sorted(PROBLEMS))
def test_every_problem_shows_the_registry_face(name):
    module = PROBLEMS[name].load()
    for attribute in ("Case", "solve", "report", "template"):
        assert callable(getattr(module, attribute, None)), f"{name} lacks {attribute}"
    if hasattr(module, "__path__"):  # a package: its face is all it exports
        assert set(module.__all__) >= {"Case", "solve", "report", "template"}
