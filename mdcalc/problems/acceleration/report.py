"""The report: the sections an acceleration scene needs."""

from __future__ import annotations

import math
from typing import Any

from mdcalc.core.units import rpm_to_rad_s
from mdcalc.output.report import Column, Note, Quantities, Quantity, Report, Table
from mdcalc.problems.acceleration.case import RAD_S_TO_RPM, Case
from mdcalc.problems.acceleration.plan import gear_limit
from mdcalc.problems.acceleration.runs import Run
from mdcalc.problems.acceleration.scene import Scene
from mdcalc.problems.acceleration.solve import Result


def report(result: Result) -> Report:
    case, scene = result.case, result.scene
    title = case.title or "Acceleration"
    sections: list[Any] = [_scene_section(case, scene), _engine_section(case, scene)]
    notes: list[Note] = []
    top = result.top
    top_rpm = scene.engine_speed_at(top.limit_gear, top.limit.speed) * RAD_S_TO_RPM
    where = f"gear {top.limit_gear + 1}, {top_rpm:.0f} rpm, {top.limit.reason}"
    if top.limit.speed == 0.0:
        where = "the car cannot move off"
    top_items = [Quantity("top_speed_kmh", "Top speed", top.limit.speed * 3.6, "km/h", where)]
    if result.status != "ok":
        sections.append(Quantities("Limits", top_items))
        sections.append(_gear_limits_table(scene))
        return Report("acceleration", title, sections, notes, result.status, result.message)

    assert result.run is not None and result.methods is not None
    if case.lecture is not None and result.lecture is not None:
        sections.append(_lecture_section(result))
        notes.append(Note("info", _lecture_conventions(result)))
    run = result.run
    outcome = [
        Quantity("time_to_target", "Time to the target speed", run.time, "s"),
        Quantity("distance_to_target", "Distance to the target speed", run.distance, "m"),
        Quantity("gear_at_target", "Gear at the target speed", run.phases[-1].gear + 1, ""),
        Quantity(
            "launch_acceleration",
            "Acceleration at launch",
            scene.acceleration(0, 0.0, scene.slipping_at(0, 0.0)),
            "m/s²",
            "adhesion-limited" if scene.adhesion_limited(0, 0.0, True) else "",
        ),
        *top_items,
    ]
    measured = case.target.measured_time
    if measured is not None:
        outcome += [
            Quantity("measured_time", "Published/measured time", measured, "s"),
            Quantity(
                "difference_from_measured",
                "Model minus measured",
                (run.time - measured) / measured * 100.0,
                "%",
            ),
        ]
    sections.append(
        Quantities(f"Reaching {scene.target * 3.6:.4g} km/h (reference method)", outcome)
    )
    sections.append(_phases_table(scene, run))
    sections.append(_speed_table(scene, run, case.target.table_step))
    sections.append(result.methods)
    if any(p.adhesion_limited for p in run.phases):
        notes.append(
            Note(
                "info",
                "traction is limited by adhesion in part of the run (phases marked): the engine "
                "could pass more torque than the driven tyres can",
            )
        )
    return Report("acceleration", title, sections, notes, result.status, result.message)


def _scene_section(case: Case, scene: Scene) -> Quantities:
    items = [
        Quantity("mass", "Mass m", scene.mass, "kg"),
        Quantity("wheel_radius", "Wheel radius r", scene.radius, "m"),
        Quantity("gear_ratios", "Gear ratios U_i", tuple(scene.ratios), ""),
        Quantity("final_drive", "Final drive U_K", scene.final_drive, ""),
        Quantity("efficiency", "Driveline efficiency η", scene.efficiency, ""),
        Quantity(
            "rotating_mass_factors",
            "Rotating-mass factors δ_i",
            tuple(scene.deltas),
            "",
            f"δ_0 = {scene.delta_free:g} while the clutch is open or slips",
        ),
        Quantity("road_resistance", "Road resistance ψ", scene.psi, ""),
        Quantity("target_speed", "Target speed", scene.target, "m/s"),
        Quantity("target_speed_kmh", "Target speed", scene.target * 3.6, "km/h"),
        Quantity("shift_time", "Shift time", scene.shift_time, "s"),
    ]
    if case.drag is not None:
        items.append(Quantity("drag_factor", "Drag factor ½·ρ·C_x·A", scene.drag, "kg/m"))
    if case.adhesion is not None:
        assert scene.phi is not None
        items += [
            Quantity(
                "adhesion", "Adhesion coefficient φ", scene.phi, "", case.adhesion.surface or ""
            ),
            Quantity("driven_axle_load", "Driven-axle load at rest", scene.axle_load, "N"),
        ]
    return Quantities("Scene", items)


def _engine_section(case: Case, scene: Scene) -> Quantities:
    curve = scene.curve
    peak_speed, peak_torque = curve.peak(scene.limit)
    items: list[Quantity] = []
    if not curve.is_table:
        items.append(
            Quantity(
                "rated_torque",
                "Torque at maximum power M_N = N_E/ω_E",
                curve.rated_torque,
                "N·m",
            )
        )
    items.append(
        Quantity(
            "peak_torque",
            "Peak torque of the curve",
            peak_torque,
            "N·m",
            f"at {peak_speed * RAD_S_TO_RPM:.0f} rpm",
        )
    )
    engine = case.engine
    if engine.max_torque is not None and engine.max_torque_speed_rpm is not None:
        at = curve.torque(rpm_to_rad_s(engine.max_torque_speed_rpm))
        items.append(
            Quantity(
                "torque_at_n_m",
                f"Curve torque at n_M = {engine.max_torque_speed_rpm:g} rpm",
                at,
                "N·m",
                f"{(at - engine.max_torque) / engine.max_torque * 100:+.2g} % against the "
                f"published {engine.max_torque:g} N·m",
            )
        )
    items += [
        Quantity(
            "launch_speed_rpm",
            "Launch engine speed (clutch slips)",
            scene.launch * RAD_S_TO_RPM,
            "rpm",
        ),
        Quantity("shift_speed_rpm", "Upshift engine speed", scene.shift * RAD_S_TO_RPM, "rpm"),
        Quantity("rev_limit_rpm", "Rev limit", scene.limit * RAD_S_TO_RPM, "rpm"),
    ]
    title = "Engine (Leiderman curve, (7.37))" if not curve.is_table else "Engine (torque table)"
    return Quantities(title, items)


def _lecture_section(result: Result) -> Quantities:
    assert result.lecture is not None
    scene = result.scene
    a_per_ratio, omega_d = result.lecture_coefficients
    items = [
        Quantity("lecture_traction_coefficient", "A/m in (7.42)", a_per_ratio, "m/s²"),
        Quantity("lecture_shift_angular_speed", "ω_D in (7.40)", omega_d, "rad/s"),
    ]
    for k, (v0, v1, t) in enumerate(result.lecture["gears"], start=1):
        items.append(Quantity(f"lecture_v_end_{k}", f"Gear {k}: v_end (7.40)", v1, "m/s"))
        items.append(
            Quantity(
                f"lecture_time_{k}",
                f"Gear {k}: t = Δv/(A·U/m - ψ) (7.42)",
                t,
                "s",
                f"from {v0:.4g} m/s",
            )
        )
    shifts = len(result.lecture["gears"]) - 1
    items.append(
        Quantity(
            "lecture_total_time",
            f"Total, with {shifts} shifts of {scene.shift_time:g} s",
            result.lecture["time"],
            "s",
        )
    )
    return Quantities("Lecture method (7.40)-(7.42)", items)


def _lecture_conventions(result: Result) -> str:
    scene = result.scene
    a_per_ratio, omega_d = result.lecture_coefficients
    peak_speed, peak_torque = scene.curve.peak(scene.limit)
    physical = scene.traction_coefficient(peak_torque)
    lecture_source = ""
    if math.isclose(a_per_ratio, 1.1):
        lecture_source = (
            "the lecture's 1.1 rests on a garbled M_max = 206 N·m and on its weight of "
            "15 000 N taken as a mass of 1500 kg; "
        )
    return (
        "the lecture method keeps the lecture's conventions so that it reproduces its numbers, "
        f"not physics: ψ = {scene.psi:g} is subtracted as an acceleration in m/s² (physically "
        f"ψ·g = {scene.psi * scene.g:.4g} m/s²); A/m = {a_per_ratio:.4g} m/s² per unit ratio "
        f"is taken as given ({lecture_source}the curve's peak "
        f"{peak_torque:.4g} N·m with η = {scene.efficiency:g} gives {physical:.3g}); the rotating "
        "masses, drag, adhesion and the speed lost in shifts are left out; each gear ends at "
        f"ω_D = {omega_d:.4g} rad/s = {omega_d * RAD_S_TO_RPM:.0f} rpm"
    )


def _phases_table(scene: Scene, run: Run) -> Table:
    rows: list[list[Any]] = []
    for p in run.phases:
        engine = None if p.engine_speed is None else round(p.engine_speed * RAD_S_TO_RPM)
        rows.append(
            [
                p.label + (" (adhesion-limited)" if p.adhesion_limited else ""),
                p.v0 * 3.6,
                p.v1 * 3.6,
                engine,
                p.duration,
                p.distance,
                p.t_end,
            ]
        )
    return Table(
        "Phases (reference run)",
        "phases",
        [
            Column("phase"),
            Column("from", "km/h"),
            Column("to", "km/h"),
            Column("engine at end", "rpm"),
            Column("time", "s"),
            Column("distance", "m"),
            Column("clock", "s"),
        ],
        rows,
    )


def _nice_step(span: float) -> float:
    raw = span / 20.0
    exponent = math.floor(math.log10(raw))
    for mantissa in (1.0, 2.0, 5.0, 10.0):
        step = mantissa * 10.0**exponent
        if step >= raw:
            return step
    return 10.0 ** (exponent + 1)


#: Most rows of the speed-time table; a finer table_step is widened to fit.
MAX_TABLE_ROWS = 2000


def _speed_table(scene: Scene, run: Run, step: float | None) -> Table:
    step = max(step or _nice_step(run.time), run.time / MAX_TABLE_ROWS)
    rows: list[list[Any]] = []
    times = [k * step for k in range(int(run.time / step) + 1)]
    if times[-1] < run.time:
        times.append(run.time)
    for t in times:
        piece = next((p for p in run.pieces if p[0] <= t <= p[1]), run.pieces[-1])
        t0, t1, gear, slipping, sol = piece
        v, x = (float(c) for c in sol(min(max(t, t0), t1)))
        engine: int | None = None
        if slipping is None:
            label = f"shift {gear + 1}→{gear + 2}"
            v = max(v, 0.0)  # a car stopped within the shift stays stopped
            a = -scene.coast_deceleration(v) if v > 0.0 else 0.0
        else:
            label = f"{gear + 1}"
            a = scene.acceleration(gear, v, slipping)
            omega = scene.engine_omega(gear, v, slipping)
            engine = round(omega * RAD_S_TO_RPM)
        rows.append([t, v * 3.6, x, a, label, engine])
    return Table(
        "Speed against time (reference run)",
        "speed_time",
        [
            Column("time", "s"),
            Column("speed", "km/h"),
            Column("distance", "m"),
            Column("acceleration", "m/s²"),
            Column("gear"),
            Column("engine", "rpm"),
        ],
        rows,
    )


def _gear_limits_table(scene: Scene) -> Table:
    rows: list[list[Any]] = []
    for gear in range(scene.gears):
        limit = gear_limit(scene, gear, 0.0)
        rows.append(
            [
                f"{gear + 1}",
                scene.ratios[gear],
                limit.speed * 3.6,
                round(scene.engine_speed_at(gear, limit.speed) * RAD_S_TO_RPM)
                if limit.speed > 0.0
                else None,
                limit.reason,
            ]
        )
    return Table(
        "How fast each gear can go from rest",
        "gear_limits",
        [
            Column("gear"),
            Column("ratio"),
            Column("top speed", "km/h"),
            Column("engine", "rpm"),
            Column("limited by"),
        ],
        rows,
    )
