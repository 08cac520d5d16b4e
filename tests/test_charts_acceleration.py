"""``acceleration`` charts (``--plot``): the data of the speed-time curve and of the
traction diagram, checked against values worked out here by hand from the brief
(PROBLEMS.md §2, seed 000 §7.3) and the case files, not copied from the program.

    F_t = M_e(ω)·U_i·U_K·η/r,   v = ω·r/(U_i·U_K),   R = ψ·m·g + ½·ρ·C_x·A·v²
    M_e = M_N·(a + b·x - c·x²), x = ω/ω_E, M_N = N_E/ω_E        (Leiderman, (7.37) as read)
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest

from mdcalc.input.casefile import read_case
from mdcalc.output.plot import Chart, Series
from mdcalc.runs.runner import solve_text
from tests.conftest import CASES

G0 = 9.80665  # standard gravity, the program's default [m/s²]
RPM = math.pi / 30.0  # rpm → rad/s
KMH = 3.6  # m/s → km/h


def charts_of(name: str, folder: str = "acceleration") -> tuple[list[Chart], Any]:
    run = solve_text(read_case(CASES / folder / f"{name}.toml"))
    return run.module.charts(run.result), run


def series(chart: Chart, start: str) -> Series:
    found = [s for s in chart.series if s.label.startswith(start)]
    assert len(found) == 1, [s.label for s in chart.series]
    return found[0]


def value_at(s: Series, x: float) -> float:
    """Linear interpolation of a series at x (x increasing)."""
    xs, ys = list(s.x), list(s.y)
    for k in range(len(xs) - 1):
        if xs[k] <= x <= xs[k + 1]:
            w = 0.0 if xs[k + 1] == xs[k] else (x - xs[k]) / (xs[k + 1] - xs[k])
            return ys[k] + w * (ys[k + 1] - ys[k])
    raise AssertionError(f"{x} outside [{xs[0]}, {xs[-1]}]")


def key(run: Any, name: str) -> Any:
    for section in run.report.sections:
        for item in getattr(section, "items", []):
            if item.key == name:
                return item.value
    raise KeyError(name)


# ------------------------------------------------------------------ speed against time


def test_constant_force_speed_is_a_times_t():
    """One gear, flat 200 N·m, δ = 1, no drag: m·a = T·U·U_K·η/r - ψ·m·g at every
    speed (the clutch slips at the same torque), so v = a·t exactly."""
    charts, _ = charts_of("constant_force")
    speed = charts[0]
    a = 200.0 * 2.0 * 4.0 * 0.9 / 0.3 / 1000.0 - 0.01 * G0  # [m/s²]
    t_target = 100.0 / KMH / a  # 5.9077 s
    run = series(speed, "reference run")
    assert run.x[0] == 0.0 and run.y[0] == 0.0
    assert run.x[-1] == pytest.approx(t_target, rel=1e-9)
    assert run.y[-1] == pytest.approx(100.0, rel=1e-9)
    for t, v in zip(run.x, run.y, strict=True):
        assert v == pytest.approx(a * t * KMH, rel=1e-8, abs=1e-9)
    assert [m for m in speed.marks if m.axis == "x"] == []  # one gear: no upshift
    (target,) = [m for m in speed.marks if m.axis == "y"]
    assert target.value == pytest.approx(100.0)


def test_constant_force_with_drag_is_tanh():
    """m·v' = F - k·v² (F net of ψ·m·g): v = s·tanh(ω·t), s = √(F/k), ω = √(F·k)/m."""
    charts, _ = charts_of("constant_force_drag")
    m, k = 1000.0, 0.5 * 1.225 * 0.3 * 2.0
    force = 200.0 * 2.0 * 4.0 * 0.9 / 0.3 - 0.01 * m * G0
    s, omega = math.sqrt(force / k), math.sqrt(force * k) / m
    run = series(charts[0], "reference run")
    assert run.x[-1] == pytest.approx(math.atanh(100.0 / KMH / s) / omega, rel=1e-9)
    for t, v in zip(run.x, run.y, strict=True):
        assert v == pytest.approx(s * math.tanh(omega * t) * KMH, rel=1e-8, abs=1e-9)


def test_vaz2106_speed_curve_ends_at_the_target_rises_in_gear_and_shifts_at_5400_rpm():
    charts, run = charts_of("vaz2106")
    assert len(charts) == 2
    speed = charts[0]
    curve = series(speed, "reference run")
    assert curve.x[-1] == pytest.approx(key(run, "time_to_target"), rel=1e-12)
    assert curve.x[-1] == pytest.approx(17.517975367618, rel=1e-8)  # the case's RK4
    assert curve.y[-1] == pytest.approx(100.0, rel=1e-9)
    assert all(b > a for a, b in zip(curve.x, curve.x[1:], strict=False))  # time runs on
    shifts = sorted(m.value for m in speed.marks if m.axis == "x")
    assert len(shifts) == 2  # 1→2 and 2→3: 5400 rpm in 3rd is 109 km/h > 100
    # Upshift where the engine reaches n_E = 5400 rpm: v = ω·r/(U_i·U_K).
    for gear_ratio, t_shift in zip((3.242, 1.989), shifts, strict=True):
        v_shift = 5400.0 * RPM * 0.269 / (gear_ratio * 3.9) * KMH  # 43.31, 70.60 km/h
        assert value_at(curve, t_shift) == pytest.approx(v_shift, rel=1e-6)
    # The speed rises while a gear is engaged and falls during each 1 s shift.
    for t, v, t_next, v_next in zip(curve.x, curve.y, curve.x[1:], curve.y[1:], strict=False):
        shifting = any(t0 <= t and t_next <= t0 + 1.0 + 1e-9 for t0 in shifts)
        assert (v_next < v) if shifting else (v_next > v), (t, t_next)
    # Drag and rolling resistance in the shift (δ_0 = 1.04, k = ½·1.225·0.5·1.85):
    # the loss is about (ψ·g + k·v²/m)/δ_0·1 s, under 1 km/h at these speeds.
    for t0 in shifts:
        loss = value_at(curve, t0) - value_at(curve, t0 + 1.0)
        v = value_at(curve, t0) / KMH
        expected = (0.015 * G0 + 0.5 * 1.225 * 0.5 * 1.85 * v * v / 1120.0) / 1.04 * KMH
        assert loss == pytest.approx(expected, rel=0.02)
    assert len(curve.x) >= 300  # a smooth curve, not the report's 20-row table


def test_lecture_curve_follows_7_40_and_7_42():
    """The lecture's run: constant A·U_i/m - ψ per gear, each ending at ω_D·r/(U_i·U_K)
    (capped at the target), the speed held through each 1 s shift. Brief §2:
    v_end = 8.64 / 14.28 / 21.90 / 27.78 m/s, total 17.49 s."""
    charts, _ = charts_of("lecture")
    lecture = series(charts[0], "lecture method")
    assert lecture.role == "comparison"
    times, v_end, clock = [0.0], [0.0], 0.0
    ratios = (3.8, 2.3, 1.5, 1.0)
    for k, u in enumerate(ratios):
        v1 = min(300.0 * 0.45 / (u * 4.11), 100.0 / KMH) if k < 3 else 100.0 / KMH
        clock += (v1 - v_end[-1]) / (1.1 * u - 0.025)
        times.append(clock)
        v_end.append(v1)
        if k < 3:
            clock += 1.0
            times.append(clock)
            v_end.append(v1)
    assert list(lecture.x) == pytest.approx(times, rel=1e-12)
    assert list(lecture.y) == pytest.approx([v * KMH for v in v_end], rel=1e-12)
    assert lecture.x[-1] == pytest.approx(17.49, abs=0.005)
    assert [v / KMH for v in lecture.y[1::2]] == pytest.approx(
        [8.64, 14.28, 21.90, 27.78], abs=0.005
    )


# ------------------------------------------------------------------ traction diagram


def test_traction_diagram_of_the_lecture_car_by_hand():
    """Leiderman's curve with the seed's a, b, c = 0.91, 0.9, 0.81; the engine from
    the launch speed n_M = 3000 rpm to the rev limit n_E = 5400 rpm."""
    charts, _ = charts_of("lecture")
    traction = charts[1]
    omega_e = 5400.0 * RPM
    m_n = 58800.0 / omega_e  # 103.98 N·m

    def torque(omega: float) -> float:
        x = omega / omega_e
        return m_n * (0.91 + 0.9 * x - 0.81 * x * x)

    r, u_k, eta = 0.45, 4.11, 0.875
    for k, u in enumerate((3.8, 2.3, 1.5, 1.0)):
        gear = series(traction, f"gear {k + 1} ")
        assert len(gear.x) >= 200
        # Ends at the rev limit, M = M_N·(a + b - c) = M_N.
        assert gear.x[-1] == pytest.approx(omega_e * r / (u * u_k) * KMH, rel=1e-12)
        assert gear.y[-1] == pytest.approx(m_n * u * u_k * eta / r, rel=1e-12)
        # Every point: F(v) from the engine speed the road speed gives.
        for v, force in zip(gear.x, gear.y, strict=True):
            omega = max(v / KMH * u * u_k / r, 3000.0 * RPM)  # below: the clutch slips
            assert force == pytest.approx(torque(omega) * u * u_k * eta / r, rel=1e-12)
        start = 0.0 if k == 0 else 3000.0 * RPM * r / (u * u_k) * KMH
        assert gear.x[0] == pytest.approx(start, rel=1e-12)
    resistance = series(traction, "resistance")
    assert resistance.label == "resistance ψ·m·g"  # no [drag] in the lecture case
    assert list(resistance.y) == pytest.approx([0.025 * 1500.0 * 9.81] * len(resistance.y))
    assert [s.label for s in traction.series if s.label.startswith("adhesion")] == []
    assert "force [N]" == traction.y_label and "[km/h]" in traction.x_label


def test_traction_diagram_with_drag_and_adhesion():
    """high_power: R = ψ·m·g + k·v²; rear-drive grip with load transfer,
    N = N_0 + m·a·h/L and a = (φ·N - R)/(δ_0·m) give
    φ·N = φ·(N_0 - s·R)/(1 - s·φ), s = h/(L·δ_0)."""
    charts, _ = charts_of("high_power")
    traction = charts[1]
    m, psi, k = 1650.0, 0.012, 0.5 * 1.225 * 0.32 * 2.1
    resistance = series(traction, "resistance")
    assert resistance.label == "resistance ψ·m·g + k·v²"
    for v, force in zip(resistance.x, resistance.y, strict=True):
        assert force == pytest.approx(psi * m * G0 + k * (v / KMH) ** 2, rel=1e-12)
    grip = series(traction, "adhesion limit")
    n0, s = 0.52 * m * G0, 0.48 / (2.70 * 1.04)
    for v, force in zip(grip.x, grip.y, strict=True):
        r = psi * m * G0 + k * (v / KMH) ** 2
        assert force == pytest.approx(1.0 * (n0 - s * r) / (1.0 - s * 1.0), rel=1e-12)
    # The torque table's corners are nodes of the curves: 650 N·m at 4500 rpm in 1st.
    first = series(traction, "gear 1 ")
    v_4500 = 4500.0 * RPM * 0.34 / (3.82 * 3.42) * KMH
    assert value_at(first, v_4500) == pytest.approx(650.0 * 3.82 * 3.42 * 0.92 / 0.34)
    assert max(first.y) == pytest.approx(650.0 * 3.82 * 3.42 * 0.92 / 0.34)
    # Upshifts (plan) at 7000 rpm, on the gear's curve.
    shifts = series(traction, "upshifts")
    assert shifts.role == "event"
    assert shifts.x[0] == pytest.approx(7000.0 * RPM * 0.34 / (3.82 * 3.42) * KMH, rel=1e-12)
    torque_7000 = 600.0 + (520.0 - 600.0) * (7000.0 - 6000.0) / 1200.0
    assert shifts.y[0] == pytest.approx(torque_7000 * 3.82 * 3.42 * 0.92 / 0.34, rel=1e-12)


def test_truck_has_no_run_but_a_diagram_crossing_at_its_top_speed():
    """No answer: only the traction diagram. In 5th (U = 1, U_K = 6.32) F_t(v) meets
    ψ·m·g + k·v² at the top speed. With Leiderman 1, 1, 1, x = v·U·U_K/(r·ω_E):
    M_N·(1 + p·v - p²·v²)·q = ψ·m·g + k·v², p = U·U_K/(r·ω_E), q = U·U_K·η/r,
    a quadratic (k + M_N·q·p²)·v² - M_N·q·p·v + ψ·m·g - M_N·q = 0."""
    charts, _ = charts_of("truck")
    assert len(charts) == 1
    traction = charts[0]
    omega_e = 3200.0 * RPM
    m_n = 110000.0 / omega_e
    r, u_k, eta, m = 0.476, 6.32, 0.85, 10525.0
    k = 0.5 * 1.225 * 0.9 * 5.5
    p, q = u_k / (r * omega_e), u_k * eta / r
    a2, a1, a0 = k + m_n * q * p * p, -m_n * q * p, 0.02 * m * G0 - m_n * q
    v_top = (-a1 + math.sqrt(a1 * a1 - 4.0 * a2 * a0)) / (2.0 * a2) * KMH
    assert v_top == pytest.approx(87.2596197747297, rel=1e-9)  # the case's hand value
    marks = {m.label: m.value for m in traction.marks}
    assert marks["top speed 87.26 km/h"] == pytest.approx(v_top, rel=1e-6)
    assert marks["target 100 km/h"] == pytest.approx(100.0)
    fifth, resistance = series(traction, "gear 5 "), series(traction, "resistance")
    below, above = v_top * 0.99, v_top * 1.01
    assert value_at(fifth, below) > value_at(resistance, below)
    assert value_at(fifth, above) < value_at(resistance, above)
    assert resistance.x[-1] == pytest.approx(100.0)  # drawn out to the target


def test_steep_hill_every_gear_below_the_resistance():
    """ψ·m·g = 0.5·1120·g = 5492 N; first gear gives at most
    M(3000 rpm)·3.242·3.9·0.9/0.269 = 4946 N: nothing moves, no speed curve."""
    charts, _ = charts_of("steep_hill")
    assert len(charts) == 1
    (traction,) = charts
    resistance = series(traction, "resistance")
    assert min(resistance.y) == pytest.approx(0.5 * 1120.0 * G0)
    gears = [s for s in traction.series if s.label.startswith("gear")]
    assert len(gears) == 4
    assert max(max(g.y) for g in gears) < min(resistance.y)
    assert [s for s in traction.series if s.label.startswith("upshift")] == []
    assert [m.label for m in traction.marks] == ["target 100 km/h"]  # top speed 0: no mark


@pytest.mark.parametrize(
    "path",
    sorted((CASES / "acceleration").glob("*.toml"))
    + sorted((CASES / "extreme").glob("acceleration_*.toml")),
    ids=lambda p: p.stem,
)
def test_every_case_has_labelled_finite_charts(path: Path):
    run = solve_text(read_case(path))
    charts = run.module.charts(run.result)
    assert len(charts) == (2 if run.result.status == "ok" else 1)
    for chart in charts:
        assert "[" in chart.x_label and "[" in chart.y_label  # units
        for s in chart.series:
            assert s.label and len(s.x) == len(s.y) > 0
            assert all(math.isfinite(v) for v in [*s.x, *s.y])
        assert all(math.isfinite(m.value) for m in chart.marks)
