"""The report: the sections a mechanism scene needs."""

from __future__ import annotations

import math
from typing import Any

from mdcalc.output.report import Column, Quantities, Quantity, Report, Table
from mdcalc.problems.mechanism.case import TWO_PI
from mdcalc.problems.mechanism.kovylin import Path
from mdcalc.problems.mechanism.reference import Reference
from mdcalc.problems.mechanism.solve import Result

RAD_S_TO_RPM = 30.0 / math.pi

TABLE_ROWS = 37


def report(result: Result) -> Report:
    case, s = result.case, result.scene
    title = case.title or "Mechanism: motion under M(φ, ω)"
    scene_items = [
        Quantity("start_angle", "Start angle φ₀", s.start_angle, "rad"),
        Quantity("start_speed", "Start speed ω₀", s.start_speed, "rad/s"),
        Quantity("start_inertia", "I(φ₀)", s.inertia(s.start_angle), "kg·m²"),
        Quantity("start_torque", "M(φ₀, ω₀)", s.torque(s.start_angle, s.start_speed), "N·m"),
        Quantity("end_angle", "End angle φ₀ + 2π·revolutions", s.end_angle, "rad"),
        Quantity("steps_per_revolution", "Kovylin's steps per revolution n", s.steps, ""),
    ]
    sections: list[Any] = [Quantities("Scene", scene_items)]
    if result.status != "ok":
        return Report("mechanism", title, sections, [], result.status, result.message)
    ref = result.reference
    assert ref is not None and result.methods is not None
    motion = [
        Quantity(
            "final_speed",
            "ω at the end angle",
            ref.final_speed,
            "rad/s",
            f"{ref.final_speed * RAD_S_TO_RPM:.6g} rpm",
        ),
        Quantity("final_time", "Time to the end angle t", ref.final_time, "s"),
        Quantity("mean_speed", "Mean speed over the run", s.span / ref.final_time, "rad/s"),
    ]
    sections.append(Quantities(f"Motion ({ref.solver} reference)", motion))
    fl = result.fluctuation
    if fl is not None:
        sections.append(
            Quantities(
                "Speed fluctuation over the last revolution",
                [
                    Quantity(
                        "max_speed",
                        "ω_max",
                        fl.maximum,
                        "rad/s",
                        f"at φ = {math.degrees(fl.maximum_angle):.5g}°",
                    ),
                    Quantity(
                        "min_speed",
                        "ω_min",
                        fl.minimum,
                        "rad/s",
                        f"at φ = {math.degrees(fl.minimum_angle):.5g}°",
                    ),
                    Quantity(
                        "mean_speed_revolution",
                        "ω_mean = 2π / time of the revolution",
                        fl.mean,
                        "rad/s",
                    ),
                    Quantity("fluctuation", "δ = (ω_max - ω_min)/ω_mean", fl.coefficient, ""),
                ],
            )
        )
    if result.path is not None:
        sections.append(_path_table(result.path, ref))
        worst = max(
            abs(w - ref.speed_at(a)) / ref.speed_at(a) if ref.speed_at(a) > 0 else 0.0
            for a, w in zip(result.path.angles, result.path.speeds, strict=True)
        )
        sections.append(
            Quantities(
                f"Kovylin at n = {s.steps}",
                [
                    Quantity(
                        "kovylin_final_speed", "ω at the end angle", result.path.speeds[-1], "rad/s"
                    ),
                    Quantity(
                        "kovylin_worst_error", "Largest relative error of ω at a node", worst, ""
                    ),
                ],
            )
        )
    sections.append(result.methods)
    return Report("mechanism", title, sections, list(result.notes))


def _path_table(path: Path, ref: Reference) -> Table:
    rows: list[list[Any]] = []
    indices = list(range(len(path.angles)))
    title = "ω(φ) and t(φ) at Kovylin's nodes"
    if len(indices) > TABLE_ROWS:
        last = path.angles[-1] - TWO_PI
        indices = [k for k in indices if path.angles[k] >= last - 1e-9]
        if len(indices) > TABLE_ROWS:
            stride = math.ceil(len(indices) / TABLE_ROWS)
            indices = indices[::stride] + ([] if indices[-1] % stride == 0 else [indices[-1]])
        title += " (last revolution)"
    for k in indices:
        phi, omega = path.angles[k], path.speeds[k]
        exact = ref.speed_at(phi)
        rows.append(
            [
                math.degrees(phi),
                omega,
                exact,
                (omega - exact) / exact if exact > 0 else 0.0,
                path.times[k],
                ref.time_at(phi),
            ]
        )
    return Table(
        title,
        "path",
        [
            Column("φ", "deg"),
            Column("ω Kovylin", "rad/s"),
            Column("ω reference", "rad/s"),
            Column("rel. error"),
            Column("t Kovylin", "s"),
            Column("t reference", "s"),
        ],
        rows,
    )
