"""``mechanism`` charts: ω(φ) of the reference over the run and M(φ, ω(φ)) along it,
checked against closed forms written out here (energy balance I·ω·dω/dφ = M):

* constant torque M, constant I, from rest: ω = √(2Mφ/I);
* M = a - b·ω, constant I: φ(ω) = (I/b)·[(ω₀ - ω) + (a/b)·ln((a - bω₀)/(a - bω))];
* M = 0, I(φ) = 1 + k·sin²φ: I·ω² = I₀·ω₀², ω = ω₀/√(1 + k·sin²φ), and the
  revolution takes T = (4/ω₀)·√(1 + k)·E(k/(1 + k)) (complete elliptic integral).

The last revolution's ω_max, ω_min and ω_mean = 2π/T also come from the case files'
[expect] tables (hand and independent time-domain values, each with its source).
"""

from __future__ import annotations

import importlib
import math
import time
import tomllib
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import CASES

EXTREME = CASES / "extreme"
MECHANISM = CASES / "mechanism"


def _run(path: Path):
    from mdcalc.input.casefile import read_case
    from mdcalc.runs.runner import solve_text

    run = solve_text(read_case(path))
    return run.module, run.result


def _expect(path: Path) -> dict[str, float]:
    table = tomllib.loads(path.read_text(encoding="utf-8")).get("expect", {})
    return {k: v["value"] for k, v in table.items() if isinstance(v.get("value"), float)}


def _curve(chart) -> tuple[np.ndarray, np.ndarray]:
    """φ [rad] and ω of the chart's first series (drawn in degrees)."""
    series = chart.series[0]
    return np.radians(np.array(series.x)), np.array(series.y)


def _marks(chart) -> dict[str, float]:
    return {m.label.split(" =")[0]: m.value for m in chart.marks if m.axis == "y"}


def _revolution_mean(phi: np.ndarray, omega: np.ndarray) -> float:
    """2π / ∫dφ/ω over the last revolution, by the trapezoid rule on the chart's grid."""
    last = phi >= phi[-1] - 2 * math.pi - 1e-12
    return 2 * math.pi / float(np.trapezoid(1.0 / omega[last], phi[last]))


def test_start_from_rest_under_a_constant_torque():
    path = EXTREME / "mechanism_start_from_rest.toml"
    module, result = _run(path)
    speed, torque = module.charts(result)
    phi, omega = _curve(speed)
    assert phi[0] == 0.0 and omega[0] == 0.0  # ω₀ = 0
    assert phi[-1] == pytest.approx(2 * math.pi, rel=1e-12)
    # I·ω²/2 = M·φ with M = 10 N·m, I = 2 kg·m²
    np.testing.assert_allclose(omega, np.sqrt(2 * 10 * phi / 2), rtol=1e-7, atol=1e-6)
    assert speed.x_label == "φ [deg]" and speed.y_label == "ω [rad/s]"
    assert torque.y_label == "M [N·m]"
    np.testing.assert_allclose(torque.series[0].y, 10.0)
    marks = _marks(speed)
    assert marks["ω_max"] == pytest.approx(math.sqrt(20 * math.pi), rel=1e-9)
    assert marks["ω_min"] == pytest.approx(0.0, abs=1e-12)
    # the revolution takes t = √(2IΦ/M) = √(0.8π)
    assert marks["ω_mean"] == pytest.approx(2 * math.pi / math.sqrt(0.8 * math.pi), rel=1e-8)


def test_linear_characteristic_follows_the_closed_form():
    path = MECHANISM / "linear_torque.toml"
    module, result = _run(path)
    speed, torque = module.charts(result)
    phi, omega = _curve(speed)
    a, b, inertia, omega0 = 100.0, 2.0, 2.0, 10.0
    assert omega[0] == omega0
    hand_phi = (inertia / b) * (
        (omega0 - omega) + (a / b) * np.log((a - b * omega0) / (a - b * omega))
    )
    np.testing.assert_allclose(hand_phi, phi, rtol=0, atol=1e-8)
    np.testing.assert_allclose(torque.series[0].y, a - b * omega, rtol=1e-12)
    assert torque.series[0].y[0] == pytest.approx(a - b * omega0)  # 80 N·m at the start
    # ω rises all the way: its last revolution's extremes are its ends
    marks = _marks(speed)
    last = phi >= phi[-1] - 2 * math.pi - 1e-12
    assert marks["ω_max"] == pytest.approx(omega[-1], rel=1e-12)
    assert marks["ω_min"] == pytest.approx(omega[last][0], rel=1e-12)
    assert marks["ω_mean"] == pytest.approx(_revolution_mean(phi, omega), rel=1e-6)
    # Kovylin's nodes at n = 16: every 22.5° over three revolutions
    nodes = speed.series[1]
    assert nodes.role == "nodes" and "n = 16" in nodes.label
    assert list(nodes.x) == pytest.approx([22.5 * k for k in range(49)])
    assert nodes.y[0] == omega0


def test_free_rotor_with_varying_inertia():
    """ω swings 100 times over a revolution: the curve reaches ω_min = ω₀/100 at 90°
    and 270°, and Kovylin's nodes that fly off (the Methods table shows it) are left
    off the scale with a word in the legend."""
    from scipy.special import ellipe

    path = EXTREME / "mechanism_inertia_ratio_1e4.toml"
    module, result = _run(path)
    speed, torque = module.charts(result)
    phi, omega = _curve(speed)
    k, omega0 = 9999.0, 100.0
    assert omega[0] == omega0
    np.testing.assert_allclose(omega, omega0 / np.sqrt(1 + k * np.sin(phi) ** 2), rtol=1e-6)
    assert omega.min() == pytest.approx(omega0 / math.sqrt(1 + k), rel=1e-8)
    assert omega.max() == pytest.approx(omega0, rel=1e-9)
    period = 4 / omega0 * math.sqrt(1 + k) * ellipe(k / (1 + k))
    marks = _marks(speed)
    assert marks["ω_min"] == pytest.approx(1.0, rel=1e-8)
    assert marks["ω_max"] == pytest.approx(100.0, rel=1e-9)
    assert marks["ω_mean"] == pytest.approx(2 * math.pi / period, rel=1e-8)
    assert _revolution_mean(phi, omega) == pytest.approx(2 * math.pi / period, rel=1e-3)
    nodes = speed.series[1]
    assert "off the scale" in nodes.label
    assert max(nodes.y) <= 2 * omega.max() - omega.min()
    np.testing.assert_allclose(torque.series[0].y, 0.0)


def test_crank_press_steady_revolution_matches_the_report():
    path = MECHANISM / "crank_press.toml"
    module, result = _run(path)
    expect = _expect(path)
    speed, torque = module.charts(result)
    phi, omega = _curve(speed)
    assert omega[0] == 80.0
    assert omega[-1] == pytest.approx(expect["final_speed"], rel=1e-8)
    marks = _marks(speed)
    assert marks["ω_max"] == pytest.approx(expect["max_speed"], rel=1e-7)
    assert marks["ω_min"] == pytest.approx(expect["min_speed"], rel=1e-7)
    last = phi >= phi[-1] - 2 * math.pi - 1e-12
    assert omega[last].max() == pytest.approx(expect["max_speed"], rel=1e-7)
    assert omega[last].min() == pytest.approx(expect["min_speed"], rel=1e-7)
    mean = _revolution_mean(phi, omega)
    assert marks["ω_mean"] == pytest.approx(mean, rel=1e-4)
    delta = (expect["max_speed"] - expect["min_speed"]) / mean
    assert delta == pytest.approx(expect["fluctuation"], rel=1e-4)
    # the start of the last revolution is marked: 39 revolutions on
    assert [m.value for m in speed.marks if m.axis == "x"] == pytest.approx([39 * 360.0])
    # M = 400(1 - ω/105) - 300·max(sin φ, 0)
    m_hand = 400 * (1 - omega / 105) - 300 * np.maximum(np.sin(phi), 0)
    np.testing.assert_allclose(torque.series[0].y, m_hand, rtol=1e-12, atol=1e-9)
    assert torque.series[0].y[0] == pytest.approx(400 * 25 / 105)


def test_tabulated_press_mean_speed():
    path = MECHANISM / "tabulated_press.toml"
    module, result = _run(path)
    expect = _expect(path)
    speed, _ = module.charts(result)
    phi, omega = _curve(speed)
    assert omega[0] == 80.0
    assert _marks(speed)["ω_mean"] == pytest.approx(expect["mean_speed_revolution"], rel=1e-8)
    assert _revolution_mean(phi, omega) == pytest.approx(expect["mean_speed_revolution"], rel=1e-4)


def test_a_stall_has_no_chart():
    module, result = _run(MECHANISM / "stall.toml")
    assert result.status == "no-answer"
    assert module.charts(result) == []


def test_charts_are_cheap_and_pure(monkeypatch, capsys):
    """The reference's dense solution is evaluated; no ODE and no Kovylin run again."""
    module, result = _run(MECHANISM / "crank_press.toml")

    def refuse(*args, **kwargs):
        raise AssertionError("charts must reuse the solver's runs")

    # Where each is defined and wherever it is looked up (the package's ``solve`` and
    # ``charts`` are functions: the modules come from importlib).
    for where in ("kovylin", "reference", "fluctuation", "solve", "charts"):
        submodule = importlib.import_module(f"mdcalc.problems.mechanism.{where}")
        for name in ("reference", "kovylin", "fluctuation_of_reference"):
            if hasattr(submodule, name):
                monkeypatch.setattr(submodule, name, refuse)
    start = time.perf_counter()
    charts = module.charts(result)
    assert time.perf_counter() - start < 2.0
    assert all(len(s.x) <= 6003 for c in charts for s in c.series)
    assert capsys.readouterr() == ("", "")
