"""Linear torsional chains: J₁ - c₁ - J₂ - c₂ - ... - Jₙ, free at both ends.

Shared by the problems that model a drive as inertias on springs (``mine-hoist``,
later ``variator`` and ``resonance``). Everything is numpy; no scipy.

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
* :func:`cosine_sum_maximum` -- the largest value of R + Σ B·cos(βt) over a time
  window, found by sampling at 16 points per period of the fastest resolved mode and
  golden-section refinement of every candidate.
* :func:`moment_equations` -- the ODE of the spring moments, M'' = -A·M + f (seed
  002 (6)), for reference runs.
* :func:`harmonic_response` -- the steady response to harmonic torques with viscous
  damping, (K - ω²J + iωC)·X = F.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

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

    def holzer(self, eigenvalue: float) -> tuple[list[float], list[float], float]:
        """Holzer's table at λ = ω² from the first mass: the angles θ (θ₁ = 1), the
        spring moments cₖ(θₖ - θₖ₊₁) and the residual torque λ·Σ Jₖθₖ past the last
        mass (zero at a natural frequency)."""
        theta = [1.0]
        moments: list[float] = []
        torque = eigenvalue * self.inertias[0]
        for k, c in enumerate(self.stiffnesses):
            moments.append(torque)  # spring k carries the inertia torques left of it
            theta.append(theta[-1] - torque / c)
            torque += eigenvalue * self.inertias[k + 1] * theta[-1]
        return theta, moments, torque

    def _misfit(self, eigenvalue: float, theta: list[float]) -> float:
        """max |(K - λJ)·θ|, scaled by the largest term that enters it."""
        worst, size = 0.0, 0.0
        for k in range(self.size):
            terms = [-eigenvalue * self.inertias[k] * theta[k]]
            if k > 0:
                terms.append(self.stiffnesses[k - 1] * (theta[k] - theta[k - 1]))
            if k + 1 < self.size:
                terms.append(self.stiffnesses[k] * (theta[k] - theta[k + 1]))
            worst = max(worst, abs(math.fsum(terms)))
            size = max(size, *(abs(t) for t in terms))
        return worst / size if size > 0.0 and math.isfinite(size) else math.inf

    def mode_shape(self, eigenvalue: float) -> tuple[list[float], list[float]]:
        """Angles θ (largest |θ| = 1) and spring moments of the mode at λ.

        Holzer's table run from both ends and joined at the mass that moves most:
        run into a part of the chain that hardly moves, a table sums inertia torques
        that cancel (a drum and a light sheave swinging against each other leave the
        next spring almost unloaded), while run out of it from the far end it does not.
        """
        n = self.size
        left, left_moments, _ = self.holzer(eigenvalue)
        right, right_moments = [1.0], []
        torque = -eigenvalue * self.inertias[-1]
        for k in range(n - 2, -1, -1):
            right_moments.append(torque)  # spring k carries the inertia torques right of it
            right.append(right[-1] + torque / self.stiffnesses[k])
            torque -= eigenvalue * self.inertias[k] * right[-1]
        right.reverse()
        right_moments.reverse()
        # Join where the joined shape fits (K - λJ)·θ = 0 best: each table is accurate
        # where it has not yet run into a part of the chain that hardly moves.
        best: tuple[float, list[float], list[float]] | None = None
        for join in range(n):
            if right[join] == 0.0 or not math.isfinite(left[join]):
                continue
            scale = left[join] / right[join]
            shape = left[: join + 1] + [scale * v for v in right[join + 1 :]]
            springs = left_moments[:join] + [scale * m for m in right_moments[join:]]
            misfit = self._misfit(eigenvalue, shape)
            if best is None or misfit < best[0]:
                best = (misfit, shape, springs)
        if best is None:
            theta, moments = left, left_moments
        else:
            _, theta, moments = best
        norm = max(abs(v) for v in theta)
        return [v / norm for v in theta], [m / norm for m in moments]


# ------------------------------------------------------------------ natural modes


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


def natural_modes(chain: Chain) -> Modes:
    """Elastic natural frequencies and mode shapes of a free-free chain."""
    guesses = _symmetric_eigenvalues(chain)
    if len(guesses) > 1:
        # The lowest from the product of all, Πc·ΣJ/ΠJ, over the others: an
        # eigensolver gives it with an absolute error near eps·λ_max, so it may even
        # come out 0 or negative when λ_max/λ_min passes 1/eps.
        log_product = (
            sum(math.log(c) for c in chain.stiffnesses)
            + math.log(chain.total_inertia)
            - sum(math.log(j) for j in chain.inertias)
        )
        guesses[0] = math.exp(log_product - float(np.sum(np.log(guesses[1:]))))
    polished = [
        _polish(chain, guess, guesses, index) for index, guess in enumerate(guesses.tolist())
    ]
    shapes = np.empty((chain.size, chain.size - 1))
    moments = np.empty((chain.size - 1, chain.size - 1))
    for j, value in enumerate(polished):
        theta, spring = chain.mode_shape(value)
        shapes[:, j] = theta
        moments[:, j] = spring
    return Modes(tuple(polished), shapes, moments, tuple(guesses.tolist()))


def _symmetric_eigenvalues(chain: Chain) -> np.ndarray:
    """Eigenvalues of the spring-moment form C^½·T·J⁻¹·Tᵀ·C^½, ascending; the
    rigid-body mode does not appear in it."""
    difference = chain.difference_matrix()
    inverse_mass = np.diag(1.0 / np.array(chain.inertias))
    root_c = np.sqrt(np.array(chain.stiffnesses))
    symmetric = root_c[:, None] * (difference @ inverse_mass @ difference.T) * root_c[None, :]
    return np.linalg.eigvalsh(symmetric)


def _polish(chain: Chain, guess: float, guesses: np.ndarray, index: int) -> float:
    """The root of the Holzer residual next to ``guess``, to full relative precision.

    The residual divided by λ is a polynomial with the n - 1 elastic eigenvalues as
    simple roots, so it changes sign at each; the bracket grows from the
    eigensolver's error bound until it does, staying short of the neighbours.
    """

    def residual(value: float) -> float:
        return chain.holzer(value)[2] / value

    eps = np.finfo(float).eps
    width = 64.0 * eps * float(guesses[-1]) + 4.0 * eps * guess
    low_limit = 0.5 * (guesses[index - 1] + guess) if index > 0 else 0.5 * guess
    high_limit = 0.5 * (guess + guesses[index + 1]) if index + 1 < len(guesses) else 2.0 * guess
    for _ in range(60):
        low, high = max(guess - width, low_limit), min(guess + width, high_limit)
        if low > 0.0 and residual(low) * residual(high) <= 0.0:
            return _bisect(residual, low, high)
        if low <= low_limit and high >= high_limit:
            break
        width *= 4.0
    return guess  # no sign change found (roots too close to separate): keep the guess


def _bisect(function: object, low: float, high: float) -> float:
    f = function  # a callable; typed loosely to keep the loop lean
    f_low = f(low)  # type: ignore[operator]
    for _ in range(200):
        middle = 0.5 * (low + high)
        if middle in (low, high):
            break
        f_middle = f(middle)  # type: ignore[operator]
        if f_middle == 0.0:
            return middle
        if (f_middle < 0.0) == (f_low < 0.0):
            low, f_low = middle, f_middle
        else:
            high = middle
    return 0.5 * (low + high)


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
        return self.static[spring] + float(np.sum(np.abs(self.amplitudes[spring])))


def static_moments(chain: Chain, torques: Sequence[float]) -> tuple[tuple[float, ...], float]:
    """Spring moments when the chain accelerates as a rigid body under ``torques``:
    spring k carries the torques left of it less the inertia torque of the masses
    left of it, Rₖ = Σᵢ≤ₖ(Mᵢ - Jᵢ·ε), ε = ΣM/ΣJ (seed 002 (11)-(12))."""
    total = chain.total_inertia
    accel = math.fsum(torques) / total
    static = []
    for k in range(chain.size - 1):
        # Rₖ = [ΣM(left)·ΣJ(right) - ΣM(right)·ΣJ(left)]/ΣJ: no difference of near
        # equals when the torques push apart (drive on the left, load on the right).
        left_torque, right_torque = math.fsum(torques[: k + 1]), math.fsum(torques[k + 1 :])
        left_inertia = math.fsum(chain.inertias[: k + 1])
        right_inertia = math.fsum(chain.inertias[k + 1 :])
        static.append((left_torque * right_inertia - right_torque * left_inertia) / total)
    return tuple(static), accel


def suddenly_applied(chain: Chain, torques: Sequence[float], modes: Modes) -> StepResponse:
    """The modal solution for constant ``torques`` [N·m] (one per mass, positive in
    the sense of rotation) applied at t = 0 to the chain at rest with unloaded springs.

    Mode j's coordinate obeys q'' + βⱼ²·q = θⱼᵀ·M/(θⱼᵀ·J·θⱼ) from rest, so
    q(t) = (θⱼᵀM)/(λⱼ·θⱼᵀJθⱼ)·(1 - cos βⱼt), and the spring moments of mode j are its
    Holzer moments times q. The constant parts add up to R: checked, not assumed.
    """
    if len(torques) != chain.size:
        raise ValueError(f"{len(torques)} torques for {chain.size} masses")
    static, accel = static_moments(chain, torques)
    inertias = np.array(chain.inertias)
    load = np.array(torques, dtype=float)
    amplitudes = np.empty((chain.size - 1, chain.size - 1))
    for j, value in enumerate(modes.eigenvalues):
        theta = modes.shapes[:, j]
        participation = float(theta @ load) / (value * float(theta @ (inertias * theta)))
        amplitudes[:, j] = -participation * modes.moments[:, j]
    scale = max(max(abs(r) for r in static), float(np.max(np.abs(amplitudes))))
    misfit = np.max(np.abs(np.array(static) + amplitudes.sum(axis=1)))
    if scale > 0.0 and misfit > 1e-9 * scale:
        raise ArithmeticError(
            f"modal solution inconsistent: M(0) = {misfit:.3g} N·m, not 0 "
            "(mode shapes lost precision on this chain)"
        )
    return StepResponse(modes.frequencies, static, amplitudes, accel)


# --------------------------------------------------------------- maxima in time


@dataclass(frozen=True)
class Maximum:
    """The largest value of a cosine sum over a window and where it is."""

    value: float
    time: float
    # Modes too fast to sample over the window are taken at their full amplitude:
    # ``bound`` is then True and the value exceeds the truth by at most ``error``.
    bound: bool = False
    error: float = 0.0


SAMPLES_PER_PERIOD = 16
SAMPLE_BUDGET = 1 << 22
_CHUNK = 1 << 17
_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def cosine_sum_maximum(
    constant: float,
    amplitudes: Sequence[float],
    frequencies: Sequence[float],
    start: float,
    end: float,
    budget: int = SAMPLE_BUDGET,
) -> Maximum:
    """max of constant + Σ Bⱼ·cos(βⱼ·t) over start ≤ t ≤ end.

    Sampled at 16 points per period of the fastest mode that fits the budget; every
    sampled local maximum within the sampling error of the best is refined by golden
    section on its two neighbouring intervals. Modes faster than the budget allows
    are added at their amplitude |Bⱼ| (they swing through it within each of their
    periods), and the result says it is a bound with its error ½·Σ|B·β²|·(π/β_fast)².
    """
    pairs = sorted(
        ((float(b), float(w)) for b, w in zip(amplitudes, frequencies, strict=True) if b != 0.0),
        key=lambda p: p[1],
    )
    span = end - start
    slow = pairs
    fast: list[tuple[float, float]] = []
    if span > 0.0:
        for count in range(len(pairs), -1, -1):
            top = pairs[count - 1][1] if count else 0.0
            if span * top / (2.0 * math.pi) * SAMPLES_PER_PERIOD <= budget:
                slow, fast = pairs[:count], pairs[count:]
                break
    b = np.array([p[0] for p in slow])
    w = np.array([p[1] for p in slow])

    def value(t: np.ndarray) -> np.ndarray:
        return constant + np.cos(np.multiply.outer(t, w)) @ b

    top = float(w[-1]) if len(w) else 0.0
    samples = max(2, int(math.ceil(span * top / (2.0 * math.pi) * SAMPLES_PER_PERIOD)) + 1)
    step = span / (samples - 1) if samples > 1 else 0.0
    slack = float(np.sum(np.abs(b) * w * w)) * step * step / 8.0
    # First pass: the best sample; second pass: candidates within the slack of it.
    best = -math.inf
    for first in range(0, samples, _CHUNK):
        times = start + step * np.arange(first, min(first + _CHUNK, samples))
        best = max(best, float(np.max(value(times))))
    candidates: list[np.ndarray] = []
    for first in range(0, samples, _CHUNK):
        index = np.arange(max(first - 1, 0), min(first + _CHUNK + 1, samples))
        values = value(start + step * index)
        inner = np.ones(len(index), dtype=bool)
        inner[1:] &= values[1:] >= values[:-1]
        inner[:-1] &= values[:-1] >= values[1:]
        own = (index >= first) & (index < first + _CHUNK)
        pick = index[inner & own & (values >= best - slack)]
        candidates.append(pick)
    picked = np.concatenate(candidates) if candidates else np.array([], dtype=int)
    low = np.clip(start + step * (picked - 1), start, end)
    high = np.clip(start + step * (picked + 1), start, end)
    for _ in range(80):  # golden section, all candidates at once
        a = high - _GOLDEN * (high - low)
        c = low + _GOLDEN * (high - low)
        keep_left = value(a) >= value(c)
        high = np.where(keep_left, c, high)
        low = np.where(keep_left, low, a)
    points = np.concatenate([0.5 * (low + high), [start, end]])
    values = value(points)
    where = int(np.argmax(values))
    fast_amplitude = math.fsum(abs(p[0]) for p in fast)
    if not fast:
        return Maximum(float(values[where]), float(points[where]))
    # One fast mode: each of its periods brings it to +|B| while the slow sum moves
    # by at most ½·Σ|B·β²|·(π/β_fast)². With several, their phases need not line up:
    # no error is claimed (0), the value is their supremum.
    error = 0.0
    if len(fast) == 1 and len(slow) > 0:
        error = 0.5 * float(np.sum(np.abs(b) * w * w)) * (math.pi / fast[0][1]) ** 2
    return Maximum(float(values[where]) + fast_amplitude, float(points[where]), True, error)


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
    electromagnetic spring) [N·m/rad].
    Raises ArithmeticError when the matrix is singular (undamped resonance)."""
    difference = chain.difference_matrix()
    alpha = np.array(spring_damping if spring_damping is not None else [0.0] * (chain.size - 1))
    ground = np.array(absolute_damping if absolute_damping is not None else [0.0] * chain.size)
    held = np.array(ground_stiffness if ground_stiffness is not None else [0.0] * chain.size)
    damping = difference.T @ np.diag(alpha) @ difference + np.diag(ground)
    stiffness = chain.stiffness_matrix() + np.diag(held)
    dynamic = stiffness - omega * omega * chain.mass_matrix() + 1j * omega * damping
    load = np.array(torques, dtype=complex)
    scale = float(np.max(np.abs(dynamic)))
    # Judge the conditioning after a symmetric diagonal scaling S⁻¹·A·S⁻¹: a chain
    # whose stiffnesses span 10¹⁶ is not singular, only badly scaled.
    weights = np.sqrt(np.maximum(np.diag(stiffness), omega * omega * np.diag(chain.mass_matrix())))
    weights[weights == 0.0] = 1.0
    scaled = dynamic / weights[:, None] / weights[None, :]
    if scale == 0.0 or np.linalg.cond(scaled) > 1e14:
        raise ArithmeticError(f"undamped resonance at ω = {omega:.6g} rad/s: amplitude unbounded")
    angles = np.linalg.solve(scaled, load / weights) / weights
    springs = (np.array(chain.stiffnesses) + 1j * omega * alpha) * (difference @ angles)
    return angles, springs
