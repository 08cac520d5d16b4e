"""Linear torsional chains: J₁ - c₁ - J₂ - c₂ - ... - Jₙ, free at both ends.

Shared by the problems that model a drive as inertias on springs (``mine-hoist``,
``variator`` and ``resonance``). Everything is numpy; no scipy. The modal work runs
on a block of chains at once (``block_modes``, ``block_step``: a study's samples), a
single chain being a block of one, so that both take the same arithmetic.

* :class:`Chain` -- inertias [kg·m²] and the stiffnesses between neighbours
  [N·m/rad]; its mass and stiffness matrices.
* :func:`natural_modes` -- the elastic natural frequencies and mode shapes. The
  eigenvalues of the symmetric form are only a first guess: each one is then
  polished as a root of the Holzer residual (the torque left past the last mass),
  which keeps the relative accuracy of the low modes when the chain is stiff or a
  mass is tiny (a plain eigensolver loses digits as λ_max/λ_min grows: a sheave
  10⁻¹² as heavy as the drum costs the lowest mode three digits).
* :func:`suddenly_applied` -- the exact (modal) response of the spring moments to
  constant torques applied at t = 0 to a chain at rest with unloaded springs:
  M(t) = R - Σⱼ qⱼ·uⱼ·cos(βⱼt) = R + Σⱼ Bⱼ·cos(βⱼt), with R the moments of uniform
  acceleration. Its undamped supremum is R + Σ|Bⱼ| per spring.
  Their largest values over a time window: :mod:`.cosine_sums`.
* :func:`moment_equations` -- the ODE of the spring moments, M'' = -A·M + f (seed
  002 (6)), for reference runs.
* :func:`harmonic_response` -- the steady response to harmonic torques with viscous
  damping, (K - ω²J + iωC)·X = F.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

# ------------------------------------------------------------------------ the chain


@dataclass(frozen=True)
class Chain:
    """A free-free torsional chain; ``stiffnesses[k]`` joins masses k and k + 1."""

    inertias: tuple[float, ...]  # J [kg·m²]
    stiffnesses: tuple[float, ...]  # c [N·m/rad]

    def __post_init__(self) -> None:
        if len(self.inertias) < 2 or len(self.stiffnesses) != len(self.inertias) - 1:
            raise ValueError("a chain needs n >= 2 inertias and n - 1 stiffnesses")
        if min(self.inertias) <= 0.0 or min(self.stiffnesses) <= 0.0:
            raise ValueError("inertias and stiffnesses must be > 0")

    @property
    def size(self) -> int:
        return len(self.inertias)

    @property
    def total_inertia(self) -> float:
        return math.fsum(self.inertias)

    def mass_matrix(self) -> np.ndarray:
        """J = diag(J₁ … Jₙ) [kg·m²]."""
        return np.diag(np.array(self.inertias, dtype=float))

    def stiffness_matrix(self) -> np.ndarray:
        """K = Tᵀ·diag(c)·T with T the difference matrix (φₖ - φₖ₊₁) [N·m/rad]."""
        difference = self.difference_matrix()
        return difference.T @ np.diag(np.array(self.stiffnesses)) @ difference

    def difference_matrix(self) -> np.ndarray:
        """T, (n-1)×n: row k gives the twist φₖ - φₖ₊₁ of spring k."""
        n = self.size
        difference = np.zeros((n - 1, n))
        for k in range(n - 1):
            difference[k, k], difference[k, k + 1] = 1.0, -1.0
        return difference

    def partial_eigenvalues(self) -> tuple[float, ...]:
        """βₖ² = cₖ·(1/Jₖ + 1/Jₖ₊₁): each spring between its two masses held alone
        (seed 002: β₁₂², β₂₃²) [1/s²]."""
        j, c = self.inertias, self.stiffnesses
        return tuple(c[k] * (1.0 / j[k] + 1.0 / j[k + 1]) for k in range(len(c)))

    def arrays(self) -> tuple[np.ndarray, np.ndarray]:
        """The chain as a block of one: inertias (1, n) and stiffnesses (1, n - 1)."""
        return (
            np.array([self.inertias], dtype=float),
            np.array([self.stiffnesses], dtype=float),
        )


# ------------------------------------------------------------------ natural modes
#
# Every function below works on a block of chains at once: inertias J of shape
# (B, n), stiffnesses c of shape (B, n - 1). A single scene is a block of one, so a
# study's samples and a single scene run the same arithmetic. Sums over masses and
# modes are written as loops in index order (never np.sum over a short axis, whose
# order of addition depends on the array's layout), so a row's result does not
# depend on the block it is in.


@dataclass(frozen=True)
class Modes:
    """The n - 1 elastic modes, slowest first (the rigid-body mode is left out)."""

    eigenvalues: tuple[float, ...]  # λⱼ = βⱼ² [1/s²]
    shapes: np.ndarray  # n × (n-1): column j is mode j's angles, largest |θ| = 1
    moments: np.ndarray  # (n-1) × (n-1): column j is mode j's spring moments [N·m/rad]
    first_guess: tuple[float, ...]  # the eigensolver's eigenvalues before polishing

    @property
    def frequencies(self) -> tuple[float, ...]:
        """βⱼ [rad/s]."""
        return tuple(math.sqrt(v) for v in self.eigenvalues)


@dataclass(frozen=True)
class ModesBlock:
    """:class:`Modes` of a block of chains: a leading axis of length B on each."""

    eigenvalues: np.ndarray  # (B, n-1), ascending
    shapes: np.ndarray  # (B, n, n-1)
    moments: np.ndarray  # (B, n-1, n-1)
    first_guess: np.ndarray  # (B, n-1)

    def row(self, index: int) -> Modes:
        return Modes(
            tuple(self.eigenvalues[index].tolist()),
            self.shapes[index],
            self.moments[index],
            tuple(self.first_guess[index].tolist()),
        )


def natural_modes(chain: Chain) -> Modes:
    """Elastic natural frequencies and mode shapes of a free-free chain."""
    return block_modes(*chain.arrays()).row(0)


def block_modes(inertias: np.ndarray, stiffnesses: np.ndarray) -> ModesBlock:
    """Elastic natural frequencies and mode shapes of a block of chains.

    The eigenvalues of the symmetric form are a first guess; the lowest is then taken
    from the product of all, Πc·ΣJ/ΠJ, over the others (an eigensolver gives it with
    an absolute error near eps·λ_max, so it may even come out 0 or negative when
    λ_max/λ_min passes 1/eps); each is then polished as a root of the Holzer residual.
    """
    j = np.asarray(inertias, dtype=float)
    c = np.asarray(stiffnesses, dtype=float)
    guesses = _symmetric_eigenvalues(j, c)
    if guesses.shape[1] > 1:
        log_product = _total(np.log(c)) + np.log(_total(j)) - _total(np.log(j))
        guesses[:, 0] = np.exp(log_product - _total(np.log(guesses[:, 1:])))
    polished = _polish(j, c, guesses)
    shapes, moments = _mode_shapes(j, c, polished)
    return ModesBlock(polished, shapes, moments, guesses)


def _total(x: np.ndarray) -> np.ndarray:
    """Σ over the last axis, added in index order."""
    total = x[..., 0].copy()
    for k in range(1, x.shape[-1]):
        total = total + x[..., k]
    return total


def _symmetric_eigenvalues(j: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Eigenvalues of the spring-moment form C^½·T·J⁻¹·Tᵀ·C^½ (tridiagonal), ascending,
    per chain; the rigid-body mode does not appear in it."""
    size, springs = c.shape
    inverse = 1.0 / j
    root_c = np.sqrt(c)
    symmetric = np.zeros((size, springs, springs))
    for k in range(springs):
        symmetric[:, k, k] = c[:, k] * (inverse[:, k] + inverse[:, k + 1])
        if k + 1 < springs:
            symmetric[:, k, k + 1] = symmetric[:, k + 1, k] = (
                -root_c[:, k] * inverse[:, k + 1] * root_c[:, k + 1]
            )
    return np.linalg.eigvalsh(symmetric)


def holzer_residual(j: np.ndarray, c: np.ndarray, eigenvalue: np.ndarray) -> np.ndarray:
    """Holzer's table at λ = ω² from the first mass (θ₁ = 1): the torque λ·Σ Jₖθₖ
    left past the last mass, zero at a natural frequency. ``eigenvalue`` (B, m): m
    trial values per chain."""
    theta = np.ones_like(eigenvalue)
    torque = eigenvalue * j[:, :1]
    for k in range(c.shape[1]):
        theta = theta - torque / c[:, k, None]
        torque = torque + eigenvalue * j[:, k + 1, None] * theta
    return torque


def _polish(j: np.ndarray, c: np.ndarray, guesses: np.ndarray) -> np.ndarray:
    """The root of the Holzer residual next to each guess, to full relative precision.

    The residual divided by λ is a polynomial with the n - 1 elastic eigenvalues as
    simple roots, so it changes sign at each; the bracket grows from the
    eigensolver's error bound until it does, staying short of the neighbours. A
    guess whose bracket never changes sign (roots too close to separate) is kept.
    Over so short a bracket the residual is a straight line to rounding: one secant
    step lands next to the root, and where the residual changes sign within four
    ulps of it the bisection starts from there (a few steps instead of up to twenty).
    """
    with np.errstate(all="ignore"):  # brackets past overflow are judged, not raised

        def residual(value: np.ndarray) -> np.ndarray:
            return holzer_residual(j, c, value) / value

        eps = np.finfo(float).eps
        g = guesses
        width = 64.0 * eps * g[:, -1:] + 4.0 * eps * g
        low_limit = 0.5 * g
        high_limit = 2.0 * g
        low_limit[:, 1:] = 0.5 * (g[:, :-1] + g[:, 1:])
        high_limit[:, :-1] = 0.5 * (g[:, :-1] + g[:, 1:])
        low, high = g.copy(), g.copy()
        f_low, f_high = np.zeros(g.shape), np.zeros(g.shape)
        searching = np.ones(g.shape, dtype=bool)
        bracketed = np.zeros(g.shape, dtype=bool)
        for _ in range(60):
            a = np.maximum(g - width, low_limit)
            b = np.minimum(g + width, high_limit)
            f_a, f_b = residual(a), residual(b)
            found = searching & (a > 0.0) & _straddle(f_a, f_b)
            low, f_low = np.where(found, a, low), np.where(found, f_a, f_low)
            high, f_high = np.where(found, b, high), np.where(found, f_b, f_high)
            bracketed |= found
            searching &= ~found & ~((a <= low_limit) & (b >= high_limit))
            if not searching.any():
                break
            width = width * 4.0
        secant = low - f_low * ((high - low) / (f_high - f_low))
        secant = np.where((secant > low) & (secant < high), secant, 0.5 * (low + high))
        ulps = 4.0 * np.spacing(secant)
        a, b = np.maximum(secant - ulps, low), np.minimum(secant + ulps, high)
        f_a, f_b = residual(a), residual(b)
        tight = bracketed & _straddle(f_a, f_b)
        low, f_low = np.where(tight, a, low), np.where(tight, f_a, f_low)
        high, f_high = np.where(tight, b, high), np.where(tight, f_b, f_high)
        roots = _bisect(residual, low, high, f_low, f_high, bracketed)
        return np.where(bracketed, roots, g)


def _straddle(f_a: np.ndarray, f_b: np.ndarray) -> np.ndarray:
    """The function changes sign between a and b, or is zero at one of them (by the
    signs: a product of two values below 1e-154 would underflow to zero)."""
    return (f_a == 0.0) | (f_b == 0.0) | ((f_a < 0.0) != (f_b < 0.0))


def _bisect(
    function: Any,
    low: np.ndarray,
    high: np.ndarray,
    f_low: np.ndarray,
    f_high: np.ndarray,
    active: np.ndarray,
) -> np.ndarray:
    """Bisection of each bracket [low, high] where ``active``, to the last bit
    (``f_low``, ``f_high``: the function at its ends; an end where it is exactly
    zero is the root)."""
    at_low = active & (f_low == 0.0)
    at_high = active & ~at_low & (f_high == 0.0)
    root = np.where(at_low, low, np.where(at_high, high, 0.0))
    exact = at_low | at_high
    running = active & ~exact
    for _ in range(200):
        middle = 0.5 * (low + high)
        running &= (middle != low) & (middle != high)
        if not running.any():
            break
        f_middle = function(middle)
        hit = running & (f_middle == 0.0)
        root = np.where(hit, middle, root)
        exact |= hit
        running &= ~hit
        left = (f_middle < 0.0) == (f_low < 0.0)
        low = np.where(running & left, middle, low)
        f_low = np.where(running & left, f_middle, f_low)
        high = np.where(running & ~left, middle, high)
    return np.where(exact, root, 0.5 * (low + high))


def _mode_shapes(
    j: np.ndarray, c: np.ndarray, eigenvalues: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Angles θ (largest |θ| = 1) and spring moments of every mode of every chain.

    Holzer's table run from both ends and joined where the joined shape fits
    (K - λJ)·θ = 0 best: run into a part of the chain that hardly moves, a table sums
    inertia torques that cancel (a drum and a light sheave swinging against each
    other leave the next spring almost unloaded), while run out of it from the far
    end it does not.
    """
    n = j.shape[1]
    lam = eigenvalues
    with np.errstate(all="ignore"):
        left = [np.ones_like(lam)]
        left_moments: list[np.ndarray] = []
        torque = lam * j[:, :1]
        for k in range(n - 1):
            left_moments.append(torque)  # spring k carries the inertia torques left of it
            left.append(left[-1] - torque / c[:, k, None])
            torque = torque + lam * j[:, k + 1, None] * left[-1]
        right = [np.ones_like(lam)]
        right_moments: list[np.ndarray] = []
        torque = -lam * j[:, n - 1 : n]
        for k in range(n - 2, -1, -1):
            right_moments.append(torque)  # spring k carries the inertia torques right of it
            right.append(right[-1] + torque / c[:, k, None])
            torque = torque - lam * j[:, k, None] * right[-1]
        right.reverse()
        right_moments.reverse()
        # The join with the least misfit; a join that cannot be made ranks last, and
        # an infinite misfit just before it (the first such join wins a tie).
        best = np.full(lam.shape, np.inf)
        where = np.full(lam.shape, -1)
        chosen_scale = np.ones(lam.shape)
        # the masses before a join see the left table alone: their part of the
        # misfit grows from join to join instead of being summed again each time
        before = (np.zeros(lam.shape), np.zeros(lam.shape))
        for join in range(n):
            usable = (right[join] != 0.0) & np.isfinite(left[join])
            scale = left[join] / right[join]
            shape = left[: join + 1] + [scale * v for v in right[join + 1 :]]
            misfit = _misfit(j, c, lam, shape, join, before)
            before = _residuals(j, c, lam, left, join, join + 1, before)
            rank = np.where(usable, np.minimum(misfit, np.finfo(float).max), np.inf)
            better = rank < best
            best = np.where(better, rank, best)
            where = np.where(better, join, where)
            chosen_scale = np.where(better, scale, chosen_scale)
        # Mass k comes from the left table up to the join, scaled from the right one
        # past it; spring k from the left table before the join. No usable join
        # (where = -1): the left table throughout.
        whole_left = where < 0
        theta = np.stack(
            [
                np.where(whole_left | (k <= where), left[k], chosen_scale * right[k])
                for k in range(n)
            ],
            axis=1,
        )
        springs = np.stack(
            [
                np.where(whole_left | (k < where), left_moments[k], chosen_scale * right_moments[k])
                for k in range(n - 1)
            ],
            axis=1,
        )
        norm = np.abs(theta[:, 0, :])
        for k in range(1, n):
            norm = np.maximum(norm, np.abs(theta[:, k, :]))
        return theta / norm[:, None, :], springs / norm[:, None, :]


def _misfit(
    j: np.ndarray,
    c: np.ndarray,
    lam: np.ndarray,
    theta: list[np.ndarray],
    first: int = 0,
    before: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """max |(K - λJ)·θ| over the masses, scaled by the largest term that enters it;
    the masses before ``first`` given as ``before`` (their largest residual and
    term: the max does not depend on the order it is taken in)."""
    worst, size = _residuals(j, c, lam, theta, first, len(theta), before)
    return np.where((size > 0.0) & np.isfinite(size), worst / size, np.inf)


def _residuals(
    j: np.ndarray,
    c: np.ndarray,
    lam: np.ndarray,
    theta: list[np.ndarray],
    first: int,
    last: int,
    before: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The largest |(K - λJ)·θ| of the masses first … last - 1 and the largest term
    that enters them, on top of ``before``."""
    n = len(theta)
    worst, size = before if before is not None else (np.zeros(lam.shape), np.zeros(lam.shape))
    for k in range(first, last):
        terms = [-lam * j[:, k, None] * theta[k]]
        if k > 0:
            terms.append(c[:, k - 1, None] * (theta[k] - theta[k - 1]))
        if k + 1 < n:
            terms.append(c[:, k, None] * (theta[k] - theta[k + 1]))
        total = terms[0]
        for term in terms[1:]:
            total = total + term
        worst = np.maximum(worst, np.abs(total))
        for term in terms:
            size = np.maximum(size, np.abs(term))
    return worst, size


# ---------------------------------------------------- suddenly applied torques


@dataclass(frozen=True)
class StepResponse:
    """Spring moments after constant torques applied at t = 0 to a chain at rest:
    Mₖ(t) = Rₖ + Σⱼ Bₖⱼ·cos(βⱼ·t), undamped, exact."""

    frequencies: tuple[float, ...]  # βⱼ [rad/s]
    static: tuple[float, ...]  # Rₖ, moments under the uniform acceleration [N·m]
    amplitudes: np.ndarray  # Bₖⱼ [N·m], spring k, mode j
    acceleration: float  # ε = ΣM/ΣJ, of the chain as a rigid body [rad/s²]

    def moments(self, times: np.ndarray) -> np.ndarray:
        """Mₖ(t) for every spring (rows) at ``times`` (columns) [N·m]."""
        phases = np.outer(np.array(self.frequencies), np.asarray(times, dtype=float))
        return np.array(self.static)[:, None] + self.amplitudes @ np.cos(phases)

    def supremum(self, spring: int) -> float:
        """The least upper bound of Mₖ(t) over all time, Rₖ + Σⱼ|Bₖⱼ| [N·m]: approached
        when the frequencies are incommensurate, since then every phase combination
        comes back arbitrarily close."""
        return float(supremum(np.array([self.static]), self.amplitudes[None])[0, spring])


@dataclass(frozen=True)
class StepBlock:
    """:class:`StepResponse` of a block of chains."""

    static: np.ndarray  # (B, n-1): Rₖ [N·m]
    amplitudes: np.ndarray  # (B, n-1, n-1): Bₖⱼ [N·m]
    acceleration: np.ndarray  # (B,): ε [rad/s²]
    eigenvalues: np.ndarray  # (B, n-1): λⱼ of the modes [1/s²]
    consistent: np.ndarray  # (B,) bool: R + ΣB = 0 at t = 0 within 1e-9 of the scale

    def row(self, index: int) -> StepResponse:
        """One chain's response; raises ArithmeticError where the constant parts and
        the modes do not add up to M(0) = 0."""
        if not self.consistent[index]:
            misfit = float(np.max(np.abs(self.static[index] + _total(self.amplitudes[index]))))
            raise ArithmeticError(
                f"modal solution inconsistent: M(0) = {misfit:.3g} N·m, not 0 "
                "(mode shapes lost precision on this chain)"
            )
        return StepResponse(
            tuple(np.sqrt(self.eigenvalues[index]).tolist()),
            tuple(self.static[index].tolist()),
            self.amplitudes[index],
            float(self.acceleration[index]),
        )


def supremum(static: np.ndarray, amplitudes: np.ndarray) -> np.ndarray:
    """Rₖ + Σⱼ|Bₖⱼ| of each spring of each chain (B, n-1) [N·m]."""
    return static + _total(np.abs(amplitudes))


def static_moments(chain: Chain, torques: Sequence[float]) -> tuple[tuple[float, ...], float]:
    """Spring moments when the chain accelerates as a rigid body under ``torques``
    (see :func:`block_static_moments`)."""
    j, _ = chain.arrays()
    static, accel = block_static_moments(j, np.array([torques], dtype=float))
    return tuple(static[0].tolist()), float(accel[0])


def block_static_moments(j: np.ndarray, torques: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Spring k carries the torques left of it less the inertia torque of the masses
    left of it, Rₖ = Σᵢ≤ₖ(Mᵢ - Jᵢ·ε), ε = ΣM/ΣJ (seed 002 (11)-(12)); written as
    Rₖ = [ΣM(left)·ΣJ(right) - ΣM(right)·ΣJ(left)]/ΣJ, so that no difference of near
    equals appears when the torques push apart (drive on the left, load on the right).
    """
    n = j.shape[1]
    total = _total(j)
    accel = _total(torques) / total
    static = np.empty((j.shape[0], n - 1))
    for k in range(n - 1):
        left_torque, right_torque = _total(torques[:, : k + 1]), _total(torques[:, k + 1 :])
        left_inertia, right_inertia = _total(j[:, : k + 1]), _total(j[:, k + 1 :])
        static[:, k] = (left_torque * right_inertia - right_torque * left_inertia) / total
    return static, accel


def suddenly_applied(chain: Chain, torques: Sequence[float], modes: Modes) -> StepResponse:
    """The modal solution for constant ``torques`` [N·m] (one per mass, positive in
    the sense of rotation) applied at t = 0 to the chain at rest with unloaded springs
    (see :func:`block_step`). Raises ArithmeticError where the constant parts and the
    modes do not add up to M(0) = 0."""
    if len(torques) != chain.size:
        raise ValueError(f"{len(torques)} torques for {chain.size} masses")
    j, _ = chain.arrays()
    block = ModesBlock(
        np.array([modes.eigenvalues]),
        modes.shapes[None],
        modes.moments[None],
        np.array([modes.first_guess]),
    )
    return block_step(j, np.array([torques], dtype=float), block).row(0)


def block_step(j: np.ndarray, torques: np.ndarray, modes: ModesBlock) -> StepBlock:
    """The modal solution of constant torques applied at t = 0 to chains at rest.

    Mode j's coordinate obeys q'' + βⱼ²·q = θⱼᵀ·M/(θⱼᵀ·J·θⱼ) from rest, so
    q(t) = (θⱼᵀM)/(λⱼ·θⱼᵀJθⱼ)·(1 - cos βⱼt), and the spring moments of mode j are its
    Holzer moments times q. The constant parts add up to R: checked, not assumed.
    """
    static, accel = block_static_moments(j, torques)
    shapes = modes.shapes
    n, m = shapes.shape[1], shapes.shape[2]
    amplitudes = np.empty((j.shape[0], n - 1, m))
    for col in range(m):
        theta = shapes[:, :, col]
        load = theta[:, 0] * torques[:, 0]
        inertia = theta[:, 0] * (j[:, 0] * theta[:, 0])
        for i in range(1, n):
            load = load + theta[:, i] * torques[:, i]
            inertia = inertia + theta[:, i] * (j[:, i] * theta[:, i])
        participation = load / (modes.eigenvalues[:, col] * inertia)
        amplitudes[:, :, col] = -participation[:, None] * modes.moments[:, :, col]
    scale = np.maximum(np.max(np.abs(static), axis=1), np.max(np.abs(amplitudes), axis=(1, 2)))
    misfit = np.max(np.abs(static + _total(amplitudes)), axis=1)
    consistent = ~((scale > 0.0) & (misfit > 1e-9 * scale))
    return StepBlock(static, amplitudes, accel, modes.eigenvalues, consistent)


# ------------------------------------------------------------- ODE of moments


def moment_equations(chain: Chain, torques: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """A and f of M'' = -A·M + f for the spring moments M = C·T·φ (seed 002 (6)):
    A = C·T·J⁻¹·Tᵀ, f = C·T·J⁻¹·M_ext."""
    difference = chain.difference_matrix()
    inverse_mass = np.diag(1.0 / np.array(chain.inertias))
    c = np.diag(np.array(chain.stiffnesses))
    a = c @ difference @ inverse_mass @ difference.T
    f = c @ difference @ inverse_mass @ np.array(torques, dtype=float)
    return a, f


# ---------------------------------------------------------- forced harmonic response


def harmonic_response(
    chain: Chain,
    omega: float,
    torques: Sequence[complex],
    spring_damping: Sequence[float] | None = None,
    absolute_damping: Sequence[float] | None = None,
    ground_stiffness: Sequence[float] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Steady response to torques Mₖ·e^(iωt) [N·m] at ω [rad/s]: complex angle
    amplitudes X [rad] from (K - ω²J + iωC)·X = M, and the complex spring moment
    amplitudes (cₖ + iωαₖ)·(Xₖ - Xₖ₊₁) [N·m]. ``spring_damping`` αₖ acts across
    spring k, ``absolute_damping`` on mass k against the ground [N·m·s/rad],
    ``ground_stiffness`` holds mass k to the ground (a shaft to a fixed end, a motor's
    electromagnetic spring) [N·m/rad]. See :func:`block_harmonic_response`.
    Raises ArithmeticError when the matrix is singular (undamped resonance)."""

    def one(values: Sequence[float] | None) -> np.ndarray | None:
        return None if values is None else np.array([values], dtype=float)

    j, c = chain.arrays()
    angles, springs, singular = block_harmonic_response(
        j,
        c,
        np.array([omega], dtype=float),
        np.array([torques], dtype=complex),
        one(spring_damping),
        one(absolute_damping),
        one(ground_stiffness),
    )
    if singular[0]:
        raise ArithmeticError(f"undamped resonance at ω = {omega:.6g} rad/s: amplitude unbounded")
    return angles[0], springs[0]


def block_harmonic_response(
    inertias: np.ndarray,
    stiffnesses: np.ndarray,
    omega: np.ndarray,
    torques: np.ndarray,
    spring_damping: np.ndarray | None = None,
    absolute_damping: np.ndarray | None = None,
    ground_stiffness: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`harmonic_response` of a block of chains (J (B, n), c (B, n-1), ω (B,),
    torques (B, n) complex, the dampings and ground springs (B, ·) or None): the
    angles (B, n), the spring moments (B, n-1), and where the matrix is singular to
    working precision (B,) — those rows' numbers mean nothing.

    The conditioning (in the 1-norm, from the inverse: the matrix is complex
    symmetric, so it bounds the 2-norm's from above) is judged after a symmetric
    diagonal scaling S⁻¹·A·S⁻¹: a chain whose stiffnesses span 10¹⁶ is not singular,
    only badly scaled."""
    size, n = inertias.shape
    alpha = spring_damping if spring_damping is not None else np.zeros((size, n - 1))
    ground = absolute_damping if absolute_damping is not None else np.zeros((size, n))
    held = ground_stiffness if ground_stiffness is not None else np.zeros((size, n))
    # The matrix is tridiagonal: its diagonal and its (symmetric) off-diagonal,
    # each term summed in the order a full assembly adds it.
    stiff, damp = np.zeros((size, n)), np.zeros((size, n))
    for diagonal, spring in ((stiff, stiffnesses), (damp, alpha)):
        diagonal[:, :-1] += spring
        diagonal[:, 1:] += spring
    stiff += held
    damp += ground
    w2 = (omega * omega)[:, None]
    turn = 1j * omega[:, None]
    main = stiff - w2 * inertias + turn * damp
    off = (0.0 - stiffnesses) + turn * (0.0 - alpha)
    scale = np.maximum(np.max(np.abs(main), axis=1), np.max(np.abs(off), axis=1, initial=0.0))
    weights = np.sqrt(np.maximum(stiff, w2 * inertias))
    weights[weights == 0.0] = 1.0
    index = np.arange(n)
    scaled = np.zeros((size, n, n), dtype=complex)
    scaled[:, index, index] = main / weights / weights
    upper = off / weights[:, :-1] / weights[:, 1:]
    lower = off / weights[:, 1:] / weights[:, :-1]
    scaled[:, index[:-1], index[1:]] = upper
    scaled[:, index[1:], index[:-1]] = lower
    scaled[scale == 0.0] = np.eye(n)
    try:  # one LU a chain gives the inverse, its 1-norm condition and the solution
        inverse = np.linalg.inv(scaled)
    except np.linalg.LinAlgError:  # a chain exactly singular: the inverse of the rest
        inverse = np.full(scaled.shape, np.nan, dtype=complex)
        with np.errstate(all="ignore"):
            fine = np.linalg.cond(scaled) <= 1e14
        inverse[fine] = np.linalg.inv(scaled[fine])
    # the 1-norm: the largest column sum, each column's three entries top down
    columns = np.abs(scaled[:, index, index])
    columns[:, 1:] = np.abs(scaled[:, index[:-1], index[1:]]) + columns[:, 1:]
    columns[:, :-1] += np.abs(scaled[:, index[1:], index[:-1]])
    norm = np.max(columns, axis=1)
    with np.errstate(all="ignore"):
        condition = norm * np.max(np.sum(np.abs(inverse), axis=1), axis=1)
    singular = (scale == 0.0) | ~(condition <= 1e14)
    inverse[singular] = np.eye(n)
    angles = (inverse @ (torques / weights)[:, :, None])[:, :, 0] / weights
    springs = (stiffnesses + 1j * omega[:, None] * alpha) * (angles[:, :-1] - angles[:, 1:])
    return angles, springs, singular
