"""The runs through the gears and shifts: the lecture's method, piecewise closed
forms, the ODE reference."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

from mdcalc.core.xp import of
from mdcalc.methods import NotApplicable
from mdcalc.problems.acceleration.plan import Stint
from mdcalc.problems.acceleration.scene import Scene

if TYPE_CHECKING:
    import numpy as np


@dataclass(frozen=True)
class PhaseRecord:
    label: str
    gear: int  # 0-based
    kind: Literal["slip", "drive", "shift"]
    v0: float
    v1: float
    duration: float
    distance: float
    t_end: float
    engine_speed: float | None  # at the end [rad/s]; None during a shift
    adhesion_limited: bool = False


@dataclass
class Run:
    """One method's run through the plan: phase by phase, with totals."""

    phases: list[PhaseRecord] = field(default_factory=list)
    # Dense solution pieces of an ODE run: (t0, t1, gear, slipping or None, sol).
    pieces: list[tuple[float, float, int, bool | None, Callable[[float], Any]]] = field(
        default_factory=list
    )

    @property
    def time(self) -> float:
        return self.phases[-1].t_end if self.phases else 0.0

    @property
    def distance(self) -> float:
        return sum(p.distance for p in self.phases)

    def values(self) -> dict[str, float]:
        return {"time_to_target": self.time, "distance_to_target": self.distance}


DriveStep = Callable[[Scene, int, bool, float, float, float, float, Run], tuple[float, float]]

ShiftStep = Callable[[Scene, int, float, float, float, Run], tuple[float, float]]


def drive_through(scene: Scene, stints: list[Stint], drive: DriveStep, shift: ShiftStep) -> Run:
    """Walk the plan: slip and drive phases per gear, shifts between; the method's
    ``drive`` and ``shift`` steps say how long each phase takes and how far it goes.
    """
    run = Run()
    t, x, v = 0.0, 0.0, 0.0
    for stint in stints:
        gear = stint.gear
        v_lock = scene.road_speed(gear, scene.launch)
        label = f"gear {gear + 1}"
        if v < v_lock and v < stint.v_end:
            v1 = min(v_lock, stint.v_end)
            dt, dx = drive(scene, gear, True, v, v1, t, x, run)
            t, x = t + dt, x + dx
            run.phases.append(
                PhaseRecord(
                    f"{label}, clutch slipping",
                    gear,
                    "slip",
                    v,
                    v1,
                    dt,
                    dx,
                    t,
                    scene.launch,
                    _adhesion_limited(scene, gear, True, v, v1),
                )
            )
            v = v1
        if v < stint.v_end:
            dt, dx = drive(scene, gear, False, v, stint.v_end, t, x, run)
            t, x = t + dt, x + dx
            run.phases.append(
                PhaseRecord(
                    label,
                    gear,
                    "drive",
                    v,
                    stint.v_end,
                    dt,
                    dx,
                    t,
                    scene.engine_speed(gear, stint.v_end),
                    _adhesion_limited(scene, gear, False, v, stint.v_end),
                )
            )
            v = stint.v_end
        if stint.shift_after:
            v1, dx = shift(scene, gear, v, t, x, run)
            t, x = t + scene.shift_time, x + dx
            run.phases.append(
                PhaseRecord(
                    f"shift {gear + 1}→{gear + 2}",
                    gear,
                    "shift",
                    v,
                    v1,
                    scene.shift_time,
                    dx,
                    t,
                    None,
                )
            )
            v = v1
    return run


def _adhesion_limited(scene: Scene, gear: int, slipping: bool, v0: float, v1: float) -> bool:
    return any(scene.adhesion_limited(gear, v, slipping) for v in (v0, 0.5 * (v0 + v1), v1))


def lecture_run(scene: Scene, traction_coefficient: float, omega_d: float) -> dict[str, Any]:
    """(7.40)-(7.42): per gear v_end = ω_D·r/(U_i·U_K) capped at the target and
    t_i = Δv/(A·U_i/m - ψ), ψ taken as m/s² (the lecture's convention)."""
    gears: list[tuple[float, float, float]] = []  # (v_start, v_end, t)
    v = 0.0
    for gear, u in enumerate(scene.ratios):
        v_end = min(scene.road_speed(gear, omega_d), scene.target)  # (7.40)
        if gear == scene.gears - 1:
            v_end = scene.target  # top gear runs on to the target
        if v_end <= v:
            continue
        a = traction_coefficient * u - scene.psi  # (7.42) denominator
        if a <= 0.0:
            raise NotApplicable(f"A·U_{gear + 1}/m - ψ = {a:.3g} m/s² is not positive")
        gears.append((v, v_end, (v_end - v) / a))
        v = v_end
        if v >= scene.target:
            break
    shifts = len(gears) - 1
    time = sum(g[2] for g in gears) + shifts * scene.shift_time
    distance = sum(0.5 * (g[0] + g[1]) * g[2] for g in gears) + sum(
        g[1] * scene.shift_time for g in gears[:-1]
    )
    return {"gears": gears, "time": time, "distance": distance}


def _piecewise_drive(
    scene: Scene, gear: int, slipping: bool, v0: float, v1: float, t: float, x: float, run: Run
) -> tuple[float, float]:
    """Constant acceleration over the phase: the physical one at its mid-speed."""
    v_mid = 0.5 * (v0 + v1)
    a = scene.acceleration(gear, v_mid, slipping)
    if a <= 0.0:
        raise NotApplicable(f"acceleration at the mid-speed of gear {gear + 1} is not positive")
    dt = (v1 - v0) / a
    return dt, v_mid * dt


def _piecewise_shift(
    scene: Scene, gear: int, v0: float, t: float, x: float, run: Run
) -> tuple[float, float]:
    """Constant deceleration over the shift at its value at the shift speed."""
    d = scene.coast_deceleration(v0)
    duration = scene.shift_time
    if d * duration >= v0:  # the car stops within the shift
        return 0.0, v0 * v0 / (2.0 * d)
    v1 = v0 - d * duration
    return v1, 0.5 * (v0 + v1) * duration


def phase_time_estimate(scene: Scene, gear: int, slipping: bool, v0: Any, v1: Any) -> Any:
    """∫ dv/a from v0 to v1 by the trapezoid rule on nodes crowded towards v1, where
    a target close to a top speed makes 1/a large: a bound for the ODE runs. Floats,
    or arrays over a block of cars."""
    nodes = [v1 - (v1 - v0) * 10.0 ** (-k / 4) for k in range(49)] + [v1]
    accelerations = [scene.acceleration(gear, v, slipping) for v in nodes]
    inverse = [1.0 / of(a).maximum(a, 1e-300) for a in accelerations]
    return sum(
        0.5 * (inverse[k] + inverse[k + 1]) * (nodes[k + 1] - nodes[k])
        for k in range(len(nodes) - 1)
    )


def piecewise_run(scene: Scene, stints: list[Stint]) -> Run:
    return drive_through(scene, stints, _piecewise_drive, _piecewise_shift)


def ode_run(scene: Scene, stints: list[Stint], rtol: float, dense: bool = False) -> Run:
    """Integrate δ·m·v' = F_t - R, x' = v phase by phase; events end each phase."""
    import numpy as np

    from mdcalc.core.ode import advance, pick_solver

    method = pick_solver(rtol)
    atol = np.array([scene.target, scene.target]) * rtol * 1e-3

    def drive(
        scene: Scene, gear: int, slipping: bool, v0: float, v1: float, t: float, x: float, run: Run
    ) -> tuple[float, float]:
        def rhs(time: float, y: np.ndarray) -> np.ndarray:
            return np.array([scene.acceleration(gear, y[0], slipping), y[0]])

        span = 2.0 * phase_time_estimate(scene, gear, slipping, v0, v1) + 1e-3
        y = np.array([v0, x])
        t0 = t
        for _ in range(4):
            segment = advance(
                rhs,
                t,
                y,
                t + span,
                rtol=rtol,
                atol=atol,
                method=method,
                terminal=[(lambda time, y: y[0] - v1, 1)],
                dense=dense,
            )
            if dense and segment.sol is not None:
                run.pieces.append((t, segment.t, gear, slipping, segment.sol))
            t, y = segment.t, segment.y
            if segment.event is not None:
                return t - t0, float(y[1]) - x
            span *= 4.0
        raise NotApplicable(
            f"{method} did not reach {v1 * 3.6:.6g} km/h in gear {gear + 1} within "
            f"{t - t0:.3g} s: the target is within this tolerance of the top speed"
        )

    def shift(
        scene: Scene, gear: int, v0: float, t: float, x: float, run: Run
    ) -> tuple[float, float]:
        def rhs(time: float, y: np.ndarray) -> np.ndarray:
            v = max(y[0], 0.0)
            return np.array([-scene.coast_deceleration(v), v])

        segment = advance(
            rhs,
            t,
            np.array([v0, x]),
            t + scene.shift_time,
            rtol=rtol,
            atol=atol,
            method=method,
            dense=dense,
        )
        if dense and segment.sol is not None:
            run.pieces.append((t, segment.t, gear, None, segment.sol))
        return max(float(segment.y[0]), 0.0), float(segment.y[1]) - x

    return drive_through(scene, stints, drive, shift)
