"""The shape of the code: the layers of the package and the one way imports run
between them, no import circle, no module too long to read, problems laid out as the
registry's docstring says.

The layers, top to bottom (``ls mdcalc/`` shows them)::

    mdcalc (the package's face: no module of it imports it)
    cli          the console entry, the typer app, command bodies, terminal helpers
    api          the calculations from Python (mdcalc.solve, Calculation)
    runs         one case under its budget, pool, cluster, batch, check, sweep, study
    problems     the registry, one package or module per problem
    domain       data and case sections several problems share (no problem of its own)
    methods | input | output     one layer: the Methods machinery, case files, reports
    core         maths shared by several problems
    errors, _version             the leaves: import nothing of mdcalc

A module imports its own layer or the layers below it, never one above, and counts
every import it makes: at module level, deferred inside a function, and under
``TYPE_CHECKING`` (it never runs, but a reader of the code sees it just the same).
"""

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
    """The mdcalc modules ``path`` imports anywhere in it: at module level, inside a
    function (a deferred import closes a circle just the same) or under
    TYPE_CHECKING (a reader sees that circle too)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(tree):
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
    graph["mdcalc.runs.pool"] = graph["mdcalc.runs.pool"] | {"mdcalc.runs.check"}
    circle = find_circle(graph)
    assert circle is not None and circle[0] == circle[-1], circle
    assert {"mdcalc.runs.check", "mdcalc.runs.pool"} <= set(circle), circle


def test_deferred_and_relative_imports_are_seen(tmp_path):
    source = tmp_path / "mdcalc" / "problems" / "demo" / "report.py"
    source.parent.mkdir(parents=True)
    source.write_text(
        "from typing import TYPE_CHECKING\n"
        "from .case import Case\n"
        "if TYPE_CHECKING:\n"
        "    from mdcalc.output.plot import Chart\n"
        "def f():\n"
        "    from mdcalc import methods\n",
        encoding="utf-8",
    )
    known = {"mdcalc.problems.demo.case", "mdcalc.methods", "mdcalc.output.plot", "mdcalc"}
    assert imports_of("mdcalc.problems.demo.report", source, known) == {
        "mdcalc.problems.demo.case",
        "mdcalc.output.plot",
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


# ----------------------------------------------------------------------------- layers

#: The layers, top (0) to bottom; a module's layer is the first part of its name
#: inside mdcalc. methods, input and output are one layer (rank 4).
RANK = {
    "mdcalc": 0,
    "cli": 1,
    "api": 1.5,
    "runs": 2,
    "problems": 3,
    "domain": 3.5,
    "methods": 4,
    "input": 4,
    "output": 4,
    "core": 5,
    "errors": 6,
    "_version": 6,
}
#: The edges between the parts of the one middle layer, each that exists (a new one
#: is a decision to write down here, not an accident): methods fills the Report
#: value; calculation documents read the case file they report on; charts and
#: documents are written through the user's-files rules.
SIBLING_EDGES = {("methods", "output"), ("output", "input")}
#: What may stand loose in mdcalc/ beside the layers' folders.
LOOSE = {"__init__.py", "_version.py", "errors.py", "methods.py"}


def part(module: str) -> str:
    """The layer part of a module's name: ``mdcalc.runs.study.spec`` -> ``runs``."""
    return module.split(".")[1] if "." in module else module


def problem_of(module: str) -> str | None:
    """``mdcalc.problems.hoist.rope`` -> ``hoist``; None for the registry itself."""
    parts = module.split(".")
    return parts[2] if len(parts) > 2 and parts[1] == "problems" else None


def layer_breaches(graph: dict[str, set[str]]) -> list[str]:
    """Every import that runs against the layers: upwards, to the package's face, a
    problem into another problem, or between the middle layer's parts outside
    SIBLING_EDGES."""
    found = []
    for module, targets in sorted(graph.items()):
        for target in sorted(targets):
            a, b = part(module), part(target)
            if b == "mdcalc" or RANK[b] < RANK[a]:
                found.append(f"{module} -> {target}: {b} is above {a}")
            elif RANK[a] == RANK[b] and a != b and (a, b) not in SIBLING_EDGES:
                found.append(f"{module} -> {target}: {a} -> {b} is not in SIBLING_EDGES")
            elif a == b == "problems":
                source, goal = problem_of(module), problem_of(target)
                if source is not None and goal is None:
                    # A problem reaches the others through the registry just as well.
                    found.append(f"{module} -> {target}: a problem imports the registry")
                elif source is not None and goal != source:
                    found.append(f"{module} -> {target}: a problem imports another")
    return found


def test_every_module_has_a_layer():
    assert {part(name) for name in modules()} <= set(RANK), set(map(part, modules())) - set(RANK)


def test_imports_run_one_way_down_the_layers():
    assert layer_breaches(import_graph()) == []


def test_the_sibling_edges_written_down_are_the_ones_there():
    graph = import_graph()
    edges = {
        (part(module), part(target))
        for module, targets in graph.items()
        for target in targets
        if RANK[part(module)] == RANK[part(target)] == 4 and part(module) != part(target)
    }
    assert edges == SIBLING_EDGES


@pytest.mark.parametrize(
    ("module", "target", "says"),
    [
        ("mdcalc.runs.sweep", "mdcalc.cli.terminal", "cli is above runs"),
        ("mdcalc.core.ode", "mdcalc.methods", "methods is above core"),
        ("mdcalc.input.model", "mdcalc.problems", "problems is above input"),
        ("mdcalc.errors", "mdcalc.core.units", "core is above errors"),
        ("mdcalc.output.report", "mdcalc.methods", "output -> methods is not in SIBLING"),
        ("mdcalc.problems.braking", "mdcalc.problems.clutch", "a problem imports another"),
        ("mdcalc.problems.hoist.rope", "mdcalc.problems.mount.kernel", "a problem imports"),
        ("mdcalc.runs.runner", "mdcalc", "mdcalc is above runs"),
        ("mdcalc.problems.mount.solve", "mdcalc.problems", "a problem imports the registry"),
        ("mdcalc.domain.vehicle", "mdcalc.problems.braking", "problems is above domain"),
        ("mdcalc.domain.tables", "mdcalc.problems", "problems is above domain"),
        ("mdcalc.input.model", "mdcalc.domain.vehicle", "domain is above input"),
    ],
)
def test_a_breach_of_the_layers_is_found(module, target, says):
    # The rule above can fail: each kind of wrong import, added to the real graph.
    graph = import_graph()
    graph[module] = graph.get(module, set()) | {target}
    breaches = layer_breaches(graph)
    assert len(breaches) == 1 and says in breaches[0], breaches


def test_a_problem_may_import_what_problems_share():
    graph = import_graph()
    assert "mdcalc.domain.vehicle" in graph["mdcalc.problems.braking"]
    assert layer_breaches(graph) == []


def test_the_tree_shows_the_layers():
    loose = {p.name for p in PACKAGE.iterdir() if p.suffix == ".py"}
    folders = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").exists()}
    assert loose == LOOSE and len(loose) <= 6
    assert folders == {"cli", "api", "runs", "problems", "domain", "input", "output", "core"}


#: The __init__.py files that carry a docstring only: a package's __init__ runs on
#: the import of any module inside it, so a piped scene would pay for every sibling.
QUIET_INITS = ["cli", "runs", "input", "output", "core", "domain"]


@pytest.mark.parametrize("folder", QUIET_INITS)
def test_a_layer_init_imports_nothing(folder):
    tree = ast.parse((PACKAGE / folder / "__init__.py").read_text(encoding="utf-8"))
    # Anywhere in it: under TYPE_CHECKING or try as well.
    imported = [
        ast.unparse(n) for n in ast.walk(tree) if isinstance(n, ast.Import | ast.ImportFrom)
    ]
    assert imported == []


def test_the_package_init_imports_the_leaves_and_the_api_on_first_use():
    """The package's __init__ runs on the import of any module inside it (a piped
    scene pays for it): at its top only the leaves; the API when a name of it is
    first read (issue 34: ``import mdcalc`` loads nothing heavy, tests/test_api.py)."""
    tree = ast.parse((PACKAGE / "__init__.py").read_text(encoding="utf-8"))
    top = [ast.unparse(n) for n in tree.body if isinstance(n, ast.Import | ast.ImportFrom)]
    assert top == [
        "from __future__ import annotations",
        "from typing import TYPE_CHECKING, Any",
        "from mdcalc._version import __version__",
        "from mdcalc.errors import InputError, NoAnswer",
    ]
    deferred = {
        ast.unparse(n)
        for f in tree.body
        if isinstance(f, ast.FunctionDef)
        for n in ast.walk(f)
        if isinstance(n, ast.Import | ast.ImportFrom)
    }
    assert deferred == {"from mdcalc import api"}


def test_the_console_script_is_where_pyproject_says():
    import importlib
    import tomllib

    with (PACKAGE.parent / "pyproject.toml").open("rb") as handle:
        project = tomllib.load(handle)
    module, _, function = project["project"]["scripts"]["mdcalc"].partition(":")
    assert module == "mdcalc.cli.launch"
    assert callable(getattr(importlib.import_module(module), function))
    version = project["tool"]["setuptools"]["dynamic"]["version"]["attr"]
    assert version == "mdcalc._version.__version__"
