"""The torsional chain: natural modes with their reference masses, the geometric sums
of the orders, resonant amplitudes (energy method, forced response and its peak)."""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

from mdcalc.core.search import golden_maximum
from mdcalc.problems.resonance.case import ChainSection


@dataclass
class Modal:
    frequencies: list[float]  # βⱼ [rad/s]
    shapes: list[list[float]]  # shapes[j][i]: a of mass i in mode j, a = 1 at reference
    moments: list[list[float]]  # moments[j][k]: shaft k's torque per unit reference angle
    references: list[int]  # per mode: index of the mass with a = 1 (the first if it moves)


def modal(section: ChainSection) -> Modal:
    from mdcalc.core.chain import Chain, natural_modes

    chain = Chain(tuple(section.inertias), tuple(section.stiffnesses))
    modes = natural_modes(chain)
    first_crank = (section.cranks[0] - 1) if section.cranks else 0
    shapes, moments, references = [], [], []
    for j in range(chain.size - 1):
        theta = modes.shapes[:, j].tolist()
        spring = modes.moments[:, j].tolist()
        ref = 0 if abs(theta[0]) > 1e-6 else first_crank
        if abs(theta[ref]) <= 1e-6:
            ref = max(range(len(theta)), key=lambda i: abs(theta[i]))
        references.append(ref)
        shapes.append([t / theta[ref] for t in theta])
        moments.append([m / theta[ref] for m in spring])
    return Modal(list(modes.frequencies), shapes, moments, references)


def geometric_sum(section: ChainSection, shape: list[float], order: float) -> complex:
    """Σ aᵢ·e^(i·k·δᵢ) over the cranks."""
    assert section.cranks is not None and section.firing_angles_deg is not None
    return sum(
        (
            shape[m - 1] * cmath.exp(1j * order * math.radians(d))
            for m, d in zip(section.cranks, section.firing_angles_deg, strict=True)
        ),
        0j,
    )


def is_main_order(section: ChainSection, order: float) -> bool:
    """All the cranks' phases k·δᵢ agree modulo 360°: the geometric sum is algebraic."""
    if section.firing_angles_deg is None:
        return False
    phases = [(order * d) % 360.0 for d in section.firing_angles_deg]
    return all(min(abs(p - phases[0]), 360.0 - abs(p - phases[0])) < 1e-6 for p in phases)


@dataclass(frozen=True)
class Amplitudes:
    reference_amplitude: float  # A at the reference mass [rad]
    shaft_torques: list[float]  # amplitude of each shaft's torque [N·m]

    @property
    def max_shaft_torque(self) -> float:
        return max(abs(t) for t in self.shaft_torques)


def energy_method(
    section: ChainSection, md: Modal, mode: int, order: float, torque: float
) -> Amplitudes:
    """The seed's (5): A = M_k·|Σ aᵢe^(ikδᵢ)|/(ω_c·Σ ξᵢaᵢ²)."""
    assert section.damping is not None
    shape = md.shapes[mode]
    omega = md.frequencies[mode]
    dissipation = math.fsum(x * a * a for x, a in zip(section.damping, shape, strict=True))
    if dissipation <= 0.0:
        raise ArithmeticError("no damping moves in this mode")
    amplitude = torque * abs(geometric_sum(section, shape, order)) / (omega * dissipation)
    return Amplitudes(amplitude, [amplitude * m for m in md.moments[mode]])


def forced_response(
    section: ChainSection, md: Modal, mode: int, order: float, torque: float, omega: float
) -> Amplitudes:
    """Exact steady state at vibration frequency ω (crank speed ω/k): torques
    M_k·e^(-i·k·δᵢ) on the cranks, (K - ω²J + iωΞ)·X = M."""
    from mdcalc.core.chain import Chain, harmonic_response

    assert section.cranks is not None and section.firing_angles_deg is not None
    chain = Chain(tuple(section.inertias), tuple(section.stiffnesses))
    load = [0j] * chain.size
    for m, d in zip(section.cranks, section.firing_angles_deg, strict=True):
        load[m - 1] = torque * cmath.exp(-1j * order * math.radians(d))
    angles, springs = harmonic_response(chain, omega, load, absolute_damping=section.damping)
    reference = md.references[mode]
    return Amplitudes(float(abs(angles[reference])), [float(abs(s)) for s in springs])


def peak_response(
    section: ChainSection, md: Modal, mode: int, order: float, torque: float
) -> tuple[float, Amplitudes]:
    """The largest reference amplitude over the vibration frequency near mode j:
    sampled between the neighbouring modes' midpoints, refined by golden section."""
    beta = md.frequencies
    low = 0.5 * (beta[mode - 1] + beta[mode]) if mode > 0 else 0.5 * beta[mode]
    high = 0.5 * (beta[mode] + beta[mode + 1]) if mode + 1 < len(beta) else 1.5 * beta[mode]
    low, high = max(low, 0.8 * beta[mode]), min(high, 1.2 * beta[mode])

    def amplitude(omega: float) -> float:
        return forced_response(section, md, mode, order, torque, omega).reference_amplitude

    samples = 401
    grid = [low + (high - low) * k / (samples - 1) for k in range(samples)]
    values = [amplitude(w) for w in grid]
    k = values.index(max(values))
    low, high = grid[max(k - 1, 0)], grid[min(k + 1, samples - 1)]
    omega = golden_maximum(amplitude, low, high, 80)
    return omega, forced_response(section, md, mode, order, torque, omega)
