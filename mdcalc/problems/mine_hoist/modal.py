"""The modal solution of the chain (the reference): modes, the first-swing
dynamic factors, the seed formula and the simplified factors."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mdcalc.core import chain as chains
from mdcalc.core import cosine_sums as cosines
from mdcalc.problems.mine_hoist.scene import Scene


@dataclass(frozen=True)
class Dynamics:
    """The modal solution of one scene and the maxima of μ₁₂ and μ₂₃."""

    modes: chains.Modes
    response: chains.StepResponse
    first_swing: tuple[cosines.Maximum, cosines.Maximum]
    horizon: float
    over_horizon: tuple[cosines.Maximum, cosines.Maximum]
    simplified: tuple[float, float]

    @property
    def period(self) -> float:
        return 2.0 * math.pi / self.modes.frequencies[0]

    @property
    def static(self) -> tuple[float, ...]:
        return self.response.static

    def factor(self, maximum: cosines.Maximum, spring: int) -> float:
        return maximum.value / self.static[spring]

    def supremum(self, spring: int) -> float:
        return self.response.supremum(spring) / self.static[spring]

    def coefficients(self, spring: int) -> list[float]:
        """bⱼ = Bⱼ/R of μ(t) = 1 + Σ bⱼ·cos(βⱼt)."""
        return [float(b) / self.static[spring] for b in self.response.amplitudes[spring]]


@dataclass(frozen=True)
class DynamicsBlock:
    """:class:`Dynamics` of a block of scenes (a study's samples): arrays of length B."""

    modes: chains.ModesBlock
    step: chains.StepBlock
    frequencies: np.ndarray  # (B, 2): β₁, β₂ [rad/s]
    first_swing: cosines.Maxima  # (B, 2): μ₁₂'s and μ₂₃'s moments
    horizon: np.ndarray  # [s]
    over_horizon: cosines.Maxima | None
    simplified: tuple[np.ndarray, np.ndarray]

    @property
    def period(self) -> np.ndarray:
        return 2.0 * math.pi / self.frequencies[:, 0]


def block_dynamics(
    inertias: np.ndarray,
    stiffnesses: np.ndarray,
    torques: np.ndarray,
    horizon: np.ndarray | None = None,
    over_horizon: bool = True,
) -> DynamicsBlock:
    """The modal solution of every scene of a block (J (B, 3), c (B, 2), torques
    (B, 3)), the maxima of μ₁₂ and μ₂₃ in the first swing and, if asked, over the
    horizon (default 20 periods 2π/β₁), and the simplified factors. A single scene
    is a block of one (:func:`dynamics`)."""
    modes = chains.block_modes(inertias, stiffnesses)
    step = chains.block_step(inertias, torques, modes)
    frequencies = np.sqrt(modes.eigenvalues)
    period = 2.0 * math.pi / frequencies[:, 0]
    window = horizon if horizon is not None else 20.0 * period
    zero = np.zeros(len(period))

    def maximum(end: np.ndarray) -> cosines.Maxima:
        return cosines.maxima(step.static, step.amplitudes, frequencies, zero, end)

    return DynamicsBlock(
        modes,
        step,
        frequencies,
        maximum(period),
        window,
        maximum(window) if over_horizon else None,
        simplified_factors(inertias, stiffnesses, modes, step),
    )


def dynamics(scene: Scene, horizon: float | None = None) -> Dynamics:
    j, c = scene.chain.arrays()
    window = np.array([horizon]) if horizon is not None else None
    block = block_dynamics(j, c, np.array([scene.torques]), window)
    assert block.over_horizon is not None
    return Dynamics(
        block.modes.row(0),
        block.step.row(0),
        (block.first_swing.row(0, 0), block.first_swing.row(0, 1)),
        float(block.horizon[0]),
        (block.over_horizon.row(0, 0), block.over_horizon.row(0, 1)),
        (float(block.simplified[0][0]), float(block.simplified[1][0])),
    )


def simplified_factors(
    inertias: np.ndarray, stiffnesses: np.ndarray, modes: chains.ModesBlock, step: chains.StepBlock
) -> tuple[np.ndarray, np.ndarray]:
    """(19) μ₁₂ ≈ 2 + B₁₂(fast)/R₁₂ and (20) μ₂₃ ≈ 1 + (R₁₂/R₂₃)(J₂/c₁₂)(β₁₂² - β_slow²)."""
    r12, r23 = step.static[:, 0], step.static[:, 1]
    j1, j2, c12 = inertias[:, 0], inertias[:, 1], stiffnesses[:, 0]
    beta12_sq = c12 * (1.0 / j1 + 1.0 / j2)
    mu12 = 2.0 + step.amplitudes[:, 0, 1] / r12
    mu23 = 1.0 + r12 / r23 * j2 / c12 * (beta12_sq - modes.eigenvalues[:, 0])
    return mu12, mu23


def first_swing_factors(scene: Scene) -> dict[str, float]:
    """The Methods row of the modal solution, timed from scratch: modes, amplitudes
    and the maxima over the first swing."""
    j, c = scene.chain.arrays()
    block = block_dynamics(j, c, np.array([scene.torques]), over_horizon=False)
    block.step.row(0)  # raises where the modal solution is inconsistent
    return {
        key: float(block.first_swing.value[0, k] / block.step.static[0, k])
        for k, key in enumerate(("mu12", "mu23"))
    }


def simplified_from_scratch(scene: Scene) -> dict[str, float]:
    """The Methods row of (19)-(20), timed with the modes it needs."""
    j, c = scene.chain.arrays()
    modes = chains.block_modes(j, c)
    step = chains.block_step(j, np.array([scene.torques]), modes)
    step.row(0)
    mu12, mu23 = simplified_factors(j, c, modes, step)
    return {"mu12": float(mu12[0]), "mu23": float(mu23[0])}


def frequency_ratio(dyn: Dynamics) -> float:
    return dyn.modes.frequencies[-1] / dyn.modes.frequencies[0]
