"""Edges of the ODE-referenced kernels (mechanism, acceleration) that random samples
of the shipped cases do not reach: each checked against single scenes."""

from __future__ import annotations

import copy
import math
import tomllib
from itertools import product

import numpy as np

from mdcalc.input.casefile import CaseText, validate
from mdcalc.input.model import DECLINED
from mdcalc.problems import PROBLEMS
from tests.conftest import CASES


def _case(name: str, relative: str, change=None):
    path = CASES / relative
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data.pop("expect", None)
    if change is not None:
        change(data)
    module = PROBLEMS[name].load()
    return module, path, data, validate(module.Case, CaseText(path, "", data))


def test_an_adhesion_only_grid_runs_vectorized_and_equals_single_scenes(monkeypatch):
    # Drawing the tyre grip alone leaves the launch's engine acceleration a plain
    # number while the grip is an array: the lesser of the two is still taken per row.
    from mdcalc import methods
    from mdcalc.runs.runner import solve_model

    module, path, data, model = _case("acceleration", "acceleration/high_power.toml")
    grip = np.array([0.8, 1.0])
    with np.errstate(all="ignore"):
        out = module.sweep(model, {"adhesion.coefficient": grip})
    assert out is not None and not out[DECLINED].any()
    monkeypatch.setattr(methods, "REFERENCE_ONLY", True)
    for i, phi in enumerate(grip.tolist()):
        point = copy.deepcopy(data)
        point["adhesion"]["coefficient"] = phi
        _, report = solve_model(
            "acceleration", module, validate(module.Case, CaseText(path, "", point)), None
        )
        results = report.results()
        for key in ("launch_acceleration", "time_to_target", "adhesion"):
            assert math.isclose(out[key][i], results[key].value, rel_tol=1e-8), key


def test_the_lecture_section_is_absent_where_742_does_not_apply():
    # A/m·U - ψ <= 0 in a gear: the single scene reports no lecture section at all,
    # its coefficients included (NaN in the kernel), while the other rows keep theirs.
    module, _, _, model = _case("acceleration", "acceleration/lecture.toml")
    with np.errstate(all="ignore"):
        out = module.sweep(model, {"lecture.traction_coefficient": np.array([1.1, 0.02])})
    assert out["lecture_traction_coefficient"][0] == 1.1
    for key in (
        "lecture_traction_coefficient",
        "lecture_shift_angular_speed",
        "lecture_total_time",
    ):
        assert math.isnan(out[key][1]), key


def test_a_mechanism_row_counts_its_evaluations_as_the_single_reference(monkeypatch):
    # The single reference keeps its dense solution: 15 evaluations a step; past the
    # explicit budget it reruns by Radau. The kernel counts the same per row (its
    # steps differ only where the error
    # estimate is at rounding level, a kink each turn here: 3371 against 3707), so a
    # row is declined (solved alone) when the single run would switch, within 10 %,
    # with or without other rows beside it.
    import importlib

    from mdcalc.problems.mechanism.reference import reference
    from mdcalc.problems.mechanism.scene import scene_of

    solve = importlib.import_module("mdcalc.problems.mechanism.solve")  # the module

    def shorter(data):
        data["motion"]["revolutions"] = 4.0

    module, path, data, model = _case("mechanism", "mechanism/crank_press.toml", shorter)
    count = reference(scene_of(model), solve.REFERENCE_RTOL, "DOP853").evaluations
    for budget, declined in ((int(0.9 * count), True), (int(1.1 * count), False)):
        monkeypatch.setattr(solve, "EXPLICIT_BUDGET", budget)
        with np.errstate(all="ignore"):
            alone = module.sweep(
                model, {"motion.steps_per_revolution": np.array([1.0])}, ["final_speed"]
            )
            beside = module.sweep(model, {"motion.steps_per_revolution": np.array([1.0, 16.0])})
        assert alone[DECLINED].tolist() == [declined], budget
        assert beside[DECLINED].tolist() == [declined, declined], budget


def test_a_block_of_tables_gives_every_row_its_single_tables_numbers_bit_for_bit():
    # PeriodicRows and two_way_rows (a row's own values) against Periodic and
    # _two_way of that row alone: the same cell, the same interpolation, at angles
    # over several turns (negative ones too) and speeds inside and beyond the table;
    # two speeds (one cell) or three; the torque table locating its angles with the
    # other table's memory of the last ones (the same angles), read in either order.
    from mdcalc.problems.mechanism.scene import Periodic, PeriodicRows, _two_way, two_way_rows

    rng = np.random.default_rng(11)
    for closing, speeds in product((True, False), ([0.0, 80.0, 200.0], [0.0, 200.0])):
        angles = sorted(rng.uniform(0.0, 2.0 * math.pi, 7).tolist())
        if closing:
            angles = [0.0, *angles, 2.0 * math.pi]
        rows = 5
        values = rng.uniform(-500.0, 500.0, (rows, len(angles), len(speeds)))
        if closing:
            values[:, -1] = values[:, 0]
        phi = rng.uniform(-20.0, 40.0, (4, rows))
        omega = rng.uniform(-50.0, 300.0, (4, rows))
        # every entry drawn (an array over the rows) but the second angle's, shared
        one_way: list = [values[:, k, 0] for k in range(len(angles))]
        one_way[1] = float(values[0, 1, 0])
        values[:, 1, 0] = values[0, 1, 0]
        two: list = [[values[:, k, j] for j in range(len(speeds))] for k in range(len(angles))]
        two[1][1] = float(values[0, 1, 1])
        values[:, 1, 1] = values[0, 1, 1]
        block = PeriodicRows(angles, one_way)
        torque, slope = two_way_rows(angles, speeds, two, share=block)
        index = np.arange(rows)
        got = block(index, phi)
        got_torque, got_slope = torque(index, phi, omega), slope(index, phi, omega)
        alone, _ = two_way_rows(angles, speeds, two)  # no memory shared
        elsewhere = phi + 1.0  # other angles after φ: located anew
        assert np.array_equal(block(index, phi), got)
        assert np.array_equal(torque(index, elsewhere, omega), alone(index, elsewhere, omega))
        assert np.array_equal(block(index, phi), got)
        assert np.array_equal(torque(index, phi.copy(), omega), got_torque)
        for r in range(rows):
            one = Periodic(angles, values[r, :, 0].tolist())
            m, c = _two_way(angles, speeds, values[r].tolist())
            for k in range(4):
                assert got[k, r] == one(float(phi[k, r]))
                assert got_torque[k, r] == m(float(phi[k, r]), float(omega[k, r]))
                assert got_slope[k, r] == c(float(phi[k, r]), float(omega[k, r]))
    shifted = PeriodicRows([a + 0.1 for a in angles[:-1]], one_way[:-1])
    shifted.share(block)  # other angles: nothing shared
    assert shifted._last is not block._last
    assert np.array_equal(
        shifted(index, phi), PeriodicRows(shifted.angles[:-1].tolist(), one_way[:-1])(index, phi)
    )


def test_a_study_of_a_tabulated_press_draws_the_tables_values(tmp_path, cli):
    # the shipped tabulated press with M at 90° and I at 120° drawn: vectorized,
    # and the sample at the case's own values gives the case's expected end speed
    import json

    text = (CASES / "mechanism" / "tabulated_press.toml").read_text(encoding="utf-8")
    expected = tomllib.loads(text)["expect"]["final_speed"]["value"]  # independent ODE
    text = text.split("[expect]")[0] + (
        "[study]\nsamples = 64\nseed = 1\nresults = ['final_speed']\n"
        "[study.inputs]\n"
        "'torque.values.3.0' = { dist = 'uniform', low = 90.0, high = 110.0 }\n"
        "'inertia.values.4' = { dist = 'uniform', low = 1.3, high = 1.5 }\n"
    )
    case = tmp_path / "press.toml"
    case.write_text(text, encoding="utf-8")
    run = cli("study", case, "--json", "--jobs", "1")
    assert run.exit_code == 0, run.stderr
    out = json.loads(run.stdout)
    assert out["how"].startswith("vectorized kernel"), out["how"]
    assert out["failed"]["samples"] == 0
    low, high = out["results"]["final_speed"]["min"], out["results"]["final_speed"]["max"]
    assert low < expected < high  # the case's own scene lies inside the spread
