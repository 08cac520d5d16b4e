"""``mdcalc coupling``: physics against hand formulas (seed 000 §8.1-8.2, brief §5),
bad input, extremes. Expected values are computed here from the formulas, not taken
from the program."""

from __future__ import annotations

import json
import math
from typing import Any

import pytest
from tomli_w import dumps as toml_dumps

from tests.conftest import CASES

EXAMPLE = {  # example 8.1
    "driving_inertia": 10.0,
    "driven_inertia": 4.0,
    "stiffness_nm_per_deg": 52.5,
    "absorption": 0.63,
}


def case(**sections: Any) -> str:
    data: dict[str, Any] = {"problem": "coupling", "coupling": dict(EXAMPLE)}
    for name, values in sections.items():
        if name == "coupling":
            data["coupling"].update(values)
        else:
            data[name] = values
    data["coupling"] = {k: v for k, v in data["coupling"].items() if v is not None}
    return toml_dumps(data)


def results(cli, write_case, text: str) -> dict[str, Any]:
    result = cli("coupling", write_case(text), "--json")
    assert result.exit_code == 0, result.stderr
    return json.loads(result.stdout)


def example_constants() -> tuple[float, float, float]:
    c = 52.5 * 180.0 / math.pi
    j = 10.0 * 4.0 / 14.0
    beta = math.sqrt(c / j)
    return c, j, beta


def test_damping_inputs_agree(cli, write_case) -> None:
    # ψ = 0.63 ⇔ δ = ψ/2 (8.14) ⇔ α = p·J with p = ψ/τ, τ = 2π/β (8.7).
    c, j, beta = example_constants()
    p = 0.63 / (2.0 * math.pi / beta)
    by_psi = results(cli, write_case, case(step={}))
    by_delta = results(
        cli, write_case, case(coupling={"absorption": None, "log_decrement": 0.315}, step={})
    )
    by_alpha = results(
        cli, write_case, case(coupling={"absorption": None, "damping": p * j}, step={})
    )
    for document in (by_psi, by_delta, by_alpha):
        assert document["results"]["damping_p"]["value"] == pytest.approx(p, rel=1e-12)
        assert document["results"]["step_dynamic_factor"]["value"] == pytest.approx(1.854, abs=5e-4)


def test_step_response_peak_matches_formula_8_16(cli, write_case) -> None:
    # (8.16) with β₁: φ/φ_st = 1 - e^(-pt/2)(cos β₁t + p/(2β₁) sin β₁t); its first
    # maximum is at β₁t = π, giving 1 + e^(-pπ/(2β₁)).
    _, _, beta = example_constants()
    p = 0.63 / (2.0 * math.pi / beta)
    beta1 = math.sqrt(beta**2 - p**2 / 4.0)
    document = results(cli, write_case, case(step={"torque": 100.0}))
    r = document["results"]
    assert r["step_peak_time"]["value"] == pytest.approx(math.pi / beta1, rel=1e-12)
    assert r["step_dynamic_factor"]["value"] == pytest.approx(
        1 + math.exp(-p * math.pi / (2 * beta1)), rel=1e-12
    )
    c = 52.5 * 180.0 / math.pi
    assert r["peak_twist"]["value"] == pytest.approx(
        r["step_dynamic_factor"]["value"] * 100.0 / c, rel=1e-12
    )


def test_duhamel_table_load_equals_a_pulse_written_as_a_table(cli, write_case) -> None:
    # A pulse given as [pulse] and as a torque table must give the same peak; the
    # undamped one also equals 2·sin(βT/2) (seed 000 (7.96)).
    _, _, beta = example_constants()
    text = case(
        coupling={"absorption": None},
        pulse={"torque": 300.0, "duration": 0.04},
        torque_table={"time": [0.0, 0.0, 0.04, 0.04], "torque": [0.0, 300.0, 300.0, 0.0]},
    )
    r = results(cli, write_case, text)["results"]
    expected = 2.0 * math.sin(beta * 0.04 / 2.0)
    assert r["pulse_dynamic_factor"]["value"] == pytest.approx(expected, rel=1e-10)
    assert r["table_dynamic_factor"]["value"] == pytest.approx(expected, rel=1e-10)


def test_harmonic_phase_sum_8_21(cli, write_case) -> None:
    # Equal amplitudes per inertia in antiphase cancel; in phase they add.
    c, j, beta = example_constants()
    same = results(
        cli,
        write_case,
        case(harmonic={"driving_torque": 100.0, "driven_torque": 40.0, "speed": 60.0}),
    )
    opposite = results(
        cli,
        write_case,
        case(
            harmonic={
                "driving_torque": 100.0,
                "driven_torque": 40.0,
                "driven_phase_deg": 180.0,
                "speed": 60.0,
            }
        ),
    )
    assert same["results"]["combined_amplitude"]["value"] == pytest.approx(
        100 / 10 + 40 / 4, rel=1e-12
    )
    assert opposite["results"]["combined_amplitude"]["value"] == pytest.approx(0.0, abs=1e-12)


def test_methods_tables_have_their_reference_and_converge(cli, write_case) -> None:
    document = results(cli, write_case, case(step={}, ramp={"torque": 100.0, "rise_time": 0.1}))
    tables = [s for s in document["sections"] if s["kind"] == "methods"]
    assert [t["key"] for t in tables] == ["step", "ramp"]
    for table in tables:
        assert sum(row["reference"] for row in table["rows"]) == 1
        errors = {row["method"]: row["rel_errors"].get("dynamic_factor") for row in table["rows"]}
        assert errors["ODE DOP853, rtol 1e-10"] < 1e-8
        assert errors["ODE RK45, rtol 1e-6"] < errors["ODE RK45, rtol 1e-3"]


@pytest.mark.parametrize(
    ("sections", "where"),
    [
        ({"coupling": {"stiffness": 3000.0}}, "coupling"),  # both stiffness forms
        ({"coupling": {"log_decrement": 0.3}}, "coupling.log_decrement"),  # two damping forms
        ({"coupling": {"driven_inertia": -4.0}}, "coupling.driven_inertia"),
        ({"pulse": {"torque": 100.0}}, "pulse.duration"),
        ({"harmonic": {"driving_torque": 0.0, "speed": 10.0}}, "harmonic.driving_torque"),
        (
            {"torque_table": {"time": [0.0, 0.2, 0.1], "torque": [1.0, 2.0, 3.0]}},
            "torque_table.time",
        ),
        ({"torque_table": {"time": [0.0, 0.1], "torque": [1.0, 2.0, 3.0]}}, "torque_table.torque"),
        ({"coupling": {"stifness": 1.0}}, "coupling.stifness"),
    ],
)
def test_bad_input(cli, write_case, sections, where) -> None:
    result = cli("coupling", write_case(case(**sections)))
    assert result.exit_code == 2, result.output
    assert f"error: {where}: " in result.stderr
    assert "Traceback" not in result.stderr


def test_undamped_resonance_exits_3(cli) -> None:
    result = cli("coupling", CASES / "coupling" / "resonance_undamped.toml")
    assert result.exit_code == 3
    assert "unbounded" in result.stderr


@pytest.mark.parametrize("zeta", [0.0, 1e-9, 0.7071, 1.0, 50.0])
def test_damping_extremes_stay_finite(cli, write_case, zeta) -> None:
    _, j, beta = example_constants()
    text = case(
        coupling={"absorption": None, "damping": 2.0 * zeta * beta * j if zeta else None},
        step={},
        harmonic={"driving_torque": 10.0, "speed": 0.5 * beta},
        ramp={"torque": 10.0, "rise_time": 0.05},
    )
    document = results(cli, write_case, text)
    text_out = json.dumps(document)
    assert "NaN" not in text_out and "Infinity" not in text_out
    factor = document["results"]["step_dynamic_factor"]["value"]
    assert 1.0 <= factor <= 2.0
