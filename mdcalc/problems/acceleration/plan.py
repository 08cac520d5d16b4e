"""The plan: in which gears the car runs, and where it shifts up (the crossover
of the accelerations)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from mdcalc.core.xp import of
from mdcalc.problems.acceleration.scene import Scene

#: Relative distance below a resistance-limited top speed inside which a target
#: counts as not reached (see :meth:`GearLimit.allows`).
ASYMPTOTE_MARGIN = 1e-6


@dataclass(frozen=True)
class GearLimit:
    """How fast a gear can take the car: to the rev limit or to where F_t = R."""

    speed: float
    reason: Literal["rev limit", "resistance"]

    def allows(self, v: float) -> bool:
        """Whether the gear gets the car to speed ``v`` (:func:`reaches`)."""
        return bool(reaches(self.speed, self.reason == "rev limit", v))


def reaches(speed: Any, rev_limit: Any, v: Any) -> Any:
    """Whether a gear limited at ``speed`` (by the rev limit, else by resistance)
    gets the car to ``v``; floats or arrays over a block of cars. Where traction
    equals resistance the car only approaches the speed (the time grows as the log
    of 1/(v_top - v)); a target within ASYMPTOTE_MARGIN of it counts as not reached."""
    return of(speed, rev_limit, v).where(
        rev_limit, lambda: v <= speed, lambda: v < speed * (1.0 - ASYMPTOTE_MARGIN)
    )


def gear_limit(scene: Scene, gear: int, v_in: float, samples: int = 256) -> GearLimit:
    """The first speed above ``v_in`` where the gear stops accelerating the car."""
    v_rev = scene.road_speed(gear, scene.limit)

    def pulls(v: float) -> bool:
        return scene.acceleration(gear, v, scene.slipping_at(gear, v)) > 0.0

    if v_in >= v_rev:
        return GearLimit(v_in, "rev limit")
    if not pulls(v_in):
        return GearLimit(v_in, "resistance")
    previous = v_in
    for k in range(1, samples + 1):
        v = v_in + (v_rev - v_in) * k / samples
        if not pulls(v):
            low, high = previous, v
            for _ in range(100):
                middle = 0.5 * (low + high)
                if middle in (low, high):
                    break
                low, high = (middle, high) if pulls(middle) else (low, middle)
            return GearLimit(high, "resistance")
        previous = v
    return GearLimit(v_rev, "rev limit")


def crossover(
    scene: Scene, gear: int, v_in: float, v_top: float, samples: int = 256
) -> float | None:
    """The first speed in [v_in, v_top) where the next gear accelerates the car
    harder than ``gear`` does, or None."""
    nxt = gear + 1

    def better(v: float) -> bool:
        here = scene.acceleration(gear, v, scene.slipping_at(gear, v))
        return scene.acceleration(nxt, v, scene.slipping_at(nxt, v)) > here

    if better(v_in):
        return v_in
    previous = v_in
    for k in range(1, samples):
        v = v_in + (v_top - v_in) * k / samples
        if better(v):
            low, high = previous, v
            for _ in range(60):
                middle = 0.5 * (low + high)
                low, high = (low, middle) if better(middle) else (middle, high)
            return high
        previous = v
    return None


@dataclass(frozen=True)
class Stint:
    """Drive in ``gear`` up to ``v_end``, then shift up if ``shift_after``."""

    gear: int
    v_end: float
    shift_after: bool


@dataclass(frozen=True)
class Plan:
    stints: list[Stint]
    reached: bool
    limit: GearLimit  # where the last gear stops accelerating the car
    limit_gear: int


def plan(scene: Scene, target: float) -> Plan:
    """Gears, shift speeds and whether the target is reached.

    Upshift at the shift engine speed while the target lies beyond it; where the
    gear stops pulling before that speed, upshift early at the speed where the next
    gear pulls harder. Do not upshift when the next gear cannot pull at the speed it
    lands at, or tops out below what the present gear reaches: then the present gear
    is held to the rev limit.
    """
    stints: list[Stint] = []
    v, gear = 0.0, 0
    while True:
        limit = gear_limit(scene, gear, v)
        last = gear == scene.gears - 1
        v_shift = scene.road_speed(gear, scene.shift)
        candidate: float | None = None
        if last:
            pass
        elif v_shift < target and limit.allows(v_shift):
            candidate = v_shift
        elif not limit.allows(min(target, v_shift)):
            # The gear stops pulling before the shift speed and the target: shift
            # early, where the next gear pulls harder.
            candidate = crossover(scene, gear, v, limit.speed)
        if candidate is not None:
            v_land, _ = scene.coast(candidate, scene.shift_time)
            nxt = gear + 1
            if scene.acceleration(nxt, v_land, scene.slipping_at(nxt, v_land)) > 0.0:
                next_limit = gear_limit(scene, nxt, v_land)
                if next_limit.speed > min(target, limit.speed) or next_limit.allows(target):
                    stints.append(Stint(gear, candidate, True))
                    v, gear = v_land, nxt
                    continue
        if limit.allows(target):
            stints.append(Stint(gear, target, False))
            return Plan(stints, True, limit, gear)
        return Plan(stints, False, limit, gear)
