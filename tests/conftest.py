"""Shared helpers: run the CLI in-process (fast) or as a real console script."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "cases"
MDCALC = Path(sys.executable).parent / "mdcalc"


@pytest.fixture
def cli():
    """Invoke the typer app in-process; returns click's Result (exit_code, stdout, stderr)."""
    from mdcalc.cli import app

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
