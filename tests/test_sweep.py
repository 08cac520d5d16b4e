"""``mdcalc sweep``: one case over a grid of values.

Braking is evaluated vectorized (numpy closed forms); other problems point by point.
Checked here: the vectorized braking grid against a stopping distance worked out by
hand in this file; the vectorized path against the point-by-point path on the same
grid; the array forms of the motion phases against the scalar ones (hypothesis); a
point-by-point sweep against single runs of each point's case file; the refusals
(exit 2, naming the place); the CSV and JSON files.
"""

from __future__ import annotations

import csv
import json
import math
import tomllib
from itertools import product
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import tomli_w
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from tests.conftest import CASES, assert_no_traceback, run_script, strict_json, walk_finite

G = 9.80665  # standard gravity, the default of a case

# Line numbers matter: the refusals must name them (adhesion on 9, resistance on 10,
# reaction_time on 13, build_up_time on 14).
BASE = """\
problem = "braking"
title = "sweep base"

[vehicle]
mass = 1500.0
initial_speed = 25.0

[road]
adhesion = 0.7
resistance = 0.02

[driver]
reaction_time = 1.0
build_up_time = 0.3
"""

PROGRESS_MARKS = ("\r", "━", "█", "%", "\x1b[")


@pytest.fixture(autouse=True)
def _restore_timing_budget(monkeypatch):
    """A point-by-point sweep lowers methods.MIN_TIMING_SECONDS in-process; restore it."""
    from mdcalc import methods

    monkeypatch.setattr(methods, "MIN_TIMING_SECONDS", methods.MIN_TIMING_SECONDS)


@pytest.fixture
def base(tmp_path: Path) -> Path:
    path = tmp_path / "base.toml"
    path.write_text(BASE, encoding="utf-8")
    return path


# ------------------------------------------------------------------ hand formula


def hand_stop(v0: float, a_brake: float, psi: float, t_r: float, t_b: float) -> dict[str, float]:
    """Stop without drag, by hand, phase by phase.

    Reaction t_r: only the road, deceleration a_r = ψ·g (the car may stop here).
    Build-up t_b: deceleration rising linearly from ψ·g to ψ·g + a_brake:
      v(t) = v1 - ψ·g·t - a_brake·t²/(2·t_b), x(t) = v1·t - ψ·g·t²/2 - a_brake·t³/(6·t_b);
      a stop inside it at the positive root of a_brake/(2·t_b)·τ² + ψ·g·τ - v1 = 0.
    Full braking: (ψ·g + a_brake) to the stop: v²/(2a), v/a.
    ``a_brake`` is the brake force over the mass: φ·g at the adhesion limit.
    """
    a_r = psi * G
    if t_r > 0.0 and v0 <= a_r * t_r:
        return {
            "stopping_distance": v0**2 / (2 * a_r),
            "stopping_time": v0 / a_r,
            "reaction_distance": v0**2 / (2 * a_r),
            "build_up_distance": 0.0,
            "braking_distance": 0.0,
            "branch": 0,
        }
    v1 = v0 - a_r * t_r
    s_r = v0 * t_r - 0.5 * a_r * t_r**2
    if t_b > 0.0:
        v2 = v1 - a_r * t_b - 0.5 * a_brake * t_b
        if v2 <= 0.0:
            qa, qb = a_brake / (2 * t_b), a_r
            tau = (-qb + math.sqrt(qb * qb + 4 * qa * v1)) / (2 * qa)
            s_b = v1 * tau - 0.5 * a_r * tau**2 - a_brake * tau**3 / (6 * t_b)
            return {
                "stopping_distance": s_r + s_b,
                "stopping_time": t_r + tau,
                "reaction_distance": s_r,
                "build_up_distance": s_b,
                "braking_distance": 0.0,
                "branch": 1,
            }
        s_b = v1 * t_b - 0.5 * a_r * t_b**2 - a_brake * t_b**2 / 6
    else:
        v2, s_b = v1, 0.0
    a = a_r + a_brake
    return {
        "stopping_distance": s_r + s_b + v2**2 / (2 * a),
        "stopping_time": t_r + t_b + v2 / a,
        "reaction_distance": s_r,
        "build_up_distance": s_b,
        "braking_distance": v2**2 / (2 * a),
        "branch": 2,
    }


def read_csv(path: Path) -> tuple[list[str], list[dict[str, str]]]:
    """Header cells and rows keyed by the bare key (``key [unit]`` -> ``key``)."""
    with path.open(encoding="utf-8", newline="") as handle:
        rows = list(csv.reader(handle))
    header = rows[0]
    keys = [cell.split(" [")[0] for cell in header]
    return header, [dict(zip(keys, row, strict=True)) for row in rows[1:]]


STOP_KEYS = [
    "stopping_distance",
    "stopping_time",
    "reaction_distance",
    "build_up_distance",
    "braking_distance",
]


def test_vectorized_braking_grid_matches_the_hand_formula(cli, base, tmp_path):
    out = tmp_path / "grid.csv"
    varies = {
        "vehicle.initial_speed": (1.0, 31.0, 4),
        "road.adhesion": (0.2, 0.8, 3),
        "road.resistance": (0.01, 0.41, 3),
        "driver.reaction_time": (0.0, 2.0, 3),
        "driver.build_up_time": (0.0, 4.0, 3),
    }
    args = [f"--vary={k}={a}:{b}:{n}" for k, (a, b, n) in varies.items()]
    result = cli("sweep", base, *args, *[f"--result={k}" for k in STOP_KEYS], "--out", out)
    assert result.exit_code == 0, result.stderr
    assert_no_traceback(result)
    assert result.stderr == f"wrote {out}: 324 points, vectorized\n"  # and no progress bar

    header, rows = read_csv(out)
    assert header == [
        "vehicle.initial_speed [m/s]",
        "road.adhesion",
        "road.resistance",
        "driver.reaction_time [s]",
        "driver.build_up_time [s]",
        "stopping_distance [m]",
        "stopping_time [s]",
        "reaction_distance [m]",
        "build_up_distance [m]",
        "braking_distance [m]",
        "status",
    ]
    # The grid, in order: the last --vary varies fastest.
    axes = [np.linspace(a, b, n) for a, b, n in varies.values()]
    assert len(rows) == math.prod(len(a) for a in axes)
    branches = [0, 0, 0]
    for row, point in zip(rows, product(*axes), strict=True):
        v0, phi, psi, t_r, t_b = point
        got = [float(row[k]) for k in varies]
        assert got == pytest.approx(list(point), rel=1e-11, abs=1e-12)
        assert row["status"] == "0"
        want = hand_stop(v0, phi * G, psi, t_r, t_b)
        branches[want["branch"]] += 1
        for key in STOP_KEYS:
            if key.endswith("_distance") and key != "stopping_distance" and t_r == t_b == 0.0:
                # As in the report: without reaction and build-up the phases are not shown.
                assert row[key] == "", (key, point)
                continue
            # The CSV carries 12 significant digits.
            assert float(row[key]) == pytest.approx(want[key], rel=1e-10, abs=1e-9), (key, point)
    # Every branch of the hand formula was reached: a stop in the reaction, in the
    # build-up and in full braking.
    assert all(count >= 10 for count in branches), branches


def test_real_script_writes_csv_without_a_progress_bar(base, tmp_path):
    out = tmp_path / "speeds.csv"
    done = run_script("sweep", base, "--vary", "vehicle.initial_speed=10:40:7", "--out", out)
    assert done.returncode == 0, done.stderr
    assert done.stderr == f"wrote {out}: 7 points, vectorized\n"
    assert not any(mark in done.stderr for mark in PROGRESS_MARKS)
    _, rows = read_csv(out)
    for row in rows:
        v0 = float(row["vehicle.initial_speed"])
        want = hand_stop(v0, 0.7 * G, 0.02, 1.0, 0.3)
        assert float(row["stopping_distance"]) == pytest.approx(want["stopping_distance"], 1e-10)
        assert float(row["stopping_time"]) == pytest.approx(want["stopping_time"], 1e-10)


def test_table_on_stdout_without_out(cli, base):
    result = cli("sweep", base, "--vary", "road.adhesion=0.3:0.9:3")
    assert result.exit_code == 0
    assert result.stderr == ""
    assert "Sweep: 3 points, vectorized" in result.stdout
    want = hand_stop(25.0, 0.3 * G, 0.02, 1.0, 0.3)["stopping_distance"]
    assert f"{want:.6g}" in result.stdout


def test_json_out_is_strict_finite_and_complete(cli, base, tmp_path):
    out = tmp_path / "grid.json"
    result = cli(
        "sweep",
        base,
        "--vary",
        "vehicle.mass=800:2000:3",
        "--vary",
        "driver.reaction_time=0.5:1.5:5",
        "--out",
        out,
    )
    assert result.exit_code == 0, result.stderr
    document = strict_json(out.read_text(encoding="utf-8"))
    walk_finite(document)
    assert document["problem"] == "braking" and document["format"] == 2
    assert document["vectorized"] is True
    assert document["vary"] == [
        {"key": "vehicle.mass", "start": 800.0, "stop": 2000.0, "n": 3},
        {"key": "driver.reaction_time", "start": 0.5, "stop": 1.5, "n": 5},
    ]
    assert document["columns"] == [
        {"key": "vehicle.mass", "unit": "kg"},
        {"key": "driver.reaction_time", "unit": "s"},
        {"key": "stopping_distance", "unit": "m"},
        {"key": "stopping_time", "unit": "s"},
    ]
    values = document["values"]
    assert set(values) == {c["key"] for c in document["columns"]}
    assert all(len(column) == 15 for column in values.values())
    assert document["status"] == [0] * 15
    grid = list(product([800.0, 1400.0, 2000.0], [0.5, 0.75, 1.0, 1.25, 1.5]))
    assert list(zip(values["vehicle.mass"], values["driver.reaction_time"], strict=True)) == grid
    for index, (_, t_r) in enumerate(grid):
        # Without drag, the mass cancels out of an adhesion-limited stop.
        want = hand_stop(25.0, 0.7 * G, 0.02, t_r, 0.3)
        assert values["stopping_distance"][index] == pytest.approx(want["stopping_distance"], 1e-12)
        assert values["stopping_time"][index] == pytest.approx(want["stopping_time"], rel=1e-12)


def test_varying_a_brake_force_the_base_case_does_not_have(cli, base, tmp_path):
    out = tmp_path / "force.csv"
    result = cli("sweep", base, "--vary", "brakes.force=1000:5000:3", "--out", out)
    assert result.exit_code == 0, result.stderr
    _, rows = read_csv(out)
    for row, force in zip(rows, (1000.0, 3000.0, 5000.0), strict=True):
        # All below the adhesion limit 0.7·1500·g = 10297 N: the brakes' force acts.
        want = hand_stop(25.0, force / 1500.0, 0.02, 1.0, 0.3)
        assert float(row["stopping_distance"]) == pytest.approx(want["stopping_distance"], 1e-10)


# ------------------------------------------------- vectorized vs point by point


def _numeric_keys(path: Path) -> list[str]:
    from mdcalc.runs.runner import run_case

    return [
        key
        for key, q in run_case(path).results().items()
        if isinstance(q.value, int | float) and not isinstance(q.value, bool)
    ]


def _both_paths(path: Path, varies: list[str], monkeypatch) -> tuple[Any, Any, list[str]]:
    from mdcalc.problems import PROBLEMS
    from mdcalc.runs.sweep import evaluate, parse_vary, plan

    keys = _numeric_keys(path)
    sweep = plan(path, [parse_vary(v) for v in varies])
    fast = evaluate(sweep, keys, 1)
    with monkeypatch.context() as patch:
        patch.setattr(PROBLEMS["braking"].load(), "sweep", lambda case, grid, wanted=None: None)
        slow = evaluate(sweep, keys, 1)
    assert fast.vectorized and not slow.vectorized
    return fast, slow, keys


VS_CASES = {
    "adhesion limit, stops in every phase": (
        BASE,
        [
            "vehicle.initial_speed=1:31:4",
            "road.resistance=0.01:0.41:3",
            "driver.reaction_time=0.5:2:2",
            "driver.build_up_time=0:4:3",
        ],
    ),
    "brake force below and above adhesion": (
        BASE.replace("[driver]", "[brakes]\nforce = 5000.0\n\n[driver]"),
        ["brakes.force=2000:20000:4", "gravity=9:10:2", "vehicle.mass=800:2000:2"],
    ),
    "drag in the reaction and braking": (
        BASE.replace("build_up_time = 0.3", "build_up_time = 0.0")
        + "\n[drag]\ndrag_coefficient = 0.4\nfrontal_area = 2.0\n",
        [
            "drag.drag_coefficient=0.2:0.6:3",
            "vehicle.initial_speed=2:110:3",
            "driver.reaction_time=0.5:4:2",
        ],
    ),
    "lecture brakes, speed in km/h": (
        (CASES / "braking" / "lecture.toml")
        .read_text(encoding="utf-8")
        .replace("initial_speed = 27.8", "initial_speed_kmh = 100.0"),
        ["brakes.force_multiple=2:12:3", "vehicle.initial_speed_kmh=30:150:3"],
    ),
}


@pytest.mark.parametrize("name", list(VS_CASES))
def test_vectorized_equals_point_by_point(name, tmp_path, monkeypatch):
    text, varies = VS_CASES[name]
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    fast, slow, keys = _both_paths(path, varies, monkeypatch)
    assert list(slow.status) == [0] * len(slow.status)
    assert len(keys) >= 5
    for key in keys:
        np.testing.assert_allclose(
            fast.columns[key], slow.columns[key], rtol=1e-12, atol=1e-12, err_msg=key
        )


def test_vectorized_and_point_by_point_have_values_at_the_same_points(tmp_path, monkeypatch):
    path = tmp_path / "case.toml"
    path.write_text(BASE.replace("build_up_time = 0.3", "build_up_time = 0.0"), encoding="utf-8")
    fast, slow, keys = _both_paths(path, ["driver.reaction_time=0:1:2"], monkeypatch)
    for key in keys:
        assert list(np.isnan(fast.columns[key])) == list(np.isnan(slow.columns[key])), key


# ------------------------------------------------- array forms vs scalar forms


def sometimes_zero(low: float, high: float) -> st.SearchStrategy[float]:
    """A positive float, or exactly 0.0 about one time in four (its own branch)."""
    values = st.floats(min_value=low, max_value=high)
    return st.tuples(st.integers(0, 3), values).map(lambda pair: pair[1] if pair[0] else 0.0)


speeds = sometimes_zero(1e-3, 150.0)
masses = st.floats(min_value=1.0, max_value=1e5)
forces = sometimes_zero(1e-3, 1e5)
drags = sometimes_zero(1e-4, 10.0)
durations = sometimes_zero(1e-4, 60.0)


@st.composite
def constant_force_rows(draw: Any) -> tuple[float, float, float, float, float | None]:
    v0, force, drag, mass = draw(speeds), draw(forces), draw(drags), draw(masses)
    if force == 0.0 and v0 > 0.0:
        duration: float | None = draw(durations)  # nothing would stop the car
    else:
        duration = draw(st.one_of(st.none(), durations))
    return v0, force, drag, mass, duration


def _close(got: float, want: float, scale: float) -> bool:
    return math.isclose(got, want, rel_tol=1e-12, abs_tol=1e-12 * scale)


def _check_constant_force(rows: list[tuple[float, float, float, float, float | None]]) -> None:
    from mdcalc.core.motion import constant_force_phase

    # One call for the rows run to the stop (duration None applies to a whole call),
    # one for the timed rows (an array of durations).
    for timed in (False, True):
        chosen = [r for r in rows if (r[4] is not None) == timed]
        if not chosen:
            continue
        v0, force, drag, mass, duration = (
            np.array(c, dtype=float) for c in zip(*chosen, strict=True)
        )
        arrays = constant_force_phase(v0, force, drag, mass, duration if timed else None)
        for index, row in enumerate(chosen):
            want = constant_force_phase(*row)
            scale = row[0] * (1.0 + (row[4] or 0.0))
            got = (arrays.speed[index], arrays.distance[index], arrays.time[index])
            for g, w in zip(got, (want.speed, want.distance, want.time), strict=True):
                assert _close(float(g), w, max(scale, 1.0)), (row, got, want)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(rows=st.lists(constant_force_rows(), min_size=1, max_size=12))
@example(rows=[(20.0, 3000.0, 0.0, 1000.0, None)])  # no drag, to the stop
@example(rows=[(20.0, 3000.0, 0.0, 1000.0, 1.0)])  # no drag, still moving after 1 s
@example(rows=[(20.0, 3000.0, 0.0, 1000.0, 30.0)])  # no drag, stops inside 30 s
@example(rows=[(20.0, 0.0, 0.0, 1000.0, 2.0)])  # coasting
@example(rows=[(20.0, 0.0, 0.5, 1000.0, 2.0)])  # drag alone
@example(rows=[(20.0, 300.0, 0.5, 1000.0, None)])  # force and drag, to the stop
@example(rows=[(20.0, 300.0, 0.5, 1000.0, 1.0)])  # force and drag, moving after 1 s
@example(rows=[(20.0, 300.0, 0.5, 1000.0, 500.0)])  # force and drag, stops inside
@example(rows=[(0.0, 300.0, 0.5, 1000.0, 1.0), (0.0, 0.0, 0.0, 1.0, None)])  # at rest
@example(  # every branch in one array
    rows=[
        (20.0, 3000.0, 0.0, 1000.0, 1.0),
        (20.0, 3000.0, 0.0, 1000.0, 30.0),
        (20.0, 0.0, 0.0, 1000.0, 2.0),
        (20.0, 0.0, 0.5, 1000.0, 2.0),
        (20.0, 300.0, 0.5, 1000.0, 1.0),
        (20.0, 300.0, 0.5, 1000.0, 500.0),
        (0.0, 0.0, 0.5, 1000.0, 0.0),
    ]
)
def test_constant_force_phase_array_equals_the_scalar(rows):
    _check_constant_force(rows)


@st.composite
def ramp_rows(draw: Any) -> tuple[float, float, float, float, float]:
    return draw(speeds), draw(forces), draw(forces), draw(masses), draw(durations)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(rows=st.lists(ramp_rows(), min_size=1, max_size=12))
@example(rows=[(20.0, 150.0, 8000.0, 1000.0, 0.3)])  # through the build-up
@example(rows=[(2.0, 150.0, 8000.0, 1000.0, 3.0)])  # stops inside it
@example(rows=[(2.0, 0.0, 8000.0, 1000.0, 3.0)])  # no road resistance, stops inside
@example(rows=[(2.0, 150.0, 0.0, 1000.0, 30.0)])  # no rise: uniform, stops inside
@example(rows=[(0.0, 150.0, 8000.0, 1000.0, 3.0), (5.0, 150.0, 8000.0, 1000.0, 0.0)])  # idle
def test_ramp_phase_array_equals_the_scalar(rows):
    from mdcalc.core.motion import ramp_phase

    v0, base, rise, mass, duration = (np.array(c, dtype=float) for c in zip(*rows, strict=True))
    arrays = ramp_phase(v0, base, rise, mass, duration)
    for index, row in enumerate(rows):
        want = ramp_phase(*row)
        got = (arrays.speed[index], arrays.distance[index], arrays.time[index])
        scale = max(row[0] * (1.0 + row[4]), 1.0)
        for g, w in zip(got, (want.speed, want.distance, want.time), strict=True):
            assert _close(float(g), w, scale), (row, got, want)


# ------------------------------------------------- point by point vs single runs


def test_point_by_point_sweep_equals_single_runs(cli, tmp_path, monkeypatch):
    # mount has a kernel now; without it the grid runs point by point in the pool.
    from mdcalc.problems import PROBLEMS

    monkeypatch.setattr(PROBLEMS["mount"].load(), "sweep", lambda case, grid, wanted=None: None)
    source = CASES / "mount" / "example_9_1.toml"
    out = tmp_path / "mount.json"
    keys = ["natural_frequency", "amplitude_1", "amplitude_2", "peak_displacement"]
    result = cli(
        "sweep",
        source,
        "--vary",
        "crank.speed=120:180:3",
        "--vary",
        "mounts.static_deflection=0.005:0.02:2",
        *[f"--result={k}" for k in keys],
        "--out",
        out,
        "--jobs",
        "2",
    )
    assert result.exit_code == 0, result.stderr
    assert result.stderr == f"wrote {out}: 6 points, point by point\n"
    document = strict_json(out.read_text(encoding="utf-8"))
    walk_finite(document)
    assert document["vectorized"] is False and document["problem"] == "mount"
    values = document["values"]
    data = tomllib.loads(source.read_text(encoding="utf-8"))
    data.pop("expect")
    g = data["gravity"]
    m, big_m = data["crank"]["piston_weight"] / g, data["engine"]["weight"] / g
    r = data["crank"]["radius"]
    grid = list(product([120.0, 150.0, 180.0], [0.005, 0.02]))
    for index, (omega, deflection) in enumerate(grid):
        assert values["crank.speed"][index] == omega
        assert values["mounts.static_deflection"][index] == deflection
        data["crank"]["speed"] = omega
        data["mounts"]["static_deflection"] = deflection
        point = tmp_path / f"point_{index}.toml"
        point.write_text(tomli_w.dumps(data), encoding="utf-8")
        single = cli("mount", point, "--json")
        assert single.exit_code == 0, single.stderr
        results = strict_json(single.stdout)["results"]
        for key in keys:
            assert values[key][index] == pytest.approx(results[key]["value"], rel=1e-12), key
        # and by hand (seed 000 (7.50), (7.70)): c = G/f, A₁ = m·r·ω²/(M·ω² - c)
        c = data["engine"]["weight"] / deflection
        assert values["natural_frequency"][index] == pytest.approx(math.sqrt(g / deflection))
        assert values["amplitude_1"][index] == pytest.approx(
            m * r * omega**2 / (big_m * omega**2 - c), rel=1e-9
        )


def test_integer_key_with_whole_steps(cli, tmp_path):
    """z₂ over 1..4 for one material: (27) C_max = π/(4·z₂·f₂·η·(1 - η))."""
    out = tmp_path / "clutch.csv"
    source = CASES / "clutch" / "one_material_065.toml"
    args = ["--vary", "pairs.driven=1:4:4", "--result", "c_max_one_material", "--out", out]
    result = cli("sweep", source, *args)
    assert result.exit_code == 0, result.stderr
    _, rows = read_csv(out)
    assert [row["pairs.driven"] for row in rows] == ["1", "2", "3", "4"]
    for row in rows:
        z2 = int(row["pairs.driven"])
        want = math.pi / (4 * z2 * 0.4 * 0.65 * 0.35)
        assert float(row["c_max_one_material"]) == pytest.approx(want, rel=1e-10)
        assert row["status"] == "0"


# ------------------------------------------------- refusals


@pytest.mark.parametrize(
    ("varies", "place"),
    [
        (["road.adhesion=0.3:2.5:3"], "{path}:9: error: road.adhesion: got 2.5; must be <= 2"),
        (["road.resistance=0:1:3"], "{path}:10: error: road.resistance: got 1.0; must be < 1"),
        (["driver.reaction_time=-1:1:3"], "{path}:13: error: driver.reaction_time: got -1.0"),
        (  # only one corner of a 2-D grid is out of bounds
            ["road.adhesion=0.5:0.9:2", "driver.build_up_time=0:20:2"],
            "{path}:14: error: driver.build_up_time: got 20.0",
        ),
        (["vehicle.nope=1:2:2"], "error: vehicle.nope: unknown key"),
        (["title=1:2:2"], "--vary title: error: title is not a number"),
        (["road.adhesion=0.3:0.5:2", "road.adhesion=0.6:0.7:2"], "a key is varied twice"),
        (["road.adhesion=0.3:0.9"], "--vary road.adhesion=0.3:0.9: error: expected KEY="),
        (["road.adhesion 0.3:0.9:3"], "--vary road.adhesion 0.3:0.9:3: error: expected KEY="),
        (["road.adhesion=a:0.9:3"], "--vary road.adhesion=a:0.9:3: error: START and STOP"),
        (["road.adhesion=0.3:inf:3"], "--vary road.adhesion=0.3:inf:3: error: START and STOP"),
        (["road.adhesion=nan:1:3"], "--vary road.adhesion=nan:1:3: error: START and STOP"),
        (["road.adhesion=0.3:0.9:0"], "--vary road.adhesion=0.3:0.9:0: error: N = 0"),
        (["road.adhesion=0.3:0.9:2.5"], "--vary road.adhesion=0.3:0.9:2.5: error: N must be"),
    ],
)
def test_bad_grid_is_exit_2_naming_the_place(cli, base, tmp_path, varies, place):
    out = tmp_path / "never.csv"
    result = cli("sweep", base, *[f"--vary={v}" for v in varies], "--out", out)
    assert result.exit_code == 2, result.stderr
    assert_no_traceback(result)
    assert place.format(path=base) in result.stderr
    assert result.stdout == "" and not out.exists()


def test_unknown_result_is_exit_2(cli, base):
    result = cli("sweep", base, "--vary", "road.adhesion=0.3:0.9:3", "--result", "nope")
    assert result.exit_code == 2
    assert_no_traceback(result)
    assert "--result: error: no numeric result 'nope'" in result.stderr
    assert "stopping_distance" in result.stderr  # the keys it does have


def test_out_must_be_csv_or_json(cli, base, tmp_path):
    out = tmp_path / "table.txt"
    result = cli("sweep", base, "--vary", "road.adhesion=0.3:0.9:3", "--out", out)
    assert result.exit_code == 2
    assert_no_traceback(result)
    assert f"{out}: error: --out takes a .csv or a .json file" in result.stderr
    assert not out.exists()


def test_no_vary_is_exit_2(cli, base):
    result = cli("sweep", base)
    assert result.exit_code == 2
    assert "--vary" in result.stderr


def test_fractional_steps_over_an_integer_key_are_exit_2(cli, tmp_path):
    source = CASES / "clutch" / "one_material_065.toml"
    result = cli("sweep", source, "--vary", "pairs.driven=1:4:3")  # 1, 2.5, 4
    assert result.exit_code == 2
    assert_no_traceback(result)
    assert "--vary pairs.driven: error: the key is an integer" in result.stderr


def test_nothing_but_the_out_file_is_written(cli, base, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    before = {p.name for p in tmp_path.iterdir()}
    result = cli("sweep", base, "--vary", "road.adhesion=0.3:0.9:3", "--out", "t.json")
    assert result.exit_code == 0
    assert {p.name for p in tmp_path.iterdir()} - before == {"t.json"}
    json.loads((tmp_path / "t.json").read_text(encoding="utf-8"))


# ------------------------------------------------- bugs found (xfail until fixed)


def test_array_index_out_of_range_is_exit_2(cli):
    result = cli("sweep", CASES / "hoist" / "crane.toml", "--vary", "drive.shafts.5.inertia=1:2:2")
    assert result.exit_code == 2, result.stderr
    assert_no_traceback(result)
    assert "drive.shafts.5.inertia" in result.stderr


def test_integer_key_absent_from_the_base_case(cli, tmp_path):
    text = (CASES / "hoist" / "crane.toml").read_text(encoding="utf-8")
    text = text.split("[expect]")[0].replace("branches = 4\n", "")
    path = tmp_path / "crane.toml"
    path.write_text(text, encoding="utf-8")
    result = cli("sweep", path, "--vary", "rope.branches=2:4:3")
    assert result.exit_code == 0, result.stderr


def test_float_key_written_as_an_integer_takes_fractional_steps(cli, tmp_path):
    path = tmp_path / "case.toml"
    path.write_text(BASE.replace("mass = 1500.0", "mass = 1500"), encoding="utf-8")
    out = tmp_path / "mass.csv"
    result = cli("sweep", path, "--vary", "vehicle.mass=1000:2000:4", "--out", out)
    assert result.exit_code == 0, result.stderr
    _, rows = read_csv(out)
    assert [float(r["vehicle.mass"]) for r in rows] == pytest.approx(
        [1000, 4000 / 3, 5000 / 3, 2000]
    )


def test_the_printed_status_says_ok_or_no_answer_as_run_does(cli):
    # M_c = m·g·r/(i·η) = 79.15 N·m at 1000 kg is more than the motor starts with
    # (cases/hoist/cannot_start.toml); 100, 400 and 700 kg start.
    case = CASES / "hoist" / "cannot_start.toml"
    table = cli("sweep", case, "--vary", "load.mass=100:1000:4", "--result", "static_torque")
    assert table.exit_code == 3, table.stderr
    rows = [line for line in table.stdout.splitlines() if line.startswith("│")]
    assert [row.split("│")[-2].strip() for row in rows] == ["ok", "ok", "ok", "no-answer"]
    # No start from 75 N·m / (79.1469 N·m / 1000 kg) = 947.6 kg on: of 100 + 4.5·k kg,
    # k = 189 ... 200, twelve points.
    ranges = cli("sweep", case, "--vary", "load.mass=100:1000:201")
    assert "points: 189 ok, 12 no-answer" in ranges.stdout


@pytest.mark.parametrize("block", [65_536, 7, 1], ids=["one-block", "blocks-of-7", "blocks-of-1"])
@pytest.mark.parametrize("failed", [False, True], ids=["all-ok", "some-failed"])
def test_csv_numbers_read_back_as_the_very_floats(failed, block, monkeypatch):
    """Every number of the CSV is the shortest text of its float (reads back exact), a
    whole-number column without ".0", NaN an empty field, the status last; the same
    text whatever the block of rows formatted at a time."""
    import numpy as np

    from mdcalc.runs import sweep
    from mdcalc.runs.sweep import Table, to_csv

    monkeypatch.setattr(sweep, "CSV_BLOCK_ROWS", block)

    rng = np.random.default_rng(7)
    x = np.linspace(800.0, 3000.0, 1001)
    y = rng.standard_normal(1001) * 10.0 ** rng.integers(-30, 30, 1001)
    count = np.arange(1001, dtype=float)  # a whole-number column
    y[5] = np.nan
    status = np.zeros(1001, dtype=int)
    if failed:
        status[[3, 1000]] = [3, 2]
    table = Table(["x", "y", "n"], {"x": "kg", "y": "m", "n": ""}, {"x": x, "y": y, "n": count},
                  status)  # fmt: skip
    text = b"".join(bytes(piece) for piece in to_csv(table)).decode()
    lines = text.split("\n")
    assert lines[0] == "x [kg],y [m],n,status" and lines[-1] == ""
    rows = [line.split(",") for line in lines[1:-1]]
    assert len(rows) == 1001 and all(len(row) == 4 for row in rows)
    for i, (a, b, n, code) in enumerate(rows):
        shortest = repr(float(x[i]))  # 802.2; a whole 800.0 is written 800
        assert a == shortest.removesuffix(".0") and float(a) == x[i]
        assert (b == "") if i == 5 else float(b) == y[i]
        assert n == str(i) and int(code) == status[i]


@pytest.mark.parametrize(
    ("case", "vary"),
    [
        ("braking/dry.toml", "vehicle.mass=800:3000:3"),
        ("coupling/example_8_1.toml", "coupling.absorption=0.2:1.2:4"),
        ("mount/example_9_1.toml", "crank.speed=120:180:3"),
    ],
)
def test_json_out_holds_the_csv_numbers(cli, tmp_path, case, vary):
    # A kernel's column may be a strided view of a 2-D array (coupling's was: exit 70,
    # "numpy array is not C contiguous"); the JSON must hold the CSV's very numbers.
    for suffix in ("csv", "json"):
        result = cli("sweep", CASES / case, "--vary", vary, "--out", tmp_path / f"g.{suffix}")
        assert result.exit_code == 0, result.stderr
    _, rows = read_csv(tmp_path / "g.csv")
    document = strict_json((tmp_path / "g.json").read_text(encoding="utf-8"))
    for column in document["columns"]:
        key = column["key"]
        from_csv = [float(row[key]) if row[key] else None for row in rows]
        assert document["values"][key] == from_csv, key
