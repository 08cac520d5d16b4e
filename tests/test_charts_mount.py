"""``mount.charts`` (``--plot``): the chart data against values worked out here.

Every expected number is computed in this file from the formulas of PROBLEMS.md §4
(or is a hand value a case file cites), never copied from the program:

* M·x″ + c_d·x′ + c·x = m·r·ω²·(cos ωt + λ·cos 2ωt), c = G/f, c_d = 2ζ·√(c·M): each
  harmonic's amplitude F/|c - M·(kω)² + i·c_d·kω| with F = m·r·ω² and λ·m·r·ω²;
* undamped, the two amplitudes are real, so the peak of X₁·cos θ + X₂·cos 2θ is at
  θ = 0, π or cos θ = -X₁/(4X₂) (the derivative -sin θ·(X₁ + 4X₂·cos θ));
  damped, by brute force over a fine grid of crank angles;
* the transmissibility √(1 + (2ζr)²)/√((1 - r²)² + (2ζr)²), 1 at r = √2 for any ζ;
* undamped, a target T is met at (ω/β)² = 1 + 1/T.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.conftest import CASES, chart, series, solved


def case(name: str) -> tuple[Any, Any, list[Any]]:
    folder = "extreme" if name.startswith("mount_") else "mount"
    return solved(CASES / folder / f"{name}.toml")


def written(tmp_path: Path, text: str) -> tuple[Any, Any, list[Any]]:
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    return solved(path)


def at(x: np.ndarray, y: np.ndarray, where: float) -> float:
    """y at a point of the grid (it must be one, to round-off)."""
    k = int(np.argmin(np.abs(x - where)))
    assert x[k] == pytest.approx(where, rel=1e-14, abs=1e-300)
    return float(y[k])


# Example 9.1 by hand: G = 10 000 N, f = 10 mm, piston 100 N, r = 50 mm, λ = 1/5.
G9, F9, W9, R9, L9, GRAV = 10000.0, 0.010, 100.0, 0.050, 0.2, 9.81
M9, m9, C9 = G9 / GRAV, W9 / GRAV, G9 / F9
BETA9 = math.sqrt(GRAV / F9)


def undamped_amplitudes(r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Signed X₁, X₂ [m] of example 9.1 at crank speed ω = r·β."""
    w = r * BETA9
    force = m9 * R9 * w**2
    return force / (C9 - M9 * w**2), L9 * force / (C9 - 4.0 * M9 * w**2)


def undamped_peak(x1: float, x2: float) -> float:
    candidates = [abs(x1 + x2), abs(-x1 + x2)]
    if x2 != 0.0 and abs(x1 / (4.0 * x2)) <= 1.0:
        c = -x1 / (4.0 * x2)
        candidates.append(abs(x1 * c + x2 * (2.0 * c * c - 1.0)))
    return max(candidates)


def transmissibility(r: np.ndarray | float, zeta: float) -> Any:
    return np.sqrt(1.0 + (2.0 * zeta * r) ** 2) / np.sqrt(
        (1.0 - r * r) ** 2 + (2.0 * zeta * r) ** 2
    )


# ------------------------------------------------------------------ amplitudes


def test_undamped_amplitudes_follow_the_hand_formulas():
    _, _, charts = case("example_9_1")
    c = chart(charts, "amplitude")
    x, a1 = series(c, "|A₁|")
    _, a2 = series(c, "|A₂|")
    _, peak = series(c, "peak")
    away = (np.abs(x - 1.0) > 0.02) & (np.abs(x - 0.5) > 0.02)
    assert away.sum() > 500
    x1, x2 = undamped_amplitudes(x[away])
    np.testing.assert_allclose(a1[away], 1e3 * np.abs(x1), rtol=1e-9)
    np.testing.assert_allclose(a2[away], 1e3 * np.abs(x2), rtol=1e-9)
    hand = [undamped_peak(p, q) for p, q in zip(x1, x2, strict=True)]
    np.testing.assert_allclose(peak[away], 1e3 * np.asarray(hand), rtol=1e-9)
    # spot values: F/(c·|1 - r²|) with F = m·r·(rβ)² at r = 2 and 1/4
    for r in (2.0, 0.25):
        k = int(np.argmin(np.abs(x - r)))
        w = x[k] * BETA9
        assert a1[k] == pytest.approx(1e3 * m9 * R9 * w * w / (C9 * abs(1 - x[k] ** 2)), rel=1e-9)


def test_damped_amplitudes_and_peak_by_brute_force():
    _, _, charts = case("resonance_damped")  # M = 1000, c = 9e5, ζ = 0.05, m = 10, r = 0.05
    m_, c_, zeta, mp, rc, lam = 1000.0, 9.0e5, 0.05, 10.0, 0.05, 0.25
    beta, cd = math.sqrt(c_ / m_), 2.0 * zeta * math.sqrt(c_ * m_)
    c = chart(charts, "amplitude")
    x, a1 = series(c, "|A₁|")
    _, a2 = series(c, "|A₂|")
    _, peak = series(c, "peak")
    theta = np.linspace(0.0, 2.0 * math.pi, 400001)
    for k in range(0, len(x), 37):
        w = x[k] * beta
        force = mp * rc * w * w
        x1 = force / complex(c_ - m_ * w * w, cd * w)
        x2 = lam * force / complex(c_ - 4.0 * m_ * w * w, 2.0 * cd * w)
        assert a1[k] == pytest.approx(1e3 * abs(x1), rel=1e-9)
        assert a2[k] == pytest.approx(1e3 * abs(x2), rel=1e-9)
        brute = np.max(np.abs((x1 * np.exp(1j * theta) + x2 * np.exp(2j * theta)).real))
        assert peak[k] == pytest.approx(1e3 * brute, rel=1e-9)
    # at resonance, |A₁| = F/(2ζ·c) = 10·0.05·900/(0.1·9e5) = 5 mm (the case file's hand value)
    assert at(x, a1, 1.0) == pytest.approx(5.0, rel=1e-12)


@pytest.mark.parametrize(
    "name",
    [
        "example_9_1",
        "resonance_damped",
        "stiff",
        "isolation",
        "mount_high_speed_limit",
        "mount_near_resonance_undamped",
        "mount_overdamped_resonance",
    ],
)
def test_the_curves_pass_through_the_reported_values(name):
    _, report, charts = case(name)
    results = report.results()
    ratio = results["frequency_ratio"].value
    c = chart(charts, "amplitude")
    wanted = {
        "peak": results["peak_displacement"].value,
        "|A₁|": results["amplitude_1"].value,
        "|A₂|": results["amplitude_2"].value,
    }
    for label, value in wanted.items():
        x, y = series(c, label)
        assert at(x, y, ratio) == pytest.approx(1e3 * value, rel=1e-12)
    x, y = series(c, "this case")
    assert list(x) == [ratio] * 3
    np.testing.assert_allclose(y, [1e3 * v for v in wanted.values()], rtol=1e-15)
    if "transmissibility_1" in results:
        t = chart(charts, "transmissibility")
        for order in (1, 2):
            x, y = series(t, f"{order}{'st' if order == 1 else 'nd'} harmonic")
            value = results[f"transmissibility_{order}"].value
            assert at(x, y, ratio) == pytest.approx(value, rel=1e-12)
        x, y = series(t, "this case")
        assert list(x) == [ratio] * 2


def test_hand_values_of_the_case_files_on_the_curves():
    # example 9.1: |A₁| = 0.523 mm, |A₂| = 0.0253 mm at ω/β = 150/√981 (PROBLEMS.md §4)
    _, _, charts = case("example_9_1")
    c = chart(charts, "amplitude")
    ratio = 150.0 / BETA9
    x1, x2 = undamped_amplitudes(np.array([ratio]))
    x, y = series(c, "|A₁|")
    assert at(x, y, ratio) == pytest.approx(1e3 * abs(x1[0]), rel=1e-12)
    assert at(x, y, ratio) == pytest.approx(0.523, abs=5e-4)
    x, y = series(c, "|A₂|")
    assert at(x, y, ratio) == pytest.approx(0.0253, abs=5e-5)
    x, y = series(c, "peak")
    assert at(x, y, ratio) == pytest.approx(1e3 * (abs(x1[0]) + abs(x2[0])), rel=1e-12)


def test_marks_of_the_amplitude_chart():
    _, _, charts = case("example_9_1")
    c = chart(charts, "amplitude")
    assert "β = 31.32 rad/s" in c.title
    assert sorted(m.value for m in c.marks if m.axis == "x") == [0.5, 1.0]
    (limit,) = [m for m in c.marks if m.axis == "y"]
    assert limit.value == pytest.approx(1e3 * W9 * R9 / G9, rel=1e-12)  # m·r/M = 0.5 mm
    assert "m·r/M" in limit.label
    assert c.y_log and not c.x_log


def test_an_undamped_resonance_is_clipped_finite():
    _, _, charts = case("example_9_1")
    c = chart(charts, "amplitude")
    ceiling = 100.0 * 1e3 * W9 * R9 / G9  # 100·m·r/M in mm
    for label in ("peak", "|A₁|", "|A₂|"):
        x, y = series(c, label)
        assert np.all(np.isfinite(y)) and np.all(y > 0.0)
        assert y.max() == pytest.approx(ceiling, rel=1e-12)
    x, y = series(c, "|A₁|")
    assert at(x, y, 1.0) == pytest.approx(ceiling, rel=1e-12)
    x, y = series(c, "|A₂|")
    assert at(x, y, 0.5) == pytest.approx(ceiling, rel=1e-12)
    assert "clipped" in c.title


@pytest.mark.parametrize(
    ("name", "ratio"), [("resonance_undamped", 1.0), ("resonance_second_undamped", 0.5)]
)
def test_no_answer_cases_still_draw_the_curves(name, ratio):
    result, _, charts = case(name)
    assert result.status == "no-answer"
    (c,) = charts
    assert not [s for s in c.series if s.label.startswith("this case")]
    (own,) = [m for m in c.marks if "unbounded" in m.label]
    assert own.axis == "x" and own.value == pytest.approx(ratio, rel=1e-15)
    for s in c.series:
        assert all(math.isfinite(v) for v in s.y)


def test_the_ratio_axis_covers_the_case():
    _, _, charts = case("example_9_1")
    x, _ = series(chart(charts, "amplitude"), "peak")
    assert x[0] <= 0.1 and x[-1] >= 3.0 and x[-1] > 150.0 / BETA9
    _, _, charts = case("stiff")  # ω/β = 100/√(1e12/1000) = 0.00316: log axis
    c = chart(charts, "amplitude")
    x, _ = series(c, "peak")
    assert c.x_log and x[0] < 100.0 / 31622.776601683792 and x[-1] >= 3.0
    _, _, charts = case("mount_high_speed_limit")  # ω/β = 1e4
    c = chart(charts, "amplitude")
    x, y = series(c, "|A₁|")
    assert c.x_log and x[0] < 0.5 and x[-1] > 1e4
    # far above resonance |A₁| → m·r/M = 10·0.05/1000 = 0.5 mm
    assert y[-1] == pytest.approx(0.5, rel=1e-6)


# ------------------------------------------------------------ transmissibility


def test_no_transmissibility_chart_without_damping_or_target():
    for name in ("example_9_1", "stiff", "mount_high_speed_limit"):
        _, _, charts = case(name)
        assert len(charts) == 1, name


def test_damped_transmissibility_follows_the_hand_formula():
    _, _, charts = case("resonance_damped")
    assert len(charts) == 2
    t = chart(charts, "transmissibility")
    x, t1 = series(t, "1st harmonic")
    _, t2 = series(t, "2nd harmonic")
    np.testing.assert_allclose(t1, transmissibility(x, 0.05), rtol=1e-9)
    np.testing.assert_allclose(t2, transmissibility(2.0 * x, 0.05), rtol=1e-9)
    # the case file's hand values at ω = β: √(1 + (2ζ)²)/(2ζ) and √(1 + (4ζ)²)/√(9 + (4ζ)²)
    assert at(x, t1, 1.0) == pytest.approx(math.sqrt(1.01) / 0.1, rel=1e-12)
    assert at(x, t2, 1.0) == pytest.approx(math.sqrt(1.04) / math.sqrt(9.04), rel=1e-12)
    values = sorted(m.value for m in t.marks if m.axis == "x")
    assert values == pytest.approx([math.sqrt(0.5), math.sqrt(2.0)], rel=1e-15)
    assert not [m for m in t.marks if m.axis == "y"]  # no target without [isolation]
    assert t.y_log


MOUNT = """
problem = "mount"
[engine]
mass = 1000.0
[mounts]
stiffness = 9.0e5
damping_ratio = {zeta}
[crank]
piston_mass = 10.0
radius = 0.05
rod_ratio = 0.25
speed = {speed!r}
"""


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.3, 1.0, 10.0])
def test_transmissibility_is_one_at_root_two_for_any_damping(tmp_path, zeta):
    beta = 30.0  # √(9e5/1000)
    _, _, charts = written(tmp_path, MOUNT.format(zeta=zeta, speed=beta * math.sqrt(2.0)))
    t = chart(charts, "transmissibility")
    x, t1 = series(t, "1st harmonic")
    assert at(x, t1, math.sqrt(2.0)) == pytest.approx(1.0, rel=1e-12)
    # the second harmonic passes T = 1 at ω/β = √2/2
    _, _, charts = written(tmp_path, MOUNT.format(zeta=zeta, speed=beta / math.sqrt(2.0)))
    x, t2 = series(chart(charts, "transmissibility"), "2nd harmonic")
    assert at(x, t2, 1.0 / math.sqrt(2.0)) == pytest.approx(1.0, rel=1e-12)


def test_overdamped_transmissibility_is_near_one_on_a_linear_axis():
    _, _, charts = case("mount_overdamped_resonance")
    t = chart(charts, "transmissibility")
    x, t1 = series(t, "1st harmonic")
    np.testing.assert_allclose(t1, transmissibility(x, 10.0), rtol=1e-9)
    # the case file: √401/20 at r = 1
    assert at(x, t1, 1.0) == pytest.approx(math.sqrt(401.0) / 20.0, rel=1e-12)
    assert not t.y_log


def test_isolation_target_undamped():
    _, _, charts = case("isolation")  # T = 0.05, ζ = 0
    t = chart(charts, "transmissibility")
    x, t1 = series(t, "1st harmonic")
    away = np.abs(x - 1.0) > 0.02
    np.testing.assert_allclose(t1[away], 1.0 / np.abs(1.0 - x[away] ** 2), rtol=1e-9)
    assert np.all(np.isfinite(t1)) and t1.max() == pytest.approx(100.0, rel=1e-12)
    (target,) = [m for m in t.marks if m.axis == "y"]
    assert target.value == 0.05
    x, y = series(t, "target met")
    needed = math.sqrt(1.0 + 1.0 / 0.05)  # u = 1 + 1/T
    assert x[0] == pytest.approx(needed, rel=1e-12) and y[0] == 0.05
    assert 1.0 / (needed**2 - 1.0) == pytest.approx(0.05, rel=1e-12)  # on the curve
    stiffness = M9 * 150.0**2 / needed**2  # the case file: 1 092 180 N/m
    assert stiffness == pytest.approx(1092179.99126256, rel=1e-12)
    assert f"{stiffness:.4g}" in series_label(t, "target met")


def series_label(c: Any, start: str) -> str:
    (label,) = [s.label for s in c.series if s.label.startswith(start)]
    return label


def test_isolation_target_damped_lies_on_the_curve(tmp_path):
    text = MOUNT.format(zeta=0.1, speed=150.0) + "[isolation]\ntransmissibility = 0.02\n"
    _, _, charts = written(tmp_path, text)
    t = chart(charts, "transmissibility")
    x, y = series(t, "target met")
    assert y[0] == 0.02
    assert transmissibility(x[0], 0.1) == pytest.approx(0.02, rel=1e-10)
    assert x[0] > math.sqrt(2.0)  # the isolating root
    grid, _ = series(t, "1st harmonic")
    assert grid[0] < x[0] < grid[-1]


def test_isolation_without_damping_ratio_draws_the_target(tmp_path):
    text = MOUNT.replace("damping_ratio = {zeta}\n", "").format(speed=150.0)
    _, _, charts = written(tmp_path, text + "[isolation]\ntransmissibility = 0.1\n")
    t = chart(charts, "transmissibility")
    x, _ = series(t, "target met")
    assert x[0] == pytest.approx(math.sqrt(11.0), rel=1e-12)


# ------------------------------------------------------------------- hygiene


def test_charts_print_nothing_and_the_module_imports_no_numpy(capsys):
    case("example_9_1")
    assert capsys.readouterr() == ("", "")
    code = "import sys, mdcalc.problems.mount; print('numpy' in sys.modules)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.stdout.strip() == "False", done.stderr
