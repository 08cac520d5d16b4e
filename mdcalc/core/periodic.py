"""Periodic steady state of a linear system under a periodic ramp load.

The system is M·x'' + C·x' + K·x = F + s·u(τ) with constant loads F, a load shape s
and a scalar excitation u that rises linearly over each period and jumps back at
its end: u(τ) = u₀ + u₁·τ for τ in [0, T) (a sawtooth; the impulse variator's Π″).
K must be invertible (the system is held to the ground or to a driver).

Three ways to the periodic state, each with its own error:

* :func:`exact_periodic` -- closed form. A linear load has the particular solution
  x = a + b·τ (K·b = s·u₁, K·a = F + s·u₀ - C·b); the rest is e^{Aτ}·d in the first-
  order form, with the periodicity (I - e^{AT})·d = (b, 0)·T solved mode by mode,
  dᵢ = T·(V⁻¹p)ᵢ/(1 - e^{λᵢT}). Exact up to the eigensolver's round-off; a mode with
  e^{λT} = 1 (an undamped resonance with a harmonic of the load) has no periodic
  state and raises :class:`Unbounded`.
* :func:`fourier_periodic` -- the static part plus K harmonics of the sawtooth,
  u - ū = -u₁·(T/π)·Σ sin(kΩτ)/k, each through the frequency response
  (K - k²Ω²M + ikΩC)⁻¹. The forcing's harmonics fall off as 1/k only, so a stiff
  system (natural frequencies far above Ω) needs many of them.
* :func:`ode_periodic` -- time integration by shooting: the period map of a
  linear system is affine, so one period integrated from 2n + 1 starts gives the
  periodic start, and one more period its maxima (events on the derivative).

Maxima of an observable w·(x, x') over a period come from samples that resolve the
fastest mode, refined by bisection on the derivative (:func:`periodic_maximum`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

#: Samples per period of the fastest mode when searching for a maximum.
SAMPLES_PER_MODE_PERIOD = 16
MAX_SAMPLES = 2**20
#: solve_ivp methods that take a Jacobian.
IMPLICIT = ("Radau", "BDF", "LSODA")


class Unbounded(ArithmeticError):
    """No periodic state: an undamped mode in resonance with a harmonic of the load."""


class Unresolved(ArithmeticError):
    """A scene outside what the closed form resolves to 8 digits (modes spread too
    wide, or one mode far slower than the load); the message says which."""


@dataclass(frozen=True)
class RampSystem:
    mass: np.ndarray  # M, n×n [kg·m²]
    damping: np.ndarray  # C, n×n [N·m·s/rad]
    stiffness: np.ndarray  # K, n×n [N·m/rad]
    constant: np.ndarray  # F, n [N·m]
    shape: np.ndarray  # s, n: load per unit of u [N·m per unit of u]
    start: float  # u₀ = u(0⁺)
    slope: float  # u₁ = du/dτ [unit of u per s]
    period: float  # T [s]

    @property
    def size(self) -> int:
        return len(self.constant)

    @property
    def mean_excitation(self) -> float:
        """ū = u₀ + u₁·T/2."""
        return self.start + 0.5 * self.slope * self.period

    def static(self) -> np.ndarray:
        """Mean position x̄ = K⁻¹·(F + s·ū)."""
        return np.linalg.solve(self.stiffness, self.constant + self.shape * self.mean_excitation)

    def first_order(self) -> np.ndarray:
        """A of y' = A·y + g for y = (x, x')."""
        n = self.size
        inverse = np.linalg.inv(self.mass)
        a = np.zeros((2 * n, 2 * n))
        a[:n, n:] = np.eye(n)
        a[n:, :n] = -inverse @ self.stiffness
        a[n:, n:] = -inverse @ self.damping
        return a

    def load(self, tau: float) -> np.ndarray:
        """g(τ) of y' = A·y + g(τ), τ in [0, T)."""
        n = self.size
        g = np.zeros(2 * n)
        force = self.constant + self.shape * (self.start + self.slope * tau)
        g[n:] = np.linalg.solve(self.mass, force)
        return g


Observable = np.ndarray  # w, 2n: the quantity w·(x, x')


# ----------------------------------------------------------------- closed form


@dataclass(frozen=True)
class Periodic:
    """The exact periodic state: y(τ) = p₀ + p₁·τ + Re Σ Vᵢ·dᵢ·e^{λᵢτ}."""

    period: float
    eigenvalues: np.ndarray  # λ, 2n complex
    vectors: np.ndarray  # V, 2n×2n complex
    coefficients: np.ndarray  # d in modal coordinates, 2n complex
    p0: np.ndarray
    p1: np.ndarray

    def observe(self, w: Observable, tau: np.ndarray) -> np.ndarray:
        weights = (w @ self.vectors) * self.coefficients
        modal = np.exp(np.outer(tau, self.eigenvalues)) @ weights
        return float(w @ self.p0) + float(w @ self.p1) * tau + modal.real

    def rate(self, w: Observable, tau: np.ndarray) -> np.ndarray:
        weights = (w @ self.vectors) * self.coefficients * self.eigenvalues
        return float(w @ self.p1) + (np.exp(np.outer(tau, self.eigenvalues)) @ weights).real

    def states(self, tau: np.ndarray) -> np.ndarray:
        modal = (np.exp(np.outer(tau, self.eigenvalues)) * self.coefficients) @ self.vectors.T
        return self.p0 + np.outer(tau, self.p1) + modal.real

    @property
    def fastest(self) -> float:
        """Largest |λ| [1/s]."""
        return float(np.max(np.abs(self.eigenvalues)))


def exact_periodic(system: RampSystem) -> Periodic:
    n, t = system.size, system.period
    k, c = system.stiffness, system.damping
    b = np.linalg.solve(k, system.shape * system.slope)
    a = np.linalg.solve(k, system.constant + system.shape * system.start - c @ b)
    p0, p1 = np.concatenate([a, b]), np.concatenate([b, np.zeros(n)])
    eigenvalues, vectors = np.linalg.eig(system.first_order())
    if np.linalg.cond(vectors) > 1e12:
        magnitudes = np.abs(eigenvalues)
        raise Unresolved(
            f"the modes cannot be separated (|λ| from {np.min(magnitudes):.3g} to "
            f"{np.max(magnitudes):.3g} 1/s, or a mode damped exactly critically): "
            "outside the range the closed form solves"
        )
    # The particular solution holds K⁻¹: a mode much slower than the load (|λ|T ≪ 1)
    # makes it and the modal part cancel, losing about ε/(λT)² of the result.
    slow = float(np.min(np.abs(eigenvalues))) * t
    if slow < 1.5e-4:  # ε/(λT)² > 1e-8
        raise Unresolved(
            f"a mode at {float(np.min(np.abs(eigenvalues))):.3g} rad/s is "
            f"{2.0 * math.pi / max(slow, 1e-300):.3g} times slower than the load's "
            f"fundamental {2.0 * math.pi / t:.6g} rad/s: the system is as good as free, "
            "and the closed form would lose more than 8 digits; outside the range solved"
        )
    # 1 - e^{λT} by expm1: a mode much slower than the load (λT → 0) has a large
    # but finite periodic part; only e^{λT} = 1 with λT ≠ 0 (λT = 2πim) is a resonance
    gap = -np.expm1(eigenvalues * t)
    # λT carries a round-off of about ε·|λT|: compare the gap with that, not with 0
    turns = np.abs(eigenvalues * t)
    resonant = (np.abs(gap) <= 1e-12 * np.maximum(1.0, turns)) & (turns > math.pi)
    if np.any(resonant):
        index = int(np.argmax(resonant))
        order = abs(eigenvalues[index].imag) * t / (2.0 * math.pi)
        raise Unbounded(
            f"undamped resonance: a natural frequency {abs(eigenvalues[index].imag):.6g} rad/s "
            f"is {order:.0f} × the excitation's fundamental {2.0 * math.pi / t:.6g} rad/s; "
            "the periodic amplitude is unbounded"
        )
    coefficients = t * np.linalg.solve(vectors, p1.astype(complex)) / gap
    return Periodic(t, eigenvalues, vectors, coefficients, p0, p1)


# --------------------------------------------------------------------- Fourier


@dataclass(frozen=True)
class FourierSeries:
    """x̄ plus K harmonics: w·y(τ) = w·ȳ + Σ Im(zₖ(w)·e^{ikΩτ})."""

    period: float
    mean: np.ndarray  # ȳ = (x̄, 0)
    responses: np.ndarray  # K × 2n complex: per unit of sin(kΩτ) forcing, (X, ikΩX)·cₖ

    @property
    def harmonics(self) -> int:
        return len(self.responses)

    def _z(self, w: Observable) -> np.ndarray:
        return self.responses @ w

    def observe(self, w: Observable, tau: np.ndarray) -> np.ndarray:
        omega = 2.0 * math.pi / self.period
        k = np.arange(1, self.harmonics + 1)
        phases = np.exp(1j * omega * np.outer(tau, k))
        return float(w @ self.mean) + (phases @ self._z(w)).imag

    def rate(self, w: Observable, tau: np.ndarray) -> np.ndarray:
        omega = 2.0 * math.pi / self.period
        k = np.arange(1, self.harmonics + 1)
        phases = np.exp(1j * omega * np.outer(tau, k))
        return (phases @ (self._z(w) * 1j * omega * k)).imag

    def sampled(self, w: Observable, samples: int) -> np.ndarray:
        """w·y at τ = jT/N by one inverse FFT (N > 2K)."""
        spectrum = np.zeros(samples, dtype=complex)
        spectrum[1 : self.harmonics + 1] = self._z(w)
        return float(w @ self.mean) + (samples * np.fft.ifft(spectrum)).imag


def fourier_periodic(system: RampSystem, harmonics: int) -> FourierSeries:
    n, t = system.size, system.period
    omega = 2.0 * math.pi / t
    k = np.arange(1, harmonics + 1)
    w = omega * k
    matrices = (
        system.stiffness[None, :, :]
        - (w * w)[:, None, None] * system.mass[None, :, :]
        + 1j * w[:, None, None] * system.damping[None, :, :]
    )
    # u - ū = -u₁·(T/π)·Σ sin(kΩτ)/k
    amplitudes = -system.slope * t / (math.pi * k)
    loads = np.broadcast_to(system.shape.astype(complex), (harmonics, n))
    x = np.linalg.solve(matrices, loads[:, :, None])[:, :, 0] * amplitudes[:, None]
    responses = np.concatenate([x, 1j * w[:, None] * x], axis=1)
    mean = np.concatenate([system.static(), np.zeros(n)])
    return FourierSeries(t, mean, responses)


# --------------------------------------------------------------------- maxima


@dataclass(frozen=True)
class PeriodicMaximum:
    value: float
    time: float  # τ in [0, T) where it occurs [s]
    samples: int
    resolved: bool  # False: the fastest mode had fewer than 16 samples per period


def samples_for(period: float, fastest: float) -> tuple[int, bool]:
    """Samples per load period that give every mode of |λ| ≤ ``fastest`` 16 samples
    per its period (a power of two, at least 256, at most 2²⁰)."""
    wanted = SAMPLES_PER_MODE_PERIOD * fastest * period / (2.0 * math.pi)
    samples = 256
    while samples < wanted and samples < MAX_SAMPLES:
        samples *= 2
    return samples, samples >= wanted


def periodic_maximum(
    observe: Callable[[np.ndarray], np.ndarray],
    rate: Callable[[np.ndarray], np.ndarray],
    period: float,
    samples: int,
    sampled: np.ndarray | None = None,
    candidates: int = 4096,
) -> tuple[float, float]:
    """Largest value of a smooth periodic function over [0, T).

    Every sampled local maximum within reach of the best sample is refined, all at
    once, by bisection on the derivative between its neighbours (times taken modulo
    T: the state is continuous across the period's end). With 16 samples per period
    of the fastest mode a sample lies at most 1 - cos(π/16) ≈ 2 % of that mode's
    amplitude below its peak, so peaks more than 5 % of the sampled range below the
    best cannot win; when many ringing peaks tie, all of them are refined (up to
    ``candidates``, the largest first)."""
    tau = np.arange(samples) * (period / samples)
    values = observe(tau) if sampled is None else sampled
    left, right = np.roll(values, 1), np.roll(values, -1)
    peaks = np.flatnonzero((values >= left) & (values >= right))
    top = int(np.argmax(values))
    if len(peaks) == 0:  # flat: every sample ties
        peaks = np.array([top])
    margin = 0.05 * float(np.max(values) - np.min(values))
    peaks = peaks[values[peaks] >= values[top] - margin]
    peaks = peaks[np.argsort(values[peaks])[::-1][:candidates]]
    best_value, best_time = float(values[top]), float(tau[top])
    h = period / samples
    low, high = tau[peaks] - h, tau[peaks] + h
    inside = (rate(low % period) > 0.0) & (rate(high % period) < 0.0)
    low, high = low[inside], high[inside]
    if len(low) == 0:
        return best_value, best_time
    for _ in range(40):  # the bracket shrinks to 2⁻⁴⁰ of a sample step
        middle = 0.5 * (low + high)
        rising = rate(middle % period) > 0.0
        low, high = np.where(rising, middle, low), np.where(rising, high, middle)
    middle = (0.5 * (low + high)) % period
    refined = observe(middle)
    k = int(np.argmax(refined))
    if float(refined[k]) > best_value:
        best_value, best_time = float(refined[k]), float(middle[k])
    return best_value, best_time


def maximum_of(
    solution: Periodic | FourierSeries, w: Observable, fastest: float
) -> PeriodicMaximum:
    """Maximum of w·y over a period of an exact or Fourier periodic state."""
    samples, resolved = samples_for(solution.period, fastest)
    sampled = None
    if isinstance(solution, FourierSeries):
        while samples <= 2 * solution.harmonics:
            samples *= 2
        sampled = solution.sampled(w, samples)
    # a Fourier series costs K complex exponentials per point: a long series refines
    # fewer candidates (it is never the reference; a missed peak is part of its error)
    candidates = 4096
    if isinstance(solution, FourierSeries):
        candidates = max(16, min(4096, 20_000 // solution.harmonics))
    value, time = periodic_maximum(
        lambda tau: solution.observe(w, tau),
        lambda tau: solution.rate(w, tau),
        solution.period,
        samples,
        sampled,
        candidates,
    )
    return PeriodicMaximum(value, time, samples, resolved)


# ------------------------------------------------------------------------ ODE


@dataclass(frozen=True)
class OdePeriodic:
    maxima: list[float]  # per observable, over the periodic state's period
    evaluations: int


def ode_periodic(
    system: RampSystem,
    observables: list[Observable],
    rtol: float,
    method: str,
) -> OdePeriodic:
    """Periodic state by shooting: the period map of a linear system is affine,
    y(T) = Φ·y(0) + γ. One integration over a period from y = 0 (γ) and from the
    2n unit states (the columns of Φ) gives the periodic start from
    (I - Φ)·y₀ = γ; one more period from y₀ gives the maxima, from events on the
    derivative of each observable. No transient has to die out: lightly damped
    and undamped systems cost the same."""
    from mdcalc.core.ode import advance

    a = system.first_order()
    t = system.period
    n2 = 2 * system.size
    g0, g1 = system.load(0.0), system.load(t) - system.load(0.0)
    g1 = g1 / t

    def bundle(tau: float, z: np.ndarray) -> np.ndarray:
        columns = a @ z.reshape(n2, n2 + 1)
        columns[:, 0] += g0 + g1 * tau
        return columns.ravel()

    # the response's scale: the static part, or the swing of the ramp's own part
    swing = np.linalg.solve(system.stiffness, system.shape * system.start)
    scale = max(float(np.max(np.abs(system.static()))), float(np.max(np.abs(swing))), 1e-300)
    # the forced column is on the scale of the response, the unit columns on 1
    atol = np.tile(np.concatenate([[scale], np.ones(n2)]), n2) * rtol * 1e-3
    starts = np.zeros((n2, n2 + 1))
    starts[:, 1:] = np.eye(n2)
    jac = np.kron(a, np.eye(n2 + 1)) if method in IMPLICIT else None
    segment = advance(bundle, 0.0, starts.ravel(), t, rtol=rtol, atol=atol, method=method, jac=jac)
    end = segment.y.reshape(n2, n2 + 1)
    gamma, phi = end[:, 0], end[:, 1:]
    y0 = np.linalg.solve(np.eye(n2) - phi, gamma)

    def rhs(tau: float, y: np.ndarray) -> np.ndarray:
        return a @ y + g0 + g1 * tau

    watch = [(_rate_event(a, g0, g1, w), -1) for w in observables]
    last = advance(
        rhs,
        0.0,
        y0,
        t,
        rtol=rtol,
        atol=scale * rtol * 1e-3,
        method=method,
        watch=watch,
        jac=a if method in IMPLICIT else None,
    )
    maxima = [max(float(w @ y0), float(w @ last.y)) for w in observables]
    for index, _time, state in last.hits:
        maxima[index] = max(maxima[index], float(observables[index] @ state))
    return OdePeriodic(maxima, segment.nfev + last.nfev)


def _rate_event(
    a: np.ndarray, g0: np.ndarray, g1: np.ndarray, w: Observable
) -> Callable[[float, np.ndarray], float]:
    def event(tau: float, y: np.ndarray) -> float:
        return float(w @ (a @ y + g0 + g1 * tau))

    return event
