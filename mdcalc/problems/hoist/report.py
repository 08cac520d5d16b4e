"""The report: the sections a hoist scene needs."""

from __future__ import annotations

import math
from typing import Any

from mdcalc.domain.tables import BRAKE_SAFETY_FACTOR
from mdcalc.output.report import Note, Quantities, Quantity, Report
from mdcalc.problems.hoist.solve import Result, _reference


def report(result: Result) -> Report:
    case, st, inertia, motion = result.case, result.steady, result.inertia, result.start
    notes: list[Note] = []
    sections: list[Any] = [
        Quantities(
            "Steady lifting",
            [
                Quantity("weight", "Load weight G", st.weight, "N"),
                Quantity("total_efficiency", "Total efficiency η", st.efficiency, ""),
                Quantity(
                    "useful_power", "Useful power N_p = G·V (7.25)", st.useful_power / 1e3, "kW"
                ),
                Quantity(
                    "motor_power", "Motor power N_d = N_p/η (7.24)", st.motor_power / 1e3, "kW"
                ),
                Quantity("motor_speed", "Motor angular speed ω1", st.motor_speed, "rad/s"),
                Quantity(
                    "static_torque",
                    "Static torque M_c = G·V/(ω1·η) (7.26)",
                    st.static_torque,
                    "N·m",
                ),
            ],
        ),
        Quantities(
            "Brake on the motor shaft",
            [
                Quantity(
                    "brake_torque",
                    f"Brake torque K_t·M_c (7.27), K_t = {case.drive.brake_safety_factor:g}",
                    st.brake_torque,
                    "N·m",
                ),
                Quantity(
                    "lowering_torque",
                    "Load torque when lowering G·V·η/ω1",
                    st.lowering_torque,
                    "N·m",
                ),
                Quantity(
                    "brake_margin",
                    "Brake margin over the lowering torque",
                    st.brake_margin,
                    "",
                ),
            ],
        ),
    ]
    k_t = BRAKE_SAFETY_FACTOR
    if not k_t.low <= case.drive.brake_safety_factor <= k_t.high:
        notes.append(
            Note(
                "warning",
                f"K_t = {case.drive.brake_safety_factor:g} is outside the "
                f"usual {k_t.low:g}…{k_t.high:g} of the duty classes",
            )
        )
    j_items = [Quantity("motor_inertia", "Motor shaft J1", inertia.motor, "kg·m²")]
    if inertia.estimated:
        j_items.append(
            Quantity(
                "reduced_inertia",
                f"J ≈ {inertia.factor:g}·J1 (7.31)",
                inertia.total,
                "kg·m²",
                "no other shafts given",
            )
        )
    else:
        j_items += [
            Quantity("shaft_inertia", "Other shafts Σ J_k·(ω_k/ω1)²", inertia.shafts, "kg·m²"),
            Quantity("load_inertia", "Load m·(V/ω1)²", inertia.load, "kg·m²"),
            Quantity("reduced_inertia", "Reduced inertia J (7.30)", inertia.total, "kg·m²"),
            Quantity(
                "inertia_ratio",
                "J/J1 (the lecture says 1.1…1.2)",
                inertia.ratio,
                "",
            ),
        ]
    sections.append(Quantities("Reduced moment of inertia on the motor shaft", j_items))
    if motion is not None:
        given_time = case.start.time is not None
        items = [
            Quantity(
                "start_time",
                "Start time t_p" + ("" if given_time else " = J·ω1/(M_start − M_c)"),
                motion.time,
                "s",
            ),
            Quantity(
                "angular_acceleration",
                "Motor acceleration ω1/t_p (7.32)",
                motion.angular_acceleration,
                "rad/s²",
            ),
            Quantity("inertia_torque", "Inertia torque J·ω1/t_p", motion.inertia_torque, "N·m"),
            Quantity(
                "starting_torque",
                "Starting torque M_c + J·ω1/t_p (7.28)",
                motion.starting_torque,
                "N·m",
            ),
            Quantity(
                "load_acceleration", "Load acceleration V/t_p", motion.load_acceleration, "m/s²"
            ),
        ]
        a = motion.load_acceleration
        if result.allowable is not None:
            low, high = result.allowable.low, result.allowable.high
            label = f"allowable for a {case.start.machine}: {low:g}…{high:g} m/s²"
        else:
            assert case.start.allowable_acceleration is not None
            low, high = 0.0, case.start.allowable_acceleration
            label = f"allowable: ≤ {high:g} m/s²"
        ok = a <= high
        items.append(
            Quantity("acceleration_ok", "Within the allowable acceleration", ok, "", label)
        )
        if not ok:
            notes.append(
                Note(
                    "warning",
                    f"the load accelerates at {a:.3g} m/s², above the {label}: lengthen the start",
                )
            )
        elif a < low:
            notes.append(
                Note(
                    "info",
                    f"the load accelerates at {a:.3g} m/s², below the usual "
                    f"{low:g} m/s² for a {case.start.machine}: a slow start",
                )
            )
        sections.append(Quantities("Start", items))
    if result.inertia_table is not None:
        sections.append(result.inertia_table)
    if result.rope is not None and result.rope_hanging and result.rope_ground:
        r = result.rope
        beta = r.beta
        sections.append(
            Quantities(
                "Rope at start (two-mass model)",
                [
                    Quantity("rope_stiffness", "Rope stiffness c", r.c, "N/m"),
                    Quantity("drive_mass", "Drive mass on the rope line m1", r.m1, "kg"),
                    Quantity(
                        "rope_frequency", "Natural frequency β = √(c·(1/m1 + 1/m2))", beta, "rad/s"
                    ),
                    Quantity(
                        "half_period", "Half period π/β (compare with t_p)", math.pi / beta, "s"
                    ),
                    Quantity(
                        "hanging_peak_force",
                        "Peak rope force, load hanging",
                        _reference(result.rope_hanging, "peak_force"),
                        "N",
                    ),
                    Quantity(
                        "hanging_dynamic_factor",
                        "Dynamic factor ψ, load hanging",
                        _reference(result.rope_hanging, "dynamic_factor"),
                        "",
                    ),
                    Quantity(
                        "ground_peak_force",
                        "Peak rope force, load lifted off the ground",
                        _reference(result.rope_ground, "peak_force"),
                        "N",
                    ),
                    Quantity(
                        "ground_dynamic_factor",
                        "Dynamic factor ψ, load lifted off the ground",
                        _reference(result.rope_ground, "dynamic_factor"),
                        "",
                    ),
                ],
            )
        )
        sections += [result.rope_hanging, result.rope_ground]
    title = case.title or "Hoist motor and brake"
    return Report("hoist", title, sections, notes, result.status, result.message)
