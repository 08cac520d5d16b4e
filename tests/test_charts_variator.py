"""``variator.charts`` (``--plot``): the chart data against values worked out here.

Every expected number is computed in this file from the formulas of PROBLEMS.md §7
(or is an independent value a case file cites), never copied from the program:

* the absorber (8.38) with k_g = c_g + iω·b_g solved by hand as a complex 2×2 system,
  the resonances from ω⁴ - (a + b + d)ω² + ad = 0;
* the clutch's secant and least-squares lines by their integrals;
* the transfer functions (8.46) at the ends and middle of the stroke;
* χ of the VK case (the case file's independent period-map values);
* the anti-resonance design (7f) as a complex 2×2 system written out from its two
  equations, with the tuning c₂' = (zω)²·J₂J₃'/(J₂ + J₃');
* the pendulum's order from the complete elliptic integral, π/(2K(sin(θ/2))).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.conftest import CASES, chart, series


def solved(path: Path) -> tuple[Any, list[Any]]:
    from mdcalc.input.casefile import read_case
    from mdcalc.runs.runner import solve_text

    run = solve_text(read_case(path))
    return run.result, run.module.charts(run.result)


def case_charts(name: str) -> list[Any]:
    return solved(CASES / "variator" / f"{name}.toml")[1]


def written(tmp_path: Path, text: str) -> list[Any]:
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    return solved(path)[1]


def at(x: np.ndarray, y: np.ndarray, where: float) -> float:
    """y at a point of the grid (to round-off)."""
    k = int(np.argmin(np.abs(x - where)))
    assert x[k] == pytest.approx(where, rel=1e-12, abs=1e-12)
    return float(y[k])


def near(x: np.ndarray, y: np.ndarray, where: float) -> tuple[float, float]:
    """The drawn point nearest ``where``: (x, y)."""
    k = int(np.argmin(np.abs(x - where)))
    assert x[k] == pytest.approx(where, rel=1e-2)
    return float(x[k]), float(y[k])


# ------------------------------------------------------------------- 7a: absorber

# seed 000 §8.2: J₁ = 2, c = 800, J₂ = 0.2, M₀ = 100, ω = 20 rad/s
J1, C, J2, M0, OMEGA = 2.0, 800.0, 0.2, 100.0, 20.0


def hand_absorber(w: float, cg: float, bg: float = 0.0) -> tuple[float, float]:
    """|A₁|, |A₂| of J₁φ₁″ + cφ₁ + k(φ₁ - φ₂) = M₀, J₂φ₂″ - k(φ₁ - φ₂) = 0."""
    k = complex(cg, w * bg)
    m = np.array([[C + k - J1 * w * w, -k], [-k, k - J2 * w * w]])
    a1, a2 = np.linalg.solve(m, np.array([M0, 0.0]))
    return abs(a1), abs(a2)


def test_tuned_undamped_absorber_has_a_zero_of_a1_at_the_design_ratio():
    c = chart(case_charts("two_disk_absorber"), "absorber")
    x1, a1 = series(c, "|A₁|")
    x2, a2 = series(c, "|A₂|")
    cg = J2 * OMEGA**2  # (8.39), 80 N·m/rad
    # A₁ = 0 exactly at the design ratio: left out of the log axis, a notch around it
    assert 1.0 not in x1
    assert at(x2, a2, 1.0) == pytest.approx(M0 / cg, rel=1e-12)  # 1.25 rad
    static = M0 / C
    for where in (1.0 - 1e-3, 1.0 + 1e-2, 0.5, 1.5, 2.0):
        ratio, value = near(x1, a1, where)
        want1, want2 = hand_absorber(ratio * OMEGA, cg)
        assert value == pytest.approx(want1, rel=1e-9)
        assert at(x2, a2, ratio) == pytest.approx(want2, rel=1e-9)
    assert at(x1, a1, 1.0 - 1e-4) < 1e-2 * static  # a notch, not a dip
    assert [m.value for m in c.marks if m.axis == "x"] == [1.0]
    assert c.y_log and "[rad]" in c.y_label


def test_peaks_of_the_absorber_curve_sit_at_the_roots_of_delta():
    c = chart(case_charts("two_disk_absorber"), "absorber")
    x, a1 = series(c, "|A₁|")
    # ω⁴ - (a + b + d)ω² + ad = 0 with a = c/J₁ = 400, b = c_g/J₁ = 40, d = c_g/J₂ = 400
    roots = [math.sqrt(420.0 - math.sqrt(420.0**2 - 160000.0)), math.sqrt(420.0 + 128.0624847)]
    step = 2.0 / 600  # the grid: 601 points over 0 … 2ω
    for lo, hi, root in ((0.0, 1.0, roots[0]), (1.0, 2.0, roots[1])):
        inside = (x > lo) & (x < hi)
        peak = x[inside][np.argmax(a1[inside])]
        assert peak == pytest.approx(root / OMEGA, abs=step)


def test_without_the_absorber_the_disk_resonates_at_the_design_ratio():
    c = chart(case_charts("two_disk_absorber"), "absorber")
    x, alone = series(c, "without the absorber")
    assert 1.0 not in x  # c/J₁ = ω²: unbounded, left out
    for where in (0.5, 0.99, 1.5):
        ratio, value = near(x, alone, where)
        assert value == pytest.approx(M0 / abs(C - J1 * (ratio * OMEGA) ** 2), rel=1e-12)


def test_damped_absorber_marks_its_minimum():
    c = chart(case_charts("absorber_damped"), "absorber")
    x, a1 = series(c, "|A₁|")
    (where,), (depth,) = series(c, "damped minimum")
    # cases/variator/absorber_damped.toml: brute-force grid of the complex 2×2 solve
    assert where * OMEGA == pytest.approx(20.0811207, rel=1e-6)
    assert depth == pytest.approx(0.15462957208195743, rel=1e-7)
    near = (x > 0.95) & (x < 1.05)
    assert np.all(a1[near] >= depth * (1.0 - 1e-9))
    assert at(x, a1, 1.0) == pytest.approx(hand_absorber(OMEGA, 80.0, 0.5)[0], rel=1e-9)
    assert "b_g = 0.5" in c.title


def test_detuned_absorber_has_its_zero_at_the_tuning_ratio(tmp_path):
    c = chart(case_charts("absorber_detuned"), "absorber")
    x, a1 = series(c, "|A₁|")
    tuning = 22.0 / 20.0
    assert sorted(m.value for m in c.marks) == pytest.approx([1.0, tuning])
    assert tuning not in x  # the notch itself: 0 or round-off, neither drawable on a log axis
    for ratio in (tuning * (1.0 - 1e-4), tuning * (1.0 + 1e-3)):
        value = at(x, a1, ratio)
        assert value == pytest.approx(hand_absorber(ratio * OMEGA, J2 * 22.0**2)[0], rel=1e-6)
        assert value < 2e-2 * M0 / C
    # (8.38) by hand at ω: 0.21694… (cases/variator/absorber_detuned.toml)
    assert at(x, a1, 1.0) == pytest.approx(0.21694214876033058, rel=1e-12)


def test_absorber_at_a_resonance_still_draws_its_curve_without_that_point():
    charts = case_charts("absorber_resonance")  # no answer: ω on a root of Δ
    assert [c.title.split(":")[0] for c in charts] == ["Anti-resonance absorber (8.38)"]
    x, a1 = series(charts[0], "|A₁|")
    assert 1.0 not in x and len(x) > 500
    assert np.all(np.isfinite(a1))


# ------------------------------------------------------ 7c, 7d: clutch, mechanism


def test_clutch_lines_over_the_vk_working_range():
    c = chart(case_charts("vk_variator"), "loading curve")
    c0, n = 2.785e5 * 9.80665, 2.15
    x1, x2 = (50.0 / c0) ** (1.0 / n), (300.0 / c0) ** (1.0 / n)
    x, m = series(c, "loading curve")
    assert np.allclose(m, c0 * x**n, rtol=1e-9, atol=1e-9)
    xs, ms = series(c, "secant")
    assert ms[-1] / xs[-1] == pytest.approx(300.0 / x2, rel=1e-9)
    # least squares through the origin: ∫ξ·c₀ξⁿ dξ / ∫ξ² dξ over [ξ₁, ξ₂]
    slope = c0 * (x2 ** (n + 2) - x1 ** (n + 2)) / (n + 2) / ((x2**3 - x1**3) / 3.0)
    xl, ml = series(c, "least squares")
    assert ml[-1] / xl[-1] == pytest.approx(slope, rel=1e-9)
    xc, mc = series(c, "chord")  # through both ends of the range, drawn over it
    assert xc[0] == pytest.approx(x1, rel=1e-12)
    assert mc[0] == pytest.approx(50.0, rel=1e-9)
    assert np.interp(x2, xc, mc) == pytest.approx(300.0, rel=1e-6)
    assert sorted(mk.value for mk in c.marks) == pytest.approx([x1, x2], rel=1e-9)


def test_transfer_functions_over_the_vk_stroke():
    c = chart(case_charts("vk_variator"), "transfer functions")
    deg, first = series(c, "Π′")
    _, second = series(c, "Π″")
    _, position = series(c, "Π - φ_c")
    d, i_c = math.pi / 2.0, 1000.0 / 185.0
    b0 = d / (2.0 * i_c * math.sin(d / 2.0))
    a0 = -12.0 / (d * d * i_c) * (d / (2.0 * math.sin(d / 2.0)) - 1.0)
    assert deg[0] == pytest.approx(-45.0) and deg[-1] == pytest.approx(45.0)
    assert first[0] == pytest.approx(a0 * d * d / 4.0 + b0, rel=1e-12)
    assert at(deg, first, 0.0) == pytest.approx(b0, rel=1e-12)
    assert second[0] == pytest.approx(-a0 * d, rel=1e-12)
    assert position[-1] == pytest.approx(a0 * (d / 2) ** 3 / 3.0 + b0 * d / 2, rel=1e-12)
    # the mean of Π′ over the stroke is 1/i_c (Simpson on the drawn points)
    h = math.radians(deg[1] - deg[0])
    simpson = h / 3.0 * (first[0] + first[-1] + 4 * first[1:-1:2].sum() + 2 * first[2:-1:2].sum())
    assert simpson / d == pytest.approx(1.0 / i_c, rel=1e-9)
    assert [mk.value for mk in c.marks] == pytest.approx([185.0 / 1000.0])


# --------------------------------------------------------- 7e, 7f: drive, design


def test_q_over_a_stroke_peaks_at_chi_before_and_after():
    c = chart(case_charts("vk_variator"), "over one stroke")
    _, before = series(c, "before")
    _, after = series(c, "after")
    # cases/variator/vk_variator.toml: independent period maps
    assert before.max() == pytest.approx(21.943320888076293, rel=2e-3)
    assert after.max() == pytest.approx(1.445029805386831, rel=2e-3)
    assert before[0] == pytest.approx(before[-1], rel=1e-6)  # a periodic state
    assert "not resolved" not in c.title


def test_a_stiff_clutch_rings_after_the_jump_and_the_samples_follow_it():
    c = chart(case_charts("drive_stiff"), "over one stroke")
    x, q = series(c, "q/q_c")
    # β/Ω = 10⁴: the ringing lasts about a thousandth of the stroke
    assert q.max() == pytest.approx(1.7782442466224568, rel=1e-3)  # case file, by hand
    assert len(x) < 10_000
    assert "not resolved" not in c.title


DESIGN = """
problem = "variator"
[mechanism]
mechanisms = 4
input_speed_rpm = 1000.0
mean_ratio = 5.0
[drive]
driven_inertia = 0.05
load_torque = 300.0
clutch_stiffness = 1.0e5
clutch_damping = 5.0
ode = false
harmonics = [1]
[antiresonance]
machine_inertia = 1.5
ratio = 2.0
coupling_damping = {b2}
"""


@pytest.mark.parametrize("b2", [0.0, 3.0])
def test_the_clutch_response_before_and_after_the_coupling(tmp_path, b2):
    c = chart(written(tmp_path, DESIGN.format(b2=b2)), "Anti-resonance (7f)")
    x_before, before = series(c, "before")
    x_after, after = series(c, "after")
    j2, j3, c1, b1, i = 0.05, 2.0**2 * 1.5, 1.0e5, 5.0, 2.0
    big_omega = 4 * 1000.0 * 2 * math.pi / 60.0  # zω
    c2 = big_omega**2 * j2 * j3 / (j2 + j3)  # tuned (8.48), reduced
    k2 = lambda nu: complex(c2, nu * i * i * b2)  # noqa: E731
    static = (j2 + j3) / c1
    for where in (1.0 + 1e-2, 0.3, 3.0):
        ratio, _ = near(x_after, after, where)
        nu = ratio * big_omega
        # J₂q₁″ + b₁q₁′ + c₁q₁ - k₂q₂ = J₂u;  J₃'(q₁″ + q₂″) + k₂q₂ = J₃'u
        m = np.array(
            [[c1 - j2 * nu * nu + 1j * nu * b1, -k2(nu)], [-j3 * nu * nu, k2(nu) - j3 * nu * nu]]
        )
        q1 = np.linalg.solve(m, np.array([j2, j3]))[0]
        rigid = (j2 + j3) / (c1 - (j2 + j3) * nu * nu + 1j * nu * b1)
        assert at(x_after, after, ratio) == pytest.approx(abs(q1) / static, rel=1e-9, abs=1e-12)
        assert at(x_before, before, ratio) == pytest.approx(abs(rigid) / static, rel=1e-9)
    if b2 == 0.0:  # the anti-resonance on the fundamental: a notch (0 itself left out)
        assert 1.0 not in x_after
        assert at(x_after, after, 1.0 - 1e-4) < 1e-3
    assert [m.value for m in c.marks] == [1.0]
    assert c.x_log and c.y_log


# ------------------------------------------------------------------ 7g: pendulum


def test_pendulum_backbone_from_the_elliptic_integral():
    from scipy.special import ellipk

    c = chart(case_charts("pendulum"), "pendulum")
    ratio, swing = series(c, "free swing")
    assert (ratio[0], swing[0]) == (1.0, 0.0)
    for k in (30, 90, 180):
        theta = math.radians(swing[k])
        # order of θ″ = -(R/L)ω²·sin θ at amplitude θ over its small-swing order
        assert ratio[k] == pytest.approx(math.pi / (2.0 * ellipk(math.sin(theta / 2) ** 2)))
    (r,), (s,) = series(c, "at θ_max")
    assert s == pytest.approx(math.degrees(0.3))
    assert 4.0 * r == pytest.approx(3.977510455404131, rel=1e-9)  # case file, DOP853
    assert sorted((m.axis, m.value) for m in c.marks) == [
        ("x", 1.0),
        ("y", pytest.approx(math.degrees(0.3))),
    ]


# ------------------------------------------------------------------------ general


def test_a_drive_without_an_answer_draws_nothing():
    assert case_charts("drive_resonance") == []


def test_the_charts_of_each_part_in_the_report_order():
    titles = [c.title.split(":")[0] for c in case_charts("vk_variator")]
    assert titles == [
        "Overrunning clutch",
        "Elementary mechanism (8.46)",
        "Clutch deformation over one stroke, periodic state; χ = max q/q_c (8.47)",
        "Anti-resonance (7f)",
    ]
    for c in case_charts("vk_variator"):
        assert "[" in c.x_label and "[" in c.y_label  # units
