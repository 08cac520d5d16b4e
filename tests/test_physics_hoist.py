"""Independent physics tests of ``mdcalc hoist`` (brief PROBLEMS.md §1, seed 000 §7.2, §7.6).

Every expected value below is a hand calculation from the formulas of the brief and of
seed ``000_3ece989f7275045f.txt`` (equation numbers cited next to each), written out in
the test; none is copied from the program's output and none uses the program's own
formula functions. The package is imported only to run a case file. Where the brief
fixes the seed's physics (rope loads, (7.92)-(7.98)), the expectation is derived here
in the comments, and a small numerical integration written in this file (scipy, tight
tolerance) cross-checks the derivations.
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
from scipy.integrate import solve_ivp
from tomli_w import dumps as toml_dumps

from mdcalc.runs.runner import run_case

TIGHT = 1e-9  # relative tolerance against exact closed forms

# ----------------------------------------------------------------------------- helpers


def write_case(tmp_path: Path, data: dict[str, Any], name: str = "case.toml") -> Path:
    path = tmp_path / name
    path.write_text(toml_dumps(data), encoding="utf-8")
    return path


def run(tmp_path: Path, data: dict[str, Any]) -> dict[str, Any]:
    """Run a case in-process; every result value by key (plus ``status``)."""
    report = run_case(write_case(tmp_path, data))
    return {key: q.value for key, q in report.results().items()}


def run_report(tmp_path: Path, data: dict[str, Any]) -> Any:
    return run_case(write_case(tmp_path, data))


def mdcalc_exe() -> str:
    found = shutil.which("mdcalc")
    if found:
        return found
    return str(Path(sys.executable).parent / "mdcalc")


def run_cli(tmp_path: Path, data: dict[str, Any]) -> tuple[int, dict[str, Any] | None, str]:
    path = write_case(tmp_path, data)
    proc = subprocess.run(
        [mdcalc_exe(), "hoist", str(path), "--json"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    document = json.loads(proc.stdout) if proc.stdout.strip() else None
    return proc.returncode, document, proc.stderr


def rel(expected: float, tol: float = TIGHT) -> Any:
    return pytest.approx(expected, rel=tol)


def rpm(n: float) -> float:
    """rpm -> rad/s: ω = 2π·n/60."""
    return 2.0 * math.pi * n / 60.0


def case(**changes: Any) -> dict[str, Any]:
    """The crane scene with sections updated ([start] is replaced: time xor torque)."""
    data = copy.deepcopy(CRANE)
    for key, value in changes.items():
        if value is None:
            data.pop(key, None)
        elif key != "start" and isinstance(value, dict) and isinstance(data.get(key), dict):
            data[key].update(value)
        else:
            data[key] = value
    return data


# An overhead crane main hoist (10 t at 0.2 m/s, motor 960 rpm), the lecture's g = 9.81.
CRANE: dict[str, Any] = {
    "problem": "hoist",
    "gravity": 9.81,
    "load": {"mass": 10000.0, "lifting_speed": 0.2},
    "drive": {
        "motor_speed_rpm": 960.0,
        "motor_inertia": 0.35,
        "stage_efficiencies": [0.97, 0.97, 0.98],
        "pulley_efficiency": 0.97,
        "brake_safety_factor": 1.75,
        "shafts": [
            {"name": "intermediate gear", "inertia": 0.5, "ratio": 5.0},
            {"name": "drum", "inertia": 40.0, "speed_rpm": 15.279},
        ],
    },
    "start": {"time": 1.5, "machine": "crane"},
}

# Hand values of the crane scene.
G_CRANE = 10000.0 * 9.81  # G = m·g = 98 100 N
V_CRANE = 0.2
ETA_CRANE = 0.97 * 0.97 * 0.98 * 0.97  # η = η1·η2·η3·η_pulley = 0.894 419 54
OMEGA_CRANE = rpm(960.0)  # 32π = 100.530 96 rad/s
J_SHAFTS_CRANE = 0.5 * (1.0 / 5.0) ** 2 + 40.0 * (15.279 / 960.0) ** 2  # (7.30) terms 2, 3
J_LOAD_CRANE = 10000.0 * (V_CRANE / OMEGA_CRANE) ** 2  # (7.30) last term m(V/ω1)²
J_CRANE = 0.35 + J_SHAFTS_CRANE + J_LOAD_CRANE  # (7.30)
M_C_CRANE = G_CRANE * V_CRANE / (OMEGA_CRANE * ETA_CRANE)  # (7.26)


# ------------------------------------------------------------- rope model, derivations


def hanging_peak(c: float, m1: float, m2: float, g_force: float, a: float, t_p: float) -> float:
    """Peak rope force, load hanging (brief §1, corrected (7.92)-(7.96)).

    Derivation: m1·x1'' = F_d - T, m2·x2'' = T - G, T = c·(x1 - x2), F_d = G + (m1+m2)·a
    for t < t_p, G afterwards; at rest T = G. With T = G + c·w and μ = m1·m2/(m1+m2):
    w'' = (F_d - G)/m1 - c·w·(1/m1 + 1/m2), i.e. μ·w'' + c·w = m2·a during the start and 0
    after: a rectangular pulse of height m2·a on a one-mass system of frequency
    β = √(c(1/m1+1/m2)). During the pulse c·w = m2·a·(1 - cos βt) (max 2·m2·a once
    βt reaches π); after it c·w = m2·a·(cos β(t-t_p) - cos βt), amplitude
    2·m2·a·sin(β·t_p/2). Hence F_max = G + 2·m2·a·(1 if t_p ≥ π/β else sin(β·t_p/2)).
    """
    beta = math.sqrt(c * (1.0 / m1 + 1.0 / m2))
    factor = 1.0 if t_p >= math.pi / beta else math.sin(beta * t_p / 2.0)
    return g_force + 2.0 * m2 * a * factor


def ground_peak(c: float, m1: float, m2: float, g_force: float, a: float) -> tuple[float, float]:
    """First peak rope force, load on the ground, rope just taut; (F_max, time of the peak).

    Own derivation, valid while the start lasts past the peak (checked by the caller):
    1. Load grounded: m1·x1'' = F - c·x1, F = G + (m1+m2)·a, x1(0) = x1'(0) = 0, so
       x1 = (F/c)(1 - cos β1·t), β1 = √(c/m1). Lift-off when c·x1 = G:
       cos θ = 1 - G/F, θ = β1·t1; drum-end speed u = (F/c)·β1·sin θ, load at rest.
    2. Both masses move: with T = G + c·w, w'' + β²·w = (F - G)/m1, β² = c(1/m1+1/m2),
       w(0) = 0, w'(0) = u. So c·w = c·A(1 - cos βτ) + (c·u/β)·sin βτ with
       c·A = c(F-G)/(m1·β²) = m2·a, and the peak is
       F_max = G + m2·a + √((m2·a)² + (c·u/β)²), (c·u/β)² = G·(2F - G)·m2/(m1+m2)
       [F²·sin²θ = G·(2F - G)]. It comes at βτ* = π - atan(u·β/(A·β²)).
    Heavy drive m1 → ∞: (c·u/β)² → 2·G·m2·a, F_max → G + m2·a + √((m2·a)² + 2·G·m2·a).
    """
    force = g_force + (m1 + m2) * a
    beta1 = math.sqrt(c / m1)
    theta = math.acos(1.0 - g_force / force)
    u = force / c * beta1 * math.sin(theta)
    beta = math.sqrt(c * (1.0 / m1 + 1.0 / m2))
    ca = m2 * a
    cu_beta_sq = g_force * (2.0 * force - g_force) * m2 / (m1 + m2)
    peak = g_force + ca + math.sqrt(ca * ca + cu_beta_sq)
    tau = (math.pi - math.atan2(math.sqrt(cu_beta_sq), ca)) / beta
    # consistency of the two forms of (c·u/β)²
    assert (c * u / beta) ** 2 == pytest.approx(cu_beta_sq, rel=1e-9)
    return peak, theta / beta1 + tau


def rope_ode_peak(
    c: float,
    m1: float,
    m2: float,
    g_force: float,
    a: float,
    t_p: float,
    hanging: bool,
) -> float:
    """Own integration of the two-mass rope model (independent of the program).

    State [x1, v1, y, vy] on the rope line, rope force c·max(x1 - y, 0), drive force
    G + (m1+m2)·a before t_p and G after. Hanging: rope stretched by G/c at t = 0, no
    ground. On the ground: the load stays at y = 0 until the rope force reaches G, and
    lands again if y comes back to 0. Peaks are found as zeros of the stretch rate.
    """
    beta = math.sqrt(c * (1.0 / m1 + 1.0 / m2))
    beta1 = math.sqrt(c / m1)
    period = 2.0 * math.pi / beta
    force = g_force + (m1 + m2) * a

    def drive(t: float) -> float:
        return force if t < t_p else g_force

    def tension(s: np.ndarray) -> float:
        return c * max(s[0] - s[2], 0.0)

    def air(t: float, s: np.ndarray) -> list[float]:
        f = tension(s)
        return [s[1], (drive(t) - f) / m1, s[3], (f - g_force) / m2]

    def ground(t: float, s: np.ndarray) -> list[float]:
        return [s[1], (drive(t) - tension(s)) / m1, 0.0, 0.0]

    def stretch_rate(t: float, s: np.ndarray) -> float:
        return s[1] - s[3]

    stretch_rate.direction = -1  # type: ignore[attr-defined]

    def lift(t: float, s: np.ndarray) -> float:
        return c * (s[0] - s[2]) - g_force

    lift.terminal = True  # type: ignore[attr-defined]
    lift.direction = 1  # type: ignore[attr-defined]

    def land(t: float, s: np.ndarray) -> float:
        return s[2]

    land.terminal = True  # type: ignore[attr-defined]
    land.direction = -1  # type: ignore[attr-defined]

    scale = force / c
    atol = [scale * 1e-13, scale * beta * 1e-13, scale * 1e-13, scale * beta * 1e-13]
    if hanging:
        t, s, on_ground = 0.0, np.array([g_force / c, 0.0, 0.0, 0.0]), False
        t_lift = 0.0
    else:
        t, s, on_ground = 0.0, np.zeros(4), True
        t_lift = math.inf
    peak = tension(s)
    for _ in range(1000):
        if on_ground:
            t_end = t_p if t < t_p else t + 4.0 * math.pi / beta1
        else:
            t_end = t_p if t < t_p else max(t_p, t_lift) + 3.0 * period
            if t >= t_end:
                return peak
        events = [stretch_rate] + ([lift] if on_ground else ([] if hanging else [land]))
        sol = solve_ivp(
            ground if on_ground else air,
            (t, t_end),
            s,
            method="DOP853",
            rtol=1e-12,
            atol=atol,
            events=events,
            max_step=min(period, 2.0 * math.pi / beta1) / 40.0,
        )
        assert sol.status >= 0, sol.message
        for state in sol.y_events[0]:
            peak = max(peak, tension(state))
        peak = max(peak, float(np.max(c * np.maximum(sol.y[0] - sol.y[2], 0.0))))
        t, s = float(sol.t[-1]), sol.y[:, -1].copy()
        if sol.status == 1:  # a terminal event: lift-off or landing
            if on_ground:
                on_ground, t_lift = False, t
            else:
                on_ground, s = True, np.array([s[0], s[1], 0.0, 0.0])
    raise AssertionError("own rope integration did not finish")


def test_own_rope_integration_agrees_with_own_closed_forms() -> None:
    """Sanity of the derivations above (no program involved)."""
    c, m1, m2, g_force = 1.0e6, 2.0e4, 1.0e4, 98100.0
    for a, t_p in ((1.0, 2.0), (1.0, 0.1)):  # t_p ≥ π/β and t_p < π/β (π/β = 0.2565 s)
        expected = hanging_peak(c, m1, m2, g_force, a, t_p)
        assert rope_ode_peak(c, m1, m2, g_force, a, t_p, hanging=True) == rel(expected, 1e-8)
    peak, t_peak = ground_peak(c, m1, m2, g_force, 1.0)
    assert t_peak < 2.0
    assert rope_ode_peak(c, m1, m2, g_force, 1.0, 2.0, hanging=False) == rel(peak, 1e-8)


# ---------------------------------------------------------------------- steady lifting


def test_steady_lifting_crane(tmp_path: Path) -> None:
    r = run(tmp_path, CRANE)
    assert r["status"] == "ok"
    # G = m·g = 10 000·9.81 = 98 100 N
    assert r["weight"] == rel(98100.0)
    # η = η1·η2·…·ηn·η_pulley = 0.97·0.97·0.98·0.97 = 0.894 419 54 (brief §1)
    assert r["total_efficiency"] == rel(0.89441954)
    # N_p = G·V = 98 100·0.2 = 19 620 W = 19.62 kW (7.25)
    assert r["useful_power"] == rel(19.62)
    # N_d = N_p/η = 19.62/0.894 419 54 = 21.936 kW (7.24)
    assert r["motor_power"] == rel(19.62 / 0.89441954)
    assert r["motor_power"] == pytest.approx(21.936, abs=5e-4)
    # ω1 = 2π·960/60 = 32π = 100.531 rad/s
    assert r["motor_speed"] == rel(32.0 * math.pi)
    # M_c = G·V/(ω1·η) = 19 620/(100.531·0.894 42) = 218.20 N·m (7.26)
    assert r["static_torque"] == rel(M_C_CRANE)
    assert r["static_torque"] == pytest.approx(218.20, abs=5e-3)
    # M_brake = K_t·M_c = 1.75·218.20 = 381.85 N·m (7.27)
    assert r["brake_torque"] == rel(1.75 * M_C_CRANE)
    assert r["brake_torque"] == pytest.approx(381.85, abs=5e-3)
    # lowering: the load drives, η multiplies: M_c,low = G·V·η/ω1 = 174.56 N·m (brief §1)
    assert r["lowering_torque"] == rel(G_CRANE * V_CRANE * ETA_CRANE / OMEGA_CRANE)
    assert r["lowering_torque"] == pytest.approx(174.56, abs=5e-3)
    # margin K_t·M_c/M_c,low = K_t/η² = 1.75/0.894 42² = 2.1875
    assert r["brake_margin"] == rel(1.75 / ETA_CRANE**2)


def test_static_torque_is_the_smallest_in_the_train(tmp_path: Path) -> None:
    """(7.26): M_c on the fastest shaft is below the drum torque G·V/ω_drum (η ≤ 1)."""
    r = run(tmp_path, CRANE)
    drum_torque_ideal = G_CRANE * V_CRANE / rpm(15.279)  # no losses after the drum
    assert r["static_torque"] < drum_torque_ideal


def test_efficiency_exactly_one(tmp_path: Path) -> None:
    data = case(drive={"stage_efficiencies": [1.0, 1.0], "pulley_efficiency": 1.0})
    r = run(tmp_path, data)
    # η = 1: N_d = N_p, M_c = M_c,low = G·V/ω1 = 19 620/(32π) = 195.17 N·m
    expected = 98100.0 * 0.2 / (32.0 * math.pi)
    assert r["total_efficiency"] == 1.0
    assert r["motor_power"] == rel(r["useful_power"])
    assert r["static_torque"] == rel(expected)
    assert r["lowering_torque"] == rel(expected)
    assert r["lowering_torque"] == rel(r["static_torque"])
    # margin = K_t exactly
    assert r["brake_margin"] == rel(1.75)


def test_pulley_efficiency_default_is_one(tmp_path: Path) -> None:
    data = case()
    del data["drive"]["pulley_efficiency"]
    r = run(tmp_path, data)
    assert r["total_efficiency"] == rel(0.97 * 0.97 * 0.98)


@pytest.mark.parametrize("gravity", [9.81, 9.80665])
def test_weight_uses_case_gravity(tmp_path: Path, gravity: float) -> None:
    r = run(tmp_path, case(gravity=gravity))
    assert r["weight"] == rel(10000.0 * gravity)
    assert r["useful_power"] == rel(10000.0 * gravity * 0.2 / 1e3)


def test_default_gravity_is_standard(tmp_path: Path) -> None:
    r = run(tmp_path, case(gravity=None))
    assert r["weight"] == rel(10000.0 * 9.80665)


# ------------------------------------------------------------------ reduced inertia


def test_reduced_inertia_by_kinetic_energy(tmp_path: Path) -> None:
    """(7.29)-(7.30): J = J1 + Σ J_k(ω_k/ω1)² + m(V/ω1)², shafts by ratio and by rpm."""
    r = run(tmp_path, CRANE)
    # gear shaft, ratio 5: 0.5/25 = 0.02; drum 15.279 rpm: 40·(15.279/960)² = 0.010 132
    assert r["shaft_inertia"] == rel(0.02 + 40.0 * (15.279 / 960.0) ** 2)
    assert r["shaft_inertia"] == pytest.approx(0.030132, abs=5e-7)
    # load: 10 000·(0.2/100.531)² = 0.039 579 kg·m²
    assert r["load_inertia"] == rel(J_LOAD_CRANE)
    assert r["load_inertia"] == pytest.approx(0.039579, abs=5e-7)
    assert r["motor_inertia"] == rel(0.35)
    # J = 0.35 + 0.030 132 + 0.039 579 = 0.419 711 kg·m²
    assert r["reduced_inertia"] == rel(J_CRANE)
    assert r["reduced_inertia"] == pytest.approx(0.419711, abs=5e-7)


def test_shaft_given_by_ratio_equals_shaft_given_by_speed(tmp_path: Path) -> None:
    """A shaft at ratio i turns at n1/i rpm: both inputs give J_k/i²."""
    by_ratio = case()
    by_ratio["drive"]["shafts"] = [{"name": "gear", "inertia": 2.0, "ratio": 8.0}]
    by_speed = case()
    by_speed["drive"]["shafts"] = [{"name": "gear", "inertia": 2.0, "speed_rpm": 960.0 / 8.0}]
    ra = run(tmp_path, by_ratio)
    rb = run(tmp_path, by_speed)
    assert ra["shaft_inertia"] == rel(2.0 / 64.0)
    assert rb["shaft_inertia"] == rel(2.0 / 64.0)


@pytest.mark.parametrize("factor", [None, 1.1, 1.2])
def test_inertia_estimate_when_no_shafts(tmp_path: Path, factor: float | None) -> None:
    """(7.31): J ≈ (1.1…1.2)·J1 when only J1 is known; default factor 1.2."""
    data = case()
    del data["drive"]["shafts"]
    if factor is not None:
        data["drive"]["inertia_estimate_factor"] = factor
    r = run(tmp_path, data)
    k = 1.2 if factor is None else factor
    assert r["reduced_inertia"] == rel(k * 0.35)
    # (7.28): M_start = M_c + J·ω1/t_p with that J
    assert r["starting_torque"] == rel(M_C_CRANE + k * 0.35 * OMEGA_CRANE / 1.5)


# ------------------------------------------------------------------------------ start


def test_starting_torque_from_start_time(tmp_path: Path) -> None:
    r = run(tmp_path, CRANE)
    # (7.32): dω/dt = ω1/t_p = 32π/1.5 = 67.021 rad/s²
    assert r["angular_acceleration"] == rel(32.0 * math.pi / 1.5)
    # M_in = J·ω1/t_p = 0.419 711·67.021 = 28.129 N·m
    assert r["inertia_torque"] == rel(J_CRANE * OMEGA_CRANE / 1.5)
    assert r["inertia_torque"] == pytest.approx(28.129, abs=5e-4)
    # (7.28): M_start = M_c + M_in = 218.202 + 28.129 = 246.331 N·m
    assert r["starting_torque"] == rel(M_C_CRANE + J_CRANE * OMEGA_CRANE / 1.5)
    assert r["starting_torque"] == pytest.approx(246.331, abs=5e-4)
    # a = V/t_p = 0.2/1.5 = 0.1333 m/s²
    assert r["start_time"] == rel(1.5)
    assert r["load_acceleration"] == rel(0.2 / 1.5)
    assert r["acceleration_ok"] is True


def test_start_time_from_catalogue_torque(tmp_path: Path) -> None:
    """t_p = J·ω1/(M_start - M_c) (brief §1)."""
    m_start = 400.0
    r = run(tmp_path, case(start={"starting_torque": m_start, "machine": "crane"}))
    t_p = J_CRANE * OMEGA_CRANE / (m_start - M_C_CRANE)  # 42.193/181.80 = 0.232 09 s
    assert r["start_time"] == rel(t_p)
    assert r["start_time"] == pytest.approx(0.23209, abs=5e-6)
    assert r["angular_acceleration"] == rel(OMEGA_CRANE / t_p)
    assert r["inertia_torque"] == rel(m_start - M_C_CRANE)
    assert r["starting_torque"] == rel(m_start)
    # a = V/t_p = 0.2/0.232 09 = 0.8617 m/s², above the crane's 0.8
    assert r["load_acceleration"] == rel(0.2 / t_p)
    assert r["acceleration_ok"] is False


def test_start_time_round_trip(tmp_path: Path) -> None:
    """The starting torque for t_p, fed back as a catalogue torque, gives t_p again."""
    m_start = M_C_CRANE + J_CRANE * OMEGA_CRANE / 2.0  # (7.28) with t_p = 2 s
    r = run(tmp_path, case(start={"starting_torque": m_start}))
    assert r["start_time"] == rel(2.0, 1e-9)


@pytest.mark.parametrize(
    ("fraction", "shafts"),
    [
        pytest.param(0.5, False, id="half-no-shafts"),
        pytest.param(1.0 - 1e-9, False, id="just-below-no-shafts"),
        pytest.param(0.5, True, id="half-with-shafts"),
        pytest.param(1.0 - 1e-9, True, id="just-below-with-shafts"),
    ],
)
def test_motor_cannot_start_the_load(tmp_path: Path, fraction: float, shafts: bool) -> None:
    """M_start ≤ M_c: valid input, no answer: exit 3, status "no-answer" (brief §1)."""
    data = case(start={"starting_torque": fraction * M_C_CRANE})
    if not shafts:
        del data["drive"]["shafts"]
    code, document, stderr = run_cli(tmp_path, data)
    assert code == 3, stderr
    assert document is not None
    assert document["status"] == "no-answer"
    assert document["message"]
    # the steady part is still reported: M_c = G·V/(ω1·η) (7.26)
    assert document["results"]["static_torque"]["value"] == rel(M_C_CRANE)
    for key in ("start_time", "starting_torque", "load_acceleration"):
        assert key not in document["results"]


def test_motor_just_able_to_start(tmp_path: Path) -> None:
    m_start = M_C_CRANE * (1.0 + 1e-6)
    code, document, _ = run_cli(tmp_path, case(start={"starting_torque": m_start}))
    assert code == 0
    assert document is not None and document["status"] == "ok"
    t_p = J_CRANE * OMEGA_CRANE / (m_start - M_C_CRANE)
    assert document["results"]["start_time"]["value"] == rel(t_p, 1e-6)


def test_cli_json_shape_and_values(tmp_path: Path) -> None:
    code, document, _ = run_cli(tmp_path, CRANE)
    assert code == 0
    assert document is not None and document["status"] == "ok"
    results = document["results"]
    assert results["static_torque"]["value"] == rel(M_C_CRANE)
    assert results["static_torque"]["unit"] == "N*m"  # the JSON's ASCII form
    assert results["useful_power"]["unit"] == "kW"
    methods = [s for s in document["sections"] if s.get("kind") == "methods"]
    assert methods
    for section in methods:
        assert sum(1 for row in section["rows"] if row["reference"]) == 1


# (a, machine, ok): cranes 0.1…0.8 m/s², lifts 1.5…2.0 m/s² (seed 000 after (7.32))
@pytest.mark.parametrize(
    ("accel", "machine", "ok"),
    [
        (0.5, "crane", True),
        (0.8, "crane", True),
        (1.0, "crane", False),
        (1.8, "crane", False),
        (1.8, "lift", True),
        (2.0, "lift", True),
        (2.5, "lift", False),
    ],
)
def test_allowable_acceleration(tmp_path: Path, accel: float, machine: str, ok: bool) -> None:
    t_p = 0.2 / accel  # a = V/t_p
    r = run(tmp_path, case(start={"time": t_p, "machine": machine}))
    assert r["load_acceleration"] == rel(accel)
    assert r["acceleration_ok"] is ok


def test_allowable_acceleration_override(tmp_path: Path) -> None:
    data = case(
        start={"time": 0.5, "machine": "crane", "allowable_acceleration": 0.3}
    )  # a = 0.4 m/s²
    report = run_report(tmp_path, data)
    r = {k: q.value for k, q in report.results().items()}
    assert r["load_acceleration"] == rel(0.4)
    assert r["acceleration_ok"] is False
    assert any(note.level == "warning" for note in report.notes)


# ------------------------------------------------------------------------------- rope


def rope_case(
    *,
    stiffness: float,
    drive_mass: float | None,
    mass: float = 10000.0,
    speed: float = 0.2,
    t_p: float = 1.5,
) -> dict[str, Any]:
    rope: dict[str, Any] = {"stiffness": stiffness}
    if drive_mass is not None:
        rope["drive_mass"] = drive_mass
    return case(
        load={"mass": mass, "lifting_speed": speed},
        start={"time": t_p, "machine": "crane"},
        rope=rope,
    )


def test_rope_crane_scene(tmp_path: Path) -> None:
    """Rope from E·A/L, drive mass from the rotating inertia, hanging branch t_p ≥ π/β."""
    data = case(rope={"elastic_modulus": 1.0e11, "area": 1.5e-4, "length": 10.0, "branches": 4})
    r = run(tmp_path, data)
    # c = n·E·A/L = 4·1e11·1.5e-4/10 = 6e6 N/m
    c = 6.0e6
    assert r["rope_stiffness"] == rel(c)
    # m1 = (J1 + Σ J_k(ω_k/ω1)²)·(ω1/V)² = 0.380 132·(502.65)² = 96 045 kg (brief §1)
    m1 = (0.35 + J_SHAFTS_CRANE) * (OMEGA_CRANE / V_CRANE) ** 2
    assert r["drive_mass"] == rel(m1)
    assert r["drive_mass"] == pytest.approx(96045.0, abs=0.5)
    m2 = 10000.0
    beta = math.sqrt(c * (1.0 / m1 + 1.0 / m2))  # 25.739 rad/s, π/β = 0.122 s < t_p
    assert r["rope_frequency"] == rel(beta)
    assert math.pi / beta < 1.5
    a = 0.2 / 1.5
    # hanging, t_p ≥ π/β: F_max = G + 2·m2·a = 98 100 + 2·10 000·0.1333 = 100 766.7 N
    assert r["hanging_peak_force"] == rel(G_CRANE + 2.0 * m2 * a)
    assert r["hanging_peak_force"] == pytest.approx(100766.7, abs=0.05)
    assert r["hanging_dynamic_factor"] == rel((G_CRANE + 2.0 * m2 * a) / G_CRANE)
    # ground: own two-mass closed form (ground_peak), peak well inside the start
    peak, t_peak = ground_peak(c, m1, m2, G_CRANE, a)
    assert t_peak < 1.5
    assert r["ground_peak_force"] == rel(peak, 1e-7)
    assert r["ground_dynamic_factor"] == rel(peak / G_CRANE, 1e-7)


def test_rope_hanging_long_start_branch(tmp_path: Path) -> None:
    """t_p ≥ π/β: F_max = G + 2·m2·V/t_p (the lecture's (7.95) holds)."""
    # c = 1e5 N/m, m1 = 5e4 kg, m2 = 1e4 kg: β = √(1e5·(2e-5 + 1e-4)) = √12 = 3.4641 rad/s,
    # π/β = 0.9069 s < t_p = 2 s; a = 0.2/2 = 0.1 m/s²
    r = run(tmp_path, rope_case(stiffness=1.0e5, drive_mass=5.0e4, t_p=2.0))
    assert r["rope_frequency"] == rel(math.sqrt(12.0))
    # F_max = 98 100 + 2·10 000·0.1 = 100 100 N, ψ = 1.020 387
    assert r["hanging_peak_force"] == rel(100100.0)
    assert r["hanging_dynamic_factor"] == rel(100100.0 / 98100.0)


def test_rope_hanging_short_start_branch(tmp_path: Path) -> None:
    """t_p < π/β: F_max = G + 2·m2·(V/t_p)·sin(β·t_p/2)."""
    # β = √12 rad/s, π/β = 0.9069 s > t_p = 0.5 s; a = 0.2/0.5 = 0.4 m/s²
    # sin(√12·0.25) = sin(0.866 03) = 0.761 76; F_max = 98 100 + 8000·0.761 76 = 104 194.08 N
    r = run(tmp_path, rope_case(stiffness=1.0e5, drive_mass=5.0e4, t_p=0.5))
    expected = 98100.0 + 2.0 * 10000.0 * 0.4 * math.sin(math.sqrt(12.0) * 0.25)
    assert r["hanging_peak_force"] == rel(expected)
    assert r["hanging_peak_force"] == pytest.approx(104194.08, abs=0.005)
    # smaller than the lecture's G + 2·m2·a = 106 100 N, which assumes t_p ≥ π/β
    assert r["hanging_peak_force"] < 98100.0 + 2.0 * 10000.0 * 0.4


def test_rope_hanging_at_half_period(tmp_path: Path) -> None:
    """t_p = π/β exactly: both branches give G + 2·m2·a."""
    beta = math.sqrt(12.0)
    t_p = math.pi / beta
    r = run(tmp_path, rope_case(stiffness=1.0e5, drive_mass=5.0e4, t_p=t_p))
    assert r["hanging_peak_force"] == rel(98100.0 + 2.0 * 10000.0 * 0.2 / t_p, 1e-9)


def test_rope_with_start_time_from_catalogue_torque(tmp_path: Path) -> None:
    """The rope sees the t_p that follows from the catalogue torque: t_p = J·ω1/(M - M_c)."""
    data = case(
        start={"starting_torque": 400.0, "machine": "crane"},
        rope={"stiffness": 1.0e5, "drive_mass": 5.0e4},
    )
    r = run(tmp_path, data)
    t_p = J_CRANE * OMEGA_CRANE / (400.0 - M_C_CRANE)  # 0.232 09 s < π/β = 0.9069 s
    expected = hanging_peak(1.0e5, 5.0e4, 1.0e4, G_CRANE, V_CRANE / t_p, t_p)
    assert r["hanging_peak_force"] == rel(expected)


def test_rope_lecture_rows(tmp_path: Path) -> None:
    """The Methods tables carry the lecture's own formulas (7.95) and (7.98)."""
    data = rope_case(stiffness=1.0e5, drive_mass=5.0e4, t_p=0.5)
    report = run_report(tmp_path, data)
    a = 0.4
    tables = {s.key: s for s in report.sections if hasattr(s, "rows") and hasattr(s, "key")}
    hanging = tables["rope_hanging"]
    ground = tables["rope_ground"]
    lecture_h = next(row for row in hanging.rows if "lecture" in row.method.lower())
    lecture_g = next(row for row in ground.rows if "lecture" in row.method.lower())
    # (7.95): G + 2·m2·V/t_p = 106 100 N; (7.98): 2·(G + m2·V/t_p) = 204 200 N
    assert lecture_h.values["peak_force"] == rel(98100.0 + 2.0 * 10000.0 * a)
    assert lecture_g.values["peak_force"] == rel(2.0 * (98100.0 + 10000.0 * a))
    # the reference's relative error is measured against the hand value (same key)
    ref = 98100.0 + 2.0 * 10000.0 * a * math.sin(math.sqrt(12.0) * 0.25)
    err = abs(lecture_h.values["peak_force"] - ref) / ref
    assert lecture_h.rel_errors["peak_force"] == rel(err, 1e-6)


def test_rope_ground_heavy_drive_limit(tmp_path: Path) -> None:
    """Very heavy drive: drum end moves as a·t²/2 and F_max = G + m2a + √((m2a)² + 2G·m2a).

    Derivation: lift-off when c·a·t1²/2 = G, drum speed then u = a·t1 = √(2aG/c); after it
    w'' + (c/m2)·w = a, w(0) = 0, w'(0) = u: c·w_max = m2·a + √((m2·a)² + c·m2·u²) and
    c·m2·u² = 2·G·m2·a. Here c = 6e6 N/m, m2 = 1e4 kg, a = 0.1333 m/s²: t1 = √(2G/(c·a))
    = 0.4952 s, π/β = π/√(c/m2) = 0.1283 s, so the peak comes before 0.63 s < t_p = 1.5 s.
    """
    m1 = 1.0e12
    r = run(tmp_path, rope_case(stiffness=6.0e6, drive_mass=m1))
    g_force, m2a = 98100.0, 10000.0 * (0.2 / 1.5)
    # 98 100 + 1 333.33 + √(1 333.33² + 2·98 100·1 333.33) = 98 100 + 1 333.33 + 16 228.92
    heavy = g_force + m2a + math.sqrt(m2a**2 + 2.0 * g_force * m2a)
    assert heavy == pytest.approx(115662.25, abs=0.005)
    peak, t_peak = ground_peak(6.0e6, m1, 10000.0, g_force, 0.2 / 1.5)
    assert t_peak < 1.5
    assert peak == rel(heavy, 1e-6)  # finite m1 differs by O(G/(2a·m1))
    assert r["ground_peak_force"] == rel(heavy, 1e-6)
    assert r["ground_dynamic_factor"] == rel(heavy / g_force, 1e-6)
    # well below the lecture's (7.98) 2·(G + m2·a) = 198 866.7 N
    assert r["ground_peak_force"] < 2.0 * (g_force + m2a)


def test_rope_ground_two_mass_closed_form(tmp_path: Path) -> None:
    """Finite drive mass, peak inside the start: own two-mass closed form (ground_peak)."""
    c, m1, m2, t_p, speed = 1.0e6, 2.0e4, 1.0e4, 2.0, 2.0  # a = 1 m/s²
    r = run(tmp_path, rope_case(stiffness=c, drive_mass=m1, speed=speed, t_p=t_p))
    peak, t_peak = ground_peak(c, m1, m2, 98100.0, speed / t_p)
    assert t_peak < t_p
    assert r["ground_peak_force"] == rel(peak, 1e-7)


def test_rope_ground_peak_after_the_start(tmp_path: Path) -> None:
    """Peak after t_p (no closed form here): own numerical integration is the reference."""
    # c = 1e6, m1 = 2e4, m2 = 1e4, V = 0.5 m/s, t_p = 0.3 s: lift-off at 0.17 s,
    # π/β = 0.256 s, so the first peak comes after the end of the start.
    c, m1, m2, speed, t_p = 1.0e6, 2.0e4, 1.0e4, 0.5, 0.3
    _, t_peak = ground_peak(c, m1, m2, 98100.0, speed / t_p)
    assert t_peak > t_p  # the closed form does not apply
    expected = rope_ode_peak(c, m1, m2, 98100.0, speed / t_p, t_p, hanging=False)
    r = run(tmp_path, rope_case(stiffness=c, drive_mass=m1, speed=speed, t_p=t_p))
    assert r["ground_peak_force"] == rel(expected, 1e-6)
    assert r["hanging_peak_force"] == rel(hanging_peak(c, m1, m2, 98100.0, speed / t_p, t_p))


def test_rope_very_short_start(tmp_path: Path) -> None:
    """t_p = 1 ms: finite values; hanging ≈ G + m2·V·β (impulse), ground by own ODE."""
    c, m1, m2, speed, t_p = 6.0e6, 96000.0, 1.0e4, 0.2, 1.0e-3
    r = run(tmp_path, rope_case(stiffness=c, drive_mass=m1, speed=speed, t_p=t_p))
    for key in ("hanging_peak_force", "ground_peak_force", "start_time", "starting_torque"):
        assert math.isfinite(r[key])
    a = speed / t_p
    assert r["hanging_peak_force"] == rel(hanging_peak(c, m1, m2, 98100.0, a, t_p))
    expected = rope_ode_peak(c, m1, m2, 98100.0, a, t_p, hanging=False)
    assert r["ground_peak_force"] == rel(expected, 1e-6)
    assert r["acceleration_ok"] is False  # 200 m/s²


def _stiff_param(ratio: float) -> Any:
    return pytest.param(ratio, id=f"c x{ratio:g}")


@pytest.mark.parametrize("ratio", [_stiff_param(r) for r in (1e3, 1e6, 1e9)])
def test_rope_very_stiff(tmp_path: Path, ratio: float) -> None:
    """A rope 1e3…1e9 times stiffer than the crane's 6e6 N/m: finite, hand-checkable values.

    Hanging: β grows, t_p ≥ π/β, F_max = G + 2·m2·a. Ground: the peak comes within a few
    rope periods of the start, so the own two-mass closed form holds; as c → ∞ it tends
    to G + m2·a + √((m2·a)² + G(2F - G)·m2/(m1+m2)), independent of c.
    """
    c = 6.0e6 * ratio
    m1 = (0.35 + J_SHAFTS_CRANE) * (OMEGA_CRANE / V_CRANE) ** 2
    data = case(rope={"stiffness": c})
    code, document, stderr = run_cli(tmp_path, data)
    assert code == 0, stderr
    assert document is not None
    results = {k: v["value"] for k, v in document["results"].items()}
    a = 0.2 / 1.5
    assert results["hanging_peak_force"] == rel(G_CRANE + 2.0 * 10000.0 * a)
    peak, t_peak = ground_peak(c, m1, 10000.0, G_CRANE, a)
    assert t_peak < 1.5
    assert results["ground_peak_force"] == rel(peak, 1e-6)
    assert math.isfinite(results["ground_dynamic_factor"])
