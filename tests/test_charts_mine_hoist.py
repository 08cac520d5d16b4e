"""``mine-hoist`` charts: μ₁₂(t) and μ₂₃(t) over the horizon, checked against the
modal solution written out here from the seed's formulas, not taken from the program:

* β₁², β₂²: roots of λ² - λ·[c₁₂(1/J₁+1/J₂) + c₂₃(1/J₂+1/J₃)] + c₁₂c₂₃ΣJ/(J₁J₂J₃) = 0;
* R₁₂ = [M₁(J₂+J₃) + W·J₁]/ΣJ, R₂₃ = [M₁J₃ + W(J₁+J₂)]/ΣJ (seed (11)-(12));
* M₁₂ = R₁₂ + Σ Bⱼcos βⱼt, M₂₃ = R₂₃ + Σ gⱼBⱼcos βⱼt with gⱼ = J₂(β₁₂² - βⱼ²)/c₁₂
  (seed (8)), the Bⱼ from the unloaded ropes at the start, M₁₂(0) = M₂₃(0) = 0;
* the supremum 1 + Σ|b|, b = B/R.
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

HOIST = CASES / "mine-hoist"


def _run(path: Path):
    from mdcalc.input.casefile import read_case
    from mdcalc.runs.runner import solve_text

    run = solve_text(read_case(path))
    return run.module, run.result


def _hand(path: Path) -> dict[str, object]:
    """The modal solution of a case without [rope], by hand (see the module docstring)."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    h, loads = data["hoist"], data["loads"]
    j1, j2, j3 = h["drum_inertia"], h["sheave_inertia"], h["cage_inertia"]
    c12, c23 = h["chord_stiffness"], h["rope_stiffness"]
    m1, w = loads["drive_torque"], loads["load_torque"]
    total = j1 + j2 + j3
    r12 = (m1 * (j2 + j3) + w * j1) / total
    r23 = (m1 * j3 + w * (j1 + j2)) / total
    s = c12 * (1 / j1 + 1 / j2) + c23 * (1 / j2 + 1 / j3)
    p = c12 * c23 * total / (j1 * j2 * j3)
    fast_sq = (s + math.sqrt(s * s - 4 * p)) / 2
    slow_sq = p / fast_sq  # the small root without cancellation
    beta12_sq = c12 * (1 / j1 + 1 / j2)
    g = [j2 * (beta12_sq - lam) / c12 for lam in (slow_sq, fast_sq)]
    # B₁ + B₂ = -R₁₂, g₁B₁ + g₂B₂ = -R₂₃
    b_fast = (-r23 + g[0] * r12) / (g[1] - g[0])
    b_slow = -r12 - b_fast
    return {
        "beta": (math.sqrt(slow_sq), math.sqrt(fast_sq)),
        "b12": (b_slow / r12, b_fast / r12),
        "b23": (g[0] * b_slow / r23, g[1] * b_fast / r23),
        "period": 2 * math.pi / math.sqrt(slow_sq),
    }


def _mu(hand: dict, key: str, t: np.ndarray, modes=(0, 1)) -> np.ndarray:
    beta, b = hand["beta"], hand[key]
    return 1.0 + sum(b[j] * np.cos(beta[j] * t) for j in modes)


def _curve(chart):
    series = chart.series[0]
    return np.array(series.x), np.array(series.y)


def _marks(chart, axis: str) -> list[float]:
    return [m.value for m in chart.marks if m.axis == axis]


def test_seed_curves_are_the_hand_modal_solution():
    path = HOIST / "seed_1025.toml"
    module, result = _run(path)
    hand = _hand(path)
    charts = module.charts(result)
    assert len(charts) == 2
    for chart, key in zip(charts, ("b12", "b23"), strict=True):
        t, mu = _curve(chart)
        # the ropes are unloaded at the start: μ(0) = 1 + Σb = 0
        assert t[0] == 0.0 and mu[0] == pytest.approx(0.0, abs=1e-12)
        np.testing.assert_allclose(mu, _mu(hand, key, t), rtol=0, atol=1e-12)
        # the horizon: 20 periods of the slow mode by default
        assert t[-1] == pytest.approx(20 * hand["period"], rel=1e-12)
        # every mode drawn: at least 16 points per period of the fast one
        assert np.max(np.diff(t)) <= 2 * math.pi / hand["beta"][1] / 16 * (1 + 1e-9)
        supremum = 1 + sum(abs(b) for b in hand[key])
        assert _marks(chart, "y") == pytest.approx([supremum, 1.0], rel=1e-12)
        assert _marks(chart, "x") == pytest.approx([hand["period"]], rel=1e-12)
        assert mu.max() <= supremum + 1e-12
        assert "[s]" in chart.x_label


def test_seed_first_swing_maximum():
    """The curve's largest sample in t ≤ 2π/β₁ is the reported first-swing maximum
    to within the sampling error, and a dense hand grid agrees with the point drawn."""
    path = HOIST / "seed_1025.toml"
    module, result = _run(path)
    hand = _hand(path)
    expect = tomllib.loads(path.read_text(encoding="utf-8"))["expect"]
    for chart, key, name in zip(
        module.charts(result), ("b12", "b23"), ("mu12", "mu23"), strict=True
    ):
        t, mu = _curve(chart)
        first = t <= hand["period"]
        dense = np.linspace(0.0, hand["period"], 400_001)
        hand_max = float(_mu(hand, key, dense).max())
        assert mu[first].max() <= hand_max + 1e-12
        # 16 points per fast period: a peak is missed by at most |b_fast|·(1 - cos(π/16))
        assert mu[first].max() >= hand_max - abs(hand[key][1]) * (1 - math.cos(math.pi / 16))
        point = chart.series[-1]
        assert point.role == "this-case" and len(point.x) == 1
        assert point.y[0] == pytest.approx(hand_max, rel=1e-9)
        if f"{name}_first_swing" in expect:
            assert point.y[0] == pytest.approx(expect[f"{name}_first_swing"]["value"], rel=1e-9)
        # over the whole horizon the curve comes close to the supremum, never above it
        supremum = 1 + sum(abs(b) for b in hand[key])
        assert supremum - 5e-3 <= mu.max() <= supremum + 1e-12


def test_stiff_chord_draws_the_fast_mode_as_an_envelope():
    """β₂ = 5814 rad/s over 46 s is 43 000 periods: too many to draw. μ₁₂ shows the
    slow mode and the envelope ± |b_fast|; μ₂₃'s fast b (1e-7) is only named."""
    path = HOIST / "stiff_chord.toml"
    module, result = _run(path)
    hand = _hand(path)
    mu12, mu23 = module.charts(result)
    t, slow = _curve(mu12)
    np.testing.assert_allclose(slow, _mu(hand, "b12", t, modes=(0,)), atol=1e-12)
    envelope, below = mu12.series[1], mu12.series[2]
    assert envelope.role == below.role == "envelope" and "envelope" in envelope.label
    assert below.label == "" and list(envelope.x) == list(below.x) == list(t)
    upper, lower = np.array(envelope.y), np.array(below.y)
    fast = abs(hand["b12"][1])
    np.testing.assert_allclose(upper - slow, fast, atol=1e-12)
    np.testing.assert_allclose(slow - lower, fast, atol=1e-12)
    assert lower[0] == pytest.approx(0.0, abs=1e-9)  # μ₁₂(0) = 0: unloaded at the start
    supremum = 1 + sum(abs(b) for b in hand["b12"])
    assert upper.max() <= supremum + 1e-12
    assert upper.max() == pytest.approx(supremum, abs=1e-3)
    t23, curve23 = _curve(mu23)
    assert len(mu23.series) == 2  # the curve and the first-swing point, no envelope
    assert "5814 rad/s" in mu23.series[0].label
    np.testing.assert_allclose(curve23, _mu(hand, "b23", t23, modes=(0,)), atol=1e-12)


def test_sweep_adds_the_table_1_chart():
    path = HOIST / "rope_sweep.toml"
    module, result = _run(path)
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    charts = module.charts(result)
    assert len(charts) == 3
    sweep = charts[2]
    assert sweep.x_label == "H [m]"
    heights = data["sweep"]["heights"]
    for series in sweep.series:
        assert list(series.x) == heights
    by_label = {s.label: list(s.y) for s in sweep.series}
    expect = data["expect"]
    # the case's length 1025 m is the last height: its hand values
    assert by_label["μ₁₂ supremum"][-1] == pytest.approx(expect["mu12_supremum"]["value"])
    assert by_label["μ₂₃ supremum"][-1] == pytest.approx(expect["mu23_supremum"]["value"])
    assert by_label["μ₁₂ by (19)"][-1] == pytest.approx(expect["mu12_simplified"]["value"])
    assert by_label["μ₂₃ by (20)"][-1] == pytest.approx(expect["mu23_simplified"]["value"])


def test_no_answer_has_no_chart():
    module, result = _run(HOIST / "cannot_lift.toml")
    assert result.status == "no-answer"
    assert module.charts(result) == []


def test_charts_are_cheap_and_pure(monkeypatch, capsys):
    """No ODE row, no new modal solution: charts only evaluates the cosine sums."""
    from mdcalc.core import chain, cosine_sums

    module, result = _run(HOIST / "stiff_chord.toml")

    def refuse(*args, **kwargs):
        raise AssertionError("charts must reuse the solver's modal solution")

    for name in ("natural_modes", "suddenly_applied", "block_modes", "block_step"):
        monkeypatch.setattr(chain, name, refuse)
    for name in ("cosine_sum_maximum", "maxima"):
        monkeypatch.setattr(cosine_sums, name, refuse)
    # where it is defined, and where the solver looks it up (the package's ``solve`` is
    # the function, so the module comes from importlib)
    for where in ("ode_rows", "solve"):
        submodule = importlib.import_module(f"mdcalc.problems.mine_hoist.{where}")
        monkeypatch.setattr(submodule, "ode_first_swing", refuse)
    start = time.perf_counter()
    charts = module.charts(result)
    assert time.perf_counter() - start < 1.0
    assert all(len(s.x) <= 2 * 8001 for c in charts for s in c.series)
    assert capsys.readouterr() == ("", "")
