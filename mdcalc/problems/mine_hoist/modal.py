"""The modal solution of the chain (the reference): modes, the first-swing
dynamic factors, the seed formula and the simplified factors."""

from __future__ import annotations

import math
from dataclasses import dataclass

from mdcalc.core import chain as chains
from mdcalc.problems.mine_hoist.scene import Scene


@dataclass(frozen=True)
class Dynamics:
    """The modal solution of one scene and the maxima of μ₁₂ and μ₂₃."""

    modes: chains.Modes
    response: chains.StepResponse
    first_swing: tuple[chains.Maximum, chains.Maximum]
    horizon: float
    over_horizon: tuple[chains.Maximum, chains.Maximum]
    simplified: tuple[float, float]

    @property
    def period(self) -> float:
        return 2.0 * math.pi / self.modes.frequencies[0]

    @property
    def static(self) -> tuple[float, ...]:
        return self.response.static

    def factor(self, maximum: chains.Maximum, spring: int) -> float:
        return maximum.value / self.static[spring]

    def supremum(self, spring: int) -> float:
        return self.response.supremum(spring) / self.static[spring]

    def coefficients(self, spring: int) -> list[float]:
        """bⱼ = Bⱼ/R of μ(t) = 1 + Σ bⱼ·cos(βⱼt)."""
        return [float(b) / self.static[spring] for b in self.response.amplitudes[spring]]


def dynamics(scene: Scene, horizon: float | None = None) -> Dynamics:
    modes = chains.natural_modes(scene.chain)
    response = chains.suddenly_applied(scene.chain, scene.torques, modes)
    period = 2.0 * math.pi / modes.frequencies[0]
    window = horizon if horizon is not None else 20.0 * period

    def maximum(spring: int, end: float) -> chains.Maximum:
        return chains.cosine_sum_maximum(
            response.static[spring], response.amplitudes[spring], modes.frequencies, 0.0, end
        )

    return Dynamics(
        modes,
        response,
        (maximum(0, period), maximum(1, period)),
        window,
        (maximum(0, window), maximum(1, window)),
        simplified_factors(scene.chain, modes, response),
    )


def simplified_factors(
    chain: chains.Chain, modes: chains.Modes, response: chains.StepResponse
) -> tuple[float, float]:
    """(19) μ₁₂ ≈ 2 + B₁₂(fast)/R₁₂ and (20) μ₂₃ ≈ 1 + (R₁₂/R₂₃)(J₂/c₁₂)(β₁₂² - β_slow²)."""
    r12, r23 = response.static
    beta12_sq = chain.partial_eigenvalues()[0]
    mu12 = 2.0 + float(response.amplitudes[0][1]) / r12
    mu23 = 1.0 + r12 / r23 * chain.inertias[1] / chain.stiffnesses[0] * (
        beta12_sq - modes.eigenvalues[0]
    )
    return mu12, mu23


def first_swing_factors(scene: Scene) -> dict[str, float]:
    """The Methods row of the modal solution, timed from scratch: modes, amplitudes
    and the maxima over the first swing."""
    modes = chains.natural_modes(scene.chain)
    response = chains.suddenly_applied(scene.chain, scene.torques, modes)
    period = 2.0 * math.pi / modes.frequencies[0]
    return {
        key: chains.cosine_sum_maximum(
            response.static[k], response.amplitudes[k], modes.frequencies, 0.0, period
        ).value
        / response.static[k]
        for k, key in enumerate(("mu12", "mu23"))
    }


def simplified_from_scratch(scene: Scene) -> dict[str, float]:
    """The Methods row of (19)-(20), timed with the modes it needs."""
    modes = chains.natural_modes(scene.chain)
    response = chains.suddenly_applied(scene.chain, scene.torques, modes)
    mu12, mu23 = simplified_factors(scene.chain, modes, response)
    return {"mu12": mu12, "mu23": mu23}


def frequency_ratio(dyn: Dynamics) -> float:
    return dyn.modes.frequencies[-1] / dyn.modes.frequencies[0]
