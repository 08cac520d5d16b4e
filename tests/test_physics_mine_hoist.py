"""Independent physics tests of ``mdcalc mine-hoist`` (brief §6, seed 002, Osipova:
mine hoist with a head sheave, a three-mass free-free chain reduced to the drum axis).

Every expected value below is computed in this file, never copied from the program:

* β₁², β₂² are the roots of the characteristic quadratic
  λ² - λ·[c₁₂(1/J₁+1/J₂) + c₂₃(1/J₂+1/J₃)] + c₁₂c₂₃ΣJ/(J₁J₂J₃) = 0, evaluated with
  ``decimal`` at 50 digits (:func:`hand_hoist`);
* R₁₂ = [M₁(J₂+J₃) + W·J₁]/ΣJ, R₂₃ = [M₁J₃ + W(J₁+J₂)]/ΣJ (seed (11)-(12));
* M₁₂ = R₁₂ + B₁cos β₁t + B₂cos β₂t, M₂₃ = R₂₃ + g₁B₁cos β₁t + g₂B₂cos β₂t with
  g = J₂(β₁₂² - β²)/c₁₂ (seed (8)), B from M₁₂(0) = M₂₃(0) = 0; suprema 1 + Σ|b|;
* maxima in time by a dense numpy grid refined by scipy's bounded scalar search
  (:func:`brute_max`);
* the simplified (19), (20), the seed's printed (1), the two-mass limit
  (series spring c₁₂c₂₃/(c₁₂+c₂₃)) and the rope-mass reduction (2)-(5) written out.

The brief's rounded reference numbers (β₁ = 2.6736, β₂ = 27.1045, μ₁₂ sup 2.0000,
μ₂₃ sup 2.0070, first swing 1.9707/2.0067, (19) ≈ 1.927, (20) ≈ 2.0825) are checked
at their printed precision on top of the tight hand comparisons.
"""

from __future__ import annotations

import copy
import json
import math
import re
from decimal import Decimal, localcontext
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from scipy.optimize import minimize_scalar
from tomli_w import dumps as toml_dumps

from tests.conftest import assert_no_traceback, run_script, strict_json, walk_finite

TIGHT = 1e-12  # relative, hand closed forms in 50-digit decimals
MAXIMUM = 1e-10  # relative, maxima in time against the own grid + refinement

# Seed 002 at H = 1025 m (rope mass already lumped), M₁ = 2·W as the brief takes it;
# W = 500 kN·m is a scale assumption (μ depends only on M₁/W).
SEED: dict[str, Any] = {
    "problem": "mine-hoist",
    "title": "seed 002 at H = 1025 m",
    "hoist": {
        "drum_inertia": 479.15e3,
        "sheave_inertia": 27.97e3,
        "cage_inertia": 156.86e3,
        "chord_stiffness": 18609.2e3,
        "rope_stiffness": 893.45e3,
    },
    "loads": {"drive_torque": 1.0e6, "load_torque": 5.0e5},
    "analysis": {"ode": False},
}

# Assumed rope data for the reduction tests (not from the seed): ρ = 7.5 kg/m,
# drum radius R = 3 m, chord L₁ = 49.2 m, H = 1025 m. EA chosen so that
# c₂₃ = EA·R²/H ≈ the seed's 893.45 kN·m/rad at 1025 m (then c₁₂ ≈ 18.6 MN·m/rad).
ROPE = {"mass_per_metre": 7.5, "drum_radius": 3.0, "chord_length": 49.2, "length": 1025.0}
EA = 893.45e3 * 1025.0 / 9.0  # N

# ----------------------------------------------------------------------------- helpers


def case(**changes: Any) -> dict[str, Any]:
    """The seed case with sections updated; a value of None deletes the key."""
    data = copy.deepcopy(SEED)
    for section, values in changes.items():
        if not isinstance(values, dict):
            data[section] = values
            continue
        target = data.setdefault(section, {})
        for key, value in values.items():
            if value is None:
                target.pop(key, None)
            else:
                target[key] = value
    return data


def run_json(cli, write_case, data: dict[str, Any]) -> dict[str, Any]:
    result = cli("mine-hoist", write_case(toml_dumps(data)), "--json")
    assert result.exit_code == 0, result.stderr
    return json.loads(result.stdout)


def values(document: dict[str, Any]) -> dict[str, float]:
    return {key: q["value"] for key, q in document["results"].items()}


def section(document: dict[str, Any], key: str) -> dict[str, Any]:
    (found,) = [s for s in document["sections"] if s.get("key") == key]
    return found


def D(x: float) -> Decimal:
    return Decimal(repr(float(x)))


def quadratic(j1, j2, j3, c12, c23) -> tuple[Decimal, Decimal]:
    """50-digit roots of the characteristic quadratic (brief §6); small root as
    2P/(S + √(S² - 4P)), free of cancellation. Arguments are Decimals."""
    s = c12 * (1 / j1 + 1 / j2) + c23 * (1 / j2 + 1 / j3)
    p = c12 * c23 * (j1 + j2 + j3) / (j1 * j2 * j3)
    root = (s * s - 4 * p).sqrt()
    return 2 * p / (s + root), (s + root) / 2


def hand_hoist(j1, j2, j3, c12, c23, m1, w) -> dict[str, Any]:
    """Everything of brief §6 for one chain, by the formulas, in 50-digit decimals."""
    with localcontext() as ctx:
        ctx.prec = 50
        j1, j2, j3, c12, c23, m1, w = (D(v) for v in (j1, j2, j3, c12, c23, m1, w))
        lam1, lam2 = quadratic(j1, j2, j3, c12, c23)
        total = j1 + j2 + j3
        r12 = (m1 * (j2 + j3) + w * j1) / total  # (11)
        r23 = (m1 * j3 + w * (j1 + j2)) / total  # (12)
        beta12_sq = c12 * (1 / j1 + 1 / j2)
        beta23_sq = c23 * (1 / j2 + 1 / j3)
        g1, g2 = (j2 * (beta12_sq - lam) / c12 for lam in (lam1, lam2))  # seed (8)
        # B₁ + B₂ = -R₁₂, g₁B₁ + g₂B₂ = -R₂₃
        big2 = (-r23 + g1 * r12) / (g2 - g1)
        big1 = -r12 - big2
        b12 = [big1 / r12, big2 / r12]
        b23 = [g1 * big1 / r23, g2 * big2 / r23]
        # seed (1) as printed: S' = [(J₁+J₂)c₁₂ + (J₂+J₃)c₂₃]/(J₁J₂) + (J₂+J₃)c₂₃/(J₂J₃)
        s_printed = ((j1 + j2) * c12 + (j2 + j3) * c23) / (j1 * j2) + (j2 + j3) * c23 / (j2 * j3)
        p = c12 * c23 * total / (j1 * j2 * j3)
        printed = s_printed / 2 - (s_printed * s_printed / 4 - p).sqrt()
        # mode shapes (2), A₁ = 1, for each root
        shapes = [
            (
                (c12 - lam * j1) / c12,
                -c12 / c23 + (c12 + c23 - lam * j2) * (c12 - lam * j1) / (c12 * c23),
            )
            for lam in (lam1, lam2)
        ]
        return {
            "lam": (lam1, lam2),
            "beta": (float(lam1.sqrt()), float(lam2.sqrt())),
            "beta12": float(beta12_sq.sqrt()),
            "beta23": float(beta23_sq.sqrt()),
            "r12": float(r12),
            "r23": float(r23),
            "accel": float((m1 - w) / total),
            "b12": [float(v) for v in b12],
            "b23": [float(v) for v in b23],
            "sup12": float(1 + abs(b12[0]) + abs(b12[1])),
            "sup23": float(1 + abs(b23[0]) + abs(b23[1])),
            "simp19": float(2 + big2 / r12),  # (19): 2 + B₁₂(fast)/R₁₂
            "simp20": float(1 + r12 / r23 * j2 / c12 * (beta12_sq - lam1)),  # (20)
            "printed1": float(printed),
            "shapes": [(float(a2), float(a3)) for a2, a3 in shapes],
        }


def brute_max(amplitudes, frequencies, end: float) -> tuple[float, float]:
    """max of 1 + Σ b·cos(βt) on [0, end] and its time: a numpy grid of 200 points per
    fast period (at least 20001), every grid local maximum within twice the grid error
    of the best refined by scipy's bounded search (xatol 1e-14), and both ends."""
    b = np.asarray(amplitudes, dtype=float)
    w = np.asarray(frequencies, dtype=float)

    def f(t):
        return 1.0 + np.cos(np.multiply.outer(np.atleast_1d(t), w)) @ b

    n = max(20001, int(math.ceil(end * w.max() / (2 * math.pi) * 200)) + 1)
    t = np.linspace(0.0, end, n)
    v = f(t)
    h = t[1] - t[0]
    slack = float(np.sum(np.abs(b) * w * w)) * h * h
    inner = (v[1:-1] >= v[:-2]) & (v[1:-1] >= v[2:]) & (v[1:-1] >= v.max() - slack)
    best = max((float(v[0]), 0.0), (float(v[-1]), end))
    for i in np.nonzero(inner)[0] + 1:
        found = minimize_scalar(
            lambda x: -float(f(x)[0]),
            bounds=(t[i - 1], t[i + 1]),
            method="bounded",
            options={"xatol": 1e-14},
        )
        best = max(best, (float(-found.fun), float(found.x)))
    return best


def hand_from_data(data: dict[str, Any]) -> dict[str, Any]:
    h, loads = data["hoist"], data["loads"]
    return hand_hoist(
        h["drum_inertia"],
        h["sheave_inertia"],
        h["cage_inertia"],
        h["chord_stiffness"],
        h["rope_stiffness"],
        loads["drive_torque"],
        loads["load_torque"],
    )


def first_swing(hand: dict[str, Any]) -> tuple[tuple[float, float], tuple[float, float]]:
    period = 2 * math.pi / hand["beta"][0]
    return brute_max(hand["b12"], hand["beta"], period), brute_max(
        hand["b23"], hand["beta"], period
    )


# ------------------------------------------------------------------ seed reference


@pytest.fixture(scope="module")
def seed_hand() -> dict[str, Any]:
    hand = hand_from_data(SEED)
    hand["first_swing"] = first_swing(hand)
    return hand


def test_seed_frequencies_and_static_moments(cli, write_case, seed_hand) -> None:
    r = values(run_json(cli, write_case, SEED))
    hand = seed_hand
    assert r["beta1"] == pytest.approx(hand["beta"][0], rel=TIGHT)  # Decimal quadratic
    assert r["beta2"] == pytest.approx(hand["beta"][1], rel=TIGHT)
    assert r["beta1"] == pytest.approx(2.6736, abs=5e-5)  # brief §6
    assert r["beta2"] == pytest.approx(27.1045, abs=5e-5)  # brief §6
    assert r["partial_beta12"] == pytest.approx(hand["beta12"], rel=TIGHT)
    assert r["partial_beta23"] == pytest.approx(hand["beta23"], rel=TIGHT)
    assert r["frequency_ratio"] == pytest.approx(hand["beta"][1] / hand["beta"][0], rel=TIGHT)
    assert r["static_moment_12"] == pytest.approx(hand["r12"], rel=TIGHT)  # (11)
    assert r["static_moment_23"] == pytest.approx(hand["r23"], rel=TIGHT)  # (12)
    assert r["acceleration"] == pytest.approx(hand["accel"], rel=TIGHT)  # (M₁ - W)/ΣJ
    # seed (1) as printed, with its extra term: 7.029 against the correct 7.148
    assert r["beta1_squared_seed_formula"] == pytest.approx(hand["printed1"], rel=TIGHT)
    assert r["beta1_squared_seed_formula"] == pytest.approx(7.029, abs=5e-4)  # brief
    assert float(hand["lam"][0]) == pytest.approx(7.148, abs=5e-4)  # brief


def test_seed_dynamic_factors(cli, write_case, seed_hand) -> None:
    r = values(run_json(cli, write_case, SEED))
    hand = seed_hand
    (f12, t12), (f23, t23) = hand["first_swing"]
    assert r["mu12_supremum"] == pytest.approx(hand["sup12"], rel=TIGHT)  # 1 + Σ|b|
    assert r["mu23_supremum"] == pytest.approx(hand["sup23"], rel=TIGHT)
    assert r["mu12_supremum"] == pytest.approx(2.0000, abs=5e-5)  # brief
    assert r["mu23_supremum"] == pytest.approx(2.0070, abs=5e-5)  # brief
    assert r["mu12_first_swing"] == pytest.approx(f12, rel=MAXIMUM)  # grid + refinement
    assert r["mu23_first_swing"] == pytest.approx(f23, rel=MAXIMUM)
    assert r["mu12_first_swing"] == pytest.approx(1.9707, abs=5e-5)  # brief
    assert r["mu23_first_swing"] == pytest.approx(2.0067, abs=5e-5)  # brief
    assert r["mu12_first_swing_time"] == pytest.approx(t12, abs=1e-6)
    assert r["mu23_first_swing_time"] == pytest.approx(t23, abs=1e-6)
    assert r["mu12_simplified"] == pytest.approx(hand["simp19"], rel=TIGHT)  # (19)
    assert r["mu23_simplified"] == pytest.approx(hand["simp20"], rel=TIGHT)  # (20)
    assert r["mu12_simplified"] == pytest.approx(1.927, abs=1e-3)  # seed Table 1
    assert r["mu23_simplified"] == pytest.approx(2.0825, abs=1e-3)  # seed Table 1
    assert r["peak_moment_12"] == pytest.approx(hand["sup12"] * hand["r12"], rel=TIGHT)
    assert r["peak_moment_23"] == pytest.approx(hand["sup23"] * hand["r23"], rel=TIGHT)
    # default horizon: 20 periods of β₁, maxima over it by the own grid
    horizon = 20 * 2 * math.pi / hand["beta"][0]
    assert r["horizon"] == pytest.approx(horizon, rel=TIGHT)
    assert r["mu12_horizon"] == pytest.approx(
        brute_max(hand["b12"], hand["beta"], horizon)[0], rel=MAXIMUM
    )
    assert r["mu23_horizon"] == pytest.approx(
        brute_max(hand["b23"], hand["beta"], horizon)[0], rel=MAXIMUM
    )
    assert r["mu12_first_swing"] <= r["mu12_horizon"] <= r["mu12_supremum"] * (1 + 1e-15)
    assert r["mu23_first_swing"] <= r["mu23_horizon"] <= r["mu23_supremum"] * (1 + 1e-15)


def test_seed_modes_and_history_tables(cli, write_case, seed_hand) -> None:
    document = run_json(cli, write_case, case(analysis={"ode": False, "time_points": 31}))
    hand = seed_hand
    modes = section(document, "modes")["rows"]
    assert len(modes) == 2
    for j, row in enumerate(modes):
        a2, a3 = hand["shapes"][j]  # mode (2) with A₁ = 1
        assert row[0] == j + 1
        assert row[1] == pytest.approx(hand["beta"][j], rel=TIGHT)
        assert row[2] == pytest.approx(2 * math.pi / hand["beta"][j], rel=TIGHT)
        assert row[3] == pytest.approx(a2, rel=1e-10)
        assert row[4] == pytest.approx(a3, rel=1e-10)
        assert row[5] == pytest.approx(hand["b12"][j], rel=1e-10)
        assert row[6] == pytest.approx(hand["b23"][j], rel=1e-10)
    history = section(document, "history")["rows"]
    period = 2 * math.pi / hand["beta"][0]
    assert len(history) == 31
    for i, (t, mu12, mu23) in enumerate(history):
        assert t == pytest.approx(period * i / 30, rel=1e-13, abs=1e-15)
        phase = np.cos(np.array(hand["beta"]) * t)
        assert mu12 == pytest.approx(1 + phase @ hand["b12"], abs=1e-12)  # μ(t) by hand
        assert mu23 == pytest.approx(1 + phase @ hand["b23"], abs=1e-12)
    assert history[0][1] == pytest.approx(0.0, abs=1e-12)  # ropes unloaded at t = 0
    assert history[0][2] == pytest.approx(0.0, abs=1e-12)


def test_given_horizon(cli, write_case, seed_hand) -> None:
    r = values(run_json(cli, write_case, case(analysis={"ode": False, "horizon": 10.0})))
    hand = seed_hand
    assert r["horizon"] == 10.0
    assert r["mu12_horizon"] == pytest.approx(
        brute_max(hand["b12"], hand["beta"], 10.0)[0], rel=MAXIMUM
    )
    assert r["mu23_horizon"] == pytest.approx(
        brute_max(hand["b23"], hand["beta"], 10.0)[0], rel=MAXIMUM
    )


def test_seed_ode_rows_agree_with_modal_reference(cli, write_case, seed_hand) -> None:
    document = run_json(cli, write_case, case(analysis={"ode": True}))
    (f12, _), (f23, _) = seed_hand["first_swing"]
    (methods,) = [s for s in document["sections"] if s["kind"] == "methods"]
    rows = {row["method"]: row for row in methods["rows"]}
    reference = [row for row in methods["rows"] if row["reference"]]
    assert len(reference) == 1
    assert reference[0]["values"]["mu12"] == pytest.approx(f12, rel=MAXIMUM)
    assert reference[0]["values"]["mu23"] == pytest.approx(f23, rel=MAXIMUM)
    tight = [name for name in rows if name.startswith("ODE") and "1e-9" in name]
    assert len(tight) == 2  # DOP853 and Radau at rtol 1e-9
    for name in tight:
        row = rows[name]
        assert row["values"]["mu12"] == pytest.approx(f12, rel=1e-8), name
        assert row["values"]["mu23"] == pytest.approx(f23, rel=1e-8), name
        assert row["rel_errors"]["mu12"] < 1e-8 and row["rel_errors"]["mu23"] < 1e-8
    # every ODE row lands within its tolerance order of the reference
    for name, row in rows.items():
        if name.startswith("ODE"):
            rtol = float(re.search(r"rtol (\S+)", name).group(1))
            assert row["values"]["mu12"] == pytest.approx(f12, rel=10 * rtol), name
            assert row["values"]["mu23"] == pytest.approx(f23, rel=10 * rtol), name
    (simplified,) = [row for name, row in rows.items() if name.startswith("simplified")]
    hand = seed_hand
    assert simplified["values"]["mu12"] == pytest.approx(hand["simp19"], rel=TIGHT)
    assert simplified["values"]["mu23"] == pytest.approx(hand["simp20"], rel=TIGHT)


# ------------------------------------------------------------------- other loads


@pytest.mark.parametrize(
    "drive,load",
    [(1.0e6, 0.0), (5.0e5, 5.0e5), (3.0e6, 1.0e6)],
    ids=["no load W = 0", "balanced M1 = W", "M1 = 3W"],
)
def test_loads_hand_solution(cli, write_case, drive: float, load: float) -> None:
    data = case(loads={"drive_torque": drive, "load_torque": load})
    r = values(run_json(cli, write_case, data))
    hand = hand_from_data(data)
    (f12, _), (f23, _) = first_swing(hand)
    assert r["static_moment_12"] == pytest.approx(hand["r12"], rel=TIGHT)  # (11)
    assert r["static_moment_23"] == pytest.approx(hand["r23"], rel=TIGHT)  # (12)
    assert r["acceleration"] == pytest.approx(hand["accel"], rel=TIGHT, abs=1e-300)
    assert r["mu12_supremum"] == pytest.approx(hand["sup12"], rel=TIGHT)
    assert r["mu23_supremum"] == pytest.approx(hand["sup23"], rel=TIGHT)
    assert r["mu12_first_swing"] == pytest.approx(f12, rel=MAXIMUM)
    assert r["mu23_first_swing"] == pytest.approx(f23, rel=MAXIMUM)
    assert r["mu12_simplified"] == pytest.approx(hand["simp19"], rel=TIGHT)
    assert r["mu23_simplified"] == pytest.approx(hand["simp20"], rel=TIGHT)
    j1, j2, j3 = 479.15e3, 27.97e3, 156.86e3
    if load == 0.0:  # R₁₂ = M₁(J₂+J₃)/ΣJ, R₂₃ = M₁J₃/ΣJ, ε = M₁/ΣJ
        assert r["static_moment_12"] == pytest.approx(drive * (j2 + j3) / (j1 + j2 + j3))
        assert r["static_moment_23"] == pytest.approx(drive * j3 / (j1 + j2 + j3))
        assert r["acceleration"] == pytest.approx(drive / (j1 + j2 + j3))
    if drive == load:  # no acceleration: both ropes carry W
        assert r["acceleration"] == 0.0
        assert r["static_moment_12"] == pytest.approx(load, rel=1e-14)
        assert r["static_moment_23"] == pytest.approx(load, rel=1e-14)


def test_drive_below_load_has_no_answer(cli, write_case) -> None:
    path = write_case(toml_dumps(case(loads={"drive_torque": 4.0e5, "load_torque": 5.0e5})))
    result = cli("mine-hoist", path)
    assert result.exit_code == 3
    assert_no_traceback(result)
    text = result.stderr
    assert "M₁" in text and "W" in text
    assert "400000" in text and "500000" in text  # both torques named with their values
    as_json = cli("mine-hoist", path, "--json")
    assert as_json.exit_code == 3
    document = json.loads(as_json.stdout)
    assert document["status"] == "no-answer"
    assert "400000" in document["message"] and "500000" in document["message"]


# ------------------------------------------------------------------ input errors

WITH_EA_ROPE = {**ROPE, "axial_stiffness": EA}

BAD_INPUTS = {
    "both torques zero": (case(loads={"drive_torque": 0.0, "load_torque": 0.0}), r"loads\."),
    "chord stiffness missing": (case(hoist={"chord_stiffness": None}), r"hoist\.chord_stiffness"),
    "chord stiffness and EA": (
        case(hoist={"rope_stiffness": None}, rope=dict(WITH_EA_ROPE)),
        r"hoist\.chord_stiffness",
    ),
    "misspelt key": (
        case(hoist={"cage_inertia": None, "cage_inertai": 156.86e3}),
        r"hoist\.cage_inertai",
    ),
    "negative inertia": (case(hoist={"sheave_inertia": -27.97e3}), r"hoist\.sheave_inertia"),
    "sweep without EA": (
        case(rope=dict(ROPE), sweep={"heights": [410.0, 1025.0]}),
        r"sweep",
    ),
    "zero sweep height": (
        case(
            hoist={"chord_stiffness": None, "rope_stiffness": None},
            rope=dict(WITH_EA_ROPE),
            sweep={"heights": [410.0, 0.0]},
        ),
        r"sweep\.heights",
    ),
    "negative drive torque": (case(loads={"drive_torque": -1.0}), r"loads\.drive_torque"),
}


@pytest.mark.parametrize("data,path", BAD_INPUTS.values(), ids=BAD_INPUTS.keys())
def test_bad_input_exits_2_with_located_message(cli, write_case, data, path) -> None:
    file = write_case(toml_dumps(data))
    result = cli("mine-hoist", file)
    assert result.exit_code == 2, result.stdout
    assert_no_traceback(result)
    pattern = rf"^{re.escape(str(file))}(:\d+)?: error: {path}"
    assert re.search(pattern, result.stderr, re.MULTILINE), result.stderr


def test_bad_input_as_console_script(write_case) -> None:
    # the real console script: exit 2, one located message, no traceback
    file = write_case(toml_dumps(case(hoist={"chord_stiffness": None})))
    done = run_script("mine-hoist", file, "--json")
    assert done.returncode == 2
    assert "Traceback" not in done.stderr
    assert re.search(r":\d+: error: hoist\.chord_stiffness: ", done.stderr), done.stderr
    below = write_case(toml_dumps(case(loads={"drive_torque": 1.0, "load_torque": 2.0})), "b.toml")
    done = run_script("mine-hoist", below)
    assert done.returncode == 3
    assert "Traceback" not in done.stderr


# ------------------------------------------------------------------ limits


def test_light_sheave_tends_to_two_mass_chain(cli, write_case) -> None:
    # J₂ → 0: two masses J₁, J₃ on the series spring c = c₁₂c₂₃/(c₁₂+c₂₃),
    # β² = c(1/J₁ + 1/J₃), R = [M₁J₃ + W·J₁]/(J₁+J₃), μ(t) = 1 - cos βt: max 2.
    data = case(hoist={"sheave_inertia": 27.97e3 * 1e-6})
    r = values(run_json(cli, write_case, data))
    j1, j3, c12, c23, m1, w = 479.15e3, 156.86e3, 18609.2e3, 893.45e3, 1.0e6, 5.0e5
    c = c12 * c23 / (c12 + c23)
    beta = math.sqrt(c * (1 / j1 + 1 / j3))
    static = (m1 * j3 + w * j1) / (j1 + j3)
    assert r["beta1"] == pytest.approx(beta, rel=1e-6)  # two-mass limit
    assert r["static_moment_12"] == pytest.approx(static, rel=1e-6)
    assert r["static_moment_23"] == pytest.approx(static, rel=1e-6)
    assert r["mu12_first_swing"] == pytest.approx(2.0, abs=1e-6)
    assert r["mu23_first_swing"] == pytest.approx(2.0, abs=1e-6)
    assert r["mu12_first_swing_time"] == pytest.approx(math.pi / beta, rel=1e-3)
    # and exactly: the 50-digit quadratic of the three-mass chain
    hand = hand_from_data(data)
    assert r["beta1"] == pytest.approx(hand["beta"][0], rel=TIGHT)
    assert r["beta2"] == pytest.approx(hand["beta"][1], rel=TIGHT)
    assert r["mu12_supremum"] == pytest.approx(hand["sup12"], rel=TIGHT)
    assert r["mu23_supremum"] == pytest.approx(hand["sup23"], rel=TIGHT)


STIFF = case(title="chord a million times the rope", hoist={"chord_stiffness": 893.45e9})


@pytest.mark.parametrize("ode", [True, False], ids=["ode on", "ode off"])
def test_chord_a_million_times_the_rope(cli, write_case, ode: bool) -> None:
    data = copy.deepcopy(STIFF)
    data["analysis"] = {"ode": ode}
    file = write_case(toml_dumps(data))
    result = cli("mine-hoist", file, "--json")
    assert result.exit_code == 0, result.stderr
    document = strict_json(result.stdout)  # no NaN / Infinity tokens
    walk_finite(document)  # nor any non-finite float anywhere
    r = values(document)
    hand = hand_from_data(data)
    assert r["beta1"] == pytest.approx(hand["beta"][0], rel=TIGHT)  # Decimal quadratic
    assert r["beta2"] == pytest.approx(hand["beta"][1], rel=TIGHT)
    # c₁₂ → ∞: drum and sheave move as one, β₁² → c₂₃(1/(J₁+J₂) + 1/J₃)
    j1, j2, j3, c23 = 479.15e3, 27.97e3, 156.86e3, 893.45e3
    assert r["beta1"] ** 2 == pytest.approx(c23 * (1 / (j1 + j2) + 1 / j3), rel=1e-5)
    assert r["mu12_supremum"] == pytest.approx(hand["sup12"], rel=TIGHT)
    assert r["mu23_supremum"] == pytest.approx(hand["sup23"], rel=TIGHT)
    (f12, _), (f23, _) = first_swing(hand)
    assert r["mu12_first_swing"] == pytest.approx(f12, rel=MAXIMUM)
    assert r["mu23_first_swing"] == pytest.approx(f23, rel=MAXIMUM)
    # the text output says the scene is stiff (neither the title nor the file path,
    # which holds this test's name, may supply the word)
    text = cli("mine-hoist", file)
    assert text.exit_code == 0
    body = text.stdout.replace(data["title"], "").replace(str(file), "")
    assert re.search(r"stiff", body, re.IGNORECASE), "no word on stiffness in the output"


# ------------------------------------------------------------- rope reduction


def hand_reduction(
    j1, j2, j3, c12, c23, rho, radius, chord, height, sheave_scale=1.0
) -> dict[str, Any]:
    """Seed (2)-(5) in 50-digit decimals: β₁ of the bare chain, mode (2), node,
    reduced inertias; J₂ reduced by (R/R_ns)² (sheave_scale), rope terms not."""
    with localcontext() as ctx:
        ctx.prec = 50
        j1, j2, j3, c12, c23 = (D(v) for v in (j1, j2, j3, c12, c23))
        j2 = j2 * D(sheave_scale)
        rho, radius, chord, height = (D(v) for v in (rho, radius, chord, height))
        lam, _ = quadratic(j1, j2, j3, c12, c23)
        a2 = (c12 - lam * j1) / c12
        a3 = -c12 / c23 + (c12 + c23 - lam * j2) * (c12 - lam * j1) / (c12 * c23)
        # own check of (2): Holzer from the drum, A₃ = A₂ - λ(J₁ + J₂A₂)/c₂₃
        assert abs(a3 - (a2 - lam * (j1 + j2 * a2) / c23)) < Decimal("1e-40") * abs(a3)
        upper = height * a2 / (a2 - a3)
        lower = height - upper
        k = rho * radius * radius / 3
        reduced = (
            j1 + (2 - j1 * lam / c12) * chord * k,
            j2 + chord * k + upper * k,
            j3 + lower * k,
        )
        rayleigh = k * (chord * (1 + a2 + a2 * a2) + height * (a2 * a2 + a2 * a3 + a3 * a3))
        lumped = (reduced[0] - j1) + (reduced[1] - j2) * a2 * a2 + (reduced[2] - j3) * a3 * a3
        assert abs(lumped - rayleigh) < Decimal("1e-40") * rayleigh  # identity, exact
        printed = (j2 / D(sheave_scale) + chord * k + upper * k) * D(sheave_scale)
        return {
            "bare_beta1": float(lam.sqrt()),
            "a2": float(a2),
            "a3": float(a3),
            "upper": float(upper),
            "lower": float(lower),
            "reduced": tuple(float(v) for v in reduced),
            "printed4": float(printed),
            "k": float(k),
        }


def test_rope_reduction_with_given_stiffnesses(cli, write_case) -> None:
    data = case(rope=dict(ROPE))
    r = values(run_json(cli, write_case, data))
    j1, j2, j3, c12, c23 = 479.15e3, 27.97e3, 156.86e3, 18609.2e3, 893.45e3
    hand = hand_reduction(j1, j2, j3, c12, c23, 7.5, 3.0, 49.2, 1025.0)
    assert r["rope_chord_mass"] == pytest.approx(7.5 * 49.2, rel=1e-15)  # ρL₁
    assert r["rope_vertical_mass"] == pytest.approx(7.5 * 1025.0, rel=1e-15)  # ρH
    assert r["bare_beta1"] == pytest.approx(hand["bare_beta1"], rel=TIGHT)
    assert r["mode_a2"] == pytest.approx(hand["a2"], rel=1e-11)  # (2)
    assert r["mode_a3"] == pytest.approx(hand["a3"], rel=1e-11)  # (2)
    assert r["node_from_sheave"] == pytest.approx(hand["upper"], rel=1e-11)  # L₂
    assert r["node_to_cage"] == pytest.approx(hand["lower"], rel=1e-11)  # L₃
    assert r["node_from_sheave"] + r["node_to_cage"] == pytest.approx(1025.0, rel=1e-15)
    keys = ("drum_inertia_reduced", "sheave_inertia_reduced", "cage_inertia_reduced")
    for key, expected in zip(keys, hand["reduced"], strict=True):
        assert r[key] == pytest.approx(expected, rel=TIGHT), key  # (3)-(5)
    for key, expected in zip(
        ("drum_inertia", "sheave_inertia", "cage_inertia"), hand["reduced"], strict=True
    ):
        assert r[key] == pytest.approx(expected, rel=TIGHT), key  # the chain uses J'
    assert r["chord_stiffness"] == c12 and r["rope_stiffness"] == c23
    # Rayleigh identity with the program's own numbers: the lumping is exact for the
    # bare mode shape, kinetic energy of the rope Σ (ΔJ)·A² = ρR²/3·[L₁(1+A₂+A₂²) +
    # H(A₂²+A₂A₃+A₃²)]
    a2, a3, k = r["mode_a2"], r["mode_a3"], hand["k"]
    lumped = (
        (r["drum_inertia_reduced"] - j1)
        + (r["sheave_inertia_reduced"] - j2) * a2**2
        + (r["cage_inertia_reduced"] - j3) * a3**2
    )
    exact = k * (49.2 * (1 + a2 + a2**2) + 1025.0 * (a2**2 + a2 * a3 + a3**2))
    assert lumped == pytest.approx(exact, rel=1e-9)
    # the dynamics run on the reduced chain
    dyn = hand_hoist(*hand["reduced"], c12, c23, 1.0e6, 5.0e5)
    assert r["beta1"] == pytest.approx(dyn["beta"][0], rel=TIGHT)
    assert r["beta2"] == pytest.approx(dyn["beta"][1], rel=TIGHT)
    assert r["mu12_supremum"] == pytest.approx(dyn["sup12"], rel=TIGHT)
    assert r["mu23_supremum"] == pytest.approx(dyn["sup23"], rel=TIGHT)
    assert r["beta1"] < r["bare_beta1"]  # added mass lowers the frequency


def test_rope_reduction_from_axial_stiffness_and_sheave_radius(cli, write_case) -> None:
    rope = {**ROPE, "axial_stiffness": EA, "sheave_radius": 2.5}
    data = case(hoist={"chord_stiffness": None, "rope_stiffness": None}, rope=rope)
    document = run_json(cli, write_case, data)
    r = values(document)
    c12, c23 = EA * 9.0 / 49.2, EA * 9.0 / 1025.0  # c = EA·R²/L
    scale = (3.0 / 2.5) ** 2  # (R/R_ns)²
    assert r["chord_stiffness"] == pytest.approx(c12, rel=1e-15)
    assert r["rope_stiffness"] == pytest.approx(c23, rel=1e-15)
    hand = hand_reduction(479.15e3, 27.97e3, 156.86e3, c12, c23, 7.5, 3.0, 49.2, 1025.0, scale)
    assert r["bare_beta1"] == pytest.approx(hand["bare_beta1"], rel=TIGHT)
    assert r["node_from_sheave"] == pytest.approx(hand["upper"], rel=1e-11)
    assert r["drum_inertia_reduced"] == pytest.approx(hand["reduced"][0], rel=TIGHT)
    assert r["sheave_inertia_reduced"] == pytest.approx(hand["reduced"][1], rel=TIGHT)
    assert r["cage_inertia_reduced"] == pytest.approx(hand["reduced"][2], rel=TIGHT)
    # the note quotes (4) as printed, rope terms scaled by (R/R_ns)² too
    notes = " ".join(note["text"] for note in document["notes"])
    assert f"{hand['printed4']:.6g}" in notes


# ------------------------------------------------------------------ height sweep


def test_sweep_rows_match_hand_chain_per_height(cli, write_case) -> None:
    heights = [410.0, 615.0, 820.0, 1025.0]
    data = case(
        hoist={"chord_stiffness": None, "rope_stiffness": None},
        rope={**ROPE, "axial_stiffness": EA},
        sweep={"heights": heights},
    )
    document = run_json(cli, write_case, data)
    table = section(document, "sweep")
    assert [c["label"] for c in table["columns"]][:3] == ["H", "β₁", "β₂"]
    assert len(table["rows"]) == len(heights)
    j1, j2, j3 = 479.15e3, 27.97e3, 156.86e3
    c12 = EA * 9.0 / 49.2  # EA·R²/L₁, the same at every height
    for row, height in zip(table["rows"], heights, strict=True):
        c23 = EA * 9.0 / height  # EA·R²/H
        reduction = hand_reduction(j1, j2, j3, c12, c23, 7.5, 3.0, 49.2, height)
        hand = hand_hoist(*reduction["reduced"], c12, c23, 1.0e6, 5.0e5)
        (f12, _), (f23, _) = first_swing(hand)
        h, beta1, beta2, fs12, fs23, sup12, sup23, s19, s20, e19, e20 = row
        assert h == height
        assert beta1 == pytest.approx(hand["beta"][0], rel=TIGHT), height
        assert beta2 == pytest.approx(hand["beta"][1], rel=TIGHT), height
        assert fs12 == pytest.approx(f12, rel=MAXIMUM), height
        assert fs23 == pytest.approx(f23, rel=MAXIMUM), height
        assert sup12 == pytest.approx(hand["sup12"], rel=TIGHT), height
        assert sup23 == pytest.approx(hand["sup23"], rel=TIGHT), height
        assert s19 == pytest.approx(hand["simp19"], rel=TIGHT), height
        assert s20 == pytest.approx(hand["simp20"], rel=TIGHT), height
        assert e19 == pytest.approx(100 * (hand["simp19"] / hand["sup12"] - 1), abs=1e-9)
        assert e20 == pytest.approx(100 * (hand["simp20"] / hand["sup23"] - 1), abs=1e-9)
    # the row at the case's own H repeats the main results
    r = values(document)
    last = table["rows"][-1]
    assert last[1] == pytest.approx(r["beta1"], rel=1e-15)
    assert last[5] == pytest.approx(r["mu12_supremum"], rel=1e-15)
    # the slow frequency falls as the rope lengthens (c₂₃ ∝ 1/H, more rope mass)
    betas = [row[1] for row in table["rows"]]
    assert betas == sorted(betas, reverse=True)


def test_results_are_finite_for_seed_with_rope(cli, write_case) -> None:
    data = case(
        hoist={"chord_stiffness": None, "rope_stiffness": None},
        rope={**ROPE, "axial_stiffness": EA},
    )
    result = cli("mine-hoist", write_case(toml_dumps(data)), "--json")
    assert result.exit_code == 0, result.stderr
    walk_finite(strict_json(result.stdout))


def test_case_file_path_is_reported(cli, tmp_path: Path) -> None:
    # a missing file is an input error, not a bug
    result = cli("mine-hoist", tmp_path / "absent.toml")
    assert result.exit_code == 2
    assert_no_traceback(result)


def test_node_off_the_vertical_rope_has_no_answer(cli, write_case) -> None:
    # H = 1 m: c₂₃ = EA·R²/H ≫ c₁₂, the lowest mode bends the chord and (2) gives
    # A₂, A₃ of one sign, so (3)-(5) (node on the vertical rope) do not apply.
    data = case(
        hoist={"chord_stiffness": None, "rope_stiffness": None},
        rope={**ROPE, "length": 1.0, "axial_stiffness": EA},
    )
    c12, c23 = EA * 9.0 / 49.2, EA * 9.0 / 1.0  # EA·R²/L
    hand = hand_reduction(479.15e3, 27.97e3, 156.86e3, c12, c23, 7.5, 3.0, 49.2, 1.0)
    assert not hand["a2"] > 0.0 > hand["a3"]  # own check: the node is not below the sheave
    result = cli("mine-hoist", write_case(toml_dumps(data)), "--json")
    assert result.exit_code == 3
    assert_no_traceback(result)
    document = json.loads(result.stdout)
    assert document["status"] == "no-answer"
    assert "node" in document["message"]
    assert f"{hand['a2']:.4g}" in document["message"]  # A₂ quoted
    assert f"{hand['a3']:.4g}" in document["message"]  # A₃ quoted
