"""The solver: the Methods, and the result."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.ode import forced
from mdcalc.methods import Method, NotApplicable, compare
from mdcalc.output.report import MethodQuantity, MethodsTable, Note
from mdcalc.problems.mechanism.case import TWO_PI, Case
from mdcalc.problems.mechanism.fluctuation import (
    Fluctuation,
    fluctuation_of_path,
    fluctuation_of_reference,
)
from mdcalc.problems.mechanism.kovylin import Path, Stall, kovylin
from mdcalc.problems.mechanism.reference import (
    EVALUATION_BUDGET,
    Reference,
    reference,
    stiffness_of,
)
from mdcalc.problems.mechanism.scene import Scene, scene_of

REFERENCE_RTOL = 1e-11

STIFF_REFERENCE_RTOL = 1e-10

LOOSE_RTOL = 1e-6

#: Above this product of |∂(dE/dφ)/∂E| and the angle span the reference uses Radau.
STIFFNESS_LIMIT = 1e3

#: An explicit reference that needs more than this is taken as stiff and rerun by Radau.
EXPLICIT_BUDGET = 100_000


@dataclass
class Result:
    case: Case
    scene: Scene
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None
    reference: Reference | None = None
    path: Path | None = None  # Kovylin at the user's step
    fluctuation: Fluctuation | None = None
    methods: MethodsTable | None = None
    stiffness: float = 0.0
    notes: list[Note] = field(default_factory=list)


def _values(final_speed: float, final_time: float, fl: Fluctuation | None) -> dict[str, float]:
    values = {"final_speed": final_speed, "final_time": final_time}
    if fl is not None:
        values["fluctuation"] = fl.coefficient
    return values


def solve(case: Case) -> Result:
    scene = scene_of(case)
    stiffness = stiffness_of(scene)
    stiff = stiffness > STIFFNESS_LIMIT
    method, rtol = ("Radau", STIFF_REFERENCE_RTOL) if stiff else ("DOP853", REFERENCE_RTOL)
    from mdcalc.core.ode import TooManySteps

    try:
        try:
            ref = reference(
                scene, rtol, method, EXPLICIT_BUDGET if not stiff else EVALUATION_BUDGET
            )
        except TooManySteps:
            if stiff:
                raise
            # stiffer than the start suggested: the implicit solver
            stiff, method, rtol = True, "Radau", STIFF_REFERENCE_RTOL
            ref = reference(scene, rtol, method)
    except Stall as stall:
        return Result(
            case,
            scene,
            "no-answer",
            f"the mechanism stalls: ω reaches zero at φ = {stall.angle:.6g} rad "
            f"({math.degrees(stall.angle):.4g}°, {(stall.angle - scene.start_angle) / TWO_PI:.4g} "
            f"revolutions from φ₀) after t = {stall.time:.6g} s; the torque cannot carry "
            "it on (the motion reverses, which this angle-stepping model does not follow)",
        )
    except ArithmeticError as exc:
        return Result(case, scene, "no-answer", f"the torque or inertia cannot be evaluated: {exc}")
    result = Result(case, scene, reference=ref, stiffness=stiffness)
    try:
        result.fluctuation = fluctuation_of_reference(scene, ref)
    except ArithmeticError as exc:
        return Result(case, scene, "no-answer", f"the torque or inertia cannot be evaluated: {exc}")
    paths: dict[int, Path] = {}

    def kovylin_row(n: int, quadratic: bool = False) -> Callable[[], dict[str, float]]:
        def run() -> dict[str, float]:
            try:
                path = kovylin(scene, n, quadratic)
            except Stall as stall:
                raise NotApplicable(
                    f"(5) cannot step past φ = {stall.angle:.6g} rad even at 2⁻³⁰ of a step"
                ) from None
            except ArithmeticError as exc:
                raise NotApplicable(f"torque or inertia not evaluable: {exc}") from None
            if not quadratic:
                paths[n] = path
            return _values(path.speeds[-1], path.times[-1], fluctuation_of_path(path))

        return run

    def ode_row(rtol_: float, method_: str) -> Callable[[], dict[str, float]]:
        def run() -> dict[str, float]:
            from mdcalc.core.ode import TooManySteps

            try:
                r = reference(scene, rtol_, method_)
            except TooManySteps as exc:
                raise NotApplicable(str(exc)) from None
            except Stall as stall:
                raise NotApplicable(
                    f"stalls at φ = {stall.angle:.6g} rad (the reference does not)"
                ) from None
            return _values(r.final_speed, r.final_time, fluctuation_of_reference(scene, r))

        return run

    def ladder(rtol_: float) -> dict[str, float]:  # --work-precision: any integrator
        return ode_row(rtol_, forced() or method)()

    n = scene.steps
    methods = [
        Method(f"Kovylin (5), n = {n}", kovylin_row(n), note="the user's step"),
        Method(f"Kovylin (5), n = {2 * n}", kovylin_row(2 * n)),
        Method(f"Kovylin (5), n = {4 * n}", kovylin_row(4 * n)),
        Method(
            f"(1) solved for ω_k, n = {n}",
            kovylin_row(n, quadratic=True),
            note="the same torque, without (3)",
        ),
        Method(
            f"{'Radau' if stiff else 'DOP853'} rtol {LOOSE_RTOL:g}",
            ode_row(LOOSE_RTOL, method),
            imports=ODE_IMPORTS,
            accuracy=2,
            ladder=ladder,
            rtol=LOOSE_RTOL,
        ),
        Method(
            f"{method} rtol {rtol:g}",
            ode_row(rtol, method),
            reference=True,
            note=f"{ref.evaluations} evaluations",
            imports=ODE_IMPORTS,
            ladder=ladder,
            rtol=rtol,
        ),
    ]
    quantities = [
        MethodQuantity("final_speed", "ω at the end", "rad/s"),
        MethodQuantity("final_time", "t at the end", "s"),
    ]
    if result.fluctuation is not None:
        quantities.append(MethodQuantity("fluctuation", "δ, last revolution", ""))
    result.methods = compare(
        "Methods: Kovylin's step against the energy ODE", "mechanism", quantities, methods
    )
    result.path = paths.get(n)
    if result.path is None and n not in paths:  # the row did not run (a study's sample)
        try:
            result.path = kovylin(scene, n)
        except ArithmeticError:  # a stall of (5), or a formula not evaluable: no path
            result.path = None
    if stiff:
        result.notes.append(
            Note(
                "info",
                f"stiff: |∂M/∂ω|/(I·ω) over the span is {stiffness:.3g}; the reference "
                "runs the implicit Radau solver",
            )
        )
    if result.path is not None and result.path.refined:
        result.notes.append(
            Note(
                "info",
                f"Kovylin at n = {n}: {result.path.refined} step(s) halved where (5) "
                "could not take them whole (ω near zero or a large increment)",
            )
        )
    if scene.speed_range is not None:
        speeds = ref.speeds_at([scene.start_angle + scene.span * k / 512 for k in range(513)])
        low, high = scene.speed_range
        if min(speeds) < low or max(speeds) > high:
            result.notes.append(
                Note(
                    "warning",
                    f"ω runs over {min(speeds):.4g}–{max(speeds):.4g} rad/s, beyond the "
                    f"table's {low:.4g}–{high:.4g} rad/s: M extrapolated linearly",
                )
            )
    fl = result.fluctuation
    if fl is not None and abs(fl.end - fl.start) > 1e-3 * fl.mean:
        result.notes.append(
            Note(
                "warning",
                f"not yet steady: ω changes by {(fl.end - fl.start) / fl.mean:+.3%} of its mean "
                "over the last revolution; δ describes a transient revolution (add revolutions)",
            )
        )
    return result
