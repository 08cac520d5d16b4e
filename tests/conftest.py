"""Shared helpers: run the CLI in-process (fast) or as a real console script."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from hypothesis import settings
from typer.testing import CliRunner

# CI (.ci/run) draws hypothesis' examples from each test's own fixed seed, so a red run
# is repeatable and never a roll of the dice; a developer's run explores new ones.
settings.register_profile("ci", derandomize=True, database=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "cases"
MDCALC = Path(sys.executable).parent / "mdcalc"


class ConsoleScript:
    """The console script (:func:`mdcalc.cli.launch.main`: a plain problem run past typer,
    the rest through it) in the shape typer's CliRunner invokes."""

    name = "mdcalc"

    def main(self, args: Any = (), prog_name: str = "mdcalc", **extra: Any) -> None:
        from mdcalc.cli.launch import main

        saved = sys.argv
        sys.argv = [prog_name, *args]
        try:
            main()
        finally:
            sys.argv = saved


@pytest.fixture
def cli(monkeypatch):
    """Invoke the console script in-process, as a user's command line reaches it;
    returns click's Result (exit_code, stdout, stderr)."""
    import typer.testing

    from mdcalc.cli.app import app

    monkeypatch.setattr(typer.testing, "_get_command", lambda _: ConsoleScript())
    runner = CliRunner()

    def invoke(*args: str):
        return runner.invoke(app, [str(a) for a in args])

    return invoke


def run_script(*args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess:
    """Run the installed console script, as a user would."""
    return subprocess.run(
        [str(MDCALC), *map(str, args)], capture_output=True, text=True, env=env, timeout=120
    )


@pytest.fixture
def write_case(tmp_path: Path):
    def write(text: str, name: str = "case.toml") -> Path:
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path

    return write


# ------------------------------------------- checks of output shared by the physics tests


def assert_no_traceback(result) -> None:
    assert "Traceback" not in (result.stderr or "")
    assert "internal error" not in (result.stderr or "")
    assert result.exception is None or isinstance(result.exception, SystemExit)


def strict_json(text: str) -> Any:
    """json.loads that refuses NaN / Infinity tokens."""

    def refuse(token: str) -> Any:
        raise AssertionError(f"non-finite number {token} in JSON")

    return json.loads(text, parse_constant=refuse)


#: Shipped scenes made shorter where a test compares two ways of computing them, not
#: their numbers: the crank press's block ODE costs ~4 s a call over 40 revolutions.
SHORTER = {
    "crank_press.toml": {"motion": {"revolutions": 8.0}},
    "tabulated_press.toml": {"motion": {"revolutions": 5.0}},
}


def shorter(path: Path, data: dict[str, Any]) -> dict[str, Any]:
    """``data`` (a case file's table, its [expect] dropped) made shorter per SHORTER."""
    data = {**data, **{k: {**data[k], **v} for k, v in SHORTER.get(path.name, {}).items()}}
    if path.name in SHORTER:
        data.pop("expect", None)  # for the whole run
    return data


def comparable_json(document: dict) -> dict:
    """A case's JSON without what differs between two runs of it: run times, and the
    case's name (a file's path, ``<string>``, ``<dict>``)."""
    text = json.dumps({k: v for k, v in document.items() if k != "case"}, sort_keys=True)
    masked = json.loads(text)
    for section in masked["sections"]:
        for row in section.get("rows", []):
            if isinstance(row, dict) and "seconds" in row:
                row["seconds"] = None
    return masked


def walk_finite(node: Any, where: str = "$") -> None:
    if isinstance(node, float):
        assert math.isfinite(node), where
    elif isinstance(node, dict):
        for key, value in node.items():
            walk_finite(value, f"{where}.{key}")
    elif isinstance(node, list):
        for index, value in enumerate(node):
            walk_finite(value, f"{where}[{index}]")


# ------------------------------------------------ the charts of --plot (tests/test_charts_*)


def solved(path: Path) -> tuple[Any, Any, list[Any]]:
    """A case file's solver result, report and charts."""
    from mdcalc.input.casefile import read_case
    from mdcalc.runs.runner import solve_text

    run = solve_text(read_case(path))
    return run.result, run.report, run.module.charts(run.result)


def chart(charts: list[Any], word: str) -> Any:
    """The one chart whose title holds ``word``."""
    found = [c for c in charts if word in c.title]
    assert len(found) == 1, [c.title for c in charts]
    return found[0]


def series(c: Any, start: str) -> tuple[Any, Any]:
    """x and y (numpy arrays) of the one series of chart ``c`` labelled ``start...``."""
    import numpy as np

    found = [s for s in c.series if s.label.startswith(start)]
    assert len(found) == 1, [s.label for s in c.series]
    return np.asarray(found[0].x, dtype=float), np.asarray(found[0].y, dtype=float)


#: A study of seed 002's mine hoist (point by point, the ODE rows off): rope stiffness
#: ±15 %, load torque triangular (tests/test_study.py, tests/test_cluster.py).
MINE_STUDY = """\
problem = "mine-hoist"
[hoist]
drum_inertia = 479.15e3
sheave_inertia = 27.97e3
cage_inertia = 156.86e3
chord_stiffness = 18609.2e3
rope_stiffness = 893.45e3
[loads]
drive_torque = 1.0e6
load_torque = 5.0e5
[analysis]
ode = false
[study]
samples = {samples}
seed = {seed}
results = ["mu12_first_swing", "mu23_first_swing"]
[study.inputs]
"hoist.rope_stiffness" = {{ nominal = 893.45e3, tol = "±15 %" }}
"loads.load_torque" = {{ dist = "triangular", low = 4.0e5, mode = 5.0e5, high = 5.5e5 }}
"""
