"""The scene: the case reduced to the twist oscillator (β, p, ζ), and the closed
forms of the suddenly applied and the harmonic torques; floats, or numpy arrays
over a sweep grid."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from mdcalc.core import sdof
from mdcalc.core.xp import of
from mdcalc.problems.coupling.case import DEG, Case, Harmonic


@dataclass(frozen=True)
class Scene:
    """Floats; or numpy arrays over a sweep's grid (the same formulas, core/xp)."""

    j1: Any
    j2: Any
    stiffness: Any  # c [N·m/rad]
    p: Any  # [1/s]

    @property
    def reduced_inertia(self) -> float:
        return self.j1 * self.j2 / (self.j1 + self.j2)

    @property
    def beta(self) -> float:
        squared = self.stiffness / self.reduced_inertia
        return of(squared).sqrt(squared)

    @property
    def period(self) -> float:
        """τ = 2π/β (8.5), the lecture's period (undamped)."""
        return 2.0 * math.pi / self.beta

    @property
    def zeta(self) -> float:
        return self.p / (2.0 * self.beta)

    @property
    def log_decrement(self) -> Any:
        """δ = p·τ/2 (8.7)."""
        return self.p * self.period / 2.0

    @property
    def absorption(self) -> Any:
        """ψ = 2δ = p·τ (8.14)."""
        return self.p * self.period

    @property
    def alpha(self) -> float:
        """α = p·J [N·m·s/rad]."""
        return self.p * self.reduced_inertia


def scene_of(case: Case) -> Scene:
    """The scene; of a case whose fields are numpy arrays in :func:`sweep`."""
    k = case.coupling
    if k.stiffness is not None:
        stiffness = k.stiffness
    else:  # validated: exactly one (no `or`: arrays in sweep)
        assert k.stiffness_nm_per_deg is not None
        stiffness = k.stiffness_nm_per_deg / DEG
    j = k.driving_inertia * k.driven_inertia / (k.driving_inertia + k.driven_inertia)
    tau = 2.0 * math.pi / of(stiffness, j).sqrt(stiffness / j)
    if k.absorption is not None:
        p = k.absorption / tau  # (8.7), (8.14): δ = ψ/2 = p·τ/2
    elif k.log_decrement is not None:
        p = 2.0 * k.log_decrement / tau
    elif k.damping is not None:
        p = k.damping / j  # p = α·(1/J₁ + 1/J₂)
    else:
        p = 0.0
    return Scene(k.driving_inertia, k.driven_inertia, stiffness, p)


def harmonic_numbers(h: Harmonic, s: Scene) -> dict[str, Any]:
    """(8.21)-(8.27) by result key, floats or (in :func:`sweep`) arrays; the report
    shows steady_torque_total and gamma only with damping. Undamped resonance (no
    answer) divides by 0."""
    torques = h.driving_torque, h.driven_torque, h.driving_phase_deg, h.driven_phase_deg
    xp = of(*torques, h.omega, s.j1, s.j2, s.stiffness, s.p)
    a1, a2 = h.driving_torque / s.j1, h.driven_torque / s.j2
    alpha, gamma_phase = h.driving_phase_deg * DEG, h.driven_phase_deg * DEG
    real = a1 * xp.cos(alpha) + a2 * xp.cos(gamma_phase)
    imag = a1 * xp.sin(alpha) + a2 * xp.sin(gamma_phase)
    m = xp.hypot(real, imag)  # (8.21)
    twist = m / xp.hypot(s.beta**2 - h.omega**2, s.p * h.omega)  # (8.27)
    return {
        "combined_amplitude": m,
        "combined_phase": xp.degrees(xp.atan2(imag, real)),
        "frequency_ratio": h.omega / s.beta,
        "steady_twist": twist,
        "steady_torque": s.stiffness * twist,
        "steady_torque_total": xp.hypot(s.stiffness, s.alpha * h.omega) * twist,
        "gamma": s.p / s.beta,
    }


def resonance(m: Any, s: Scene) -> tuple[Any, Any]:
    """λ of the resonance peak (8.31) and its twist (corrected (8.32)) for the combined
    amplitude m; the report shows them for p > 0 and γ² < 2."""
    gamma = s.p / s.beta
    xp = of(m, gamma)
    peak = m / (s.beta**2 * gamma * xp.sqrt(1.0 - gamma**2 / 4.0))
    return xp.sqrt(1 - gamma**2 / 2), peak


def step_numbers(torque: Any, s: Scene) -> dict[str, Any]:
    """(8.15)-(8.16) by result key: the suddenly applied torque's dynamic factor, the
    time of its first peak (None, or nan in an array, without overshoot) and the
    envelope; the twist and torque where the torque is given. Floats or arrays."""
    zeta = s.zeta
    factor = sdof.step_peak(zeta)
    numbers = {
        "step_dynamic_factor": factor,
        "step_peak_time": sdof.step_peak_time(s.beta, zeta),
        "envelope_at_period": sdof.step_envelope(s.period, s.beta, zeta),
        "envelope_at_1_5_period": sdof.step_envelope(1.5 * s.period, s.beta, zeta),
        "undamped_dynamic_factor": 2.0,
    }
    if torque is not None:
        numbers |= {
            "static_twist": torque / s.stiffness,
            "peak_twist": factor * torque / s.stiffness,
            "peak_torque": factor * torque,
        }
    return numbers
