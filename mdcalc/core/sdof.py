"""Single-degree-of-freedom responses, shared by problems.

The oscillator is x'' + 2·ζ·β·x' + β²·x = β²·f(t), so ``f`` is the load in units
of the static response (F/k, or M/c for a torsional spring) and x/f is the dynamic
factor. β is the undamped natural frequency [rad/s], ζ the damping ratio.
The closed forms take floats or numpy arrays alike (:mod:`mdcalc.core.xp`): a single
scene stays pure Python (no numpy import), a sweep's kernel passes its grid through
the same formula. The exact response to piecewise-linear loads (the Duhamel
integral evaluated exactly step by step) is pure Python.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from mdcalc.core.xp import of


def rectangular_pulse_peak(beta: Any, duration: Any) -> Any:
    """Peak response to a rectangular force pulse, in units of its static response.

    x'' + β²·x = F/m for 0 < t < T, then 0, from rest (seed 000 (7.92)-(7.96)):
    during the pulse the peak is 2 (at t = π/β, reached if T ≥ π/β); after it the
    free vibration has amplitude 2·|sin(β·T/2)|. So the maximum over all time is
    2 when T ≥ π/β, else 2·sin(β·T/2).
    """
    xp = of(beta, duration)
    return xp.where(
        beta * duration >= math.pi, lambda: 2.0, lambda: 2.0 * xp.sin(0.5 * beta * duration)
    )


# ------------------------------------------------------------------ step load


def damped_frequency(beta: Any, zeta: Any) -> Any:
    """β₁ = β·√(1 - ζ²) [rad/s]; 0 at and above critical damping."""
    xp = of(beta, zeta)
    return xp.where(zeta < 1.0, lambda: beta * xp.sqrt(1.0 - zeta * zeta), lambda: 0.0)


def step_response(t: Any, beta: Any, zeta: Any) -> Any:
    """x/x_st after a suddenly applied constant load, from rest (all damping regimes)."""
    xp = of(t, beta, zeta)
    decay = zeta * beta

    def under() -> Any:
        b1 = damped_frequency(beta, zeta)
        return 1.0 - xp.exp(-decay * t) * (xp.cos(b1 * t) + decay / b1 * xp.sin(b1 * t))

    def critical() -> Any:
        return 1.0 - xp.exp(-beta * t) * (1.0 + beta * t)

    def over() -> Any:
        root = beta * xp.sqrt(zeta * zeta - 1.0)
        # 1 - e^{-ζβt}·(cosh(rt) + ζβ/r·sinh(rt)), written with decaying exponentials only.
        slow, fast = decay - root, decay + root
        return 1.0 - (fast * xp.exp(-slow * t) - slow * xp.exp(-fast * t)) / (2.0 * root)

    def moving() -> Any:
        return xp.where(zeta < 1.0, under, lambda: xp.where(zeta == 1.0, critical, over))

    return xp.where(t <= 0.0, lambda: 0.0, moving)


def step_peak(zeta: Any) -> Any:
    """Dynamic factor of a suddenly applied load: the first (largest) peak of
    :func:`step_response`, 1 + exp(-π·ζ/√(1 - ζ²)); exactly 2 undamped, 1 from
    critical damping on (no overshoot)."""
    xp = of(zeta)
    return xp.where(
        zeta >= 1.0,
        lambda: 1.0,
        lambda: 1.0 + xp.exp(-math.pi * zeta / xp.sqrt(1.0 - zeta * zeta)),
    )


def step_peak_time(beta: Any, zeta: Any) -> Any:
    """Time of that first peak, π/β₁; None without overshoot (nan in an array)."""
    xp = of(beta, zeta)
    return xp.where(zeta >= 1.0, lambda: xp.missing, lambda: math.pi / damped_frequency(beta, zeta))


def step_envelope(t: Any, beta: Any, zeta: Any) -> Any:
    """Upper envelope of the step response, 1 + e^(-ζ·β·t) (seed 000 §8.1)."""
    return 1.0 + of(t, beta, zeta).exp(-zeta * beta * t)


# ------------------------------------------------------------- harmonic load


def magnification(ratio: Any, zeta: Any) -> Any:
    """Steady amplitude over static, 1/√((1 - r²)² + (2ζr)²), r = ω/β; inf at
    undamped resonance (the caller says "unbounded")."""
    xp = of(ratio, zeta)
    denominator = xp.hypot(1.0 - ratio * ratio, 2.0 * zeta * ratio)
    return xp.where(denominator == 0.0, lambda: math.inf, lambda: 1.0 / denominator)


def phase_lag(ratio: Any, zeta: Any) -> Any:
    """Phase of the steady response behind the load [rad], in [0, π]."""
    return of(ratio, zeta).atan2(2.0 * zeta * ratio, 1.0 - ratio * ratio)


def transmissibility(ratio: Any, zeta: Any) -> Any:
    """Force passed to the support over the exciting force, √(1 + (2ζr)²)·magnification."""
    return of(ratio, zeta).hypot(1.0, 2.0 * zeta * ratio) * magnification(ratio, zeta)


def resonance_peak(zeta: float) -> tuple[float, float]:
    """(r, magnification) at the peak of the amplitude curve: r = √(1 - 2ζ²) and
    1/(2ζ·√(1 - ζ²)); for ζ ≥ 1/√2 the curve falls from r = 0 (peak 1 there).
    Undamped: (1, inf). Floats only (a pair of regimes, not a grid)."""
    if zeta == 0.0:
        return 1.0, math.inf
    if 2.0 * zeta * zeta >= 1.0:
        return 0.0, 1.0
    return math.sqrt(1.0 - 2.0 * zeta * zeta), 1.0 / (2.0 * zeta * math.sqrt(1.0 - zeta * zeta))


# ------------------------------------------------- piecewise-linear loads (Duhamel)


@dataclass(frozen=True)
class Propagator:
    """Exact one-step map of x'' + 2ζβx' + β²x = β²·f with f linear over the step:
    z1 = Φ·z0 + Γ0·b·f0 + Γ1·b·s, z = (x, x'), s the load's slope, b = (0, β²)."""

    phi: tuple[float, float, float, float]
    gamma0: tuple[float, float]  # Γ0·b
    gamma1: tuple[float, float]  # Γ1·b

    @classmethod
    def of(cls, beta: float, zeta: float, h: float) -> Propagator:
        # e^{Ah} for the 2×2 A = [[0, 1], [-β², -2ζβ]] through its eigen-structure:
        # e^{Ah} = e^{μh}·(C·I + S·(A - μI)), μ = -ζβ, Δ = μ² - β².
        mu = -zeta * beta
        # √|μ² - β²| without squaring ζβ (which overflows far over critical damping)
        # and without the cancellation of μ² - β² near critical damping.
        if zeta > 1.0:
            delta, root = 1.0, beta * zeta * math.sqrt((1.0 - 1.0 / zeta) * (1.0 + 1.0 / zeta))
        elif zeta < 1.0:
            delta, root = -1.0, beta * math.sqrt((1.0 - zeta) * (1.0 + zeta))
        else:
            delta, root = 0.0, 0.0
        x = root * h
        if delta > 0.0 and x > 1e-8:
            # Over-damped: e^{μh}·cosh and e^{μh}·sinh from the two decay rates, so
            # that a heavily damped scene (μh and x past 700) does not overflow; the
            # slow rate in the form free of cancellation.
            slow, fast = -beta * beta / (zeta * beta + root), mu - root
            e_slow, e_fast = math.exp(slow * h), math.exp(fast * h)
            ec, es = 0.5 * (e_slow + e_fast), 0.5 * (e_slow - e_fast) / root
        else:
            if delta > 0.0:
                c, s = math.cosh(x), h * (1 + x * x / 6)
            elif delta < 0.0:
                c, s = math.cos(x), (math.sin(x) / root if x > 1e-8 else h * (1 - x * x / 6))
            else:
                c, s = 1.0, h
            e = math.exp(mu * h)
            ec, es = e * c, e * s
        a00, a01, a10, a11 = 0.0 - mu, 1.0, -beta * beta, -2.0 * zeta * beta - mu
        phi = (ec + es * a00, es * a01, es * a10, ec + es * a11)
        # A⁻¹ = [[-2ζβ, -1], [β², 0]]/β².
        inv = (-2.0 * zeta / beta, -1.0 / (beta * beta), 1.0, 0.0)

        def times_inverse(m: tuple[float, float, float, float], v: tuple[float, float]):
            w = (m[0] * v[0] + m[1] * v[1], m[2] * v[0] + m[3] * v[1])
            return (inv[0] * w[0] + inv[1] * w[1], inv[2] * w[0] + inv[3] * w[1])

        b = (0.0, beta * beta)
        # Γ0·b = A⁻¹(Φ - I)·b; Γ1·b = A⁻¹(Γ0·b - h·b).
        phi_minus_i = (phi[0] - 1.0, phi[1], phi[2], phi[3] - 1.0)
        g0 = times_inverse(phi_minus_i, b)
        g1 = times_inverse((1.0, 0.0, 0.0, 1.0), (g0[0] - h * b[0], g0[1] - h * b[1]))
        return cls(phi, g0, g1)

    def step(self, x: float, v: float, f0: float, slope: float) -> tuple[float, float]:
        p, g0, g1 = self.phi, self.gamma0, self.gamma1
        return (
            p[0] * x + p[1] * v + g0[0] * f0 + g1[0] * slope,
            p[2] * x + p[3] * v + g0[1] * f0 + g1[1] * slope,
        )


#: Steps that cover a segment's rest once its free motion has died away.
SETTLED_STEPS = 256


def _steps(span: float, h_max: float, settle: float) -> Iterator[tuple[float, float, float]]:
    """(start, length, end) of the steps over a segment of ``span``, times from its
    start: at most ``h_max`` long until ``settle``, then the rest in SETTLED_STEPS."""
    n = max(1, math.ceil(span / h_max))
    h = span / n
    fine = n if settle >= span else min(n, math.ceil(settle / h))
    if n - fine <= SETTLED_STEPS:
        fine = n  # nothing to gain: the uniform grid
    for k in range(fine):
        yield k * h, h, (k + 1) * h
    if fine < n:
        begin = fine * h
        rest = (span - begin) / SETTLED_STEPS
        for k in range(SETTLED_STEPS):
            yield (
                begin + k * rest,
                rest,
                (span if k == SETTLED_STEPS - 1 else begin + (k + 1) * rest),
            )


@dataclass(frozen=True)
class Response:
    """Sampled response to a piecewise-linear load and its largest |x| (refined
    between samples to machine precision)."""

    times: list[float]
    displacements: list[float]
    peak: float  # max |x| over the horizon, in units of the static response
    peak_time: float


def piecewise_linear_response(
    times: Sequence[float],
    loads: Sequence[float],
    beta: float,
    zeta: float,
    horizon: float,
    samples_per_period: int = 64,
) -> Response:
    """Exact response from rest to the load through the points (times, loads),
    held at its last value after the last point, up to ``horizon``.

    A repeated time is a jump (a rectangular pulse is 0, 0→1 at t0, 1→0 at t1).
    Samples are at most 1/``samples_per_period`` of a natural period apart; the
    largest |x| is refined by bisection on x' = 0 with the exact step.

    Once the free motion that a knot starts has died away (e^-40 of it left: the
    oscillation, or the fast mode of an over-damped system), the rest of the segment
    holds no extremum that coarse samples would miss (x' has at most one zero left),
    and the exact step covers it in SETTLED_STEPS steps: a stiff or heavily damped
    coupling under a long pulse takes milliseconds, not 10⁸ steps.
    """
    knots = list(zip(times, loads, strict=True))
    if knots[-1][0] < horizon:
        knots.append((horizon, knots[-1][1]))
    period = 2.0 * math.pi / beta
    h_max = period / samples_per_period
    t, x, v = knots[0][0], 0.0, 0.0
    out_t, out_x = [t], [x]
    best = (0.0, t)
    cache: dict[float, Propagator] = {}
    # How fast the free motion dies: the envelope e^{-ζβt}, or the fast mode of an
    # over-damped system, e^{-(ζβ + β√(ζ²-1))t}.
    decay = zeta * beta + (beta * math.sqrt(zeta * zeta - 1.0) if zeta > 1.0 else 0.0)
    settle = 40.0 / decay if decay > 0.0 else math.inf

    def propagate(x: float, v: float, f0: float, slope: float, h: float) -> tuple[float, float]:
        key = round(h, 15)
        if key not in cache:
            if len(cache) > 64:
                cache.clear()
            cache[key] = Propagator.of(beta, zeta, h)
        return cache[key].step(x, v, f0, slope)

    for (t0, f0), (t1, f1) in zip(knots, knots[1:], strict=False):
        span = min(t1, horizon) - t0
        if span <= 0.0:
            continue  # a jump: the load changes, the state does not
        slope = (f1 - f0) / (t1 - t0)
        for start, h, end in _steps(span, h_max, settle):
            f_start = f0 + slope * start
            x1, v1 = propagate(x, v, f_start, slope, h)
            if v * v1 < 0.0 or v1 == 0.0:  # an extremum of x inside the step
                low, high = 0.0, h
                for _ in range(80):
                    middle = 0.5 * (low + high)
                    _, vm = propagate(x, v, f_start, slope, middle)
                    low, high = (middle, high) if vm * v > 0.0 else (low, middle)
                xm, _ = propagate(x, v, f_start, slope, 0.5 * (low + high))
                if abs(xm) > best[0]:
                    best = (abs(xm), t + start + 0.5 * (low + high))
            x, v = x1, v1
            out_t.append(t0 + end)
            out_x.append(x)
            if abs(x) > best[0]:
                best = (abs(x), out_t[-1])
        t = t0 + span
        if t >= horizon:
            break
    return Response(out_t, out_x, best[0], best[1])
