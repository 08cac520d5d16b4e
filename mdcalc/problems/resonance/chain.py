"""The torsional chain: natural modes with their reference masses, the geometric sums
of the orders, resonant amplitudes (energy method, forced response and its peak).

Each works on a block of chains at once (a study's samples: numpy arrays with a
leading axis of length B); one scene is a block of one, so both take the same
arithmetic."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mdcalc.core.search import golden_maximum
from mdcalc.problems.resonance.case import ChainSection


@dataclass
class Modal:
    frequencies: list[float]  # βⱼ [rad/s]
    shapes: list[list[float]]  # shapes[j][i]: a of mass i in mode j, a = 1 at reference
    moments: list[list[float]]  # moments[j][k]: shaft k's torque per unit reference angle
    references: list[int]  # per mode: index of the mass with a = 1 (the first if it moves)


@dataclass
class ModalBlock:
    """:class:`Modal` of a block of chains."""

    frequencies: np.ndarray  # (B, m)
    shapes: np.ndarray  # (B, m, n)
    moments: np.ndarray  # (B, m, n-1)
    references: np.ndarray  # (B, m), int


def whole(values: list[Any], size: int) -> np.ndarray:
    """A list of the case whose items are floats or arrays over the block: (B, len)."""
    return np.stack([np.broadcast_to(np.asarray(v, dtype=float), (size,)) for v in values], 1)


def modal(section: ChainSection) -> Modal:
    block = modal_block(section, 1)
    return Modal(
        block.frequencies[0].tolist(),
        block.shapes[0].tolist(),
        block.moments[0].tolist(),
        [int(r) for r in block.references[0]],
    )


def modal_block(section: ChainSection, size: int) -> ModalBlock:
    """The natural modes, each scaled to a = 1 at its reference mass: the first mass,
    or the first crank where the first mass is (nearly) a node, else the mass that
    moves most."""
    from mdcalc.core.chain import block_modes

    modes = block_modes(whole(section.inertias, size), whole(section.stiffnesses, size))
    theta, spring = modes.shapes, modes.moments  # (B, n, m), (B, n-1, m)
    first_crank = (section.cranks[0] - 1) if section.cranks else 0
    reference = np.where(np.abs(theta[:, 0, :]) > 1e-6, 0, first_crank)
    at = np.take_along_axis(theta, reference[:, None, :], axis=1)[:, 0, :]
    reference = np.where(np.abs(at) <= 1e-6, np.argmax(np.abs(theta), axis=1), reference)
    at = np.take_along_axis(theta, reference[:, None, :], axis=1)[:, 0, :]
    shapes = np.swapaxes(theta / at[:, None, :], 1, 2)
    moments = np.swapaxes(spring / at[:, None, :], 1, 2)
    return ModalBlock(np.sqrt(modes.eigenvalues), shapes, moments, reference)


def geometric_sum(section: ChainSection, shape: list[float], order: float) -> complex:
    """Σ aᵢ·e^(i·k·δᵢ) over the cranks."""
    return complex(geometric_sums(section, np.array([shape]), order)[0])


def geometric_sums(section: ChainSection, shapes: np.ndarray, order: Any) -> np.ndarray:
    """Σ aᵢ·e^(i·k·δᵢ) over the cranks, for each row of ``shapes`` (B, n)."""
    assert section.cranks is not None and section.firing_angles_deg is not None
    total = np.zeros(len(shapes), dtype=complex)
    for m, d in zip(section.cranks, section.firing_angles_deg, strict=True):
        total = total + shapes[:, m - 1] * np.exp(1j * (order * np.radians(d)))
    return total


def crank_sum(section: ChainSection, shapes: np.ndarray) -> np.ndarray:
    """Σ aᵢ over the cranks (the algebraic sum), for each row of ``shapes`` (B, n)."""
    assert section.cranks is not None
    total = np.zeros(len(shapes))
    for m in section.cranks:
        total = total + shapes[:, m - 1]
    return total


def algebraic_sum(section: ChainSection, shape: list[float]) -> float:
    """Σ aᵢ over the cranks of one mode shape."""
    return float(crank_sum(section, np.array([shape]))[0])


def total_damping(damping: np.ndarray) -> np.ndarray:
    """Σ ξᵢ of each row (B, n) [N·m·s/rad]."""
    total = damping[:, 0]
    for i in range(1, damping.shape[1]):
        total = total + damping[:, i]
    return total


def undamped_mode(damping: np.ndarray, work: np.ndarray) -> np.ndarray:
    """Where no damping moves in the mode: Σ ξᵢ·aᵢ² ≤ 10⁻¹² Σ ξᵢ, or no damping."""
    return (work <= 1e-12 * total_damping(damping)) | ~np.any(damping != 0.0, axis=1)


def dissipation(damping: np.ndarray, shapes: np.ndarray) -> np.ndarray:
    """Σ ξᵢ·aᵢ² of a mode, for each row (damping and shapes (B, n)) [N·m·s/rad]."""
    total = np.zeros(len(shapes))
    for i in range(shapes.shape[1]):
        total = total + damping[:, i] * shapes[:, i] * shapes[:, i]
    return total


def modal_dissipation(section: ChainSection, md: Modal, mode: int) -> float:
    assert section.damping is not None
    return float(dissipation(np.array([section.damping]), np.array([md.shapes[mode]]))[0])


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


@dataclass(frozen=True)
class AmplitudesBlock:
    """:class:`Amplitudes` of a block of chains."""

    reference_amplitude: np.ndarray  # (B,)
    shaft_torques: np.ndarray  # (B, n-1)
    singular: np.ndarray  # (B,) bool: the forced response has no finite answer

    @property
    def max_shaft_torque(self) -> np.ndarray:
        return np.max(np.abs(self.shaft_torques), axis=1)

    def row(self, index: int) -> Amplitudes:
        return Amplitudes(
            float(self.reference_amplitude[index]), self.shaft_torques[index].tolist()
        )


def _one(md: Modal) -> ModalBlock:
    return ModalBlock(
        np.array([md.frequencies]),
        np.array([md.shapes]),
        np.array([md.moments]),
        np.array([md.references]),
    )


def energy_method(
    section: ChainSection, md: Modal, mode: int, order: float, torque: float
) -> Amplitudes:
    """The seed's (5): A = M_k·|Σ aᵢe^(ikδᵢ)|/(ω_c·Σ ξᵢaᵢ²)."""
    assert section.damping is not None
    block = energy_block(section, _one(md), mode, order, torque, np.array([section.damping]))
    if block.singular[0]:
        raise ArithmeticError("no damping moves in this mode")
    return block.row(0)


def energy_block(
    section: ChainSection,
    md: ModalBlock,
    mode: int,
    order: Any,
    torque: Any,
    damping: np.ndarray,
) -> AmplitudesBlock:
    """The seed's (5) for a block: ``singular`` where no damping moves in the mode."""
    shapes = md.shapes[:, mode, :]
    omega = md.frequencies[:, mode]
    work = dissipation(damping, shapes)
    with np.errstate(all="ignore"):
        amplitude = torque * np.abs(geometric_sums(section, shapes, order)) / (omega * work)
    torques = amplitude[:, None] * md.moments[:, mode, :]
    return AmplitudesBlock(amplitude, torques, ~(work > 0.0))


def forced_response(
    section: ChainSection, md: Modal, mode: int, order: float, torque: float, omega: float
) -> Amplitudes:
    """Exact steady state at vibration frequency ω (crank speed ω/k): torques
    M_k·e^(-i·k·δᵢ) on the cranks, (K - ω²J + iωΞ)·X = M."""
    assert section.damping is not None
    block = forced_block(
        section, _one(md), mode, order, torque, np.array([omega]), np.array([section.damping]), 1
    )
    if block.singular[0]:
        raise ArithmeticError(f"undamped resonance at ω = {omega:.6g} rad/s: amplitude unbounded")
    return block.row(0)


def forced_block(
    section: ChainSection,
    md: ModalBlock,
    mode: int,
    order: Any,
    torque: Any,
    omega: np.ndarray,
    damping: np.ndarray,
    size: int,
) -> AmplitudesBlock:
    """The exact steady state of a block of chains at ω each (``singular`` where the
    dynamic matrix is singular to working precision)."""
    from mdcalc.core.chain import block_harmonic_response

    assert section.cranks is not None and section.firing_angles_deg is not None
    j, c = whole(section.inertias, size), whole(section.stiffnesses, size)
    load = np.zeros(j.shape, dtype=complex)
    for m, d in zip(section.cranks, section.firing_angles_deg, strict=True):
        load[:, m - 1] = torque * np.exp(-1j * (order * np.radians(d)))
    angles, springs, singular = block_harmonic_response(j, c, omega, load, absolute_damping=damping)
    reference = md.references[:, mode]
    at = np.abs(np.take_along_axis(angles, reference[:, None], axis=1)[:, 0])
    return AmplitudesBlock(at, np.abs(springs), singular)


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
