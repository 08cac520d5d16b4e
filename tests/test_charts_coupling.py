"""``coupling.charts`` (``--plot``): the chart data against values worked out here.

Every expected number is computed in this file from the formulas of PROBLEMS.md §5
(or is a hand value a case file cites), never taken from the program:

* φ'' + p·φ' + β²·φ = β²·f(t), β² = c/J, J = J₁J₂/(J₁ + J₂), p = ψ/τ, τ = 2π/β;
* suddenly applied torque: 1 - e^(-pt/2)·(cos β₁t + p/(2β₁)·sin β₁t), β₁ = √(β² - p²/4),
  first peak 1 + exp(-πζ/√(1 - ζ²)) at π/β₁, envelope 1 ± e^(-pt/2); critically damped
  1 - e^(-βt)·(1 + βt); over-damped 1 - (s₂e^(-s₁t) - s₁e^(-s₂t))/(s₂ - s₁), s₁,₂ the
  roots ζβ ∓ β√(ζ² - 1);
* undamped, a piecewise-linear load is a sum of steps 1 - cos βt and ramps
  t - sin(βt)/β started at the knots: the rectangular pulse is 2·sin(βT/2)·sin β(t - T/2)
  after it;
* the response curve (8.28): φ_max·β²/M = 1/√((1 - λ²)² + (γλ)²), γ = p/β, with M
  the combined amplitude |M₁/J₁·e^(iα) + M₂/J₂·e^(iγ)| (8.21).
"""

from __future__ import annotations

import cmath
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.conftest import CASES, chart, series, solved


def case(name: str) -> tuple[Any, Any, list[Any]]:
    folder = "extreme" if name.startswith("coupling_") else "coupling"
    return solved(CASES / folder / f"{name}.toml")


def written(tmp_path: Path, text: str) -> tuple[Any, Any, list[Any]]:
    path = tmp_path / "case.toml"
    path.write_text('problem = "coupling"\n' + text, encoding="utf-8")
    return solved(path)


def marks(c: Any, axis: str) -> dict[str, float]:
    return {m.label: m.value for m in c.marks if m.axis == axis}


def finite(charts: list[Any]) -> None:
    for c in charts:
        for s in c.series:
            assert len(s.x) == len(s.y) > 0, s.label
            assert all(math.isfinite(v) for v in [*s.x, *s.y]), s.label
        for m in c.marks:
            assert math.isfinite(m.value), m.label


# Example 8.1 by hand: c = 52.5 N·m/deg, ψ = 0.63, J₁ = 10, J₂ = 4 kg·m².
C81 = 52.5 * 180.0 / math.pi
J81 = 10.0 * 4.0 / 14.0
BETA81 = math.sqrt(C81 / J81)
TAU81 = 2.0 * math.pi / BETA81
P81 = 0.63 / TAU81
ZETA81 = P81 / (2.0 * BETA81)


def underdamped_step(t: np.ndarray, beta: float, p: float) -> np.ndarray:
    b1 = math.sqrt(beta * beta - p * p / 4.0)
    return 1.0 - np.exp(-p * t / 2.0) * (np.cos(b1 * t) + p / (2.0 * b1) * np.sin(b1 * t))


# ------------------------------------------------------------- suddenly applied


def test_step_response_of_example_8_1_follows_the_closed_form():
    _, _, charts = case("example_8_1")
    assert len(charts) == 1
    c = chart(charts, "Suddenly applied torque")
    t, y = series(c, "φ/φ_st = 1 - e^(-pt/2)")
    assert t[0] == 0.0 and np.all(np.diff(t) > 0.0) and len(t) >= 300
    assert y == pytest.approx(underdamped_step(t, BETA81, P81), abs=1e-12)
    for when in (0.01, 0.05, TAU81 / 2.0, TAU81, 0.3):  # on the grid or between points
        assert np.interp(when, t, y) == pytest.approx(
            float(underdamped_step(np.array([when]), BETA81, P81)[0]), abs=2e-3
        )
    exact = 1.0 + math.exp(-math.pi * ZETA81 / math.sqrt(1.0 - ZETA81**2))
    assert y.max() == pytest.approx(exact, rel=1e-12)
    assert y.max() == pytest.approx(1.854, abs=5e-4)  # PROBLEMS.md §5 reference
    assert t[-1] >= 3.0 * TAU81  # several swings of the decaying envelope


def test_step_peak_envelope_and_marks_of_example_8_1():
    _, report, charts = case("example_8_1")
    c = charts[0]
    tp, yp = series(c, "first peak")
    b1 = math.sqrt(BETA81**2 - P81**2 / 4.0)
    assert tp.tolist() == pytest.approx([math.pi / b1], rel=1e-12)
    assert yp.tolist() == pytest.approx([1.8541074238678923], rel=1e-12)  # the case file
    te, ye = series(c, "envelope 1 ± e^(-pt/2)")
    (lower,) = [s for s in c.series if s.role == "envelope" and not s.label]
    assert list(lower.x) == te.tolist()
    assert ye == pytest.approx(1.0 + np.exp(-P81 * te / 2.0), rel=1e-12)
    assert lower.y == pytest.approx(1.0 - np.exp(-P81 * te / 2.0), abs=1e-12)
    t, y = series(c, "φ/φ_st = 1 - e^(-pt/2)")
    # The lecture's envelope passes through the peaks (it is not a bound: the swing
    # is e^(-pt/2)/√(1 - ζ²) between them, and the rise starts below 1 - e^(-pt/2)).
    k = np.flatnonzero((np.abs(y[1:-1] - 1.0) >= np.abs(y[:-2] - 1.0))
                       & (np.abs(y[1:-1] - 1.0) >= np.abs(y[2:] - 1.0))) + 1  # fmt: skip
    assert len(k) >= 7  # the swings of 4·τ
    assert np.abs(y[k] - 1.0) == pytest.approx(np.exp(-P81 * t[k] / 2.0), abs=2e-3)
    assert np.abs(y - 1.0).max() <= 1.0 / math.sqrt(1.0 - ZETA81**2)
    tr, yr = series(c, "envelope at τ, 1.5·τ")
    assert tr.tolist() == pytest.approx([TAU81, 1.5 * TAU81], rel=1e-12)
    assert yr.tolist() == pytest.approx([1.7297888742690568, 1.6234417141174893], rel=1e-12)
    assert marks(c, "y") == {"static, φ/φ_st = 1": 1.0}
    # the chart shows what the report prints
    results = {q.key: q.value for s in report.sections for q in getattr(s, "items", [])}
    assert yp[0] == results["step_dynamic_factor"] and tp[0] == results["step_peak_time"]


def test_undamped_step_swings_between_0_and_2():
    _, _, charts = case("undamped")
    c = chart(charts, "Suddenly applied torque")
    t, y = series(c, "φ/φ_st = 1 - e^(-pt/2)")
    assert y == pytest.approx(1.0 - np.cos(BETA81 * t), abs=1e-12)
    assert y.max() == 2.0 or y.max() == pytest.approx(2.0, rel=1e-15)
    assert series(c, "first peak")[1].tolist() == [2.0]
    _, ye = series(c, "envelope 1 ±")
    assert set(ye.tolist()) == {2.0}  # the upper edge; the lower, unlabelled, at 0
    (lower,) = [s for s in c.series if s.role == "envelope" and not s.label]
    assert set(lower.y) == {0.0}
    assert "undamped" in c.title


def test_overdamped_step_rises_to_1_without_overshoot():
    _, _, charts = case("overdamped")
    c = charts[0]
    assert "over-damped" in c.title and "factor 1" in c.title
    assert [s.label for s in c.series] == ["φ/φ_st, closed form (no overshoot)"]
    t, y = series(c, "φ/φ_st")
    zeta, beta = 3.0, BETA81
    s1 = beta * (zeta - math.sqrt(zeta * zeta - 1.0))
    s2 = beta * (zeta + math.sqrt(zeta * zeta - 1.0))
    expected = 1.0 - (s2 * np.exp(-s1 * t) - s1 * np.exp(-s2 * t)) / (s2 - s1)
    assert y == pytest.approx(expected, rel=1e-7, abs=1e-9)  # ζ = 3 to 1e-9 in the case
    assert np.all(np.diff(y) >= -1e-15) and y.max() < 1.0
    assert y[-1] > 0.99  # drawn until the slow decay has nearly settled


def test_critically_damped_step(tmp_path):
    beta = 30.0  # J₁ = J₂ = 2: J = 1, c = 900; α = 2βJ = 60
    _, _, charts = written(
        tmp_path,
        "[coupling]\ndriving_inertia = 2.0\ndriven_inertia = 2.0\nstiffness = 900.0\n"
        "damping = 60.0\n[step]\n",
    )
    finite(charts)
    c = charts[0]
    assert "critically damped" in c.title
    t, y = series(c, "φ/φ_st")
    assert y == pytest.approx(1.0 - np.exp(-beta * t) * (1.0 + beta * t), abs=1e-12)
    assert y.max() < 1.0 and y[-1] > 0.98


# ------------------------------------------------------------------ transients


def test_undamped_rectangular_pulse_after_it_is_2_sin_half_beta_t():
    result, _, charts = case("undamped")
    c = chart(charts, "Rectangular pulse")
    t, y = series(c, "φ/φ_st, exact Duhamel")
    duration = 0.05
    during, after = t <= duration, t >= duration
    assert y[during] == pytest.approx(1.0 - np.cos(BETA81 * t[during]), abs=1e-10)
    amplitude = 2.0 * abs(math.sin(BETA81 * duration / 2.0))
    assert amplitude == pytest.approx(1.4501948049481754, rel=1e-12)  # the case file
    assert y[after] == pytest.approx(
        amplitude * np.sin(BETA81 * (t[after] - duration / 2.0)), abs=1e-10
    )
    assert np.abs(y[after]).max() == pytest.approx(amplitude, rel=1e-10)
    assert t[-1] == pytest.approx(duration + 2.0 * TAU81, rel=1e-12)  # the peak search's
    tp, yp = series(c, "peak")
    transient, _, (factor, when) = result.transient_methods[0]
    assert transient.key == "pulse" and tp.tolist() == [when]
    assert abs(yp[0]) == factor == pytest.approx(amplitude, rel=1e-10)
    assert yp[0] == pytest.approx(amplitude * math.sin(BETA81 * (when - duration / 2.0)))
    tl, load = series(c, "torque M(t)/M_max")
    assert list(zip(tl, load, strict=True)) == [
        (0.0, 0.0),
        (0.0, 1.0),
        (duration, 1.0),
        (duration, 0.0),
        (pytest.approx(duration + 2.0 * TAU81), 0.0),
    ]


def test_undamped_ramp_then_hold():
    _, _, charts = case("undamped")
    c = chart(charts, "Ramp to 500")
    t, y = series(c, "φ/φ_st, exact Duhamel")
    rise, b = 0.3, BETA81
    expected = np.where(
        t <= rise,
        (t - np.sin(b * t) / b) / rise,
        1.0 - (np.sin(b * t) - np.sin(b * (t - rise))) / (b * rise),
    )
    assert y == pytest.approx(expected, abs=1e-10)
    peak = 1.0 + abs(math.sin(b * rise / 2.0)) / (b * rise / 2.0)
    assert peak == pytest.approx(1.2030104560268964, rel=1e-12)  # the case file
    assert series(c, "peak")[1].tolist() == pytest.approx([peak], rel=1e-10)
    assert y.max() == pytest.approx(peak, rel=1e-10)


def test_a_torque_table_with_reversal_by_superposition(tmp_path):
    """Undamped: steps 1 - cos β(t - tₖ) and ramps (t - tₖ) - sin β(t - tₖ)/β."""
    times, torques = [0.02, 0.06, 0.1, 0.1], [300.0, -500.0, -500.0, 0.0]
    result, _, charts = written(
        tmp_path,
        "[coupling]\ndriving_inertia = 2.0\ndriven_inertia = 2.0\nstiffness = 900.0\n"
        f"[torque_table]\ntime = {times}\ntorque = {torques}\nhorizon = 0.5\n",
    )
    finite(charts)
    beta = 30.0
    c = chart(charts, "Tabulated torque")
    t, y = series(c, "φ/φ_st, exact Duhamel")
    knots = [(0.0, 0.0), *zip(times, (m / 500.0 for m in torques), strict=True)]
    expected = np.zeros_like(t)
    slope = 0.0
    for (t0, f0), (t1, f1) in zip(knots, [*knots[1:], (math.inf, knots[-1][1])], strict=True):
        lag = np.clip(t - t0, 0.0, None)
        new = 0.0 if t1 == math.inf or t1 == t0 else (f1 - f0) / (t1 - t0)
        expected += (new - slope) * (lag - np.sin(beta * lag) / beta)
        slope = new
        if t1 == t0:  # a jump
            expected += (f1 - f0) * (1.0 - np.cos(beta * lag))
    assert y == pytest.approx(expected, abs=1e-9)
    tp, yp = series(c, "peak")
    factor = result.transient_methods[0][2][0]
    assert abs(yp[0]) == factor == pytest.approx(np.abs(y).max(), rel=1e-12)
    assert yp[0] < 0.0  # the reversal swings furthest, and the point is where it is
    assert t[-1] == 0.5


def test_a_stiff_pulse_is_thinned_to_a_band():
    from mdcalc.problems.coupling.charts import CHART_MAX_POINTS

    _, _, charts = case("stiff")
    c = charts[0]
    t, y = series(c, "φ/φ_st, exact Duhamel")
    assert len(t) <= CHART_MAX_POINTS + 2 and np.all(np.diff(t) >= 0.0)
    during = t <= 0.05
    assert y[during].max() == pytest.approx(2.0, rel=1e-9)  # T ≥ π/β: 2 (7.96)
    assert y[during].min() == pytest.approx(0.0, abs=1e-6)
    assert series(c, "peak")[1].tolist() == pytest.approx([2.0], rel=1e-9)


def test_heavily_damped_pulse_peak_is_the_case_files():
    _, _, charts = case("coupling_heavily_damped_pulse")
    c = charts[0]
    tp, yp = series(c, "peak")
    assert tp.tolist() == pytest.approx([0.30081766773317637], rel=1e-8)
    assert yp.tolist() == pytest.approx([0.08605592747015965], rel=1e-9)
    _, y = series(c, "φ/φ_st, exact Duhamel")
    assert y.max() == pytest.approx(yp[0], rel=1e-12) and y.min() >= 0.0


# -------------------------------------------------------------------- harmonic


def combined(m1: float, j1: float, a: float, m2: float, j2: float, g: float) -> float:
    return abs(
        m1 / j1 * cmath.exp(1j * math.radians(a)) + m2 / j2 * cmath.exp(1j * math.radians(g))
    )


def test_harmonic_response_curve_is_8_28():
    _, _, charts = case("harmonic")
    assert len(charts) == 1
    c = charts[0]
    lam, y = series(c, "φ_max(λ)")
    m = combined(200.0, 10.0, 0.0, 100.0, 4.0, 60.0)
    assert m == pytest.approx(39.05124837953327, rel=1e-12)  # the case file
    gamma = P81 / BETA81
    assert len(lam) >= 300 and lam[0] == 0.0 and lam[-1] == pytest.approx(3.0)
    assert y * BETA81**2 / m == pytest.approx(
        1.0 / np.sqrt((1.0 - lam**2) ** 2 + (gamma * lam) ** 2), rel=1e-12
    )
    assert not c.y_log and not c.x_log
    own = 30.0 / BETA81
    lp, yp = series(c, "this case")
    assert lp.tolist() == pytest.approx([own], rel=1e-15)
    assert yp.tolist() == pytest.approx([0.2153719532152294], rel=1e-12)  # the case file
    assert own in lam.tolist()  # the curve passes through the case's point
    ratio = math.sqrt(1.0 - gamma**2 / 2.0)
    assert ratio == pytest.approx(0.9974834348381654, rel=1e-12)
    lr, yr = series(c, "resonance peak")
    assert lr.tolist() == pytest.approx([ratio], rel=1e-12)
    assert yr.tolist() == pytest.approx([0.37039978437071447], rel=1e-12)
    assert y.max() == pytest.approx(yr[0], rel=1e-12)
    x_marks = marks(c, "x")
    assert x_marks["resonance λ = √(1 - γ²/2) = 0.9975"] == pytest.approx(ratio, rel=1e-12)
    assert x_marks["advice: λ > 1.5"] == 1.5
    assert list(marks(c, "y").values()) == pytest.approx([m / BETA81**2], rel=1e-12)


def test_undamped_resonance_is_clipped_and_marked_unbounded():
    result, _, charts = case("resonance_undamped")
    assert result.status == "no-answer"
    finite(charts)
    assert len(charts) == 1
    c = charts[0]
    lam, y = series(c, "φ_max(λ)")
    static = (100.0 / 2.0) / 900.0  # M/J₁ over β²
    assert y.max() == pytest.approx(100.0 * static, rel=1e-12)
    assert y[lam == 1.0].tolist() == [pytest.approx(100.0 * static)]
    away = np.abs(1.0 - lam**2) > 0.02
    assert y[away] == pytest.approx(static / np.abs(1.0 - lam[away] ** 2), rel=1e-12)
    assert c.y_log
    assert marks(c, "x")["this case: λ = 1, unbounded"] == 1.0
    assert not [s for s in c.series if s.label.startswith("this case")]


def test_undamped_near_resonance_keeps_the_case_point_on_the_curve(tmp_path):
    speed = 30.0 * (1.0 + 1e-6)  # 5·10⁵ times static: above the clip
    _, _, charts = written(
        tmp_path,
        "[coupling]\ndriving_inertia = 2.0\ndriven_inertia = 2.0\nstiffness = 900.0\n"
        f"[harmonic]\ndriving_torque = 100.0\nspeed = {speed!r}\n",
    )
    finite(charts)
    lam, y = series(charts[0], "φ_max(λ)")
    lp, yp = series(charts[0], "this case")
    expected = (50.0 / 900.0) / abs(1.0 - (speed / 30.0) ** 2)
    assert yp.tolist() == pytest.approx([expected], rel=1e-6)
    assert y.max() == yp[0] and y[lam == lp[0]].tolist() == [yp[0]]


def test_rigid_driver_near_undamped_curve_on_log_axes():
    _, _, charts = case("coupling_rigid_driver")
    finite(charts)
    c = chart(charts, "Steady twist")
    lam, y = series(c, "φ_max(λ)")
    gamma = 2.0 * 1.0e-6 / (2.0 * math.pi)  # p = 2δ/τ, γ = p/β = δ/π
    m = 1.0  # M₂/J₂ alone
    assert y * 100.0**2 / m == pytest.approx(
        1.0 / np.sqrt((1.0 - lam**2) ** 2 + (gamma * lam) ** 2), rel=1e-6
    )
    assert c.y_log
    assert series(c, "resonance peak")[1].tolist() == pytest.approx([314.1592653589833], rel=5e-9)


def test_a_high_speed_case_gets_a_log_ratio_axis(tmp_path):
    _, _, charts = written(
        tmp_path,
        "[coupling]\ndriving_inertia = 2.0\ndriven_inertia = 2.0\nstiffness = 900.0\n"
        "log_decrement = 0.1\n[harmonic]\ndriving_torque = 100.0\nspeed = 600.0\n",
    )
    finite(charts)
    c = charts[0]
    assert c.x_log
    lam, y = series(c, "φ_max(λ)")
    assert lam.min() > 0.0 and lam.max() >= 3.0 * 20.0 - 1e-9 and 20.0 in lam.tolist()
    gamma = 2.0 * 0.1 / (2.0 * math.pi)
    assert y * 900.0 / 50.0 == pytest.approx(
        1.0 / np.sqrt((1.0 - lam**2) ** 2 + (gamma * lam) ** 2), rel=1e-12
    )


def test_charts_follow_the_report_order_and_a_heavily_damped_harmonic(tmp_path):
    # γ² ≥ 2: no resonance peak; the curve falls from the static twist.
    _, _, charts = written(
        tmp_path,
        "[coupling]\ndriving_inertia = 2.0\ndriven_inertia = 2.0\nstiffness = 900.0\n"
        "damping = 60.0\n[step]\n[harmonic]\ndriving_torque = 100.0\nspeed = 15.0\n"
        "[pulse]\ntorque = 10.0\nduration = 0.1\n[ramp]\ntorque = 10.0\nrise_time = 0.1\n",
    )
    finite(charts)
    assert [c.title.split(" ")[0] for c in charts] == ["Suddenly", "Steady", "Rectangular", "Ramp"]
    c = charts[1]
    assert not [s for s in c.series if s.label.startswith("resonance")]
    lam, y = series(c, "φ_max(λ)")
    assert np.all(np.diff(y) < 0.0) and y[0] == pytest.approx(50.0 / 900.0, rel=1e-12)


# ------------------------------------------------------------------- hygiene


def test_charts_print_nothing_and_import_neither_numpy_nor_matplotlib(capsys):
    case("undamped")
    assert capsys.readouterr() == ("", "")
    code = (
        "import sys, mdcalc.problems.coupling; print('numpy' in sys.modules)\n"
        "from mdcalc.input.casefile import read_case\n"
        "from pathlib import Path\nfrom mdcalc.runs.runner import solve_text\n"
        f"run = solve_text(read_case(Path({str(CASES / 'coupling' / 'harmonic.toml')!r})))\n"
        "run.module.charts(run.result); print('matplotlib' in sys.modules)"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.stdout.split() == ["False", "False"], done.stderr
