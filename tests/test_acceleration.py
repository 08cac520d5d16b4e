"""``mdcalc acceleration`` from the command line: bad input, no-answer scenes,
extremes, JSON content. The physics is pinned in test_physics_acceleration.py and
in the [expect] tables of cases/acceleration/."""

from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path
from typing import Any

import pytest
from tomli_w import dumps as toml_dumps

from tests.conftest import CASES

VAZ = CASES / "acceleration" / "vaz2106.toml"


def vaz(**changes: dict[str, Any]) -> dict[str, Any]:
    """The VAZ-2106 case without its [expect] table, sections updated by ``changes``."""
    data = tomllib.loads(VAZ.read_text(encoding="utf-8"))
    data.pop("expect")
    for section, values in changes.items():
        if values is None:
            data.pop(section, None)
        else:
            data.setdefault(section, {}).update(values)
    return data


def finite_everywhere(document: Any) -> bool:
    if isinstance(document, float):
        return math.isfinite(document)
    if isinstance(document, dict):
        return all(finite_everywhere(v) for v in document.values())
    if isinstance(document, list):
        return all(finite_everywhere(v) for v in document)
    return True


# ---------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    ("changes", "where", "says"),
    [
        (
            {"transmission": {"gear_ratios": [3.2, 3.5, 1.0]}},
            "transmission.gear_ratios",
            "decrease",
        ),
        (
            {"vehicle": {"rotating_mass_factors": [1.4, 1.2]}},
            "vehicle.rotating_mass_factors",
            "4 gears",
        ),
        ({"engine": {"leiderman": [1.0, 1.0]}}, "engine.leiderman", "at least 3"),
        ({"engine": {"max_powr": 57000.0}}, "engine.max_powr", "did you mean 'max_power'"),
        ({"transmission": {"efficiency": 1.2}}, "transmission.efficiency", "<= 1"),
        ({"transmission": {"shift_speed_rpm": 2000.0}}, "transmission", "launch <= shift"),
        ({"engine": {"max_speed_rpm": 12000.0}}, "engine.max_speed_rpm", "beyond the torque curve"),
        ({"adhesion": {"cg_height": 4.0}}, "adhesion.cg_height", "front wheels would lift"),
        ({"adhesion": {"wheelbase": None}}, "adhesion.wheelbase", "go together"),
        ({"target": {"speed": 20.0}}, "target", "exactly one of speed or speed_kmh"),
        ({"road": {"resistance": -0.1}}, "road.resistance", ">= 0"),
        ({"vehicle": {"mass": 0.0}}, "vehicle.mass", "> 0 kg"),
    ],
)
def test_bad_input_names_the_key(cli, write_case, changes, where, says) -> None:
    data = vaz(**{k: v for k, v in changes.items()})
    if "wheelbase" in changes.get("adhesion", {}):
        del data["adhesion"]["wheelbase"]
    path = write_case(toml_dumps(data))
    result = cli("acceleration", path)
    assert result.exit_code == 2, result.output
    assert f"error: {where}: " in result.stderr
    assert says in result.stderr
    assert "Traceback" not in result.stderr
    first = result.stderr.splitlines()[0]
    assert first.startswith(f"{path}:"), first


def test_torque_table_must_pair_up(cli, write_case) -> None:
    data = vaz(engine=None)
    data["engine"] = {
        "torque_curve": {"speed_rpm": [1000.0, 3000.0, 5000.0], "torque": [90.0, 110.0]}
    }
    result = cli("acceleration", write_case(toml_dumps(data)))
    assert result.exit_code == 2
    assert "engine.torque_curve.torque: " in result.stderr


def test_engine_needs_a_curve(cli, write_case) -> None:
    data = vaz(engine=None)
    data["engine"] = {"max_power": 57000.0}
    result = cli("acceleration", write_case(toml_dumps(data)))
    assert result.exit_code == 2
    assert "max_power_speed_rpm" in result.stderr


# --------------------------------------------------------------------- no answer


def test_truck_cannot_reach_100(cli) -> None:
    result = cli("acceleration", CASES / "acceleration" / "truck.toml")
    assert result.exit_code == 3
    assert "not reachable: top speed is 87.26 km/h" in result.stderr
    assert "traction equals resistance" in result.stderr


def test_steep_hill_cannot_move_off(cli) -> None:
    result = cli("acceleration", CASES / "acceleration" / "steep_hill.toml")
    assert result.exit_code == 3
    assert "cannot move off" in result.stderr


def test_ice_limits_the_tyres_not_the_engine(cli, write_case) -> None:
    result = cli("acceleration", write_case(toml_dumps(vaz(adhesion={"surface": "ice"}))))
    assert result.exit_code == 3
    assert "the tyres can pass" in result.stderr


def test_target_on_the_asymptote_is_no_answer(cli, write_case) -> None:
    # Truck top speed 87.2596197747 km/h (hand quadratic, truck.toml); 2e-9 below it.
    data = tomllib.loads((CASES / "acceleration" / "truck.toml").read_text(encoding="utf-8"))
    data.pop("expect")
    data["target"]["speed_kmh"] = 87.2596196
    result = cli("acceleration", write_case(toml_dumps(data)))
    assert result.exit_code == 3
    assert "only approaches" in result.stderr


def test_no_answer_json_has_status_and_top_speed(cli) -> None:
    result = cli("acceleration", CASES / "acceleration" / "truck.toml", "--json")
    assert result.exit_code == 3
    document = json.loads(result.stdout)
    assert document["status"] == "no-answer"
    assert "87.26 km/h" in document["message"]
    assert document["results"]["top_speed_kmh"]["unit"] == "km/h"
    assert [s["key"] for s in document["sections"] if s["kind"] == "table"] == ["gear_limits"]


# ---------------------------------------------------------------------- extremes


@pytest.mark.parametrize(
    "changes",
    [
        {"target": {"speed_kmh": 0.5}},  # inside the launch slip
        {"target": {"speed_kmh": 140.0}},  # in top gear, just below the rev-limit speed
        {"transmission": {"shift_time": 0.0}},
        {"transmission": {"shift_time": 10.0}},
        {"road": {"resistance": 0.0}, "drag": None, "adhesion": None},
        {"vehicle": {"mass": 50.0}},  # a featherweight: adhesion-limited everywhere
        {"vehicle": {"mass": 4000.0}},
        {"adhesion": {"drive": "all", "driven_axle_load": 1.0}},
        {"adhesion": {"drive": "front", "driven_axle_load": 0.6}},
        {"drag": {"drag_coefficient": 3.0, "frontal_area": 10.0}},
        {"transmission": {"launch_speed_rpm": 5400.0}},
        {"transmission": {"gear_ratios": [3.0]}},
    ],
)
def test_extremes_stay_finite(cli, write_case, changes) -> None:
    result = cli("acceleration", write_case(toml_dumps(vaz(**changes))), "--json")
    assert result.exit_code in (0, 3), result.output + result.stderr
    document = json.loads(result.stdout)
    assert finite_everywhere(document)
    if result.exit_code == 0:
        assert document["results"]["time_to_target"]["value"] > 0
        assert "Traceback" not in result.stderr
    else:
        assert document["message"]


def test_json_carries_the_tables_and_methods(cli) -> None:
    result = cli("acceleration", VAZ, "--json")
    assert result.exit_code == 0
    document = json.loads(result.stdout)
    tables = {s["key"]: s for s in document["sections"] if s["kind"] == "table"}
    assert set(tables) == {"phases", "speed_time"}
    speed_time = tables["speed_time"]
    assert [c["label"] for c in speed_time["columns"]][:2] == ["time", "speed"]
    last = speed_time["rows"][-1]
    assert last[0] == pytest.approx(document["results"]["time_to_target"]["value"], rel=1e-12)
    assert last[1] == pytest.approx(100.0, rel=1e-9)
    methods = next(s for s in document["sections"] if s["kind"] == "methods")
    names = [row["method"] for row in methods["rows"]]
    assert names == [
        "lecture (7.42)",
        "piecewise-constant acceleration",
        "ODE RK45, rtol 1e-3",
        "ODE RK45, rtol 1e-6",
        "ODE DOP853, rtol 1e-11",
    ]
    assert [row["reference"] for row in methods["rows"]] == [False] * 4 + [True]
    assert all(row["seconds"] > 0 for row in methods["rows"])
    # Error falls with the tolerance: the run-time/accuracy trade the table shows.
    errors = [row["rel_errors"]["time_to_target"] for row in methods["rows"][2:4]]
    assert errors[1] < errors[0] < 1e-3


def test_lecture_section_only_with_lecture_table(cli) -> None:
    with_lecture = json.loads(
        cli("acceleration", CASES / "acceleration" / "lecture.toml", "--json").stdout
    )
    without = json.loads(cli("acceleration", VAZ, "--json").stdout)
    assert "lecture_total_time" in with_lecture["results"]
    assert "lecture_total_time" not in without["results"]
    assert any("conventions" in n["text"] for n in with_lecture["notes"])


def test_template_runs(cli, tmp_path: Path) -> None:
    path = tmp_path / "new.toml"
    assert cli("new", "acceleration", "-o", path).exit_code == 0
    result = cli("acceleration", path)
    assert result.exit_code == 0, result.stderr


# ------------------------------------------------- regressions from the review


def load(name: str) -> dict[str, Any]:
    data = tomllib.loads((CASES / "acceleration" / f"{name}.toml").read_text(encoding="utf-8"))
    data.pop("expect", None)
    return data


def run_json(cli, write_case, data: dict[str, Any]) -> tuple[int, dict[str, Any]]:
    result = cli("acceleration", write_case(toml_dumps(data)), "--json")
    return result.exit_code, json.loads(result.stdout) if result.stdout else {}


def test_a_gear_that_tops_out_early_is_left_early(cli, write_case) -> None:
    # Nine close ratios on a 6 % grade: each gear stops pulling below the 3200 rpm
    # shift speed, so the driver must upshift early; gear 5 alone reaches 46.7 km/h
    # from rest, so 45 km/h is reachable (the plan once stopped at 39.7 km/h).
    data = load("truck")
    data["engine"]["max_speed_rpm"] = 4500.0
    data["transmission"]["gear_ratios"] = [7.44, 5.5, 4.10, 3.0, 2.29, 1.8, 1.47, 1.2, 1.0]
    data["road"]["resistance"] = 0.06
    data["target"]["speed_kmh"] = 45.0
    code, document = run_json(cli, write_case, data)
    assert code == 0, document.get("message")
    assert document["results"]["top_speed_kmh"]["value"] > 46.7


def test_stop_during_a_long_shift_never_shows_negative_speed(cli, write_case) -> None:
    data = vaz(adhesion=None, road={"resistance": 0.25}, transmission={"shift_time": 10.0})
    data["engine"] = {"max_power": 300000.0, "max_power_speed_rpm": 5400.0}
    data["engine"]["max_torque_speed_rpm"] = 3000.0
    code, document = run_json(cli, write_case, data)
    assert code == 0
    table = next(s for s in document["sections"] if s.get("key") == "speed_time")
    assert min(row[1] for row in table["rows"]) >= 0.0
    assert all(row[3] == 0.0 for row in table["rows"] if row[1] == 0.0 and row[0] > 0)


def test_rear_drive_launch_never_lifts_the_front(cli, write_case) -> None:
    # h/L = 0.9 and φ = 1.05: the tyres alone would allow more than the front axle's
    # share of the weight can hold down. Front lifts at a = (m·g - N0)·L/(m·h)
    # = (1 - 0.52)·9.80665/0.9 = 5.2302 m/s² (hand).
    data = load("high_power")
    data["adhesion"].update({"coefficient": 1.05, "cg_height": 0.9, "wheelbase": 1.0})
    code, document = run_json(cli, write_case, data)
    assert code == 0
    launch = document["results"]["launch_acceleration"]["value"]
    assert launch == pytest.approx((1 - 0.52) * 9.80665 / 0.9, rel=1e-12)


def test_near_asymptote_loose_solver_gives_up_quickly(cli, write_case) -> None:
    # 2e-6 below the truck's top speed: outside the 1e-6 margin, so an answer; the
    # rtol 1e-3 run cannot get there and says so instead of integrating for minutes.
    data = load("truck")
    data["target"]["speed_kmh"] = 87.25944
    code, document = run_json(cli, write_case, data)
    assert code == 0
    rows = next(s for s in document["sections"] if s["kind"] == "methods")["rows"]
    loose = next(r for r in rows if r["method"] == "ODE RK45, rtol 1e-3")
    assert loose["seconds"] is None or loose["seconds"] < 5.0
    assert finite_everywhere(document)


@pytest.mark.parametrize(
    ("engine", "where"),
    [
        (  # rising table and a rev limit inside it: the peak is at the limit
            {
                "torque_curve": {
                    "speed_rpm": [2000.0, 4000.0, 6000.0],
                    "torque": [100.0, 150.0, 200.0],
                },
                "max_speed_rpm": 3000.0,
            },
            "transmission.launch_speed_rpm",
        ),
        (  # rev limit below the table
            {
                "torque_curve": {
                    "speed_rpm": [2000.0, 4000.0, 6000.0],
                    "torque": [100.0, 150.0, 120.0],
                },
                "max_speed_rpm": 1500.0,
            },
            "engine.max_speed_rpm",
        ),
        (
            {"max_power": 57000.0, "max_power_speed_rpm": 5400.0, "max_torque": 116.0},
            "engine.max_torque_speed_rpm",
        ),
    ],
)
def test_engine_curves_without_a_launch_speed(cli, write_case, engine, where) -> None:
    data = vaz(engine=None)
    data["engine"] = engine
    result = cli("acceleration", write_case(toml_dumps(data)))
    assert result.exit_code == 2
    assert f"error: {where}: " in result.stderr


def test_table_peak_between_points_counts(cli, write_case) -> None:
    # Peak torque of a table capped by the rev limit: 125 N·m at 3000 rpm by linear
    # interpolation between (2000, 100) and (4000, 150) (hand).
    data = vaz(engine=None, transmission={"launch_speed_rpm": 2500.0})
    data["engine"] = {
        "torque_curve": {"speed_rpm": [2000.0, 4000.0, 6000.0], "torque": [100.0, 150.0, 200.0]},
        "max_speed_rpm": 3000.0,
    }
    code, document = run_json(cli, write_case, data)
    assert code in (0, 3)
    assert document["results"]["peak_torque"]["value"] == pytest.approx(125.0, rel=1e-12)


def test_rotating_factor_below_base_is_an_error(cli, write_case) -> None:
    data = vaz(vehicle={"rotating_mass_factors": [1.5, 1.2, 1.1, 1.02]})
    result = cli("acceleration", write_case(toml_dumps(data)))
    assert result.exit_code == 2
    assert "vehicle.rotating_mass_factors" in result.stderr


def test_lecture_note_names_the_lectures_origin_only_for_its_coefficient(cli, write_case) -> None:
    data = load("lecture")
    data["lecture"]["traction_coefficient"] = 2.0
    code, document = run_json(cli, write_case, data)
    assert code == 0
    assert not any("206" in n["text"] for n in document["notes"])


def test_a_table_drawn_row_by_row_is_each_rows_own_table_to_the_bit(monkeypatch) -> None:
    # the kernel's torque table over a block (a study drawing table values, and the
    # rev limit) against each row's table on the float path: interpolation at and
    # between the knots and beyond both ends, the peak torque and the peak power
    # (a plateau on a third of the rows at random: the first of equals; the peaks
    # move from row to row; the rows sought 7 at a time), to the last bit. Values
    # far apart (M[k-1] + (M[k] - M[k-1]) is not M[k] in floating point): a speed
    # at a knot must still give the knot's own value.
    import numpy as np

    from mdcalc.problems.acceleration import engine
    from mdcalc.problems.acceleration.engine import EngineCurve

    monkeypatch.setattr(engine, "BEST_ROWS", 7)

    rng = np.random.default_rng(31)
    speeds = (100.0, 200.0, 300.0, 450.0, 600.0, 720.0)
    rows = 64
    drawn = 560.0 * rng.uniform(0.05, 1.3, rows)
    plateau = np.where(rng.random(rows) < 0.3, 640.0, 650.0 * rng.uniform(0.9, 1.1, rows))
    last = 520.0 * rng.uniform(0.6, 1.4, rows)  # the power's peak: inside or at the top
    torques = (400.0, drawn, 640.0, plateau, 600.0 * rng.uniform(0.2, 1.2, rows), last)
    block = EngineCurve(speeds, torques)

    def row(b: int) -> EngineCurve:
        return EngineCurve(speeds, tuple(float(np.broadcast_to(m, (rows,))[b]) for m in torques))

    omega = np.concatenate(
        [np.array(speeds)[:, None] * np.ones((1, rows)), rng.uniform(50.0, 800.0, (40, rows))]
    )
    got = block.torque(omega)
    for b in range(rows):
        single = row(b)
        assert [single.torque(float(w)) for w in omega[:, b]] == got[:, b].tolist()
    limits = rng.uniform(500.0, 720.0, rows)
    for limit in (700.0, limits):
        peak, at_peak = block.peak(limit)
        power = block.max_power_speed(limit)
        for b in range(rows):
            one = float(np.broadcast_to(limit, (rows,))[b])
            assert row(b).peak(one) == (peak[b], at_peak[b])
            assert row(b).max_power_speed(one) == power[b]


def test_the_least_torque_over_a_span_is_the_least_of_a_fine_grid() -> None:
    # EngineCurve.least bounds a gear's traction over a span of engine speeds (the
    # kernel skips a scan where it proves the car pulls throughout): against the
    # least of 20 001 speeds of each span, knots included, for a table with dips
    # (drawn row by row, and fixed) and Leiderman's curves (concave, convex, linear)
    import numpy as np

    from mdcalc.problems.acceleration.engine import EngineCurve

    rng = np.random.default_rng(5)
    rows = 40
    speeds = (100.0, 200.0, 300.0, 450.0, 600.0, 720.0)
    fixed = (400.0, 300.0, 500.0, 200.0, 600.0, 520.0)
    drawn = tuple(m * rng.uniform(0.8, 1.2, rows) for m in fixed)
    low = rng.uniform(50.0, 700.0, rows)
    high = low + rng.uniform(0.0, 300.0, rows)
    low[::5], high[::5] = high[::5], low[::5].copy()  # either order

    def fine(b: int) -> np.ndarray:
        lo, hi = sorted((low[b], high[b]))
        inside = [s for s in speeds if lo <= s <= hi]
        return np.sort(np.concatenate([np.linspace(lo, hi, 20_001), inside]))

    for torques in (fixed, drawn):
        least, scale = EngineCurve(speeds, torques).least(low, high)
        for b in range(rows):
            row = [float(np.broadcast_to(m, (rows,))[b]) for m in torques]
            assert least[b] == pytest.approx(np.min(np.interp(fine(b), speeds, row)), rel=1e-12)
            assert np.broadcast_to(scale, (rows,))[b] == max(abs(m) for m in row)
    for a, b_, c in ((0.5, 1.5, 1.0), (1.2, -0.8, -0.3), (0.9, 0.2, 0.0)):
        curve = EngineCurve((), (), 300.0, 500.0, (a, b_, c))
        least, _ = curve.least(low, high)
        for b in range(rows):
            x = fine(b) / 500.0
            dense = np.min(300.0 * (a + b_ * x - c * x * x))
            assert least[b] == pytest.approx(dense, rel=1e-9, abs=1e-9)
