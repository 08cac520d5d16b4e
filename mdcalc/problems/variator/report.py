"""The report: a section for each part the case has."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mdcalc.core import periodic
from mdcalc.output.report import Column, Note, Quantities, Quantity, Report, Table
from mdcalc.problems.variator.absorber import AbsorberScene, absorber_minimum
from mdcalc.problems.variator.case import KGF_M, Clutch, Drive, Mechanism, Motor, Pendulum
from mdcalc.problems.variator.clutch import clutch_lines, clutch_values
from mdcalc.problems.variator.drive import CLUTCH, drive_values, three_mass_values
from mdcalc.problems.variator.motor import motor_models, motor_values
from mdcalc.problems.variator.pendulum import pendulum_values
from mdcalc.problems.variator.solve import Result
from mdcalc.problems.variator.transfer import mechanism_values, transfer_of


def report(result: Result) -> Report:
    case = result.case
    title = case.title or "Impulse variator: anti-resonance and absorbers"
    sections: list[Any] = []
    notes = list(result.notes)
    if case.absorber is not None and result.absorber is not None:
        sections.extend(_absorber_sections(result.absorber, result, notes))
    if result.status != "ok":
        return Report("variator", title, sections, notes, result.status, result.message)
    if case.motor is not None:
        sections.extend(_motor_sections(case.motor, result))
    if case.clutch is not None:
        sections.append(_clutch_section(case.clutch, case.drive, notes))
    if case.mechanism is not None:
        sections.extend(_mechanism_sections(case.mechanism))
    if result.drive is not None and result.two_mass is not None:
        sections.extend(_drive_sections(result, notes))
    if result.three_mass is not None and result.three_mass_state is not None:
        sections.extend(_three_mass_sections(result, notes))
    if case.pendulum is not None:
        sections.append(_pendulum_section(case.pendulum, notes))
    return Report("variator", title, sections, notes)


def _absorber_sections(s: AbsorberScene, result: Result, notes: list[Note]) -> list[Any]:
    low, high = s.resonances()
    items = [
        Quantity(
            "absorber_stiffness",
            "Absorber shaft c_g",
            s.cg,
            "N·m/rad",
            "tuned: c_g = J₂·ω² (8.39)" if s.tuned else "",
        ),
        Quantity("absorber_tuning", "Absorber tuned to √(c_g/J₂)", math.sqrt(s.cg / s.j2), "rad/s"),
        Quantity(
            "absorber_partial",
            "Disk alone √(c/J₁)",
            math.sqrt(s.c / s.j1),
            "rad/s",
            "(8.35): resonance without the absorber when it equals ω",
        ),
        Quantity("absorber_resonance_low", "Lower resonance of the two-disk system", low, "rad/s"),
        Quantity(
            "absorber_resonance_high", "Upper resonance of the two-disk system", high, "rad/s"
        ),
    ]
    sections: list[Any] = [Quantities("Anti-resonance absorber (8.36)–(8.39)", items)]
    if result.status != "ok":
        return sections
    a1, a2 = s.amplitudes(s.omega)
    alone = s.untuned(s.omega)
    static = s.m0 / s.c
    amp = [
        Quantity(
            "absorber_a1",
            "|A₁|, the disk",
            abs(a1),
            "rad",
            "exactly 0: the absorber takes the whole torque" if a1 == 0 else "",
        ),
        Quantity("absorber_a2", "|A₂|, the absorber disk", abs(a2), "rad"),
        Quantity(
            "absorber_moment",
            "Moment in the absorber shaft",
            abs(complex(s.cg, s.omega * s.bg) * (a2 - a1)),
            "N·m",
            "= M₀ when tuned" if s.tuned and s.bg == 0.0 else "",
        ),
        Quantity("absorber_static", "Static twist M₀/c", static, "rad"),
    ]
    if alone is None:
        amp.append(
            Quantity(
                "absorber_untuned",
                "|A| of the disk without the absorber",
                "unbounded",
                "",
                "c/J₁ = ω² (8.35): resonance",
            )
        )
    else:
        amp.append(
            Quantity("absorber_untuned", "|A| of the disk without the absorber", alone, "rad")
        )
    if s.bg == 0.0:
        b_low, b_high = s.band()
        amp += [
            Quantity(
                "absorber_band_low",
                "Absorber helps from",
                b_low,
                "rad/s",
                "|A₁| < M₀/|c - J₁ω²| between these",
            ),
            Quantity("absorber_band_high", "Absorber helps up to", b_high, "rad/s"),
        ]
    elif (minimum := absorber_minimum(s)) is not None:
        depth, where = minimum
        amp += [
            Quantity(
                "absorber_minimum",
                "Smallest |A₁| (damped minimum)",
                depth,
                "rad",
                f"at {where:.6g} rad/s",
            ),
            Quantity("absorber_minimum_frequency", "at", where, "rad/s"),
            Quantity("absorber_minimum_depth", "Its depth, |A₁|min/(M₀/c)", depth / static, ""),
        ]
    else:
        notes.append(
            Note(
                "warning",
                "the absorber is damped so heavily that |A₁| has no minimum between the two "
                "resonances: it no longer works as an anti-resonance absorber",
            )
        )
    sections.append(Quantities(f"Amplitudes at ω = {s.omega:.6g} rad/s", amp))
    assert result.case.absorber is not None
    sections.append(_absorber_curve(s, high, result.case.absorber.curve_points))
    assert result.absorber_methods is not None
    sections.append(result.absorber_methods)
    if s.tuned and s.bg > 0.0 and absorber_minimum(s) is not None:
        notes.append(Note("info", "with absorber damping the zero of A₁ becomes a minimum"))
    return sections


def _absorber_curve(s: AbsorberScene, high: float, points: int) -> Table:
    """|A₁|, |A₂| from ω/points up to max(2ω, 1.25 × the upper resonance)."""
    span = max(2.0, 1.25 * high / s.omega)
    rows: list[list[Any]] = []
    for k in range(1, points + 1):
        w = s.omega * span * k / points
        alone = s.untuned(w)
        try:
            if s.determinant_is_zero(w):
                raise ZeroDivisionError
            a1, a2 = s.amplitudes(w)
            cells: list[Any] = [abs(a1), abs(a2)]
        except ZeroDivisionError:
            cells = ["unbounded", "unbounded"]
        rows.append([w, w / s.omega, alone if alone is not None else "unbounded", *cells])
    return Table(
        "A₁(ω) and A₂(ω)",
        "absorber_curve",
        [
            Column("ω", "rad/s"),
            Column("ω/ω of the torque"),
            Column("|A| without absorber", "rad"),
            Column("|A₁|", "rad"),
            Column("|A₂|", "rad"),
        ],
        rows,
    )


def _motor_sections(m: Motor, result: Result) -> list[Any]:
    _, _, (kloss, _, printed) = motor_models(m)
    v = motor_values(m)
    items = [
        Quantity("motor_mains", "ω_c = 2π·f_c", v["motor_mains"], "rad/s"),
        Quantity("motor_field_speed", "ω₀ = ω_c/P", v["motor_field_speed"], "rad/s"),
        Quantity("motor_synchronous_rpm", "Synchronous speed n", v["motor_synchronous_rpm"], "rpm"),
        Quantity("motor_nominal_torque", "M_H", v["motor_nominal_torque"], "N·m"),
        Quantity("motor_critical_torque", "M_K = λ_m·M_H", v["motor_critical_torque"], "N·m"),
        Quantity(
            "motor_slip",
            "S_H = (n - n_H)/n",
            v["motor_slip"],
            "",
            f"the seed's (8.41) divides by n_H: {printed.slip:.5g}",
        ),
        Quantity(
            "motor_critical_slip",
            "S_K, seed's correction",
            v["motor_critical_slip"],
            "",
            f"plain Kloss: {kloss.critical_slip:.5g}",
        ),
        Quantity(
            "motor_critical_slip_kloss", "S_K, plain Kloss", v["motor_critical_slip_kloss"], ""
        ),
        Quantity(
            "motor_time_constant",
            "T_D = 1/(ω_c·S_K), seed's correction",
            v["motor_time_constant"],
            "s",
            f"plain Kloss: {kloss.time_constant:.5g} s",
        ),
        Quantity(
            "motor_stiffness",
            "c_D = 1/(T_D·ν·ω₀) = 2·P·M_K",
            v["motor_stiffness"],
            "N·m/rad",
            "the same for every S_K",
        ),
        Quantity(
            "motor_damping",
            "b_D = 1/(ν·ω₀), seed's correction",
            v["motor_damping"],
            "N·m·s/rad",
            f"plain Kloss: {kloss.damping:.5g}",
        ),
        Quantity("motor_damping_kloss", "b_D, plain Kloss", v["motor_damping_kloss"], "N·m·s/rad"),
    ]
    assert result.motor_methods is not None
    return [
        Quantities("Induction motor as a spring-damper (8.40)–(8.41)", items),
        result.motor_methods,
    ]


def _clutch_section(c: Clutch, drive: Drive | None, notes: list[Note]) -> Quantities:
    _, _, lines = clutch_lines(c)
    v = clutch_values(c)
    items = [
        Quantity(
            "clutch_c0", "c₀ of M = c₀·ξⁿ", c.c0, "N·m/radⁿ", f"{c.c0 / KGF_M:.5g} kgf·m/radⁿ"
        ),
        Quantity("clutch_exponent", "n", v["clutch_exponent"], ""),
        Quantity("clutch_twist_min", "ξ at the lowest working load", v["clutch_twist_min"], "rad"),
        Quantity("clutch_twist_max", "ξ at the highest working load", v["clutch_twist_max"], "rad"),
        Quantity(
            "clutch_tangent",
            "Tangent stiffness at the top, n·M_max/ξ_max",
            v["clutch_tangent"],
            "N·m/rad",
        ),
    ]
    for line in lines:
        items.append(
            Quantity(
                f"clutch_{line.key}",
                f"{line.name}",
                line.stiffness,
                "N·m/rad",
                f"{line.stiffness / KGF_M:.5g} kgf·m/rad",
            )
        )
        items.append(
            Quantity(f"clutch_{line.key}_error", "  its largest error / M_max", line.error, "")
        )
    if c.unloading is not None:
        ls = lines[1].stiffness
        items.append(
            Quantity(
                "clutch_unloading",
                "Unloading line (linearized)",
                c.unloading,
                "N·m/rad",
                f"{c.unloading / ls:.4g} × the least-squares loading line",
            )
        )
        if not 0.2 < c.unloading / ls < 5:
            notes.append(
                Note(
                    "warning",
                    f"the clutch's unloading line is {c.unloading / ls:.3g} times its loading "
                    "line over the working range: the loading curve and the linear stiffness "
                    "do not describe the same clutch at these loads",
                )
            )
    if c.loop_area_ratio is not None:
        psi = c.loop_area_ratio
        items.append(
            Quantity(
                "clutch_damping_ratio",
                "Damping ratio ζ = ψ/(4π) from the loop (8.43)–(8.44)",
                v["clutch_damping_ratio"],
                "",
                f"ψ = {psi:g}; b = ψ/(2π)·√(J·c)",
            )
        )
    if drive is not None:
        ratio = drive.stiffness / lines[1].stiffness
        if not 0.2 < ratio < 5:
            notes.append(
                Note(
                    "info",
                    f"[drive] uses c = {drive.stiffness:.5g} N·m/rad, {ratio:.3g} times the "
                    "least-squares line of [clutch]",
                )
            )
    return Quantities("Overrunning clutch: loading curve (8.42) and its lines", items)


def _mechanism_sections(m: Mechanism) -> list[Any]:
    t = transfer_of(m)
    v = mechanism_values(m)
    items = [
        Quantity(
            "mechanism_stroke",
            "Working stroke Δα = 2π/z",
            v["mechanism_stroke"],
            "rad",
            f"{math.degrees(t.stroke):.4g}°",
        ),
        Quantity("mechanism_ratio", "Mean ratio i_c", v["mechanism_ratio"], ""),
        Quantity(
            "mechanism_output_rpm", "Mean output speed n₁/i_c", v["mechanism_output_rpm"], "rpm"
        ),
        Quantity("mechanism_a0", "a₀", v["mechanism_a0"], ""),
        Quantity("mechanism_b0", "b₀ = Π′max", v["mechanism_b0"], ""),
        Quantity(
            "mechanism_first_end", "Π′ at the ends of the stroke", v["mechanism_first_end"], ""
        ),
        Quantity(
            "mechanism_second_end",
            "|Π″| at the ends of the stroke",
            v["mechanism_second_end"],
            "1/rad",
        ),
        Quantity(
            "mechanism_mean_first",
            "Mean of Π′ over the stroke",
            v["mechanism_mean_first"],
            "",
            f"1/i_c = {1.0 / t.ratio:.10g}",
        ),
        Quantity(
            "mechanism_mean_check", "(mean Π′)·i_c - 1", v["mechanism_mean_check"], "", "check: 0"
        ),
    ]
    rows: list[list[Any]] = []
    for k in range(9):
        x = t.stroke * (k / 8.0 - 0.5)
        rows.append([math.degrees(x), t.position(x), t.first(x), t.second(x)])
    table = Table(
        "Transfer functions over the stroke (8.46)",
        "mechanism_transfer",
        [Column("α - α_c", "deg"), Column("Π - φ_c", "rad"), Column("Π′"), Column("Π″", "1/rad")],
        rows,
    )
    return [Quantities("Elementary mechanism (8.46)", items), table]


def _drive_sections(result: Result, notes: list[Note]) -> list[Any]:
    d, exact = result.drive, result.two_mass
    assert d is not None and exact is not None and result.two_mass_methods is not None
    zeta = d.damping / (2.0 * math.sqrt(d.stiffness * d.inertia))
    top = periodic.maximum_of(exact, CLUTCH, exact.fastest)
    v = drive_values(d, top.value)
    machine = result.three_mass is not None
    items = [
        Quantity(
            "drive_inertia",
            "J of the two-mass model" + (", J₂ + i²J₃" if machine else ""),
            v["drive_inertia"],
            "kg·m²",
        ),
        Quantity("drive_stiffness", "Clutch c", v["drive_stiffness"], "N·m/rad"),
        Quantity("drive_damping", "Clutch b", v["drive_damping"], "N·m·s/rad", f"ζ = {zeta:.4g}"),
        Quantity("drive_fundamental", "Excitation Ω = z·ω", v["drive_fundamental"], "rad/s"),
        Quantity("drive_natural", "β = √(c/J)", v["drive_natural"], "rad/s"),
        Quantity("drive_frequency_ratio", "β/Ω", v["drive_frequency_ratio"], ""),
        Quantity("drive_acceleration", "Peak of J·ω²·Π″", v["drive_acceleration"], "N·m"),
        Quantity("drive_static", "q_c = M_c/c", v["drive_static"], "rad"),
        Quantity("drive_q_max", "q_max", v["drive_q_max"], "rad"),
        Quantity(
            "drive_chi",
            "χ = q_max/q_c (8.47)",
            v["drive_chi"],
            "",
            f"peak at {top.time / d.period * math.degrees(d.transfer.stroke):.4g}° into the stroke",
        ),
        Quantity("drive_moment_max", "Peak clutch moment c·q_max", v["drive_moment_max"], "N·m"),
    ]
    title = "Two-mass model, periodic state" + (" (before: J₃ rigid on J₂)" if machine else "")
    points = result.case.drive.points if result.case.drive else 13
    tau = np.linspace(0.0, d.period, points)
    q = exact.observe(CLUTCH, tau)
    table = Table(
        "q(τ) over one stroke",
        "drive_history",
        [Column("τ", "s"), Column("α - α₁", "deg"), Column("q", "rad"), Column("q/q_c")],
        [
            [
                float(t),
                float(t) / d.period * math.degrees(d.transfer.stroke),
                float(v),
                float(v) / d.static,
            ]
            for t, v in zip(tau, q, strict=True)
        ],
    )
    _resolution_note(exact, d.period, notes)
    return [Quantities(title, items), table, result.two_mass_methods]


def _three_mass_sections(result: Result, notes: list[Note]) -> list[Any]:
    three, exact = result.three_mass, result.three_mass_state
    assert three is not None and exact is not None and result.drive is not None
    assert result.two_mass is not None and result.three_mass_methods is not None
    d = three.drive
    v = three_mass_values(
        three,
        periodic.maximum_of(result.two_mass, CLUTCH, result.two_mass.fastest).value,
        periodic.maximum_of(exact, np.array([1.0, 0.0, 0.0, 0.0]), exact.fastest).value,
        periodic.maximum_of(exact, three.coupling(), exact.fastest).value,
        result.chi_after_kept_damping,
    )
    items = [
        Quantity("antiresonance_machine", "J₃' = i²·J₃", v["antiresonance_machine"], "kg·m²"),
        Quantity(
            "antiresonance_coupling",
            "Coupling c₂",
            v["antiresonance_coupling"],
            "N·m/rad",
            "tuned: (zω)²·J₂J₃'/(J₂ + J₃')/i²"
            if result.case.antiresonance and result.case.antiresonance.coupling_stiffness is None
            else "as given",
        ),
        Quantity(
            "antiresonance_frequency",
            "Clutch anti-resonance √(c₂'(J₂ + J₃')/(J₂J₃'))",
            v["antiresonance_frequency"],
            "rad/s",
            f"excitation Ω = {d.fundamental:.6g} rad/s",
        ),
    ]
    for key, label, unit in (
        ("antiresonance_natural_low", "Natural frequency, lower", "rad/s"),
        ("antiresonance_natural_high", "Natural frequency, upper", "rad/s"),
        ("antiresonance_chi_before", "χ before (J₃ rigid on J₂)", ""),
        ("antiresonance_chi_after", "χ after", ""),
    ):
        items.append(Quantity(key, label, v[key], unit))
    items += [
        Quantity(
            "antiresonance_reduction",
            "Dynamic load on the clutch reduced",
            v["antiresonance_reduction"],
            "×",
            "(χ_before - 1)/(χ_after - 1); seed: 30 calculated, 29 measured",
        ),
        Quantity("antiresonance_chi_ratio", "χ_before/χ_after", v["antiresonance_chi_ratio"], ""),
        Quantity(
            "antiresonance_coupling_max",
            "Peak coupling moment (at the coupling)",
            v["antiresonance_coupling_max"],
            "N·m",
        ),
        Quantity(
            "antiresonance_coupling_factor",
            "Coupling M_max/M_c, the load moved onto c₂",
            v["antiresonance_coupling_factor"],
            "",
        ),
        Quantity(
            "antiresonance_clutch_damping",
            "Clutch b₁ in this model",
            v["antiresonance_clutch_damping"],
            "N·m·s/rad",
        ),
    ]
    if "antiresonance_chi_after_kept_damping" in v:
        reduction = v["antiresonance_reduction_kept_damping"]
        items += [
            Quantity(
                "antiresonance_chi_after_kept_damping",
                "χ after, had the clutch kept b₁ of the two-mass model",
                v["antiresonance_chi_after_kept_damping"],
                "",
                "(8.44) read with J₂ + i²J₃ instead of J₂",
            ),
            Quantity("antiresonance_reduction_kept_damping", "Reduction then", reduction, "×"),
        ]
        notes.append(
            Note(
                "info",
                "b₁ follows (8.44) with the inertia the clutch faces (J₂ + i²J₃ before, J₂ "
                f"after); with b₁ kept from the two-mass model the reduction would be "
                f"{reduction:.3g}×",
            )
        )
    _resolution_note(exact, d.period, notes)
    return [
        Quantities("Three-mass anti-resonance design (Fig. 8.10)", items),
        result.three_mass_methods,
    ]


def _resolution_note(exact: periodic.Periodic, period: float, notes: list[Note]) -> None:
    samples, resolved = periodic.samples_for(period, exact.fastest)
    if not resolved:
        notes.append(
            Note(
                "warning",
                f"the fastest mode ({exact.fastest:.4g} rad/s) has fewer than 16 of the "
                f"{samples} samples per period: maxima may be short by its amplitude",
            )
        )


def _pendulum_section(p: Pendulum, notes: list[Note]) -> Quantities:
    v = pendulum_values(p)
    length = v["pendulum_length"]
    items = [
        Quantity(
            "pendulum_length", "Tuned length L = R/n² (8.55)", length, "m", f"{length * 1e3:.4g} mm"
        ),
        Quantity("pendulum_length_ratio", "L/R", v["pendulum_length_ratio"], ""),
    ]
    if "pendulum_frequency" in v:
        items.append(
            Quantity(
                "pendulum_frequency", "Pendulum frequency n·ω", v["pendulum_frequency"], "rad/s"
            )
        )
    if "pendulum_order_at_swing" in v:
        items += [
            Quantity(
                "pendulum_order_at_swing",
                "Order at the full swing, n·AGM(1, cos(θ/2))",
                v["pendulum_order_at_swing"],
                "",
                "a large swing detunes the pendulum downwards",
            ),
            Quantity(
                "pendulum_length_at_swing",
                "L tuned at the full swing",
                v["pendulum_length_at_swing"],
                "m",
            ),
        ]
    if "pendulum_mass" in v:
        mass, bob = v["pendulum_mass"], v["pendulum_bob_radius"]
        items += [
            Quantity("pendulum_mass", "Mass m = M/(ω²(R + L)·R·θ_max) (8.56)", mass, "kg"),
            Quantity("pendulum_bob_radius", "Radius of a ball of that mass", bob, "m"),
            Quantity(
                "pendulum_buildable", "Fits on the pendulum (ball radius < L)", bob < length, ""
            ),
        ]
        if bob >= length:
            notes.append(
                Note(
                    "warning",
                    f"L = {length * 1e3:.4g} mm is too short to build: a bob of {mass:.4g} kg "
                    f"is a ball of radius {bob * 1e3:.4g} mm; use a bifilar or bushing design "
                    "(Fig. 8.16), where L is the difference of two diameters",
                )
            )
    else:
        notes.append(
            Note(
                "info",
                "give speed, inertia_torque and max_swing in [pendulum] to size the bob "
                "(8.56) and check that it fits on so short a pendulum",
            )
        )
    if p.bifilar_pin_diameter is not None:
        items.append(
            Quantity(
                "pendulum_bifilar_hole",
                "Bifilar: hole diameter d + L",
                v["pendulum_bifilar_hole"],
                "m",
                f"pin {p.bifilar_pin_diameter * 1e3:.4g} mm",
            )
        )
    return Quantities("Centrifugal pendulum absorber (8.49)–(8.56)", items)
