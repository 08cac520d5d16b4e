"""The solver: the Methods for the peak displacement, and the result."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from mdcalc.methods import Method, compare
from mdcalc.output.report import MethodQuantity, MethodsTable
from mdcalc.problems.mount.case import Case
from mdcalc.problems.mount.scene import Scene, peak_of_two_harmonics, scene_of


@dataclass
class Result:
    case: Case
    scene: Scene
    methods: MethodsTable | None
    peak: tuple[float, float] = (0.0, 0.0)
    force_peak: tuple[float, float] = (0.0, 0.0)
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


QUANTITIES = [MethodQuantity("peak_displacement", "peak |x|", "m")]


def solve(case: Case) -> Result:
    scene = scene_of(case)
    ratio = scene.omega / scene.beta
    if scene.zeta == 0.0 and ratio in (1.0, 0.5):
        order = 1 if ratio == 1.0 else 2
        speed = scene.beta if order == 1 else scene.beta / 2.0
        return Result(
            case,
            scene,
            None,
            status="no-answer",
            message=(
                f"undamped resonance of the {'first' if order == 1 else 'second'} harmonic: "
                f"the crank speed {scene.omega:.6g} rad/s is exactly "
                f"{'β' if order == 1 else 'β/2'} = {speed:.6g} rad/s, the amplitude is "
                "unbounded; give the mounts a damping_ratio or move the speed"
            ),
        )
    first, second = scene.response(1), scene.response(2)
    mr_over_m = scene.piston_mass * scene.radius / scene.engine_mass
    methods = [
        Method(
            "lecture m·r/M",
            lambda: {"peak_displacement": mr_over_m},
            note="high-speed limit, first harmonic",
        ),
        Method(
            "lecture m·r/M + m·r·λ/(4M)",
            lambda: {"peak_displacement": mr_over_m * (1.0 + scene.rod_ratio / 4.0)},
            note="high-speed limit, both harmonics",
        ),
        Method("first harmonic |A₁|", lambda: {"peak_displacement": abs(first)}),
        Method(
            "|A₁| + |A₂|",
            lambda: {"peak_displacement": abs(first) + abs(second)},
            note="bound: both peaks in phase",
        ),
        Method(
            "exact peak of the two-harmonic sum",
            lambda: {"peak_displacement": peak_of_two_harmonics(first, second)[0]},
            reference=True,
        ),
    ]
    table = compare("Methods: peak displacement over a revolution", "peak", QUANTITIES, methods)
    return Result(
        case,
        scene,
        table,
        peak=peak_of_two_harmonics(first, second),
        force_peak=peak_of_two_harmonics(scene.transmitted(1), scene.transmitted(2)),
    )
