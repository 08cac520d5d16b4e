"""Independent physics tests of ``mdcalc braking`` (brief PROBLEMS.md §3, seed 000 §7.4).

Every expected value below is a hand calculation from the formulas of the brief and of
seed ``000_3ece989f7275045f.txt`` ((7.43)-(7.48)), or an exact closed form derived in the
comments, written out in the test; none is copied from the program's output and none
uses the program's own formula functions. The package is imported only to run a case
file. Where drag acts during the brake build-up there is no closed form, and a small
numerical integration written in this file (scipy, tight tolerance) is the expectation.

Model (brief §3): brake force through the tyres F_b = min(demand, φ·m·g); road resistance
ψ·m·g all the time; drag k·v², k = ½·ρ·C_x·A; phases: reaction t_r (no brake), build-up
t_b (brake force rising linearly 0 → F_b), full braking to the stop.
"""

from __future__ import annotations

import copy
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from tomli_w import dumps as toml_dumps

from mdcalc.runs.runner import run_case

TIGHT = 1e-9  # relative tolerance against exact closed forms

# ----------------------------------------------------------------------------- helpers


def write_case(tmp_path: Path, data: dict[str, Any]) -> Path:
    path = tmp_path / "case.toml"
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


def rel(expected: float, tol: float = TIGHT) -> Any:
    return pytest.approx(expected, rel=tol)


def scene(**sections: Any) -> dict[str, Any]:
    """A 1500 kg car at 100 km/h on a road of φ = 0.8, g = 9.81 as in the lecture."""
    data: dict[str, Any] = {
        "problem": "braking",
        "gravity": 9.81,
        "vehicle": {"mass": 1500.0, "initial_speed_kmh": 100.0},
        "road": {"adhesion": 0.8},
    }
    for key, value in sections.items():
        if value is None:
            data.pop(key, None)
        else:
            data[key] = copy.deepcopy(value)
    return data


G = 9.81
M = 1500.0
V100 = 100.0 / 3.6  # 27.777… m/s

# Seed 000 §7.4 lecture example (brief §3 reference).
LECTURE: dict[str, Any] = {
    "problem": "braking",
    "gravity": 9.81,
    "vehicle": {"mass": 1500.0, "initial_speed": 27.8},
    "brakes": {"traction_force": 1644.0, "force_multiple": 10.0},
    "road": {"surface": "dry-asphalt"},
}


def own_stop_ode(
    v0: float,
    mass: float,
    brake: float,
    road: float,
    drag: float,
    t_r: float,
    t_b: float,
) -> tuple[float, float]:
    """Own integration of m·v' = -(road + F_b(t) + drag·v²), x' = v, to v = 0.

    F_b(t) = 0 for t < t_r, brake·(t - t_r)/t_b for t_r ≤ t < t_r + t_b, brake after.
    Returns (distance, time). Phases integrated separately so the kinks are exact.
    """

    def stopped(t: float, s: np.ndarray) -> float:
        return s[0]

    stopped.terminal = True  # type: ignore[attr-defined]
    stopped.direction = -1  # type: ignore[attr-defined]

    phases = [
        (t_r, lambda t: 0.0),
        (t_r + t_b, lambda t: brake * (t - t_r) / t_b),
        (math.inf, lambda t: brake),
    ]
    t, s = 0.0, np.array([v0, 0.0])
    for t_end, force in phases:
        if t_end <= t:
            continue
        if math.isinf(t_end):
            t_end = t + 2.0 * mass * s[0] / (road + brake) + 1.0

        def rhs(time: float, y: np.ndarray, force: Any = force) -> list[float]:
            return [-(road + force(time) + drag * y[0] * y[0]) / mass, y[0]]

        sol = solve_ivp(
            rhs,
            (t, t_end),
            s,
            method="DOP853",
            rtol=1e-13,
            atol=[v0 * 1e-14, v0 * 1e-14],
            events=stopped,
        )
        assert sol.status >= 0, sol.message
        if sol.status == 1:
            return float(sol.y_events[0][0][1]), float(sol.t_events[0][0])
        t, s = float(sol.t[-1]), sol.y[:, -1].copy()
    raise AssertionError("own braking integration did not stop")


# ---------------------------------------------------------------- lecture method (7.48)


def test_lecture_reference(tmp_path: Path) -> None:
    """Brief §3 reference: 27.8 m/s, 1500 kg, k = 10, P_D = 1644 N → 2.54 s, 35.3 m."""
    r = run(tmp_path, LECTURE)
    assert r["status"] == "ok"
    assert r["initial_speed"] == rel(27.8)
    # seed 000 (7.48): t = V0·m/(k·P_D) = 27.8·1500/16 440 = 2.5365 s
    assert r["lecture_time"] == rel(27.8 * 1500.0 / 16440.0)
    assert r["lecture_time"] == pytest.approx(2.54, abs=0.005)
    # seed 000 (7.48): S = V0²·m/(2·k·P_D) = 772.84·1500/32 880 = 35.257 m
    assert r["lecture_distance"] == rel(27.8**2 * 1500.0 / (2.0 * 16440.0))
    assert r["lecture_distance"] == pytest.approx(35.3, abs=0.05)
    # S = V0·t - k·P_D·t²/(2m) is the same number
    t = 27.8 * 1500.0 / 16440.0
    assert r["lecture_distance"] == rel(27.8 * t - 16440.0 * t**2 / (2.0 * 1500.0))


def test_lecture_demand_locks_the_wheels(tmp_path: Path) -> None:
    """Brief §3: 10.96 m/s² = 1.12·g demanded; no road gives it; wheels lock."""
    report = run_report(tmp_path, LECTURE)
    r = {k: q.value for k, q in report.results().items()}
    # P_T/m = 16 440/1500 = 10.96 m/s² = 10.96/9.81 g = 1.1172 g
    assert r["demanded_deceleration"] == rel(10.96)
    assert r["demanded_deceleration_g"] == rel(10.96 / 9.81)
    assert r["demanded_deceleration_g"] == pytest.approx(1.12, abs=0.005)
    # dry asphalt φ = 0.7…0.9 (seed 000 §7.4); the low end is used
    assert r["adhesion"] == rel(0.7)
    assert r["wheel_lock"] is True
    assert any(note.level == "warning" for note in report.notes)
    # adhesion limit φ·g = 0.7·9.81 = 6.867 m/s²
    assert r["adhesion_deceleration"] == rel(0.7 * G)
    # V0/(φ·g) = 27.8/6.867 = 4.0483 s; V0²/(2·φ·g) = 772.84/13.734 = 56.272 m
    assert r["adhesion_limited_time"] == rel(27.8 / (0.7 * G))
    assert r["adhesion_limited_distance"] == rel(27.8**2 / (2.0 * 0.7 * G))
    assert r["adhesion_limited_distance"] == pytest.approx(56.272, abs=5e-4)
    # what the tyres pass: F_b = min(16 440, 0.7·1500·9.81 = 10 300.5) = 10 300.5 N
    assert r["braking_force"] == rel(0.7 * 1500.0 * G)
    assert r["deceleration"] == rel(0.7 * G)
    # no road resistance given: the stop is the adhesion-limited one
    assert r["stopping_distance"] == rel(27.8**2 / (2.0 * 0.7 * G))
    assert r["stopping_time"] == rel(27.8 / (0.7 * G))
    # and it is longer than the lecture's 35.3 m
    assert r["stopping_distance"] > r["lecture_distance"]


def test_lecture_default_gravity(tmp_path: Path) -> None:
    """Without gravity = ..., g = 9.80665: 27.8²/(2·0.7·9.806 65) = 56.2912 m."""
    data = copy.deepcopy(LECTURE)
    del data["gravity"]
    r = run(tmp_path, data)
    assert r["adhesion_limited_distance"] == rel(27.8**2 / (2.0 * 0.7 * 9.80665))
    assert r["adhesion_limited_distance"] == pytest.approx(56.2912, abs=5e-5)
    assert r["demanded_deceleration_g"] == rel(10.96 / 9.80665)
    # the lecture's own numbers do not depend on g
    assert r["lecture_time"] == rel(27.8 * 1500.0 / 16440.0)


@pytest.mark.parametrize(("factor", "locks"), [(1.0001, True), (0.9999, False)])
def test_wheel_lock_threshold(tmp_path: Path, factor: float, locks: bool) -> None:
    """Lock when the demanded deceleration exceeds φ·g (brief §3)."""
    demand = factor * 0.8 * G  # m/s²
    r = run(tmp_path, scene(brakes={"deceleration": demand}))
    assert r["wheel_lock"] is locks
    # F_b = min(m·demand, φ·m·g)
    assert r["braking_force"] == rel(M * min(demand, 0.8 * G))


def test_no_lock_braking_by_demanded_deceleration(tmp_path: Path) -> None:
    """5 m/s² asked on φ = 0.8: S = V0²/(2·5) = 771.6/10 = 77.160 m, t = V0/5 = 5.556 s."""
    r = run(tmp_path, scene(brakes={"deceleration": 5.0}))
    assert r["wheel_lock"] is False
    assert r["braking_force"] == rel(7500.0)
    assert r["deceleration"] == rel(5.0)
    assert r["stopping_distance"] == rel(V100**2 / 10.0)
    assert r["stopping_distance"] == pytest.approx(77.160, abs=5e-4)
    assert r["stopping_time"] == rel(V100 / 5.0)
    # (7.48) with P_T = m·5: the same when nothing else acts
    assert r["lecture_distance"] == rel(V100**2 / 10.0)


def test_brake_force_input(tmp_path: Path) -> None:
    """brakes.force = 6000 N on 1500 kg: 4 m/s², S = V0²/8 = 96.451 m."""
    r = run(tmp_path, scene(brakes={"force": 6000.0}))
    assert r["demanded_deceleration"] == rel(4.0)
    assert r["wheel_lock"] is False
    assert r["stopping_distance"] == rel(V100**2 / 8.0)
    assert r["stopping_distance"] == pytest.approx(96.451, abs=5e-4)


def test_speed_in_kmh(tmp_path: Path) -> None:
    r = run(tmp_path, scene())
    assert r["initial_speed"] == rel(100.0 / 3.6)


@pytest.mark.parametrize(("surface", "phi"), [("dry-asphalt", 0.7), ("ice", 0.01)])
def test_lecture_surfaces(tmp_path: Path, surface: str, phi: float) -> None:
    """Seed 000 §7.4: dry asphalt 0.7…0.9, ice 0.01…0.03; low end used: V0²/(2φg)."""
    r = run(tmp_path, scene(road={"surface": surface}))
    assert r["adhesion"] == rel(phi)
    assert r["stopping_distance"] == rel(V100**2 / (2.0 * phi * G))


def test_without_brakes_demand_is_adhesion_limit(tmp_path: Path) -> None:
    """No [brakes]: full braking at φ·m·g; the lecture section is not shown."""
    r = run(tmp_path, scene())
    assert r["braking_force"] == rel(0.8 * M * G)  # 11 772 N
    assert r["deceleration"] == rel(0.8 * G)
    # V0²/(2·0.8·9.81) = 771.60/15.696 = 49.159 m
    assert r["stopping_distance"] == rel(V100**2 / (2.0 * 0.8 * G))
    assert r["stopping_distance"] == pytest.approx(49.159, abs=5e-4)
    for key in ("lecture_time", "lecture_distance", "wheel_lock", "reaction_distance"):
        assert key not in r


# ------------------------------------------------------------------- road resistance


def test_road_resistance_adds_psi_g(tmp_path: Path) -> None:
    """(7.43) m·x'' = -(ψ·m·g + P_T): deceleration (φ + ψ)·g at the adhesion limit."""
    r = run(tmp_path, scene(road={"adhesion": 0.8, "resistance": 0.015}))
    a = (0.8 + 0.015) * G  # 7.995 15 m/s²
    assert r["deceleration"] == rel(a)
    # S = V0²/(2a) = 771.60/15.990 = 48.255 m, t = V0/a = 3.4743 s
    assert r["stopping_distance"] == rel(V100**2 / (2.0 * a))
    assert r["stopping_distance"] == pytest.approx(48.255, abs=5e-4)
    assert r["stopping_time"] == rel(V100 / a)
    assert r["stopping_time"] == pytest.approx(3.4743, abs=5e-5)


def test_road_resistance_with_locked_lecture_brakes(tmp_path: Path) -> None:
    data = copy.deepcopy(LECTURE)
    data["road"] = {"surface": "dry-asphalt", "resistance": 0.02}
    r = run(tmp_path, data)
    a = (0.7 + 0.02) * G
    assert r["braking_force"] == rel(0.7 * 1500.0 * G)
    assert r["stopping_distance"] == rel(27.8**2 / (2.0 * a))
    # the lecture's own numbers neglect the road (7.44)
    assert r["lecture_distance"] == rel(27.8**2 * 1500.0 / (2.0 * 16440.0))


def test_energy_balance_without_drag(tmp_path: Path) -> None:
    """½·m·V0² = (F_b + ψ·m·g)·S when nothing else acts (work of the forces)."""
    data = scene(brakes={"deceleration": 6.0}, road={"adhesion": 0.5, "resistance": 0.03})
    r = run(tmp_path, data)
    # demand 9000 N > φ·m·g = 7357.5 N: locked, F_b = 7357.5 N
    assert r["braking_force"] == rel(0.5 * M * G)
    work = (r["braking_force"] + 0.03 * M * G) * r["stopping_distance"]
    assert work == rel(0.5 * M * V100**2)


# --------------------------------------------------------- reaction and build-up phases


def test_reaction_and_build_up_exact(tmp_path: Path) -> None:
    """Three phases by hand (brief §3), φ = 0.8, ψ = 0.015, t_r = 1 s, t_b = 0.2 s.

    Reaction (road only, a0 = ψ·g = 0.147 15 m/s²): v1 = V0 - a0·t_r = 27.630 628 m/s,
    s1 = V0·t_r - a0·t_r²/2 = 27.704 203 m.
    Build-up (F_b = 0.8·1500·9.81 = 11 772 N rising over t_b, jerk j = F_b/(m·t_b)
    = 39.24 m/s³): v2 = v1 - a0·t_b - j·t_b²/2 = 26.816 398 m/s,
    s2 = v1·t_b - a0·t_b²/2 - j·t_b³/6 = 5.470 863 m.
    Full braking (a = (φ+ψ)·g = 7.995 15 m/s²): s3 = v2²/(2a) = 44.972 214 m,
    t3 = v2/a = 3.354 083 s. S = 78.147 279 m, t = 4.554 083 s.
    """
    data = scene(
        road={"adhesion": 0.8, "resistance": 0.015},
        driver={"reaction_time": 1.0, "build_up_time": 0.2},
    )
    r = run(tmp_path, data)
    t_r, t_b, a0 = 1.0, 0.2, 0.015 * G
    v1 = V100 - a0 * t_r
    s1 = V100 * t_r - a0 * t_r**2 / 2.0
    jerk = 0.8 * M * G / (M * t_b)
    v2 = v1 - a0 * t_b - jerk * t_b**2 / 2.0
    s2 = v1 * t_b - a0 * t_b**2 / 2.0 - jerk * t_b**3 / 6.0
    a_full = (0.8 + 0.015) * G
    s3 = v2**2 / (2.0 * a_full)
    t3 = v2 / a_full
    assert r["reaction_distance"] == rel(s1)
    assert r["build_up_distance"] == rel(s2)
    assert r["braking_distance"] == rel(s3)
    assert r["stopping_distance"] == rel(s1 + s2 + s3)
    assert r["stopping_time"] == rel(t_r + t_b + t3)
    assert r["reaction_distance"] == pytest.approx(27.704203, abs=5e-6)
    assert r["build_up_distance"] == pytest.approx(5.470863, abs=5e-6)
    assert r["braking_distance"] == pytest.approx(44.972214, abs=5e-6)
    assert r["stopping_distance"] == pytest.approx(78.147279, abs=5e-6)
    assert r["stopping_time"] == pytest.approx(4.554083, abs=5e-6)
    # cross-check of the hand algebra by an own integration
    own = own_stop_ode(V100, M, 0.8 * M * G, 0.015 * M * G, 0.0, t_r, t_b)
    assert own[0] == rel(s1 + s2 + s3, 1e-10)
    assert own[1] == rel(t_r + t_b + t3, 1e-10)


def test_energy_balance_with_phases(tmp_path: Path) -> None:
    """½·m·V0² = ψ·m·g·S + F_b·s3 + ∫ F_b·(t/t_b)·v(t) dt over the build-up."""
    t_r, t_b = 0.8, 0.5
    data = scene(
        road={"adhesion": 0.6, "resistance": 0.02},
        driver={"reaction_time": t_r, "build_up_time": t_b},
    )
    r = run(tmp_path, data)
    f_b, road = 0.6 * M * G, 0.02 * M * G
    assert r["braking_force"] == rel(f_b)
    v1 = V100 - road / M * t_r  # speed at the end of the reaction

    def build_up_power(t: float) -> float:
        v = v1 - road / M * t - f_b / (M * t_b) * t**2 / 2.0
        return f_b * t / t_b * v

    ramp_work, _ = quad(build_up_power, 0.0, t_b, epsabs=0.0, epsrel=1e-13)
    work = road * r["stopping_distance"] + f_b * r["braking_distance"] + ramp_work
    assert work == rel(0.5 * M * V100**2)


def test_stop_inside_build_up(tmp_path: Path) -> None:
    """2 m/s, t_r = 0.5 s, t_b = 1 s: the car stops while the brake force still rises.

    v1 = 2 - 0.147 15·0.5 = 1.926 425 m/s, s1 = 1 - 0.147 15·0.25/2 = 0.981 606 m.
    Ramp: j/2·τ² + a0·τ - v1 = 0, j = 0.8·9.81/1 = 7.848 m/s³ → τ = 0.682 168 s;
    s2 = v1·τ - a0·τ²/2 - j·τ³/6 = 0.864 684 m. S = 1.846 290 m, t = 1.182 168 s.
    """
    data = scene(
        vehicle={"mass": 1500.0, "initial_speed": 2.0},
        road={"adhesion": 0.8, "resistance": 0.015},
        driver={"reaction_time": 0.5, "build_up_time": 1.0},
    )
    r = run(tmp_path, data)
    a0, jerk = 0.015 * G, 0.8 * G / 1.0
    v1 = 2.0 - a0 * 0.5
    s1 = 2.0 * 0.5 - a0 * 0.25 / 2.0
    tau = (-a0 + math.sqrt(a0 * a0 + 2.0 * jerk * v1)) / jerk
    s2 = v1 * tau - a0 * tau**2 / 2.0 - jerk * tau**3 / 6.0
    assert r["stopping_distance"] == rel(s1 + s2)
    assert r["stopping_distance"] == pytest.approx(1.846290, abs=5e-6)
    assert r["stopping_time"] == rel(0.5 + tau)
    assert r["reaction_distance"] == rel(s1)
    assert r["build_up_distance"] == rel(s2)
    assert r["braking_distance"] == pytest.approx(0.0, abs=1e-12)


def test_stop_inside_reaction(tmp_path: Path) -> None:
    """1 m/s, ψ = 0.3, t_r = 2 s: the road alone stops the car in 1/(0.3·9.81) = 0.3398 s.

    S = V0²/(2ψg) = 1/5.886 = 0.169 895 m; nothing is left for the brakes.
    """
    data = scene(
        vehicle={"mass": 1500.0, "initial_speed": 1.0},
        road={"adhesion": 0.8, "resistance": 0.3},
        driver={"reaction_time": 2.0, "build_up_time": 0.3},
    )
    r = run(tmp_path, data)
    assert r["stopping_distance"] == rel(1.0 / (2.0 * 0.3 * G))
    assert r["stopping_distance"] == pytest.approx(0.169895, abs=5e-7)
    assert r["stopping_time"] == rel(1.0 / (0.3 * G))
    assert r["reaction_distance"] == rel(1.0 / (2.0 * 0.3 * G))


# ----------------------------------------------------------------------------- drag


def drag_stop(v0: float, mass: float, force: float, k: float) -> tuple[float, float]:
    """m·v' = -(F + k·v²) to v = 0 (own derivation).

    dt = -m·dv/(F + k·v²) → t = m/√(F·k)·atan(v0·√(k/F));
    dx = v·dt = -m·v·dv/(F + k·v²) → S = m/(2k)·ln(1 + k·v0²/F).
    """
    return (
        mass / (2.0 * k) * math.log1p(k * v0 * v0 / force),
        mass / math.sqrt(force * k) * math.atan(v0 * math.sqrt(k / force)),
    )


def test_drag_closed_form(tmp_path: Path) -> None:
    """40 m/s, C_x = 0.35, A = 2.2 m², ρ = 1.225: k = ½ρC_xA = 0.471 625 kg/m.

    F = (φ + ψ)·m·g = (0.8 + 0.015)·1500·9.81 = 11 992.725 N:
    S = 1500/(2·0.471 625)·ln(1 + 0.471 625·1600/11 992.725) = 97.0388 m (no drag: 100.061 m),
    t = 4.9019 s.
    """
    data = scene(
        vehicle={"mass": 1500.0, "initial_speed": 40.0},
        road={"adhesion": 0.8, "resistance": 0.015},
        drag={"drag_coefficient": 0.35, "frontal_area": 2.2, "air_density": 1.225},
    )
    r = run(tmp_path, data)
    k = 0.5 * 1.225 * 0.35 * 2.2
    distance, time = drag_stop(40.0, M, 0.815 * M * G, k)
    assert r["stopping_distance"] == rel(distance)
    assert r["stopping_distance"] == pytest.approx(97.0388, abs=5e-5)
    assert r["stopping_time"] == rel(time)
    assert r["stopping_time"] == pytest.approx(4.9019, abs=5e-5)
    # energy: ½mV0² - (F_b + ψmg)·S is the drag work, 0 < W_drag < k·V0²·S
    w_drag = 0.5 * M * 40.0**2 - (r["braking_force"] + 0.015 * M * G) * r["stopping_distance"]
    assert 0.0 < w_drag < k * 40.0**2 * r["stopping_distance"]


def test_drag_default_air_density(tmp_path: Path) -> None:
    data = scene(drag={"drag_coefficient": 0.3, "frontal_area": 2.0})
    r = run(tmp_path, data)
    k = 0.5 * 1.225 * 0.3 * 2.0  # ρ = 1.225 kg/m³ by default
    assert r["stopping_distance"] == rel(drag_stop(V100, M, 0.8 * M * G, k)[0])


def test_drag_with_reaction_closed_form(tmp_path: Path) -> None:
    """ψ = 0, t_r = 1.5 s: drag alone coasts, then brake + drag.

    Reaction: m·v' = -k·v² → v1 = V0/(1 + k·V0·t_r/m), s1 = (m/k)·ln(1 + k·V0·t_r/m).
    Then S3 = m/(2k)·ln(1 + k·v1²/F), F = φ·m·g, and t3 = m/√(Fk)·atan(v1·√(k/F)).
    """
    k = 0.5 * 1.225 * 0.32 * 2.1
    data = scene(
        road={"adhesion": 0.7},
        drag={"drag_coefficient": 0.32, "frontal_area": 2.1},
        driver={"reaction_time": 1.5},
    )
    r = run(tmp_path, data)
    u = k * V100 * 1.5 / M
    v1 = V100 / (1.0 + u)
    s1 = M / k * math.log1p(u)
    s3, t3 = drag_stop(v1, M, 0.7 * M * G, k)
    assert r["reaction_distance"] == rel(s1)
    assert r["build_up_distance"] == pytest.approx(0.0, abs=1e-12)
    assert r["braking_distance"] == rel(s3)
    assert r["stopping_distance"] == rel(s1 + s3)
    assert r["stopping_time"] == rel(1.5 + t3)
    own = own_stop_ode(V100, M, 0.7 * M * G, 0.0, k, 1.5, 0.0)
    assert own[0] == rel(s1 + s3, 1e-10)


def test_drag_with_build_up_by_integration(tmp_path: Path) -> None:
    """Drag during the build-up has no closed form: own tight integration is the reference."""
    k = 0.5 * 1.225 * 0.35 * 2.2
    data = scene(
        vehicle={"mass": 1500.0, "initial_speed_kmh": 130.0},
        road={"adhesion": 0.75, "resistance": 0.015},
        drag={"drag_coefficient": 0.35, "frontal_area": 2.2},
        driver={"reaction_time": 1.0, "build_up_time": 0.3},
    )
    r = run(tmp_path, data)
    distance, time = own_stop_ode(130.0 / 3.6, M, 0.75 * M * G, 0.015 * M * G, k, 1.0, 0.3)
    assert r["stopping_distance"] == rel(distance, 1e-7)
    assert r["stopping_time"] == rel(time, 1e-7)
    # the split into phases is not reported when no closed form gives it
    assert "reaction_distance" not in r


@pytest.mark.parametrize("driver", [False, True])
def test_extreme_speed_with_drag(tmp_path: Path, driver: bool) -> None:
    """400 km/h with drag: finite, and between the bounds of the closed forms.

    No driver: S = m/(2k)·ln(1 + k·V0²/F) with k = ½·1.225·0.3·2.2 = 0.404 25 kg/m,
    F = 0.8·1500·9.81 = 11 772 N: S = 655.723 m (no drag V0²/(2·0.8·g) = 786.549 m).
    """
    v0 = 400.0 / 3.6
    k = 0.5 * 1.225 * 0.3 * 2.2
    data = scene(
        vehicle={"mass": 1500.0, "initial_speed_kmh": 400.0},
        drag={"drag_coefficient": 0.3, "frontal_area": 2.2},
    )
    if driver:
        data["driver"] = {"reaction_time": 1.0, "build_up_time": 0.5}
    r = run(tmp_path, data)
    assert r["status"] == "ok"
    for key in ("stopping_distance", "stopping_time", "braking_force", "deceleration"):
        assert math.isfinite(r[key])
    if driver:
        expected = own_stop_ode(v0, M, 0.8 * M * G, 0.0, k, 1.0, 0.5)
        assert r["stopping_distance"] == rel(expected[0], 1e-7)
        assert r["stopping_time"] == rel(expected[1], 1e-7)
        # more than the immediate stop, less than no drag with the whole lead at V0
        assert r["stopping_distance"] > 655.7231
        assert r["stopping_distance"] < v0 * 1.5 + v0**2 / (2.0 * 0.8 * G)
    else:
        distance, time = drag_stop(v0, M, 0.8 * M * G, k)
        assert r["stopping_distance"] == rel(distance)
        assert r["stopping_distance"] == pytest.approx(655.7232, abs=5e-4)
        assert r["stopping_time"] == rel(time)
        assert r["stopping_distance"] < v0**2 / (2.0 * 0.8 * G)


# ---------------------------------------------------------------------- report shape


def test_cli_json_and_methods_reference(tmp_path: Path) -> None:
    path = write_case(tmp_path, LECTURE)
    proc = subprocess.run(
        [mdcalc_exe(), "braking", str(path), "--json"], capture_output=True, text=True, timeout=120
    )
    assert proc.returncode == 0, proc.stderr
    document = json.loads(proc.stdout)
    assert document["status"] == "ok"
    results = document["results"]
    assert results["lecture_time"]["value"] == rel(27.8 * 1500.0 / 16440.0)
    assert results["lecture_time"]["unit"] == "s"
    assert results["stopping_distance"]["unit"] == "m"
    methods = [s for s in document["sections"] if s.get("kind") == "methods"]
    assert len(methods) == 1
    rows = methods[0]["rows"]
    reference = [row for row in rows if row["reference"]]
    assert len(reference) == 1
    ref_distance = reference[0]["values"]["stopping_distance"]
    assert ref_distance == rel(27.8**2 / (2.0 * 0.7 * G))
    # the lecture row: (7.48) 35.257 m, off the reference by 1 - 35.257/56.272 = 37.3 %
    lecture = next(row for row in rows if "lecture" in row["method"].lower())
    assert lecture["values"]["stopping_distance"] == rel(27.8**2 * 1500.0 / 32880.0)
    expected_error = abs(27.8**2 * 1500.0 / 32880.0 - ref_distance) / ref_distance
    assert lecture["rel_errors"]["stopping_distance"] == rel(expected_error, 1e-6)


def test_surface_table(tmp_path: Path) -> None:
    """Road-surface table: V0²/(2·(min(P_T, φ·m·g)/m + ψ·g)) at each end of φ's range."""
    data = copy.deepcopy(LECTURE)
    data["road"] = {"surface": "dry-asphalt", "compare_surfaces": True}
    report = run_report(tmp_path, data)
    table = next(s for s in report.sections if getattr(s, "key", None) == "surfaces")
    rows = {row[0]: row for row in table.rows}
    dry = rows["dry-asphalt"]
    # φ high 0.9: 0.9·1500·9.81 = 13 243.5 N < 16 440 N, S = 27.8²/(2·0.9·9.81) = 43.767 m
    assert dry[3] == rel(27.8**2 / (2.0 * 0.9 * G))
    assert dry[4] == rel(27.8**2 / (2.0 * 0.7 * G))
    ice = rows["ice"]
    assert ice[4] == rel(27.8**2 / (2.0 * 0.01 * G))  # 3939.0 m on glaze ice
