"""The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study`` for acceleration:
every numeric result of the scene over a block of cars at once.

The scene's own methods (:class:`~.scene.Scene`, written once for floats and arrays)
run on arrays: the plan (:func:`plan_block`: each gear's limit by the same 256-point
scan and bisection, the crossover of the accelerations, the shift decisions) for
every row at once, gear by gear; the lecture's (7.40)-(7.42) in closed form; and the
reference, the ODE run through the plan's phases (DOP853 at rtol 10⁻¹¹, each drive
phase ended by the event v = v_end, located on DOP853's continuous extension, with
the single run's spans and retries; the shifts coasting for t_shift), stepped for
every row at once by :func:`mdcalc.core.block_ode.dop853_block`.

A row the single scene answers otherwise is marked ``DECLINED``, to be solved alone:
a target the car cannot reach (no answer, with its reason), a phase whose event the
retries do not reach, a failed run.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Collection
from dataclasses import dataclass
from typing import Any

from mdcalc.core.units import rpm_to_rad_s
from mdcalc.input.model import in_tiles, kernel_answer, value_at, with_values
from mdcalc.problems.acceleration.case import RAD_S_TO_RPM, Case
from mdcalc.problems.acceleration.engine import EngineCurve
from mdcalc.problems.acceleration.plan import reaches
from mdcalc.problems.acceleration.runs import phase_time_estimate
from mdcalc.problems.acceleration.scene import Scene, scene_of

#: Keys ``mdcalc sweep`` and ``mdcalc study`` may vary in the vectorized form (N: any
#: list index). ``engine.max_power`` and ``engine.max_power_speed_rpm`` shape
#: Leiderman's curve; the launch, shift and rev-limit speeds, given or by default,
#: are each row's own. A torque table stays the case's (with it, the rev limit too).
SWEEP_KEYS = {
    "gravity": "g",
    "vehicle.mass": "m",
    "vehicle.wheel_radius": "r",
    "vehicle.rotating_mass_base": "δ_0",
    "vehicle.rotating_mass_engine": "δ_e",
    "vehicle.rotating_mass_factors.N": "δ_i",
    "transmission.gear_ratios.N": "U_i",
    "transmission.final_drive": "U_K",
    "transmission.efficiency": "η",
    "transmission.shift_time": "t_shift",
    "road.resistance": "ψ",
    "drag.drag_coefficient": "C_x",
    "drag.frontal_area": "A",
    "drag.air_density": "ρ",
    "adhesion.coefficient": "φ",
    "adhesion.driven_axle_load": "driven-axle share",
    "adhesion.cg_height": "h",
    "adhesion.wheelbase": "L",
    "target.speed": "v_target",
    "target.speed_kmh": "v_target",
    "target.measured_time": "measured time",
    "engine.max_power": "N_E",
    "engine.max_power_speed_rpm": "n_E",
    "engine.max_torque": "M_E (checked)",
    "engine.max_torque_speed_rpm": "n_M (the launch speed by default)",
    "engine.max_speed_rpm": "rev limit",
    "engine.torque_curve.torque.N": "M at a speed of the torque table",
    "transmission.shift_speed_rpm": "shift speed",
    "transmission.launch_speed_rpm": "launch speed",
    "lecture.traction_coefficient": "A/m",
    "lecture.shift_angular_speed": "ω_D",
}

#: Samples a call runs at once: the reference's arrays stay in the cache (16 384
#: rows of lecture.toml run at 1.1x the rate of 65 536).
TILE_ROWS = 16_384

#: The reference is the ODE run at rtol 10⁻¹¹ (DOP853, as the single scene's): the
#: kernel takes the single run's steps up to rounding and locates each phase's end
#: on the same continuous extension.
ODE_REFERENCED: dict[str, float | tuple[float, float]] = {
    "time_to_target": 1e-8,
    "distance_to_target": 1e-8,
    "difference_from_measured": (1e-8, 1e-8),
}

REFERENCE_RTOL = 1e-11
#: Spans a drive phase tries before the single run gives up (each 4 times longer).
TRIES = 4


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result of the block's scenes (numpy), as the single scene gives
    them. None for a key this form does not know, or one the case does not give."""
    import numpy as np

    for key in grid:
        parts = key.split(".")
        pattern = ".".join("N" if p.isdigit() else p for p in parts)
        if pattern not in SWEEP_KEYS or value_at(case, key) is None:
            return None
    if case.engine.torque_curve is not None and "engine.max_power" in grid:
        return None  # a number the table replaces: each point says so alone
    tiles = in_tiles(sweep, case, grid, wanted, TILE_ROWS)
    if tiles is not None:
        return tiles
    size = max([np.size(v) for v in grid.values()] + [1])
    c = with_values(case, {key: np.asarray(v, dtype=float) for key, v in grid.items()})
    scene = scene_of(c)
    values: dict[str, Any] = {}
    want = set(wanted) if wanted is not None else None
    with np.errstate(all="ignore"):
        values |= _echo(c, scene)
        limits: dict[int, Any] = {}
        target = np.broadcast_to(scene.target, (size,))
        declined = ~(target > 0.0)
        main = plan_block(scene, target, size, limits)
        if want is None or "top_speed_kmh" in want:
            top = plan_block(scene, math.inf, size, limits)
            values["top_speed_kmh"] = top.limit_speed * 3.6
        declined |= ~main.reached
        if c.lecture is not None:
            values |= _lecture(c, scene, size)
        values["launch_acceleration"] = scene.acceleration(0, 0.0, scene.slipping_at(0, 0.0))
        ode = want is None or bool(
            want & {"time_to_target", "distance_to_target", "gear_at_target"}
            or "difference_from_measured" in want
        )
        if ode:
            time, distance, gear, failed = _reference_run(scene, main, size)
            declined |= failed
            values |= {
                "time_to_target": time,
                "distance_to_target": distance,
                "gear_at_target": gear + 1.0,
            }
            measured = c.target.measured_time
            if measured is not None:
                values["measured_time"] = measured
                values["difference_from_measured"] = (time - measured) / measured * 100.0
        elif c.target.measured_time is not None:
            values["measured_time"] = c.target.measured_time
    return kernel_answer(values, declined, size)


def _echo(case: Case, scene: Scene) -> dict[str, Any]:
    """The scene's and the engine's numbers the report shows."""
    curve = scene.curve
    _, peak_torque = curve.peak(scene.limit)
    values: dict[str, Any] = {
        "mass": scene.mass,
        "wheel_radius": scene.radius,
        "final_drive": scene.final_drive,
        "efficiency": scene.efficiency,
        "road_resistance": scene.psi,
        "target_speed": scene.target,
        "target_speed_kmh": scene.target * 3.6,
        "shift_time": scene.shift_time,
        "peak_torque": peak_torque,
        "launch_speed_rpm": scene.launch * RAD_S_TO_RPM,
        "shift_speed_rpm": scene.shift * RAD_S_TO_RPM,
        "rev_limit_rpm": scene.limit * RAD_S_TO_RPM,
    }
    if case.drag is not None:
        values["drag_factor"] = scene.drag
    if case.adhesion is not None:
        values["adhesion"] = scene.phi
        values["driven_axle_load"] = scene.axle_load
    if not curve.is_table:
        values["rated_torque"] = curve.rated_torque
    engine = case.engine
    if engine.max_torque is not None and engine.max_torque_speed_rpm is not None:
        values["torque_at_n_m"] = curve.torque(rpm_to_rad_s(engine.max_torque_speed_rpm))
    return values


def take(scene: Scene, rows: Any) -> Scene:
    """The rows ``rows`` of a block's scene (its array numbers indexed, the rest kept)."""
    import numpy as np

    def part(value: Any) -> Any:
        if isinstance(value, np.ndarray) and value.ndim:
            return value[rows]
        if isinstance(value, tuple):
            return tuple(part(v) for v in value)
        if isinstance(value, EngineCurve):  # M_N, ω_E, a table's M where a study draws them
            return dataclasses.replace(
                value,
                rated_torque=part(value.rated_torque),
                rated_speed=part(value.rated_speed),
                torques=part(value.torques),
            )
        return value

    return dataclasses.replace(
        scene, **{f.name: part(getattr(scene, f.name)) for f in dataclasses.fields(scene)}
    )


# ------------------------------------------------------------------------ the plan


@dataclass
class PlanBlock:
    """:class:`~.plan.Plan` over a block: stint k is in gear k."""

    present: Any  # (gears, n) bool: row has a stint in gear k
    v_end: Any  # (gears, n)
    shift_after: Any  # (gears, n) bool
    reached: Any  # (n,) bool
    limit_speed: Any  # (n,): where the last gear stops accelerating the car
    limit_rev: Any  # (n,) bool: that limit is the rev limit (else resistance)
    limit_gear: Any  # (n,) int


def _pulls(scene: Scene, gear: int, v: Any) -> Any:
    import numpy as np

    return np.broadcast_to(scene.acceleration(gear, v, scene.slipping_at(gear, v)) > 0.0, v.shape)


#: Sample points of a scan tried at once (a (CHUNK, rows) array): fewer numpy calls.
CHUNK = 16


def _first(
    test: Any, part: Scene, start: Any, stop: Any, first: int, last: int, samples: int
) -> tuple[Any, Any, Any]:
    """The single scene's scan over a block: the first k in first..last where
    ``test(scene, v)`` holds at v = start + (stop - start)·k/samples, and the sample
    before it (start itself for the first k). (found, low, high) per row."""
    import numpy as np

    m = np.size(start)
    found = np.zeros(m, dtype=bool)
    low, high = np.full(m, np.nan), np.full(m, np.nan)
    previous = np.array(start, dtype=float)
    for k0 in range(first, last + 1, CHUNK):
        open_ = np.flatnonzero(~found)
        if not open_.size:
            break
        ks = np.arange(k0, min(k0 + CHUNK, last + 1), dtype=float)[:, None]
        v0, v1 = start[open_], stop[open_]
        v = v0 + (v1 - v0) * ks / samples  # (chunk, rows): the scalar's k-th sample
        holds = test(take(part, open_), v)
        hit = holds.any(axis=0)
        k = np.argmax(holds, axis=0)
        columns = np.flatnonzero(hit)
        rows = open_[columns]
        found[rows] = True
        high[rows] = v[k[columns], columns]
        before = np.where(k[columns] > 0, v[np.maximum(k[columns] - 1, 0), columns], 0.0)
        low[rows] = np.where(k[columns] > 0, before, previous[rows])
        previous[open_] = v[-1]
    return found, low, high


def _bisect(holds: Any, part: Scene, low: Any, high: Any, iterations: int, until_ulp: bool) -> Any:
    """The single plan's bisection over a block: ``high`` moves to the middle where
    ``holds``, ``low`` elsewhere; ``until_ulp`` stops a row where the middle is an end
    (:func:`~.plan.gear_limit`'s break; :func:`~.plan.crossover` runs on)."""
    import numpy as np

    for _ in range(iterations):
        middle = 0.5 * (low + high)
        left = holds(part, middle)
        moves = ~((middle == low) | (middle == high)) if until_ulp else True
        low, high = np.where(moves & ~left, middle, low), np.where(moves & left, middle, high)
    return high


#: A bound stands for the sign of every sample's acceleration where it clears zero by
#: this share of the numbers it is made of (their rounding is ~10⁻¹⁵ of them).
PROOF_MARGIN = 1e-9


def _pulls_throughout(scene: Scene, gear: int, low: Any, high: Any) -> Any:
    """The rows whose car the gear accelerates at every speed of [low, high], proven
    by bounds (False: not proven): the least full-throttle torque over the engine
    speeds those speeds give (the launch speed where the clutch slips) against the
    resistance at ``high`` (R = ψ·m·g + k·v² rises with v ≥ 0); with adhesion, the
    tyres' force less R at ``high`` (φ·(N - s·R)/(1 - s·φ) - R falls as R rises
    where 1 - s·φ > 0). The front wheels' lift limit does not depend on v: the
    rows asked about pull at ``low``, so it is positive at every speed. Each bound
    clears zero by :data:`PROOF_MARGIN` of its numbers, and the speeds reach a hair
    beyond the ends: so every sample of :func:`~.plan.gear_limit`'s scan pulls, and
    the scan, which would find no speed that stops the car, is not needed (the rev
    limit)."""
    import numpy as np

    hair = 1e-12
    top = high * (1.0 + hair)
    omega_low = np.maximum(scene.engine_speed(gear, low) * (1.0 - hair), scene.launch)
    torque, scale = scene.curve.least(omega_low, scene.engine_speed(gear, top))
    to_force = scene.overall(gear) * scene.efficiency / scene.radius
    resistance = scene.resistance(top)
    proven = (low >= 0.0) & (
        torque * to_force - resistance > PROOF_MARGIN * (scale * to_force + resistance)
    )
    if scene.phi is not None:
        s = scene.transfer / scene.delta_free
        grip = scene.adhesion_force(top)
        proven &= (1.0 - s * scene.phi > 0.0) & (
            grip - resistance > PROOF_MARGIN * (np.abs(grip) + resistance)
        )
    return np.broadcast_to(proven, np.shape(low))


def gear_limit_block(scene: Scene, gear: int, v_in: Any, samples: int = 256) -> tuple[Any, Any]:
    """:func:`~.plan.gear_limit` for every row: (speed, is the rev limit)."""
    import numpy as np

    n = np.size(v_in)
    v_rev = np.broadcast_to(scene.road_speed(gear, scene.limit), (n,))
    speed, rev = v_in.copy(), np.ones(n, dtype=bool)
    above = v_in >= v_rev
    pulling = _pulls(scene, gear, v_in)
    rev[~above & ~pulling] = False
    scan = np.flatnonzero(~above & pulling)
    if scan.size:  # a row that pulls at every speed up to the rev limit has no scan
        proven = _pulls_throughout(take(scene, scan), gear, v_in[scan], v_rev[scan])
        speed[scan[proven]] = v_rev[scan[proven]]
        scan = scan[~proven]
    if not scan.size:
        return speed, rev
    part = take(scene, scan)
    found, low, high = _first(
        lambda sub, v: ~_pulls(sub, gear, v), part, v_in[scan], v_rev[scan], 1, samples, samples
    )
    at = np.flatnonzero(found)
    if at.size:
        stalls = lambda sub, v: ~_pulls(sub, gear, v)  # noqa: E731
        high[at] = _bisect(stalls, take(part, at), low[at], high[at], 100, until_ulp=True)
    speed[scan] = np.where(found, high, v_rev[scan])
    rev[scan] = ~found
    return speed, rev


def crossover_block(scene: Scene, gear: int, v_in: Any, v_top: Any, samples: int = 256) -> Any:
    """:func:`~.plan.crossover` for every row (NaN for None)."""
    import numpy as np

    nxt = gear + 1

    def better(part: Scene, v: Any) -> Any:
        here = part.acceleration(gear, v, part.slipping_at(gear, v))
        return np.broadcast_to(part.acceleration(nxt, v, part.slipping_at(nxt, v)) > here, v.shape)

    out = np.where(better(scene, v_in), v_in, np.nan)
    todo = np.flatnonzero(np.isnan(out))
    if not todo.size:
        return out
    part = take(scene, todo)
    found, low, high = _first(better, part, v_in[todo], v_top[todo], 1, samples - 1, samples)
    at = np.flatnonzero(found)
    if at.size:
        result = np.full(todo.size, np.nan)
        result[at] = _bisect(better, take(part, at), low[at], high[at], 60, until_ulp=False)
        out[todo] = result
    return out


def _limits(
    scene: Scene, gear: int, rows: Any, v: Any, cache: dict[int, Any], n: int
) -> tuple[Any, Any]:
    """:func:`gear_limit_block` of the rows ``rows`` of the block from speeds ``v``,
    each (gear, row, speed) computed once for the plans that share it."""
    import numpy as np

    if gear not in cache:
        cache[gear] = (np.full(n, np.nan), np.full(n, np.nan), np.zeros(n, dtype=bool))
    known_v, speeds, revs = cache[gear]
    new = np.flatnonzero(~(known_v[rows] == v))
    if new.size:
        speed, rev = gear_limit_block(take(scene, rows[new]), gear, v[new])
        known_v[rows[new]], speeds[rows[new]], revs[rows[new]] = v[new], speed, rev
    return speeds[rows], revs[rows]


def plan_block(scene: Scene, target: Any, n: int, cache: dict[int, Any] | None = None) -> PlanBlock:
    """:func:`~.plan.plan` for every row: gear by gear, each row deciding as the
    single scene's plan does. ``cache`` shares the gears' limits between plans."""
    import numpy as np

    cache = {} if cache is None else cache

    gears = scene.gears
    target = np.broadcast_to(np.asarray(target, dtype=float), (n,))
    out = PlanBlock(
        np.zeros((gears, n), dtype=bool),
        np.full((gears, n), np.nan),
        np.zeros((gears, n), dtype=bool),
        np.zeros(n, dtype=bool),
        np.full(n, np.nan),
        np.zeros(n, dtype=bool),
        np.zeros(n, dtype=np.int64),
    )
    v = np.zeros(n)
    active = np.ones(n, dtype=bool)
    for gear in range(gears):
        rows = np.flatnonzero(active)
        if not rows.size:
            break
        part = take(scene, rows)
        vr, tr = v[rows], target[rows]
        speed, rev = _limits(scene, gear, rows, vr, cache, n)
        v_shift = np.broadcast_to(part.road_speed(gear, part.shift), rows.shape)
        candidate = np.full(rows.size, np.nan)
        if gear < gears - 1:
            first = (v_shift < tr) & reaches(speed, rev, v_shift)
            early = ~first & ~reaches(speed, rev, np.minimum(tr, v_shift))
            candidate[first] = v_shift[first]
            at = np.flatnonzero(early)
            if at.size:
                candidate[at] = crossover_block(take(part, at), gear, vr[at], speed[at])
        shifts = np.zeros(rows.size, dtype=bool)
        has = np.flatnonzero(np.isfinite(candidate))
        if has.size:
            sub = take(part, has)
            v_land, _ = sub.coast(candidate[has], sub.shift_time)
            v_land = np.broadcast_to(v_land, has.shape)
            nxt = gear + 1
            pulls = np.broadcast_to(
                sub.acceleration(nxt, v_land, sub.slipping_at(nxt, v_land)) > 0.0, has.shape
            )
            ok = has[pulls]
            if ok.size:
                next_speed, next_rev = _limits(scene, nxt, rows[ok], v_land[pulls], cache, n)
                go = (next_speed > np.minimum(tr[ok], speed[ok])) | reaches(
                    next_speed, next_rev, tr[ok]
                )
                shifts[ok[go]] = True
                v[rows[ok[go]]] = v_land[pulls][go]
        moving = rows[shifts]
        out.present[gear, moving] = True
        out.v_end[gear, moving] = candidate[shifts]
        out.shift_after[gear, moving] = True
        ending = ~shifts
        ends = rows[ending]
        reached = reaches(speed[ending], rev[ending], tr[ending])
        out.present[gear, ends[reached]] = True
        out.v_end[gear, ends[reached]] = tr[ending][reached]
        out.reached[ends] = reached
        out.limit_speed[ends] = speed[ending]
        out.limit_rev[ends] = rev[ending]
        out.limit_gear[ends] = gear
        active[ends] = False
    return out


# --------------------------------------------------------------------- the lecture


def _lecture(case: Case, scene: Scene, n: int) -> dict[str, Any]:
    """(7.40)-(7.42) over the block, as :func:`~.runs.lecture_run`; NaN where it does
    not apply (a gear with A·U/m - ψ not positive) and beyond a row's gears."""
    import numpy as np

    from mdcalc.problems.acceleration.solve import lecture_coefficients

    traction, omega_d = lecture_coefficients(case, scene)
    values: dict[str, Any] = {}
    gears = scene.gears
    target = np.broadcast_to(scene.target, (n,))
    v = np.zeros(n)
    count = np.zeros(n, dtype=np.int64)
    ends, times = np.full((gears, n), np.nan), np.full((gears, n), np.nan)
    total = np.zeros(n)
    done = np.zeros(n, dtype=bool)
    failed = np.zeros(n, dtype=bool)
    for gear, u in enumerate(scene.ratios):
        v_end = np.minimum(scene.road_speed(gear, omega_d), target)
        if gear == gears - 1:
            v_end = target
        runs = ~done & ~failed & ~(v_end <= v)
        a = np.broadcast_to(traction * u - scene.psi, (n,))
        failed |= runs & ~(a > 0.0)
        runs &= a > 0.0
        t = (v_end - v) / a
        at = np.flatnonzero(runs)
        ends[count[at], at] = np.broadcast_to(v_end, (n,))[at]
        times[count[at], at] = t[at]
        total = np.where(runs, total + t, total)
        count[at] += 1
        v = np.where(runs, v_end, v)
        done |= runs & (v >= target)
    total = total + (count - 1) * np.broadcast_to(scene.shift_time, (n,))
    for k in range(gears):
        values[f"lecture_v_end_{k + 1}"] = np.where(failed, np.nan, ends[k])
        values[f"lecture_time_{k + 1}"] = np.where(failed, np.nan, times[k])
    values["lecture_total_time"] = np.where(failed, np.nan, total)
    # where (7.42) does not apply the single scene shows no lecture section at all
    values["lecture_traction_coefficient"] = np.where(failed, np.nan, traction)
    values["lecture_shift_angular_speed"] = np.where(failed, np.nan, omega_d)
    return values


# ------------------------------------------------------------------ the reference


def _reference_run(scene: Scene, plan: PlanBlock, n: int) -> tuple[Any, Any, Any, Any]:
    """:func:`~.runs.ode_run` through every row's plan, phase by phase as
    :func:`~.runs.drive_through` walks it: (time, distance, gear of the last phase,
    failed)."""
    import numpy as np

    t, x, v, distance = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    gear_at = np.full(n, -1, dtype=np.int64)
    failed = ~plan.reached
    target = np.broadcast_to(scene.target, (n,))
    atol = np.stack([target, target], axis=1) * REFERENCE_RTOL * 1e-3
    for gear in range(scene.gears):
        has = plan.present[gear] & ~failed
        v_end = plan.v_end[gear]
        v_lock = np.broadcast_to(scene.road_speed(gear, scene.launch), (n,))
        for slipping in (True, False):
            if slipping:
                rows = np.flatnonzero(has & (v < v_lock) & (v < v_end))
                v1 = np.minimum(v_lock, v_end)
            else:
                rows = np.flatnonzero(has & ~failed & (v < v_end))
                v1 = v_end
            if not rows.size:
                continue
            dt, dx, ok = _drive(
                take(scene, rows), gear, slipping, v[rows], v1[rows], t[rows], x[rows], atol[rows]
            )
            t[rows], x[rows] = t[rows] + dt, x[rows] + dx
            distance[rows] = distance[rows] + dx
            v[rows] = v1[rows]
            gear_at[rows] = gear
            failed[rows[~ok]] = True
        rows = np.flatnonzero(has & ~failed & plan.shift_after[gear])
        if rows.size:
            part = take(scene, rows)
            v1, dx, ok = _shift(part, v[rows], t[rows], x[rows], atol[rows])
            t[rows] = t[rows] + np.broadcast_to(part.shift_time, rows.shape)
            x[rows] = x[rows] + dx
            distance[rows] = distance[rows] + dx
            v[rows] = v1
            gear_at[rows] = gear
            failed[rows[~ok]] = True
    return t, distance, gear_at.astype(float), failed


def _drive(
    scene: Scene, gear: int, slipping: bool, v0: Any, v1: Any, t: Any, x: Any, atol: Any
) -> tuple[Any, Any, Any]:
    """A drive phase of every row to v = v1: (dt, dx, reached) as the single run's
    ``drive`` (its span, four tries each four times longer)."""
    import numpy as np

    from mdcalc.core.block_ode import dop853_block

    m = v0.size
    span = 2.0 * phase_time_estimate(scene, gear, slipping, v0, v1) + 1e-3
    now, y = t.copy(), np.stack([v0, x], axis=1)
    end_t, end_x = np.full(m, np.nan), np.full(m, np.nan)
    pending = np.arange(m)
    for _ in range(TRIES):
        if not pending.size:
            break
        part = take(scene, pending)
        level = v1[pending]

        def rhs(rows: Any, time: Any, state: Any, part: Scene = part, m: int = pending.size) -> Any:
            speed = state[:, 0]
            here = part if rows.size == m else take(part, rows)
            a = here.acceleration(gear, speed, slipping)
            return np.stack([np.broadcast_to(a, speed.shape), speed], axis=1)

        hit_t, hit_x = np.full(pending.size, np.nan), np.full(pending.size, np.nan)

        def stop(step: Any, level: Any = level, hit_t: Any = hit_t, hit_x: Any = hit_x) -> Any:
            g_old = step.y_old[:, 0] - level[step.rows]
            g_new = step.y_new[:, 0] - level[step.rows]
            up = (g_old <= 0.0) & (g_new >= 0.0)
            at = np.flatnonzero(up)
            if at.size:
                dense = step.dense().take(at)
                when = dense.crossing(0, level[step.rows[at]])
                hit_t[step.rows[at]] = when
                hit_x[step.rows[at]] = dense.at(when, 1)
            return up

        run = dop853_block(
            rhs,
            now[pending],
            y[pending],
            now[pending] + span[pending],
            rtol=REFERENCE_RTOL,
            atol=atol[pending],
            stop=stop,
        )
        hit = run.stopped & np.isfinite(hit_t)
        end_t[pending[hit]], end_x[pending[hit]] = hit_t[hit], hit_x[hit]
        going = run.done & ~hit
        now[pending[going]], y[pending[going]] = run.t[going], run.y[going]
        span[pending[going]] *= 4.0
        pending = pending[going]
    reached = np.isfinite(end_t)
    return end_t - t, end_x - x, reached


def _shift(scene: Scene, v0: Any, t: Any, x: Any, atol: Any) -> tuple[Any, Any, Any]:
    """A shift of every row: coasting for t_shift, as the single run's ``shift``:
    (speed after, dx, done)."""
    import numpy as np

    from mdcalc.core.block_ode import dop853_block

    def rhs(rows: Any, time: Any, state: Any) -> Any:
        speed = np.maximum(state[:, 0], 0.0)
        here = scene if rows.size == v0.size else take(scene, rows)
        decel = here.coast_deceleration(speed)
        return np.stack([-np.broadcast_to(decel, speed.shape), speed], axis=1)

    duration = np.broadcast_to(scene.shift_time, v0.shape)
    run = dop853_block(
        rhs, t, np.stack([v0, x], axis=1), t + duration, rtol=REFERENCE_RTOL, atol=atol
    )
    return np.maximum(run.y[:, 0], 0.0), run.y[:, 1] - x, run.done
