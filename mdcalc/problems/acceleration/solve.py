"""The solver: the Methods, and the result."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import partial
from typing import Any, Literal

from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.units import rpm_to_rad_s
from mdcalc.methods import Method, NotApplicable, compare
from mdcalc.output.report import MethodQuantity, MethodsTable
from mdcalc.problems.acceleration.case import RAD_S_TO_RPM, Case, Lecture
from mdcalc.problems.acceleration.plan import ASYMPTOTE_MARGIN, Plan, plan
from mdcalc.problems.acceleration.runs import Run, lecture_run, ode_run, piecewise_run
from mdcalc.problems.acceleration.scene import Scene, scene_of


@dataclass
class Result:
    case: Case
    scene: Scene
    plan: Plan
    top: Plan  # the plan with no target: the top speed
    run: Run | None = None  # the reference run (dense)
    methods: MethodsTable | None = None
    lecture: dict[str, Any] | None = None
    lecture_coefficients: tuple[float, float] = (0.0, 0.0)
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


QUANTITIES = [
    MethodQuantity("time_to_target", "time", "s"),
    MethodQuantity("distance_to_target", "distance", "m"),
]

REFERENCE_RTOL = 1e-11


def lecture_coefficients(case: Case, scene: Scene) -> tuple[float, float]:
    """(A/m, ω_D) for the lecture method: the lecture's values or the physical ones."""
    lecture = case.lecture or Lecture()
    peak_speed, peak_torque = scene.curve.peak(scene.limit)
    if lecture.traction_coefficient is not None:
        a_per_ratio = lecture.traction_coefficient
    else:  # (7.35): A = M_max·U_K·η/r
        a_per_ratio = scene.traction_coefficient(peak_torque)
    if lecture.shift_angular_speed is not None:
        omega_d = lecture.shift_angular_speed
    elif case.engine.max_torque_speed_rpm is not None:  # ω_D: the speed of maximum torque
        omega_d = rpm_to_rad_s(case.engine.max_torque_speed_rpm)
    else:
        omega_d = peak_speed
    return a_per_ratio, omega_d


def solve(case: Case) -> Result:
    scene = scene_of(case)
    top = plan(scene, math.inf)
    the_plan = plan(scene, scene.target)
    result = Result(case, scene, the_plan, top)
    if not scene.target > 0.0:  # a positive km/h that underflows to 0 m/s
        result.status = "no-answer"
        result.message = (
            f"the target speed ({case.target.value:.3g} m/s) is zero in double precision; "
            "there is nothing to accelerate to"
        )
        return result
    if not the_plan.reached:
        result.status = "no-answer"
        result.message = _no_answer(scene, the_plan)
        return result
    coefficients = lecture_coefficients(case, scene)
    result.lecture_coefficients = coefficients
    stints = the_plan.stints
    reference: dict[str, Run] = {}

    def reference_run() -> dict[str, float]:
        reference["run"] = ode_run(scene, stints, REFERENCE_RTOL, dense=True)
        return reference["run"].values()

    def ladder(rtol: float) -> dict[str, float]:  # (and --work-precision's rungs)
        return ode_run(scene, stints, rtol).values()

    def lecture_values() -> dict[str, float]:
        run = lecture_run(scene, *coefficients)
        return {"time_to_target": run["time"], "distance_to_target": run["distance"]}

    lecture_note = "ψ as m/s², A/m = {:.3g} m/s², ω_D = {:.4g} rad/s".format(*coefficients)
    methods = [
        Method("lecture (7.42)", lecture_values, note=lecture_note),
        Method(
            "piecewise-constant acceleration",
            lambda: piecewise_run(scene, stints).values(),
            note="physical a at each phase's mid-speed",
        ),
        Method(
            "ODE RK45, rtol 1e-3",
            partial(ladder, 1e-3),
            imports=ODE_IMPORTS,
            accuracy=1,
            ladder=ladder,
            rtol=1e-3,
        ),
        Method(
            "ODE RK45, rtol 1e-6",
            partial(ladder, 1e-6),
            imports=ODE_IMPORTS,
            accuracy=2,
            ladder=ladder,
            rtol=1e-6,
        ),
        Method(
            "ODE DOP853, rtol 1e-11",
            reference_run,
            reference=True,
            imports=ODE_IMPORTS,
            ladder=ladder,
            rtol=REFERENCE_RTOL,
            note="with dense output for the tables",
        ),
    ]
    result.methods = compare(
        "Methods: time and distance to the target speed", "target", QUANTITIES, methods
    )
    if "run" not in reference:  # the reference ran over its budget: a looser ODE row
        stand_in = next(row.method for row in result.methods.rows if row.reference)
        rtol = {m.name: m.rtol for m in methods}[stand_in]  # stands in (a table's run)
        reference["run"] = ode_run(scene, stints, rtol or REFERENCE_RTOL, dense=True)
    result.run = reference["run"]
    try:
        result.lecture = lecture_run(scene, *coefficients)
    except NotApplicable:
        result.lecture = None
    return result


def _no_answer(scene: Scene, the_plan: Plan) -> str:
    if not the_plan.stints and the_plan.limit.speed == 0.0:
        return _cannot_move(scene)
    limit, gear = the_plan.limit, the_plan.limit_gear
    if scene.target < limit.speed:
        return (
            f"target speed {scene.target * 3.6:.7g} km/h lies within {ASYMPTOTE_MARGIN:g} of "
            f"the top speed {limit.speed * 3.6:.7g} km/h (gear {gear + 1}), which the car only "
            "approaches: traction equals resistance there and the time to it is unbounded"
        )
    engine_rpm = scene.engine_speed_at(gear, limit.speed) * RAD_S_TO_RPM
    where = (
        f"gear {gear + 1} at the rev limit, {engine_rpm:.0f} rpm"
        if limit.reason == "rev limit"
        else f"gear {gear + 1} at {engine_rpm:.0f} rpm, where traction equals resistance"
    )
    return (
        f"target speed {scene.target * 3.6:.4g} km/h is not reachable: top speed is "
        f"{limit.speed * 3.6:.4g} km/h ({where})"
    )


def _cannot_move(scene: Scene) -> str:
    resistance = scene.resistance(0.0)
    engine = scene.engine_force(0, 0.0, True)
    text = (
        f"the car cannot move off: road resistance ψ·m·g = {resistance:.5g} N is not less than "
        f"the first-gear traction"
    )
    if scene.phi is not None:
        grip = scene.adhesion_force(0.0)
        if grip < engine:
            return (
                f"{text} the tyres can pass, φ·N = {grip:.5g} N (the engine gives {engine:.5g} N)"
            )
    launch_rpm = scene.launch * RAD_S_TO_RPM
    return f"{text}, {engine:.5g} N with the engine at the launch speed {launch_rpm:.0f} rpm"
