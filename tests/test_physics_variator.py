"""Independent physics tests of ``mdcalc variator`` (brief §7, seed lecture 000 §8.2–8.5:
anti-resonance absorber, induction motor as a spring-damper, overrunning clutch,
impulse-variator transfer functions, two- and three-mass periodic states, centrifugal
pendulum absorber).

Every expected value below is computed in this file, never copied from the program:

* absorber: (8.38) A₁ = M₀(c_g/J₂ - ω²)/(J₁Δ), A₂ = M₀(c_g/J₂)/(J₁Δ),
  Δ = (c_g/J₂)(c/J₁ - ω²) - ω²((c + c_g)/J₁ - ω²) in exact ``fractions``; the
  resonances as the roots of Δ = 0 in ω² (50-digit ``decimal``); the useful band both
  from its quadratic ω⁴ - (a + d + b/2)ω² + ad = 0 and by scipy's brentq on
  |A₁| = M₀/|c - J₁ω²| written out; damping through numpy's complex 2×2 solve of
  the equations of motion and a brute-force grid + bounded search for the minimum;
* motor: (8.40)–(8.41) with S_H = (n - n_H)/n written out (brief §7b), c_D = 2·P·M_K;
* clutch: M = c₀ξⁿ; the least-squares slope ∫Mξ dξ/∫ξ² dξ by scipy's ``quad``, the
  errors as the maximum of |line - curve|/M_max on a dense grid refined by a bounded
  search;
* mechanism: (8.46) written out at 50 digits (``decimal``, sine by its Taylor series),
  the mean of Π′ over the stroke by ``quad``;
* drive: the clutch equation J·q'' + b·q' + c·q = M_c + J·ω²Π″(ωt) with the sawtooth
  Π″ = 2a₀(α - α_c) written out here; its periodic state by integrating from rest with
  scipy's ``solve_ivp`` (DOP853, rtol 1e-12) stroke by stroke until the transient has
  died out, or (undamped, or a lightly damped three-mass mode) as the fixed point of the
  period map from scipy's ``expm`` of the augmented first-order system, checked by one
  more ``solve_ivp`` period; a stiff clutch by the hand decomposition "ramp + free
  decay from the jump";
* anti-resonance: the tuning c₂' = (zω)²J₂J₃'/(J₂ + J₃') from the harmonic balance of
  the 2×2 system at zω (numpy complex solve, built here), natural frequencies from the
  characteristic quadratic in 50-digit ``decimal``;
* pendulum: L = R/n² (seed 000 §8.5: R = 0.1 m, n = 4 gives L = 6.25 mm), the mass
  (8.56), the large-swing order against the period of θ'' = -n²ω² sin θ integrated here
  and against scipy's complete elliptic integral K.
"""

from __future__ import annotations

import copy
import math
import re
from decimal import Decimal, getcontext, localcontext
from fractions import Fraction
from typing import Any

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.linalg import expm
from scipy.optimize import brentq, minimize_scalar
from scipy.special import ellipk
from tomli_w import dumps as toml_dumps

from tests.conftest import assert_no_traceback, run_script, strict_json, walk_finite

KGF_M = 9.80665  # N·m per kgf·m (standard gravity, the seed's unit)

# ----------------------------------------------------------------------------- cases

# Tuned absorber: c/J₁ = ω² = c_g/J₂ = 400 (the disk alone would be in resonance).
ABSORBER = {
    "inertia": 2.0,
    "stiffness": 800.0,
    "absorber_inertia": 0.2,
    "torque_amplitude": 100.0,
    "frequency": 20.0,
}
# The seed's drive (brief §7e): z = 4, n₁ = 1000 rpm, i_c = 5.4054 (n₂ = 185 rpm),
# J = 1.55 kg·m², c = 8.9e5 kgf·m/rad, ψ = 0.6, M_c = 300 N·m.
MECHANISM = {"mechanisms": 4, "input_speed_rpm": 1000.0, "mean_ratio": 1000.0 / 185.0}
DRIVE = {
    "driven_inertia": 1.55,
    "load_torque": 300.0,
    "clutch_stiffness_kgfm": 8.9e5,
    "clutch_loop_area_ratio": 0.6,
    "harmonics": [1, 100],
}
# J₃' = i²J₃ = 4·11.625 = 46.5 = 30·J₂
ANTIRESONANCE = {"machine_inertia": 11.625, "ratio": 2.0}


def variator(**sections: Any) -> dict[str, Any]:
    data: dict[str, Any] = {"problem": "variator"}
    for name, values in sections.items():
        data[name] = copy.deepcopy(values)
    return data


def with_(base: dict[str, Any], **changes: Any) -> dict[str, Any]:
    """A copy of a section with keys changed; a value of None deletes the key."""
    out = copy.deepcopy(base)
    for key, value in changes.items():
        if value is None:
            out.pop(key, None)
        else:
            out[key] = value
    return out


# ----------------------------------------------------------------------------- helpers


def run_json(cli, write_case, data: dict[str, Any]) -> dict[str, Any]:
    result = cli("variator", write_case(toml_dumps(data)), "--json")
    assert result.exit_code == 0, (result.stdout, result.stderr)
    return strict_json(result.stdout)


def values(document: dict[str, Any]) -> dict[str, Any]:
    return {key: q["value"] for key, q in document["results"].items()}


def section(document: dict[str, Any], key: str) -> dict[str, Any]:
    (found,) = [s for s in document["sections"] if s.get("key") == key]
    return found


def method_rows(document: dict[str, Any], key: str) -> dict[str, dict[str, Any]]:
    return {row["method"]: row for row in section(document, key)["rows"]}


def F(x: float) -> Fraction:
    """The decimal number as written in the case file, exactly (0.2 is 1/5)."""
    return Fraction(repr(float(x)))


def D(x: float | Fraction) -> Decimal:
    if isinstance(x, Fraction):
        return Decimal(x.numerator) / Decimal(x.denominator)
    return Decimal(repr(float(x)))


def quadratic_roots(s: Decimal, p: Decimal) -> tuple[Decimal, Decimal]:
    """Roots of x² - s·x + p = 0 (both positive), the small one as 2p/(s + √(s² - 4p))."""
    root = (s * s - 4 * p).sqrt()
    return 2 * p / (s + root), (s + root) / 2


def test_three_mass_natural_frequencies_over_wide_scenes_by_hand() -> None:
    # ω² of the three-mass model with the driver held, the roots of
    # J₂J₃'x² - (c₁J₃' + c₂'(J₂ + J₃'))x + c₁c₂' = 0 at 50 digits, over 300 scenes
    # whose stiffnesses span four decades and inertias three: each frequency to
    # 2e-15 (numpy's eigvals of M⁻¹K had the lower one 5e-12 off on such scenes)
    from mdcalc.problems.variator.drive import DriveScene, ThreeMass
    from mdcalc.problems.variator.transfer import Transfer

    rng = np.random.default_rng(8)
    n = 300
    j2, j3 = rng.uniform(0.01, 1.0, n), 10 ** rng.uniform(-2, 1, n)
    c1, c2 = 10 ** rng.uniform(3, 7, n), 10 ** rng.uniform(3, 7, n)
    drive = DriveScene(100.0, Transfer(0.5, 5.0, -0.1, 0.2), j2, c1, 1.0, 10.0)
    low, high = ThreeMass(drive, j3, c2, 1.0, 1.0).natural_frequencies()
    with localcontext() as ctx:
        ctx.prec = 50
        for i in range(n):
            a2, a3, k1, k2 = D(j2[i]), D(j3[i]), D(c1[i]), D(c2[i])
            small, large = quadratic_roots(
                (k1 * a3 + k2 * (a2 + a3)) / (a2 * a3), k1 * k2 / (a2 * a3)
            )
            assert low[i] == pytest.approx(float(small.sqrt()), rel=2e-15)
            assert high[i] == pytest.approx(float(large.sqrt()), rel=2e-15)


# ----------------------------------------------------------------------------- absorber


def hand_absorber(j1, c, j2, cg, m0, omega) -> dict[str, Any]:
    """(8.38) in exact fractions; resonances and band edges at 50 digits."""
    j1, c, j2, cg, m0, w = (F(v) for v in (j1, c, j2, cg, m0, omega))
    x = w * w
    a, b, d = c / j1, cg / j1, cg / j2
    delta = d * (a - x) - x * ((c + cg) / j1 - x)
    out: dict[str, Any] = {}
    if delta != 0:
        a1 = m0 * (d - x) / (j1 * delta)
        a2 = m0 * d / (j1 * delta)
        out.update(a1=a1, a2=a2, moment=abs(cg * (a2 - a1)))
    out["delta"] = delta
    out["untuned"] = None if c == j1 * x else m0 / abs(c - j1 * x)
    with localcontext() as ctx:
        ctx.prec = 50
        da, db, dd = D(a), D(b), D(d)
        # Δ = 0: x² - (a + b + d)x + ad = 0 (Δ expanded: (a - x)(d - x) - b·x)
        low, high = quadratic_roots(da + db + dd, da * dd)
        out["resonances"] = (float(low.sqrt()), float(high.sqrt()))
        low, high = quadratic_roots(da + dd + db / 2, da * dd)
        out["band"] = (float(low.sqrt()), float(high.sqrt()))
    return out


def complex_amplitudes(j1, c, j2, cg, bg, m0, omega) -> tuple[complex, complex]:
    """The equations of motion at e^{iωt}, k_g = c_g + iωb_g:
    (c + k_g - J₁ω²)A₁ - k_g·A₂ = M₀,  -k_g·A₁ + (k_g - J₂ω²)A₂ = 0."""
    kg = cg + 1j * omega * bg
    matrix = np.array([[c + kg - j1 * omega**2, -kg], [-kg, kg - j2 * omega**2]])
    a1, a2 = np.linalg.solve(matrix, np.array([m0, 0.0], dtype=complex))
    return complex(a1), complex(a2)


def band_by_root_finding(j1, c, j2, cg, m0, low, high) -> list[float]:
    """Where |A₁(ω)| = M₀/|c - J₁ω²|: with (8.38) multiplied by |J₁Δ|·|c - J₁ω²|/M₀
    (finite at the resonances), h(ω) = |(d - x)(c - J₁x)| - |J₁Δ| = 0, x = ω²; the
    sign changes of h on a fine grid polished by brentq. M₀ cancels."""

    def h(w: float) -> float:
        x = w * w
        d = cg / j2
        delta = d * (c / j1 - x) - x * ((c + cg) / j1 - x)
        return abs((d - x) * (c - j1 * x)) - abs(j1 * delta)

    grid = np.linspace(low, high, 20001)
    v = np.array([h(float(w)) for w in grid])
    roots = []
    for i in np.flatnonzero(np.sign(v[:-1]) * np.sign(v[1:]) < 0):
        roots.append(brentq(h, float(grid[i]), float(grid[i + 1]), xtol=1e-15, rtol=1e-15))
    return roots


def test_tuned_absorber_by_hand(cli, write_case) -> None:
    r = values(run_json(cli, write_case, variator(absorber=ABSORBER)))
    hand = hand_absorber(2.0, 800.0, 0.2, 80.0, 100.0, 20.0)
    # (8.39): c_g = J₂ω² = 0.2·400
    assert r["absorber_stiffness"] == pytest.approx(80.0, rel=1e-15)
    # tuned: A₁ = 0 exactly (not round-off), A₂ = M₀/c_g, the shaft carries M₀
    assert hand["a1"] == 0
    assert r["absorber_a1"] == 0.0
    assert float(abs(hand["a2"])) == pytest.approx(100.0 / 80.0, rel=1e-15)
    assert r["absorber_a2"] == pytest.approx(float(abs(hand["a2"])), rel=1e-14)
    assert r["absorber_moment"] == pytest.approx(100.0, rel=1e-14)
    assert r["absorber_static"] == pytest.approx(100.0 / 800.0, rel=1e-15)
    # c/J₁ = ω²: the disk without the absorber would be in resonance
    assert r["absorber_untuned"] == "unbounded"
    low, high = hand["resonances"]
    assert r["absorber_resonance_low"] == pytest.approx(low, rel=1e-14)
    assert r["absorber_resonance_high"] == pytest.approx(high, rel=1e-14)
    # by hand: x² - 840x + 160000 = 0 and x² - 820x + 160000 = 0 (band: 320 and 500)
    assert low**2 == pytest.approx(420.0 - math.sqrt(16400.0), rel=1e-14)
    assert r["absorber_band_low"] == pytest.approx(math.sqrt(320.0), rel=1e-14)
    assert r["absorber_band_high"] == pytest.approx(math.sqrt(500.0), rel=1e-14)


@pytest.mark.parametrize(
    "j1,c,j2,cg,m0,omega",
    [
        (2.0, 1000.0, 0.2, 90.0, 100.0, 20.0),  # detuned stiff absorber
        (2.0, 1000.0, 0.2, 60.0, 100.0, 20.0),  # detuned soft absorber
        (0.7, 350.0, 0.05, 30.0, 12.5, 33.0),  # ω above both resonances
        (5.0, 2.0e4, 1.3, 5.0e3, 1.0e3, 9.0),  # ω below both resonances
    ],
)
def test_detuned_absorber_against_8_38(cli, write_case, j1, c, j2, cg, m0, omega) -> None:
    data = {
        "inertia": j1,
        "stiffness": c,
        "absorber_inertia": j2,
        "absorber_stiffness": cg,
        "torque_amplitude": m0,
        "frequency": omega,
    }
    document = run_json(cli, write_case, variator(absorber=data))
    r = values(document)
    hand = hand_absorber(j1, c, j2, cg, m0, omega)
    assert r["absorber_stiffness"] == cg
    assert r["absorber_a1"] == pytest.approx(float(abs(hand["a1"])), rel=1e-13)
    assert r["absorber_a2"] == pytest.approx(float(abs(hand["a2"])), rel=1e-13)
    assert r["absorber_moment"] == pytest.approx(float(hand["moment"]), rel=1e-13)
    # the shaft moment is what accelerates J₂: c_g|A₂ - A₁| = J₂ω²|A₂|
    assert r["absorber_moment"] == pytest.approx(j2 * omega**2 * r["absorber_a2"], rel=1e-12)
    assert r["absorber_untuned"] == pytest.approx(float(hand["untuned"]), rel=1e-14)
    assert r["absorber_static"] == pytest.approx(m0 / c, rel=1e-15)
    low, high = hand["resonances"]
    assert r["absorber_resonance_low"] == pytest.approx(low, rel=1e-14)
    assert r["absorber_resonance_high"] == pytest.approx(high, rel=1e-14)
    assert r["absorber_band_low"] == pytest.approx(hand["band"][0], rel=1e-14)
    assert r["absorber_band_high"] == pytest.approx(hand["band"][1], rel=1e-14)
    # the band from its definition, by root finding on (8.38) itself
    roots = band_by_root_finding(j1, c, j2, cg, m0, 0.2 * low, 2.0 * high)
    assert len(roots) == 2
    assert r["absorber_band_low"] == pytest.approx(roots[0], rel=1e-10)
    assert r["absorber_band_high"] == pytest.approx(roots[1], rel=1e-10)
    # the three methods of the Methods table agree with the hand values
    for row in section(document, "absorber")["rows"]:
        if not row["values"]:  # a method that says it does not apply here
            continue
        assert row["values"]["a1"] == pytest.approx(float(abs(hand["a1"])), rel=1e-12), row
        assert row["values"]["a2"] == pytest.approx(float(abs(hand["a2"])), rel=1e-12), row


@pytest.mark.parametrize("detune", [0.0, 1e-10, -1e-7, 1e-4])
def test_near_tuned_absorber_shaft(cli, write_case, detune) -> None:
    # J₂ω² = 0.3·49 = 14.7 exactly in decimals; a given c_g = 14.7 is the tuned absorber
    # (A₁ = 0), a c_g off by a relative δ leaves A₁ ∝ (c_g/J₂ - ω²), which (8.38) in
    # exact fractions gives to the last digit; the program's float subtraction of two
    # nearly equal numbers may lose about eps/δ of it
    cg = 14.7 * (1.0 + detune)
    data = {
        "inertia": 2.0,
        "stiffness": 1000.0,
        "absorber_inertia": 0.3,
        "absorber_stiffness": cg,
        "torque_amplitude": 100.0,
        "frequency": 7.0,
    }
    r = values(run_json(cli, write_case, variator(absorber=data)))
    hand = hand_absorber(2.0, 1000.0, 0.3, cg, 100.0, 7.0)
    if detune == 0.0:
        assert hand["a1"] == 0
        assert r["absorber_a1"] == 0.0
    else:
        assert hand["a1"] != 0
        assert r["absorber_a1"] == pytest.approx(
            float(abs(hand["a1"])), rel=max(1e-12, 1e-14 / abs(detune))
        )
    assert r["absorber_a2"] == pytest.approx(float(abs(hand["a2"])), rel=1e-13)


def test_tuning_frequency_sets_the_absorber_shaft(cli, write_case) -> None:
    # c_g = J₂·ω_t² with ω_t = 19 rad/s ≠ ω: detuned, A₁ ≠ 0
    data = with_(ABSORBER, tuning_frequency=19.0)
    r = values(run_json(cli, write_case, variator(absorber=data)))
    cg = 0.2 * 19.0**2
    assert r["absorber_stiffness"] == pytest.approx(cg, rel=1e-15)
    hand = hand_absorber(2.0, 800.0, 0.2, cg, 100.0, 20.0)
    assert r["absorber_a1"] == pytest.approx(float(abs(hand["a1"])), rel=1e-12)
    assert r["absorber_a1"] > 0.0
    assert r["absorber_a2"] == pytest.approx(float(abs(hand["a2"])), rel=1e-12)
    # tuning_frequency = ω is the tuned absorber again
    tuned = values(
        run_json(cli, write_case, variator(absorber=with_(ABSORBER, tuning_frequency=20.0)))
    )
    assert tuned["absorber_a1"] == 0.0
    assert tuned["absorber_stiffness"] == pytest.approx(80.0, rel=1e-15)


def test_absorber_curve_rows_follow_8_38(cli, write_case) -> None:
    data = {
        "inertia": 2.0,
        "stiffness": 1000.0,
        "absorber_inertia": 0.2,
        "absorber_stiffness": 90.0,
        "torque_amplitude": 100.0,
        "frequency": 20.0,
        "curve_points": 41,
    }
    table = section(run_json(cli, write_case, variator(absorber=data)), "absorber_curve")
    assert len(table["rows"]) == 41
    for w, _, alone, a1, a2 in table["rows"]:
        hand = hand_absorber(2.0, 1000.0, 0.2, 90.0, 100.0, w)
        assert alone == pytest.approx(float(hand["untuned"]), rel=1e-12)
        assert a1 == pytest.approx(float(abs(hand["a1"])), rel=1e-10)
        assert a2 == pytest.approx(float(abs(hand["a2"])), rel=1e-10)


@pytest.mark.parametrize("bg", [0.5, 1.0])
def test_damped_absorber_against_complex_solve_and_grid_minimum(cli, write_case, bg) -> None:
    data = with_(ABSORBER, absorber_damping=bg, stiffness=1000.0)
    r = values(run_json(cli, write_case, variator(absorber=data)))
    a1, a2 = complex_amplitudes(2.0, 1000.0, 0.2, 80.0, bg, 100.0, 20.0)
    assert r["absorber_a1"] == pytest.approx(abs(a1), rel=1e-12)
    assert r["absorber_a2"] == pytest.approx(abs(a2), rel=1e-12)
    assert r["absorber_a1"] > 0.0  # damping: no exact zero any more
    # the shaft (spring and damper) moment accelerates J₂: |k_g(A₂ - A₁)| = J₂ω²|A₂|
    assert r["absorber_moment"] == pytest.approx(0.2 * 400.0 * abs(a2), rel=1e-12)
    # smallest |A₁| between the (undamped) resonances: dense log grid + bounded search
    low, high = hand_absorber(2.0, 1000.0, 0.2, 80.0, 100.0, 20.0)["resonances"]

    def size(w: float) -> float:
        return abs(complex_amplitudes(2.0, 1000.0, 0.2, 80.0, bg, 100.0, w)[0])

    grid = np.geomspace(low, high, 20001)[1:-1]
    v = np.array([size(float(w)) for w in grid])
    k = int(np.argmin(v))
    found = minimize_scalar(
        size, bounds=(grid[k - 1], grid[k + 1]), method="bounded", options={"xatol": 1e-13}
    )
    assert r["absorber_minimum"] == pytest.approx(found.fun, rel=1e-9)
    assert r["absorber_minimum"] <= r["absorber_a1"] * (1.0 + 1e-12)
    # the minimum is flat: its place is known to about √eps
    assert r["absorber_minimum_frequency"] == pytest.approx(found.x, rel=1e-6)
    assert low < r["absorber_minimum_frequency"] < high


def test_heavily_damped_absorber_reports_no_false_minimum(cli, write_case) -> None:
    # b_g = 2: |A₁| falls all the way through the band to the upper resonance, so there
    # is no minimum inside. A reported absorber_minimum must then be the smallest |A₁|
    # in the band (its edge value); a value at some inner point is wrong. Leaving the
    # key out (no minimum inside) is fine.
    data = with_(ABSORBER, absorber_damping=2.0, stiffness=1000.0)
    r = values(run_json(cli, write_case, variator(absorber=data)))
    low, high = hand_absorber(2.0, 1000.0, 0.2, 80.0, 100.0, 20.0)["resonances"]
    grid = np.geomspace(low, high, 20001)[1:-1]
    v = np.array([abs(complex_amplitudes(2.0, 1000.0, 0.2, 80.0, 2.0, 100.0, w)[0]) for w in grid])
    assert int(np.argmin(v)) == len(grid) - 1  # monotonic: the smallest is at the edge
    if "absorber_minimum" in r:
        assert r["absorber_minimum"] <= float(v.min()) * (1.0 + 1e-9)
    # the amplitudes at ω are still the complex solve's
    a1, _ = complex_amplitudes(2.0, 1000.0, 0.2, 80.0, 2.0, 100.0, 20.0)
    assert r["absorber_a1"] == pytest.approx(abs(a1), rel=1e-12)


def test_two_disk_resonance_is_unbounded(cli, write_case) -> None:
    # J₁ = 1, c = 2, J₂ = 0.5, c_g = 1, ω = 1: a = 2, b = 1, d = 2, x = 1:
    # Δ = 2·(2 - 1) - 1·(3 - 1) = 0 exactly
    data = {
        "inertia": 1.0,
        "stiffness": 2.0,
        "absorber_inertia": 0.5,
        "absorber_stiffness": 1.0,
        "torque_amplitude": 1.0,
        "frequency": 1.0,
    }
    assert hand_absorber(1.0, 2.0, 0.5, 1.0, 1.0, 1.0)["delta"] == 0
    path = write_case(toml_dumps(variator(absorber=data)))
    result = cli("variator", path)
    assert result.exit_code == 3, result.stdout
    assert_no_traceback(result)
    assert "unbounded" in result.stderr
    as_json = cli("variator", path, "--json")
    assert as_json.exit_code == 3
    document = strict_json(as_json.stdout)
    assert document["status"] == "no-answer"
    assert "unbounded" in document["message"]
    assert "absorber_a1" not in document["results"]
    # the resonances are still reported: 1 and 2 rad/s (x² - 5x + 4 = 0)
    r = values(document)
    assert r["absorber_resonance_low"] == pytest.approx(1.0, rel=1e-14)
    assert r["absorber_resonance_high"] == pytest.approx(2.0, rel=1e-14)
    # a little damping across the absorber: a finite answer, the complex solve's
    damped = values(
        run_json(cli, write_case, variator(absorber=with_(data, absorber_damping=0.05)))
    )
    a1, a2 = complex_amplitudes(1.0, 2.0, 0.5, 1.0, 0.05, 1.0, 1.0)
    assert damped["absorber_a1"] == pytest.approx(abs(a1), rel=1e-12)
    assert damped["absorber_a2"] == pytest.approx(abs(a2), rel=1e-12)


def test_curve_rows_at_the_resonances_are_finite(cli, write_case) -> None:
    # ω = 0.5 with 5 rows over 5ω hits both resonances (1 and 2 rad/s) exactly
    data = {
        "inertia": 1.0,
        "stiffness": 2.0,
        "absorber_inertia": 0.5,
        "absorber_stiffness": 1.0,
        "torque_amplitude": 1.0,
        "frequency": 0.5,
        "curve_points": 5,
    }
    result = cli("variator", write_case(toml_dumps(variator(absorber=data))), "--json")
    assert result.exit_code == 0, result.stderr
    document = strict_json(result.stdout)
    walk_finite(document)
    for w, _, _alone, a1, a2 in section(document, "absorber_curve")["rows"]:
        hand = hand_absorber(1.0, 2.0, 0.5, 1.0, 1.0, w)
        if hand["delta"] == 0:
            assert a1 == a2 == "unbounded"
        else:
            assert a1 == pytest.approx(float(abs(hand["a1"])), rel=1e-12)
            assert a2 == pytest.approx(float(abs(hand["a2"])), rel=1e-12)


def test_chain_core_with_ground_spring_is_the_two_disk_absorber() -> None:
    # chain.harmonic_response(ground_stiffness=...) against the 2×2 written out here
    from mdcalc.core.chain import Chain, harmonic_response

    for bg, omega in ((0.0, 17.0), (1.5, 20.0), (0.3, 31.0)):
        angles, springs = harmonic_response(
            Chain((2.0, 0.2), (90.0,)),
            omega,
            [100.0, 0.0],
            spring_damping=[bg],
            ground_stiffness=[1000.0, 0.0],
        )
        a1, a2 = complex_amplitudes(2.0, 1000.0, 0.2, 90.0, bg, 100.0, omega)
        assert complex(angles[0]) == pytest.approx(a1, rel=1e-12)
        assert complex(angles[1]) == pytest.approx(a2, rel=1e-12)
        assert abs(springs[0]) == pytest.approx(0.2 * omega**2 * abs(a2), rel=1e-12)


# ----------------------------------------------------------------------------- motor


def hand_motor(fc, p, n, n_h, torque, lam) -> dict[str, float]:
    """(8.40)–(8.41), brief §7b: S_H = (n - n_H)/n; a = λ_m + 5(λ_m - 1)S_H (seed) or
    λ_m (Kloss); S_K = S_H(a + √(a² - 1)); ν = S_K/(2M_K); T_D = 1/(ω_c·S_K);
    c_D = 1/(T_D·ν·ω₀); b_D = 1/(ν·ω₀)."""
    wc = 2.0 * math.pi * fc
    w0 = wc / p
    mk = lam * torque

    def model(s_h: float, a: float) -> dict[str, float]:
        s_k = s_h * (a + math.sqrt(a * a - 1.0))
        nu = s_k / (2.0 * mk)
        t_d = 1.0 / (wc * s_k)
        return {
            "slip": s_h,
            "critical_slip": s_k,
            "time_constant": t_d,
            "stiffness": 1.0 / (t_d * nu * w0),
            "damping": 1.0 / (nu * w0),
        }

    s_h = (n - n_h) / n
    seed = model(s_h, lam + 5.0 * (lam - 1.0) * s_h)
    kloss = model(s_h, lam)
    printed_slip = (n - n_h) / n_h  # the seed's (8.41) as printed
    printed = model(printed_slip, lam + 5.0 * (lam - 1.0) * printed_slip)
    return {"mk": mk, "seed": seed, "kloss": kloss, "printed": printed}


MOTOR_CASES = {
    "4-pole 50 Hz torque": (
        {
            "pole_pairs": 2,
            "nominal_speed_rpm": 1440.0,
            "nominal_torque": 100.0,
            "overload_ratio": 2.5,
        },
        (50.0, 2, 1500.0, 1440.0, 100.0, 2.5),
    ),
    "6-pole 60 Hz": (
        {
            "mains_frequency": 60.0,
            "pole_pairs": 3,
            "nominal_speed_rpm": 1164.0,
            "nominal_torque": 850.0,
            "overload_ratio": 1.8,
        },
        (60.0, 3, 1200.0, 1164.0, 850.0, 1.8),
    ),
    "given synchronous speed": (
        {
            "pole_pairs": 2,
            "synchronous_speed_rpm": 1490.0,
            "nominal_speed_rpm": 1455.0,
            "nominal_torque": 40.0,
            "overload_ratio": 3.0,
        },
        (50.0, 2, 1490.0, 1455.0, 40.0, 3.0),
    ),
}


@pytest.mark.parametrize("data,args", MOTOR_CASES.values(), ids=MOTOR_CASES.keys())
def test_motor_by_hand(cli, write_case, data, args) -> None:
    document = run_json(cli, write_case, variator(motor=data))
    r = values(document)
    hand = hand_motor(*args)
    fc, p, n, n_h, torque, lam = args
    seed, kloss = hand["seed"], hand["kloss"]
    assert r["motor_nominal_torque"] == pytest.approx(torque, rel=1e-15)
    assert r["motor_critical_torque"] == pytest.approx(lam * torque, rel=1e-15)
    assert r["motor_slip"] == pytest.approx((n - n_h) / n, rel=1e-14)
    assert r["motor_critical_slip"] == pytest.approx(seed["critical_slip"], rel=1e-14)
    assert r["motor_critical_slip_kloss"] == pytest.approx(kloss["critical_slip"], rel=1e-14)
    assert r["motor_time_constant"] == pytest.approx(seed["time_constant"], rel=1e-14)
    assert r["motor_damping"] == pytest.approx(seed["damping"], rel=1e-14)
    assert r["motor_damping_kloss"] == pytest.approx(kloss["damping"], rel=1e-14)
    # c_D = 1/(T_D·ν·ω₀) = ω_c·S_K·2M_K/(S_K·ω₀) = 2·P·M_K, whatever S_K
    assert r["motor_stiffness"] == pytest.approx(2.0 * p * lam * torque, rel=1e-14)
    assert seed["stiffness"] == pytest.approx(2.0 * p * lam * torque, rel=1e-14)
    assert kloss["stiffness"] == pytest.approx(2.0 * p * lam * torque, rel=1e-14)
    # the seed's printed slip (divided by n_H) is a different, larger number
    printed = hand["printed"]
    assert printed["slip"] > r["motor_slip"] * (1.0 + 1e-3)
    rows = list(method_rows(document, "motor").values())
    assert len(rows) == 3
    slips = sorted(row["values"]["critical_slip"] for row in rows)
    expected = sorted(m["critical_slip"] for m in (seed, kloss, printed))
    assert slips == pytest.approx(expected, rel=1e-14)


def test_motor_from_nominal_power(cli, write_case) -> None:
    # M_H = P_H/(n_H·π/30): 15 kW at 1455 rpm
    data = {
        "pole_pairs": 2,
        "nominal_speed_rpm": 1455.0,
        "nominal_power": 15.0e3,
        "overload_ratio": 2.2,
    }
    r = values(run_json(cli, write_case, variator(motor=data)))
    torque = 15.0e3 / (1455.0 * 2.0 * math.pi / 60.0)
    assert r["motor_nominal_torque"] == pytest.approx(torque, rel=1e-14)
    hand = hand_motor(50.0, 2, 1500.0, 1455.0, torque, 2.2)
    assert r["motor_damping"] == pytest.approx(hand["seed"]["damping"], rel=1e-13)
    assert r["motor_stiffness"] == pytest.approx(2.0 * 2 * 2.2 * torque, rel=1e-13)


# ----------------------------------------------------------------------------- clutch


def dense_max(f, low: float, high: float, points: int = 200001) -> float:
    """max of f on [low, high]: a dense grid, its best point polished by a bounded
    search, both ends included."""
    x = np.linspace(low, high, points)
    v = f(x)
    k = int(np.argmax(v))
    best = float(v[k])
    if 0 < k < points - 1:
        found = minimize_scalar(
            lambda t: -float(f(np.array([t]))[0]),
            bounds=(x[k - 1], x[k + 1]),
            method="bounded",
            options={"xatol": 1e-15 * high},
        )
        best = max(best, float(-found.fun))
    return best


CLUTCH_CASES = {
    "stiffening n = 1.5, kgf·m": (
        {
            "loading_coefficient_kgfm": 2.0e5,
            "loading_exponent": 1.5,
            "load_min": 200.0,
            "load_max": 3000.0,
        },
        2.0e5 * KGF_M,
    ),
    "softening n = 0.6": (
        {
            "loading_coefficient": 5.0e4,
            "loading_exponent": 0.6,
            "load_min": 50.0,
            "load_max": 900.0,
        },
        5.0e4,
    ),
    "softening n = 0.6 from zero load": (
        {"loading_coefficient": 5.0e4, "loading_exponent": 0.6, "load_max": 900.0},
        5.0e4,
    ),
    "n = 2 from zero load": (
        {"loading_coefficient": 3.0e7, "loading_exponent": 2.0, "load_max": 1.0e4},
        3.0e7,
    ),
}


@pytest.mark.parametrize("data,c0", CLUTCH_CASES.values(), ids=CLUTCH_CASES.keys())
def test_clutch_lines_by_hand(cli, write_case, data, c0) -> None:
    r = values(run_json(cli, write_case, variator(clutch=data)))
    n = data["loading_exponent"]
    m1, m2 = data.get("load_min", 0.0), data["load_max"]
    x1, x2 = (m1 / c0) ** (1.0 / n), (m2 / c0) ** (1.0 / n)
    assert r["clutch_twist_min"] == pytest.approx(x1, rel=1e-14, abs=1e-300)
    assert r["clutch_twist_max"] == pytest.approx(x2, rel=1e-14)
    secant = m2 / x2
    top, _ = quad(lambda x: c0 * x**n * x, x1, x2, epsabs=0.0, epsrel=1e-13)
    bottom, _ = quad(lambda x: x * x, x1, x2, epsabs=0.0, epsrel=1e-13)
    squares = top / bottom
    chord = (m2 - m1) / (x2 - x1)
    assert r["clutch_secant"] == pytest.approx(secant, rel=1e-14)
    assert r["clutch_least_squares"] == pytest.approx(squares, rel=1e-12)
    assert r["clutch_chord"] == pytest.approx(chord, rel=1e-13)
    lines = {
        "secant": lambda x: secant * x,
        "least_squares": lambda x: squares * x,
        "chord": lambda x: m1 + chord * (x - x1),
    }
    for key, line in lines.items():
        error = dense_max(lambda x, line=line: np.abs(line(x) - c0 * x**n) / m2, x1, x2)
        assert r[f"clutch_{key}_error"] == pytest.approx(error, rel=1e-9, abs=1e-14), key
    # the chord passes through both ends; the secant through the top
    assert m1 + chord * (x2 - x1) == pytest.approx(m2, rel=1e-14)


def test_linear_clutch_has_one_line(cli, write_case) -> None:
    data = {
        "loading_coefficient": 7.0e5,
        "loading_exponent": 1.0,
        "load_min": 10.0,
        "load_max": 99.0,
    }
    r = values(run_json(cli, write_case, variator(clutch=data)))
    for key in ("secant", "least_squares", "chord"):
        assert r[f"clutch_{key}"] == pytest.approx(7.0e5, rel=1e-13)
        assert abs(r[f"clutch_{key}_error"]) <= 1e-12


def test_clutch_unloading_in_kgfm(cli, write_case) -> None:
    data = with_(CLUTCH_CASES["stiffening n = 1.5, kgf·m"][0], unloading_stiffness_kgfm=3.0e4)
    r = values(run_json(cli, write_case, variator(clutch=data)))
    assert r["clutch_unloading"] == pytest.approx(3.0e4 * KGF_M, rel=1e-15)
    data = with_(data, unloading_stiffness_kgfm=None, unloading_stiffness=2.5e5)
    assert values(run_json(cli, write_case, variator(clutch=data)))[
        "clutch_unloading"
    ] == pytest.approx(2.5e5, rel=1e-15)


# ----------------------------------------------------------------------------- mechanism


PI = Decimal("3.14159265358979323846264338327950288419716939937510")


def decimal_sin(x: Decimal) -> Decimal:
    """Taylor series, |x| ≤ π/2, to the context's precision."""
    term, total, k = x, x, 1
    while abs(term) > Decimal(10) ** -(getcontext().prec + 2):
        term = -term * x * x / ((2 * k) * (2 * k + 1))
        total += term
        k += 1
    return total


def hand_transfer(z: int, ratio: float) -> tuple[float, float, float]:
    """(8.46): Δα = 2π/z, a₀ = -12/(Δα²i_c)·(Δα/(2 sin(Δα/2)) - 1),
    b₀ = Δα/(2i_c sin(Δα/2)), at 50 digits (the bracket of a₀ cancels for large z)."""
    with localcontext() as ctx:
        ctx.prec = 50
        stroke = 2 * PI / z
        i_c = D(ratio)
        half = decimal_sin(stroke / 2)
        a0 = -12 / (stroke**2 * i_c) * (stroke / (2 * half) - 1)
        b0 = stroke / (2 * i_c * half)
        return float(stroke), float(a0), float(b0)


@pytest.mark.parametrize("z", [2, 3, 4, 7, 64])
def test_mechanism_transfer_functions(cli, write_case, z) -> None:
    ratio = 1000.0 / 185.0
    mechanism = {"mechanisms": z, "input_speed_rpm": 1000.0, "mean_ratio": ratio}
    document = run_json(cli, write_case, variator(mechanism=mechanism))
    r = values(document)
    stroke, a0, b0 = hand_transfer(z, ratio)
    assert r["mechanism_stroke"] == pytest.approx(stroke, rel=1e-15)
    assert r["mechanism_ratio"] == pytest.approx(ratio, rel=1e-15)
    assert r["mechanism_a0"] == pytest.approx(a0, rel=1e-12)
    assert r["mechanism_b0"] == pytest.approx(b0, rel=1e-14)
    assert r["mechanism_first_end"] == pytest.approx(a0 * stroke**2 / 4.0 + b0, rel=1e-13)
    assert r["mechanism_output_rpm"] == pytest.approx(185.0, rel=1e-14)
    # the mean of Π′ over a stroke is 1/i_c: quadrature of the hand Π′ and the program
    integral, _ = quad(lambda x: a0 * x * x + b0, -stroke / 2, stroke / 2, epsabs=0.0, epsrel=1e-13)
    assert integral / stroke == pytest.approx(1.0 / ratio, rel=1e-13)
    assert r["mechanism_mean_first"] == pytest.approx(1.0 / ratio, rel=1e-13)
    # the output turns Δα/i_c per stroke: Π(Δα/2) - Π(-Δα/2) from the transfer table
    rows = section(document, "mechanism_transfer")["rows"]
    assert rows[0][0] == pytest.approx(-math.degrees(stroke) / 2, rel=1e-14)
    assert rows[-1][1] - rows[0][1] == pytest.approx(stroke / ratio, rel=1e-12)
    for deg, position, first, second in rows:
        x = math.radians(deg)
        assert position == pytest.approx(a0 * x**3 / 3 + b0 * x, rel=1e-12, abs=1e-15)
        assert first == pytest.approx(a0 * x * x + b0, rel=1e-12)
        assert second == pytest.approx(2 * a0 * x, rel=1e-12, abs=1e-15)


def test_mechanism_from_output_speed(cli, write_case) -> None:
    mechanism = {"mechanisms": 6, "input_speed_rpm": 1450.0, "output_speed_rpm": 90.0}
    r = values(run_json(cli, write_case, variator(mechanism=mechanism)))
    ratio = 1450.0 / 90.0
    stroke, a0, b0 = hand_transfer(6, ratio)
    assert r["mechanism_ratio"] == pytest.approx(ratio, rel=1e-15)
    assert r["mechanism_output_rpm"] == pytest.approx(90.0, rel=1e-14)
    assert r["mechanism_a0"] == pytest.approx(a0, rel=1e-12)
    assert r["mechanism_mean_first"] == pytest.approx(90.0 / 1450.0, rel=1e-13)


# ----------------------------------------------------------------------------- drive


def sawtooth(mechanism: dict[str, Any]) -> tuple[float, float, float, float]:
    """u(τ) = ω²Π″ = 2a₀ω²(ωτ - Δα/2) over a stroke τ in [0, T), T = Δα/ω:
    returns (u₀, u₁, T, ω) with u = u₀ + u₁τ."""
    z = mechanism["mechanisms"]
    ratio = (
        mechanism.get("mean_ratio") or mechanism["input_speed_rpm"] / mechanism["output_speed_rpm"]
    )
    stroke, a0, _ = hand_transfer(z, ratio)
    omega = 2.0 * math.pi * mechanism["input_speed_rpm"] / 60.0
    return -a0 * omega**2 * stroke, 2.0 * a0 * omega**3, stroke / omega, omega


def augmented(m, c, k, f, s, u0, u1) -> np.ndarray:
    """B of z' = B·z, z = (x, x', 1, τ), for M·x'' + C·x' + K·x = F + s·(u₀ + u₁τ)."""
    m, c, k = (np.atleast_2d(np.asarray(v, dtype=float)) for v in (m, c, k))
    f, s = np.atleast_1d(np.asarray(f, float)), np.atleast_1d(np.asarray(s, float))
    n = len(f)
    mi = np.linalg.inv(m)
    b = np.zeros((2 * n + 2, 2 * n + 2))
    b[:n, n : 2 * n] = np.eye(n)
    b[n : 2 * n, :n] = -mi @ k
    b[n : 2 * n, n : 2 * n] = -mi @ c
    b[n : 2 * n, 2 * n] = mi @ (f + s * u0)
    b[n : 2 * n, 2 * n + 1] = mi @ (s * u1)
    b[2 * n + 1, 2 * n] = 1.0
    return b


def fixed_point(b: np.ndarray, t: float) -> np.ndarray:
    """Periodic start: (I - Φ)·y₀ = γ from the exact period map expm(B·T)."""
    n2 = b.shape[0] - 2
    e = expm(b * t)
    return np.linalg.solve(np.eye(n2) - e[:n2, :n2], e[:n2, n2])


def one_period(b: np.ndarray, y0: np.ndarray, t: float):
    """solve_ivp (DOP853, rtol 1e-12) over one stroke from y0; dense solution."""
    n2 = b.shape[0] - 2
    a, g = b[:n2, :n2], b[:n2, n2:]
    scale = np.maximum(np.abs(y0), 1e-6 * np.abs(y0).max())  # for atol only

    def rhs(tau: float, y: np.ndarray) -> np.ndarray:
        return a @ y + g[:, 0] + g[:, 1] * tau

    return solve_ivp(
        rhs, (0.0, t), y0, method="DOP853", rtol=1e-12, atol=1e-12 * scale, dense_output=True
    )


def from_rest(b: np.ndarray, t: float, limit: int):
    """Integrate from rest stroke by stroke (solve_ivp) until the slowest transient
    e^{-σ·τ} has fallen below e^{-36} (at most ``limit`` strokes, else the test is
    mis-set);
    returns the state at the start of the last stroke and that stroke's solution."""
    n2 = b.shape[0] - 2
    sigma = float(np.min(-np.linalg.eigvals(b[:n2, :n2]).real))
    periods = int(math.ceil(36.0 / (sigma * t)))
    assert periods <= limit, f"{periods} strokes to settle"
    a, g = b[:n2, :n2], b[:n2, n2:]
    y = np.zeros(n2)
    size = np.abs(fixed_point(b, t))  # a size for atol only; the start is from rest
    scale = np.maximum(size, 1e-6 * size.max())

    def rhs(tau: float, y: np.ndarray) -> np.ndarray:
        return a @ y + g[:, 0] + g[:, 1] * tau

    for _ in range(periods):
        run = solve_ivp(rhs, (0.0, t), y, method="DOP853", rtol=1e-12, atol=1e-13 * scale)
        y = run.y[:, -1]
    return y, one_period(b, y, t)


def period_maximum(sol, w: np.ndarray, t: float, points: int = 40001) -> float:
    """max over the stroke of w·y(τ) from a dense solution: grid + bounded search
    around the best grid points (the first and last steps included)."""
    tau = np.linspace(0.0, t, points)
    v = w @ sol.sol(tau)
    best = float(v.max())
    order = np.argsort(v)[::-1][:5]
    for k in {*order.tolist(), 0, points - 1}:
        low, high = tau[max(k - 1, 0)], tau[min(k + 1, points - 1)]
        found = minimize_scalar(
            lambda x: -float(w @ sol.sol(x)),
            bounds=(low, high),
            method="bounded",
            options={"xatol": 1e-13 * t},
        )
        best = max(best, float(-found.fun))
    return best


def two_mass(mechanism, j, c, b, load) -> np.ndarray:
    u0, u1, _, _ = sawtooth(mechanism)
    return augmented([[j]], [[b]], [[c]], [load], [j], u0, u1)


def test_seed_drive_chi_by_integration_from_rest(cli, write_case) -> None:
    document = run_json(cli, write_case, variator(mechanism=MECHANISM, drive=DRIVE))
    r = values(document)
    j, c, load = 1.55, 8.9e5 * KGF_M, 300.0
    b = 0.6 / (2.0 * math.pi) * math.sqrt(j * c)  # (8.44)
    _, _, t, omega = sawtooth(MECHANISM)
    assert r["drive_stiffness"] == pytest.approx(c, rel=1e-15)
    assert r["drive_damping"] == pytest.approx(b, rel=1e-14)
    assert r["drive_fundamental"] == pytest.approx(4 * omega, rel=1e-14)
    assert r["drive_fundamental"] == pytest.approx(2.0 * math.pi / t, rel=1e-14)
    assert r["drive_natural"] == pytest.approx(math.sqrt(c / j), rel=1e-15)
    assert r["drive_static"] == pytest.approx(load / c, rel=1e-15)
    system = two_mass(MECHANISM, j, c, b, load)
    start, sol = from_rest(system, t, 200)
    q_max = period_maximum(sol, np.array([1.0, 0.0]), t)
    assert r["drive_q_max"] == pytest.approx(q_max, rel=1e-8)
    assert r["drive_chi"] == pytest.approx(q_max / (load / c), rel=1e-8)
    # the q(τ) table is the same periodic state
    for tau, _, q, chi in section(document, "drive_history")["rows"]:
        assert q == pytest.approx(float(sol.sol(tau)[0]), abs=1e-8 * q_max)
        assert chi == pytest.approx(q / (load / c), rel=1e-12)
    # the Fourier rows and the ODE rows of the Methods table are near the truth too
    rows = method_rows(document, "two_mass")
    for name, row in rows.items():
        if row["values"] and name.startswith(("Fourier series, 100 ", "ODE")):
            assert row["values"]["chi"] == pytest.approx(q_max / (load / c), rel=1e-4), name


def test_drive_with_given_damping(cli, write_case) -> None:
    drive = with_(DRIVE, clutch_loop_area_ratio=None, clutch_damping=3000.0)
    drive = with_(drive, clutch_stiffness_kgfm=None, clutch_stiffness=5.0e6)
    r = values(run_json(cli, write_case, variator(mechanism=MECHANISM, drive=drive)))
    assert r["drive_damping"] == 3000.0
    _, _, t, _ = sawtooth(MECHANISM)
    start, sol = from_rest(two_mass(MECHANISM, 1.55, 5.0e6, 3000.0, 300.0), t, 200)
    q_max = period_maximum(sol, np.array([1.0, 0.0]), t)
    assert r["drive_chi"] == pytest.approx(q_max / (300.0 / 5.0e6), rel=1e-8)


def test_undamped_drive_is_the_fixed_point(cli, write_case) -> None:
    # no damping: no transient ever dies; the fixed point of the exact period map,
    # checked by integrating one more stroke from it
    drive = with_(DRIVE, clutch_loop_area_ratio=None)
    document = run_json(cli, write_case, variator(mechanism=MECHANISM, drive=drive))
    walk_finite(document)
    r = values(document)
    assert r["drive_damping"] == 0.0
    c = 8.9e5 * KGF_M
    system = two_mass(MECHANISM, 1.55, c, 0.0, 300.0)
    _, _, t, _ = sawtooth(MECHANISM)
    y0 = fixed_point(system, t)
    sol = one_period(system, y0, t)
    assert sol.y[:, -1] == pytest.approx(y0, rel=1e-9, abs=1e-9 * np.abs(y0).max())
    q_max = period_maximum(sol, np.array([1.0, 0.0]), t)
    assert r["drive_chi"] == pytest.approx(q_max / (300.0 / c), rel=1e-8)


@pytest.mark.parametrize("harmonic", [1, 3])
def test_undamped_drive_at_resonance_is_unbounded(cli, write_case, harmonic) -> None:
    # z = 4 at 15 rpm: ω = π/2 rad/s, Δα = π/2, T = 1 s; J = 1, c = (2πm)²: β·T = 2πm
    mechanism = {"mechanisms": 4, "input_speed_rpm": 15.0, "mean_ratio": 2.0}
    drive = {
        "driven_inertia": 1.0,
        "load_torque": 1.0,
        "clutch_stiffness": (2.0 * math.pi * harmonic) ** 2,
    }
    path = write_case(toml_dumps(variator(mechanism=mechanism, drive=drive)))
    result = cli("variator", path)
    assert result.exit_code == 3, result.stdout
    assert_no_traceback(result)
    assert "unbounded" in result.stderr
    as_json = cli("variator", path, "--json")
    assert as_json.exit_code == 3
    document = strict_json(as_json.stdout)
    assert document["status"] == "no-answer" and "unbounded" in document["message"]
    # with a loop area the same clutch has a periodic state (from rest, solve_ivp)
    damped = with_(drive, clutch_loop_area_ratio=0.6)
    r = values(run_json(cli, write_case, variator(mechanism=mechanism, drive=damped)))
    c = (2.0 * math.pi * harmonic) ** 2
    b = 0.6 / (2.0 * math.pi) * math.sqrt(c)
    _, _, t, _ = sawtooth(mechanism)
    assert t == pytest.approx(1.0, rel=1e-15)
    _, sol = from_rest(two_mass(mechanism, 1.0, c, b, 1.0), t, 400)
    assert r["drive_chi"] == pytest.approx(
        period_maximum(sol, np.array([1.0, 0.0]), t) * c, rel=1e-8
    )


def test_three_mass_undamped_resonance_is_unbounded(cli, write_case) -> None:
    # J₂ = J₃ = 1, c₁ = c₂ = c, no damping: λ = c(3 ± √5)/2 with the driver held; put the
    # lower one on the fundamental Ω = 2π (z = 4, 15 rpm): c = Ω²·2/(3 - √5). The
    # two-mass "before" (J = 2, β = √(c/2) ≈ 1.144·Ω) is not resonant, the three-mass is.
    big = 2.0 * math.pi
    c = big**2 * 2.0 / (3.0 - math.sqrt(5.0))
    mechanism = {"mechanisms": 4, "input_speed_rpm": 15.0, "mean_ratio": 2.0}
    drive = {"driven_inertia": 1.0, "load_torque": 1.0, "clutch_stiffness": c}
    ar = {"machine_inertia": 1.0, "coupling_stiffness": c}
    beta = math.sqrt(c / 2.0)
    assert abs(beta / big - round(beta / big)) > 0.1
    path = write_case(toml_dumps(variator(mechanism=mechanism, drive=drive, antiresonance=ar)))
    result = cli("variator", path)
    assert result.exit_code == 3, result.stdout
    assert_no_traceback(result)
    assert "unbounded" in result.stderr
    # without the machine the same clutch has an answer
    alone = values(run_json(cli, write_case, variator(mechanism=mechanism, drive=drive)))
    _, _, t, _ = sawtooth(mechanism)
    system = two_mass(mechanism, 1.0, c, 0.0, 1.0)
    sol = one_period(system, fixed_point(system, t), t)
    assert alone["drive_chi"] == pytest.approx(
        period_maximum(sol, np.array([1.0, 0.0]), t) * c, rel=1e-8
    )


def test_stiff_clutch_is_finite_and_right(cli, write_case) -> None:
    # β/Ω ≈ 1e4. Each stroke the transient of the jump dies out (ζβT ≈ 3000), so the
    # periodic state is the ramp's particular solution q_p = A + B·τ (c·B = J·u₁,
    # c·A = M_c + J·u₀ - b·B) plus a free decay from q(0) - q_p(0) = B·T, q'(0) = B:
    # q = A + Bτ + B·T·e^{-ζβτ}(cos β_dτ + ζ/√(1-ζ²)·sin β_dτ).
    j, c, load = 1.55, 2.7e13, 300.0
    drive = with_(DRIVE, clutch_stiffness_kgfm=None, clutch_stiffness=c)
    result = cli(
        "variator", write_case(toml_dumps(variator(mechanism=MECHANISM, drive=drive))), "--json"
    )
    assert result.exit_code == 0, result.stderr
    document = strict_json(result.stdout)
    walk_finite(document)
    r = values(document)
    u0, u1, t, _ = sawtooth(MECHANISM)
    b = 0.6 / (2.0 * math.pi) * math.sqrt(j * c)
    beta = math.sqrt(c / j)
    zeta = b / (2.0 * math.sqrt(j * c))
    assert r["drive_natural"] / r["drive_fundamental"] == pytest.approx(beta * t / (2 * math.pi))
    assert beta * t / (2 * math.pi) > 9000
    slope = j * u1 / c
    offset = (load + j * u0 - b * slope) / c
    damped = beta * math.sqrt(1.0 - zeta**2)

    def q(tau):
        free = np.cos(damped * tau) + zeta / math.sqrt(1 - zeta**2) * np.sin(damped * tau)
        return offset + slope * tau + slope * t * np.exp(-zeta * beta * tau) * free

    # the peak is the first overshoot, at β_dτ ≈ π
    q_max = dense_max(q, 0.0, 4.0 * math.pi / damped, 20001)
    assert r["drive_chi"] == pytest.approx(q_max / (load / c), rel=1e-9)
    # the textbook estimate: quasi-static peak + step 2J|u₀| times the overshoot e^{-ζπ/√(1-ζ²)}
    estimate = (load + j * u0) + 2 * j * u0 * math.exp(-zeta * math.pi / math.sqrt(1 - zeta**2))
    assert r["drive_chi"] == pytest.approx(estimate / load, rel=1e-3)


def test_critically_damped_clutch_is_never_an_internal_error(cli, write_case) -> None:
    # b = 2√(J·c) is a valid clutch (ζ = 1): an answer (exit 0, e^{Aτ} where the modes
    # meet; its χ in test_critically_damped_clutch_chi), never exit 70 or 3
    mechanism = {"mechanisms": 4, "input_speed_rpm": 15.0, "mean_ratio": 2.0}
    drive = {
        "driven_inertia": 1.0,
        "load_torque": 1.0,
        "clutch_stiffness": 4.0,
        "clutch_damping": 4.0,
    }
    path = write_case(toml_dumps(variator(mechanism=mechanism, drive=drive)))
    result = cli("variator", path, "--json")
    assert result.exit_code == 0, (result.exit_code, result.stderr)
    assert_no_traceback(result)
    strict_json(result.stdout)


@pytest.mark.parametrize("offset", [1e-9, 1e-6, -1e-6])
def test_nearly_critically_damped_clutch(cli, write_case, offset) -> None:
    # b = 2√(J·c)·(1 + δ): the closed form has nearly parallel modes here; the answer
    # must still be the one integrated from rest
    mechanism = {"mechanisms": 4, "input_speed_rpm": 15.0, "mean_ratio": 2.0}
    b = 4.0 * (1.0 + offset)
    drive = {
        "driven_inertia": 1.0,
        "load_torque": 1.0,
        "clutch_stiffness": 4.0,
        "clutch_damping": b,
    }
    r = values(run_json(cli, write_case, variator(mechanism=mechanism, drive=drive)))
    _, _, t, _ = sawtooth(mechanism)
    _, sol = from_rest(two_mass(mechanism, 1.0, 4.0, b, 1.0), t, 100)
    assert r["drive_chi"] == pytest.approx(
        period_maximum(sol, np.array([1.0, 0.0]), t) * 4.0, rel=1e-7
    )


def test_critically_damped_clutch_chi(cli, write_case) -> None:
    # b = 2√(J·c) (ζ = 1): the first-order matrix is defective, and the closed form
    # takes e^{Aτ} whole; χ is the one integrated from rest (it was exit 3, "the modes
    # cannot be separated", before)
    mechanism = {"mechanisms": 4, "input_speed_rpm": 15.0, "mean_ratio": 2.0}
    drive = {
        "driven_inertia": 1.0,
        "load_torque": 1.0,
        "clutch_stiffness": 4.0,
        "clutch_damping": 4.0,
    }
    path = write_case(toml_dumps(variator(mechanism=mechanism, drive=drive)))
    result = cli("variator", path, "--json")
    _, _, t, _ = sawtooth(mechanism)
    _, sol = from_rest(two_mass(mechanism, 1.0, 4.0, 4.0, 1.0), t, 100)
    expected = period_maximum(sol, np.array([1.0, 0.0]), t) * 4.0
    assert 1.0 < expected < 10.0  # a plain, finite answer
    assert result.exit_code == 0, (result.exit_code, result.stderr)
    r = values(strict_json(result.stdout))
    assert r["drive_chi"] == pytest.approx(expected, rel=1e-6)


def test_clutch_loop_area_ratio_damps_the_drive(cli, write_case) -> None:
    # [clutch] loop_area_ratio ψ (8.43): ζ = ψ/(4π); [drive] without its own damping
    # takes b = ψ/(2π)·√(J·c) (8.44) from it (README, [clutch]); ζ = b/(2√(Jc)) by hand
    clutch = with_(CLUTCH_CASES["stiffening n = 1.5, kgf·m"][0], loop_area_ratio=0.6)
    drive = with_(DRIVE, clutch_loop_area_ratio=None)
    r = values(run_json(cli, write_case, variator(clutch=clutch, mechanism=MECHANISM, drive=drive)))
    j, c = 1.55, 8.9e5 * KGF_M
    b = 0.6 / (2.0 * math.pi) * math.sqrt(j * c)
    assert r["clutch_damping_ratio"] == pytest.approx(b / (2.0 * math.sqrt(j * c)), rel=1e-14)
    assert r["drive_damping"] == pytest.approx(b, rel=1e-14)
    # the drive's own value wins
    own = with_(DRIVE, clutch_loop_area_ratio=0.3)
    r = values(run_json(cli, write_case, variator(clutch=clutch, mechanism=MECHANISM, drive=own)))
    assert r["drive_damping"] == pytest.approx(0.3 / (2.0 * math.pi) * math.sqrt(j * c), rel=1e-14)


# ----------------------------------------------------------------------------- anti-resonance


def three_mass(mechanism, j2, j3, c1, b1, c2, b2, load) -> np.ndarray:
    """q₁ clutch, q₂ coupling twist (reduced to the output shaft), brief §7f:
    J₂q₁'' + b₁q₁' + c₁q₁ - (c₂q₂ + b₂q₂') = J₂u,
    J₃(q₁'' + q₂'') + c₂q₂ + b₂q₂' = M_c + J₃u."""
    u0, u1, _, _ = sawtooth(mechanism)
    return augmented(
        [[j2, 0.0], [j3, j3]],
        [[b1, -b2], [0.0, b2]],
        [[c1, -c2], [0.0, c2]],
        [0.0, load],
        [j2, j3],
        u0,
        u1,
    )


def test_tuned_coupling_zeroes_the_clutch_at_the_fundamental(cli, write_case) -> None:
    data = variator(mechanism=MECHANISM, drive=DRIVE, antiresonance=ANTIRESONANCE)
    r = values(run_json(cli, write_case, data))
    j2, i = 1.55, 2.0
    j3 = i * i * 11.625  # J₃' = i²J₃ = 46.5 = 30·J₂
    c1 = 8.9e5 * KGF_M
    b1 = 0.6 / (2.0 * math.pi) * math.sqrt((j2 + j3) * c1)  # (8.44) with J₂ + J₃'
    _, _, t, omega = sawtooth(MECHANISM)
    big = 4 * omega  # zω
    tuned = big**2 * j2 * j3 / (j2 + j3)
    assert r["antiresonance_coupling"] == pytest.approx(tuned / i**2, rel=1e-13)
    assert r["antiresonance_frequency"] == pytest.approx(big, rel=1e-13)
    # harmonic balance at zω with the reported c₂ (reduced): the clutch does not move
    c2 = r["antiresonance_coupling"] * i**2

    def clutch_amplitude(c2: float) -> complex:
        k = np.array([[c1 + 1j * big * b1, -c2], [0.0, c2]])
        m = np.array([[j2, 0.0], [j3, j3]])
        x = np.linalg.solve(k - big**2 * m, np.array([j2, j3], dtype=complex))
        return complex(x[0])

    reference = abs(clutch_amplitude(1.01 * c2))
    assert abs(clutch_amplitude(c2)) <= 1e-9 * reference
    # natural frequencies with the driver held: λ²J₂J₃ - λ(c₁J₃ + c₂(J₂ + J₃)) + c₁c₂ = 0
    with localcontext() as ctx:
        ctx.prec = 50
        dj2, dj3, dc1, dc2 = D(j2), D(j3), D(c1), D(tuned)
        low, high = quadratic_roots(
            (dc1 * dj3 + dc2 * (dj2 + dj3)) / (dj2 * dj3), dc1 * dc2 / (dj2 * dj3)
        )
    assert r["antiresonance_natural_low"] == pytest.approx(float(low.sqrt()), rel=1e-15)
    assert r["antiresonance_natural_high"] == pytest.approx(float(high.sqrt()), rel=1e-15)


def chi_after(j2, j3, c1, b1, c2, b2, load) -> tuple[float, float]:
    """χ after and the coupling's M_max/M_c of the three-mass model, tuned or not: the
    coupling mode is barely damped when b₂ = 0 (J₂ hardly moves in it), so the periodic
    start is the fixed point of the exact period map, checked by one solve_ivp stroke."""
    _, _, t, _ = sawtooth(MECHANISM)
    system = three_mass(MECHANISM, j2, j3, c1, b1, c2, b2, load)
    y0 = fixed_point(system, t)
    sol = one_period(system, y0, t)
    scale = np.abs(sol.y).max(axis=1)
    assert np.all(np.abs(sol.y[:, -1] - y0) <= 1e-8 * scale)  # it is periodic
    clutch = period_maximum(sol, np.array([1.0, 0.0, 0.0, 0.0]), t) / (load / c1)
    coupling = period_maximum(sol, np.array([0.0, c2, 0.0, b2]), t) / load
    return clutch, coupling


def test_chi_before_and_after_with_given_clutch_damping(cli, write_case) -> None:
    # a clutch damping given as b is the clutch's in both models (brief §7f)
    b1 = 1500.0
    drive = with_(DRIVE, clutch_loop_area_ratio=None, clutch_damping=b1)
    data = variator(mechanism=MECHANISM, drive=drive, antiresonance=ANTIRESONANCE)
    document = run_json(cli, write_case, data)
    walk_finite(document)
    r = values(document)
    j2, j3, c1, load = 1.55, 46.5, 8.9e5 * KGF_M, 300.0
    _, _, t, omega = sawtooth(MECHANISM)
    c2 = (4 * omega) ** 2 * j2 * j3 / (j2 + j3)
    # before: J₃ rigid on the output shaft, J = J₂ + J₃', integrated from rest
    _, sol = from_rest(two_mass(MECHANISM, j2 + j3, c1, b1, load), t, 400)
    before = period_maximum(sol, np.array([1.0, 0.0]), t) / (load / c1)
    assert r["drive_inertia"] == pytest.approx(j2 + j3, rel=1e-15)
    assert r["drive_damping"] == b1
    assert r["antiresonance_chi_before"] == pytest.approx(before, rel=1e-8)
    assert r["drive_chi"] == pytest.approx(before, rel=1e-8)
    after, coupling = chi_after(j2, j3, c1, b1, c2, 0.0, load)
    assert r["antiresonance_chi_after"] == pytest.approx(after, rel=1e-7)
    assert r["antiresonance_coupling_factor"] == pytest.approx(coupling, rel=1e-7)
    reduction = (before - 1.0) / (after - 1.0)
    assert r["antiresonance_reduction"] == pytest.approx(reduction, rel=1e-6)
    # J₃'/J₂ = 30 with light damping: the clutch's dynamic load drops more than tenfold
    assert r["antiresonance_reduction"] > 10.0


def test_chi_before_and_after_with_loop_area_ratio(cli, write_case) -> None:
    # ψ = 0.6: before, b = ψ/(2π)·√((J₂ + J₃')·c₁) (8.44). After, the brief keeps that
    # b₁ ("the same b1 as the two-mass model"); a later reading of (8.44) uses the J the
    # clutch faces, J₂ alone, and reports it as antiresonance_clutch_damping with the
    # brief's reading beside it (*_kept_damping). Either way every number must be the
    # one integrated here for the b₁ it says it used, and that b₁ must be one of the two.
    data = variator(mechanism=MECHANISM, drive=DRIVE, antiresonance=ANTIRESONANCE)
    document = run_json(cli, write_case, data)
    walk_finite(document)
    r = values(document)
    j2, j3, c1, load = 1.55, 46.5, 8.9e5 * KGF_M, 300.0
    kept = 0.6 / (2.0 * math.pi) * math.sqrt((j2 + j3) * c1)
    faced = 0.6 / (2.0 * math.pi) * math.sqrt(j2 * c1)
    _, _, t, omega = sawtooth(MECHANISM)
    c2 = (4 * omega) ** 2 * j2 * j3 / (j2 + j3)
    _, sol = from_rest(two_mass(MECHANISM, j2 + j3, c1, kept, load), t, 400)
    before = period_maximum(sol, np.array([1.0, 0.0]), t) / (load / c1)
    assert r["drive_damping"] == pytest.approx(kept, rel=1e-14)
    assert r["antiresonance_chi_before"] == pytest.approx(before, rel=1e-8)
    b1 = r.get("antiresonance_clutch_damping", kept)
    assert b1 == pytest.approx(kept, rel=1e-12) or b1 == pytest.approx(faced, rel=1e-12)
    after, coupling = chi_after(j2, j3, c1, b1, c2, 0.0, load)
    assert r["antiresonance_chi_after"] == pytest.approx(after, rel=1e-7)
    assert r["antiresonance_coupling_factor"] == pytest.approx(coupling, rel=1e-7)
    assert r["antiresonance_reduction"] == pytest.approx((before - 1) / (after - 1), rel=1e-6)
    assert r["antiresonance_reduction"] > 10.0
    if "antiresonance_chi_after_kept_damping" in r:
        after_kept, _ = chi_after(j2, j3, c1, kept, c2, 0.0, load)
        assert r["antiresonance_chi_after_kept_damping"] == pytest.approx(after_kept, rel=1e-7)


def test_given_damped_coupling_by_integration_from_rest(cli, write_case) -> None:
    # a given coupling (not tuned) with damping b₂ and a given clutch b₁: every mode
    # decays, so the periodic state is reached from rest
    ar = with_(ANTIRESONANCE, coupling_stiffness=5.0e4, coupling_damping=1000.0)
    b1 = 1000.0
    drive = with_(DRIVE, clutch_loop_area_ratio=None, clutch_damping=b1)
    data = variator(mechanism=MECHANISM, drive=drive, antiresonance=ar)
    r = values(run_json(cli, write_case, data))
    i, j2, j3, c1, load = 2.0, 1.55, 46.5, 8.9e5 * KGF_M, 300.0
    c2, b2 = i * i * 5.0e4, i * i * 1000.0  # reduced to the output shaft
    assert r["antiresonance_coupling"] == pytest.approx(5.0e4, rel=1e-15)
    assert r["antiresonance_frequency"] == pytest.approx(
        math.sqrt(c2 * (j2 + j3) / (j2 * j3)), rel=1e-14
    )
    _, _, t, _ = sawtooth(MECHANISM)
    _, sol = from_rest(three_mass(MECHANISM, j2, j3, c1, b1, c2, b2, load), t, 3000)
    after = period_maximum(sol, np.array([1.0, 0.0, 0.0, 0.0]), t) / (load / c1)
    coupling = period_maximum(sol, np.array([0.0, c2, 0.0, b2]), t) / load
    assert r["antiresonance_chi_after"] == pytest.approx(after, rel=1e-7)
    assert r["antiresonance_coupling_factor"] == pytest.approx(coupling, rel=1e-7)


# ----------------------------------------------------------------------------- pendulum


def agm_by_hand(a: float, b: float) -> float:
    for _ in range(40):
        a, b = (a + b) / 2, math.sqrt(a * b)
    return a


def pendulum_order(order: float, swing: float) -> float:
    """Oscillations per revolution of θ'' = -n²ω² sin θ swung to θ_max, from the period
    of the integrated equation (ω = 1: the order is 2π/period): a quarter period is the
    time from θ_max at rest to θ = 0 (an event of solve_ivp, rtol 1e-13)."""

    def rhs(_t: float, y: np.ndarray) -> list[float]:
        return [y[1], -(order**2) * math.sin(y[0])]

    def crossing(_t: float, y: np.ndarray) -> float:
        return y[0]

    crossing.terminal = True  # type: ignore[attr-defined]
    crossing.direction = -1  # type: ignore[attr-defined]
    run = solve_ivp(
        rhs, (0.0, 100.0 / order), [swing, 0.0], events=crossing, rtol=1e-13, atol=1e-15
    )
    quarter = float(run.t_events[0][0])
    return 2.0 * math.pi / (4.0 * quarter)


def test_pendulum_seed_reference_length(cli, write_case) -> None:
    # seed 000 §8.5: R = 0.1 m, n = 4 → L = R/n² = 6.25 mm
    r = values(run_json(cli, write_case, variator(pendulum={"pivot_radius": 0.1, "order": 4.0})))
    assert r["pendulum_length"] == pytest.approx(6.25e-3, rel=1e-15)


@pytest.mark.parametrize("swing", [0.1, 0.5, 1.2, 2.5, 3.1])
def test_pendulum_detuning_at_large_swing(cli, write_case, swing) -> None:
    data = {"pivot_radius": 0.1, "order": 4.0, "max_swing": swing}
    r = values(run_json(cli, write_case, variator(pendulum=data)))
    numeric = pendulum_order(4.0, swing)
    assert r["pendulum_order_at_swing"] == pytest.approx(numeric, rel=1e-9)
    # π/(2K(k)), k = sin(θ/2), with scipy's K(m = k²)
    elliptic = 4.0 * math.pi / (2.0 * float(ellipk(math.sin(swing / 2) ** 2)))
    assert r["pendulum_order_at_swing"] == pytest.approx(elliptic, rel=1e-13)
    assert r["pendulum_order_at_swing"] < 4.0  # a large swing detunes downwards
    # the pendulum of the reported length has order n at that swing
    length = r["pendulum_length_at_swing"]
    assert length == pytest.approx(6.25e-3 * agm_by_hand(1.0, math.cos(swing / 2)) ** 2, rel=1e-14)
    assert pendulum_order(math.sqrt(0.1 / length), swing) == pytest.approx(4.0, rel=1e-9)


@pytest.mark.parametrize(
    "torque,buildable", [(0.5, True), (50.0, False)], ids=["light bob", "heavy bob"]
)
def test_pendulum_mass_and_bob(cli, write_case, torque, buildable) -> None:
    data = {
        "pivot_radius": 0.1,
        "order": 4.0,
        "speed_rpm": 3000.0,
        "inertia_torque": torque,
        "max_swing": 0.3,
        "bifilar_pin_diameter": 0.012,
    }
    document = run_json(cli, write_case, variator(pendulum=data))
    r = values(document)
    omega = 3000.0 * 2.0 * math.pi / 60.0
    length = 0.1 / 16.0
    mass = torque / (omega**2 * (0.1 + length) * 0.1 * 0.3)  # (8.56)
    radius = (3.0 * mass / (4.0 * math.pi * 7850.0)) ** (1.0 / 3.0)
    assert r["pendulum_mass"] == pytest.approx(mass, rel=1e-14)
    assert r["pendulum_bob_radius"] == pytest.approx(radius, rel=1e-14)
    assert (radius < length) is buildable
    assert r["pendulum_buildable"] is buildable
    warned = [n for n in document["notes"] if n.get("level") == "warning"]
    assert bool(warned) is (not buildable)
    assert r["pendulum_bifilar_hole"] == pytest.approx(0.012 + length, rel=1e-15)
    # the speed in rad/s gives the same
    fast = with_(data, speed_rpm=None, speed=omega)
    assert values(run_json(cli, write_case, variator(pendulum=fast)))["pendulum_mass"] == (
        pytest.approx(mass, rel=1e-14)
    )


def test_pendulum_density(cli, write_case) -> None:
    data = {
        "pivot_radius": 0.2,
        "order": 3.0,
        "speed": 150.0,
        "inertia_torque": 12.0,
        "max_swing": 0.4,
        "bob_density": 11340.0,
    }
    r = values(run_json(cli, write_case, variator(pendulum=data)))
    length = 0.2 / 9.0
    mass = 12.0 / (150.0**2 * (0.2 + length) * 0.2 * 0.4)
    assert r["pendulum_length"] == pytest.approx(length, rel=1e-15)
    assert r["pendulum_bob_radius"] == pytest.approx(
        (3.0 * mass / (4.0 * math.pi * 11340.0)) ** (1.0 / 3.0), rel=1e-14
    )


# ----------------------------------------------------------------------------- input errors

BAD_INPUTS = {
    "misspelt key": (
        variator(absorber=with_(ABSORBER, inertia=None, inertai=2.0)),
        r"absorber\.inertai",
    ),
    "negative inertia": (variator(absorber=with_(ABSORBER, inertia=-2.0)), r"absorber\.inertia"),
    "both tunings": (
        variator(absorber=with_(ABSORBER, absorber_stiffness=80.0, tuning_frequency=20.0)),
        r"absorber",
    ),
    "drive without mechanism": (variator(drive=DRIVE), r"drive"),
    "antiresonance without drive": (
        variator(mechanism=MECHANISM, antiresonance=ANTIRESONANCE),
        r"antiresonance",
    ),
    "nominal speed at synchronous": (
        variator(
            motor={
                "pole_pairs": 2,
                "nominal_speed_rpm": 1500.0,
                "nominal_torque": 1.0,
                "overload_ratio": 2.0,
            }
        ),
        r"motor\.nominal_speed_rpm",
    ),
    "nominal speed above synchronous": (
        variator(
            motor={
                "pole_pairs": 2,
                "nominal_speed_rpm": 1600.0,
                "nominal_torque": 1.0,
                "overload_ratio": 2.0,
            }
        ),
        r"motor\.nominal_speed_rpm",
    ),
    "torque and power": (
        variator(
            motor={
                "pole_pairs": 2,
                "nominal_speed_rpm": 1450.0,
                "nominal_torque": 1.0,
                "nominal_power": 1.0e3,
                "overload_ratio": 2.0,
            }
        ),
        r"motor",
    ),
    "one mechanism": (variator(mechanism=with_(MECHANISM, mechanisms=1)), r"mechanism\.mechanisms"),
    "ratio and output speed": (
        variator(mechanism=with_(MECHANISM, output_speed_rpm=185.0)),
        r"mechanism",
    ),
    "loop area and damping": (
        variator(mechanism=MECHANISM, drive=with_(DRIVE, clutch_damping=10.0)),
        r"drive",
    ),
    "negative load torque": (
        variator(mechanism=MECHANISM, drive=with_(DRIVE, load_torque=-300.0)),
        r"drive\.load_torque",
    ),
    "load range empty": (
        variator(clutch=with_(CLUTCH_CASES["softening n = 0.6"][0], load_min=900.0)),
        r"clutch\.load_min",
    ),
    "mass without swing": (
        variator(
            pendulum={"pivot_radius": 0.1, "order": 4.0, "speed": 10.0, "inertia_torque": 5.0}
        ),
        r"pendulum\.max_swing",
    ),
    "no section": ({"problem": "variator", "title": "nothing"}, r""),
}


@pytest.mark.parametrize("data,path", BAD_INPUTS.values(), ids=BAD_INPUTS.keys())
def test_bad_input_exits_2_with_located_message(cli, write_case, data, path) -> None:
    file = write_case(toml_dumps(data))
    result = cli("variator", file)
    assert result.exit_code == 2, result.stdout
    assert_no_traceback(result)
    pattern = rf"^{re.escape(str(file))}(:\d+)?: error: {path}"
    assert re.search(pattern, result.stderr, re.MULTILINE), result.stderr


def test_console_script_exit_codes(write_case) -> None:
    # the real console script: 0 with JSON, 2 located, 3 unbounded; never a traceback
    good = write_case(toml_dumps(variator(absorber=ABSORBER)), "good.toml")
    done = run_script("variator", good, "--json")
    assert done.returncode == 0, done.stderr
    assert strict_json(done.stdout)["results"]["absorber_a1"]["value"] == 0.0
    bad = write_case(toml_dumps(variator(drive=DRIVE)), "bad.toml")
    done = run_script("variator", bad)
    assert done.returncode == 2
    assert "Traceback" not in done.stderr
    assert re.search(r":\d+: error: drive", done.stderr), done.stderr
    resonant = {
        "inertia": 1.0,
        "stiffness": 2.0,
        "absorber_inertia": 0.5,
        "absorber_stiffness": 1.0,
        "torque_amplitude": 1.0,
        "frequency": 1.0,
    }
    done = run_script("variator", write_case(toml_dumps(variator(absorber=resonant)), "r.toml"))
    assert done.returncode == 3
    assert "unbounded" in done.stderr and "Traceback" not in done.stderr


def test_every_section_at_once_is_finite(cli, write_case) -> None:
    data = variator(
        absorber=with_(ABSORBER, absorber_damping=0.5),
        motor=MOTOR_CASES["4-pole 50 Hz torque"][0],
        clutch=CLUTCH_CASES["stiffening n = 1.5, kgf·m"][0],
        mechanism=MECHANISM,
        drive=DRIVE,
        antiresonance=ANTIRESONANCE,
        pendulum={
            "pivot_radius": 0.1,
            "order": 4.0,
            "speed": 100.0,
            "inertia_torque": 1.0,
            "max_swing": 0.5,
        },
    )
    document = run_json(cli, write_case, data)
    walk_finite(document)
    assert document["status"] == "ok"
    # text output works too
    text = cli("variator", write_case(toml_dumps(data), "all.toml"))
    assert text.exit_code == 0, text.stderr
    assert "6.25" in text.stdout or "0.00625" in text.stdout  # L = 6.25 mm
