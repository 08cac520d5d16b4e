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
* :func:`~mdcalc.core.periodic_ode.ode_periodic` (its own module) -- time
  integration by shooting: the period map of a linear system is affine, so one
  period integrated from 2n + 1 starts gives the periodic start, and one more
  period its maxima (events on the derivative).

Maxima of an observable w·(x, x') over a period come from samples that resolve the
fastest mode, refined by regula falsi on the derivative (:func:`periodic_maximum`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

#: Regula falsi (Illinois) steps that locate a sampled peak on its slope.
REGULA_FALSI_STEPS = 16
#: Samples per period of the fastest mode when searching for a maximum.
SAMPLES_PER_MODE_PERIOD = 16
MAX_SAMPLES = 2**20


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
    start: Any  # u₀ = u(0⁺) (a float; in a block, one per row)
    slope: Any  # u₁ = du/dτ [unit of u per s]
    period: Any  # T [s]

    @property
    def size(self) -> int:
        return int(np.shape(self.constant)[-1])

    @property
    def mean_excitation(self) -> float:
        """ū = u₀ + u₁·T/2."""
        return self.start + 0.5 * self.slope * self.period

    def static(self) -> np.ndarray:
        """Mean position x̄ = K⁻¹·(F + s·ū)."""
        return np.linalg.solve(self.stiffness, self.constant + self.shape * self.mean_excitation)

    def first_order(self) -> np.ndarray:
        """A of y' = A·y + g for y = (x, x') (one per row of a block: leading axes)."""
        n = self.size
        inverse = np.linalg.inv(self.mass)
        a = np.zeros((*np.shape(self.mass)[:-2], 2 * n, 2 * n))
        a[..., :n, n:] = np.eye(n)
        a[..., n:, :n] = -inverse @ self.stiffness
        a[..., n:, n:] = -inverse @ self.damping
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

    def block(self) -> PeriodicBlock:
        """This state as a block of one."""
        return PeriodicBlock(
            np.array([self.period]),
            self.eigenvalues[None],
            self.vectors[None],
            self.coefficients[None],
            self.p0[None],
            self.p1[None],
            np.array([SOLVED]),
        )


#: Why a row of a block has no exact periodic state (SOLVED: it has one).
SOLVED, UNSEPARATED, AS_GOOD_AS_FREE, RESONANT = 0, 1, 2, 3


@dataclass(frozen=True)
class PeriodicBlock:
    """The exact periodic states of a block of systems, one per row (a study's
    samples; a single scene is a block of one). ``failure`` says which rows have none
    and why; their other numbers mean nothing."""

    period: np.ndarray  # T, (m,)
    eigenvalues: np.ndarray  # λ, (m, 2n) complex
    vectors: np.ndarray  # V, (m, 2n, 2n) complex
    coefficients: np.ndarray  # d, (m, 2n) complex
    p0: np.ndarray  # (m, 2n)
    p1: np.ndarray  # (m, 2n)
    failure: np.ndarray  # (m,) SOLVED, UNSEPARATED, AS_GOOD_AS_FREE or RESONANT

    @property
    def fastest(self) -> np.ndarray:
        """Largest |λ| of each row [1/s]."""
        return np.max(np.abs(self.eigenvalues), axis=-1)

    def row(self, i: int) -> Periodic:
        """Row i's state; raises :class:`Unresolved` or :class:`Unbounded` with the
        reason when it has none."""
        if self.failure[i] != SOLVED:
            raise _failure(int(self.failure[i]), self.eigenvalues[i], float(self.period[i]))
        return Periodic(
            float(self.period[i]),
            self.eigenvalues[i],
            self.vectors[i],
            self.coefficients[i],
            self.p0[i],
            self.p1[i],
        )

    def maxima(
        self, w: Observable, fastest: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Largest w·y over a period of each row (``w``: (2n,) or one per row): values,
        times, samples per period and whether they resolve the fastest mode (each
        row's own, or ``fastest``). NaN where a row has no state. Rows are sampled
        in groups of one sample count and in parts of at most :data:`BLOCK_CELLS`
        complex exponentials."""
        m, width = self.p0.shape
        w = np.broadcast_to(np.asarray(w, dtype=float), (m, width))
        lam = self.eigenvalues
        weights = (w[:, None, :] @ self.vectors)[:, 0, :] * self.coefficients
        slopes = weights * lam
        level, drift = np.sum(w * self.p0, axis=-1), np.sum(w * self.p1, axis=-1)

        def observe(rows: np.ndarray, tau: np.ndarray) -> np.ndarray:
            modal = np.exp(tau[..., None] * lam[rows][:, None, :]) * weights[rows][:, None, :]
            return level[rows][:, None] + drift[rows][:, None] * tau + modal.sum(axis=-1).real

        kept: list[Any] = [None, None]  # the last rows asked and their numbers

        def rate(rows: np.ndarray, tau: np.ndarray) -> np.ndarray:
            if kept[0] is not rows:  # the refinement asks about the same rows each step
                kept[:] = [rows, (lam[rows][:, None, :], slopes[rows][:, None, :], drift[rows])]
            lam_rows, slope_rows, drift_rows = kept[1]
            modal = np.exp(tau[..., None] * lam_rows) * slope_rows
            return drift_rows[:, None] + modal.sum(axis=-1).real

        samples, resolved = _samples(self.period, self.fastest if fastest is None else fastest)
        values, times = np.full(m, math.nan), np.full(m, math.nan)
        solved = self.failure == SOLVED
        for count in np.unique(samples[solved]):
            group = np.flatnonzero(solved & (samples == count))
            parts = max(1, -(-len(group) * int(count) * width // BLOCK_CELLS))
            for rows in np.array_split(group, parts):
                h = self.period[rows] / count
                grid = _grid(level[rows], drift[rows], weights[rows], lam[rows], h, int(count))
                values[rows], times[rows] = periodic_maxima(
                    observe, rate, self.period[rows], int(count), rows, grid
                )
        return values, times, samples, resolved


#: Samples a run of powers of e^{λh} covers between exact exponentials.
RUN = 32


def _grid(
    level: np.ndarray,
    drift: np.ndarray,
    weights: np.ndarray,
    lam: np.ndarray,
    h: np.ndarray,
    count: int,
) -> np.ndarray:
    """level + drift·jh + Re Σᵢ wᵢ·e^{λᵢ·jh} for j = 0 … count - 1 of each row: an
    exact exponential at every :data:`RUN`-th sample, times the powers of e^{λh}
    between (a product per sample, not an exponential; round-off grows to about
    RUN·ε of the modal part). With j = m·RUN + r, each run of a row is one small
    matrix product: its anchors' factors (w·e^{λ·mRUN·h} in real and imaginary
    parts, the level and drift there, the drift's step) by the run's (the powers'
    parts, 1, r)."""
    k, width = lam.shape
    run = min(RUN, count)
    # A conjugate pair of modes (eig gives them side by side) sums to twice the real
    # part of the first: its partner is not evaluated (to the round-off of the
    # partner's weight, which is the first's conjugate up to it)
    weights = weights.copy()
    taken = np.zeros(k, dtype=bool)
    skipped = np.zeros(width, dtype=bool)
    for i in range(width - 1):
        pair = ~taken & (lam[:, i + 1] == np.conj(lam[:, i])) & (lam[:, i].imag != 0.0)
        weights[:, i] = np.where(pair, 2.0 * weights[:, i], weights[:, i])
        weights[:, i + 1] = np.where(pair, 0.0, weights[:, i + 1])
        taken = pair
        skipped[i + 1] = bool(np.all(pair))
    used = np.flatnonzero(~skipped)
    lam, weights = lam[:, used], weights[:, used]
    step = np.exp(h[:, None] * lam)
    powers = np.ones((k, run, len(used)), dtype=complex)
    powers[:, 1:] = step[:, None, :]
    powers = np.cumprod(powers, axis=1)
    start = np.arange(0, count, run) * h[:, None]  # (k, M): the anchors' times
    anchors = np.exp(start[..., None] * lam[:, None, :]) * weights[:, None, :]
    factors = np.concatenate(
        [
            anchors.real,
            -anchors.imag,
            (level[:, None] + drift[:, None] * start)[..., None],
            np.broadcast_to((drift * h)[:, None, None], start.shape + (1,)),
        ],
        axis=2,
    )
    runs = np.concatenate(
        [
            powers.real,
            powers.imag,
            np.ones((k, run, 1)),
            np.broadcast_to(np.arange(run, dtype=float)[None, :, None], (k, run, 1)),
        ],
        axis=2,
    )
    return (factors @ runs.transpose(0, 2, 1)).reshape(k, count)


#: Complex exponentials evaluated at once when a block of states is sampled.
BLOCK_CELLS = 2**21


def exact_block(system: RampSystem, size: int = 1) -> PeriodicBlock:
    """The closed form for every row of a block of ``size`` rows (a
    :class:`RampSystem` whose arrays carry one leading axis of rows, or none where
    a number is shared by every row)."""
    n = system.size
    m = np.broadcast_shapes(
        np.shape(system.mass)[:-2],
        np.shape(system.damping)[:-2],
        np.shape(system.stiffness)[:-2],
        np.shape(system.constant)[:-1],
        np.shape(system.shape)[:-1],
        np.shape(system.start),
        np.shape(system.slope),
        np.shape(system.period),
        (size,),
    )[0]

    def rows(x: Any, tail: tuple[int, ...]) -> np.ndarray:
        return np.broadcast_to(np.asarray(x, dtype=float), (m, *tail))

    k, c = rows(system.stiffness, (n, n)), rows(system.damping, (n, n))
    shape, t = rows(system.shape, (n,)), rows(system.period, ())
    mass, constant = rows(system.mass, (n, n)), rows(system.constant, (n,))
    start, slope = rows(system.start, ()), rows(system.slope, ())
    # a row with a number that is not finite has no state; it must not sink the
    # block's batched solves (a harmless system stands in for it)
    broken = ~(
        np.all(np.isfinite(k), axis=(1, 2))
        & np.all(np.isfinite(c), axis=(1, 2))
        & np.all(np.isfinite(mass), axis=(1, 2))
        & np.all(np.isfinite(shape), axis=1)
        & np.all(np.isfinite(constant), axis=1)
        & np.isfinite(t)
        & (t > 0.0)
        & np.isfinite(start)
        & np.isfinite(slope)
    )
    if broken.any():
        eye, zero = np.eye(n), np.zeros(n)
        k, c, mass = (np.where(broken[:, None, None], eye, x) for x in (k, c, mass))
        shape, constant = (np.where(broken[:, None], zero, x) for x in (shape, constant))
        t = np.where(broken, 1.0, t)
        start, slope = np.where(broken, 0.0, start), np.where(broken, 0.0, slope)
    b = np.linalg.solve(k, (shape * slope[:, None])[..., None])[..., 0]
    force = constant + shape * start[:, None]
    a = np.linalg.solve(k, (force - (c @ b[..., None])[..., 0])[..., None])[..., 0]
    p0 = np.concatenate([a, b], axis=-1)
    p1 = np.concatenate([b, np.zeros((m, n))], axis=-1)
    first = replace(system, mass=mass, damping=c, stiffness=k).first_order()
    eigenvalues, vectors = np.linalg.eig(first)
    # complex throughout: an overdamped block's are all real, and numpy says so
    eigenvalues, vectors = eigenvalues.astype(complex), vectors.astype(complex)
    failure = np.where(broken, UNSEPARATED, SOLVED)
    # the 1-norm condition (an inverse; the 2-norm's SVD cost three times as much)
    with np.errstate(all="ignore"):
        failure[~(np.linalg.cond(vectors, 1) <= 1e12)] = UNSEPARATED
    # The particular solution holds K⁻¹: a mode much slower than the load (|λ|T ≪ 1)
    # makes it and the modal part cancel, losing about ε/(λT)² of the result.
    slow = np.min(np.abs(eigenvalues), axis=-1) * t
    failure[(failure == SOLVED) & (slow < 1.5e-4)] = AS_GOOD_AS_FREE  # ε/(λT)² > 1e-8
    # 1 - e^{λT} by expm1: a mode much slower than the load (λT → 0) has a large
    # but finite periodic part; only e^{λT} = 1 with λT ≠ 0 (λT = 2πim) is a resonance
    gap = -np.expm1(eigenvalues * t[:, None])
    failure[(failure == SOLVED) & np.any(_resonant(gap, eigenvalues * t[:, None]), axis=-1)] = (
        RESONANT
    )
    solved = failure == SOLVED
    vectors = np.where(solved[:, None, None], vectors, np.eye(2 * n))  # no singular solve
    gap = np.where(solved[:, None], gap, 1.0)
    modal = np.linalg.solve(vectors, p1.astype(complex)[..., None])[..., 0]
    return PeriodicBlock(t, eigenvalues, vectors, t[:, None] * modal / gap, p0, p1, failure)


def _resonant(gap: np.ndarray, turns: np.ndarray) -> np.ndarray:
    """e^{λT} = 1 to round-off with λT ≠ 0: λT carries a round-off of about
    ε·|λT|, so the gap is compared with that, not with 0."""
    turns = np.abs(turns)
    return (np.abs(gap) <= 1e-12 * np.maximum(1.0, turns)) & (turns > math.pi)


def _failure(code: int, eigenvalues: np.ndarray, t: float) -> ArithmeticError:
    magnitudes = np.abs(eigenvalues)
    if code == UNSEPARATED:
        return Unresolved(
            f"the modes cannot be separated (|λ| from {np.min(magnitudes):.3g} to "
            f"{np.max(magnitudes):.3g} 1/s, or a mode damped exactly critically): "
            "outside the range the closed form solves"
        )
    if code == AS_GOOD_AS_FREE:
        slow = float(np.min(magnitudes)) * t
        return Unresolved(
            f"a mode at {float(np.min(magnitudes)):.3g} rad/s is "
            f"{2.0 * math.pi / max(slow, 1e-300):.3g} times slower than the load's "
            f"fundamental {2.0 * math.pi / t:.6g} rad/s: the system is as good as free, "
            "and the closed form would lose more than 8 digits; outside the range solved"
        )
    index = int(np.argmax(_resonant(-np.expm1(eigenvalues * t), eigenvalues * t)))
    order = abs(eigenvalues[index].imag) * t / (2.0 * math.pi)
    return Unbounded(
        f"undamped resonance: a natural frequency {abs(eigenvalues[index].imag):.6g} rad/s "
        f"is {order:.0f} × the excitation's fundamental {2.0 * math.pi / t:.6g} rad/s; "
        "the periodic amplitude is unbounded"
    )


def exact_periodic(system: RampSystem) -> Periodic:
    """The closed form of one system: a block of one."""
    batch = replace(
        system,
        mass=system.mass[None],
        damping=system.damping[None],
        stiffness=system.stiffness[None],
        constant=system.constant[None],
        shape=system.shape[None],
        start=np.array([system.start]),
        slope=np.array([system.slope]),
        period=np.array([system.period]),
    )
    return exact_block(batch).row(0)


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
    samples, resolved = _samples(np.array([period]), np.array([fastest]))
    return int(samples[0]), bool(resolved[0])


def _samples(period: np.ndarray, fastest: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`samples_for` of every row: the least power of two from 256 to 2²⁰ at or
    above the wanted count."""
    wanted = SAMPLES_PER_MODE_PERIOD * fastest * period / (2.0 * math.pi)
    wanted = np.where(np.isfinite(wanted), wanted, 0.0)  # (a row without a state)
    with np.errstate(all="ignore"):
        power = np.ceil(np.log2(np.clip(wanted, 256.0, float(MAX_SAMPLES))))
    samples = np.exp2(power)
    # log2 rounds: one step up or down where it missed the least power of two
    samples = np.where((samples < wanted) & (samples < MAX_SAMPLES), 2.0 * samples, samples)
    samples = np.where((0.5 * samples >= wanted) & (samples > 256), 0.5 * samples, samples)
    return samples.astype(np.int64), samples >= wanted


def periodic_maximum(
    observe: Callable[[np.ndarray], np.ndarray],
    rate: Callable[[np.ndarray], np.ndarray],
    period: float,
    samples: int,
    sampled: np.ndarray | None = None,
    candidates: int = 4096,
) -> tuple[float, float]:
    """Largest value of one smooth periodic function over [0, T): :func:`periodic_maxima`
    on a block of one."""
    values, times = periodic_maxima(
        lambda rows, tau: observe(tau.ravel()).reshape(tau.shape),
        lambda rows, tau: rate(tau.ravel()).reshape(tau.shape),
        np.array([period]),
        samples,
        np.array([0]),
        None if sampled is None else sampled[None, :],
        candidates,
    )
    return float(values[0]), float(times[0])


Sampler = Callable[[np.ndarray, np.ndarray], np.ndarray]  # (rows (k,), τ (k, s)) -> (k, s)


def periodic_maxima(
    observe: Sampler,
    rate: Sampler,
    period: np.ndarray,
    samples: int,
    rows: np.ndarray,
    sampled: np.ndarray | None = None,
    candidates: int = 4096,
) -> tuple[np.ndarray, np.ndarray]:
    """Largest value of a smooth periodic function over [0, T) for each of a block
    of rows (``rows`` names them to ``observe`` and ``rate``): values and times.

    Every sampled local maximum within reach of the best sample is refined, all at
    once, by regula falsi on the derivative between its neighbours (times taken
    modulo T: the state is continuous across the period's end). With 16 samples per
    period of the fastest mode a sample lies at most 1 - cos(π/16) ≈ 2 % of that
    mode's amplitude below its peak, so peaks more than 5 % of the sampled range below the
    best cannot win; when many ringing peaks tie, all of them are refined (up to
    ``candidates`` a row, the largest first)."""
    line = np.arange(len(rows))
    step = period / samples
    if sampled is None:
        values = observe(rows, np.arange(samples)[None, :] * step[:, None])
    else:
        values = sampled
    top = np.argmax(values, axis=1)  # a local maximum of its row, or a row of NaN
    best_value, best_time = values[line, top], top * step
    margin = 0.05 * (best_value - np.min(values, axis=1))
    # the samples within reach of the best (few: one comparison and a flat search),
    # then the local maxima among them, neighbours taken across the period's end
    near = np.flatnonzero(values >= (best_value - margin)[:, None])
    owner, where = np.divmod(near, samples)
    here = values.ravel()[near]
    peak = (here >= values[owner, (where - 1) % samples]) & (
        here >= values[owner, (where + 1) % samples]
    )
    owner, where, here = owner[peak], where[peak], here[peak]
    crowded = np.flatnonzero(np.bincount(owner, minlength=len(rows)) > candidates)
    if crowded.size:  # many ringing ties: a row's largest ``candidates``
        keep = np.ones(len(owner), dtype=bool)
        for i in crowded:
            found = np.flatnonzero(owner == i)
            keep[found] = False
            keep[found[np.argsort(here[found])[::-1][:candidates]]] = True
        owner, where = owner[keep], where[keep]
    h, p = step[owner], period[owner]
    low, high = where * h - h, where * h + h

    who = rows[owner]  # one array for the calls that follow (a sampler may keep its rows)

    def slope(at: np.ndarray) -> np.ndarray:
        return rate(who, (at % p)[:, None])[:, 0]

    g_low, g_high = slope(low), slope(high)
    inside = (g_low > 0.0) & (g_high < 0.0)
    owner, low, high, p = owner[inside], low[inside], high[inside], p[inside]
    g_low, g_high = g_low[inside], g_high[inside]
    who = rows[owner]
    if len(owner) == 0:
        return best_value, best_time
    # The slope's root by regula falsi, Illinois' way (the end that stays twice has
    # its slope halved): superlinear, a rate evaluation a step, and never outside
    # the bracket; from a bracket of two sample steps 16 steps reach the rounding.
    # A candidate leaves once its slope is within 1e-12 of its bracket's end slopes
    # (about 5 steps): its time is then off by about 1e-12 of a sample step, and its
    # value by the square of that (those left take the rest of the steps).
    done = np.empty(len(owner))  # each candidate's time
    active = np.arange(len(owner))
    settled_at = 1e-12 * np.maximum(g_low, -g_high)
    was_up = np.zeros(len(owner), dtype=bool)  # the last step moved the low end
    was_down = np.zeros(len(owner), dtype=bool)  # ... the high end
    for _ in range(REGULA_FALSI_STEPS):
        with np.errstate(all="ignore"):
            middle = high - g_high * (high - low) / (g_high - g_low)
        middle = np.where(np.isfinite(middle), np.clip(middle, low, high), low)
        g = slope(middle)
        settled = np.abs(g) <= settled_at
        if settled.any():
            done[active[settled]] = middle[settled]
            go = ~settled
            active, middle, g, low, high = active[go], middle[go], g[go], low[go], high[go]
            g_low, g_high, was_up, was_down = g_low[go], g_high[go], was_up[go], was_down[go]
            settled_at, p, who = settled_at[go], p[go], who[go]
            if not active.size:
                break
        up = g > 0.0
        g_high = np.where(up & was_up, 0.5 * g_high, g_high)  # the high end kept twice
        g_low = np.where(~up & was_down, 0.5 * g_low, g_low)  # the low end kept twice
        low, g_low = np.where(up, middle, low), np.where(up, g, g_low)
        high, g_high = np.where(up, high, middle), np.where(up, g_high, g)
        was_up, was_down = up, ~up
    done[active] = np.where(np.abs(g_low) <= np.abs(g_high), low, high)
    middle = done % period[owner]
    who = rows[owner]
    refined = observe(who, middle[:, None])[:, 0]
    order = np.lexsort((-refined, owner))  # each row's best refined peak first
    first = order[np.r_[True, owner[order][1:] != owner[order][:-1]]]
    better = refined[first] > best_value[owner[first]]
    best_value[owner[first][better]] = refined[first][better]
    best_time[owner[first][better]] = middle[first][better]
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
    if isinstance(solution, Periodic):  # the block path, on a block of one
        values, times, _, _ = solution.block().maxima(w, np.array([fastest]))
        return PeriodicMaximum(float(values[0]), float(times[0]), samples, resolved)
    value, time = periodic_maximum(
        lambda tau: solution.observe(w, tau),
        lambda tau: solution.rate(w, tau),
        solution.period,
        samples,
        sampled,
        candidates,
    )
    return PeriodicMaximum(value, time, samples, resolved)
