"""The report: the sections a resonance scene needs."""

from __future__ import annotations

import math
from typing import Any

from mdcalc.output.report import Column, Quantities, Quantity, Report, Table, Value
from mdcalc.problems.resonance.case import Campbell, ChainSection, Mathieu, Measured, Resonance
from mdcalc.problems.resonance.chain import (
    Modal,
    algebraic_sum,
    energy_method,
    forced_response,
    geometric_sum,
    is_main_order,
    modal_dissipation,
)
from mdcalc.problems.resonance.mathieu import (
    first_approximation,
    monodromy_rk4,
    spectral_radius,
    verdict,
)
from mdcalc.problems.resonance.solve import Result

TWO_PI = 2.0 * math.pi

HZ_TO_RPM = 60.0

MAX_MODES_SHOWN = 5


def report(result: Result) -> Report:
    case = result.case
    title = case.title or "Torsional resonance"
    sections: list[Any] = []
    notes = list(result.notes)
    c = case.chain
    md = result.modal
    if md is None and c is not None:
        return Report("resonance", title, sections, notes, result.status, result.message)
    if c is not None and md is not None:
        sections += _modes_sections(c, md)
        if case.campbell is not None:
            sections.append(_campbell_table(c, md, case.campbell))
        if case.resonance is not None:
            sections.append(_resonance_section(c, md, case.resonance, result.status == "ok"))
            if case.resonance.harmonic_torque is not None and result.status == "ok":
                sections.append(_shaft_table(c, md, case.resonance))
    if case.measured is not None:
        sections += _measured_sections(case.measured, md)
    if result.status != "ok":
        return Report("resonance", title, sections, notes, result.status, result.message)
    sections += [t for t in result.methods if t.key == "resonance"]
    if case.mathieu is not None:
        sections += _mathieu_sections(case.mathieu, result)
        sections += [t for t in result.methods if t.key == "floquet"]
    return Report("resonance", title, sections, notes)


def _modes_sections(c: ChainSection, md: Modal) -> list[Any]:
    shown = min(len(md.frequencies), MAX_MODES_SHOWN)
    items = []
    for j in range(shown):
        beta = md.frequencies[j]
        items.append(
            Quantity(
                f"frequency_{j + 1}",
                f"Mode {j + 1}: natural frequency f",
                beta / TWO_PI,
                "Hz",
                f"β = {beta:.6g} rad/s",
            )
        )
    columns = [Column("mass"), Column("J", "kg·m²")]
    columns += [Column(f"a, mode {j + 1}") for j in range(shown)]
    rows: list[list[Value]] = []
    cranks = set(c.cranks or [])
    for i, inertia in enumerate(c.inertias):
        label = f"{i + 1}" + (" (crank)" if i + 1 in cranks else "")
        rows.append([label, inertia, *(md.shapes[j][i] for j in range(shown))])
    ref = ", ".join(sorted({str(r + 1) for r in md.references[:shown]}))
    return [
        Quantities("Natural frequencies", items),
        Table(f"Mode shapes, relative amplitudes (a = 1 at mass {ref})", "modes", columns, rows),
    ]


def default_orders(strokes: int) -> list[float]:
    step = 0.5 if strokes == 4 else 1.0
    return [step * k for k in range(1, int(12 / step) + 1)]


def _campbell_table(c: ChainSection, md: Modal, cb: Campbell) -> Table:
    orders = cb.orders or default_orders(c.strokes)
    rows: list[list[Value]] = []
    for j, beta in enumerate(md.frequencies):
        f = beta / TWO_PI
        for k in orders:
            speed = HZ_TO_RPM * f / k
            if not cb.from_rpm <= speed <= cb.to_rpm:
                continue
            row: list[Value] = [speed, k, j + 1, f]
            if c.cranks is not None:
                row += [
                    abs(geometric_sum(c, md.shapes[j], k)),
                    "main" if is_main_order(c, k) else "",
                ]
            rows.append(row)
    rows.sort(key=lambda r: float(r[0]))  # type: ignore[arg-type]  # a speed
    columns = [
        Column("critical speed", "rpm"),
        Column("order k"),
        Column("mode"),
        Column("f", "Hz"),
    ]
    if c.cranks is not None:
        columns += [Column("|Σ a·e^(ikδ)|"), Column("order")]
    return Table(
        f"Campbell table: n = 60·f/k within {cb.from_rpm:g} … {cb.to_rpm:g} rpm",
        "campbell",
        columns,
        rows,
    )


def _resonance_section(c: ChainSection, md: Modal, r: Resonance, solved: bool) -> Quantities:
    j = r.mode - 1
    beta = md.frequencies[j]
    f = beta / TWO_PI
    items = [
        Quantity("resonance_frequency", f"Mode {r.mode} frequency f", f, "Hz"),
        Quantity(
            "critical_speed_rpm",
            f"Critical speed of order {r.order:g}, n = 60·f/k",
            HZ_TO_RPM * f / r.order,
            "rpm",
        ),
    ]
    if c.cranks is not None:
        s = geometric_sum(c, md.shapes[j], r.order)
        items += [
            Quantity("geometric_sum", "|Σ aᵢ·e^(i·k·δᵢ)| over the cranks", abs(s), ""),
            Quantity(
                "algebraic_sum",
                "Σ aᵢ over the cranks",
                algebraic_sum(c, md.shapes[j]),
                "",
            ),
            Quantity("main_order", "Main order (all phases equal)", is_main_order(c, r.order), ""),
        ]
    if r.harmonic_torque is not None and c.damping is not None:
        dissipation = modal_dissipation(c, md, j)
        items.append(Quantity("modal_damping", "Σ ξᵢ·aᵢ²", dissipation, "N·m·s/rad"))
        if solved:
            amp = energy_method(c, md, j, r.order, r.harmonic_torque)
            exact = forced_response(c, md, j, r.order, r.harmonic_torque, beta)
            items += [
                Quantity(
                    "amplitude",
                    f"A at mass {md.references[j] + 1}, energy balance (5)",
                    amp.reference_amplitude,
                    "rad",
                    f"{math.degrees(amp.reference_amplitude):.4g}°",
                ),
                Quantity(
                    "amplitude_exact",
                    "A, exact damped response at ω = β",
                    exact.reference_amplitude,
                    "rad",
                ),
                Quantity(
                    "max_shaft_torque",
                    "Largest shaft torque, energy balance",
                    amp.max_shaft_torque,
                    "N·m",
                ),
                Quantity(
                    "max_shaft_torque_exact",
                    "Largest shaft torque, exact",
                    exact.max_shaft_torque,
                    "N·m",
                ),
            ]
    return Quantities(f"Resonance: order {r.order:g}, mode {r.mode}", items)


def _shaft_table(c: ChainSection, md: Modal, r: Resonance) -> Table:
    assert r.harmonic_torque is not None
    j = r.mode - 1
    amp = energy_method(c, md, j, r.order, r.harmonic_torque)
    exact = forced_response(c, md, j, r.order, r.harmonic_torque, md.frequencies[j])
    rows: list[list[Value]] = []
    for k, stiffness in enumerate(c.stiffnesses):
        rows.append(
            [f"{k + 1}–{k + 2}", stiffness, abs(amp.shaft_torques[k]), exact.shaft_torques[k]]
        )
    return Table(
        "Shaft torques at the resonance, cₖ·(Aₖ - Aₖ₊₁)",
        "shafts",
        [
            Column("shaft"),
            Column("c", "N·m/rad"),
            Column("energy balance", "N·m"),
            Column("exact", "N·m"),
        ],
        rows,
    )


def _measured_sections(measured: list[Measured], md: Modal | None) -> list[Any]:
    items = []
    columns = [Column("order k"), Column("speed", "rpm"), Column("f = n·k/60", "Hz")]
    columns.append(Column("stated f", "Hz"))
    columns.append(Column("stated/implied - 1"))
    if md is not None:
        columns += [
            Column("nearest mode"),
            Column("its f", "Hz"),
            Column("its critical speed", "rpm"),
        ]
    rows: list[list[Value]] = []
    for k, m in enumerate(measured):
        f = m.speed_rpm * m.order / HZ_TO_RPM
        items.append(
            Quantity(
                f"measured_frequency_{k + 1}",
                f"Order {m.order:g} at {m.speed_rpm:g} rpm: f = n·k/60",
                f,
                "Hz",
            )
        )
        row: list[Value] = [m.order, m.speed_rpm, f]
        row += [m.frequency_hz, m.frequency_hz / f - 1.0] if m.frequency_hz else ["", ""]
        if m.frequency_hz is not None:
            items.append(
                Quantity(
                    f"stated_speed_{k + 1}",
                    f"Speed at which order {m.order:g} meets the stated {m.frequency_hz:g} Hz",
                    HZ_TO_RPM * m.frequency_hz / m.order,
                    "rpm",
                )
            )
        if md is not None:
            fs = [b / TWO_PI for b in md.frequencies]
            j = min(range(len(fs)), key=lambda i: abs(fs[i] - f))
            row += [j + 1, fs[j], HZ_TO_RPM * fs[j] / m.order]
        rows.append(row)
    return [
        Quantities("Measured resonances", items),
        Table("Measured resonances against n = 60·f/k", "measured", columns, rows),
    ]


def _mathieu_sections(m: Mathieu, result: Result) -> list[Any]:
    out: list[Any] = []
    c = m.damping
    if result.floquet:
        items = []
        rows: list[list[Value]] = []
        for k, (a, q, trace, det) in enumerate(result.floquet):
            rho = spectral_radius(trace, det)
            state = verdict(trace, c)
            items.append(
                Quantity(
                    f"stability_{k + 1}",
                    f"(a, q) = ({a:g}, {q:g})",
                    state,
                    "",
                    f"|trace| = {abs(trace):.6g} against 1 + e^(-cπ) = "
                    f"{1 + math.exp(-c * math.pi):.6g}",
                )
            )
            items.append(
                Quantity(f"floquet_radius_{k + 1}", f"ρ = max |μ| at ({a:g}, {q:g})", rho, "")
            )
            rows.append(
                [a, q, trace, math.exp(-c * math.pi), rho, state, first_approximation(a, q, c)]
            )
        out.append(
            Quantities(f"Parametric resonance, c = {c:g}: x″ + c·x′ + (a - 2q·cos 2t)·x = 0", items)
        )
        out.append(
            Table(
                "Floquet multipliers of one period π (DOP853, rtol 1e-12)",
                "floquet_points",
                [
                    Column("a"),
                    Column("q"),
                    Column("trace"),
                    Column("det = e^(-cπ)"),
                    Column("ρ = max |μ|"),
                    Column("verdict"),
                    Column("first approximation"),
                ],
                rows,
            )
        )
    if m.chart:
        out.append(_chart(m))
    return out


def _chart(m: Mathieu) -> Table:
    import numpy as np

    a_values = np.linspace(m.a_from, m.a_to, m.columns)
    q_values = np.linspace(0.0, m.q_to, m.rows)
    a_grid, q_grid = np.meshgrid(a_values, q_values)
    trace, _ = monodromy_rk4(a_grid, q_grid, m.damping, 400)
    edge = 1.0 + math.exp(-m.damping * math.pi)
    rows: list[list[Value]] = []
    for i in range(m.rows - 1, -1, -1):
        marks = "".join("·" if abs(t) < edge else "█" for t in trace[i].tolist())
        rows.append([float(q_values[i]), marks])
    return Table(
        f"Ince–Strutt chart, c = {m.damping:g}: █ unstable, · stable; "
        f"a from {m.a_from:g} to {m.a_to:g} in {m.columns} columns (RK4, 400 steps)",
        "chart",
        [Column("q"), Column("a →")],
        rows,
    )
