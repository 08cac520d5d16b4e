"""Independent physics tests of ``mdcalc mount`` (brief PROBLEMS.md §4, seed 000 §7.5,
(7.49)-(7.78), example 9.1).

Every expected value below is a hand calculation from the formulas of the brief and of
seed ``000_3ece989f7275045f.txt`` (equation numbers cited next to each), written out in
the test, or a numerical computation written in this file: dense sampling of the
steady two-harmonic sum over a revolution, and a long integration of the ODE (scipy's
DOP853 at rtol 1e-12) run into steady state. None is copied from the program's output
and none uses the program's own formula functions; the package is imported only to
run a case file.

Model (brief §4, (7.60)): M·x'' + c_d·x' + c·x = m·r·ω²·(cos ωt + λ·cos 2ωt), c = G/f
(7.50), c_d = 2ζ√(cM). Each harmonic k = 1, 2 has the steady complex amplitude
X_k = F_k/(c - M·(kω)² + i·c_d·kω), F₁ = m·r·ω², F₂ = λ·m·r·ω², and x = Re(X₁e^{iθ} +
X₂e^{2iθ}), θ = ωt the crank angle. The force on the frame is c·x + c_d·x', of
complex amplitude (c + i·c_d·kω)·X_k per harmonic.
"""

from __future__ import annotations

import cmath
import copy
import json
import math
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from scipy.integrate import ode
from scipy.optimize import brentq, minimize_scalar
from tomli_w import dumps as toml_dumps

from mdcalc.output.jsondoc import to_json
from mdcalc.runs.runner import run_case

TIGHT = 1e-10  # relative tolerance against hand values (brief: "to 1e-10")
ODE = 1e-8  # relative tolerance against the own integration into steady state

# ----------------------------------------------------------------------------- helpers


def write_case(tmp_path: Path, data: dict[str, Any], name: str = "case.toml") -> Path:
    path = tmp_path / name
    path.write_text(toml_dumps(data), encoding="utf-8")
    return path


def run_report(tmp_path: Path, data: dict[str, Any]) -> Any:
    return run_case(write_case(tmp_path, data))


def run(tmp_path: Path, data: dict[str, Any]) -> dict[str, Any]:
    """Run a case in-process; every result value by key (plus ``status``)."""
    return {key: q.value for key, q in run_report(tmp_path, data).results().items()}


def mdcalc_exe() -> str:
    found = shutil.which("mdcalc")
    if found:
        return found
    return str(Path(sys.executable).parent / "mdcalc")


def run_script(path: Path, *options: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [mdcalc_exe(), "mount", str(path), *options], capture_output=True, text=True, timeout=120
    )


def rel(expected: float, tol: float = TIGHT) -> Any:
    return pytest.approx(expected, rel=tol)


# Seed 000 example 9.1 (brief §4 reference), with the lecture's g = 9.81.
EXAMPLE: dict[str, Any] = {
    "problem": "mount",
    "gravity": 9.81,
    "engine": {"weight": 10000.0},
    "mounts": {"static_deflection": 0.01},
    "crank": {"piston_weight": 100.0, "radius": 0.05, "rod_ratio": 0.2, "speed": 150.0},
}


def scene(
    mass: float,
    stiffness: float,
    piston: float,
    radius: float,
    rod_ratio: float,
    speed: float,
    zeta: float | None = None,
    **extra: Any,
) -> dict[str, Any]:
    """A case given by masses and stiffness directly (SI)."""
    mounts: dict[str, Any] = {"stiffness": stiffness}
    if zeta is not None:
        mounts["damping_ratio"] = zeta
    data: dict[str, Any] = {
        "problem": "mount",
        "engine": {"mass": mass},
        "mounts": mounts,
        "crank": {
            "piston_mass": piston,
            "radius": radius,
            "rod_ratio": rod_ratio,
            "speed": speed,
        },
    }
    data.update(copy.deepcopy(extra))
    return data


def amplitudes(
    mass: float, stiffness: float, piston: float, radius: float, lam: float, w: float, zeta: float
) -> tuple[complex, complex, float]:
    """Own complex steady amplitudes X₁, X₂ (module docstring) and c_d."""
    cd = 2.0 * zeta * math.sqrt(stiffness * mass)
    f1 = piston * radius * w * w
    x1 = f1 / complex(stiffness - mass * w * w, cd * w)
    x2 = lam * f1 / complex(stiffness - 4.0 * mass * w * w, 2.0 * cd * w)
    return x1, x2, cd


def sampled_peak(first: complex, second: complex) -> tuple[float, float]:
    """max over θ of |Re(first·e^{iθ} + second·e^{2iθ})| and its θ in [0, 2π): 2¹⁶
    samples, then the best one refined by a bounded scalar search over ± one sample."""
    n = 1 << 16
    theta = np.arange(n) * (2.0 * math.pi / n)
    values = np.abs((first * np.exp(1j * theta) + second * np.exp(2j * theta)).real)
    k = int(np.argmax(values))
    step = 2.0 * math.pi / n

    def minus(t: float) -> float:
        return -abs((first * cmath.exp(1j * t) + second * cmath.exp(2j * t)).real)

    found = minimize_scalar(
        minus,
        bounds=(theta[k] - step, theta[k] + step),
        method="bounded",
        options={"xatol": 1e-13},
    )
    best = max((float(values[k]), float(theta[k])), (-float(found.fun), float(found.x)))
    return best[0], best[1] % (2.0 * math.pi)


def steady_ode_peaks(
    mass: float, stiffness: float, cd: float, f1: float, f2: float, w: float
) -> tuple[float, float]:
    """Own integration of M·x'' + c_d·x' + c·x = F₁cos ωt + F₂cos 2ωt from rest, over
    whole revolutions until the free vibration has decayed by e^-32 (rate ζβ = c_d/(2M),
    or the slow root β(ζ - √(ζ²-1)) when over-damped), then the largest |x| and
    |c·x + c_d·x'| over one more revolution: 400 samples, every extremum in between
    refined by Brent's method on the derivative (re-integrating from the sample before it)."""
    beta = math.sqrt(stiffness / mass)
    scale = (f1 + f2) / stiffness

    def rhs(t: float, y: np.ndarray) -> list[float]:
        force = f1 * math.cos(w * t) + f2 * math.cos(2.0 * w * t)
        return [y[1], (force - cd * y[1] - stiffness * y[0]) / mass]

    def solver_from(y0: Any, t0: float) -> Any:
        solver = ode(rhs).set_integrator(
            "dop853",
            rtol=1e-12,
            atol=1e-14 * scale,
            nsteps=10**8,
            first_step=1e-3 / max(beta, w),
        )
        solver.set_initial_value(list(y0), t0)
        return solver

    period = 2.0 * math.pi / w
    zeta = cd / (2.0 * math.sqrt(stiffness * mass))
    rate = zeta * beta if zeta <= 1.0 else beta * (zeta - math.sqrt(zeta * zeta - 1.0))
    start = math.ceil(32.0 / rate / period) * period
    solver = solver_from([0.0, 0.0], 0.0)
    solver.integrate(start)
    n = 400
    grid = start + period * np.arange(n + 1) / n
    states = [np.array(solver.y)]
    for t in grid[1:]:
        states.append(np.array(solver.integrate(t)))
    assert solver.successful()

    def accel(t: float, y: np.ndarray) -> float:
        return rhs(t, y)[1]

    def force(t: float, y: np.ndarray) -> float:
        return stiffness * y[0] + cd * y[1]

    def d_force(t: float, y: np.ndarray) -> float:
        return stiffness * y[1] + cd * accel(t, y)

    def peak(value: Any, slope: Any) -> float:
        best = max(abs(value(t, y)) for t, y in zip(grid, states, strict=True))
        for j in range(n):
            ta, ya, tb = float(grid[j]), states[j], float(grid[j + 1])

            def along(t: float, ta: float = ta, ya: np.ndarray = ya) -> np.ndarray:
                return ya if t == ta else np.array(solver_from(ya, ta).integrate(t))

            sa, sb = slope(ta, ya), slope(tb, along(tb))
            if sa * sb < 0.0:
                root = brentq(lambda t: slope(t, along(t)), ta, tb, xtol=1e-15, rtol=1e-15)
                best = max(best, abs(value(root, along(root))))
        return best

    return peak(lambda t, y: y[0], lambda t, y: y[1]), peak(force, d_force)


def transmissibility(r: float, zeta: float) -> float:
    """Textbook force transmissibility √(1 + (2ζr)²)/√((1 - r²)² + (2ζr)²)."""
    return math.sqrt(1.0 + (2.0 * zeta * r) ** 2) / math.sqrt(
        (1.0 - r * r) ** 2 + (2.0 * zeta * r) ** 2
    )


def crank_angle(report: Any) -> float:
    """The crank angle [°] printed in the note of peak_displacement."""
    note = report.results()["peak_displacement"].note
    found = re.search(r"crank angle (-?[\d.]+)°", note)
    assert found, note
    return float(found.group(1))


# ------------------------------------------------------------------ example 9.1


G_EX = 9.81
M_EX = 10000.0 / G_EX  # engine mass 1019.37 kg
P_EX = 100.0 / G_EX  # piston mass 10.194 kg
C_EX = 10000.0 / 0.01  # (7.50) c = G/f = 1.0e6 N/m
W_EX = 150.0
F1_EX = P_EX * 0.05 * W_EX**2  # m·r·ω² = 11 467.9 N
A1_EX = F1_EX / (C_EX - M_EX * W_EX**2)  # (7.75): -5.2279e-4 m (above resonance: negative)
A2_EX = 0.2 * F1_EX / (C_EX - 4.0 * M_EX * W_EX**2)  # -2.5275e-5 m


def test_example_9_1_reference_numbers(tmp_path: Path) -> None:
    """Brief §4 reference (rounded, as printed there): c = 1.0e6 N/m, β = 31.3 rad/s,
    second-harmonic resonance 15.7 rad/s, |A₁| = 0.523 mm, |A₂| = 0.0253 mm, lecture
    estimate m·r/M = 10·50/10³ = 0.5 mm."""
    r = run(tmp_path, EXAMPLE)
    assert r["status"] == "ok"
    assert r["stiffness"] == rel(1.0e6)
    assert r["natural_frequency"] == pytest.approx(31.3, abs=0.05)
    assert r["resonant_speed_1"] == pytest.approx(31.3, abs=0.05)
    assert r["resonant_speed_2"] == pytest.approx(15.7, abs=0.05)
    assert r["amplitude_1"] * 1e3 == pytest.approx(0.523, abs=5e-4)
    assert r["amplitude_2"] * 1e3 == pytest.approx(0.0253, abs=5e-5)
    report = run_report(tmp_path, EXAMPLE)
    methods = json.loads(to_json(report))
    table = next(s for s in methods["sections"] if s["kind"] == "methods")
    lecture = next(row for row in table["rows"] if row["method"] == "lecture m·r/M")
    assert lecture["values"]["peak_displacement"] * 1e3 == pytest.approx(0.5, rel=TIGHT)


def test_example_9_1_hand_values(tmp_path: Path) -> None:
    """Unrounded hand values of example 9.1 (g = 9.81): M = 10⁴/9.81, m = 100/9.81,
    c = G/f = 10⁶ (7.50); β = √(c/M) = √(g/f) = √981 = 31.3209 rad/s; F₁ = m·r·ω²;
    A₁, A₂ by (7.70)/(7.75) with the brief's second-harmonic denominator c - 4Mω²;
    μ = 1/(1 - ω²M/c) (7.78) = -0.045588. Peak: x = A₁cos θ + A₂cos 2θ, x' = -sin θ·
    (A₁ + 4A₂cos θ) vanishes only at θ = 0, π (|A₁/(4A₂)| = 5.17 > 1), so the peak is
    |A₁ + A₂| = |A₁| + |A₂| (same sign) at θ = 0."""
    report = run_report(tmp_path, EXAMPLE)
    r = {key: q.value for key, q in report.results().items()}
    beta = math.sqrt(981.0)
    assert r["stiffness"] == rel(C_EX)
    assert r["static_deflection"] == rel(0.01)
    assert r["natural_frequency"] == rel(beta)
    assert r["natural_frequency_hz"] == rel(beta / (2.0 * math.pi))
    assert r["resonant_speed_1"] == rel(beta)
    assert r["resonant_speed_2"] == rel(beta / 2.0)
    assert r["frequency_ratio"] == rel(W_EX / beta)
    assert r["force_1"] == rel(F1_EX)
    assert r["force_2"] == rel(0.2 * F1_EX)
    assert r["amplitude_1"] == rel(abs(A1_EX))
    assert r["amplitude_2"] == rel(abs(A2_EX))
    assert A1_EX < 0 and A2_EX < 0 and abs(A1_EX) > 4.0 * abs(A2_EX)
    assert r["peak_displacement"] == rel(abs(A1_EX) + abs(A2_EX))  # 0.54806 mm
    assert crank_angle(report) % 360.0 == pytest.approx(0.0, abs=0.05)
    assert r["dynamic_factor"] == rel(1.0 / (1.0 - W_EX**2 * M_EX / C_EX))
    assert r["quasi_static"] is False
    for key in ("damping_coefficient", "transmitted_force_peak", "required_stiffness"):
        assert key not in r  # no damping, no [isolation]


def test_example_9_1_methods_table(tmp_path: Path) -> None:
    """Methods rows (brief §4): lecture m·r/M = 5e-4 m; with the second harmonic
    m·r/M·(1 + λ/4) = 5.25e-4 m; |A₁|; |A₁| + |A₂|; the exact peak (reference) =
    |A₁| + |A₂| here (see test_example_9_1_hand_values). Errors relative to it."""
    document = json.loads(to_json(run_report(tmp_path, EXAMPLE)))
    assert document["status"] == "ok"
    tables = [s for s in document["sections"] if s["kind"] == "methods"]
    assert len(tables) == 1
    rows = {row["method"]: row for row in tables[0]["rows"]}
    peak = abs(A1_EX) + abs(A2_EX)
    expected = {
        "lecture m·r/M": 100.0 * 0.05 / 10000.0,
        "lecture m·r/M + m·r·λ/(4M)": 100.0 * 0.05 / 10000.0 * (1.0 + 0.2 / 4.0),
        "first harmonic |A₁|": abs(A1_EX),
        "|A₁| + |A₂|": peak,
        "exact peak of the two-harmonic sum": peak,
    }
    assert set(rows) == set(expected)
    for name, value in expected.items():
        assert rows[name]["values"]["peak_displacement"] == rel(value)
        assert rows[name]["reference"] is (name == "exact peak of the two-harmonic sum")
        if not rows[name]["reference"]:
            error = rows[name]["rel_errors"]["peak_displacement"]
            assert error == pytest.approx(abs(value - peak) / peak, rel=1e-6, abs=1e-12)
    assert document["results"]["peak_displacement"]["unit"] == "m"


def test_example_default_gravity_and_rpm(tmp_path: Path) -> None:
    """Without ``gravity``: g = 9.80665, so M = 10⁴/9.80665, m = 100/9.80665, c = G/f =
    10⁶ still, β = √(g/f); the speed in rpm: ω = 2π·n/60."""
    data = copy.deepcopy(EXAMPLE)
    del data["gravity"]
    n_rpm = 1432.0
    data["crank"] = {**data["crank"], "speed_rpm": n_rpm}
    del data["crank"]["speed"]
    r = run(tmp_path, data)
    g = 9.80665
    mass, piston, w = 10000.0 / g, 100.0 / g, 2.0 * math.pi * n_rpm / 60.0
    assert r["stiffness"] == rel(1.0e6)
    assert r["natural_frequency"] == rel(math.sqrt(g / 0.01))
    assert r["force_1"] == rel(piston * 0.05 * w * w)
    assert r["amplitude_1"] == rel(piston * 0.05 * w * w / abs(1.0e6 - mass * w * w))
    assert r["amplitude_2"] == rel(0.2 * piston * 0.05 * w * w / abs(1.0e6 - 4 * mass * w * w))


def test_mass_and_stiffness_inputs(tmp_path: Path) -> None:
    """Masses and stiffness given directly: f = M·g/c is reported (g = 9.80665 default),
    β = √(c/M) = √(8e5/400) = √2000."""
    r = run(tmp_path, scene(400.0, 8.0e5, 3.0, 0.04, 0.25, 120.0))
    assert r["static_deflection"] == rel(400.0 * 9.80665 / 8.0e5)
    assert r["natural_frequency"] == rel(math.sqrt(2000.0))
    x1, x2, _ = amplitudes(400.0, 8.0e5, 3.0, 0.04, 0.25, 120.0, 0.0)
    assert r["amplitude_1"] == rel(abs(x1))
    assert r["amplitude_2"] == rel(abs(x2))


# ------------------------------------------------------ peak of the two-harmonic sum

# (mass, stiffness, piston, radius, λ, ω, ζ); β = √(c/M)
PEAK_CASES = {
    # β = 10 rad/s below: ω = 3 (both harmonics below resonance, in phase: θ = 0)
    "undamped-below-both": (100.0, 1.0e4, 2.0, 0.1, 0.3, 3.0, None),
    # β/2 < ω < β: A₁ > 0, A₂ < 0, the peak |A₁| + |A₂| at θ = π, not 0
    "undamped-between": (100.0, 1.0e4, 2.0, 0.1, 0.25, 7.5, None),
    # second harmonic dominant (2ω just above β) and out of phase with the first
    "undamped-second-large": (100.0, 1.0e4, 2.0, 0.1, 0.9, 5.2, None),
    "undamped-example-9.1": (10000.0 / 9.81, 1.0e6, 100.0 / 9.81, 0.05, 0.2, 150.0, None),
    "explicit-zero-damping": (100.0, 1.0e4, 2.0, 0.1, 0.25, 7.5, 0.0),
    # damped: phases differ, the peak is at a general crank angle
    "damped-second-near-resonance": (100.0, 1.0e4, 2.0, 0.1, 0.3, 5.2, 0.2),
    "damped-between": (100.0, 1.0e4, 2.0, 0.1, 0.6, 7.5, 0.1),
    "damped-example-9.1": (10000.0 / 9.81, 1.0e6, 100.0 / 9.81, 0.05, 0.2, 150.0, 0.05),
    "damped-light-at-half-beta": (50.0, 2.0e5, 1.0, 0.08, 0.35, 31.0, 0.02),
    "damped-heavy": (100.0, 1.0e4, 2.0, 0.1, 0.5, 8.0, 0.7),
    "over-damped": (100.0, 1.0e4, 2.0, 0.1, 0.5, 4.0, 2.5),
}


@pytest.mark.parametrize("name", list(PEAK_CASES))
def test_peak_against_dense_sampling(tmp_path: Path, name: str) -> None:
    """peak_displacement = max over a revolution of |x|, against the own dense sampling
    of the own complex amplitudes; the crank angle in its note against the sampled one;
    |A₁|, |A₂| against the moduli."""
    mass, stiffness, piston, radius, lam, w, zeta = PEAK_CASES[name]
    report = run_report(tmp_path, scene(mass, stiffness, piston, radius, lam, w, zeta))
    r = {key: q.value for key, q in report.results().items()}
    x1, x2, _ = amplitudes(mass, stiffness, piston, radius, lam, w, zeta or 0.0)
    peak, theta = sampled_peak(x1, x2)
    assert r["amplitude_1"] == rel(abs(x1))
    assert r["amplitude_2"] == rel(abs(x2))
    assert r["peak_displacement"] == rel(peak)
    assert abs(x1) + abs(x2) >= peak * (1 - 1e-12)  # the |A₁| + |A₂| bound
    # the printed angle (one decimal); |x(θ)| is even in θ when undamped, so for a peak at
    # θ = 0 or π compare modulo the symmetry
    printed = math.radians(crank_angle(report))
    assert (
        abs(abs((x1 * cmath.exp(1j * printed) + x2 * cmath.exp(2j * printed)).real) - peak)
        <= peak * 1e-5
    )
    if name == "undamped-between":
        assert theta == pytest.approx(math.pi, abs=1e-6)
        assert peak == rel(abs(x1) + abs(x2))
        assert crank_angle(report) == pytest.approx(180.0, abs=0.05)
    if name.startswith("damped-second") or name == "damped-between":
        assert min(theta, 2.0 * math.pi - theta) > 0.1  # not at θ = 0
        assert abs(theta - math.pi) > 0.1  # nor at π (damped-between: θ = 187°)
        assert math.remainder(math.radians(crank_angle(report)) - theta, 2 * math.pi) == (
            pytest.approx(0.0, abs=math.radians(0.06))
        )


ODE_CASES = ["damped-second-near-resonance", "damped-between", "damped-example-9.1", "over-damped"]


@pytest.mark.parametrize("name", ODE_CASES)
def test_damped_peaks_against_own_integration(tmp_path: Path, name: str) -> None:
    """With damping: peak_displacement and transmitted_force_peak against the own long
    integration of the ODE from rest into steady state (max over the last revolution)."""
    mass, stiffness, piston, radius, lam, w, zeta = PEAK_CASES[name]
    assert zeta
    r = run(tmp_path, scene(mass, stiffness, piston, radius, lam, w, zeta))
    cd = 2.0 * zeta * math.sqrt(stiffness * mass)
    f1 = piston * radius * w * w
    peak_x, peak_force = steady_ode_peaks(mass, stiffness, cd, f1, lam * f1, w)
    assert r["peak_displacement"] == rel(peak_x, ODE)
    assert r["transmitted_force_peak"] == rel(peak_force, ODE)


@pytest.mark.parametrize(
    "name", ["damped-second-near-resonance", "damped-between", "damped-heavy", "over-damped"]
)
def test_transmitted_force_against_dense_sampling(tmp_path: Path, name: str) -> None:
    """transmitted_force_peak = max over a revolution of |c·x + c_d·x'|, the sum of the
    harmonics (c + i·c_d·kω)·X_k, by the own dense sampling."""
    mass, stiffness, piston, radius, lam, w, zeta = PEAK_CASES[name]
    r = run(tmp_path, scene(mass, stiffness, piston, radius, lam, w, zeta))
    x1, x2, cd = amplitudes(mass, stiffness, piston, radius, lam, w, zeta or 0.0)
    t1, t2 = complex(stiffness, cd * w) * x1, complex(stiffness, 2.0 * cd * w) * x2
    assert r["transmitted_force_peak"] == rel(sampled_peak(t1, t2)[0])


@pytest.mark.parametrize(
    "name", ["damped-second-near-resonance", "damped-example-9.1", "over-damped"]
)
def test_damping_keys_hand_values(tmp_path: Path, name: str) -> None:
    """c_d = 2ζ√(cM); transmissibility of harmonic k at r_k = kω/β by the textbook
    formula; transmitted force k = T_k·F_k; μ = 1/√((1 - r²)² + (2ζr)²) damped."""
    mass, stiffness, piston, radius, lam, w, zeta = PEAK_CASES[name]
    assert zeta
    r = run(tmp_path, scene(mass, stiffness, piston, radius, lam, w, zeta))
    beta = math.sqrt(stiffness / mass)
    f1 = piston * radius * w * w
    assert r["damping_coefficient"] == rel(2.0 * zeta * math.sqrt(stiffness * mass))
    for k, force in ((1, f1), (2, lam * f1)):
        t_k = transmissibility(k * w / beta, zeta)
        assert r[f"transmissibility_{k}"] == rel(t_k)
        assert r[f"transmitted_force_{k}"] == rel(t_k * force)
    ratio = w / beta
    assert r["dynamic_factor"] == rel(
        1.0 / math.sqrt((1.0 - ratio**2) ** 2 + (2.0 * zeta * ratio) ** 2)
    )


def test_explicit_zero_damping_transmits_stiffness_force(tmp_path: Path) -> None:
    """damping_ratio = 0 given: c_d = 0, the frame gets c·x, so its peak is c·peak|x|,
    T_k = 1/|1 - r_k²| (β = 10, ω = 7.5: T₁ = 1/0.4375, T₂ = 1/1.25)."""
    mass, stiffness, piston, radius, lam, w, _ = PEAK_CASES["explicit-zero-damping"]
    r = run(tmp_path, scene(mass, stiffness, piston, radius, lam, w, 0.0))
    x1, x2, _ = amplitudes(mass, stiffness, piston, radius, lam, w, 0.0)
    assert r["damping_coefficient"] == 0.0
    assert r["transmissibility_1"] == rel(1.0 / 0.4375)
    assert r["transmissibility_2"] == rel(1.0 / 1.25)
    assert r["transmitted_force_peak"] == rel(stiffness * (abs(x1) + abs(x2)))
    assert r["dynamic_factor"] == rel(1.0 / 0.4375)


def test_high_speed_limit_is_the_lecture_estimate(tmp_path: Path) -> None:
    """ω ≫ β: A₁ → -m·r/M, A₂ → -λ·m·r/(4M), both negative, so the peak → m·r/M·
    (1 + λ/4), the lecture's two-term estimate (β = 10, ω = 10⁴: off by ~(β/ω)² = 1e-6)."""
    r = run(tmp_path, scene(100.0, 1.0e4, 2.0, 0.1, 0.3, 1.0e4))
    assert r["peak_displacement"] == pytest.approx(2.0 * 0.1 / 100.0 * (1 + 0.3 / 4), rel=2e-6)


# -------------------------------------------------------------------- isolation


@pytest.mark.parametrize("target", [0.5, 0.1, 0.02, 1e-4])
def test_isolation_undamped(tmp_path: Path, target: float) -> None:
    """Undamped T = 1/(r² - 1) on the isolating side, so r² = 1 + 1/T and c = M·ω²/r²;
    f = M·g/c; β = √(c/M)."""
    data = copy.deepcopy(EXAMPLE)
    data["isolation"] = {"transmissibility": target}
    r = run(tmp_path, data)
    u = 1.0 + 1.0 / target
    c_req = M_EX * W_EX**2 / u
    assert r["required_stiffness"] == rel(c_req)
    assert r["required_static_deflection"] == rel(M_EX * G_EX / c_req)
    assert r["required_natural_frequency"] == rel(math.sqrt(c_req / M_EX))
    assert transmissibility(W_EX / math.sqrt(r["required_stiffness"] / M_EX), 0.0) == rel(target)


@pytest.mark.parametrize("zeta", [0.05, 0.3, 1.0, 4.0])
@pytest.mark.parametrize("target", [0.9, 0.2, 0.02])
def test_isolation_damped(tmp_path: Path, zeta: float, target: float) -> None:
    """At the reported stiffness the own textbook transmissibility (same ζ) at ω is the
    target, on the isolating side r > √2; f and β follow from that stiffness."""
    data = copy.deepcopy(EXAMPLE)
    data["mounts"] = {"static_deflection": 0.01, "damping_ratio": zeta}
    data["isolation"] = {"transmissibility": target}
    r = run(tmp_path, data)
    c_req = r["required_stiffness"]
    ratio = W_EX / math.sqrt(c_req / M_EX)
    assert ratio > math.sqrt(2.0)
    assert transmissibility(ratio, zeta) == rel(target)
    assert r["required_static_deflection"] == rel(M_EX * G_EX / c_req)
    assert r["required_natural_frequency"] == rel(math.sqrt(c_req / M_EX))


# ------------------------------------------------------------- quasi-static rule


def test_quasi_static_rule_constants(tmp_path: Path) -> None:
    """(7.78) μ = 1/(1 - r²) = 1.05 → r = √(1 - 1/1.05) = √(1/21) = 0.21822 (lecture:
    0.218), ω = r·β, T/T₀ = 1/r = √21 = 4.5826 (lecture: 4.59, from 1/0.218)."""
    r = run(tmp_path, EXAMPLE)
    ratio = math.sqrt(1.0 / 21.0)
    assert r["quasi_static_ratio"] == rel(ratio)
    assert r["quasi_static_ratio"] == pytest.approx(0.218, abs=5e-4)
    assert r["quasi_static_speed"] == rel(ratio * math.sqrt(981.0))
    assert r["quasi_static_period_ratio"] == rel(math.sqrt(21.0))
    assert r["quasi_static_period_ratio"] == pytest.approx(4.59, abs=0.01)


def test_quasi_static_rule_at_the_ratio(tmp_path: Path) -> None:
    """At ω = √(1/21)·β: μ = 1/(1 - 1/21) = 21/20 = 1.05 exactly; just below, the load
    is quasi-static, just above it is not (β = 10 rad/s)."""
    ratio = math.sqrt(1.0 / 21.0)
    r = run(tmp_path, scene(100.0, 1.0e4, 1.0, 0.1, 0.2, ratio * 10.0))
    assert r["dynamic_factor"] == rel(1.05, 1e-12)
    r = run(tmp_path, scene(100.0, 1.0e4, 1.0, 0.1, 0.2, 0.99 * ratio * 10.0))
    assert r["quasi_static"] is True
    assert r["dynamic_factor"] == rel(1.0 / (1.0 - (0.99 * ratio) ** 2))
    r = run(tmp_path, scene(100.0, 1.0e4, 1.0, 0.1, 0.2, 1.01 * ratio * 10.0))
    assert r["quasi_static"] is False


# --------------------------------------------------------------- resonance, extremes


@pytest.mark.parametrize("speed, zeta", [(10.0, None), (5.0, None), (10.0, 0.0), (5.0, 0.0)])
def test_undamped_resonance_has_no_answer(tmp_path: Path, speed: float, zeta: float | None) -> None:
    """Brief §4: undamped, ω = β or ω = β/2 (β = √(10⁶/10⁴) = 10 exactly) makes A₁ or A₂
    = F/0: status "no-answer", exit 3, a message saying "unbounded"."""
    data = scene(1.0e4, 1.0e6, 10.0, 0.05, 0.2, speed, zeta)
    report = run_report(tmp_path, data)
    assert report.status == "no-answer"
    assert "unbounded" in (report.message or "")
    if zeta is None and speed == 10.0:  # ω = β/2 through the script: the JSON test below
        proc = run_script(write_case(tmp_path, data, "resonance.toml"))
        assert proc.returncode == 3, proc.stderr
        assert "unbounded" in proc.stderr


def test_undamped_resonance_json(tmp_path: Path) -> None:
    proc = run_script(write_case(tmp_path, scene(1.0e4, 1.0e6, 10.0, 0.05, 0.2, 5.0)), "--json")
    assert proc.returncode == 3, proc.stderr
    document = json.loads(proc.stdout)
    assert document["status"] == "no-answer"
    assert "unbounded" in document["message"]


@pytest.mark.parametrize("zeta", [0.01, 0.1, 0.5])
def test_damped_at_resonance(tmp_path: Path, zeta: float) -> None:
    """ω = β: c - Mω² = 0, |A₁| = F₁/(c_d·β) = m·r·β²/(2ζc), μ = 1/(2ζ),
    T₁ = √(1 + 4ζ²)/(2ζ). ω = β/2: |A₂| = λ·m·r·(β/2)²/(2ζc). (β = 10.)"""
    m, c, mass = 10.0, 1.0e6, 1.0e4
    r = run(tmp_path, scene(mass, c, m, 0.05, 0.2, 10.0, zeta))
    assert r["status"] == "ok"
    assert r["amplitude_1"] == rel(m * 0.05 * 100.0 / (2.0 * zeta * c))
    assert r["dynamic_factor"] == rel(1.0 / (2.0 * zeta))
    assert r["transmissibility_1"] == rel(math.sqrt(1.0 + 4.0 * zeta**2) / (2.0 * zeta))
    r = run(tmp_path, scene(mass, c, m, 0.05, 0.2, 5.0, zeta))
    assert r["amplitude_2"] == rel(0.2 * m * 0.05 * 25.0 / (2.0 * zeta * c))
    assert math.isfinite(r["peak_displacement"])


def test_near_undamped_resonance_is_finite_and_large(tmp_path: Path) -> None:
    """ω = β(1 + 1e-9), undamped: |A₁| = F/(c·|1 - r²|) ≈ F/(c·2e-9)."""
    w = 10.0 * (1.0 + 1e-9)
    r = run(tmp_path, scene(1.0e4, 1.0e6, 10.0, 0.05, 0.2, w))
    f1 = 10.0 * 0.05 * w * w
    assert r["amplitude_1"] == rel(f1 / abs(1.0e6 - 1.0e4 * w * w), 1e-6)
    assert r["amplitude_1"] == pytest.approx(f1 / (1.0e6 * 2e-9), rel=1e-6)


@pytest.mark.parametrize("zeta", [None, 0.05])
def test_very_stiff_mount(tmp_path: Path, zeta: float | None) -> None:
    """c = 10¹², M = 100, ω = 100: Mω²/c = 10⁻⁶, so |A₁| = F/(c - Mω²) ≈ F/c (static
    deflection under the crank force), μ = 1/(1 - 10⁻⁶) → 1, quasi-static."""
    c, w = 1.0e12, 100.0
    f1 = 1.0 * 0.1 * w * w  # 1000 N
    r = run(tmp_path, scene(100.0, c, 1.0, 0.1, 0.2, w, zeta))
    assert r["amplitude_1"] == pytest.approx(f1 / c, rel=2e-6)
    assert r["amplitude_2"] == pytest.approx(0.2 * f1 / c, rel=5e-6)
    assert r["dynamic_factor"] == pytest.approx(1.0, rel=2e-6)
    assert r["peak_displacement"] == pytest.approx(1.2 * f1 / c, rel=5e-6)
    assert r["quasi_static"] is True
    if zeta is None:
        assert r["amplitude_1"] == rel(f1 / (c - 100.0 * w * w))
        assert r["dynamic_factor"] == rel(1.0 / (1.0 - 1e-6))
    else:
        assert r["transmitted_force_peak"] == pytest.approx(1.2 * f1, rel=1e-4)


# ---------------------------------------------------------------------- bad input


BAD_INPUT = {
    "negative-mass": (("engine",), {"mass": -1000.0}, "engine.mass"),
    "mass-and-weight": (("engine",), {"mass": 1000.0, "weight": 9810.0}, "weight"),
    "unknown-key": (("mounts",), {"stiffness": 1.0e6, "stifness": 1.0}, "stifness"),
    "zero-deflection": (("mounts",), {"static_deflection": 0.0}, "static_deflection"),
    "negative-damping": (("mounts",), {"stiffness": 1.0e6, "damping_ratio": -0.1}, "damping_ratio"),
    "rod-ratio-one": (
        ("crank",),
        {"piston_mass": 10.0, "radius": 0.05, "rod_ratio": 1.0, "speed": 150.0},
        "rod_ratio",
    ),
    "speed-and-rpm": (
        ("crank",),
        {"piston_mass": 10.0, "radius": 0.05, "rod_ratio": 0.2, "speed": 150.0, "speed_rpm": 1.0},
        "speed_rpm",
    ),
    "transmissibility-one": (("isolation",), {"transmissibility": 1.0}, "transmissibility"),
}


@pytest.mark.parametrize("name", list(BAD_INPUT))
def test_bad_input_exits_2_naming_the_key(cli, tmp_path: Path, name: str) -> None:
    """Brief: bad input exits 2 and the message names the key."""
    (section,), body, key = BAD_INPUT[name]
    data = copy.deepcopy(EXAMPLE)
    data[section] = body
    path = write_case(tmp_path, data)
    result = cli("mount", path)
    assert result.exit_code == 2, result.stdout + result.stderr
    assert key in result.stderr
    assert str(path) in result.stderr and "Traceback" not in result.stderr


def test_bad_input_script(tmp_path: Path) -> None:
    """The same through the console script: negative piston weight, exit 2."""
    data = copy.deepcopy(EXAMPLE)
    data["crank"] = {**data["crank"], "piston_weight": -100.0}
    proc = run_script(write_case(tmp_path, data))
    assert proc.returncode == 2
    assert "crank.piston_weight" in proc.stderr
