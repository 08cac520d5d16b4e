"""The solver: the Methods of each load, and the result."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

from mdcalc.core import sdof
from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.ode import pick_solver
from mdcalc.methods import Method, compare
from mdcalc.output.report import MethodQuantity, MethodsTable
from mdcalc.problems.coupling.case import Case
from mdcalc.problems.coupling.scene import Scene, scene_of
from mdcalc.problems.coupling.transients import Transient, duhamel_peak, ode_peak, transients


@dataclass
class Result:
    case: Case
    scene: Scene
    step_methods: MethodsTable | None = None
    harmonic_methods: MethodsTable | None = None
    transient_methods: list[tuple[Transient, MethodsTable, tuple[float, float]]] = field(
        default_factory=list
    )
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


FACTOR = [MethodQuantity("dynamic_factor", "dynamic factor", "")]

ODE_RTOLS = (1e-3, 1e-6, 1e-10)
#: Above this damping ratio the decay rates differ by 4ζ² = 400 and more: the ODE
#: rows run the implicit Radau (explicit steps would take minutes at ζ = 10⁴).
STIFF_ZETA = 10.0


def _ode_methods(run: Callable[[float, bool], float], zeta: float) -> list[Method]:
    stiff = zeta > STIFF_ZETA

    def ladder(rtol: float) -> dict[str, float]:
        return {"dynamic_factor": run(rtol, stiff)}

    def method(rtol: float) -> Method:
        name = pick_solver(rtol, stiff)
        return Method(
            f"ODE {name}, rtol {rtol:.0e}".replace("e-0", "e-"),
            lambda: ladder(rtol),
            imports=ODE_IMPORTS,
            note=f"stiff: ζ = {zeta:.3g}" if stiff else "",
            ladder=ladder,
        )

    return [method(rtol) for rtol in ODE_RTOLS]


def step_factor_lecture(scene: Scene) -> float:
    """Example 8.1's reading of (8.16): peak at t = τ/2 with β₁ ≈ β and (p/2)²
    neglected: 1 + e^(-p·τ/4)."""
    return 1.0 + math.exp(-scene.p * scene.period / 4.0)


def solve(case: Case) -> Result:
    scene = scene_of(case)
    result = Result(case, scene)
    if case.harmonic is not None and scene.p == 0.0:
        ratio = case.harmonic.omega / scene.beta
        if ratio == 1.0:
            result.status = "no-answer"
            result.message = (
                f"undamped resonance: ω = β = {scene.beta:.6g} rad/s and the coupling has no "
                "damping, so the steady twist (8.27) is unbounded; give absorption, "
                "log_decrement or damping"
            )
            return result
    if case.step is not None:
        zeta = scene.zeta
        peak_time = sdof.step_peak_time(scene.beta, zeta)
        if peak_time is not None:
            horizon = 1.5 * peak_time
        else:  # critically or over-damped: x creeps up to 1; run until within e⁻³⁰ of it
            slow = scene.beta / (zeta + math.sqrt(max(zeta * zeta - 1.0, 0.0)))
            horizon = 30.0 / slow
        step = Transient("step", "step", [(0.0, 1.0)], horizon)
        result.step_methods = compare(
            "Methods: dynamic factor of a suddenly applied torque",
            "step",
            FACTOR,
            [
                Method(
                    "lecture: t = τ/2, β₁ ≈ β",
                    lambda: {"dynamic_factor": step_factor_lecture(scene)},
                    note="example 8.1",
                ),
                Method(
                    "exact 1 + exp(-πζ/√(1-ζ²))",
                    lambda: {"dynamic_factor": sdof.step_peak(zeta)},
                    reference=True,
                ),
                *_ode_methods(lambda rtol, stiff: ode_peak(scene, step, rtol, stiff), zeta),
            ],
        )
    if case.harmonic is not None and scene.p > 0.0:
        gamma = scene.p / scene.beta
        if gamma * gamma < 2.0:
            result.harmonic_methods = compare(
                "Methods: resonance peak of the twist, in units of M/β²",
                "resonance",
                [MethodQuantity("resonance_peak", "peak·β²/M", "")],
                [
                    Method(
                        "(8.32) as printed, √(1 - γ²/2)",
                        lambda: {"resonance_peak": 1.0 / (gamma * math.sqrt(1.0 - gamma**2 / 2.0))},
                    ),
                    Method(
                        "corrected (8.32), √(1 - γ²/4)",
                        lambda: {"resonance_peak": 1.0 / (gamma * math.sqrt(1.0 - gamma**2 / 4.0))},
                        reference=True,
                    ),
                    Method(
                        "max of (8.28) on a λ grid of 10⁴ points",
                        lambda: {"resonance_peak": _grid_peak(gamma)},
                    ),
                ],
            )
    for transient in transients(case, scene):
        kept: dict[str, tuple[float, float]] = {}
        table = compare(
            f"Methods: {transient.title}",
            transient.key,
            FACTOR,
            _transient_methods(scene, transient, kept),
        )
        peak = kept.get("peak") or duhamel_peak(scene, transient)  # the reference's run
        result.transient_methods.append((transient, table, peak))
    return result


def _transient_methods(
    scene: Scene, transient: Transient, kept: dict[str, tuple[float, float]]
) -> list[Method]:
    def duhamel() -> dict[str, float]:
        kept["peak"] = duhamel_peak(scene, transient)
        return {"dynamic_factor": kept["peak"][0]}

    methods: list[Method] = []
    exact = transient.closed_form
    if exact is not None:
        methods.append(
            Method(
                transient.closed_form_name,
                lambda: {"dynamic_factor": exact},
                note="undamped",
                accuracy=3,  # exact: it may stand in for a Duhamel run over the budget
            )
        )
    methods.append(
        Method(
            "Duhamel, exact for piecewise-linear loads",
            duhamel,
            reference=True,
        )
    )
    return methods + _ode_methods(
        lambda rtol, stiff: ode_peak(scene, transient, rtol, stiff), scene.zeta
    )


def _grid_peak(gamma: float) -> float:
    return max(
        1.0 / math.hypot(1.0 - lam * lam, gamma * lam)
        for lam in (3.0 * k / 10000 for k in range(10001))
    )
