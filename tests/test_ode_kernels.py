"""Edges of the ODE-referenced kernels (mechanism, acceleration) that random samples
of the shipped cases do not reach: each checked against single scenes."""

from __future__ import annotations

import copy
import math
import tomllib
from itertools import product

import numpy as np
import pytest

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


def _against_single_scenes(data: dict, grid: dict[str, list[float]]) -> dict:
    """The mechanism kernel on ``grid`` over the case ``data``, each row against its
    single scene (every numeric result, within the ODE reference's tolerance); the
    kernel's answer."""
    from mdcalc.runs.runner import solve_model
    from tests.test_sweep_kernels import tolerance

    module = PROBLEMS["mechanism"].load()
    path = CASES / "mechanism" / "fuzz.toml"  # a name for messages only
    model = validate(module.Case, CaseText(path, "", data))
    size = len(next(iter(grid.values())))
    with np.errstate(all="ignore"):
        out = module.sweep(model, {k: np.array(v, dtype=float) for k, v in grid.items()})
    assert out is not None and not np.any(out.pop(DECLINED, False))
    for row in range(size):
        point = copy.deepcopy(data)
        for key, values in grid.items():
            section, name = key.split(".")
            point[section][name] = values[row]
        _, report = solve_model(
            "mechanism", module, validate(module.Case, CaseText(path, "", point)), None
        )
        assert report.status == "ok", report.message
        for key, q in report.results().items():
            if not isinstance(q.value, float) or key not in out:
                continue
            rel, tol = tolerance(module, key, 1e-9)
            got = float(np.broadcast_to(out[key], (size,))[row])
            assert got == pytest.approx(q.value, rel=rel, abs=tol), (key, row)
    return out


#: A one-way torque table whose zero crossings make two humps of ω per turn.
HUMPS = {
    "problem": "mechanism",
    "title": "two humps",
    "torque": {
        "angles_deg": [-75.648, -64.149, -9.276, 6.377, 147.862, 163.369],
        "values": [-31.677474689146482, 108.82379556263867, 38.06299309917377,
                   -64.80247732933884, 112.15153011526489, -70.26879376637808],
    },  # fmt: skip
    "inertia": {"value": 2.0370541040696937},
    "motion": {"start_speed": 111.58297629414109, "revolutions": 9.227088222361369,
               "steps_per_revolution": 21, "start_angle": 0.1792708704449225},
}  # fmt: skip


def test_an_extreme_just_past_the_end_of_its_step_is_found():
    # The slowest sample of the last turn was a step's last, and the minimum lay in
    # the next step, farther than the best step's own spacing of samples but nearer
    # than the next step's: golden section on the best step's spacing stopped at its
    # edge, 3.6e-7 above the minimum (the unevenness 8.3e-5 off) at 095f1b9.
    _against_single_scenes(HUMPS, {"motion.start_speed": [111.58297629414109, 105.0, 118.0]})


def test_an_extreme_between_samples_of_a_long_step_is_found():
    # Steps as long as a table's pieces (here half a turn: two angles a turn) sampled
    # at nine points each passed over a broad hump of ω 6e-5 above the value at the
    # last turn's start; samples as close as the single scene's grid find it.
    data = {
        "problem": "mechanism",
        "title": "a broad hump",
        "torque": {
            "angles_deg": [0.0, 180.0, 360.0],
            "speeds": [0.0, 169.71522407387226],
            "values": [[108.03563621092486, -634.8630512917571],
                       [164.15358262849745, -383.85333488134864],
                       [108.03563621092486, -634.8630512917571]],
        },  # fmt: skip
        "inertia": {"value": 2.636032160324569},
        "motion": {"start_speed": 38.70391288112007, "revolutions": 4.772457591488289,
                   "steps_per_revolution": 12, "start_angle": 1.0344322925353877},
    }  # fmt: skip
    _against_single_scenes(data, {"motion.start_speed": [38.70391288112007, 36.0, 41.0]})


@pytest.mark.parametrize(
    "speeds, inertia, motion",
    [
        # a one-way table, a constant inertia, a start between knots
        (None, {"value": 1.7}, {"start_speed": 60.0, "start_angle": 0.4}),
        # three speed columns (a kink of M in ω), I's table on other angles, from rest
        ([0.0, 60.0, 150.0], {"angles_deg": [0, 45, 200, 360], "values": [2.0, 2.6, 1.5, 2.0]},
         {"start_speed": 0.0, "start_angle": 0.0}),
        # two columns, I's table on the torque's angles, a negative start angle
        ([0.0, 200.0], {"angles_deg": [0, 90, 180, 270, 360], "values": [2.4, 1.6, 1.9, 2.3, 2.4]},
         {"start_speed": 80.0, "start_angle": -2.5}),
    ],
)  # fmt: skip
def test_table_pieces_agree_with_single_scenes(speeds, inertia, motion):
    # The kernel steps from knot to knot of the tables with each piece's lines of I
    # and M, going on with the step the last piece proposed; the single scene
    # restarts its DOP853 at every knot. Rows differ in start speed, start angle
    # (pieces cut at other places) and revolutions (other last pieces).
    angles = [0.0, 30.0, 75.0, 120.0, 190.0, 250.0, 300.0, 360.0]
    shape = [300.0, 180.0, 90.0, 140.0, 260.0, 330.0, 310.0, 300.0]
    if speeds is None:
        torque = {"angles_deg": angles, "values": [v - 200.0 for v in shape]}
    else:
        values = [[v - 2.0 * s for s in speeds] for v in shape]
        torque = {"angles_deg": angles, "speeds": speeds, "values": values}
    data = {
        "problem": "mechanism",
        "title": "tables",
        "torque": torque,
        "inertia": inertia,
        "motion": {**motion, "revolutions": 6.0, "steps_per_revolution": 12},
    }
    start, angle = motion["start_speed"], motion["start_angle"]
    _against_single_scenes(
        data,
        {
            "motion.start_speed": [start, start + 3.0, start + 7.0] if start else [0.0, 0.0, 0.0],
            "motion.start_angle": [angle, angle + 0.013, angle - 0.29],
            "motion.revolutions": [6.0, 5.61, 6.37],
        },
    )


def test_a_best_sample_at_a_steps_end_is_refined_over_the_neighbours_spacing():
    # The extreme may lie in the neighbouring step, beyond the best step's spacing of
    # samples but nearer than the neighbour's: golden section must reach that far.
    from mdcalc.core.block_ode import Dense
    from mdcalc.problems.mechanism.extremes import Best, Last

    def step(t_old: float, h: float) -> Dense:
        return Dense(np.array([t_old]), np.array([h]), np.zeros((1, 1)), np.zeros((7, 1, 1)))

    rows = np.array([0])
    for index, count in ((8, 8), (0, 8), (3, 8)):
        best, last = Best(1, 1.0), Last(1)
        last.put(rows, step(0.0, 0.4), np.array([0.05]))  # the step before: spacing 0.05
        here = step(0.4, 0.16)
        best.offer(rows, np.array([1.0]), np.array([0.4 + 0.02 * index]), np.array([index]),
                   np.array([count]), np.array([0.02]), here, last)  # fmt: skip
        last.put(rows, here, np.array([0.02]))
        best.fill_next(rows, step(0.56, 0.8), np.array([0.1]))  # the step after: 0.1
        below = 0.05 if index == 0 else 0.02
        above = 0.1 if index == count else 0.02
        assert (best.below[0], best.above[0]) == (below, above), index


@pytest.mark.parametrize("cells", [2**22, 400])
def test_the_steps_that_cannot_hold_an_extreme_are_not_sampled(monkeypatch, cells):
    # The last turn's steps are kept and sampled at its end only where ω between a
    # step's ends may, by the curvature's bound, pass the best of all the steps' ends
    # (or, past KEPT_CELLS, in parts, by the best ends seen so far). Every number is
    # the same, bit for bit, as with every step sampled (a bound of infinity), and
    # far fewer steps are sampled on the tabulated press.
    from mdcalc.problems.mechanism import extremes

    monkeypatch.setattr(extremes, "KEPT_CELLS", cells)

    module, _, data, model = _case("mechanism", "mechanism/tabulated_press.toml")
    grid = {
        "motion.start_speed": np.linspace(60.0, 100.0, 9),
        "motion.revolutions": np.linspace(3.0, 4.5, 9),
    }
    sampled = []
    real = extremes.Extremes._sample

    def counted(self, step, chosen):
        sampled.append(chosen.size)
        return real(self, step, chosen)

    monkeypatch.setattr(extremes.Extremes, "_sample", counted)
    with np.errstate(all="ignore"):
        pruned = module.sweep(model, grid)
    few = sum(sampled)
    kept = extremes._Step
    monkeypatch.setattr(
        extremes, "_Step", lambda *fields: kept(*fields[:-1], np.full_like(fields[-1], np.inf))
    )
    sampled.clear()
    with np.errstate(all="ignore"):
        every = module.sweep(model, grid)
    assert not pruned[DECLINED].any()
    for key, value in every.items():
        assert np.array_equal(np.asarray(value), np.asarray(pruned[key]), equal_nan=True), key
    assert few < (0.4 if cells > 10**6 else 0.8) * sum(sampled), (few, sum(sampled))


def test_the_samples_between_coarse_ones_are_taken_only_where_they_may_pass_them(
    monkeypatch,
):
    # A step is sampled at every COARSE_STRIDE-th point first, then between two of
    # them only where the curvature's bound lets ω pass their best: every number is
    # the same, bit for bit, as with every sample taken (a stride of 1), on the
    # tabulated press and on the review's scenes with humps of ω (formulas of I
    # without a bound among them), and the press takes far fewer samples.
    from mdcalc.problems.mechanism import extremes

    module = PROBLEMS["mechanism"].load()
    cells: list[int] = []
    real = extremes.Extremes._speeds

    def counted(self, step, r, dense, low, high, width, count, index):
        cells.append(index.size)
        return real(self, step, r, dense, low, high, width, count, index)

    monkeypatch.setattr(extremes.Extremes, "_speeds", counted)
    _, _, press, _ = _case("mechanism", "mechanism/tabulated_press.toml")
    scenes = [(press, {"motion.start_speed": np.linspace(60.0, 100.0, 7),
                       "motion.revolutions": np.linspace(3.0, 4.5, 7)})]  # fmt: skip
    scenes += list(_balanced_scenes(5, 8))
    strides = (1, 3, extremes.COARSE_STRIDE)
    press_cells = {}
    for number, (data, grid) in enumerate(scenes):
        model = validate(module.Case, CaseText(CASES / "x.toml", "", data))
        out = {}
        for stride in strides:
            monkeypatch.setattr(extremes, "COARSE_STRIDE", stride)
            cells.clear()
            with np.errstate(all="ignore"):
                out[stride] = module.sweep(model, grid)
            if number == 0:
                press_cells[stride] = sum(cells)
        for stride in strides[1:]:
            for key, value in out[1].items():
                same = np.array_equal(
                    np.asarray(value), np.asarray(out[stride][key]), equal_nan=True
                )
                assert same, (number, stride, key)
    assert press_cells[strides[-1]] < 0.4 * press_cells[1], press_cells


def test_a_best_sample_between_coarse_ones_far_from_their_best_is_found(monkeypatch):
    # E/I over a step of 64 samples (I = 1) with two humps: 1.0 at sample 48, a
    # coarse one (every 8th), and 1.001 at sample 20, between coarse samples of 0.99.
    # Only the curvature's bound over a stride brings the span from 16 to 24 in
    # (its ends alone would leave it out), and sample 20 is the best, as with every
    # sample taken.
    from types import SimpleNamespace

    from mdcalc.core.block_ode import Dense
    from mdcalc.problems.mechanism import extremes
    from mdcalc.problems.mechanism.pieces import Piece

    powers = np.arange(8)
    points = [(0.3125, 1.001), (0.25, 0.99), (0.375, 0.99), (0.75, 1.0), (0.0, 0.9), (1.0, 0.9)]
    rows = [x**powers for x, _ in points] + [powers * x ** np.maximum(powers - 1, 0)
                                               for x in (0.3125, 0.75)]  # fmt: skip
    c = np.linalg.solve(np.array(rows), [v for _, v in points] + [0.0, 0.0])
    x = np.linspace(0.0, 1.0, 65)
    assert np.argmax(np.polyval(c[::-1], x)) == 20 and np.argmax(np.polyval(c[::-1], x[::8])) == 6

    def extension(terms):
        return Dense(np.zeros(1), np.ones(1), np.array([[c[0]]]), np.reshape(terms, (7, 1, 1)))

    basis = np.stack([extension(np.eye(7)[j]).at(x[:, None], 0)[:, 0] - c[0] for j in range(7)], 1)
    terms = np.linalg.lstsq(basis, np.polyval(c[::-1], x) - c[0], rcond=None)[0]
    dense = extension(terms)
    one, nothing = np.ones(1), np.zeros(1)
    piece = Piece(nothing, nothing, (one, nothing), (nothing, nothing), None)
    reach = extremes._curvature(dense, one, nothing) / 8.0
    step = extremes._Step(np.array([0]), dense, piece, nothing, one, np.array([64]), None, reach)
    kept = extremes.Extremes.__new__(extremes.Extremes)
    kept.start, kept.base = np.array([-1.0]), SimpleNamespace(start_speed=nothing)
    kept.formulas, kept.best = None, {1.0: None, -1.0: None}
    found = kept._sample(step, np.array([0]))
    monkeypatch.setattr(extremes, "COARSE_STRIDE", 1)
    every = kept._sample(step, np.array([0]))
    assert found[1.0][1][0] == every[1.0][1][0] == 20
    for sign in (1.0, -1.0):
        assert found[sign][0][0] == every[sign][0][0] and found[sign][1][0] == every[sign][1][0]


def _every_step_in_turn(self):
    """The kernel's sampling before the steps were kept: each step of the last turn
    sampled whole as it came, then offered, then put as the last one."""
    for step in self.steps:
        r = step.rows
        width = (step.high - step.low) / step.count
        found = self._sample(step, np.arange(r.size))
        for sign, best in self.best.items():
            value, where = found[sign]
            angle = np.where(where == step.count, step.high, step.low + width * where)
            best.fill_next(r, step.dense, width)
            best.offer(r, value, angle, where, step.count, width, step.dense, self.last)
        self.last.put(r, step.dense, width)
    self.steps, self.kept = [], 0


def _balanced_scenes(seed: int, count: int):
    """A review's adversarial scenes: torque that nearly balances over a turn (a
    periodic regime with humps of ω), as a table of φ, of φ and ω, or a formula;
    I constant, a table or a formula; 12 rows each from near rest to fast, over
    whole and fractional turns, some from a drawn start angle."""
    rng = np.random.default_rng(seed)
    for _ in range(count):
        knots = int(rng.choice([3, 4, 5, 7, 9, 13]))
        angles = np.linspace(0, 360, knots).round(6).tolist()
        kind = rng.integers(0, 6)
        m = rng.normal(size=knots) * 10 ** rng.uniform(0, 3)
        m[-1] = m[0]
        m -= np.mean(m[:-1]) * rng.uniform(0.9, 1.0)
        data: dict = {"problem": "mechanism", "title": "balanced"}
        inertia = 10 ** rng.uniform(-1, 1)
        if kind in (0, 1, 2):
            data["torque"] = {"angles_deg": angles, "values": m.tolist()}
        elif kind == 3:
            slope = -abs(rng.normal()) * 10 ** rng.uniform(-1, 1)
            data["torque"] = {"angles_deg": angles, "speeds": [0.0, 200.0],
                              "values": [[v, v + 200 * slope] for v in m]}  # fmt: skip
        else:
            a = rng.normal(size=3) * 10 ** rng.uniform(0, 3)
            data["torque"] = {"formula": f"{a[0]:.6g}*sin(phi) + {a[1]:.6g}*sin(3*phi)**3"
                                         f" + {a[2]:.6g}*cos(2*phi)**5"}  # fmt: skip
        if kind in (0, 3):
            values = inertia * (1 + 0.8 * rng.uniform(-1, 1, knots))
            values[-1] = values[0]
            data["inertia"] = {"angles_deg": angles, "values": values.tolist()}
        elif kind == 5 and rng.random() < 0.5:
            data["inertia"] = {"formula": f"{inertia:.6g}*(1 + 0.3*cos(phi))"}
        else:
            data["inertia"] = {"value": inertia}
        data["motion"] = {"start_speed": 10.0, "revolutions": 2.0, "steps_per_revolution": 8}
        rows = 12
        grid = {
            "motion.start_speed": 10 ** rng.uniform(-0.5, 2.5, rows) * (rng.random(rows) > 0.15),
            "motion.revolutions": rng.choice([1.0, 1.0, 1.5, 2.0, 2.37, 3.0, 5.0], rows)
            + rng.choice([0, 1e-9], rows),
        }
        if rng.random() < 0.4:
            grid["motion.start_angle"] = rng.uniform(-3, 3, rows)
        yield data, grid


def test_the_kept_steps_give_what_sampling_each_step_as_it_came_gives(monkeypatch):
    # against the loop the kernel ran before the steps were kept (above): every
    # number bit for bit, where the best's neighbours, spacings and samples decide
    # them. Two of the review's 60 scenes where leaving out the step after the best
    # (fill_next) changed a number (a formula of M and I; a table of M with a drawn
    # start angle): fractional turns, rows from rest
    from mdcalc.problems.mechanism import extremes

    module = PROBLEMS["mechanism"].load()
    for index, (data, grid) in enumerate(_balanced_scenes(1, 57)):
        if index not in (44, 56):
            continue
        model = validate(module.Case, CaseText(CASES / "x.toml", "", data))
        with np.errstate(all="ignore"):
            kept = module.sweep(model, grid)
            with monkeypatch.context() as patch:
                patch.setattr(extremes.Extremes, "_replay", _every_step_in_turn)
                each = module.sweep(model, grid)
        for key, value in each.items():
            same = np.array_equal(np.asarray(value), np.asarray(kept[key]), equal_nan=True)
            assert same, (index, key)


def test_the_golden_search_reads_the_neighbouring_step_beyond_the_best_ones_ends():
    from mdcalc.core.block_ode import Dense
    from mdcalc.problems.mechanism.extremes import Best

    def step(t_old: float, h: float, level: float) -> Dense:
        return Dense(np.array([t_old]), np.array([h]), np.full((1, 1), level), np.zeros((7, 1, 1)))

    best = Best(1, 1.0)
    rows = np.array([0])
    best.pieces = {"previous": step(0.0, 1.0, 1.0), "best": step(1.0, 1.0, 2.0),
                   "next": step(2.0, 1.0, 3.0)}  # fmt: skip
    extension = best.around(rows)
    for angle, level in ((0.5, 1.0), (1.0, 2.0), (1.5, 2.0), (2.0, 2.0), (2.5, 3.0)):
        assert extension(np.array([angle])).at(np.array([angle]), 0)[0] == level, angle
    best.pieces["next"].h[0] = np.nan  # no step after the best (a stale one is cleared)
    assert best.around(rows)(np.array([2.5])).at(np.array([2.5]), 0)[0] == 2.0


def test_a_hump_of_speed_inside_a_step_below_the_best_end_is_the_maximum():
    # M of φ alone, I = 1: E = E₀ + ∫M dφ is exactly quadratic over each 45° piece,
    # which DOP853 takes in one step. Between 45° and 90° M falls from 94 to -91
    # N·m: E humps 18.7 J above its ends there, higher than every knot's E, though
    # both ends lie below the knot at 180° (E₀ + 18.06 J). At 100 rad/s and more
    # each piece is one step, sampled by its curvature's bound (its ends alone
    # would leave it out: 100.18 rad/s against 100.27). By hand: the hump
    # at M = 0, E₀ + 8.247 + 94·(π/4)(94/185)/2 J (ΣM over a turn is 0: E₀ each turn).
    module = PROBLEMS["mechanism"].load()
    values = [-73.0, 94.0, -91.0, 50.0, 13.0, -77.0, 23.0, 61.0, -73.0]
    data = {
        "problem": "mechanism",
        "title": "a hump inside a piece",
        "torque": {"angles_deg": list(range(0, 361, 45)), "values": values},
        "inertia": {"value": 1.0},
        "motion": {"start_speed": 100.0, "revolutions": 3.0, "steps_per_revolution": 8},
    }
    model = validate(module.Case, CaseText(CASES / "x.toml", "", data))
    speeds = np.array([100.0, 110.0])
    with np.errstate(all="ignore"):
        out = module.sweep(model, {"motion.start_speed": speeds})
    quarter = math.pi / 4
    at_45 = (-73.0 + 94.0) / 2 * quarter
    hump = at_45 + 94.0 * quarter * (94.0 / 185.0) / 2
    expected = np.sqrt(2.0 * (0.5 * speeds**2 + hump))
    assert not out[DECLINED].any()
    assert np.allclose(out["max_speed"], expected, rtol=1e-10, atol=0.0), (
        out["max_speed"] - expected
    )


def test_the_curvature_bound_holds_on_random_extensions():
    # The sampling of a step rests on |d²(E/I)/dx²| <= _curvature(...): checked
    # against second differences on a fine grid of random extensions and lines of I.
    from mdcalc.core.block_ode import Dense
    from mdcalc.problems.mechanism.extremes import _curvature

    rng = np.random.default_rng(7)
    m = 400
    dense = Dense(
        np.zeros(m),
        rng.uniform(0.01, 3.0, m),
        rng.uniform(1.0, 100.0, (m, 1)),
        rng.standard_normal((7, m, 1)) * rng.uniform(0.01, 10.0, (1, m, 1)),
    )
    inertia = rng.uniform(0.5, 3.0, m)
    slope = rng.uniform(-0.4, 0.4, m) * inertia / dense.h  # I stays above 0.6·I
    bound = _curvature(dense, inertia, slope)
    x = np.linspace(0.0, 1.0, 4001)[:, None]
    u = dense.at(x * dense.h, 0) / (inertia + slope * x * dense.h)
    second = np.abs(np.diff(u, 2, axis=0)) / (x[1, 0] - x[0, 0]) ** 2
    assert np.all(second.max(axis=0) <= bound)
    assert np.median(second.max(axis=0) / bound) > 0.2  # a bound, not a wild one (0.48)


def test_a_spike_of_speed_at_a_dip_of_inertia_is_the_maximum():
    # I dips to 1.2 between two knots 0.01° on either side of 180°: ω spikes there,
    # narrower than the single scene's grid of 2048 a turn, which stepped over it
    # (54.06 rad/s reported against 66.09 at 095f1b9). Each table knot of the last
    # turn is now a candidate. With M a table of φ alone, E = E₀ + ∫M dφ exactly
    # (M piecewise linear: its integral is the trapezoids'), so ω at the dip, the
    # maximum, is √(2E/1.2) by hand.
    data = {
        "problem": "mechanism",
        "title": "a dip of I",
        "torque": {"angles_deg": [0, 120, 240, 360], "values": [30.0, -20.0, 10.0, 30.0]},
        "inertia": {
            "angles_deg": [0, 90, 179.99, 180, 180.01, 270, 360],
            "values": [2.0, 2.2, 2.0, 1.2, 2.0, 1.8, 2.0],
        },
        "motion": {"start_speed": 50.0, "revolutions": 3.0, "steps_per_revolution": 12,
                   "start_angle": 0.3},
    }  # fmt: skip
    phi = np.concatenate([[0.3], np.radians(np.arange(120, 901, 120)), [5 * math.pi]])
    torque = np.interp(np.degrees(phi) % 360, [0, 120, 240, 360], [30.0, -20.0, 10.0, 30.0])
    energy = 0.5 * (2.0 + 0.2 * math.degrees(0.3) / 90) * 50.0**2 + np.trapezoid(torque, phi)
    peak = math.sqrt(2.0 * energy / 1.2)
    out = _against_single_scenes(data, {"motion.start_speed": [50.0]})
    assert out["max_speed"][0] == pytest.approx(peak, rel=1e-9)


def test_a_row_across_its_knots_leaves_the_others_on_their_lines(monkeypatch):
    # A row with more knots than MAX_SEGMENTS runs across them with the formulas'
    # right-hand side (as the single scene does); it sent its whole block there,
    # so a row's bits depended on its block-mates. Now each row keeps its own way.
    from mdcalc.problems.mechanism import reference

    monkeypatch.setattr(reference, "MAX_SEGMENTS", 100)
    module, _, data, model = _case("mechanism", "mechanism/tabulated_press.toml")
    data["motion"]["revolutions"] = 3.0  # 36 knots; 10 revolutions: 120
    model = validate(module.Case, CaseText(CASES / "x.toml", "", data))
    with np.errstate(all="ignore"):
        alone = module.sweep(model, {"motion.revolutions": np.array([3.0])})
        both = module.sweep(model, {"motion.revolutions": np.array([3.0, 10.0])})
    for key, value in alone.items():
        assert np.array_equal(np.broadcast_to(value, (1,)), np.broadcast_to(both[key], (2,))[:1],
                              equal_nan=True), key  # fmt: skip
    _against_single_scenes(data, {"motion.revolutions": [10.0]})


def test_an_inertia_of_zero_at_a_knot_is_declined():
    # ω is infinite there (1/ω = 0: no NaN to stop the run), and the single scene's
    # validation refuses the value: the kernel leaves the row to it.
    module = PROBLEMS["mechanism"].load()
    data = {
        "problem": "mechanism",
        "title": "M of φ alone",
        "torque": {"angles_deg": [0, 90, 180, 270, 360], "values": [50.0, 80.0, -20.0, 10.0, 50.0]},
        "inertia": {"angles_deg": [0, 90, 180, 270, 360], "values": [2.0, 1.5, 1.0, 2.5, 2.0]},
        "motion": {"start_speed": 60.0, "revolutions": 3.3, "steps_per_revolution": 12},
    }
    model = validate(module.Case, CaseText(CASES / "x.toml", "", data))
    drawn = {"inertia.values.2": np.array([1.0, 0.0, 1e-300, 1e-14])}
    with np.errstate(all="ignore"):
        out = module.sweep(model, drawn)
    # 1e-14 beside 2 is valid, but lines of I across the dip lose its digits (ω_max
    # came 4e-4 high): left to the single scene too
    assert out[DECLINED].tolist() == [False, True, True, True]
    data["torque"] = {"formula": "50 + 30*sin(phi)"}  # no lines: the same check
    model = validate(module.Case, CaseText(CASES / "x.toml", "", data))
    with np.errstate(all="ignore"):
        out = module.sweep(model, drawn)
    assert out[DECLINED].tolist() == [False, True, True, True]


def test_two_angles_of_a_table_closer_than_a_nanoradian_are_refused(cli, tmp_path):
    # A jump written as 90° and 90.0000000001° (1.75e-12 rad apart): the angles'
    # rounding over a few turns (1e-15 rad) reads part of the jump, so the knot's
    # speed came 6e-4 off. The case must give the jump a step of its own.
    text = (CASES / "mechanism" / "tabulated_press.toml").read_text(encoding="utf-8")
    old = "angles_deg = [0, 30, 60, 90, 120, 150, 180, 210, 240, 270, 300, 330, 360]\nvalues = [2.4"
    new = old.replace("90, 120", "90, 90.0000000001")  # the inertia's table (values 2.4 ...)
    assert text.count(old) == 1
    text = text.replace(old, new)
    case = tmp_path / "jump.toml"
    case.write_text(text, encoding="utf-8")
    run = cli("mechanism", case)
    assert run.exit_code == 2
    assert "inertia.angles_deg: two angles 1.75e-12 rad apart" in run.stderr
    assert "Traceback" not in run.stderr
