"""The report: the sections a coupling scene needs."""

from __future__ import annotations

import math
from typing import Any

from mdcalc.output.report import Column, Note, Quantities, Quantity, Report, Table
from mdcalc.problems.coupling.case import DEG, Case, Harmonic, Step
from mdcalc.problems.coupling.scene import Scene, harmonic_numbers, resonance, step_numbers
from mdcalc.problems.coupling.solve import Result


def report(result: Result) -> Report:
    case, s = result.case, result.scene
    title = case.title or "Elastic coupling"
    sections: list[Any] = [_scene_section(case, s)]
    notes: list[Note] = []
    if result.status != "ok":
        return Report("coupling", title, sections, notes, result.status, result.message)
    if case.step is not None:
        sections.append(_step_section(case.step, s))
        assert result.step_methods is not None
        sections.append(result.step_methods)
    if case.harmonic is not None:
        harmonic_sections, harmonic_notes = _harmonic_sections(case.harmonic, s)
        sections += harmonic_sections
        notes += harmonic_notes
        if result.harmonic_methods is not None:
            sections.append(result.harmonic_methods)
    for transient, table, (factor, when) in result.transient_methods:
        static = transient.peak_torque / s.stiffness
        sections.append(
            Quantities(
                transient.title,
                [
                    Quantity(
                        f"{transient.key}_dynamic_factor", "Dynamic factor φ_max/φ_st", factor, ""
                    ),
                    Quantity(f"{transient.key}_peak_time", "Time of the peak", when, "s"),
                    Quantity(
                        f"{transient.key}_peak_twist", "Peak twist φ_max", factor * static, "rad"
                    ),
                    Quantity(
                        f"{transient.key}_peak_torque",
                        "Peak elastic torque c·φ_max",
                        factor * transient.peak_torque,
                        "N·m",
                    ),
                ],
            )
        )
        sections.append(table)
    return Report("coupling", title, sections, notes)


def _scene_section(case: Case, s: Scene) -> Quantities:
    items = [
        Quantity("driving_inertia", "J₁", s.j1, "kg·m²"),
        Quantity("driven_inertia", "J₂", s.j2, "kg·m²"),
        Quantity(
            "stiffness", "Stiffness c", s.stiffness, "N·m/rad", f"{s.stiffness * DEG:.5g} N·m/deg"
        ),
        Quantity("reduced_inertia", "J = J₁·J₂/(J₁ + J₂)", s.reduced_inertia, "kg·m²"),
        Quantity("natural_frequency", "β = √(c/J)", s.beta, "rad/s"),
        Quantity("period", "τ = 2π/β (8.5)", s.period, "s"),
    ]
    if s.p > 0.0:
        items += [
            Quantity("damping_p", "p (8.3)", s.p, "1/s"),
            Quantity("damping_alpha", "α = p·J", s.alpha, "N·m·s/rad"),
            Quantity("log_decrement", "δ = p·τ/2 (8.7)", s.log_decrement, ""),
            Quantity("absorption", "ψ = 2δ (8.14)", s.absorption, ""),
            Quantity("damping_ratio", "ζ = p/(2β)", s.zeta, ""),
        ]
    return Quantities("Coupling", items)


def _step_section(step: Step, s: Scene) -> Quantities:
    n = step_numbers(step.torque, s)
    peak_time = n["step_peak_time"]
    items = [
        Quantity(
            "step_dynamic_factor",
            "Dynamic factor, first peak",
            n["step_dynamic_factor"],
            "",
            "over-damped: no overshoot" if peak_time is None else "",
        ),
    ]
    if peak_time is not None:
        items.append(Quantity("step_peak_time", "Time of the first peak π/β₁", peak_time, "s"))
    items += [
        Quantity(
            "envelope_at_period", "Envelope 1 + e^(-pτ/2) at t = τ", n["envelope_at_period"], ""
        ),
        Quantity(
            "envelope_at_1_5_period", "Envelope at t = 1.5·τ", n["envelope_at_1_5_period"], ""
        ),
        Quantity("undamped_dynamic_factor", "Without damping", n["undamped_dynamic_factor"], ""),
    ]
    if step.torque is not None:
        items += [
            Quantity("static_twist", "Static twist M₀/c", n["static_twist"], "rad"),
            Quantity("peak_twist", "Peak twist", n["peak_twist"], "rad"),
            Quantity("peak_torque", "Peak elastic torque", n["peak_torque"], "N·m"),
        ]
    return Quantities("Suddenly applied torque (8.15)-(8.16)", items)


def _harmonic_sections(h: Harmonic, s: Scene) -> tuple[list[Any], list[Note]]:
    n = harmonic_numbers(h, s)
    omega, lam, gamma = h.omega, n["frequency_ratio"], n["gamma"]
    items = [
        Quantity(
            "combined_amplitude", "M (8.21), in units of M/J", n["combined_amplitude"], "rad/s²"
        ),
        Quantity("combined_phase", "ε", n["combined_phase"], "deg"),
        Quantity("frequency_ratio", "λ = ω/β", lam, ""),
        Quantity("steady_twist", "Steady twist amplitude φ_max (8.27)", n["steady_twist"], "rad"),
        Quantity("steady_torque", "Elastic torque amplitude c·φ_max", n["steady_torque"], "N·m"),
    ]
    if s.p > 0.0:
        items.append(
            Quantity(
                "steady_torque_total",
                "Torque amplitude with damping √(c² + (αω)²)·φ_max",
                n["steady_torque_total"],
                "N·m",
            )
        )
        items.append(Quantity("gamma", "γ = p/β", gamma, ""))
        if gamma * gamma < 2.0:
            ratio, peak = resonance(n["combined_amplitude"], s)
            items += [
                Quantity("resonance_ratio", "Peak at λ = √(1 - γ²/2) (8.31)", ratio, ""),
                Quantity(
                    "resonance_twist",
                    "Peak twist M/(β²·γ·√(1 - γ²/4))",
                    peak,
                    "rad",
                    "the printed (8.32) has √(1 - γ²/2)",
                ),
            ]
    rows: list[list[Any]] = []
    for k in range(31):
        x = 0.1 * k
        rows.append(
            [x, 1.0 / math.hypot(1 - x * x, gamma * x) if (x != 1.0 or gamma > 0) else None]
        )
    curve = Table(
        "Response curve (8.28): φ_max·β²/M against λ",
        "response_curve",
        [Column("λ"), Column("φ_max·β²/M")],
        rows,
    )
    notes = []
    if lam <= 1.5:
        notes.append(
            Note(
                "warning",
                f"λ = ω/β = {lam:.3g}: the lecture's advice is λ > 1.5 (a softer coupling, "
                f"c < {s.reduced_inertia * (omega / 1.5) ** 2:.4g} N·m/rad), passing "
                "the resonance quickly at start and stop",
            )
        )
    return [Quantities("Harmonic torques (8.19)-(8.27)", items), curve], notes
