"""The scene: the rope reduced to two springs, the three-mass chain at a height."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mdcalc.core import chain as chains
from mdcalc.core.xp import of
from mdcalc.problems.mine_hoist.case import Case, Hoist, Rope


@dataclass(frozen=True)
class RopeReduction:
    """Seed (2)-(5): the rope's mass lumped on the masses by the lowest mode."""

    bare: chains.Chain  # the chain without the rope's mass
    bare_beta1: float  # β₁ of it [rad/s]
    a2: float  # mode (2), A₁ = 1
    a3: float
    upper: float  # L₂, vertical rope from the sheave to the node [m]
    lower: float  # L₃, from the node to the cage [m]
    chord_mass: float  # ρ·L₁ [kg]
    vertical_mass: float  # ρ·H [kg]
    reduced: tuple[float, float, float]  # J₁', J₂', J₃' [kg·m²]
    sheave_seed_printed: float | None  # J₂' by (4) as printed, where it differs


@dataclass(frozen=True)
class Scene:
    chain: chains.Chain
    drive_torque: float
    load_torque: float
    rope: RopeReduction | None = None

    @property
    def torques(self) -> tuple[float, float, float]:
        return (self.drive_torque, 0.0, -self.load_torque)


class NoNode(ValueError):
    """The lowest mode has its node on the chord, where (3)-(5) do not apply."""


def rope_reduction(
    hoist: Hoist, rope: Rope, height: float, c12: float, c23: float
) -> RopeReduction:
    """Seed (2)-(5) for one scene (:func:`reduce_rope` on a block of one); raises
    :class:`NoNode` where the lowest mode's node is not on the vertical rope."""
    block = reduce_rope(hoist, rope, height, c12, c23)
    if not block.node_on_rope[0]:
        raise NoNode(
            f"the lowest mode's node is not on the vertical rope (A₂ = {block.a2[0]:.4g}, "
            f"A₃ = {block.a3[0]:.4g}): the seed's reduction (3)-(5) assumes it is"
        )
    j1, j2, j3 = (float(part[0]) for part in block.bare)
    printed = block.sheave_seed_printed
    if rope.sheave_radius is not None and (rope.drum_radius / rope.sheave_radius) ** 2 == 1.0:
        printed = None  # (4) as printed agrees when the radii are equal
    return RopeReduction(
        chains.Chain((j1, j2, j3), (float(block.c12[0]), float(block.c23[0]))),
        float(block.bare_beta1[0]),
        float(block.a2[0]),
        float(block.a3[0]),
        float(block.upper[0]),
        float(block.lower[0]),
        float(block.chord_mass[0]),
        float(block.vertical_mass[0]),
        (float(block.reduced[0][0]), float(block.reduced[1][0]), float(block.reduced[2][0])),
        float(printed[0]) if printed is not None else None,
    )


@dataclass(frozen=True)
class ReductionBlock:
    """Seed (2)-(5) over a block of scenes: every field an array of length B."""

    bare: tuple[np.ndarray, np.ndarray, np.ndarray]  # J₁, J₂, J₃ without the rope
    c12: np.ndarray
    c23: np.ndarray
    bare_beta1: np.ndarray
    a2: np.ndarray
    a3: np.ndarray
    upper: np.ndarray
    lower: np.ndarray
    chord_mass: np.ndarray
    vertical_mass: np.ndarray
    reduced: tuple[np.ndarray, np.ndarray, np.ndarray]
    sheave_seed_printed: np.ndarray | None
    node_on_rope: np.ndarray  # bool: A₂ > 0 > A₃, where (3)-(5) apply


def reduce_rope(hoist: Hoist, rope: Rope, height: Any, c12: Any, c23: Any) -> ReductionBlock:
    """Seed (2)-(5): the rope's mass lumped on the masses by the lowest mode of the
    chain without it. The fields of ``hoist`` and ``rope`` and the other arguments
    may be floats or arrays over a block (a study's samples); the result has arrays."""
    r = rope.drum_radius
    sheave_scale = (r / rope.sheave_radius) ** 2 if rope.sheave_radius is not None else 1.0
    given = (hoist.drum_inertia, hoist.sheave_inertia * sheave_scale, hoist.cage_inertia)
    every = (*given, c12, c23, height, r, rope.mass_per_metre, rope.chord_length)
    size = np.broadcast_shapes(*(np.shape(v) for v in every)) or (1,)
    j = np.stack([np.broadcast_to(np.asarray(v, dtype=float), size) for v in given], 1)
    c = np.stack([np.broadcast_to(np.asarray(v, dtype=float), size) for v in (c12, c23)], 1)
    j1, j2, j3 = j[:, 0], j[:, 1], j[:, 2]
    c12, c23 = c[:, 0], c[:, 1]
    beta1_sq = chains.block_modes(j, c).eigenvalues[:, 0]
    a2 = (c12 - beta1_sq * j1) / c12  # (2)
    a3 = -c12 / c23 + (c12 + c23 - beta1_sq * j2) * (c12 - beta1_sq * j1) / (c12 * c23)
    upper = height * a2 / (a2 - a3)
    lower = height - upper
    third = rope.mass_per_metre * r * r / 3.0
    chord = rope.chord_length * third
    reduced = (
        j1 + (2.0 - j1 * beta1_sq / c12) * chord,  # (3) = J₁ + (1 + A₂)·ρL₁R²/3
        j2 + chord + upper * third,  # (4), rope terms already at the drum radius
        j3 + lower * third,  # (5)
    )
    printed = None
    if rope.sheave_radius is not None:  # (4) as printed scales the rope terms by (R/R_ns)²
        printed = np.broadcast_to(
            (hoist.sheave_inertia + chord + upper * third) * sheave_scale, size
        )
    whole = [np.broadcast_to(np.asarray(v, dtype=float), size) for v in (*reduced, upper, lower)]
    return ReductionBlock(
        (j1, j2, j3),
        c12,
        c23,
        np.sqrt(beta1_sq),
        a2,
        a3,
        whole[3],
        whole[4],
        np.broadcast_to(np.asarray(rope.mass_per_metre * rope.chord_length, dtype=float), size),
        np.broadcast_to(np.asarray(rope.mass_per_metre * height, dtype=float), size),
        (whole[0], whole[1], whole[2]),
        printed,
        (a2 > 0.0) & (a3 < 0.0),
    )


def stiffnesses_at(case: Case, height: float) -> tuple[float, float]:
    if case.rope is not None and case.rope.axial_stiffness is not None:
        ear2 = case.rope.axial_stiffness * case.rope.drum_radius**2
        return ear2 / case.rope.chord_length, ear2 / height
    assert case.hoist.chord_stiffness is not None and case.hoist.rope_stiffness is not None
    return case.hoist.chord_stiffness, case.hoist.rope_stiffness


def scene_at(case: Case, height: float | None = None) -> Scene:
    h = case.hoist
    if case.rope is None:
        c12, c23 = stiffnesses_at(case, 1.0)
        chain = chains.Chain((h.drum_inertia, h.sheave_inertia, h.cage_inertia), (c12, c23))
        return Scene(chain, case.loads.drive_torque, case.loads.load_torque)
    height = case.rope.length if height is None else height
    c12, c23 = stiffnesses_at(case, height)
    reduction = rope_reduction(h, case.rope, height, c12, c23)
    chain = chains.Chain(reduction.reduced, (c12, c23))
    return Scene(chain, case.loads.drive_torque, case.loads.load_torque, reduction)


def seed_formula_1(j1: Any, j2: Any, j3: Any, c12: Any, c23: Any) -> Any:
    """β₁² by the seed's (1) as printed: its first fraction carries an extra
    (J₂ + J₃)·c₂₃/(J₁·J₂) [1/s²]. Floats, or arrays over a block of scenes."""
    xp = of(j1, j2, j3, c12, c23)
    half = (((j1 + j2) * c12 + (j2 + j3) * c23) / (j1 * j2) + (j2 + j3) * c23 / (j2 * j3)) / 2.0
    product = (j1 + j2 + j3) * c12 * c23 / (j1 * j2 * j3)
    return product / (half + xp.sqrt(half * half - product))  # the smaller root
