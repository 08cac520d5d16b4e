"""The scene: the rope reduced to two springs, the three-mass chain at a height."""

from __future__ import annotations

import math
from dataclasses import dataclass

from mdcalc.core import chain as chains
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
    r = rope.drum_radius
    sheave_scale = (r / rope.sheave_radius) ** 2 if rope.sheave_radius is not None else 1.0
    j1, j2, j3 = hoist.drum_inertia, hoist.sheave_inertia * sheave_scale, hoist.cage_inertia
    bare = chains.Chain((j1, j2, j3), (c12, c23))
    beta1_sq = chains.natural_modes(bare).eigenvalues[0]
    a2 = (c12 - beta1_sq * j1) / c12  # (2)
    a3 = -c12 / c23 + (c12 + c23 - beta1_sq * j2) * (c12 - beta1_sq * j1) / (c12 * c23)
    if not (a2 > 0.0 > a3):
        raise NoNode(
            f"the lowest mode's node is not on the vertical rope (A₂ = {a2:.4g}, "
            f"A₃ = {a3:.4g}): the seed's reduction (3)-(5) assumes it is"
        )
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
    if sheave_scale != 1.0:  # (4) as printed scales the rope terms by (R/R_ns)² too
        printed = (hoist.sheave_inertia + chord + upper * third) * sheave_scale
    return RopeReduction(
        bare,
        math.sqrt(beta1_sq),
        a2,
        a3,
        upper,
        lower,
        rope.mass_per_metre * rope.chord_length,
        rope.mass_per_metre * height,
        reduced,
        printed,
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


def seed_formula_1(chain: chains.Chain) -> float:
    """β₁² by the seed's (1) as printed: its first fraction carries an extra
    (J₂ + J₃)·c₂₃/(J₁·J₂) [1/s²]."""
    (j1, j2, j3), (c12, c23) = chain.inertias, chain.stiffnesses
    half = (((j1 + j2) * c12 + (j2 + j3) * c23) / (j1 * j2) + (j2 + j3) * c23 / (j2 * j3)) / 2.0
    product = (j1 + j2 + j3) * c12 * c23 / (j1 * j2 * j3)
    return product / (half + math.sqrt(half * half - product))  # the smaller root
