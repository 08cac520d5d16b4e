"""Independent tests of ``mdcalc.core.sdof`` (the one-degree-of-freedom oscillator).

The oscillator is x'' + 2·ζ·β·x' + β²·x = β²·f(t), the load f in units of the static
response. Every expectation below is either a textbook closed form written out here
(derived in the comments) or a numerical integration of the ODE written in this file
(scipy's DOP853 at rtol 1e-12, through ``scipy.integrate.ode`` -- the Fortran code, fast
enough for the long runs into steady state). Only the functions under test are called
from the package; none of its other formulas are used for an expectation.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
import pytest
from scipy.integrate import ode, solve_ivp
from scipy.optimize import brentq, minimize_scalar

from mdcalc.core import sdof

TIGHT = 1e-12  # against closed forms evaluated here
INTEGRATION = 1e-9  # against the own integrations (relative to the response scale)
TWO_PI = 2.0 * math.pi

# ------------------------------------------------------------------- own integrations


def _dop853(
    rhs: Callable[[float, np.ndarray], list[float]],
    y0: Sequence[float] | np.ndarray,
    t0: float,
    first_step: float,
):
    # an explicit first step: DOP853's own first guess fails from a state at rest (x = x' = 0)
    solver = ode(rhs).set_integrator(
        "dop853", rtol=1e-12, atol=1e-13, nsteps=10**8, first_step=first_step
    )
    solver.set_initial_value(list(y0), t0)
    return solver


class OwnLoad:
    """Own integration of x'' + 2ζβx' + β²x = β²·f(t) from rest, f piecewise linear
    through (times, loads) (a repeated time is a jump), held after the last point.

    Each linear piece is integrated on its own (the load's kinks and jumps are then
    exact); ``sweep`` gives the states at sorted times, ``peak`` the largest |x| on a
    dense grid of 100 points per natural period with every x' = 0 in between refined
    by Brent's method (re-integrating from the grid point before it).
    """

    def __init__(
        self,
        times: Sequence[float],
        loads: Sequence[float],
        beta: float,
        zeta: float,
        horizon: float,
    ) -> None:
        self.beta, self.zeta, self.horizon = beta, zeta, horizon
        self.first = 1e-3 / beta
        knots = list(zip(times, loads, strict=True))
        if knots[-1][0] < horizon:
            knots.append((horizon, knots[-1][1]))
        self.start = knots[0][0]
        # pieces: (t0, t1, f0, slope, state at t0)
        self.pieces: list[tuple[float, float, float, float, np.ndarray]] = []
        y = np.zeros(2)
        for (t0, f0), (t1, f1) in zip(knots, knots[1:], strict=False):
            end = min(t1, horizon)
            if end <= t0:
                continue
            slope = (f1 - f0) / (t1 - t0)
            self.pieces.append((t0, end, f0, slope, y.copy()))
            solver = _dop853(self._rhs(t0, f0, slope), y, t0, self.first)
            y = np.array(solver.integrate(end))
            assert solver.successful()
            if end >= horizon:
                break

    def _rhs(
        self, t0: float, f0: float, slope: float
    ) -> Callable[[float, np.ndarray], list[float]]:
        b2, c = self.beta**2, 2.0 * self.zeta * self.beta

        def rhs(t: float, y: np.ndarray) -> list[float]:
            return [y[1], b2 * (f0 + slope * (t - t0) - y[0]) - c * y[1]]

        return rhs

    def _piece(self, t: float) -> int:
        for i, (_t0, t1, *_rest) in enumerate(self.pieces):
            if t <= t1:
                return i
        return len(self.pieces) - 1

    def sweep(self, ts: Sequence[float]) -> np.ndarray:
        """States (x, x') at the sorted times ts (times before the start: rest)."""
        out = np.zeros((len(ts), 2))
        index, solver = -1, None
        for k, t in enumerate(ts):
            if t <= self.start:
                continue
            i = self._piece(t)
            if i != index:
                t0, _, f0, slope, y0 = self.pieces[i]
                index, solver = i, _dop853(self._rhs(t0, f0, slope), y0, t0, self.first)
            assert solver is not None
            out[k] = solver.integrate(t) if t > solver.t else solver.y
            assert solver.successful()
        return out

    def advance(self, t_from: float, y_from: np.ndarray, t_to: float) -> np.ndarray:
        t0, _, f0, slope, _ = self.pieces[self._piece(t_from)]
        if t_to == t_from:
            return y_from
        solver = _dop853(self._rhs(t0, f0, slope), y_from, t_from, self.first)
        return np.array(solver.integrate(t_to))

    def peak(self, per_period: int = 100) -> tuple[float, float]:
        """(max |x|, its time) over [start, horizon]."""
        period = TWO_PI / self.beta
        best = (0.0, self.start)
        for t0, t1, *_ in self.pieces:
            n = max(2, math.ceil((t1 - t0) / period * per_period))
            grid = np.linspace(t0, t1, n + 1)
            states = self.sweep(list(grid))
            k = int(np.argmax(np.abs(states[:, 0])))
            if abs(states[k, 0]) > best[0]:
                best = (abs(float(states[k, 0])), float(grid[k]))
            for j in range(n):
                va, vb = states[j, 1], states[j + 1, 1]
                if va * vb < 0.0:
                    ta, ya, tb = float(grid[j]), states[j], float(grid[j + 1])

                    def velocity(t: float, ta: float = ta, ya: np.ndarray = ya) -> float:
                        return float(self.advance(ta, ya, t)[1])

                    if velocity(tb) * va >= 0.0:  # x' = 0 at the grid point itself
                        continue
                    root = brentq(velocity, ta, tb, xtol=1e-15, rtol=1e-15)
                    x = abs(float(self.advance(ta, ya, root)[0]))
                    if x > best[0]:
                        best = (x, root)
        return best


def own_steady_harmonic(beta: float, zeta: float, omega: float) -> tuple[float, float, float]:
    """Run x'' + 2ζβx' + β²x = β²·cos ωt from rest until the free part has decayed by
    e^-30 (rate ζβ, or the slow root β(ζ - √(ζ²-1)) when over-damped), then over one
    more forcing period project x and the support force per unit load, (β²x +
    2ζβx')/β², on cos ωt and sin ωt (64 equal samples: exact for a pure harmonic).
    Returns (amplitude of x, phase lag of x behind the load, amplitude of the support
    force)."""

    def rhs(t: float, y: np.ndarray) -> list[float]:
        return [y[1], beta * beta * (math.cos(omega * t) - y[0]) - 2.0 * zeta * beta * y[1]]

    period = TWO_PI / omega
    rate = zeta * beta if zeta <= 1.0 else beta * (zeta - math.sqrt(zeta * zeta - 1.0))
    start = math.ceil(30.0 / rate / period) * period
    solver = _dop853(rhs, [0.0, 0.0], 0.0, 1e-3 / beta)
    solver.integrate(start)
    n = 64
    ts = start + period * np.arange(n) / n
    states = np.array([solver.integrate(t) if t > solver.t else solver.y for t in ts])
    assert solver.successful()
    cos, sin = np.cos(omega * ts), np.sin(omega * ts)
    x, force = states[:, 0], states[:, 0] + 2.0 * zeta / beta * states[:, 1]
    a, b = 2.0 * np.mean(x * cos), 2.0 * np.mean(x * sin)  # x = a·cos + b·sin
    fa, fb = 2.0 * np.mean(force * cos), 2.0 * np.mean(force * sin)
    return math.hypot(a, b), math.atan2(b, a), math.hypot(fa, fb)


# ------------------------------------------------------------------ own closed forms


def undamped_rect(t: float, beta: float, duration: float) -> float:
    """Undamped response to a unit rectangular pulse from rest: 1 - cos βt during it,
    then (superposition of +1 at 0 and -1 at T) cos β(t - T) - cos βt."""
    if t <= duration:
        return 1.0 - math.cos(beta * t)
    return math.cos(beta * (t - duration)) - math.cos(beta * t)


def undamped_ramp(t: float, beta: float, rise: float) -> float:
    """Undamped response to f = t/t_r (then 1): Duhamel of a ramp is (t - sin βt/β)/t_r;
    after t_r subtract the same ramp delayed by t_r."""
    if t <= rise:
        return (t - math.sin(beta * t) / beta) / rise
    return 1.0 - (math.sin(beta * t) - math.sin(beta * (t - rise))) / (beta * rise)


def test_own_integration_agrees_with_own_closed_forms() -> None:
    """Sanity of the helpers above (no program involved)."""
    beta = 2.0
    pulse = OwnLoad([0.0, 0.0, 0.7, 0.7], [0.0, 1.0, 1.0, 0.0], beta, 0.0, 12.0)
    ts = list(np.linspace(0.0, 12.0, 37))
    xs = pulse.sweep(ts)[:, 0]
    assert np.max(np.abs(xs - [undamped_rect(t, beta, 0.7) for t in ts])) < 1e-11
    peak, when = pulse.peak()
    assert peak == pytest.approx(2.0 * math.sin(0.7), rel=1e-12)  # 2·sin(βT/2)
    # |x| = 2 sin(βT/2)·|sin β(t - T/2)| peaks every half period after β(t - T/2) = π/2
    assert math.remainder(when - 0.35 - math.pi / 4.0, math.pi / 2.0) == pytest.approx(0, abs=1e-9)
    ramp = OwnLoad([0.0, 1.3], [0.0, 1.0], beta, 0.0, 9.0)
    xs = ramp.sweep(ts[:28])[:, 0]
    assert np.max(np.abs(xs - [undamped_ramp(t, beta, 1.3) for t in ts[:28]])) < 1e-11
    assert ramp.peak()[0] == pytest.approx(1.0 + abs(math.sin(1.3)) / 1.3, rel=1e-12)
    amp, lag, force = own_steady_harmonic(1.0, 0.2, 0.5)
    # the textbook values: 1/√((1-r²)² + (2ζr)²) = 1/√(0.5625 + 0.04), lag atan(0.2/0.75)
    assert amp == pytest.approx(1.0 / math.sqrt(0.6025), rel=1e-10)
    assert lag == pytest.approx(math.atan2(0.2, 0.75), abs=1e-10)
    assert force == pytest.approx(math.sqrt(1.04 / 0.6025), rel=1e-10)


# ------------------------------------------------------------------------ step load

ZETAS = [0.0, 0.05, 0.5, 1.0, 3.0]


@pytest.mark.parametrize("zeta", ZETAS + [1.0 - 1e-9, 1.0 + 1e-9])
def test_step_response_against_own_integration(zeta: float) -> None:
    """step_response(t) against solve_ivp (DOP853, rtol 1e-12) of x'' + 2ζβx' + β²x = β²
    from rest, every damping regime, including both sides of critical damping."""
    beta = 3.0
    ts = np.linspace(0.0, 6.0 * TWO_PI / beta, 97)
    sol = solve_ivp(
        lambda t, y: [y[1], beta * beta * (1.0 - y[0]) - 2.0 * zeta * beta * y[1]],
        (0.0, ts[-1]),
        [0.0, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-15,
        t_eval=ts,
    )
    assert sol.success
    got = np.array([sdof.step_response(float(t), beta, zeta) for t in ts])
    assert np.all(np.isfinite(got))
    assert np.max(np.abs(got - sol.y[0])) < INTEGRATION
    assert sdof.step_response(-1.0, beta, zeta) == 0.0  # before the load: at rest


@pytest.mark.parametrize("zeta", ZETAS)
def test_step_response_closed_forms(zeta: float) -> None:
    """Textbook closed forms (rest, unit step): ζ < 1: 1 - e^{-ζβt}(cos β₁t + ζβ/β₁ sin β₁t),
    β₁ = β√(1-ζ²); ζ = 1: 1 - e^{-βt}(1 + βt); ζ > 1: 1 - (s₂e^{-s₁t} - s₁e^{-s₂t})/(s₂ - s₁),
    s₁,₂ = β(ζ ∓ √(ζ²-1))."""
    beta = 7.0
    for t in (0.01, 0.2, 0.9, 2.5):
        if zeta < 1.0:
            b1 = beta * math.sqrt(1.0 - zeta * zeta)
            expected = 1.0 - math.exp(-zeta * beta * t) * (
                math.cos(b1 * t) + zeta * beta / b1 * math.sin(b1 * t)
            )
        elif zeta == 1.0:
            expected = 1.0 - math.exp(-beta * t) * (1.0 + beta * t)
        else:
            s1 = beta * (zeta - math.sqrt(zeta * zeta - 1.0))
            s2 = beta * (zeta + math.sqrt(zeta * zeta - 1.0))
            expected = 1.0 - (s2 * math.exp(-s1 * t) - s1 * math.exp(-s2 * t)) / (s2 - s1)
        assert sdof.step_response(t, beta, zeta) == pytest.approx(expected, rel=1e-12, abs=1e-14)


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.3, 0.5, 0.9])
def test_step_peak_and_time(zeta: float) -> None:
    """Textbook overshoot: first peak 1 + exp(-πζ/√(1-ζ²)) at t = π/β₁ (x' ∝ e^{-ζβt}·
    sin β₁t vanishes there first); cross-checked by the own integration's refined
    maximum over the first natural period and a half (the first peak is the largest)."""
    beta = 4.0
    b1 = beta * math.sqrt(1.0 - zeta * zeta)
    expected = 1.0 + math.exp(-math.pi * zeta / math.sqrt(1.0 - zeta * zeta))
    assert sdof.step_peak(zeta) == pytest.approx(expected, rel=TIGHT)
    assert sdof.step_peak_time(beta, zeta) == pytest.approx(math.pi / b1, rel=TIGHT)
    own = OwnLoad([0.0], [1.0], beta, zeta, 1.5 * TWO_PI / b1)
    peak, when = own.peak()
    assert sdof.step_peak(zeta) == pytest.approx(peak, rel=INTEGRATION)
    assert sdof.step_peak_time(beta, zeta) == pytest.approx(when, abs=1e-7)


def test_step_peak_limits() -> None:
    """Brief: exactly 2 undamped; 1 from critical damping on (no overshoot), no NaN at
    ζ = 1 (the formula's √(1-ζ²) would be 0 there); and no peak time without overshoot."""
    assert sdof.step_peak(0.0) == 2.0
    assert sdof.step_peak_time(2.0, 0.0) == pytest.approx(math.pi / 2.0, rel=TIGHT)
    for zeta in (1.0, 1.5, 3.0, 10.0):
        assert sdof.step_peak(zeta) == 1.0
        assert sdof.step_peak_time(2.0, zeta) is None
    # just below critical: 1 + e^{-π·0.999999/√(1.999999e-6)} = 1 + e^{-2221} = 1 + 0
    below = sdof.step_peak(1.0 - 1e-6)
    assert math.isfinite(below) and below == pytest.approx(1.0, abs=1e-15)
    assert math.isfinite(sdof.step_peak(math.nextafter(1.0, 0.0)))
    near = sdof.step_peak_time(2.0, math.nextafter(1.0, 0.0))
    assert near is not None and math.isfinite(near)


@pytest.mark.parametrize("zeta", [1.0, 3.0])
def test_no_overshoot_when_critically_or_over_damped(zeta: float) -> None:
    """Own integration: from ζ = 1 on, x rises monotonically to 1 (sup = step_peak = 1)."""
    beta = 2.0
    own = OwnLoad([0.0], [1.0], beta, zeta, 30.0)
    xs = own.sweep(list(np.linspace(0.0, 30.0, 601)))[:, 0]
    assert np.all(np.diff(xs) >= -1e-13) and xs.max() <= 1.0 + 1e-12
    # by t = 30 the slow root β(ζ - √(ζ²-1)) = 0.343 s⁻¹ (ζ = 3) has left e^-10.3 ≈ 3e-5
    assert xs[-1] == pytest.approx(sdof.step_peak(zeta), abs=1e-4)


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.3])
def test_step_envelope(zeta: float) -> None:
    """Envelope 1 + e^{-ζβt} (seed 000 §8.1): the step response's extrema are at
    t_k = kπ/β₁ (x' ∝ e^{-ζβt} sin β₁t), where x = 1 - e^{-ζβt_k}·cos kπ: on the
    envelope for odd k, on its mirror 1 - e^{-ζβt} for even k. Checked on the own
    integration."""
    beta = 5.0
    b1 = beta * math.sqrt(1.0 - zeta * zeta)
    ks = list(range(1, 9))
    ts = [k * math.pi / b1 for k in ks]
    own = OwnLoad([0.0], [1.0], beta, zeta, ts[-1] + 0.1).sweep(ts)[:, 0]
    for k, t, x in zip(ks, ts, own, strict=True):
        envelope = sdof.step_envelope(t, beta, zeta)
        assert envelope == pytest.approx(1.0 + math.exp(-zeta * beta * t), rel=TIGHT)
        assert (envelope if k % 2 else 2.0 - envelope) == pytest.approx(x, abs=INTEGRATION)
    assert sdof.step_envelope(0.0, beta, zeta) == 2.0


# -------------------------------------------------------------------- harmonic load


def magnification_formula(r: float, zeta: float) -> float:
    return 1.0 / math.sqrt((1.0 - r * r) ** 2 + (2.0 * zeta * r) ** 2)


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.5, 1.0, 3.0])
@pytest.mark.parametrize("r", [0.0, 0.3, 0.9, 1.0, 1.7, 5.0])
def test_harmonic_closed_forms(r: float, zeta: float) -> None:
    """Textbook: X/X_st = 1/√((1-r²)² + (2ζr)²); lag = atan2(2ζr, 1 - r²) in [0, π];
    T = √(1 + (2ζr)²)·X/X_st (support force c·x + k·x' over the load)."""
    if zeta == 0.0 and r == 1.0:
        assert sdof.magnification(r, zeta) == math.inf  # undamped resonance
        return
    mag = magnification_formula(r, zeta)
    assert sdof.magnification(r, zeta) == pytest.approx(mag, rel=TIGHT)
    assert sdof.phase_lag(r, zeta) == pytest.approx(
        math.atan2(2.0 * zeta * r, 1.0 - r * r), abs=1e-14
    )
    assert 0.0 <= sdof.phase_lag(r, zeta) <= math.pi
    assert sdof.transmissibility(r, zeta) == pytest.approx(
        math.sqrt(1.0 + (2.0 * zeta * r) ** 2) * mag, rel=TIGHT
    )


def test_harmonic_special_points() -> None:
    """Hand values: r = 1 → X/X_st = 1/(2ζ), lag π/2; undamped lag 0 below resonance and
    π above; every ζ transmits exactly 1 at r = √2 ((1-2)² + 8ζ² = 1 + 8ζ²); r = 0 → 1."""
    for zeta in (0.01, 0.1, 0.7, 2.0):
        assert sdof.magnification(1.0, zeta) == pytest.approx(1.0 / (2.0 * zeta), rel=TIGHT)
        assert sdof.phase_lag(1.0, zeta) == pytest.approx(math.pi / 2.0, rel=TIGHT)
        assert sdof.transmissibility(math.sqrt(2.0), zeta) == pytest.approx(1.0, rel=1e-12)
        assert sdof.magnification(0.0, zeta) == 1.0
    assert sdof.phase_lag(0.5, 0.0) == 0.0
    assert sdof.phase_lag(2.0, 0.0) == pytest.approx(math.pi, rel=TIGHT)
    assert sdof.transmissibility(math.sqrt(2.0), 0.0) == pytest.approx(1.0, rel=1e-12)
    assert sdof.transmissibility(3.0, 0.0) == pytest.approx(1.0 / 8.0, rel=TIGHT)  # 1/(r²-1)


@pytest.mark.parametrize(
    "zeta, r", [(0.1, 0.5), (0.1, 1.0), (0.1, 2.5), (0.5, 0.8), (0.5, 3.0), (1.5, 1.0)]
)
def test_harmonic_against_own_steady_state(zeta: float, r: float) -> None:
    """Amplitude, lag and transmitted force measured from the own long integration run
    into steady state (see own_steady_harmonic)."""
    beta = 2.0
    amp, lag, force = own_steady_harmonic(beta, zeta, r * beta)
    assert sdof.magnification(r, zeta) == pytest.approx(amp, rel=INTEGRATION)
    assert sdof.phase_lag(r, zeta) == pytest.approx(lag, abs=INTEGRATION)
    assert sdof.transmissibility(r, zeta) == pytest.approx(force, rel=INTEGRATION)


@pytest.mark.parametrize("zeta", [0.02, 0.1, 0.3, 0.5, 0.7])
def test_resonance_peak(zeta: float) -> None:
    """d/dr[(1-r²)² + 4ζ²r²] = 0 → r² = 1 - 2ζ², then (1-r²)² + 4ζ²r² = 4ζ²(1-ζ²), so the
    peak is 1/(2ζ√(1-ζ²)); cross-checked by maximising the textbook curve numerically."""
    r_peak, peak = sdof.resonance_peak(zeta)
    assert r_peak == pytest.approx(math.sqrt(1.0 - 2.0 * zeta * zeta), rel=TIGHT)
    assert peak == pytest.approx(1.0 / (2.0 * zeta * math.sqrt(1.0 - zeta * zeta)), rel=TIGHT)
    found = minimize_scalar(
        lambda r: -magnification_formula(r, zeta),
        bounds=(0.0, 1.5),
        method="bounded",
        options={"xatol": 1e-12},
    )
    assert peak == pytest.approx(-found.fun, rel=1e-10)
    assert r_peak == pytest.approx(found.x, abs=1e-5)


def test_resonance_peak_limits() -> None:
    """ζ ≥ 1/√2: (1-r²)² + 4ζ²r² = 1 + 2r²(2ζ² - 1) + r⁴ only grows, peak 1 at r = 0;
    undamped: (1, ∞)."""
    for zeta in (1.0 / math.sqrt(2.0), 0.75, 1.0, 3.0):
        r_peak, peak = sdof.resonance_peak(zeta)
        assert r_peak == pytest.approx(0.0, abs=1e-7)
        assert peak == pytest.approx(1.0, rel=1e-12)
    for zeta in (0.75, 1.0, 3.0):
        assert sdof.resonance_peak(zeta) == (0.0, 1.0)
    assert sdof.resonance_peak(0.0) == (1.0, math.inf)


# ------------------------------------------------------- piecewise-linear loads


def check_against_own(
    times: Sequence[float],
    loads: Sequence[float],
    beta: float,
    zeta: float,
    horizon: float,
) -> sdof.Response:
    """The program's response against the own integration: every sample (to 1e-9 of the
    response's scale), the peak (1e-9 relative) and the sampling contract."""
    got = sdof.piecewise_linear_response(times, loads, beta, zeta, horizon)
    own = OwnLoad(times, loads, beta, zeta, horizon)
    assert got.times[0] == times[0]
    assert got.times[-1] == pytest.approx(horizon, rel=1e-14)
    steps = np.diff(got.times)
    assert np.all(steps > 0.0) and steps.max() <= TWO_PI / beta / 64 * (1 + 1e-12)
    expected = own.sweep(got.times)[:, 0]
    scale = max(1.0, float(np.max(np.abs(expected))))
    assert np.all(np.isfinite(got.displacements))
    assert np.max(np.abs(np.array(got.displacements) - expected)) < INTEGRATION * scale
    peak, when = own.peak()
    assert got.peak == pytest.approx(peak, rel=INTEGRATION)
    # the peak time matters only where the maximum is sharp (not a flat creep to 1)
    x_at = own.sweep([got.peak_time])[0, 0]
    assert abs(x_at) == pytest.approx(peak, rel=INTEGRATION)
    return got


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.5, 1.0, 3.0])
@pytest.mark.parametrize("duration", [0.4, 2.0])
def test_rectangular_pulse_against_own(zeta: float, duration: float) -> None:
    """Unit rectangular pulse (times [0, 0, T, T], loads [0, 1, 1, 0]); β = 2, so π/β =
    1.571: T = 0.4 is a short pulse, T = 2 a long one."""
    check_against_own([0.0, 0.0, duration, duration], [0.0, 1.0, 1.0, 0.0], 2.0, zeta, 10.0)


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.5, 1.0, 3.0])
@pytest.mark.parametrize("rise", [0.3, 2.0, 4.7])
def test_ramp_against_own(zeta: float, rise: float) -> None:
    """A ramp to 1 over t_r (times [0, t_r], loads [0, 1]), held after."""
    check_against_own([0.0, rise], [0.0, 1.0], 2.0, zeta, 10.0)


@pytest.mark.parametrize("zeta", [0.0, 0.1, 0.7, 1.0, 2.5])
def test_tabulated_load_against_own(zeta: float) -> None:
    """A tabulated load with a jump at the start, kinks, a jump to a negative value, and
    a non-zero last value held to the horizon."""
    times = [0.0, 0.25, 0.9, 0.9, 1.6, 2.4, 3.0]
    loads = [0.3, 1.0, 0.4, -0.6, 0.2, 0.8, 0.5]
    check_against_own(times, loads, 3.0, zeta, 9.0)


@pytest.mark.parametrize("duration", [0.1, 0.5, 1.0, 1.5, 1.6, 3.0, 7.0])
def test_rectangular_pulse_undamped_peak(duration: float) -> None:
    """Brief and seed 000 (7.92)-(7.96): peak 2·sin(βT/2) for T < π/β (free vibration of
    amplitude 2 sin(βT/2) after the pulse, reached at t = T/2 + π/(2β)), 2 otherwise
    (reached at t = π/β inside the pulse). β = 2 → π/β = 1.5708."""
    beta = 2.0
    got = sdof.piecewise_linear_response(
        [0.0, 0.0, duration, duration], [0.0, 1.0, 1.0, 0.0], beta, 0.0, 12.0
    )
    if duration < math.pi / beta:
        expected, when = 2.0 * math.sin(beta * duration / 2.0), duration / 2 + math.pi / 4
    else:
        expected, when = 2.0, math.pi / beta
    assert got.peak == pytest.approx(expected, rel=1e-12)
    assert sdof.rectangular_pulse_peak(beta, duration) == pytest.approx(expected, rel=1e-12)
    # undamped, the peak recurs: after the pulse |x| peaks every half period π/β; inside
    # a long pulse (T ≥ π/β) 1 - cos βt = 2 first at π/β, then every 2π/β
    assert abs(undamped_rect(got.peak_time, beta, duration)) == pytest.approx(expected, rel=1e-12)
    recur = math.pi / beta if got.peak_time > duration else 2.0 * math.pi / beta
    assert math.remainder(got.peak_time - when, recur) == pytest.approx(0.0, abs=1e-8)
    closed = [undamped_rect(t, beta, duration) for t in got.times]
    assert np.max(np.abs(np.array(got.displacements) - closed)) < 1e-12


@pytest.mark.parametrize("rise", [0.2, 1.0, 2.5, 4.0, 9.0])
def test_ramp_undamped_peak(rise: float) -> None:
    """Brief: undamped ramp peak 1 + |sin(β·t_r/2)|/(β·t_r/2): after the ramp
    x = 1 - 2·cos(β(t - t_r/2))·sin(βt_r/2)/(βt_r) (see undamped_ramp); on the ramp
    x ≤ t/t_r + 1/(βt_r) stays below that."""
    beta = 2.0
    got = sdof.piecewise_linear_response([0.0, rise], [0.0, 1.0], beta, 0.0, rise + 8.0)
    half = beta * rise / 2.0
    assert got.peak == pytest.approx(1.0 + abs(math.sin(half)) / half, rel=1e-12)
    closed = [undamped_ramp(t, beta, rise) for t in got.times]
    assert np.max(np.abs(np.array(got.displacements) - closed)) < 1e-12


def test_horizon_inside_the_pulse() -> None:
    """A horizon before the pulse ends: the response is the step response up to it
    (closed form 1 - cos βt undamped, peak 2 at π/β)."""
    got = sdof.piecewise_linear_response([0.0, 0.0, 5.0, 5.0], [0.0, 1.0, 1.0, 0.0], 2.0, 0.0, 2.0)
    assert got.times[-1] == pytest.approx(2.0, rel=1e-14)
    closed = [1.0 - math.cos(2.0 * t) for t in got.times]
    assert np.max(np.abs(np.array(got.displacements) - closed)) < 1e-12
    assert got.peak == pytest.approx(2.0, rel=1e-12)


def test_stiff_extreme_long_horizon() -> None:
    """β = 1e4 rad/s over 0.2 s (≈ 318 natural periods, 20 000 steps): still the exact
    undamped closed forms, to 1e-9 (rounding grows ~ linearly with the step count)."""
    beta, duration = 1.0e4, 2.0e-4  # βT = 2 < π: peak 2 sin(1)
    got = sdof.piecewise_linear_response(
        [0.0, 0.0, duration, duration], [0.0, 1.0, 1.0, 0.0], beta, 0.0, 0.2
    )
    assert np.all(np.isfinite(got.displacements))
    closed = [undamped_rect(t, beta, duration) for t in got.times]
    assert np.max(np.abs(np.array(got.displacements) - closed)) < 1e-9
    assert got.peak == pytest.approx(2.0 * math.sin(1.0), rel=1e-9)
    rise = 1.0e-3  # β·t_r/2 = 5
    ramp = sdof.piecewise_linear_response([0.0, rise], [0.0, 1.0], beta, 0.0, 0.2)
    closed = [undamped_ramp(t, beta, rise) for t in ramp.times]
    assert np.max(np.abs(np.array(ramp.displacements) - closed)) < 1e-9
    assert ramp.peak == pytest.approx(1.0 + abs(math.sin(5.0)) / 5.0, rel=1e-9)


def test_stiff_extreme_over_damped() -> None:
    """β = 1e4, ζ = 3 (decay rates β(3 ∓ √8) = 1716 and 58 284 s⁻¹): the over-damped step
    closed form (as in test_step_response_closed_forms) at every sample, no overflow."""
    beta, zeta = 1.0e4, 3.0
    got = sdof.piecewise_linear_response([0.0], [1.0], beta, zeta, 0.05)
    s1, s2 = beta * (zeta - math.sqrt(8.0)), beta * (zeta + math.sqrt(8.0))
    closed = [
        1.0 - (s2 * math.exp(-s1 * t) - s1 * math.exp(-s2 * t)) / (s2 - s1) for t in got.times
    ]
    assert np.all(np.isfinite(got.displacements))
    assert np.max(np.abs(np.array(got.displacements) - closed)) < 1e-12
    assert got.peak == pytest.approx(1.0, abs=1e-12)  # creeps up to 1, never beyond


def test_tiny_damping() -> None:
    """ζ = 1e-6 on a rectangular pulse (β = 2, T = 0.4, 15 s): the own integration; the
    peak is the undamped 2 sin(βT/2) less the decay e^{-ζβt} ≈ 1 - 1e-6 by then."""
    got = check_against_own([0.0, 0.0, 0.4, 0.4], [0.0, 1.0, 1.0, 0.0], 2.0, 1e-6, 15.0)
    assert got.peak == pytest.approx(2.0 * math.sin(0.4), rel=1e-5)
    stiff = sdof.piecewise_linear_response([0.0, 1e-3], [0.0, 1.0], 1.0e4, 1e-6, 0.2)
    assert np.all(np.isfinite(stiff.displacements))
    # first overshoot at t ≈ 1.3 ms, decay e^{-1e-6·1e4·0.0013} = 1 - 1.3e-5
    assert stiff.peak == pytest.approx(1.0 + abs(math.sin(5.0)) / 5.0, rel=1e-4)


def test_sampling_density_option() -> None:
    """samples_per_period bounds the sample spacing at 2π/β/n (docstring contract) and
    does not change the values at the common end point (own closed form)."""
    beta = 2.0
    for n in (16, 200):
        got = sdof.piecewise_linear_response([0.0], [1.0], beta, 0.0, 10.0, samples_per_period=n)
        assert np.diff(got.times).max() <= TWO_PI / beta / n * (1 + 1e-12)
        assert got.displacements[-1] == pytest.approx(1.0 - math.cos(20.0), abs=1e-12)
        assert got.peak == pytest.approx(2.0, rel=1e-12)
