"""Independent physics tests of ``mdcalc clutch`` (brief PROBLEMS.md §10, seed 004:
Fokin, Gavrilenko, Shishkarev, adaptive friction clutch with differentiated pairs).

Every expected value is computed inside this file from the brief's formulas, written
out again here (``own_*`` helpers below), or is a number printed in the brief (2.877,
4.091) or in the seed digest's hand table of Fig. 2. Nothing is copied from the
program's output. The program's own functions ``gain_bound``, ``torques``,
``criterion``, ``bound_by_bisection`` and ``gain_bound_one_material`` are only ever
*checked* against the own formulas, never used to make an expected value.

Model (brief §10), with b = C·z₂f₂, S₀ = z₁f₁ + z₂f₂, S₁ = z₁η₁f₁ + z₂η₂f₂:
  (18) F_p = F_n·b/(1 + b)             (19) T_n = F_n·R_cp·S₀/(1 + b)
  (20) T_c = F_n·R_cp·S₁/(1 + b)       (23) F₁p = F_p·η₂
  (25) T_a = F_n·R_cp·S₁·(1 + b(1 - η₂))/(1 + b)
  stable iff 4(T_a - T_c) < π·T_n, i.e. (26) C < C_max = π·S₀/[4·z₂f₂·S₁·(1 - η₂)];
  η₁ = η₂ = η: (27) C_max = π/(4·z₂·f₂·η(1 - η)); η₂ = 1: unbounded.
  Ramp geometry: C = (R_cp/r)·tan α.
"""

from __future__ import annotations

import math
import random
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from tomli_w import dumps as toml_dumps

from mdcalc.methods import NotApplicable
from mdcalc.problems.clutch import (
    Friction,
    bound_by_bisection,
    criterion,
    gain_bound,
    gain_bound_one_material,
    torques,
)
from tests.conftest import CASES, assert_no_traceback, run_script, strict_json, walk_finite

TIGHT = 1e-12
PI = math.pi

# The seed's Fig. 2 data (z₁ = 1, z₂ = 3, f₁ = 0.3, f₂ = 0.4).
FIG2 = {"z1": 1, "z2": 3, "f1": 0.3, "f2": 0.4}

# ----------------------------------------------------------------------- own formulas


def own_cmax(z1: int, z2: int, f1: float, f2: float, e1: float, e2: float) -> float:
    """(26), written out again; inf when η₂ = 1."""
    if e2 == 1.0:
        return math.inf
    s0 = z1 * f1 + z2 * f2
    s1 = z1 * e1 * f1 + z2 * e2 * f2
    return PI * s0 / (4.0 * z2 * f2 * s1 * (1.0 - e2))


def own_cmax_one(z2: int, f: float, eta: float) -> float:
    """(27)."""
    return PI / (4.0 * z2 * f * eta * (1.0 - eta))


def own_torques(
    z1: int, z2: int, f1: float, f2: float, e1: float, e2: float, fn: float, r: float, c: float
) -> dict[str, float]:
    """(18)-(25) from the brief: forces [N], torques [N·m]."""
    b = c * z2 * f2
    s0 = z1 * f1 + z2 * f2
    s1 = z1 * e1 * f1 + z2 * e2 * f2
    fp = fn * b / (1.0 + b)
    tn = fn * r * s0 / (1.0 + b)
    tc = fn * r * s1 / (1.0 + b)
    ta = fn * r * s1 * (1.0 + b * (1.0 - e2)) / (1.0 + b)
    return {
        "b": b,
        "spreading_force": fp,
        "pack_force": fn - fp,
        "limit_torque": tn,
        "sliding_torque": tc,
        "relaxed_spreading_force": fp * e2,
        "first_amplitude": ta,
        "torque_margin": PI * tn - 4.0 * (ta - tc),
    }


# ------------------------------------------------------------------------- case files


def case(
    z1: int = 1,
    z2: int = 3,
    f1: float = 0.3,
    f2: float = 0.4,
    e1: float = 0.65,
    e2: float = 0.8,
    clutch: dict[str, Any] | None = None,
    curves: dict[str, Any] | None = None,
) -> dict[str, Any]:
    data: dict[str, Any] = {
        "problem": "clutch",
        "pairs": {
            "driving": z1,
            "driven": z2,
            "driving_friction": f1,
            "driven_friction": f2,
            "driving_ratio": e1,
            "driven_ratio": e2,
        },
    }
    if clutch is not None:
        data["clutch"] = clutch
    if curves is not None:
        data["curves"] = curves
    return data


def put(tmp_path: Path, data: dict[str, Any], name: str = "case.toml") -> Path:
    path = tmp_path / name
    path.write_text(toml_dumps(data), encoding="utf-8")
    return path


def run_json(cli, path: Path) -> dict[str, Any]:
    result = cli("clutch", path, "--json")
    assert_no_traceback(result)
    assert result.exit_code == 0, result.stderr
    doc = strict_json(result.stdout)
    walk_finite(doc)
    return doc


def values(doc: dict[str, Any]) -> dict[str, Any]:
    return {key: item["value"] for key, item in doc["results"].items()}


def section(doc: dict[str, Any], kind: str) -> dict[str, Any] | None:
    found = [s for s in doc["sections"] if s["kind"] == kind]
    assert len(found) <= 1
    return found[0] if found else None


def method_row(doc: dict[str, Any], starts: str) -> dict[str, Any]:
    table = section(doc, "methods")
    assert table is not None
    rows = [row for row in table["rows"] if row["method"].startswith(starts)]
    assert len(rows) == 1, [row["method"] for row in table["rows"]]
    return rows[0]


def rel(expected: float, tol: float = TIGHT) -> Any:
    return pytest.approx(expected, rel=tol)


NONFINITE = re.compile(r"\b(nan|inf|infinity)\b", re.IGNORECASE)


# ---------------------------------------------------------------- brief's references


@pytest.mark.parametrize(("eta", "printed"), [(0.65, 2.877), (0.8, 4.091)])
def test_brief_references_one_material(cli, tmp_path: Path, eta: float, printed: float) -> None:
    # Brief §10: z₂ = 3, f = 0.4: C_max = π/(4.8·η(1 - η)) = 2.877 at 0.65, 4.091 at 0.8.
    hand = PI / (4.8 * eta * (1.0 - eta))
    assert hand == pytest.approx(printed, abs=5e-4)
    got = values(run_json(cli, put(tmp_path, case(e1=eta, e2=eta))))
    assert got["c_max"] == pytest.approx(printed, abs=5e-4)
    assert got["c_max"] == rel(hand)
    assert got["c_max_one_material"] == rel(hand)
    assert got["unconditionally_stable"] is False
    assert got["static_sum"] == rel(1.5)
    assert got["sliding_sum"] == rel(eta * 1.5)


def test_brief_reference_through_console_script(tmp_path: Path) -> None:
    proc = run_script("clutch", CASES / "clutch" / "one_material_065.toml", "--json")
    assert proc.returncode == 0, proc.stderr
    doc = strict_json(proc.stdout)
    walk_finite(doc)
    assert values(doc)["c_max"] == rel(PI / (4.0 * 3 * 0.4 * 0.65 * 0.35))


def test_fig2_differentiated_hand_values(cli, tmp_path: Path) -> None:
    # Fig. 2 data, η₁ = 0.65, η₂ = 0.8, F_n = 1000 N, R_cp = 0.1 m, C = 2.
    data = case(clutch={"gain": 2.0, "spring_force": 1000.0, "mean_radius": 0.1})
    got = values(run_json(cli, put(tmp_path, data)))
    own = own_torques(1, 3, 0.3, 0.4, 0.65, 0.8, 1000.0, 0.1, 2.0)
    # Hand: b = 2.4, S₀ = 1.5, S₁ = 0.195 + 0.96 = 1.155.
    assert own["limit_torque"] == rel(100.0 * 1.5 / 3.4)
    assert own["sliding_torque"] == rel(100.0 * 1.155 / 3.4)
    assert own["first_amplitude"] == rel(100.0 * 1.155 / 3.4 * 1.48)
    for key in (
        "spreading_force",
        "pack_force",
        "limit_torque",
        "sliding_torque",
        "relaxed_spreading_force",
        "first_amplitude",
        "torque_margin",
    ):
        assert got[key] == rel(own[key]), key
    assert got["feedback"] == rel(2.4)
    assert got["c_max"] == rel(PI * 1.5 / (4.0 * 1.2 * 1.155 * 0.2))
    assert got["gain_margin"] == rel(PI * 1.5 / (4.0 * 1.2 * 1.155 * 0.2) / 2.0)
    assert got["overshoot"] == rel(own["first_amplitude"] / own["limit_torque"])
    assert got["stable"] is True


def test_ramp_geometry_gain(cli, tmp_path: Path) -> None:
    # C = (R_cp/r)·tan α: R_cp = 0.12, r = 0.02, α = 30° -> 6/√3 = 2√3.
    data = case(
        z1=2,
        z2=4,
        f1=0.35,
        f2=0.3,
        e1=0.7,
        e2=0.6,
        clutch={
            "rolling_radius": 0.02,
            "ramp_angle_deg": 30.0,
            "mean_radius": 0.12,
            "spring_force": 2000.0,
        },
    )
    got = values(run_json(cli, put(tmp_path, data)))
    gain = 2.0 * math.sqrt(3.0)
    assert got["gain"] == rel(gain)
    cmax = own_cmax(2, 4, 0.35, 0.3, 0.7, 0.6)
    assert got["c_max"] == rel(cmax)
    assert gain > cmax
    assert got["stable"] is False
    own = own_torques(2, 4, 0.35, 0.3, 0.7, 0.6, 2000.0, 0.12, gain)
    assert got["torque_margin"] == rel(own["torque_margin"])
    assert got["torque_margin"] < 0.0
    assert got["limit_torque"] == rel(own["limit_torque"])
    assert got["first_amplitude"] == rel(own["first_amplitude"])


# --------------------------------------------------------- (26) on random valid inputs

z1s = st.integers(min_value=0, max_value=100)
z2s = st.integers(min_value=1, max_value=100)
frictions = st.floats(min_value=1e-3, max_value=2.0)
ratios = st.floats(min_value=1e-6, max_value=1.0 - 1e-6)
HYP = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@HYP
@given(z1=z1s, z2=z2s, f1=frictions, f2=frictions, e1=ratios, e2=ratios)
def test_gain_bound_is_26(z1: int, z2: int, f1: float, f2: float, e1: float, e2: float) -> None:
    assert gain_bound(Friction(z1, z2, f1, f2, e1, e2)) == rel(own_cmax(z1, z2, f1, f2, e1, e2))


@HYP
@given(
    z1=z1s,
    z2=z2s,
    f1=frictions,
    f2=frictions,
    e1=ratios,
    e2=ratios,
    fn=st.floats(min_value=1e-3, max_value=1e9),
    r=st.floats(min_value=1e-3, max_value=1e3),
    c=st.floats(min_value=0.0, max_value=1e6),
)
def test_torques_are_18_to_25_and_margin_identity(
    z1: int, z2: int, f1: float, f2: float, e1: float, e2: float, fn: float, r: float, c: float
) -> None:
    t = torques(Friction(z1, z2, f1, f2, e1, e2), fn, r, c)
    own = own_torques(z1, z2, f1, f2, e1, e2, fn, r, c)
    assert t.spreading == rel(own["spreading_force"])
    assert t.limit == rel(own["limit_torque"])
    assert t.sliding == rel(own["sliding_torque"])
    assert t.relaxed_spreading == rel(own["relaxed_spreading_force"])
    assert t.amplitude == rel(own["first_amplitude"])
    # pack = F_n - F_p = F_n/(1 + b): compare on the scale of F_n (cancellation at big b).
    assert t.pack == pytest.approx(own["pack_force"], rel=1e-9, abs=1e-12 * fn)
    # The identity C_max/C = π·T_n/(4(T_a - T_c)), all from own numbers.
    cmax = own_cmax(z1, z2, f1, f2, e1, e2)
    gap = own["first_amplitude"] - own["sliding_torque"]
    # (T_a - T_c)/T_c = b(1 - η₂): keep it away from cancellation in the difference.
    if own["b"] * (1.0 - e2) > 1e-4:
        assert cmax / c == pytest.approx(PI * own["limit_torque"] / (4.0 * gap), rel=1e-9)


@HYP
@given(z1=z1s, z2=z2s, f1=frictions, f2=frictions, e1=ratios, e2=ratios)
def test_criterion_changes_sign_at_cmax(
    z1: int, z2: int, f1: float, f2: float, e1: float, e2: float
) -> None:
    fr = Friction(z1, z2, f1, f2, e1, e2)
    cmax = own_cmax(z1, z2, f1, f2, e1, e2)
    for factor, stable in ((1.0 - 1e-7, True), (1.0 + 1e-7, False)):
        own = own_torques(z1, z2, f1, f2, e1, e2, 1.0, 1.0, cmax * factor)
        assert (own["torque_margin"] > 0.0) is stable
        assert (criterion(fr, cmax * factor) > 0.0) is stable


@HYP
@given(z1=z1s, z2=z2s, f1=frictions, f2=frictions, e1=ratios, e2=ratios)
def test_bisection_agrees_with_26(
    z1: int, z2: int, f1: float, f2: float, e1: float, e2: float
) -> None:
    cmax = own_cmax(z1, z2, f1, f2, e1, e2)
    assume(abs(cmax / 1e6 - 1.0) > 1e-9)
    fr = Friction(z1, z2, f1, f2, e1, e2)
    if cmax > 1e6:
        # The criterion holds for every allowed gain: nothing to bisect.
        with pytest.raises(NotApplicable):
            bound_by_bisection(fr)
    else:
        assert bound_by_bisection(fr) == rel(cmax)


@HYP
@given(z2=z2s, f=frictions, eta=ratios, z1=z1s, f1=frictions)
def test_27_is_26_with_equal_ratios_and_has_its_minimum_at_half(
    z2: int, f: float, eta: float, z1: int, f1: float
) -> None:
    own = own_cmax_one(z2, f, eta)
    assert gain_bound_one_material(z2, f, eta) == rel(own)
    # (27) holds whatever z₁ and f₁ are (S₁ = η·S₀).
    assert gain_bound(Friction(z1, z2, f1, f, eta, eta)) == rel(own)
    # η(1 - η) ≤ 1/4: the least bound is π/(z₂f₂), at η = 1/2.
    floor = PI / (z2 * f)
    assert gain_bound_one_material(z2, f, 0.5) == rel(floor)
    assert own >= floor * (1.0 - 1e-12)


def random_cases(count: int) -> list[tuple[int, int, float, float, float, float]]:
    rng = random.Random(20110510)  # date the seed's paper was received
    cases = []
    for _ in range(count):
        cases.append(
            (
                rng.randint(0, 12),
                rng.randint(1, 12),
                round(rng.uniform(0.05, 1.0), 6),
                round(rng.uniform(0.05, 1.0), 6),
                round(rng.uniform(0.3, 0.99), 6),
                round(rng.uniform(0.3, 0.99), 6),
            )
        )
    return cases


@pytest.mark.parametrize(("z1", "z2", "f1", "f2", "e1", "e2"), random_cases(6))
def test_cli_random_cases(
    cli, tmp_path: Path, z1: int, z2: int, f1: float, f2: float, e1: float, e2: float
) -> None:
    fn, radius = 750.0, 0.085
    cmax = own_cmax(z1, z2, f1, f2, e1, e2)
    gain = 0.6 * cmax
    data = case(z1, z2, f1, f2, e1, e2, {"gain": gain, "spring_force": fn, "mean_radius": radius})
    doc = run_json(cli, put(tmp_path, data))
    got = values(doc)
    assert got["static_sum"] == rel(z1 * f1 + z2 * f2)
    assert got["sliding_sum"] == rel(z1 * e1 * f1 + z2 * e2 * f2)
    assert got["c_max"] == rel(cmax)
    own = own_torques(z1, z2, f1, f2, e1, e2, fn, radius, gain)
    for key in ("spreading_force", "limit_torque", "sliding_torque", "first_amplitude"):
        assert got[key] == rel(own[key]), key
    assert got["relaxed_spreading_force"] == rel(own["spreading_force"] * e2)
    assert got["torque_margin"] == rel(own["torque_margin"], 1e-10)
    # Gain margin: C_max/C, and the identity π·T_n/(4(T_a - T_c)) from own torques.
    assert got["gain_margin"] == rel(1.0 / 0.6)
    identity = PI * own["limit_torque"] / (4.0 * (own["first_amplitude"] - own["sliding_torque"]))
    assert got["gain_margin"] == rel(identity, 1e-10)
    assert got["stable"] is True
    # Methods: bisection of the criterion agrees with (26) to ~1e-12.
    assert method_row(doc, "(26) closed")["values"]["c_max"] == rel(cmax)
    assert method_row(doc, "criterion")["values"]["c_max"] == rel(cmax)
    row27 = method_row(doc, "(27)")
    if e1 != e2:
        assert row27["values"] == {}
        assert "not applicable" in row27["note"]


# ----------------------------------------------------- stability verdict across C_max


@pytest.mark.parametrize(
    "pairs",
    [
        (1, 3, 0.3, 0.4, 0.65, 0.8),
        (1, 3, 0.3, 0.4, 0.7, 0.7),
        (2, 4, 0.35, 0.3, 0.7, 0.6),
        (0, 2, 0.3, 0.25, 0.5, 0.9),
        (5, 1, 0.6, 0.1, 0.95, 0.3),
    ],
)
@pytest.mark.parametrize("offset", [1e-9, 1e-6, 1e-3])
def test_verdict_flips_across_cmax(cli, tmp_path: Path, pairs: tuple, offset: float) -> None:
    cmax = own_cmax(*pairs)
    for factor, stable in ((1.0 - offset, True), (1.0 + offset, False)):
        gain = cmax * factor
        clutch = {"gain": gain, "spring_force": 1000.0, "mean_radius": 0.1}
        doc = run_json(cli, put(tmp_path, case(*pairs, clutch=clutch)))
        got = values(doc)
        assert got["stable"] is stable, (factor, got)
        assert (got["torque_margin"] > 0.0) is stable
        own = own_torques(*pairs, 1000.0, 0.1, gain)
        assert (own["torque_margin"] > 0.0) is stable
        assert got["gain_margin"] == rel(1.0 / factor, 1e-11)
        warned = any("above C_max" in note["text"] for note in doc["notes"])
        assert warned is (not stable)


def test_zero_gain_is_stable_and_torques_collapse(cli, tmp_path: Path) -> None:
    # C = 0 (plain safety clutch): F_p = 0, T_a = T_c, the criterion is π·T_n > 0.
    clutch = {"gain": 0.0, "spring_force": 1000.0, "mean_radius": 0.1}
    got = values(run_json(cli, put(tmp_path, case(clutch=clutch))))
    assert got["stable"] is True
    assert got["spreading_force"] == 0.0
    assert got["pack_force"] == rel(1000.0)
    assert got["limit_torque"] == rel(100.0 * 1.5)
    assert got["first_amplitude"] == rel(got["sliding_torque"])
    assert got["sliding_torque"] == rel(100.0 * (0.3 * 0.65 + 1.2 * 0.8))
    assert got["torque_margin"] == rel(PI * 150.0)
    assert got.get("gain_margin") in (None, "unbounded")


# ------------------------------------------------------------------- methods table


def test_27_row_applies_only_with_equal_ratios(cli, tmp_path: Path) -> None:
    doc = run_json(cli, put(tmp_path, case(e1=0.65, e2=0.8)))
    row = method_row(doc, "(27)")
    assert row["values"] == {}
    assert "not applicable" in row["note"]
    assert "c_max_one_material" not in values(doc)

    doc = run_json(cli, put(tmp_path, case(e1=0.72, e2=0.72), "same.toml"))
    own = own_cmax_one(3, 0.4, 0.72)
    assert method_row(doc, "(27)")["values"]["c_max"] == rel(own)
    assert values(doc)["c_max_one_material"] == rel(own)
    assert values(doc)["c_max"] == rel(own)


@pytest.mark.parametrize(
    "pairs",
    [
        (1, 3, 0.3, 0.4, 0.65, 0.8),
        (100, 100, 2.0, 2.0, 0.5, 0.5),  # C_max = π/200, far below 1
        (0, 1, 0.3, 0.01, 0.5, 0.999),  # C_max ≈ 7.9e4
        (3, 7, 1.1, 0.05, 0.2, 0.05),
    ],
)
def test_bisection_row_agrees_with_26(cli, tmp_path: Path, pairs: tuple) -> None:
    doc = run_json(cli, put(tmp_path, case(*pairs)))
    cmax = own_cmax(*pairs)
    row = method_row(doc, "criterion")
    assert row["values"]["c_max"] == rel(cmax)
    assert row["rel_errors"]["c_max"] < 1e-12
    assert method_row(doc, "(26) closed")["values"]["c_max"] == rel(cmax)
    # The scan's garbled "(26) without π" row is off by exactly the factor π.
    assert method_row(doc, "(26) without")["values"]["c_max"] == rel(cmax / PI)


# ------------------------------------------------------------------- Fig. 2 curves


def fig2_curves(cli, tmp_path: Path, **curves: Any) -> dict[str, Any]:
    doc = run_json(cli, put(tmp_path, case(e1=0.65, e2=0.8, curves=curves)))
    table = section(doc, "table")
    assert table is not None and table["key"] == "curves"
    return table


def test_fig2_curves_match_own_26(cli, tmp_path: Path) -> None:
    n = 31  # step 0.005 over 0.65 … 0.8: 0.735 is a row
    table = fig2_curves(
        cli,
        tmp_path,
        eta_from=0.65,
        eta_to=0.8,
        points=n,
        driven_ratios=[0.8, 0.735],
        driving_ratios=[0.65],
    )
    labels = [c["label"] for c in table["columns"]]
    assert len(labels) == 5
    assert "0.8" in labels[1] and "0.735" in labels[2] and "0.65" in labels[3]
    z1, z2, f1, f2 = FIG2["z1"], FIG2["z2"], FIG2["f1"], FIG2["f2"]
    rows = table["rows"]
    assert len(rows) == n
    for k, row in enumerate(rows):
        eta = row[0]
        assert eta == pytest.approx(0.65 + 0.15 * k / (n - 1), abs=1e-14)
        assert row[1] == rel(own_cmax(z1, z2, f1, f2, eta, 0.8))  # curve 1
        assert row[2] == rel(own_cmax(z1, z2, f1, f2, eta, 0.735))  # curve 2
        assert row[3] == rel(own_cmax(z1, z2, f1, f2, 0.65, eta))  # curve 3
        assert row[4] == rel(own_cmax_one(z2, f2, eta))  # curve 4, (27)
        assert row[4] == rel(own_cmax(z1, z2, f1, f2, eta, eta))
    # Crossings with the base curve 4 where η₁ = η₂: c1 at 0.8, c2 at 0.735, c3 at 0.65.
    by_eta = {round(row[0], 9): row for row in rows}
    assert by_eta[0.8][1] == rel(by_eta[0.8][4])
    assert by_eta[0.735][2] == rel(by_eta[0.735][4])
    assert by_eta[0.65][3] == rel(by_eta[0.65][4])
    # c1 at η₁ = 0.65 and c3 at η₂ = 0.8 are one point (0.65, 0.8).
    assert by_eta[0.65][1] == rel(by_eta[0.8][3])
    assert by_eta[0.65][1] == rel(own_cmax(1, 3, 0.3, 0.4, 0.65, 0.8))
    # The digest's hand table (4 decimals).
    hand = {
        0.65: (4.2500, 3.4398, 2.8769, 2.8769),
        0.70: (4.1955, 3.3926, 3.1618, 3.1167),
        0.735: (4.1582, 3.3603, 3.4398, 3.3603),
        0.75: (4.1424, 3.3466, 3.5863, 3.4907),
        0.80: (4.0906, 3.3019, 4.2500, 4.0906),
    }
    for eta, expected in hand.items():
        assert by_eta[eta][1:] == pytest.approx(list(expected), abs=6e-5), eta
    # Seed's qualitative claims: c1, c2 fall with η₁, c3, c4 rise; c2 < c1 (smaller η₂
    # tightens the bound); for η₁ < η₂ the bound is above the base curve 4.
    for before, after in zip(rows, rows[1:], strict=False):
        assert after[1] < before[1] and after[2] < before[2]
        assert after[3] > before[3] and after[4] > before[4]
    for row in rows:
        assert row[2] < row[1]
        if row[0] < 0.8 - 1e-9:
            assert row[1] > row[4]
        if row[0] > 0.65 + 1e-9:
            assert row[3] > row[4]


def test_curves_default_to_the_case_ratios(cli, tmp_path: Path) -> None:
    table = fig2_curves(cli, tmp_path, eta_from=0.6, eta_to=0.9, points=4)
    assert len(table["columns"]) == 4
    for row in table["rows"]:
        eta = row[0]
        assert row[1] == rel(own_cmax(1, 3, 0.3, 0.4, eta, 0.8))
        assert row[2] == rel(own_cmax(1, 3, 0.3, 0.4, 0.65, eta))
        assert row[3] == rel(own_cmax_one(3, 0.4, eta))


def test_curves_reach_eta_one_as_unbounded(cli, tmp_path: Path) -> None:
    table = fig2_curves(cli, tmp_path, eta_from=0.9, eta_to=1.0, points=3)
    last = table["rows"][-1]
    assert last[0] == rel(1.0)
    assert last[1] == rel(own_cmax(1, 3, 0.3, 0.4, 1.0, 0.8))  # η₁ = 1: finite
    assert last[2] == "unbounded"  # η₂ = 1
    assert last[3] == "unbounded"


def test_minimum_of_27_is_at_half(cli, tmp_path: Path) -> None:
    # Base curve over 0.1 … 0.9 in steps of 0.01: least at η = 0.5, π/(z₂f₂).
    table = fig2_curves(cli, tmp_path, eta_from=0.1, eta_to=0.9, points=81)
    column = [(row[-1], row[0]) for row in table["rows"]]
    least, at = min(column)
    assert at == pytest.approx(0.5, abs=1e-12)
    assert least == rel(PI / 1.2)
    # Symmetric about 1/2: η(1 - η) is.
    for (a, _), (b, _) in zip(column, reversed(column), strict=True):
        assert a == rel(b, 1e-9)


def test_minimum_of_27_through_a_case(cli, tmp_path: Path) -> None:
    got = values(run_json(cli, put(tmp_path, case(z1=4, z2=5, f1=0.7, f2=0.25, e1=0.5, e2=0.5))))
    assert got["c_max"] == rel(PI / 1.25)
    assert got["c_max_one_material"] == rel(PI / 1.25)


# ------------------------------------------------------------------------- η₂ = 1


@pytest.mark.parametrize("e1", [0.3, 0.7, 1.0])
@pytest.mark.parametrize("gain", [0.5, 1e4, 1e6])
def test_no_drop_in_driven_pairs_is_unbounded(cli, tmp_path: Path, e1: float, gain: float) -> None:
    fn, radius = 500.0, 0.08
    data = case(2, 2, 0.3, 0.35, e1, 1.0, {"gain": gain, "spring_force": fn, "mean_radius": radius})
    doc = run_json(cli, put(tmp_path, data))
    got = values(doc)
    assert got["c_max"] == "unbounded"
    assert got["unconditionally_stable"] is True
    assert got["stable"] is True
    assert got["gain_margin"] == "unbounded"
    own = own_torques(2, 2, 0.3, 0.35, e1, 1.0, fn, radius, gain)
    assert own["first_amplitude"] == own["sliding_torque"]
    assert got["first_amplitude"] == rel(got["sliding_torque"])
    assert got["torque_margin"] == rel(PI * own["limit_torque"])
    assert got["torque_margin"] > 0.0
    assert not any("above C_max" in note["text"] for note in doc["notes"])
    if e1 == 1.0:
        assert got["c_max_one_material"] == "unbounded"
    text = cli("clutch", put(tmp_path, data, "text.toml"))
    assert text.exit_code == 0
    assert "unbounded" in text.stdout
    assert not NONFINITE.search(text.stdout)


# ----------------------------------------------------------------------- bad input

BASE = """problem = "clutch"

[pairs]
driving = 1
driven = 3
driving_friction = 0.3
driven_friction = 0.4
driving_ratio = 0.65
driven_ratio = 0.8
"""

BAD = [
    ("misspelt key", BASE.replace("driven_friction", "driven_frictoin"), r"driven_frictoin"),
    ("eta above 1", BASE.replace("driving_ratio = 0.65", "driving_ratio = 1.2"), r"driving_ratio"),
    ("eta zero", BASE.replace("driven_ratio = 0.8", "driven_ratio = 0.0"), r"driven_ratio"),
    (
        "negative friction",
        BASE.replace("driving_friction = 0.3", "driving_friction = -0.3"),
        r"driving_friction",
    ),
    ("z2 zero", BASE.replace("driven = 3", "driven = 0"), r"pairs\.driven\b"),
    ("z2 negative", BASE.replace("driven = 3", "driven = -3"), r"pairs\.driven\b"),
    ("float z", BASE.replace("driving = 1", "driving = 1.0"), r"pairs\.driving\b"),
    ("float z2", BASE.replace("driven = 3", "driven = 2.5"), r"pairs\.driven\b"),
    ("bool number", BASE.replace("driven_friction = 0.4", "driven_friction = true"), "driven_f"),
    ("nan", BASE.replace("driving_ratio = 0.65", "driving_ratio = nan"), r"driving_ratio"),
    ("inf", BASE.replace("driven_friction = 0.4", "driven_friction = inf"), r"driven_friction"),
    # A quoted "3" is a dimensionless quantity string (issue 9) and is taken; a
    # string that is no number is refused at its key.
    ("string", BASE.replace("driven = 3", 'driven = "three"'), r"pairs\.driven\b"),
    ("string fraction", BASE.replace("driven = 3", 'driven = "2.5"'), r"pairs\.driven\b"),
    ("missing key", BASE.replace("driving_ratio = 0.65\n", ""), r"driving_ratio"),
    (
        "ramp 90",
        BASE + "[clutch]\nrolling_radius = 0.05\nramp_angle_deg = 90.0\nmean_radius = 0.1\n",
        r"ramp_angle_deg",
    ),
    (
        "ramp 0",
        BASE + "[clutch]\nrolling_radius = 0.05\nramp_angle_deg = 0.0\nmean_radius = 0.1\n",
        r"ramp_angle_deg",
    ),
    (
        "gain and rolling radius",
        BASE + "[clutch]\ngain = 2.0\nrolling_radius = 0.05\nmean_radius = 0.1\n",
        r"clutch\.(gain|rolling_radius)",
    ),
    (
        "gain and ramp angle",
        BASE + "[clutch]\ngain = 2.0\nramp_angle_deg = 30.0\n",
        r"clutch\.(gain|ramp_angle_deg)",
    ),
    (
        "rolling radius without mean radius",
        BASE + "[clutch]\nrolling_radius = 0.05\nramp_angle_deg = 30.0\n",
        r"mean_radius",
    ),
    (
        "ramp without rolling radius",
        BASE + "[clutch]\nramp_angle_deg = 30.0\nmean_radius = 0.1\n",
        r"rolling_radius",
    ),
    (
        "spring force without mean radius",
        BASE + "[clutch]\ngain = 2.0\nspring_force = 1000.0\n",
        r"mean_radius",
    ),
    ("negative gain", BASE + "[clutch]\ngain = -1.0\n", r"clutch\.gain"),
    ("gain above limit", BASE + "[clutch]\ngain = 1.0e7\n", r"clutch\.gain"),
    ("nan gain", BASE + "[clutch]\ngain = nan\n", r"clutch\.gain"),
    (
        "no feedback",
        BASE + "[clutch]\nspring_force = 10.0\nmean_radius = 0.1\n",
        r"clutch\b.*(gain|feedback)",
    ),
    (
        "negative spring force",
        BASE + "[clutch]\ngain = 1.0\nspring_force = -5.0\nmean_radius = 0.1\n",
        r"spring_force",
    ),
    ("eta_to equal", BASE + "[curves]\neta_from = 0.7\neta_to = 0.7\n", r"eta_to"),
    ("eta_to below", BASE + "[curves]\neta_from = 0.8\neta_to = 0.65\n", r"eta_to"),
    ("eta_to above 1", BASE + "[curves]\neta_to = 1.5\n", r"eta_to"),
    ("curve ratio", BASE + "[curves]\ndriven_ratios = [0.8, 1.5]\n", r"driven_ratios"),
    ("curve ratio zero", BASE + "[curves]\ndriving_ratios = [0.0]\n", r"driving_ratios"),
    ("one point", BASE + "[curves]\npoints = 1\n", r"points"),
    ("wrong problem", BASE.replace('"clutch"', '"mount"'), r"problem\b.*mount"),
]


@pytest.mark.parametrize(("what", "text", "field"), BAD, ids=[b[0] for b in BAD])
def test_bad_input_exits_2_naming_the_field(
    cli, write_case, what: str, text: str, field: str
) -> None:
    for options in ((), ("--json",)):
        result = cli("clutch", write_case(text), *options)
        assert_no_traceback(result)
        assert result.exit_code == 2, (what, result.stdout, result.stderr)
        assert re.search(field, result.stderr), (what, result.stderr)
        assert "error" in result.stderr
        assert result.stdout == "" or "Traceback" not in result.stdout


# ------------------------------------------------------------------------ extremes

EXTREMES = [
    ("gain 0", case(clutch={"gain": 0.0, "spring_force": 1e3, "mean_radius": 0.1})),
    ("gain 1e6", case(clutch={"gain": 1e6, "spring_force": 1e3, "mean_radius": 0.1})),
    (
        "gain 1e6, F 1e9, R 1e3",
        case(clutch={"gain": 1e6, "spring_force": 1e9, "mean_radius": 1e3}),
    ),
    ("spring 1e9", case(clutch={"gain": 2.0, "spring_force": 1e9, "mean_radius": 0.1})),
    (
        "eta tiny both",
        case(e1=1e-9, e2=1e-9, clutch={"gain": 3.0, "spring_force": 1e3, "mean_radius": 0.1}),
    ),
    (
        "eta2 tiny",
        case(e1=0.65, e2=1e-9, clutch={"gain": 3.0, "spring_force": 1e3, "mean_radius": 0.1}),
    ),
    (
        "eta1 tiny",
        case(e1=1e-9, e2=0.8, clutch={"gain": 3.0, "spring_force": 1e3, "mean_radius": 0.1}),
    ),
    (
        "eta2 next to 1",
        case(e2=1.0 - 1e-12, clutch={"gain": 1e6, "spring_force": 1e9, "mean_radius": 1e3}),
    ),
    (
        "eta1 = eta2 next to 1",
        case(e1=1.0 - 1e-12, e2=1.0 - 1e-12, clutch={"gain": 5.0}),
    ),
    (
        "z1 = 0, gain 1e6",
        case(z1=0, z2=2, f1=0.3, f2=0.25, e1=0.5, e2=0.9, clutch={"gain": 1e6}),
    ),
    (
        "largest pack",
        case(
            z1=100,
            z2=100,
            f1=2.0,
            f2=2.0,
            e1=1e-9,
            e2=1.0 - 1e-12,
            clutch={"gain": 1e6, "spring_force": 1e9, "mean_radius": 1e3},
        ),
    ),
    (
        "ramp near 90",
        case(
            clutch={
                "rolling_radius": 0.05,
                "ramp_angle_deg": 89.9,
                "mean_radius": 0.1,
                "spring_force": 1e3,
            }
        ),
    ),
    (
        "ramp tiny",
        case(
            clutch={
                "rolling_radius": 0.05,
                "ramp_angle_deg": 1e-9,
                "mean_radius": 0.1,
                "spring_force": 1e3,
            }
        ),
    ),
    (
        "fine curves",
        case(curves={"eta_from": 1e-9, "eta_to": 1.0, "points": 1001}),
    ),
]


@pytest.mark.parametrize(("what", "data"), EXTREMES, ids=[e[0] for e in EXTREMES])
def test_extremes_stay_finite(cli, tmp_path: Path, what: str, data: dict[str, Any]) -> None:
    path = put(tmp_path, data)
    text = cli("clutch", path)
    assert_no_traceback(text)
    assert text.exit_code == 0, (what, text.stderr)
    assert not NONFINITE.search(text.stdout), what
    got = values(run_json(cli, path))
    p = data["pairs"]
    pairs = (
        p["driving"],
        p["driven"],
        p["driving_friction"],
        p["driven_friction"],
        p["driving_ratio"],
        p["driven_ratio"],
    )
    cmax = own_cmax(*pairs)
    assert got["c_max"] == rel(cmax, 1e-9)
    clutch = data.get("clutch")
    if clutch is None:
        return
    if "gain" in clutch:
        gain = clutch["gain"]
    else:
        gain = clutch["mean_radius"] / clutch["rolling_radius"]
        gain *= math.tan(math.radians(clutch["ramp_angle_deg"]))
        assert got["gain"] == rel(gain, 1e-12)
    assert got["stable"] is (gain < cmax)
    if gain > 0.0:
        assert got["gain_margin"] == rel(cmax / gain, 1e-9)
    if "spring_force" in clutch:
        own = own_torques(*pairs, clutch["spring_force"], clutch["mean_radius"], gain)
        for key in ("spreading_force", "limit_torque", "sliding_torque", "first_amplitude"):
            assert got[key] == rel(own[key], 1e-9), key
        assert (got["torque_margin"] > 0.0) is got["stable"]


# ------------------------------------------------------------- bugs found (xfail)


@pytest.mark.parametrize(
    "clutch",
    [
        {"gain": 1e-308},
        {"rolling_radius": 1.0, "ramp_angle_deg": 1e-307, "mean_radius": 1.0},
        {"rolling_radius": 1e-308, "ramp_angle_deg": 45.0, "mean_radius": 1e3, "spring_force": 1.0},
        {"rolling_radius": 1e-3, "ramp_angle_deg": 89.9999, "mean_radius": 1e3},
    ],
    ids=["gain 1e-308", "ramp 1e-307 deg", "ramp gain overflows", "ramp gain 5.7e11"],
)
def test_gain_out_of_range_is_an_input_error(cli, tmp_path: Path, clutch: dict[str, Any]) -> None:
    # Found by these tests: a tiny gain overflowed C_max/C to inf (exit 70 with
    # --json) and the ramp-geometry gain escaped the 1e6 bound (exit 70). Both are
    # now input errors that name the key.
    for extra in ((), ("--json",)):
        result = cli("clutch", put(tmp_path, case(clutch=clutch)), *extra)
        assert_no_traceback(result)
        assert result.exit_code == 2, result.stdout
        assert re.search(r"clutch\.(gain|ramp_angle_deg|rolling_radius)", result.stderr), (
            result.stderr
        )


# ------------------------------------------------------------------------ imports

PROBE = """
import sys
sys.argv = ["mdcalc", *{args!r}]
from mdcalc.cli.launch import main
try:
    main()
except SystemExit:
    pass
heavy = sorted({{m.split(".")[0] for m in sys.modules}} & {{"numpy", "scipy"}})
print("CLUTCH", "mdcalc.problems.clutch" in sys.modules, file=sys.stderr)
print("HEAVY", heavy, file=sys.stderr)
"""


def test_clutch_imports_no_numpy_or_scipy(tmp_path: Path) -> None:
    data = case(
        clutch={"gain": 2.0, "spring_force": 1e3, "mean_radius": 0.1},
        curves={"eta_from": 0.65, "eta_to": 0.8, "points": 7, "driven_ratios": [0.8, 0.735]},
    )
    path = put(tmp_path, data)
    for options in ((), ("--json",)):
        args = ["clutch", str(path), *options]
        done = subprocess.run(
            [sys.executable, "-X", "importtime", "-c", PROBE.format(args=args)],
            capture_output=True,
            text=True,
            timeout=120,
        )
        lines = done.stderr.strip().splitlines()
        assert lines[-1] == "HEAVY []", lines[-1]
        assert lines[-2] == "CLUTCH True"
        imported = [line.split("|")[-1].strip() for line in lines if line.startswith("import time")]
        # (importlib.import_module, used to load the problem, is not logged by
        # -X importtime; the sys.modules line above shows the module did load.)
        assert not [m for m in imported if m.split(".")[0] in ("numpy", "scipy")]
        assert "internal error" not in done.stderr
        assert "Traceback" not in done.stderr
