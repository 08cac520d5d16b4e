"""The speed fluctuation over a period: coefficient of unevenness, extremes."""

from __future__ import annotations

import bisect
from dataclasses import dataclass

from mdcalc.core.search import golden_maximum
from mdcalc.problems.mechanism.case import TWO_PI
from mdcalc.problems.mechanism.kovylin import Path
from mdcalc.problems.mechanism.reference import Reference, knots_between
from mdcalc.problems.mechanism.scene import Scene

#: Points of the grid over the last revolution where the extremes of ω are sought
#: (each then refined by golden section between its neighbours).
GRID_POINTS = 2048


@dataclass(frozen=True)
class Fluctuation:
    """Over the last revolution of the run."""

    maximum: float
    maximum_angle: float
    minimum: float
    minimum_angle: float
    mean: float  # 2π / (time of the revolution)
    start: float  # ω at the start of the revolution
    end: float

    @property
    def coefficient(self) -> float:
        """δ = (ω_max - ω_min)/ω_mean."""
        return (self.maximum - self.minimum) / self.mean


def fluctuation_of_path(path: Path) -> Fluctuation | None:
    end = path.angles[-1]
    first = end - TWO_PI
    if first < path.angles[0] - 1e-9:
        return None
    nodes = [k for k, a in enumerate(path.angles) if a >= first - 1e-9 * TWO_PI]
    speeds = [path.speeds[k] for k in nodes]
    k_max = nodes[speeds.index(max(speeds))]
    k_min = nodes[speeds.index(min(speeds))]
    t_first = _interpolate(path.angles, path.times, first)
    omega_first = _interpolate(path.angles, path.speeds, first)
    return Fluctuation(
        path.speeds[k_max],
        path.angles[k_max],
        path.speeds[k_min],
        path.angles[k_min],
        TWO_PI / (path.times[-1] - t_first),
        omega_first,
        path.speeds[-1],
    )


def _interpolate(xs: list[float], ys: list[float], x: float) -> float:
    k = min(max(bisect.bisect_right(xs, x) - 1, 0), len(xs) - 2)
    w = (x - xs[k]) / (xs[k + 1] - xs[k])
    return ys[k] + w * (ys[k + 1] - ys[k])


def fluctuation_of_reference(scene: Scene, ref: Reference) -> Fluctuation | None:
    end = scene.end_angle
    first = end - TWO_PI
    if first < scene.start_angle - 1e-9:
        return None
    samples = GRID_POINTS
    grid = [first + TWO_PI * k / samples for k in range(samples + 1)]
    speeds = ref.speeds_at(grid)

    def refine(k: int, sign: float) -> tuple[float, float]:
        low, high = grid[max(k - 1, 0)], grid[min(k + 1, samples)]
        f = lambda a: sign * ref.speed_at(a)  # noqa: E731
        best = golden_maximum(f, low, high, 60)  # on the dense solution
        candidates = [(f(best), best), (f(grid[k]), grid[k])]
        value, angle = max(candidates)
        return sign * value, angle

    top, top_angle = refine(speeds.index(max(speeds)), 1.0)
    low, low_angle = refine(speeds.index(min(speeds)), -1.0)
    # ω has a kink at each knot of a table of I (a spike where I dips between two
    # close knots): the grid can step over one, so each is a candidate of its own
    knots = knots_between(scene, first, end)
    for angle, value in zip(knots, ref.speeds_at(knots), strict=True):
        if value > top:
            top, top_angle = value, angle
        if value < low:
            low, low_angle = value, angle
    return Fluctuation(
        top,
        top_angle,
        low,
        low_angle,
        TWO_PI / (ref.final_time - ref.time_at(first)),
        ref.speed_at(first),
        ref.final_speed,
    )
