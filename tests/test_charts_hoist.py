"""``hoist`` charts (``--plot``): the rope dynamic factor ψ = F/G against time at the
start, checked against the two-mass rope model written out here by hand from the brief
(PROBLEMS.md §1, seed 000 §7.6) and the case files, not taken from the program.

Drive m1, rope c, load m2 = G/g; drive force D = G + (m1 + m2)·a during the start
(a = V/t_p), G after it; rope force F = c·(x1 - y - s) while taut. With the load in
the air, F'' = c·(D/m1 + G/m2) - β²·F, β² = c·(1/m1 + 1/m2): F swings about
(D·m2 + G·m1)/(m1 + m2), which is G + m2·a during the start and G after it. With the
load on the ground, m1·x1'' = D - c·(x1 - s): F swings about D at β1 = √(c/m1).

* Hanging (F(0) = G, at rest): ψ = 1 + (a/g)·(1 - cos βt) during the start, then
  ψ = 1 + (a/g)·(cos β(t - t_p) - cos βt).
* On the ground, no slack: F = D·(1 - cos β1·t) until F = G (lift-off at t_L, rate
  Ḟ_L = D·β1·sin β1·t_L); then F = G + m2·a·(1 - cos βτ) + (Ḟ_L/β)·sin βτ.
* With slack s: the drive runs free, D/m1, for t_s = √(2·s·m1/D) and hits the rope at
  v_s = D·t_s/m1; then F = D·(1 - cos β1τ) + (c·v_s/β1)·sin β1τ.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path
from typing import Any

import pytest

from mdcalc.input.casefile import read_case
from mdcalc.output.plot import Chart, Series
from mdcalc.runs.runner import solve_text
from tests.conftest import CASES

G0 = 9.80665  # standard gravity, the program's default [m/s²]
RPM = math.pi / 30.0  # rpm → rad/s


def charts_of(path: Path) -> tuple[list[Chart], Any]:
    run = solve_text(read_case(path))
    return run.module.charts(run.result), run.result


def expect(path: Path, key: str) -> float:
    return tomllib.loads(path.read_text(encoding="utf-8"))["expect"][key]["value"]


def curve(chart: Chart) -> Series:
    assert chart.series[0].label.startswith("ψ(t)")
    return chart.series[0]


def points(chart: Chart, start: str) -> Series:
    found = [s for s in chart.series if s.label.startswith(start)]
    assert len(found) == 1, [s.label for s in chart.series]
    assert found[0].role == "event"
    return found[0]


def marks(chart: Chart, axis: str) -> list[float]:
    return [m.value for m in chart.marks if m.axis == axis]


def crane_scene(c: float, t_p: float) -> dict[str, float]:
    """The crane's drive (cases/hoist/crane.toml) on a rope of stiffness c."""
    m2, v = 10000.0, 0.2
    w1 = 960.0 * RPM
    j_drive = 0.35 + 0.5 / 5.0**2 + 40.0 * (15.279 / 960.0) ** 2  # (7.30) without the load
    m1 = j_drive * (w1 / v) ** 2
    return {"m1": m1, "m2": m2, "c": c, "a": v / t_p, "t_p": t_p, "s": 0.0}


def beta(sc: dict[str, float]) -> float:
    return math.sqrt(sc["c"] * (1.0 / sc["m1"] + 1.0 / sc["m2"]))


def hanging_psi(sc: dict[str, float], t: float) -> float:
    b, k, t_p = beta(sc), sc["a"] / G0, sc["t_p"]
    if t <= t_p:
        return 1.0 + k * (1.0 - math.cos(b * t))
    return 1.0 + k * (math.cos(b * (t - t_p)) - math.cos(b * t))


def ground_by_hand(sc: dict[str, float]) -> dict[str, float]:
    """Slack, grounded swing and lift-off by hand; the air phase's swing."""
    m1, m2, c, a, s = sc["m1"], sc["m2"], sc["c"], sc["a"], sc["s"]
    g_force = m2 * G0
    d = g_force + (m1 + m2) * a
    b1 = math.sqrt(c / m1)
    t_s = math.sqrt(2.0 * s * m1 / d)
    v_s = d * t_s / m1
    # D - D·cos x + B·sin x = G, B = c·v_s/β1: R·cos(x + φ) = D - G, R = √(D² + B²),
    # tan φ = B/D; F rises where sin(x + φ) > 0
    amp, phi = math.hypot(d, c * v_s / b1), math.atan2(c * v_s / b1, d)
    tau = (math.acos((d - g_force) / amp) - phi) / b1
    rate = d * b1 * math.sin(b1 * tau) + c * v_s * math.cos(b1 * tau)  # Ḟ at lift-off
    return {"D": d, "b1": b1, "t_s": t_s, "v_s": v_s, "t_L": t_s + tau, "rate": rate}


def ground_force_in_air(sc: dict[str, float], hand: dict[str, float], t: float) -> float:
    """F after lift-off, during the start, while the rope is taut."""
    b, m2a = beta(sc), sc["m2"] * sc["a"]
    tau = t - hand["t_L"]
    return sc["m2"] * G0 + m2a * (1.0 - math.cos(b * tau)) + hand["rate"] / b * math.sin(b * tau)


def ground_peak(sc: dict[str, float], hand: dict[str, float]) -> tuple[float, float]:
    """(time, F) of the first crest after lift-off: G + m2·a + √((m2·a)² + (Ḟ_L/β)²)."""
    b, m2a = beta(sc), sc["m2"] * sc["a"]
    crest = (math.atan2(hand["rate"] / b, -m2a) % (2.0 * math.pi)) / b
    return hand["t_L"] + crest, sc["m2"] * G0 + m2a + math.hypot(m2a, hand["rate"] / b)


# ------------------------------------------------------------------ load hanging


def test_crane_hanging_curve_is_the_rectangular_pulse_response():
    path = CASES / "hoist" / "crane.toml"
    charts, result = charts_of(path)
    assert len(charts) == 2
    chart = charts[0]
    assert "hanging" in chart.title
    sc = crane_scene(4 * 1.0e11 * 1.5e-4 / 10.0, 1.5)
    b = beta(sc)
    assert b == pytest.approx(expect(path, "rope_frequency"), rel=1e-8)
    s = curve(chart)
    assert s.x[0] == 0.0 and s.y[0] == pytest.approx(1.0, abs=1e-12)  # static at t = 0
    for t, psi in zip(s.x, s.y, strict=True):
        assert psi == pytest.approx(hanging_psi(sc, t), rel=1e-10, abs=1e-12), t
    # the report's horizon: the start and two rope periods after it
    assert s.x[-1] == pytest.approx(1.5 + 2 * (2 * math.pi / b), rel=1e-12)
    # t_p > π/β: the peak is 1 + 2·a/g, first reached at π/β (7.95)
    peak = 1.0 + 2.0 * sc["a"] / G0
    assert max(s.y) == pytest.approx(peak, rel=1e-12)
    assert max(s.y) == pytest.approx(expect(path, "hanging_dynamic_factor"), rel=1e-8)
    assert sorted(marks(chart, "y")) == pytest.approx([1.0, peak], rel=1e-12)
    assert marks(chart, "x") == pytest.approx([math.pi / b], rel=1e-9)
    # the crests during the start are one rope period apart
    crests = [
        s.x[k]
        for k in range(1, len(s.x) - 1)
        if s.x[k] < 1.5 and s.y[k] >= s.y[k - 1] and s.y[k] > s.y[k + 1]
    ]
    gaps = [b2 - b1 for b1, b2 in zip(crests, crests[1:], strict=False)]
    assert len(crests) == 6
    assert gaps == pytest.approx([2 * math.pi / b] * len(gaps), abs=2 * math.pi / b / 40)
    assert points(chart, "start ends").x == [1.5]
    assert points(chart, "start ends").y[0] == pytest.approx(hanging_psi(sc, 1.5), rel=1e-12)


def test_short_start_hanging_peak_is_the_residual_swing():
    """t_p < π/β: after the pulse, 1 + (a/g)·(cos β(t - t_p) - cos βt), whose crest
    is 1 + 2·(a/g)·sin(β·t_p/2) (PROBLEMS.md §1)."""
    path = CASES / "hoist" / "short_start.toml"
    chart = charts_of(path)[0][0]
    sc = crane_scene(6.0e6, 0.01)
    b = beta(sc)
    assert b * sc["t_p"] < math.pi
    s = curve(chart)
    for t, psi in zip(s.x, s.y, strict=True):
        assert psi == pytest.approx(hanging_psi(sc, t), rel=1e-10), t
    peak = 1.0 + 2.0 * sc["a"] / G0 * math.sin(b * sc["t_p"] / 2.0)
    assert max(s.y) == pytest.approx(peak, rel=1e-12)
    assert max(s.y) * 10000.0 * G0 == pytest.approx(expect(path, "hanging_peak_force"), rel=1e-9)
    # = 1 + 2·(a/g)·sin(β·t_p/2)·sin β(t - t_p/2): the crest at t = t_p/2 + π/(2β)
    assert marks(chart, "x") == pytest.approx([sc["t_p"] / 2 + math.pi / (2 * b)], rel=1e-9)


def test_impulsive_hanging_rope_goes_slack_and_stays_at_zero():
    """The residual swing 2·(a/g)·sin(βt_p/2) = 3.6 exceeds 1: the rope goes slack
    where the hand formula reaches ψ = 0, and ψ stays 0 while it is slack."""
    path = CASES / "extreme" / "hoist_impulsive_start.toml"
    chart = charts_of(path)[0][0]
    sc = {"m1": 4000.0, "m2": 1000.0, "c": 1.0e6, "a": 1.0e5, "t_p": 1.0e-5, "s": 0.0}
    b = beta(sc)
    # ψ = 1 + 2·(a/g)·sin(βt_p/2)·sin β(t - t_p/2): its first zero is past π/β
    lo, hi = math.pi / b, 2 * math.pi / b
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if hanging_psi(sc, mid) > 0 else (lo, mid)
    slack = points(chart, "rope slack")
    assert slack.x[0] == pytest.approx(hi, rel=1e-9)
    assert slack.y == [0.0, 0.0]
    s = curve(chart)
    for t, psi in zip(s.x, s.y, strict=True):
        if t <= slack.x[0]:
            assert psi == pytest.approx(hanging_psi(sc, t), rel=1e-9, abs=1e-9)
        elif t < slack.x[1]:
            assert psi == 0.0
    assert max(s.y) == pytest.approx(expect(path, "hanging_dynamic_factor"), rel=1e-9)


# ------------------------------------------------------------ load on the ground


def test_crane_ground_curve_grounded_swing_then_lift_off():
    path = CASES / "hoist" / "crane.toml"
    chart = charts_of(path)[0][1]
    assert "ground" in chart.title
    sc = crane_scene(6.0e6, 1.5)
    hand = ground_by_hand(sc)
    s = curve(chart)
    weight = sc["m2"] * G0
    assert s.x[0] == 0.0 and s.y[0] == 0.0  # the rope carries nothing yet
    for t, psi in zip(s.x, s.y, strict=True):
        if t <= hand["t_L"]:
            force = hand["D"] * (1.0 - math.cos(hand["b1"] * t))
        elif t <= sc["t_p"]:
            force = ground_force_in_air(sc, hand, t)
        else:
            continue
        assert psi == pytest.approx(force / weight, rel=1e-9, abs=1e-12), t
    lift = points(chart, "load lifts off")
    assert lift.x == pytest.approx([hand["t_L"]], rel=1e-10) and lift.y == [1.0]
    t_peak, f_peak = ground_peak(sc, hand)
    assert max(s.y) == pytest.approx(f_peak / weight, rel=1e-10)
    assert max(s.y) == pytest.approx(expect(path, "ground_dynamic_factor"), rel=1e-8)
    assert marks(chart, "x") == pytest.approx([t_peak], rel=1e-9)
    reported = [v for v in marks(chart, "y") if v != 1.0]
    assert reported == pytest.approx([f_peak / weight], rel=1e-8)  # the ODE reference
    b = beta(sc)
    assert s.x[-1] == pytest.approx(1.5 + 2 * (2 * math.pi / b), rel=1e-12)


def test_slack_rope_taken_up_then_lift_off_then_slack_again():
    """efficiency_one: 50 mm of slack, given m1 = 20 t; ψ = 0 until the drive has run
    the slack out, then the grounded swing, lift-off and the first crest, which the
    rope does not survive: it goes slack after it (the closed form's limit)."""
    path = CASES / "hoist" / "efficiency_one.toml"
    chart = charts_of(path)[0][1]
    sc = {"m1": 20000.0, "m2": 5000.0, "c": 2.0e6, "a": 0.5 / 2.0, "t_p": 2.0, "s": 0.05}
    hand = ground_by_hand(sc)
    weight = sc["m2"] * G0
    taut = points(chart, "slack taken up")
    assert taut.x == pytest.approx([hand["t_s"]], rel=1e-12) and taut.y == [0.0]
    assert points(chart, "load lifts off").x == pytest.approx([hand["t_L"]], rel=1e-10)
    # first slack after lift-off: the air-phase formula down to 0, by bisection
    t_peak, f_peak = ground_peak(sc, hand)
    lo, hi = t_peak, t_peak + math.pi / beta(sc)
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ground_force_in_air(sc, hand, mid) > 0 else (lo, mid)
    slack = points(chart, "rope goes slack")
    assert slack.x[0] == pytest.approx(hi, rel=1e-9)
    assert all(y == 0.0 for y in slack.y)
    s = curve(chart)
    for t, psi in zip(s.x, s.y, strict=True):
        if t <= hand["t_s"]:
            force = 0.0
        elif t <= hand["t_L"]:
            tau = t - hand["t_s"]
            b1 = hand["b1"]
            force = hand["D"] * (1 - math.cos(b1 * tau)) + sc["c"] * hand["v_s"] / b1 * math.sin(
                b1 * tau
            )
        elif t <= slack.x[0]:
            force = ground_force_in_air(sc, hand, t)
        else:
            break
        assert psi == pytest.approx(force / weight, rel=1e-9, abs=1e-12), t
    assert max(s.y) == pytest.approx(f_peak / weight, rel=1e-10)
    assert max(s.y) == pytest.approx(expect(path, "ground_dynamic_factor"), rel=1e-8)
    assert marks(chart, "x") == pytest.approx([t_peak], rel=1e-9)


@pytest.mark.parametrize(
    ("name", "rel"),
    [("hoist_impulsive_start", 1e-12), ("hoist_barely_starts", 1e-9)],
)
def test_ground_peak_matches_the_independent_mpmath_values(name, rel):
    """Both case files carry the ground peak from an independent mpmath evaluation;
    the curve's exact piecewise solution meets it more tightly than the report's ODE
    reference (1e-7) on the impulsive start."""
    path = CASES / "extreme" / f"{name}.toml"
    chart = charts_of(path)[0][1]
    assert max(curve(chart).y) == pytest.approx(expect(path, "ground_dynamic_factor"), rel=rel)


# ---------------------------------------------------------------- long horizons


@pytest.mark.parametrize("name", ["stiff_rope", "very_stiff_rope"])
def test_a_long_horizon_shows_its_opening(name):
    """250 and 6100 rope periods in the start: only the opening is drawn (the title
    says so), with the lift-off and the peak in it; the peak is still exact."""
    path = CASES / "hoist" / f"{name}.toml"
    charts, result = charts_of(path)
    sc = crane_scene(6.0e12 if name == "very_stiff_rope" else 1.0e10, 1.5)
    period = 2 * math.pi / beta(sc)
    hand = ground_by_hand(sc)
    for chart, top in zip(
        charts,
        [expect(path, "hanging_dynamic_factor"), expect(path, "ground_dynamic_factor")],
        strict=True,
    ):
        s = curve(chart)
        assert "shown" in chart.title
        assert s.x[-1] < 10 * period
        assert len(s.x) < 1000
        assert max(s.y) == pytest.approx(top, rel=1e-6)
    assert marks(charts[0], "x") == pytest.approx([math.pi / beta(sc)], rel=1e-6)
    assert points(charts[1], "load lifts off").x == pytest.approx([hand["t_L"]], rel=1e-8)


# ----------------------------------------------------------------- no curve


@pytest.mark.parametrize("name", ["lift", "cannot_start"])
def test_no_rope_or_no_answer_draws_nothing(name):
    charts, result = charts_of(CASES / "hoist" / f"{name}.toml")
    assert charts == []


def test_every_rope_chart_is_finite_and_marks_static_and_reported():
    for path in sorted((CASES / "hoist").glob("*.toml")):
        charts, result = charts_of(path)
        for chart in charts:
            assert sorted(m.axis for m in chart.marks) == ["x", "y", "y"]
            assert 1.0 in marks(chart, "y")
            for series in chart.series:
                assert all(math.isfinite(v) for v in [*series.x, *series.y])
                assert list(series.x) == sorted(series.x) or series.role == "event"


# ------------------------------------------------- touch-down (not in the cases)


def test_touch_down_of_a_load_on_a_taut_rope_against_an_ode_run():
    """No shipped case brings the load back down; the piece that would (a taut rope
    pulling less than G on a load sinking 2 mm above the ground) against a direct
    integration of x1'' = (D - F)/m1, y'' = (F - G)/m2."""
    from scipy.integrate import solve_ivp

    from mdcalc.problems.hoist.history import RopePiece, _load, _touch_down
    from mdcalc.problems.hoist.rope import RopeScene

    m1, m2, c, a = 1000.0, 1000.0, 1.0e6, 0.1
    weight = m2 * G0
    r = RopeScene(c, m1, m2, weight, a, 10.0, 0.0)
    drive = weight + (m1 + m2) * a
    p = RopePiece(0.0, 0.0, True, False, drive, 0.5 * weight / c, 0.0, 0.002, -0.1)

    def rhs(t, state):
        x1, v1, y, vy = state
        force = c * (x1 - y)
        return [v1, (drive - force) / m1, vy, (force - weight) / m2]

    def ground(t, state):
        return state[2]

    ground.terminal, ground.direction = True, -1  # type: ignore[attr-defined]
    run = solve_ivp(
        rhs, (0.0, 1.0), [p.u + p.y, p.du + p.vy, p.y, p.vy], method="DOP853",
        rtol=1e-12, atol=1e-15, events=ground, dense_output=True,
    )  # fmt: skip
    assert run.status == 1
    t_down = float(run.t_events[0][0])
    assert _touch_down(r, p, 1.0) == pytest.approx(t_down, rel=1e-8)
    for tau in (0.3 * t_down, 0.7 * t_down):
        y, vy = _load(r, p, tau)
        state = run.sol(tau)
        assert float(y) == pytest.approx(state[2], rel=1e-8, abs=1e-12)
        assert float(vy) == pytest.approx(state[3], rel=1e-8, abs=1e-12)
