"""``mine-hoist``: dynamic factors in the ropes of a mine hoist with a head sheave,
a three-mass torsional chain (seed 002; brief §6).

Model: J₁ (motor, reducer, drum), J₂ (head sheave), J₃ (cage with load and its share
of the rope), all reduced to the drum axis; c₁₂ the rope chord from drum to sheave,
c₂₃ the vertical rope from sheave to cage. The drive torque M₁ and the load torque
W (resisting) are applied suddenly to the chain at rest with unloaded ropes. The
rope moments M₁₂ = c₁₂(φ₁ - φ₂), M₂₃ = c₂₃(φ₂ - φ₃) obey seed (6); their static
parts R₁₂, R₂₃ are (11)-(12) with M₃ = -W; μ = M/R are the dynamic factors.

* Exact modal solution (:mod:`mdcalc.core.chain`): μ(t) = 1 + Σ bⱼ·cos(βⱼt), the
  maximum in the first swing (t ≤ 2π/β₁), over a horizon, and the undamped supremum
  1 + Σ|bⱼ|.
* The seed's simplified formulas (19)-(20), read by meaning: the seed's labels of the
  two modes are swapped between (17) and (18). (19) is 2 + b₁₂(fast), i.e. the slow
  swing alone; (20) is 1 + (R₁₂/R₂₃)(J₂/c₁₂)(β₁₂² - β_slow²), i.e. B₁₂(slow) ≈ -R₁₂.
* ODE runs of (6), explicit (DOP853) and implicit (Radau) at three tolerances.
* Optional rope-mass reduction (2)-(5) and a height sweep (the seed's Table 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import partial
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from pydantic import Field, model_validator

from mdcalc.core import chain as chains
from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.methods import Method, NotApplicable, compare
from mdcalc.model import CaseBase, CaseModel, FieldError
from mdcalc.report import (
    Column,
    MethodQuantity,
    MethodsTable,
    Note,
    Quantities,
    Quantity,
    Report,
    Table,
)

if TYPE_CHECKING:
    from mdcalc.plot import Chart

# ------------------------------------------------------------------------ the case


class Hoist(CaseModel):
    drum_inertia: float = Field(
        gt=0, description="J₁, motor rotor, reducer and drum, at the drum axis [kg·m^2]"
    )
    sheave_inertia: float = Field(
        gt=0,
        description=(
            "J₂, head sheave reduced to the drum axis; its own inertia when "
            "rope.sheave_radius is given [kg·m^2]"
        ),
    )
    cage_inertia: float = Field(
        gt=0,
        description=(
            "J₃, cage with load reduced to the drum axis (m·R²), with the rope's share "
            "unless a [rope] section adds it [kg·m^2]"
        ),
    )
    chord_stiffness: float | None = Field(
        default=None,
        gt=0,
        description="c₁₂, rope chord drum-sheave; or rope.axial_stiffness [N·m/rad]",
    )
    rope_stiffness: float | None = Field(
        default=None,
        gt=0,
        description="c₂₃, vertical rope sheave-cage; or rope.axial_stiffness [N·m/rad]",
    )


class Loads(CaseModel):
    drive_torque: float = Field(
        ge=0, le=1e12, description="M₁, starting torque of the drive on the drum [N·m]"
    )
    load_torque: float = Field(
        ge=0, le=1e12, description="W, load torque resisting the lift, at the drum axis [N·m]"
    )

    @model_validator(mode="after")
    def _something(self) -> Loads:
        if self.drive_torque == 0.0 and self.load_torque == 0.0:
            raise FieldError(("drive_torque",), "both torques are 0: nothing loads the ropes")
        return self


class Rope(CaseModel):
    mass_per_metre: float = Field(gt=0, description="ρ, mass of one metre of rope [kg/m]")
    drum_radius: float = Field(gt=0, description="R, drum radius [m]")
    chord_length: float = Field(gt=0, description="L₁, rope chord from drum to sheave [m]")
    length: float = Field(gt=0, description="H, vertical rope from sheave to cage [m]")
    axial_stiffness: float | None = Field(
        default=None,
        gt=0,
        description="E·A of the rope; then c₁₂ = EA·R²/L₁ and c₂₃ = EA·R²/H [N]",
    )
    sheave_radius: float | None = Field(
        default=None,
        gt=0,
        description="R_ns; then hoist.sheave_inertia is the sheave's own, reduced by (R/R_ns)² [m]",
    )


class Analysis(CaseModel):
    horizon: float | None = Field(
        default=None, gt=0, description="Window for the maxima; default 20 periods 2π/β₁ [s]"
    )
    time_points: int = Field(
        default=21, ge=2, le=2001, description="Rows of the μ(t) table over the first swing [-]"
    )
    ode: bool = Field(default=True, description="Run the ODE rows of the Methods table [-]")


class Sweep(CaseModel):
    heights: list[float] = Field(
        min_length=1, max_length=200, description="Heights H for the seed's Table 1 [m]"
    )

    @model_validator(mode="after")
    def _positive(self) -> Sweep:
        for index, height in enumerate(self.heights):
            if not height > 0.0:
                raise FieldError(("heights", index), f"got {height}; every height must be > 0 m")
        return self


class Case(CaseBase):
    problem: Literal["mine-hoist"] = Field(description="Problem name [-]")
    hoist: Hoist
    loads: Loads
    rope: Rope | None = None
    analysis: Analysis = Analysis()
    sweep: Sweep | None = None

    @model_validator(mode="after")
    def _stiffness_sources(self) -> Case:
        from_rope = self.rope is not None and self.rope.axial_stiffness is not None
        for key in ("chord_stiffness", "rope_stiffness"):
            given = getattr(self.hoist, key) is not None
            if given and from_rope:
                raise FieldError(
                    ("hoist", key),
                    "given twice: rope.axial_stiffness already sets it (c = EA·R²/L)",
                )
            if not given and not from_rope:
                raise FieldError(("hoist", key), "missing: give it, or rope.axial_stiffness")
        if self.sweep is not None and not from_rope:
            raise FieldError(
                ("sweep", "heights"),
                "a height sweep needs [rope] with axial_stiffness (c₂₃ = EA·R²/H changes with H)",
            )
        return self


# ------------------------------------------------------------------------ the scene


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


# ---------------------------------------------------------------------- dynamics


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


# ------------------------------------------------------------------------ ODE rows

#: Right-hand-side evaluations per period of the fastest mode, measured on the
#: seed's case, to predict an ODE row's cost before running it.
EVALUATIONS_PER_FAST_PERIOD = {
    ("DOP853", 1e-3): 45,
    ("DOP853", 1e-6): 105,
    ("DOP853", 1e-9): 205,
    ("Radau", 1e-3): 90,
    ("Radau", 1e-6): 420,
    ("Radau", 1e-9): 2200,
}
EVALUATION_BUDGET = 60_000
#: β_max/β_min from which the scene counts as stiff (and Radau is the ODE reference).
STIFF_RATIO = 100.0


def ode_evaluations(dyn: Dynamics, method: str, rtol: float) -> int:
    """Predicted right-hand-side evaluations of an ODE row over the first swing."""
    return int(followed_periods(dyn, method, rtol) * EVALUATIONS_PER_FAST_PERIOD[(method, rtol)])


def followed_frequency(dyn: Dynamics, method: str, rtol: float) -> float:
    """The fastest mode a solver has to follow: for an explicit one the fastest of
    all (its stability demands it); an implicit one steps over modes whose
    amplitude in μ is below its tolerance."""
    frequencies = dyn.modes.frequencies
    if method != "Radau":
        return frequencies[-1]
    b12, b23 = dyn.coefficients(0), dyn.coefficients(1)
    return max(
        (w for j, w in enumerate(frequencies) if max(abs(b12[j]), abs(b23[j])) > rtol),
        default=frequencies[0],
    )


def followed_periods(dyn: Dynamics, method: str, rtol: float) -> float:
    return dyn.period * followed_frequency(dyn, method, rtol) / (2.0 * math.pi) + 5.0


def ode_first_swing(scene: Scene, dyn: Dynamics, method: str, rtol: float) -> dict[str, float]:
    from mdcalc.core.ode import TooManySteps, linear_oscillator_maxima

    estimate = ode_evaluations(dyn, method, rtol)
    if estimate > EVALUATION_BUDGET:
        raise NotApplicable(
            f"about {estimate:,} evaluations (the budget is {EVALUATION_BUDGET:,}): the "
            f"solver must follow the mode at {followed_frequency(dyn, method, rtol):.5g} "
            f"rad/s through {followed_periods(dyn, method, rtol):,.0f} periods in the first "
            "swing"
        )
    a, f = chains.moment_equations(scene.chain, scene.torques)
    r = np.array(dyn.static)
    try:
        peaks, _, _ = linear_oscillator_maxima(
            a * r[None, :] / r[:, None],  # in units of R: μ'' = -D⁻¹AD·μ + D⁻¹f
            f / r,
            dyn.period,
            rtol,
            method,
            max_evaluations=2 * EVALUATION_BUDGET,
        )
    except TooManySteps as stopped:
        raise NotApplicable(str(stopped)) from None
    return {"mu12": peaks[0], "mu23": peaks[1]}


# ------------------------------------------------------------------------- result


@dataclass
class SweepRow:
    height: float
    scene: Scene
    dynamics: Dynamics


@dataclass
class Result:
    case: Case
    scene: Scene | None = None
    dynamics: Dynamics | None = None
    methods: MethodsTable | None = None
    sweep: list[SweepRow] = field(default_factory=list)
    ode_reference: str | None = None  # the Methods row that stands as the ODE reference
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


FACTORS = [
    MethodQuantity("mu12", "μ₁₂ max", ""),
    MethodQuantity("mu23", "μ₂₃ max", ""),
]
ODE_ROWS = (
    ("DOP853", "explicit", 1e-3),
    ("DOP853", "explicit", 1e-6),
    ("DOP853", "explicit", 1e-9),
    ("Radau", "implicit", 1e-3),
    ("Radau", "implicit", 1e-6),
    ("Radau", "implicit", 1e-9),
)


def _mark_ode_reference(table: MethodsTable, dyn: Dynamics) -> str | None:
    """Mark the ODE reference among the rows that produced a value: the tightest
    Radau row on a stiff chain, else the tightest DOP853 row."""
    solver = "Radau" if frequency_ratio(dyn) >= STIFF_RATIO else "DOP853"
    ran = [row for row in table.rows if row.method.startswith(f"ODE {solver}") and row.values]
    if not ran:
        return None
    ran[-1].note = "ODE reference for this scene"
    return ran[-1].method


def frequency_ratio(dyn: Dynamics) -> float:
    return dyn.modes.frequencies[-1] / dyn.modes.frequencies[0]


def solve(case: Case) -> Result:
    result = Result(case)
    loads = case.loads
    if loads.drive_torque < loads.load_torque:
        result.status = "no-answer"
        result.message = (
            f"the drive torque M₁ = {loads.drive_torque:.6g} N·m is below the load torque "
            f"W = {loads.load_torque:.6g} N·m: the drive cannot lift the cage"
        )
        return result
    try:
        scene = scene_at(case)
    except NoNode as reason:
        result.status, result.message = "no-answer", str(reason)
        return result
    dyn = dynamics(scene, case.analysis.horizon)
    result.scene, result.dynamics = scene, dyn
    methods = [
        Method("modal solution, exact", lambda: first_swing_factors(scene), reference=True),
        Method(
            "simplified (19)-(20)",
            lambda: simplified_from_scratch(scene),
            note="seed 002",
        ),
    ]
    if case.analysis.ode:
        for method, kind, rtol in ODE_ROWS:
            methods.append(
                Method(
                    f"ODE {method} ({kind}), rtol {rtol:.0e}".replace("e-0", "e-"),
                    partial(ode_first_swing, scene, dyn, method, rtol),
                    imports=ODE_IMPORTS,
                )
            )
    result.methods = compare(
        "Methods: largest μ in the first swing, t ≤ 2π/β₁",
        "first_swing",
        FACTORS,
        methods,
    )
    result.ode_reference = _mark_ode_reference(result.methods, dyn)
    if case.sweep is not None:
        for height in case.sweep.heights:
            try:
                at = scene_at(case, height)
            except NoNode as reason:
                result.status = "no-answer"
                result.message = f"at H = {height:g} m {reason}"
                return result
            result.sweep.append(SweepRow(height, at, dynamics(at)))
    return result


# ------------------------------------------------------------------------- report


def report(result: Result) -> Report:
    case = result.case
    title = case.title or "Mine hoist with head sheave"
    notes: list[Note] = []
    if result.status != "ok" or result.scene is None or result.dynamics is None:
        return Report("mine-hoist", title, [], notes, result.status, result.message)
    scene, dyn = result.scene, result.dynamics
    sections: list[Any] = []
    if scene.rope is not None:
        assert case.rope is not None
        sections.append(_rope_section(case.rope, scene.rope))
    sections.append(_chain_section(scene, dyn))
    sections.append(_static_section(scene, dyn))
    sections.append(_modes_table(dyn))
    sections.append(_factors_section(dyn))
    assert result.methods is not None
    sections.append(result.methods)
    sections.append(_history_table(dyn, case.analysis.time_points))
    if result.sweep:
        sections.append(_sweep_table(result.sweep))
    ratio = frequency_ratio(dyn)
    if ratio >= STIFF_RATIO:
        text = f"stiff chain: β₂/β₁ = {ratio:.4g}. The modal solution is exact at any ratio."
        if case.analysis.ode:
            text += (
                f" The ODE reference is the implicit row “{result.ode_reference}”."
                if result.ode_reference
                else " No Radau (implicit) row fits the budget: the undamped fast mode, "
                "excited by the sudden start well above the tolerances, must be followed "
                "through every period."
            )
        notes.append(Note("info", text))
    for spring, maximum, r in (
        (12, dyn.over_horizon[0], dyn.static[0]),
        (23, dyn.over_horizon[1], dyn.static[1]),
    ):
        if maximum.bound:
            notes.append(
                Note(
                    "info",
                    f"μ{spring} over the horizon: modes too fast to sample over "
                    f"{dyn.horizon:.4g} s are taken at their full amplitude, so the value "
                    + (
                        f"is an upper bound, high by at most {maximum.error / r:.2g}"
                        if maximum.error > 0.0
                        else "is an upper bound (the supremum, where no mode could be sampled)"
                    ),
                )
            )
    if scene.rope is not None and scene.rope.sheave_seed_printed is not None:
        notes.append(
            Note(
                "info",
                f"(4) as printed multiplies the rope terms by (R/R_ns)² too and gives "
                f"J₂' = {scene.rope.sheave_seed_printed:.6g} kg·m²; the rope moves with the "
                "drum's rim speed, so only the sheave's own inertia is scaled here",
            )
        )
    return Report("mine-hoist", title, sections, notes)


def _rope_section(rope: Rope, red: RopeReduction) -> Quantities:
    j1, j2, j3 = red.reduced
    return Quantities(
        "Rope-mass reduction (2)-(5), by the lowest mode of the chain without rope mass",
        [
            Quantity("rope_chord_mass", "Chord mass ρ·L₁", red.chord_mass, "kg"),
            Quantity("rope_vertical_mass", "Vertical rope mass ρ·H", red.vertical_mass, "kg"),
            Quantity("bare_beta1", "β₁ without rope mass", red.bare_beta1, "rad/s"),
            Quantity("mode_a2", "Mode (2): A₂ (A₁ = 1)", red.a2, ""),
            Quantity("mode_a3", "Mode (2): A₃", red.a3, ""),
            Quantity("node_from_sheave", "Node O below the sheave, L₂", red.upper, "m"),
            Quantity("node_to_cage", "Node O above the cage, L₃", red.lower, "m"),
            Quantity("drum_inertia_reduced", "J₁' (3)", j1, "kg·m²"),
            Quantity("sheave_inertia_reduced", "J₂' (4)", j2, "kg·m²"),
            Quantity("cage_inertia_reduced", "J₃' (5)", j3, "kg·m²"),
        ],
    )


def _chain_section(scene: Scene, dyn: Dynamics) -> Quantities:
    chain = scene.chain
    (j1, j2, j3), (c12, c23) = chain.inertias, chain.stiffnesses
    beta12_sq, beta23_sq = chain.partial_eigenvalues()
    beta1, beta2 = dyn.modes.frequencies
    printed = seed_formula_1(chain)
    return Quantities(
        "Three-mass chain",
        [
            Quantity("drum_inertia", "J₁", j1, "kg·m²"),
            Quantity("sheave_inertia", "J₂", j2, "kg·m²"),
            Quantity("cage_inertia", "J₃", j3, "kg·m²"),
            Quantity("chord_stiffness", "c₁₂", c12, "N·m/rad"),
            Quantity("rope_stiffness", "c₂₃", c23, "N·m/rad"),
            Quantity("partial_beta12", "β₁₂ = √(c₁₂(1/J₁ + 1/J₂))", math.sqrt(beta12_sq), "rad/s"),
            Quantity("partial_beta23", "β₂₃ = √(c₂₃(1/J₂ + 1/J₃))", math.sqrt(beta23_sq), "rad/s"),
            Quantity("beta1", "β₁, lowest natural frequency", beta1, "rad/s"),
            Quantity("beta2", "β₂", beta2, "rad/s"),
            Quantity("period1", "Period 2π/β₁ (the first swing)", dyn.period, "s"),
            Quantity("frequency_ratio", "β₂/β₁", beta2 / beta1, ""),
            Quantity(
                "beta1_squared_seed_formula",
                "β₁² by (1) as printed",
                printed,
                "1/s²",
                f"{printed / beta1**2 - 1:+.2%} against the characteristic equation "
                f"({beta1**2:.6g} 1/s²)",
            ),
        ],
    )


def _static_section(scene: Scene, dyn: Dynamics) -> Quantities:
    r12, r23 = dyn.static
    return Quantities(
        "Static rope moments (11)-(12)",
        [
            Quantity("drive_torque", "M₁", scene.drive_torque, "N·m"),
            Quantity("load_torque", "W", scene.load_torque, "N·m"),
            Quantity("acceleration", "ε = (M₁ - W)/ΣJ", dyn.response.acceleration, "rad/s²"),
            Quantity("static_moment_12", "R₁₂ = [M₁(J₂ + J₃) + W·J₁]/ΣJ", r12, "N·m"),
            Quantity("static_moment_23", "R₂₃ = [M₁·J₃ + W(J₁ + J₂)]/ΣJ", r23, "N·m"),
        ],
    )


def _modes_table(dyn: Dynamics) -> Table:
    rows: list[list[Any]] = []
    b12, b23 = dyn.coefficients(0), dyn.coefficients(1)
    for j, beta in enumerate(dyn.modes.frequencies):
        shape = dyn.modes.shapes[:, j] / dyn.modes.shapes[0, j]
        rows.append(
            [j + 1, beta, 2.0 * math.pi / beta, float(shape[1]), float(shape[2]), b12[j], b23[j]]
        )
    return Table(
        "Modal solution (15)-(16): μ(t) = 1 + Σ b·cos(βt)",
        "modes",
        [
            Column("mode"),
            Column("β", "rad/s"),
            Column("period", "s"),
            Column("θ₂/θ₁"),
            Column("θ₃/θ₁"),
            Column("b in μ₁₂"),
            Column("b in μ₂₃"),
        ],
        rows,
    )


def _factors_section(dyn: Dynamics) -> Quantities:
    r12, r23 = dyn.static
    f12, f23 = dyn.first_swing
    h12, h23 = dyn.over_horizon
    s12, s23 = dyn.simplified
    sup12, sup23 = dyn.supremum(0), dyn.supremum(1)
    return Quantities(
        "Dynamic factors μ = M/R",
        [
            Quantity("mu12_first_swing", "μ₁₂, first swing", dyn.factor(f12, 0), ""),
            Quantity("mu12_first_swing_time", "at t", f12.time, "s"),
            Quantity("mu23_first_swing", "μ₂₃, first swing", dyn.factor(f23, 1), ""),
            Quantity("mu23_first_swing_time", "at t", f23.time, "s"),
            Quantity("horizon", "Horizon", dyn.horizon, "s"),
            Quantity(
                "mu12_horizon",
                "μ₁₂, over the horizon",
                dyn.factor(h12, 0),
                "",
                "upper bound" if h12.bound else "",
            ),
            Quantity(
                "mu23_horizon",
                "μ₂₃, over the horizon",
                dyn.factor(h23, 1),
                "",
                "upper bound" if h23.bound else "",
            ),
            Quantity("mu12_supremum", "μ₁₂, undamped supremum 1 + Σ|b|", sup12, ""),
            Quantity("mu23_supremum", "μ₂₃, undamped supremum 1 + Σ|b|", sup23, ""),
            Quantity(
                "mu12_simplified",
                "μ₁₂ by (19)",
                s12,
                "",
                f"{s12 / sup12 - 1:+.2%} against the supremum",
            ),
            Quantity(
                "mu23_simplified",
                "μ₂₃ by (20)",
                s23,
                "",
                f"{s23 / sup23 - 1:+.2%} against the supremum",
            ),
            Quantity("peak_moment_12", "Peak chord moment μ₁₂,sup·R₁₂", sup12 * r12, "N·m"),
            Quantity("peak_moment_23", "Peak rope moment μ₂₃,sup·R₂₃", sup23 * r23, "N·m"),
        ],
    )


def _history_table(dyn: Dynamics, points: int) -> Table:
    times = np.linspace(0.0, dyn.period, points)
    moments = dyn.response.moments(times)
    rows: list[list[Any]] = [
        [float(t), float(moments[0, i] / dyn.static[0]), float(moments[1, i] / dyn.static[1])]
        for i, t in enumerate(times)
    ]
    return Table(
        "μ(t) over the first swing (samples; the fast mode runs between them)",
        "history",
        [Column("t", "s"), Column("μ₁₂"), Column("μ₂₃")],
        rows,
    )


def _sweep_table(rows: list[SweepRow]) -> Table:
    out: list[list[Any]] = []
    for row in rows:
        d = row.dynamics
        sup12, sup23 = d.supremum(0), d.supremum(1)
        s12, s23 = d.simplified
        out.append(
            [
                row.height,
                d.modes.frequencies[0],
                d.modes.frequencies[-1],
                d.factor(d.first_swing[0], 0),
                d.factor(d.first_swing[1], 1),
                sup12,
                sup23,
                s12,
                s23,
                100.0 * (s12 / sup12 - 1.0),
                100.0 * (s23 / sup23 - 1.0),
            ]
        )
    return Table(
        "Height sweep (the seed's Table 1): modal maxima and the simplified formulas",
        "sweep",
        [
            Column("H", "m"),
            Column("β₁", "rad/s"),
            Column("β₂", "rad/s"),
            Column("μ₁₂ 1st swing"),
            Column("μ₂₃ 1st swing"),
            Column("μ₁₂ sup"),
            Column("μ₂₃ sup"),
            Column("μ₁₂ (19)"),
            Column("μ₂₃ (20)"),
            Column("(19) error", "%"),
            Column("(20) error", "%"),
        ],
        out,
    )


# -------------------------------------------------------------------------- charts

#: Samples per period of a mode drawn in μ(t) (the line between them is straight).
CHART_SAMPLES_PER_PERIOD = 16
#: Points of one μ(t) curve at most, and at least (the slow mode stays smooth).
CHART_POINTS = (1001, 8001)
#: A mode too fast to draw over the horizon is drawn as an envelope above this Σ|b|.
CHART_ENVELOPE = 1e-4


def charts(result: Result) -> list[Chart]:
    """μ₁₂(t) and μ₂₃(t) over the report's horizon from the modal solution, with the
    supremum 1 + Σ|b|, the static level 1 and the first swing's maximum; and with a
    height sweep, the sweep's maxima against H. [] for a scene without an answer."""
    if result.status != "ok" or result.dynamics is None:
        return []
    dyn = result.dynamics
    out = [_factor_chart(dyn, spring) for spring in (0, 1)]
    if len(result.sweep) > 0:
        out.append(_sweep_chart(result.sweep))
    return out


def _factor_chart(dyn: Dynamics, spring: int) -> Chart:
    """μ(t) = 1 + Σ bⱼ·cos(βⱼt) on a grid of 16 points per period of the fastest mode
    that fits :data:`CHART_POINTS` over the horizon. Faster modes swing through ±|b|
    within each of their periods: above :data:`CHART_ENVELOPE` they are drawn as the
    envelope (drawn curve) ± Σ|b|, below it they are left out and the label says so."""
    from mdcalc.plot import Chart, Mark, Series

    name = ("μ₁₂", "μ₂₃")[spring]
    frequencies = list(dyn.modes.frequencies)
    coefficients = dyn.coefficients(spring)
    horizon = dyn.horizon
    low, high = CHART_POINTS

    def points_for(beta: float) -> int:
        return math.ceil(horizon * beta / (2.0 * math.pi) * CHART_SAMPLES_PER_PERIOD) + 1

    drawn = [j for j, beta in enumerate(frequencies) if points_for(beta) <= high]
    left_out = [j for j in range(len(frequencies)) if j not in drawn]
    count = max([low, *(points_for(frequencies[j]) for j in drawn)])
    times = np.linspace(0.0, horizon, count)
    mu = np.ones(count)
    for j in drawn:
        mu += coefficients[j] * np.cos(frequencies[j] * times)
    fast = math.fsum(abs(coefficients[j]) for j in left_out)
    x = times.tolist()
    label = f"{name}(t)"
    series: list[Series] = []
    if left_out:
        cut = frequencies[left_out[0]]
        modes = "mode" if len(left_out) == 1 else "modes"
        without = f" without the {modes} from {cut:.4g} rad/s"
        if fast > CHART_ENVELOPE:
            # one closed outline, upper edge out and lower edge back: one colour, one entry
            outline = [*(mu + fast).tolist(), *(mu - fast)[::-1].tolist()]
            series.append(Series(label + without, x, mu.tolist()))
            series.append(
                Series(
                    f"envelope ± {fast:.3g} of the {modes} too fast to draw",
                    [*x, *x[::-1]],
                    outline,
                    "dashed",
                )
            )
        else:
            series.append(Series(f"{label}{without} (Σ|b| = {fast:.1e})", x, mu.tolist()))
    else:
        series.append(Series(label, x, mu.tolist()))
    first = dyn.first_swing[spring]
    peak = dyn.factor(first, spring)
    series.append(
        Series(
            f"first-swing maximum {peak:.5g} at t = {first.time:.4g} s",
            [first.time],
            [peak],
            "points",
        )
    )
    supremum = dyn.supremum(spring)
    return Chart(
        f"Dynamic factor {name} = M/R over the horizon {horizon:.4g} s "
        f"(R = {dyn.static[spring]:.6g} N·m)",
        "t [s]",
        f"{name} [-]",
        series,
        [
            Mark("y", supremum, f"supremum 1 + Σ|b| = {supremum:.5g}"),
            Mark("y", 1.0, "static, μ = 1"),
            Mark("x", dyn.period, f"first swing ends, 2π/β₁ = {dyn.period:.4g} s"),
        ],
    )


def _sweep_chart(rows: list[SweepRow]) -> Chart:
    """The seed's Table 1: the suprema and the simplified (19)-(20) against H."""
    from mdcalc.plot import Chart, Series

    heights = [row.height for row in rows]
    style: Any = "points" if len(rows) < 2 else "line"
    dashed: Any = "points" if len(rows) < 2 else "dashed"
    return Chart(
        "Height sweep: the undamped suprema and the simplified formulas (19)-(20)",
        "H [m]",
        "μ [-]",
        [
            Series("μ₁₂ supremum", heights, [r.dynamics.supremum(0) for r in rows], style),
            Series("μ₁₂ by (19)", heights, [r.dynamics.simplified[0] for r in rows], dashed),
            Series("μ₂₃ supremum", heights, [r.dynamics.supremum(1) for r in rows], style),
            Series("μ₂₃ by (20)", heights, [r.dynamics.simplified[1] for r in rows], dashed),
        ],
    )


def template() -> dict[str, Any]:
    return {
        "problem": "mine-hoist",
        "title": "Mine hoist, seed 002 data at H = 1025 m, M₁ = 2·W",
        "hoist": {
            "drum_inertia": 479.15e3,
            "sheave_inertia": 27.97e3,
            "cage_inertia": 156.86e3,
            "chord_stiffness": 18609.2e3,
            "rope_stiffness": 893.45e3,
        },
        "loads": {"drive_torque": 1.0e6, "load_torque": 5.0e5},
    }
