"""A study's kernel gives every sample the value its single scene gives.

For each problem with a vectorized kernel and each of its shipped case files, 50
random samples of every key the kernel varies (each key scattered below its value,
so the upper bounds hold; integer keys by whole steps) are solved at once by the
kernel and one by one as single scenes in this process (each Methods table's
reference alone, as a study's sample runs), and every result key the kernel
returns must equal the single scene's to 1e-9 relative (NaN where the single
scene has no number: "unbounded", or a quantity it leaves out). A scene whose single
run takes long (ODE check rows) is compared on 10 of the samples.

Problems whose kernel gives every numeric result of the report are listed in
EVERY_KEY; for them the kernel must return each numeric key the single scene has.
"""

from __future__ import annotations

import copy
import math
import time
import tomllib
from pathlib import Path

import numpy as np
import pytest

from mdcalc.input.model import DECLINED
from mdcalc.problems import PROBLEMS
from tests.conftest import CASES, shorter

# The kernel problems, their shipped cases, and a key held in a case: as the sweep test.
from tests.test_sweep_kernels import CASE_FILES, tolerance
from tests.test_sweep_kernels import _held as held

#: The problems whose kernel covers every numeric result key (issue 31, item 1).
EVERY_KEY = {"clutch", "mine-hoist", "hoist", "resonance", "variator", "mechanism", "acceleration"}
SAMPLES = 50
#: Samples of a scene whose single run takes an ODE (the crank press: 1-2 s each).
ODE_SAMPLES = 3


def expand(patterns, data: dict) -> list[str]:
    """The kernel's keys with each list index N spelt out for the lists the case has
    (at most three items of a list, its first, middle and last), and ``*`` for every
    key of a table (a mechanism's parameters)."""
    keys: list[str] = []
    for pattern in patterns:
        done = [""]
        for part in pattern.split("."):
            grown = []
            for prefix in done:
                node = data
                for step in prefix.split(".") if prefix else []:
                    node = node[int(step)] if isinstance(node, list) else node.get(step, {})
                if part == "*":  # every key of a table of named numbers
                    grown += (
                        [f"{prefix}.{k}".lstrip(".") for k in node]
                        if isinstance(node, dict)
                        else []
                    )
                elif part == "N":
                    size = len(node) if isinstance(node, list) else 0
                    picks = sorted({0, size // 2, size - 1}) if size else []
                    grown += [f"{prefix}.{i}".lstrip(".") for i in picks]
                else:
                    grown.append(f"{prefix}.{part}".lstrip("."))
            done = grown
        keys += done
    return keys


def put(data: dict, key: str, value: float) -> None:
    *path, last = key.split(".")
    node = data
    for part in path:
        node = node[int(part)] if isinstance(node, list) else node[part]
    if isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value


@pytest.mark.parametrize(("name", "path"), CASE_FILES, ids=[f"{n}:{p.name}" for n, p in CASE_FILES])
def test_kernel_equals_single_scenes_on_random_samples(name: str, path: Path, monkeypatch):
    from mdcalc import methods
    from mdcalc.errors import InputError
    from mdcalc.input.casefile import CaseText, is_integer_field, validate
    from mdcalc.runs.runner import solve_model

    module = PROBLEMS[name].load()
    data = shorter(path, tomllib.loads(path.read_text(encoding="utf-8")))
    data.pop("expect", None)
    keys = [k for k in expand(module.SWEEP_KEYS, data) if held(data, k) not in (None, 0)]
    if not keys:
        pytest.skip("the case holds no key the kernel varies")

    def valid(sample: dict) -> bool:
        try:
            validate(module.Case, CaseText(path, "", sample))
        except InputError:
            return False
        return True

    # Each key scattered below its value, or above where the value is at a lower bound;
    # a key that cannot move alone (the closing point of a table over a whole
    # revolution repeats its first) is left out.
    spans = {}
    for key in list(keys):
        lower, upper = copy.deepcopy(data), copy.deepcopy(data)
        put(lower, key, float(held(data, key) or 0.0) * 0.9)
        put(upper, key, float(held(data, key) or 0.0) * 1.1)
        if valid(lower):
            spans[key] = (0.8, 1.0)
        elif valid(upper):
            spans[key] = (1.0, 1.25)
        else:
            keys.remove(key)
    monkeypatch.setattr(methods, "MIN_TIMING_SECONDS", 2e-5)  # timings are not compared
    monkeypatch.setattr(methods, "REFERENCE_ONLY", True)  # each single scene's reference
    rng = np.random.default_rng(31)
    rows, models = [], []
    wanted, first = SAMPLES, None
    for _ in range(4 * SAMPLES):
        sample = copy.deepcopy(data)
        row = []
        for key in keys:
            value = held(data, key)
            assert value is not None
            new: float
            if is_integer_field(module.Case, tuple(key.split("."))):
                new = int(value) + int(rng.integers(0, 3)) if value < 50 else int(value)
            else:
                new = float(value) * rng.uniform(*spans[key])
            put(sample, key, new)
            row.append(float(new))
        try:  # (validated once: a mechanism's formulas take ~0.1 s to check)
            models.append(validate(module.Case, CaseText(path, "", sample)))
        except InputError:
            continue  # a sample outside a bound or a cross-field rule: not a scene
        rows.append(row)
        if first is None:  # an ODE scene (1-2 s each): 3 samples, drawn no further
            start = time.perf_counter()
            first = solve_model(name, module, models[0], None)[1]
            if time.perf_counter() - start > 0.05:
                wanted = ODE_SAMPLES
        if len(rows) == wanted:
            break
    assert len(rows) >= wanted // 2, "too few valid samples"
    grid = {key: np.array([r[j] for r in rows]) for j, key in enumerate(keys)}
    answer = module.sweep(validate(module.Case, CaseText(path, "", data)), grid)
    if answer is None:
        pytest.skip("the scene needs the point-by-point path (an ODE or a no-answer point)")
    declined = np.broadcast_to(answer.pop(DECLINED, False), len(models))

    def same(answer: dict, rows: int, index: int, report) -> None:
        """Row ``index`` of the kernel's ``answer`` (of ``rows``) against ``report``."""
        assert report.status == "ok", (index, report.message)
        numbers = {
            key: float(q.value)
            for key, q in report.results().items()
            if isinstance(q.value, int | float) and not isinstance(q.value, bool)
        }
        if name in EVERY_KEY:
            assert set(numbers) <= set(answer), set(numbers) - set(answer)
        for key, column in answer.items():
            got = float(np.broadcast_to(np.asarray(column, dtype=float), rows)[index])
            want = numbers.get(key, math.nan)
            if math.isnan(want) or math.isinf(want):
                assert math.isnan(got), (key, index, got, want)
            else:
                rel, tol = tolerance(module, key, 1e-9)
                assert got == pytest.approx(want, rel=rel, abs=tol), (key, index)

    compared = 0
    for index, model in enumerate(models):
        if declined[index]:  # left to the single scene, which solves it alone
            continue
        _, report = (None, first) if index == 0 else solve_model(name, module, model, None)
        same(answer, len(models), index, report)
        compared += 1
    # A kernel that declined every drawn sample (three of a scene near a stall may all
    # stall) compared nothing: then the case's own scene is compared, unless the
    # kernel declines it too.
    if compared == 0:
        base = validate(module.Case, CaseText(path, "", data))
        itself = module.sweep(base, {key: np.array([float(held(data, key))]) for key in keys})
        assert itself is not None
        if not bool(np.all(itself.pop(DECLINED, False))):
            same(itself, 1, 0, solve_model(name, module, base, None)[1])


@pytest.mark.parametrize(
    ("pairs", "clutch"),
    [
        ({}, {"gain": 0.0}),  # no feedback: no gain margin
        ({"driven_ratio": 1.0}, {}),  # η₂ = 1: C_max unbounded
        ({"driving_ratio": 0.8, "driven_ratio": 0.8}, {}),  # η₁ = η₂: (27) too
        ({"driving_ratio": 1.0, "driven_ratio": 1.0}, {}),  # (27) unbounded as well
        ({}, {"spring_force": None}),  # no spring force: no torques
        ({}, None),  # no [clutch] section: the pairs alone
    ],
)
def test_clutch_kernel_at_the_edges_of_its_scene(pairs, clutch):
    # The random samples above never reach these: fixed grids on each edge, the
    # kernel against single scenes, every key.
    from mdcalc.input.casefile import CaseText, validate
    from mdcalc.runs.runner import solve_model

    module = PROBLEMS["clutch"].load()
    path = CASES / "clutch" / "fig2_differentiated.toml"
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data.pop("expect", None)
    data.pop("curves", None)
    data["pairs"] |= pairs
    if clutch is None:
        data.pop("clutch")
    else:
        for key, value in clutch.items():
            if value is None:
                data["clutch"].pop(key)
            else:
                if key == "gain":  # a gain given replaces the ramp's, if any
                    data["clutch"].pop("rolling_radius", None)
                    data["clutch"].pop("ramp_angle_deg", None)
                data["clutch"][key] = value
    friction = [0.2, 0.3, 0.4]  # vary f₁: every edge above holds at each point
    grid = {"pairs.driving_friction": np.array(friction)}
    answer = module.sweep(validate(module.Case, CaseText(path, "", data)), grid)
    assert answer is not None
    for index, f1 in enumerate(friction):
        point = copy.deepcopy(data)
        point["pairs"]["driving_friction"] = f1
        _, report = solve_model(
            "clutch", module, validate(module.Case, CaseText(path, "", point)), None
        )
        numbers = {
            key: float(q.value)
            for key, q in report.results().items()
            if isinstance(q.value, int | float) and not isinstance(q.value, bool)
        }
        assert set(numbers) <= set(answer), set(numbers) - set(answer)
        for key, column in answer.items():
            got = float(np.broadcast_to(np.asarray(column, dtype=float), len(friction))[index])
            want = numbers.get(key, math.nan)
            if math.isnan(want):
                assert math.isnan(got), (key, got)
            else:
                assert got == pytest.approx(want, rel=1e-12, abs=0.0), key


def test_variator_samples_where_a_square_rounds_apart_equal_their_single_scenes(monkeypatch):
    # Python's x**2 of a float (libm pow) and numpy's of an array (x·x) differ by an
    # ulp for about one input in 1500, and the stiff three-mass model (c1/c2 = 1e6)
    # amplifies that to 1e-8. Input speeds picked where the tuned coupling's (zω)²
    # rounds apart: the kernel's numbers are each single scene's, bit for bit.
    import copy

    from mdcalc import methods
    from mdcalc.input.casefile import CaseText, validate
    from mdcalc.problems.variator.solve import drive_scene
    from mdcalc.runs.runner import solve_model

    module = PROBLEMS["variator"].load()
    path = CASES / "variator" / "antiresonance_stiff.toml"
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data.pop("expect", None)
    rng = np.random.default_rng(5)
    speeds, models = [], []
    for rpm in rng.uniform(800.0, 1000.0, 40_000).tolist():
        sample = copy.deepcopy(data)
        sample["mechanism"]["input_speed_rpm"] = rpm
        model = validate(module.Case, CaseText(path, "", sample))
        f = drive_scene(model, with_machine=False).fundamental
        if f**2 != float(np.square(np.array([f]))[0]):
            speeds.append(rpm)
            models.append(model)
        if len(speeds) == 4:
            break
    assert len(speeds) == 4
    base = validate(module.Case, CaseText(path, "", data))
    answer = module.sweep(base, {"mechanism.input_speed_rpm": np.array(speeds)})
    monkeypatch.setattr(methods, "MIN_TIMING_SECONDS", 2e-5)
    monkeypatch.setattr(methods, "REFERENCE_ONLY", True)
    for index, model in enumerate(models):
        _, report = solve_model("variator", module, model, None)
        for key, quantity in report.results().items():
            if key.startswith("antiresonance_") and isinstance(quantity.value, float):
                assert answer[key][index] == quantity.value, (key, index)


def test_variator_samples_at_and_near_critical_damping_equal_their_single_scenes(monkeypatch):
    # b = 2√(Jc) (ζ = 1: a defective first-order matrix) and next to it: the kernel takes
    # every row (none declined) and gives each single scene's numbers
    from mdcalc import methods
    from mdcalc.input.casefile import CaseText, validate
    from mdcalc.input.model import DECLINED
    from mdcalc.runs.runner import solve_model

    module = PROBLEMS["variator"].load()
    path = CASES / "variator" / "drive_critical.toml"
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data.pop("expect", None)
    dampings = [4.0, 4.0 * (1.0 + 1e-9), 4.0 * (1.0 - 1e-6), 4.0 * (1.0 + 1e-3), 2.0, 40.0]
    base = validate(module.Case, CaseText(path, "", data))
    answer = module.sweep(base, {"drive.clutch_damping": np.array(dampings)})
    assert not np.any(answer.pop(DECLINED, False))
    monkeypatch.setattr(methods, "MIN_TIMING_SECONDS", 2e-5)
    monkeypatch.setattr(methods, "REFERENCE_ONLY", True)
    for index, b in enumerate(dampings):
        sample = copy.deepcopy(data)
        sample["drive"]["clutch_damping"] = b
        _, report = solve_model(
            "variator", module, validate(module.Case, CaseText(path, "", sample)), None
        )
        assert report.status == "ok", report.message
        for key, quantity in report.results().items():
            if key.startswith("drive_") and isinstance(quantity.value, float):
                assert answer[key][index] == pytest.approx(quantity.value, rel=1e-12), (key, b)


def test_a_variator_study_that_draws_nothing_of_the_drive_solves_it_once(monkeypatch):
    # vk_variator with only the motor's overload ratio drawn: every sample's drive
    # and anti-resonance numbers are the case's own (its single scene's, bit for
    # bit), from one periodic state, not one a sample
    import importlib

    from mdcalc.input.casefile import CaseText, validate

    variator_solve = importlib.import_module("mdcalc.problems.variator.solve")
    module = PROBLEMS["variator"].load()
    path = CASES / "variator" / "vk_variator.toml"
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data.pop("expect", None)
    base = validate(module.Case, CaseText(path, "", data))
    sizes = []
    real = variator_solve.drive_block

    def spy(case, size, asked):
        sizes.append(size)
        return real(case, size, asked)

    with monkeypatch.context() as patch:
        patch.setattr(variator_solve, "drive_block", spy)
        answer = module.sweep(base, {"motor.overload_ratio": np.array([2.0, 2.5, 3.0])})
    assert sizes == [1]
    alone = module.sweep(base, {"drive.load_torque": np.array([300.0])})
    for key in ("drive_chi", "antiresonance_chi_after", "antiresonance_reduction"):
        assert answer[key].tolist() == [alone[key][0]] * 3, key
    assert len(set(answer["motor_critical_torque"].tolist())) == 3


@pytest.mark.parametrize(
    ("name", "change", "grip"),
    [
        ("high_power", {}, False),  # a table, adhesion, rear drive
        ("high_power", {"adhesion": {"drive": "front"}}, False),
        ("high_power", {}, True),  # φ drawn low: the tyres stop gears short
        ("high_power", {"adhesion": {"drive": "front"}}, True),
        ("vaz2106", {}, False),  # Leiderman's curve
        ("near_top_speed", {}, False),  # the top gear stops 0.011 % above the target
        ("steep_hill", {}, False),
    ],
)
def test_gears_proven_to_pull_up_to_the_rev_limit_are_the_ones_the_scan_finds(
    name: str, change: dict, grip: bool, monkeypatch
):
    # A gear's limit is found by scanning 256 speeds up to the rev limit for the
    # first that does not pull; the kernel skips the scan of a row where bounds
    # (least torque against the most resistance over the span) prove every speed
    # pulls. With drag, road and mass scattered widely (and adhesion, so that the
    # tyres' grip falls to the resistance), so that some gears stop short of the
    # rev limit and some rows are not proven: the kernel's every key
    # is the same, to the bit, with the proof as without it, and the proof held
    # on proven and unproven rows alike.
    from mdcalc.input.casefile import CaseText, validate
    from mdcalc.problems.acceleration import kernel

    module = PROBLEMS["acceleration"].load()
    data = tomllib.loads((CASES / "acceleration" / f"{name}.toml").read_text(encoding="utf-8"))
    data.pop("expect")
    for section, values in change.items():
        data[section].update(values)
    data.setdefault("drag", {"drag_coefficient": 0.3, "frontal_area": 2.0})
    base = validate(module.Case, CaseText(Path(f"{name}.toml"), "", data))
    rng = np.random.default_rng(11)
    n = 400
    grid = {
        "drag.drag_coefficient": data["drag"]["drag_coefficient"] * rng.uniform(0.3, 4.0, n),
        "road.resistance": rng.uniform(0.0, 0.2, n),
        "vehicle.mass": data["vehicle"]["mass"] * rng.uniform(0.7, 2.5, n),
    }
    if grip:
        grid["adhesion.coefficient"] = rng.uniform(0.05, 0.6, n)
    proven: list[int] = []
    unproven: list[int] = []
    bound = kernel._pulls_throughout

    def counting(*args):
        out = bound(*args)
        proven.append(int(np.sum(out)))
        unproven.append(int(np.sum(~out)))
        return out

    monkeypatch.setattr(kernel, "_pulls_throughout", counting)
    fast = module.sweep(base, grid)
    monkeypatch.setattr(kernel, "_pulls_throughout", lambda s, g, v, top: np.zeros(v.shape, bool))
    slow = module.sweep(base, grid)
    assert fast is not None and slow is not None and fast.keys() == slow.keys()
    for key in fast:
        assert np.array_equal(fast[key], slow[key], equal_nan=True), key
    assert sum(proven) > 0 and sum(unproven) > 0, (proven, unproven)


def test_acceleration_kernel_draws_a_torque_table_and_its_rev_limit(monkeypatch):
    # A study may draw a torque table's values and the rev limit over it: each row
    # then has its own table, its own peak-torque launch speed and maximum-power
    # shift speed. The kernel against single scenes (their reference alone) on 12
    # samples; and, independently of mdcalc, the launch speed is the table's
    # highest point and the shift speed the maximum of M·ω on a fine grid.
    from mdcalc import methods
    from mdcalc.input.casefile import CaseText, validate
    from mdcalc.runs.runner import solve_model

    module = PROBLEMS["acceleration"].load()
    speeds = [1000.0, 2000.0, 3000.0, 4000.0, 5000.0, 6000.0]
    data = tomllib.loads((CASES / "acceleration" / "vaz2106.toml").read_text(encoding="utf-8"))
    data.pop("expect")
    data["engine"] = {
        "torque_curve": {"speed_rpm": speeds, "torque": [90.0, 110.0, 118.0, 116.0, 108.0, 95.0]},
        "max_speed_rpm": 6000.0,
    }
    path = Path("table.toml")
    base = validate(module.Case, CaseText(path, "", data))
    rng = np.random.default_rng(4)
    n = 12
    grid = {
        "engine.torque_curve.torque.2": 118.0 * rng.uniform(0.9, 1.05, n),
        "engine.torque_curve.torque.3": 116.0 * rng.uniform(0.95, 1.1, n),
        "engine.torque_curve.torque.5": 95.0 * rng.uniform(0.8, 1.2, n),
        "engine.max_speed_rpm": rng.uniform(5200.0, 6000.0, n),
    }
    answer = module.sweep(base, grid)
    assert answer is not None and not np.any(answer[DECLINED])
    monkeypatch.setattr(methods, "MIN_TIMING_SECONDS", 2e-5)
    monkeypatch.setattr(methods, "REFERENCE_ONLY", True)
    for i in range(n):
        sample = copy.deepcopy(data)
        torques = sample["engine"]["torque_curve"]["torque"]
        for j in (2, 3, 5):
            torques[j] = float(grid[f"engine.torque_curve.torque.{j}"][i])
        limit = float(grid["engine.max_speed_rpm"][i])
        sample["engine"]["max_speed_rpm"] = limit
        # independent: the launch speed is the table's highest point; the shift
        # speed maximizes M·ω, M interpolated linearly, up to the rev limit
        assert answer["launch_speed_rpm"][i] == pytest.approx(speeds[int(np.argmax(torques))])
        fine = np.linspace(speeds[0], limit, 200_001)
        power = np.interp(fine, speeds, torques) * fine
        span = (limit - speeds[0]) / 512  # the candidates' grid step
        assert abs(answer["shift_speed_rpm"][i] - fine[np.argmax(power)]) <= span
        _, report = solve_model(
            "acceleration", module, validate(module.Case, CaseText(path, "", sample)), None
        )
        assert report.status == "ok", report.message
        for key, q in report.results().items():
            if isinstance(q.value, int | float) and not isinstance(q.value, bool):
                rel, tol = tolerance(module, key, 1e-9)
                assert answer[key][i] == pytest.approx(float(q.value), rel=rel, abs=tol), (key, i)
        # the table's peak by the float path's formula: the same bits
        assert answer["peak_torque"][i] == report.results()["peak_torque"].value
