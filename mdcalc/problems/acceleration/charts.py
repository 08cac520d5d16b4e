"""The charts of ``--plot``: speed against time and the traction diagram (data
only)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from mdcalc.problems.acceleration.case import RAD_S_TO_RPM
from mdcalc.problems.acceleration.runs import Run
from mdcalc.problems.acceleration.solve import Result

if TYPE_CHECKING:
    from mdcalc.output.plot import Chart


#: Points of the speed-time curve over the whole run, and of each gear's curve.
CHART_POINTS = 400

GEAR_POINTS = 200


def charts(result: Result) -> list[Chart]:
    """``--plot``: the speed-time curve of the reference run (with the lecture
    method's, when it applies), and the traction diagram. The diagram needs no run,
    so a car that cannot reach the target, or cannot move off, still gets it."""
    charts: list[Chart] = []
    if result.run is not None and result.run.pieces:
        charts.append(_speed_chart(result, result.run))
    charts.append(_traction_chart(result))
    return charts


def _speed_chart(result: Result, run: Run) -> Chart:
    """v(t) from the reference run's dense output, piece by piece; marks at the
    upshifts and at the target speed."""
    from mdcalc.output.plot import Chart, Mark, Series

    scene = result.scene
    times: list[float] = []
    speeds: list[float] = []
    for t0, t1, _gear, _slipping, sol in run.pieces:
        n = max(8, math.ceil(CHART_POINTS * (t1 - t0) / run.time))
        for k in range(n + 1):
            if times and k == 0:
                continue  # the piece starts where the last one ended
            t = t0 + (t1 - t0) * k / n
            v = max(float(sol(t)[0]), 0.0)  # a car stopped within a shift stays stopped
            times.append(t)
            speeds.append(v * 3.6)
    series = [Series("reference run (DOP853)", times, speeds)]
    if result.lecture is not None:
        lecture_t, lecture_v, clock = [0.0], [0.0], 0.0
        gears = result.lecture["gears"]
        for k, (_v0, v1, dt) in enumerate(gears):
            clock += dt
            lecture_t.append(clock)
            lecture_v.append(v1 * 3.6)
            if k < len(gears) - 1:  # (7.42): the speed is kept through the shift
                clock += scene.shift_time
                lecture_t.append(clock)
                lecture_v.append(v1 * 3.6)
        series.append(Series("lecture method (7.40)-(7.42)", lecture_t, lecture_v, "comparison"))
    shifts = [p for p in run.phases if p.kind == "shift"]
    marks = [
        Mark("x", p.t_end - p.duration, "upshift" if k == 0 else "", "event")
        for k, p in enumerate(shifts)
    ]
    marks.append(
        Mark("y", scene.target * 3.6, f"target {scene.target * 3.6:.4g} km/h", "this-case")
    )
    return Chart(
        f"Speed against time: {scene.target * 3.6:.4g} km/h in {run.time:.4g} s "
        f"(gear {run.phases[-1].gear + 1} at the target)",
        "time t [s]",
        "speed v [km/h]",
        series,
        marks,
    )


def _traction_chart(result: Result) -> Chart:
    """Per gear, F_t = M_e·U_i·U_K·η/r over the engine speeds from the launch speed
    to the rev limit (first gear with the slipping launch from rest); the road
    resistance ψ·m·g + k·v², the adhesion limit φ·N and the planned upshifts."""
    from mdcalc.output.plot import Chart, Mark, Series

    scene = result.scene
    curve = scene.curve
    span = scene.limit - scene.launch
    nodes = sorted(
        {scene.launch + span * k / GEAR_POINTS for k in range(GEAR_POINTS + 1)}
        | {w for w in curve.speeds if scene.launch < w < scene.limit}  # the table's corners
    )
    series: list[Series] = []
    for gear in range(scene.gears):
        speeds = [scene.road_speed(gear, omega) * 3.6 for omega in nodes]
        forces = [scene.engine_force(gear, speed / 3.6, False) for speed in speeds]
        if gear == 0:  # from rest, the clutch slips with the engine at the launch speed
            speeds.insert(0, 0.0)
            forces.insert(0, scene.engine_force(0, 0.0, True))
        series.append(Series(f"gear {gear + 1} (U = {scene.ratios[gear]:g})", speeds, forces))
    v_end = max(scene.road_speed(scene.gears - 1, scene.limit), scene.target)
    road = [v_end * k / GEAR_POINTS for k in range(GEAR_POINTS + 1)]
    name = "resistance ψ·m·g + k·v²" if scene.drag > 0.0 else "resistance ψ·m·g"
    series.append(
        Series(name, [v * 3.6 for v in road], [scene.resistance(v) for v in road], "load")
    )
    if scene.phi is not None:
        grip = [scene.adhesion_force(v) for v in road]
        series.append(Series("adhesion limit φ·N", [v * 3.6 for v in road], grip, "limit"))
    upshifts = [s for s in result.plan.stints if s.shift_after]
    if upshifts:
        series.append(
            Series(
                "upshifts (plan)",
                [s.v_end * 3.6 for s in upshifts],
                [
                    scene.engine_force(s.gear, s.v_end, scene.slipping_at(s.gear, s.v_end))
                    for s in upshifts
                ],
                "event",
            )
        )
    marks = [Mark("x", scene.target * 3.6, f"target {scene.target * 3.6:.4g} km/h", "this-case")]
    top = result.top.limit.speed
    if result.status != "ok" and top > 0.0:
        marks.append(Mark("x", top * 3.6, f"top speed {top * 3.6:.4g} km/h", "limit"))
    return Chart(
        f"Traction diagram: F_t = M_e·U_i·U_K·η/r, engine {scene.launch * RAD_S_TO_RPM:.0f}"
        f"–{scene.limit * RAD_S_TO_RPM:.0f} rpm",
        "road speed v [km/h]",
        "force [N]",
        series,
        marks,
    )
