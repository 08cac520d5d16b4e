"""The charts of ``--plot``: speed and torque against the angle (data only)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from mdcalc.problems.mechanism.case import TWO_PI
from mdcalc.problems.mechanism.fluctuation import Fluctuation
from mdcalc.problems.mechanism.scene import Scene
from mdcalc.problems.mechanism.solve import Result

if TYPE_CHECKING:
    from mdcalc.output.plot import Chart


#: Points of the ω(φ) curve per revolution, and at least and at most over the run.
CHART_POINTS_PER_REVOLUTION = 720

CHART_POINTS = (1441, 6001)


def charts(result: Result) -> list[Chart]:
    """ω(φ) of the reference over the run (its dense solution on a fine grid, no new
    ODE run) with Kovylin's nodes at the user's n and the last revolution's ω_mean,
    ω_max and ω_min; and M(φ, ω(φ)) along it. [] when the mechanism stalls."""
    ref = result.reference
    if result.status != "ok" or ref is None:
        return []
    scene, fl = result.scene, result.fluctuation
    angles = _chart_grid(scene, fl)
    speeds = ref.speeds_at(angles)
    out = [_speed_chart(result, angles, speeds)]
    try:
        torques = [scene.torque(phi, omega) for phi, omega in zip(angles, speeds, strict=True)]
    except ArithmeticError:
        return out
    if all(math.isfinite(m) for m in torques):
        out.append(_torque_chart(angles, torques))
    return out


def _chart_grid(scene: Scene, fl: Fluctuation | None) -> list[float]:
    """Equal steps over the run, with the last revolution's extremes added so that
    the curve reaches the report's ω_max and ω_min [rad]."""
    low, high = CHART_POINTS
    count = min(max(math.ceil(scene.revolutions * CHART_POINTS_PER_REVOLUTION) + 1, low), high)
    grid = [scene.start_angle + scene.span * k / (count - 1) for k in range(count)]
    grid[-1] = scene.end_angle
    if fl is not None:
        step = scene.span / (count - 1)
        for angle in (fl.maximum_angle, fl.minimum_angle):
            nearest = round((angle - scene.start_angle) / step)
            if abs(angle - scene.start_angle - nearest * step) > 1e-6 * step:
                grid.append(angle)
        grid = sorted(set(grid))
    return grid


def _speed_chart(result: Result, angles: list[float], speeds: list[float]) -> Chart:
    from mdcalc.output.plot import Chart, Mark, Series

    ref, scene, fl = result.reference, result.scene, result.fluctuation
    assert ref is not None
    degrees = [math.degrees(a) for a in angles]
    series = [Series(f"ω(φ), {ref.solver} reference", degrees, speeds)]
    marks: list[Mark] = []
    if fl is not None:
        marks += [
            Mark("y", fl.maximum, f"ω_max = {fl.maximum:.5g} rad/s", "reported"),
            Mark("y", fl.mean, f"ω_mean = {fl.mean:.5g} rad/s (last revolution)", "mean"),
            Mark("y", fl.minimum, f"ω_min = {fl.minimum:.5g} rad/s", "reported"),
        ]
        first = scene.end_angle - TWO_PI
        if first > scene.start_angle + 1e-9 * TWO_PI:
            marks.append(Mark("x", math.degrees(first), "last revolution"))
    else:
        mean = scene.span / ref.final_time
        marks.append(Mark("y", mean, f"mean over the run {mean:.5g} rad/s", "mean"))
    path = result.path
    if path is not None:
        # Nodes far off the reference's range would squash its curve: left out, and said
        low, high = min(speeds), max(speeds)
        margin = max(high - low, 1e-3 * high)
        kept = [
            (math.degrees(a), w)
            for a, w in zip(path.angles, path.speeds, strict=True)
            if low - margin <= w <= high + margin
        ]
        label = f"Kovylin (5), n = {scene.steps}"
        if len(kept) < len(path.angles):
            label += f" ({len(path.angles) - len(kept)} of {len(path.angles)} nodes off the scale)"
        if kept:
            series.append(Series(label, [a for a, _ in kept], [w for _, w in kept], "nodes"))
    return Chart(
        "Angular speed ω(φ) over the run",
        "φ [deg]",
        "ω [rad/s]",
        series,
        marks,
    )


def _torque_chart(angles: list[float], torques: list[float]) -> Chart:
    from mdcalc.output.plot import Chart, Mark, Series

    return Chart(
        "Reduced torque along the run: driving above 0, resisting below",
        "φ [deg]",
        "M [N·m]",
        [Series("M(φ, ω(φ))", [math.degrees(a) for a in angles], torques)],
        [Mark("y", 0.0, role="static")],
    )
