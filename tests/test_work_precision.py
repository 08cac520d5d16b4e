"""Work-precision diagrams (issue 35): every ODE method of a scene run with each of
scipy's integrators over a ladder of tolerances, its error against the scene's exact
or high-accuracy reference, its run time and its right-hand-side evaluations."""

from __future__ import annotations

import json
import math
import time

import pytest

import mdcalc
from mdcalc import methods
from mdcalc.core import ode
from tests.conftest import CASES, strict_json, walk_finite

#: One scene of every problem with ODE methods (the quick one where there are several).
SCENES = {
    "hoist": "hoist/crane.toml",
    "acceleration": "acceleration/lecture.toml",
    "braking": "braking/drag.toml",
    "coupling": "coupling/example_8_1.toml",
    "mine-hoist": "mine-hoist/balanced.toml",
    "variator": "variator/drive_undamped.toml",
    "mechanism": "mechanism/linear_torque.toml",
    "resonance": "resonance/mathieu_undamped.toml",
}
COLUMNS = ["method", "family", "rtol", "error", "run time", "evaluations", "status"]


def ladders(calc) -> list[dict]:
    """The work-precision tables of a calculation's JSON, each row a dict."""
    out = []
    for section in calc.to_dict()["sections"]:
        if section.get("key", "").startswith("work_precision."):
            labels = [c["label"] for c in section["columns"]]
            assert labels == COLUMNS
            out.append(
                {**section, "rows": [dict(zip(labels, r, strict=True)) for r in section["rows"]]}
            )
    return out


def rungs(table: dict, method: str) -> list[dict]:
    return [r for r in table["rows"] if r["method"] == method]


@pytest.fixture
def short_ladder(monkeypatch):
    """Five rungs (1e-3, 1e-5 ... 1e-11): the ladder's shape at a third of its cost,
    every rung run whatever the machine's speed (no time allotment)."""
    monkeypatch.setattr(methods, "LADDER_RTOLS", (1e-3, 1e-5, 1e-7, 1e-9, 1e-11))
    monkeypatch.setattr(methods, "LADDER_SECONDS", math.inf)


def test_a_smooth_scene_with_an_exact_reference_converges_with_every_integrator(short_ladder):
    # Example 8.1's step: the reference is the exact 1 + exp(-πζ/√(1-ζ²)), not an ODE
    calc = mdcalc.solve(
        CASES / "coupling" / "example_8_1.toml", time_limit=None, work_precision=True
    )
    (table,) = ladders(calc)
    assert table["key"] == "work_precision.step"
    assert "exact 1 + exp" in table["title"]
    for solver in ode.SOLVERS:
        ladder = rungs(table, solver)
        assert [r["rtol"] for r in ladder] == list(methods.LADDER_RTOLS)
        assert all(r["status"] == "ok" for r in ladder), ladder
        assert all(isinstance(r["evaluations"], int) and r["evaluations"] > 0 for r in ladder)
        best = math.inf
        for r in ladder:
            # within 100 times its tolerance (not stiff), and no worse than 10 times
            # the best of the looser rungs until it is down to 1e-12 of the reference
            assert r["error"] <= 100.0 * r["rtol"], (solver, r)
            assert r["error"] <= max(10.0 * best, 1e-12), (solver, r)
            best = min(best, r["error"])
        assert best < 1e-9, (solver, best)
        # a tighter tolerance costs more evaluations
        counts = [r["evaluations"] for r in ladder]
        assert counts[-1] > counts[0], (solver, counts)
    (lecture,) = [r for r in table["rows"] if r["family"] == "single"]
    # the lecture's reading 1 + e^(-p·τ/4) = 1 + e^(-ψ/4) against the exact factor,
    # by hand: ψ = 0.63 (p = ψ/τ), ζ = p/(2β) = ψ/(4π)
    zeta = 0.63 / (4.0 * math.pi)
    exact = 1.0 + math.exp(-math.pi * zeta / math.sqrt(1.0 - zeta * zeta))
    lecture_value = 1.0 + math.exp(-0.63 / 4.0)
    assert lecture["error"] == pytest.approx(abs(lecture_value - exact) / exact, rel=1e-9)
    assert lecture["rtol"] == lecture["evaluations"] == ""


def test_the_mine_hoists_modal_solution_is_the_reference_of_its_ladder(monkeypatch):
    monkeypatch.setattr(methods, "LADDER_RTOLS", (1e-3, 1e-5, 1e-7, 1e-9))
    monkeypatch.setattr(methods, "LADDER_SECONDS", math.inf)
    monkeypatch.setattr(ode, "SOLVERS", ("DOP853", "Radau", "LSODA"))
    path = CASES / "mine-hoist" / "balanced.toml"
    calc = mdcalc.solve(path, time_limit=None, work_precision=True)
    (table,) = ladders(calc)
    assert "modal solution, exact" in table["title"]
    for solver in ("DOP853", "Radau", "LSODA"):
        ladder = rungs(table, solver)
        assert all(r["status"] == "ok" for r in ladder), ladder
        best = math.inf
        for r in ladder:
            assert r["error"] <= 100.0 * r["rtol"], (solver, r)
            assert r["error"] <= max(10.0 * best, 1e-12), (solver, r)
            best = min(best, r["error"])
        assert best < 1e-8


def test_on_a_stiff_scene_the_implicit_methods_reach_1e_8_for_fewer_evaluations(monkeypatch):
    # ζ = 50: the fast decaying mode bounds an explicit step whatever the tolerance
    monkeypatch.setattr(methods, "LADDER_RTOLS", (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8))
    monkeypatch.setattr(methods, "LADDER_SECONDS", math.inf)
    monkeypatch.setattr(ode, "SOLVERS", ("RK45", "Radau", "BDF"))
    path = CASES / "extreme" / "coupling_heavily_damped_pulse.toml"
    (table,) = ladders(mdcalc.solve(path, time_limit=None, work_precision=True))

    def cost(solver: str) -> int:
        reached = [r["evaluations"] for r in rungs(table, solver)
                   if r["status"] == "ok" and r["error"] <= 1e-8]  # fmt: skip
        assert reached, rungs(table, solver)
        return min(reached)

    explicit = cost("RK45")
    assert cost("Radau") < explicit / 3 and cost("BDF") < explicit / 3, (
        cost("Radau"), cost("BDF"), explicit,
    )  # fmt: skip
    # RK45 is held to its stability limit: thousands of evaluations at rtol 1e-3
    assert rungs(table, "RK45")[0]["evaluations"] > 2000


def test_the_ladder_ends_by_its_budget_and_says_which_rungs_it_skipped():
    import scipy.integrate  # noqa: F401  # (its first import is no rung's)

    path = CASES / "extreme" / "coupling_heavily_damped_pulse.toml"
    plain = mdcalc.solve(path, time_limit=1.5)
    start = time.perf_counter()
    calc = mdcalc.solve(path, time_limit=1.5, work_precision=True)
    took = time.perf_counter() - start
    assert calc.status == "ok" and took < 1.5 + 2.0, took  # (reading and reporting)
    # the ladders run after the scene: its numbers are those of a run without them
    assert calc.results == plain.results
    (table,) = ladders(calc)
    spent = sum(r["run time"] for r in table["rows"] if r["family"] != "single" and r["run time"])
    assert spent < 1.5
    statuses = [r["status"] for r in table["rows"] if r["family"] != "single"]
    assert len(statuses) == len(ode.SOLVERS) * len(methods.LADDER_RTOLS)  # none dropped
    assert any(s.startswith(("skipped", "over the time budget")) for s in statuses)
    for r in table["rows"]:
        if r["status"] != "ok":
            assert r["error"] == r["run time"] == r["evaluations"] == ""


@pytest.mark.parametrize("solver", ode.SOLVERS)
@pytest.mark.parametrize("repeated", [False, True])
def test_a_rung_counts_every_evaluation_of_the_right_hand_side(solver, repeated, monkeypatch):
    # a right-hand side that counts its own calls: the finite-difference Jacobians of
    # Radau and BDF included (scipy's nfev leaves them out); one run's count, also
    # where timed() repeats a quick run (identical runs: calls a multiple of it)
    import numpy as np

    if not repeated:
        monkeypatch.setattr(methods, "MIN_TIMING_SECONDS", 0.0)  # one run

    calls = [0]

    def rhs(t, y):
        calls[0] += 1
        return np.array([y[1], -100.0 * y[0] - 0.5 * y[1]])

    def run(rtol):
        ode.advance(rhs, 0.0, np.array([1.0, 0.0]), 2.0, rtol=rtol, atol=rtol * 1e-3,
                    method="RK45")  # fmt: skip
        return {"x": 1.0}

    job = methods._Job("t", "k", ["x"], [], [], {"x": 1.0})
    rung = methods._rung(solver, solver, run, job, 1e-6)
    assert rung.status == "ok" and rung.error == 0.0
    if not repeated:
        assert rung.evaluations == calls[0]
    else:
        assert calls[0] % rung.evaluations == 0  # (a run over 2 ms is not repeated)


def test_rungs_at_an_ode_references_own_tolerance_are_not_measured(monkeypatch):
    # the acceleration's reference is DOP853 at rtol 1e-11: a rung at 1e-10 or tighter
    # would compare that computation with itself (10·1e-11 is 9.99e-11 in floats)
    monkeypatch.setattr(ode, "SOLVERS", ("DOP853",))
    calc = mdcalc.solve(CASES / "acceleration" / "lecture.toml", time_limit=None,
                        work_precision=True)  # fmt: skip
    (table,) = ladders(calc)
    status = {r["rtol"]: r["status"] for r in rungs(table, "DOP853")}
    assert [status[t] for t in (1e-10, 1e-11, 1e-12)] == [
        "not measured: the reference's own tolerance"
    ] * 3
    assert status[1e-9] == "ok"


def test_a_stand_in_reference_is_not_measured_against_itself(monkeypatch):
    # the reference (DOP853 1e-11) over its budget: RK45 at 1e-6 stands in for it
    import importlib

    acceleration = importlib.import_module("mdcalc.problems.acceleration.solve")

    real = acceleration.ode_run

    def slow_reference(scene, stints, rtol, dense=False):
        if rtol == acceleration.REFERENCE_RTOL:
            raise methods.budget.OverBudget
        return real(scene, stints, rtol, dense)

    monkeypatch.setattr(acceleration, "ode_run", slow_reference)
    monkeypatch.setattr(ode, "SOLVERS", ("RK45",))
    calc = mdcalc.solve(CASES / "acceleration" / "lecture.toml", time_limit=None,
                        work_precision=True)  # fmt: skip
    assert calc.status == "ok", calc.message  # (was a KeyError, exit 70: the tables'
    (table,) = ladders(calc)  # dense run now comes from the stand-in's tolerance)
    assert "RK45, rtol 1e-6" in table["title"]  # the stand-in
    status = {r["rtol"]: r["status"] for r in rungs(table, "RK45")}
    assert status[1e-5] == "not measured: the reference's own tolerance"
    assert status[1e-4] == "ok"


@pytest.mark.parametrize("problem", sorted(SCENES))
def test_every_problem_with_ode_methods_draws_its_diagram(problem, monkeypatch):
    monkeypatch.setattr(methods, "LADDER_RTOLS", (1e-4, 1e-7))
    monkeypatch.setattr(ode, "SOLVERS", ("RK45", "BDF"))
    calc = mdcalc.solve(CASES / SCENES[problem], work_precision=True)
    assert calc.status == "ok", calc.message
    walk_finite(strict_json(calc.to_json()))
    tables = ladders(calc)
    assert tables, "no work-precision table"
    for table in tables:
        ok = [r for r in table["rows"] if r["family"] != "single" and r["status"] == "ok"]
        assert ok, table["rows"]
        assert all(0.0 <= r["error"] < 1.0 and r["run time"] > 0.0 for r in ok)
    from mdcalc.output import precision

    charts = precision.charts(calc.run.report)
    assert len(charts) == 2 * len(tables)
    assert all(c.x_log and c.y_log and c.series for c in charts)


def test_the_diagram_reads_at_a_glance(monkeypatch):
    monkeypatch.setattr(methods, "LADDER_RTOLS", (1e-3, 1e-6, 1e-9))
    pytest.importorskip("matplotlib")
    from mdcalc.output.plot import figure_of
    from tests.test_plots import assert_reads_at_a_glance

    calc = mdcalc.solve(CASES / "coupling" / "example_8_1.toml", work_precision=True)
    from mdcalc.output import precision

    charts = precision.charts(calc.run.report)
    assert [c.title.split(":")[0] for c in charts] == [
        "Work–precision",
        "The same against right-hand-side evaluations",
    ]
    roles = {s.role for c in charts for s in c.series}
    assert roles == {"explicit", "implicit", "switching", "single"}
    assert_reads_at_a_glance(figure_of(charts, calc.to_dict()["title"]))


def test_the_command_line_writes_the_picture_json_and_report(cli, tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    monkeypatch.setattr(methods, "LADDER_RTOLS", (1e-3, 1e-6))
    case = CASES / "coupling" / "example_8_1.toml"
    picture, page = tmp_path / "wp.png", tmp_path / "wp.html"
    done = cli("coupling", case, "--work-precision", picture, "--report", page, "--json")
    assert done.exit_code == 0, done.stderr
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    document = json.loads(done.stdout)
    keys = [s.get("key") for s in document["sections"]]
    assert keys[-1] == "work_precision.step"
    html = page.read_text(encoding="utf-8")
    # the two charts inline under the table's heading, just above it
    at = html.index("<h2>Work–precision: ")
    table = html.index("<table", at)
    assert html.count("<svg", at, table) == 2
    assert "<figcaption><strong>Figure 2.</strong> Work–precision: " in html[at:table]
    assert "<figcaption><strong>Figure 3.</strong> The same against" in html[at:table]
    assert html.count("<svg", 0, at) == 1  # the scene's own chart, in its Charts


def test_bad_use_is_exit_2_and_a_scene_without_ode_rows_says_so(cli, tmp_path):
    case = CASES / "coupling" / "example_8_1.toml"
    done = cli("coupling", case, "--work-precision", tmp_path / "wp.txt")
    assert done.exit_code == 2 and "--work-precision: use a file ending .png" in done.stderr
    same = tmp_path / "x.png"
    done = cli("coupling", case, "--plot", same, "--work-precision", same)
    assert done.exit_code == 2 and "the same file as --plot" in done.stderr
    done = cli(
        "clutch", CASES / "clutch" / "one_material_065.toml", "--work-precision", tmp_path / "c.png"
    )
    assert done.exit_code == 2 and "No such option" in done.stderr
    text = (CASES / "mine-hoist" / "balanced.toml").read_text(encoding="utf-8")
    off = tmp_path / "off.toml"
    off.write_text(text + "\n[analysis]\node = false\n", encoding="utf-8")
    done = cli("mine-hoist", off, "--work-precision", tmp_path / "m.png", "--json")
    assert done.exit_code == 0, done.stderr
    assert "this scene runs no ODE method; no file written" in done.stderr
    assert not (tmp_path / "m.png").exists()
