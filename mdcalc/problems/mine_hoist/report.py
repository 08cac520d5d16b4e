"""The report: the sections a mine-hoist scene needs."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mdcalc.output.report import Column, Note, Quantities, Quantity, Report, Table
from mdcalc.problems.mine_hoist.case import Rope
from mdcalc.problems.mine_hoist.modal import Dynamics, frequency_ratio
from mdcalc.problems.mine_hoist.ode_rows import STIFF_RATIO
from mdcalc.problems.mine_hoist.scene import RopeReduction, Scene, seed_formula_1
from mdcalc.problems.mine_hoist.solve import Result, SweepRow


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
    printed = seed_formula_1(*chain.inertias, *chain.stiffnesses)
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
