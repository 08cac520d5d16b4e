"""The example notebook (examples/mdcalc_in_a_notebook.ipynb, issue 34.3) runs under a
real Jupyter kernel (nbclient + ipykernel), and the numbers of its last cell — a dict
shown as JSON — are those of ``mdcalc … --json`` on the same cases."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path
from typing import Any

import nbformat
import pytest
import tomli_w
from nbclient import NotebookClient

from tests.conftest import CASES, ROOT

NOTEBOOK = ROOT / "examples" / "mdcalc_in_a_notebook.ipynb"
PAYLOADS = ["5 t", "10 t", "16 t"]
HOIST_KEYS = [
    "motor_power", "static_torque", "brake_torque", "starting_torque",
    "reduced_inertia", "hanging_dynamic_factor", "ground_dynamic_factor",
]  # fmt: skip


def _executed() -> nbformat.NotebookNode:
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    for cell in notebook.cells:
        assert cell.cell_type != "code" or not cell.outputs, "store the notebook without outputs"
    client = NotebookClient(
        notebook,
        timeout=120,
        kernel_name="python3",
        resources={"metadata": {"path": str(NOTEBOOK.parent)}},
    )
    client.execute()  # a cell that raises fails the test with its traceback
    return notebook


def _summary(notebook: nbformat.NotebookNode) -> dict[str, Any]:
    """The last cell's dict, as the kernel sent it (application/json)."""
    outputs = notebook.cells[-1].outputs
    shown = [o for o in outputs if "application/json" in o.get("data", {})]
    assert len(shown) == 1, outputs
    summary: dict[str, Any] = shown[0]["data"]["application/json"]
    return summary


def _same(notebook: Any, command_line: Any, where: str) -> None:
    """Equal to 12 digits (the numbers cross the kernel's JSON), keys and all."""
    if isinstance(command_line, dict):
        assert isinstance(notebook, dict) and notebook.keys() == command_line.keys(), where
        for key in command_line:
            _same(notebook[key], command_line[key], f"{where}.{key}")
    elif isinstance(command_line, list):
        assert isinstance(notebook, list) and len(notebook) == len(command_line), where
        for index, (a, b) in enumerate(zip(notebook, command_line, strict=True)):
            _same(a, b, f"{where}[{index}]")
    elif isinstance(command_line, float) and not isinstance(notebook, bool):
        assert notebook == pytest.approx(command_line, rel=1e-12, abs=1e-300), where
    else:
        assert notebook == command_line, where


def test_the_notebook_runs_and_gives_the_command_lines_numbers(cli, tmp_path):
    """One test, so the notebook runs once (pytest-xdist spreads tests, not modules)."""
    executed = _executed()
    _every_cell_shows_something_and_the_charts_are_pictures(executed)
    summary = _summary(executed)
    _the_hoists_numbers_are_the_command_lines(summary["hoist"], cli, tmp_path)
    _the_coupling_studys_numbers_are_the_command_lines(summary["coupling_study"], cli, tmp_path)
    _the_braking_sweeps_numbers_are_the_command_lines(summary["braking_sweep"], cli, tmp_path)


def _every_cell_shows_something_and_the_charts_are_pictures(executed):
    code = [cell for cell in executed.cells if cell.cell_type == "code"]
    errors = [o for cell in code for o in cell.outputs if o.output_type == "error"]
    assert not errors
    assert all(cell.outputs for cell in code), "a code cell without output"
    kinds = [set(o.get("data", {})) for cell in code for o in cell.outputs]
    # the study's histogram and the sweep's plot drawn inline (the inline backend is
    # kept: mdcalc sets no matplotlib backend), the calculation's report as HTML
    assert sum("image/png" in k for k in kinds) == 2, kinds
    assert any("text/html" in k and "text/plain" in k for k in kinds)


def _the_hoists_numbers_are_the_command_lines(summary, cli, tmp_path):
    crane = tomllib.loads((CASES / "hoist" / "crane.toml").read_text(encoding="utf-8"))
    del crane["expect"]
    for payload in PAYLOADS:
        case = {**crane, "load": {**crane["load"], "mass": payload}}
        path = tmp_path / f"crane {payload}.toml"
        path.write_text(tomli_w.dumps(case), encoding="utf-8")
        result = cli("hoist", path, "--json")
        assert result.exit_code == 0, result.stderr
        values = json.loads(result.stdout)["results"]
        _same(summary[payload], {k: values[k]["value"] for k in HOIST_KEYS}, payload)
    # the load's weight at 16 t, by hand: 16 000 kg · g; power G·V/η in kW
    weight = 16000 * 9.80665
    eta = 0.97 * 0.97 * 0.98 * 0.97
    assert summary["16 t"]["motor_power"] == pytest.approx(weight * 0.2 / eta / 1e3, rel=1e-9)


def _the_coupling_studys_numbers_are_the_command_lines(summary, cli, tmp_path):
    study = tomllib.loads((CASES / "studies" / "coupling_scatter.toml").read_text("utf-8"))
    study["study"]["samples"] = 20_000  # as the notebook asks (seed 81, the file's)
    path = tmp_path / "coupling.toml"
    path.write_text(tomli_w.dumps(study), encoding="utf-8")
    result = cli("study", path, "--json")
    assert result.exit_code == 0, result.stderr
    document = json.loads(result.stdout)
    assert document["samples"] == 20_000
    _same(summary["statistics"], document["results"], "statistics")
    _same(summary["limits"], [limit["probability"] for limit in document["limits"]], "limits")
    _same(summary["sobol"], document["sensitivity"]["indices"], "sobol")


def _the_braking_sweeps_numbers_are_the_command_lines(summary, cli, tmp_path):
    out = tmp_path / "sweep.json"
    result = cli(
        "sweep", CASES / "braking" / "dry.toml",
        "--vary", "vehicle.initial_speed_kmh=20:140:13",
        "--result", "stopping_distance", "--result", "stopping_time", "--out", out,
    )  # fmt: skip
    assert result.exit_code == 0, result.stderr
    _same(summary, json.loads(out.read_text(encoding="utf-8"))["values"], "sweep")
    assert summary["vehicle.initial_speed_kmh"] == [20.0 + 10.0 * i for i in range(13)]


def test_the_notebook_names_no_path_outside_the_repository():
    """It reads ../cases from examples/ and writes nothing."""
    text = Path(NOTEBOOK).read_text(encoding="utf-8")
    assert "/work" not in text and "/tmp" not in text and "savefig" not in text
