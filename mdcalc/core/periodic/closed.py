"""The exact periodic state in closed form, for one system or a block of them (a
study's samples): modes, or e^{Aτ} whole where eigenvalues meet; its maxima."""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from mdcalc.core.periodic.modes import _modes, _paired, _pairs, _unfold
from mdcalc.core.periodic.peaks import _samples, periodic_maxima
from mdcalc.core.periodic.system import Observable, RampSystem, Unbounded, Unresolved
from mdcalc.core.powers import powers


@dataclass(frozen=True)
class Periodic:
    """The exact periodic state: y(τ) = p₀ + p₁·τ + Re Σ Vᵢ·dᵢ·e^{λᵢτ}; or, where
    eigenvalues meet (``matrix`` given), y(τ) = p₀ + p₁·τ + S·e^{Bτ}·d₀ with
    B = S⁻¹·A·S balanced (``basis`` S: a permutation times powers of two)."""

    period: float
    eigenvalues: np.ndarray  # λ, 2n complex
    vectors: np.ndarray  # V, 2n×2n complex
    coefficients: np.ndarray  # d in modal coordinates, 2n complex
    p0: np.ndarray
    p1: np.ndarray
    matrix: np.ndarray | None = None  # B, 2n×2n: the state by e^{Bτ} (modes meet)
    origin: np.ndarray | None = None  # d₀ = S⁻¹·(y(0) - p₀), 2n: ... from it
    basis: np.ndarray | None = None  # S, 2n×2n: ... back to y

    def observe(self, w: Observable, tau: np.ndarray) -> np.ndarray:
        if self.matrix is not None:
            return self.states(tau) @ w
        weights = (w @ self.vectors) * self.coefficients
        modal = np.exp(np.outer(tau, self.eigenvalues)) @ weights
        return float(w @ self.p0) + float(w @ self.p1) * tau + modal.real

    def rate(self, w: Observable, tau: np.ndarray) -> np.ndarray:
        if self.matrix is not None and self.origin is not None and self.basis is not None:
            flow = _flow(self.matrix, np.asarray(tau, dtype=float)) @ self.origin
            return float(w @ self.p1) + flow @ (w @ self.basis @ self.matrix)
        weights = (w @ self.vectors) * self.coefficients * self.eigenvalues
        return float(w @ self.p1) + (np.exp(np.outer(tau, self.eigenvalues)) @ weights).real

    def states(self, tau: np.ndarray) -> np.ndarray:
        if self.matrix is not None and self.origin is not None and self.basis is not None:
            flow = _flow(self.matrix, np.asarray(tau, dtype=float)) @ self.origin
            return self.p0 + np.outer(tau, self.p1) + flow @ self.basis.T
        modal = (np.exp(np.outer(tau, self.eigenvalues)) * self.coefficients) @ self.vectors.T
        return self.p0 + np.outer(tau, self.p1) + modal.real

    @property
    def fastest(self) -> float:
        """Largest |λ| [1/s]."""
        return float(np.max(np.abs(self.eigenvalues)))

    def block(self) -> PeriodicBlock:
        """This state as a block of one."""
        width = len(self.p0)
        matrix, origin, basis = np.zeros((width, width)), np.zeros(width), np.eye(width)
        if self.matrix is not None and self.origin is not None and self.basis is not None:
            matrix, origin, basis = self.matrix, self.origin, self.basis
        return PeriodicBlock(
            np.array([self.period]),
            self.eigenvalues[None],
            self.vectors[None],
            self.coefficients[None],
            self.p0[None],
            self.p1[None],
            np.array([SOLVED]),
            np.array([self.matrix is not None]),
            matrix[None],
            origin[None],
            basis[None],
        )


#: Why a row of a block has no exact periodic state (SOLVED: it has one).
SOLVED, UNSEPARATED, AS_GOOD_AS_FREE, RESONANT, SPREAD = 0, 1, 2, 3, 4


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
    failure: np.ndarray  # (m,) SOLVED, UNSEPARATED, AS_GOOD_AS_FREE, RESONANT or SPREAD
    # rows whose eigenvalues meet, solved by e^{Bτ} (:class:`Periodic`): their B, d₀
    # and S (zeros and I elsewhere; the modal numbers of a row that meets mean nothing)
    meet: np.ndarray  # (m,) bool
    matrix: np.ndarray  # B, (m, 2n, 2n)
    origin: np.ndarray  # d₀, (m, 2n)
    basis: np.ndarray  # S, (m, 2n, 2n)

    @functools.cached_property
    def fastest(self) -> np.ndarray:
        """Largest |λ| of each row [1/s] (taken once: the maxima and every observable
        of them ask)."""
        return np.max(np.abs(self.eigenvalues), axis=-1)

    def row(self, i: int) -> Periodic:
        """Row i's state; raises :class:`Unresolved` or :class:`Unbounded` with the
        reason when it has none."""
        if self.failure[i] != SOLVED:
            raise _failure(int(self.failure[i]), self.eigenvalues[i], float(self.period[i]))
        meet = bool(self.meet[i])
        return Periodic(
            float(self.period[i]),
            self.eigenvalues[i],
            self.vectors[i],
            self.coefficients[i],
            self.p0[i],
            self.p1[i],
            self.matrix[i] if meet else None,
            self.origin[i] if meet else None,
            self.basis[i] if meet else None,
        )

    def maxima(
        self, w: Observable, fastest: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Largest w·y over a period of each row (``w``: (2n,) or one per row): values,
        times, samples per period and whether they resolve the fastest mode (each
        row's own, or ``fastest``). NaN where a row has no state. Rows are sampled
        in groups of one sample count and in parts of at most :data:`BLOCK_CELLS`
        complex exponentials."""
        return self.maxima_of([w], fastest)[0]

    def maxima_of(
        self, ws: Sequence[Observable], fastest: np.ndarray | None = None
    ) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
        """:meth:`maxima` of each observable of ``ws``, the exponentials of the
        grids, which the modes alone set, taken once for them all."""
        m, width = self.p0.shape
        each = [_Observed(self, w) for w in ws]
        samples, resolved = _samples(self.period, self.fastest if fastest is None else fastest)
        found = [(np.full(m, math.nan), np.full(m, math.nan)) for _ in each]
        solved = self.failure == SOLVED
        paired = _paired(self.eigenvalues[solved & ~self.meet], none_real=True)
        for count in np.unique(samples[solved]):
            for meet in (False, True):
                group = np.flatnonzero(solved & (samples == count) & (self.meet == meet))
                parts = max(1, -(-len(group) * int(count) * width // BLOCK_CELLS))
                for rows in np.array_split(group, min(parts, group.size)) if group.size else []:
                    h = self.period[rows] / count
                    lam = self.eigenvalues[rows]
                    grid_of = None if meet else _grid_of(lam, h, int(count), paired)
                    for one, (values, times) in zip(each, found, strict=True):
                        if grid_of is None:
                            grid = _flow_grid(one.level[rows], one.drift[rows], one.w_s[rows],
                                              self.matrix[rows], self.origin[rows], h,
                                              int(count))  # fmt: skip
                            sampler, slope = one.observe_flow, one.rate_flow
                        else:
                            grid = grid_of(one.level[rows], one.drift[rows], one.weights[rows])
                            sampler, slope = one.observe, one.rate
                        bounds = None if meet else (one.curvature[rows], one.size[rows])
                        values[rows], times[rows] = periodic_maxima(
                            sampler, slope, self.period[rows], int(count), rows, grid,
                            bounds=bounds, bend=None if meet else one.bend,
                        )  # fmt: skip
        return [(values, times, samples, resolved) for values, times in found]


class _Observed:
    """An observable w of a block's states: its level, drift and modal weights, and
    its value and rate at times of given rows (modal, or by e^{Bτ} where the rows'
    eigenvalues meet)."""

    def __init__(self, block: PeriodicBlock, w: Observable) -> None:
        m, width = block.p0.shape
        w = np.broadcast_to(np.asarray(w, dtype=float), (m, width))
        self.block, self.lam = block, block.eigenvalues
        self.weights = (w[:, None, :] @ block.vectors)[:, 0, :] * block.coefficients
        self.slopes = self.weights * self.lam
        self.level, self.drift = _real_sum(w * block.p0), _real_sum(w * block.p1)
        # bounds of |w·y''| and |w·y| over a period, from each mode's weight at its
        # largest (at τ = 0, but for a mode that grows), for the search's reach (of
        # the modal rows)
        amplitude = np.abs(self.weights)
        if np.any(self.lam.real > 0.0):
            with np.errstate(all="ignore"):
                amplitude *= np.maximum(1.0, np.exp(self.lam.real * block.period[:, None]))
        self.curvature = _real_sum(amplitude * np.abs(self.lam) ** 2)
        self.size = np.abs(self.level) + np.abs(self.drift) * block.period
        self.size += _real_sum(amplitude)
        # ... and the scale of its samples' rounding, which grows with the phase λτ
        # its exponentials round (ε·|λ|T of the modal part: a review's 4.6·10⁵-sample
        # row was 7·10⁻¹² of |w·y| off), for the search's allowance of 1e-12 of it
        self.size *= 1.0 + block.fastest * block.period / 1000.0
        # the rows that meet observe w·S·e^{Bτ}·d₀ and its rate w·S·B·e^{Bτ}·d₀
        meet = np.flatnonzero(block.meet)
        self.w_s, self.w_a = np.zeros((m, width)), np.zeros((m, width))
        self.w_s[meet] = (w[meet, None, :] @ block.basis[meet])[:, 0, :]
        self.w_a[meet] = (self.w_s[meet, None, :] @ block.matrix[meet])[:, 0, :]
        self.kept: list[Any] = [None, None]  # the last rows asked and their numbers
        # every mode's partner beside it, in every row (an underdamped block): the
        # partner's exponential is the first's conjugate, bit for bit but for the
        # sign of a zero imaginary part at τ = 0 (τ·λ̄ is the conjugate of τ·λ, and
        # so is its exp; the real parts of the sums the same), and is not taken again
        self.paired = _paired(self.lam)

    def _exp(self, tau: np.ndarray, lam: np.ndarray) -> np.ndarray:
        """e^{λτ} of every mode, (…, modes), at times ``tau`` (…) for ``lam``
        broadcast against them."""
        if not self.paired:
            return np.exp(tau[..., None] * lam)
        return _unfold(np.exp(tau[..., None] * lam[..., ::2]), -1)

    # The exact value and rate take every mode with its own weight: a conjugate
    # pair's second weight is the first's conjugate only to the round-off of the
    # coordinates, which a pair near critical damping amplifies (twice the real
    # part of the first lost 1.6e-11 of a χ against a 40-digit reference)
    def observe(self, rows: np.ndarray, tau: np.ndarray) -> np.ndarray:
        modal = self._exp(tau, self.lam[rows][:, None, :]) * self.weights[rows][:, None, :]
        return self.level[rows][:, None] + self.drift[rows][:, None] * tau + _real_sum(modal)

    def rate(self, rows: np.ndarray, tau: np.ndarray) -> np.ndarray:
        lam_rows, slope_rows, drift_rows = self._rows(rows)
        modal = self._exp(tau, lam_rows) * slope_rows
        return drift_rows[:, None] + _real_sum(modal)

    def bend(self, rows: np.ndarray, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The rate and its own rate, from one exponential of each mode."""
        lam_rows, slope_rows, drift_rows = self._rows(rows)
        modal = self._exp(tau, lam_rows) * slope_rows
        return drift_rows[:, None] + _real_sum(modal), _real_sum(modal * lam_rows)

    def _rows(self, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """λ, w·λ and the drift of ``rows`` (kept: the refinement asks about the same
        rows each step)."""
        kept = self.kept
        if kept[0] is not rows:
            lam, slopes = self.lam[rows][:, None, :], self.slopes[rows][:, None, :]
            kept[:] = [rows, (lam, slopes, self.drift[rows])]
        return kept[1]

    def observe_flow(self, rows: np.ndarray, tau: np.ndarray) -> np.ndarray:
        b = self.block
        flow = np.einsum(
            "ksij,kj,ki->ks", _flow(b.matrix[rows], tau), b.origin[rows], self.w_s[rows]
        )
        return self.level[rows][:, None] + self.drift[rows][:, None] * tau + flow

    def rate_flow(self, rows: np.ndarray, tau: np.ndarray) -> np.ndarray:
        b = self.block
        flow = np.einsum(
            "ksij,kj,ki->ks", _flow(b.matrix[rows], tau), b.origin[rows], self.w_a[rows]
        )
        return self.drift[rows][:, None] + flow


def _real_sum(modal: np.ndarray) -> np.ndarray:
    """Re Σ over the last axis (the modes, a handful; or of a real array), term by
    term in index order: numpy's reduction along so short an axis costs some six
    times the adds."""
    total = modal[..., 0].real.copy()
    for j in range(1, modal.shape[-1]):
        total += modal[..., j].real
    return total


def _one_norm(matrices: np.ndarray) -> np.ndarray:
    """The 1-norm (largest column sum of sizes) of each of a stack of small
    matrices: numpy's norm, sum for sum, at a quarter of its cost (its reductions
    over axes of two to four)."""
    sizes = np.abs(matrices)
    sums = sizes[:, 0, :].copy()
    for i in range(1, sizes.shape[1]):
        sums += sizes[:, i, :]
    largest = sums[:, 0].copy()
    for j in range(1, sums.shape[1]):
        np.maximum(largest, sums[:, j], out=largest)
    return largest


#: Samples a run of powers of e^{λh} covers between exact exponentials.
RUN = 32
#: Anchors between two exact exponentials (powers of e^{λ·RUN·h} between).
ANCHOR_POWERS = 16


def _grid(
    level: np.ndarray,
    drift: np.ndarray,
    weights: np.ndarray,
    lam: np.ndarray,
    h: np.ndarray,
    count: int,
) -> np.ndarray:
    """level + drift·jh + Re Σᵢ wᵢ·e^{λᵢ·jh} for j = 0 … count - 1 of each row: an
    anchor at every :data:`RUN`-th sample, times the powers of e^{λh} between (a
    product per sample, not an exponential); the anchors themselves an exact
    exponential every :data:`ANCHOR_POWERS`-th, times powers of e^{λ·RUN·h} between
    (:func:`~mdcalc.core.powers.powers`; an exponential costs some 30 ns here, a
    product 0.5). Round-off grows to about (RUN + ANCHOR_POWERS + |λ|·jh)·ε of the
    modal part (the last the rounding of the phase, as in any exponential of λ·jh),
    inside the search's allowance (:class:`_Observed`'s size). With j = m·RUN + r,
    each run of a row is one small matrix product: its anchors' factors
    (w·e^{λ·mRUN·h} in real and imaginary parts, the level and drift there, the
    drift's step) by the run's (the powers' parts, 1, r)."""
    return _grid_of(lam, h, count)(level, drift, weights)


def _grid_of(
    lam: np.ndarray, h: np.ndarray, count: int, paired: bool = False
) -> Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]:
    """:func:`_grid` in two parts: what the modes alone set (the powers and the
    anchors' exponentials, for any observable of the rows), and the function of
    the level, drift and weights that finishes it. ``paired``: every row's modes
    are conjugate pairs side by side, none real (else they are sought)."""
    k, width = lam.shape
    run = min(RUN, count)
    # A conjugate pair of modes (eig gives them side by side) sums to twice the real
    # part of the first: its partner is not evaluated (to the round-off of the
    # partner's weight, which is the first's conjugate up to it)
    pairs = [] if paired else _pairs(lam)
    if paired:
        used = np.arange(0, width, 2)
    else:  # (a mode whose pair is in every row is skipped)
        used = np.flatnonzero([True] + [not np.all(pair) for pair in pairs])
    lam = lam[:, used]
    u = len(used)
    inner = powers(np.exp(h[:, None] * lam), run)  # (run, k, u): e^{λ·rh}
    # the anchors e^{λ·mRUN·h}: exact every ANCHOR_POWERS-th, powers of e^{λ·RUN·h} between
    start = np.arange(0, count, run) * h[:, None]  # (k, M): the anchors' times
    exact = np.exp(start[:, ::ANCHOR_POWERS, None] * lam[:, None, :])  # (k, C, u)
    between = powers(np.exp((run * h)[:, None] * lam), ANCHOR_POWERS).transpose(1, 0, 2)
    anchors = (exact[:, :, None, :] * between[:, None, :, :]).reshape(k, -1, u)
    anchors = anchors[:, : start.shape[1]]
    runs = np.empty((k, 2 * u + 2, run))
    runs[:, :u], runs[:, u : 2 * u] = inner.real.transpose(1, 2, 0), inner.imag.transpose(1, 2, 0)
    runs[:, 2 * u], runs[:, 2 * u + 1] = 1.0, np.arange(run)

    def finish(level: np.ndarray, drift: np.ndarray, weights: np.ndarray) -> np.ndarray:
        if paired:
            weights = 2.0 * weights[:, used]
        else:
            weights = weights.copy()
            for i, pair in enumerate(pairs):
                weights[:, i] = np.where(pair, 2.0 * weights[:, i], weights[:, i])
                weights[:, i + 1] = np.where(pair, 0.0, weights[:, i + 1])
            weights = weights[:, used]
        weighted = anchors * weights[:, None, :]
        factors = np.empty(start.shape + (2 * u + 2,))
        factors[:, :, :u], factors[:, :, u : 2 * u] = weighted.real, -weighted.imag
        factors[:, :, 2 * u] = level[:, None] + drift[:, None] * start
        factors[:, :, 2 * u + 1] = (drift * h)[:, None]
        return (factors @ runs).reshape(k, count)

    return finish


def _flow(a: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """e^{Aτ} for every τ: A (…, N, N) and τ (…, S) give (…, S, N, N)."""
    from scipy.linalg import expm

    return np.asarray(expm(a[..., None, :, :] * tau[..., None, None]))


def _flow_grid(
    level: np.ndarray,
    drift: np.ndarray,
    w: np.ndarray,
    a: np.ndarray,
    origin: np.ndarray,
    h: np.ndarray,
    count: int,
) -> np.ndarray:
    """level + drift·jh + w·e^{B·jh}·d₀ for j = 0 … count - 1 of each row whose
    eigenvalues meet (``w`` the observable times S): e^{B·jh} as e^{B·rh}·e^{B·mRUN·h}
    (j = m·RUN + r), each factor
    an exponential of its own (no powers: no round-off that grows with j)."""
    run = min(RUN, count)
    start = np.arange(0, count, run) * h[:, None]  # (k, M): the anchors' times
    anchors = np.einsum("kmij,kj->kmi", _flow(a, start), origin)  # e^{B·mRUN·h}·d₀
    inside = np.einsum("ki,krij->krj", w, _flow(a, np.arange(run) * h[:, None]))  # w·e^{B·rh}
    modal = np.einsum("krj,kmj->kmr", inside, anchors)
    times = start[:, :, None] + np.arange(run) * h[:, None, None]
    return (level[:, None, None] + drift[:, None, None] * times + modal).reshape(len(h), -1)


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
    pencil = replace(system, mass=mass, damping=c, stiffness=k)

    def first(rows: Any) -> np.ndarray:
        """The first-order matrices A of ``rows`` (only where they are needed)."""
        return replace(pencil, mass=mass[rows], damping=c[rows], stiffness=k[rows]).first_order()

    eigenvalues, vectors, sure, inverse, closest = _modes(first, mass, c, k)
    paired = _paired(eigenvalues)
    failure = np.where(broken, UNSEPARATED, SOLVED)
    # Eigenvalues that (nearly) meet -- a mode damped (nearly) critically -- have
    # (nearly) parallel eigenvectors, and the modal sum loses about ε/gap of the state
    # (gap: their distance over their size). Such rows take e^{Aτ} whole, balanced.
    meet = ~broken & (closest < MEET)
    # the 1-norm condition, from V⁻¹ (the 2-norm's SVD cost three times as much),
    # which gives the modal coordinates below too: of one or two coordinates from
    # the left eigenvectors (_modes; NaN or inf where V is singular: the row
    # meets); of more by numpy (rows that meet invert I: a repeated eigenvalue is
    # the usual way to a singular V; any other row found singular is inverted
    # alone, its condition NaN: it meets)
    if inverse is None:
        plain = meet | ~np.all(np.isfinite(vectors), axis=(1, 2))
        inverse = _inverse(np.where(plain[:, None, None], np.eye(2 * n), vectors))
    with np.errstate(all="ignore"):
        # (a conjugate pair's columns of V have the same sizes: one of each will do)
        columns = vectors[:, :, ::2] if paired else vectors
        condition = _one_norm(columns) * _one_norm(inverse)
        meet |= ~broken & ~(condition <= 1e12)
    # The particular solution holds K⁻¹: a mode much slower than the load (|λ|T ≪ 1)
    # makes it and the modal part cancel, losing about ε/(λT)² of the result.
    slow = np.min(np.abs(eigenvalues), axis=-1) * t
    failure[(failure == SOLVED) & (slow < 1.5e-4)] = AS_GOOD_AS_FREE  # ε/(λT)² > 1e-8
    # 1 - e^{λT} by expm1: a mode much slower than the load (λT → 0) has a large
    # but finite periodic part; only e^{λT} = 1 with λT ≠ 0 (λT = 2πim) is a resonance
    gap = (
        -np.expm1(eigenvalues * t[:, None])
        if not paired
        else _unfold(-np.expm1(eigenvalues[:, ::2] * t[:, None]), -1)
    )  # (of a conjugate pair, the conjugate: bit for bit)
    failure[(failure == SOLVED) & np.any(_resonant(gap, eigenvalues * t[:, None]), axis=-1)] = (
        RESONANT
    )
    # modes that neither the closed form nor eigvals has within 1 % (eigvals: the
    # slow ones beyond |λ_fast/λ_slow| ≈ 10¹³), so that Newton cannot start, or
    # that the determinant's rounding leaves uncertain beyond 1e-8 of themselves (K
    # all but singular): no answer here (where eigenvalues meet, e^{Aτ} is taken
    # whole, and they only set the sampling)
    failure[(failure == SOLVED) & ~meet & ~sure] = SPREAD
    solved = failure == SOLVED
    meet &= solved
    modes = solved & ~meet
    vectors = np.where(modes[:, None, None], vectors, np.eye(2 * n))
    inverse = np.where(modes[:, None, None], inverse, np.eye(2 * n))
    gap = np.where(modes[:, None], gap, 1.0)
    load = p1.astype(complex)[..., None]
    modal = inverse @ load
    # The state sums the modes V as computed, so it wants the coordinates of (b, 0)
    # in those: V⁻¹·(b, 0) alone has them only to about cond(V)·ε (cond(V) 10⁶–10⁷ on
    # stiff drives, whose rows (x, λx) are scaled far apart: 4·10⁻⁷ of a velocity's
    # range seen). One step of refinement, its residual in working precision, takes
    # that to about 10⁻¹¹ (a review: an extended-precision residual does no better).
    modal = (modal + inverse @ (load - vectors @ modal))[..., 0]
    coefficients = np.where(modes[:, None], t[:, None] * modal / gap, 0.0)
    matrix, origin = np.zeros((m, 2 * n, 2 * n)), np.zeros_like(p1)
    basis = np.broadcast_to(np.eye(2 * n), matrix.shape).copy()
    if meet.any():  # balanced, B = S⁻¹·A·S; d₀ = (I - e^{BT})⁻¹·S⁻¹·p₁·T
        from scipy.linalg import matrix_balance

        # Balancing brings ‖B‖ near the fastest |λ| (‖A‖ holds K/M): without it expm's
        # scaling and squaring lost 3x the conditioning of a stiff system's state
        meeting = np.flatnonzero(meet)
        for i, a in zip(meeting.tolist(), first(meeting), strict=True):
            matrix[i], (scale, order) = matrix_balance(a, permute=True, separate=True)
            basis[i] = np.eye(2 * n)[:, order] * scale
        step = np.eye(2 * n) - _flow(matrix[meet], t[meet][:, None])[:, 0]
        load = np.linalg.solve(basis[meet], (p1[meet] * t[meet][:, None])[..., None])
        origin[meet] = np.linalg.solve(step, load)[..., 0]
    return PeriodicBlock(
        t, eigenvalues, vectors, coefficients, p0, p1, failure, meet, matrix, origin, basis
    )


def _inverse(vectors: np.ndarray) -> np.ndarray:
    """V⁻¹ of each row; NaN where V is singular (numpy's batched inverse refuses the
    whole block for one such row: then each row alone, which LAPACK solves with the
    same operations, so the other rows keep their digits)."""
    try:
        return np.asarray(np.linalg.inv(vectors))
    except np.linalg.LinAlgError:
        inverse = np.full_like(vectors, np.nan)
        for i, v in enumerate(vectors):
            try:
                inverse[i] = np.linalg.inv(v)
            except np.linalg.LinAlgError:
                pass
        return inverse


#: Eigenvalues closer than this (relative to the larger) are solved by e^{Aτ}: the
#: modal sum loses about 4·10⁻¹⁵/gap of the state (1.4·10⁻¹² at ζ = 1 + 10⁻⁶, a
#: gap of 2.8·10⁻³), so it keeps 12 digits or more outside. A mode is taken this way
#: within about 1.25·10⁻⁵ of critical damping.
MEET = 1e-2


def _resonant(gap: np.ndarray, turns: np.ndarray) -> np.ndarray:
    """e^{λT} = 1 to round-off with λT ≠ 0: λT carries a round-off of about
    ε·|λT|, so the gap is compared with that, not with 0."""
    turns = np.abs(turns)
    return (np.abs(gap) <= 1e-12 * np.maximum(1.0, turns)) & (turns > math.pi)


def _failure(code: int, eigenvalues: np.ndarray, t: float) -> ArithmeticError:
    magnitudes = np.abs(eigenvalues)
    if code == UNSEPARATED:
        return Unresolved("a number of the system is not finite, or its period not positive")
    if code == SPREAD:
        return Unresolved(
            f"the modes spread from {float(np.min(magnitudes)):.3g} to "
            f"{float(np.max(magnitudes)):.3g} rad/s, a ratio of "
            f"{float(np.max(magnitudes) / max(np.min(magnitudes), 1e-300)):.2g}: the slow "
            "ones cannot be found to 8 digits in double precision (modes spread so far, or "
            "a stiffness matrix all but singular); outside the range solved"
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


def block_of_one(system: RampSystem) -> RampSystem:
    """One system as a block of one row (its arrays with a leading axis)."""
    return replace(
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


def exact_periodic(system: RampSystem) -> Periodic:
    """The closed form of one system: a block of one."""
    return exact_block(block_of_one(system)).row(0)
