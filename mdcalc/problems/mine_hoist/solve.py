"""The solver: the Methods, the height sweep, and the result."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import partial
from typing import Literal

from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.ode import forced
from mdcalc.methods import Method, compare
from mdcalc.output.report import MethodQuantity, MethodsTable
from mdcalc.problems.mine_hoist.case import Case
from mdcalc.problems.mine_hoist.modal import (
    Dynamics,
    dynamics,
    first_swing_factors,
    frequency_ratio,
    simplified_from_scratch,
)
from mdcalc.problems.mine_hoist.ode_rows import STIFF_RATIO, ode_first_swing
from mdcalc.problems.mine_hoist.scene import NoNode, Scene, scene_at


@dataclass
class SweepRow:
    height: float
    scene: Scene
    dynamics: Dynamics


@dataclass
class Result:
    case: Case
    scene: Scene | None = None
    dynamics: Dynamics | None = None
    methods: MethodsTable | None = None
    sweep: list[SweepRow] = field(default_factory=list)
    ode_reference: str | None = None  # the Methods row that stands as the ODE reference
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


FACTORS = [
    MethodQuantity("mu12", "μ₁₂ max", ""),
    MethodQuantity("mu23", "μ₂₃ max", ""),
]

ODE_ROWS = (
    ("DOP853", "explicit", 1e-3),
    ("DOP853", "explicit", 1e-6),
    ("DOP853", "explicit", 1e-9),
    ("Radau", "implicit", 1e-3),
    ("Radau", "implicit", 1e-6),
    ("Radau", "implicit", 1e-9),
)


def _mark_ode_reference(table: MethodsTable, dyn: Dynamics) -> str | None:
    """Mark the ODE reference among the rows that produced a value: the tightest
    Radau row on a stiff chain, else the tightest DOP853 row."""
    solver = "Radau" if frequency_ratio(dyn) >= STIFF_RATIO else "DOP853"
    ran = [row for row in table.rows if row.method.startswith(f"ODE {solver}") and row.values]
    if not ran:
        return None
    ran[-1].note = "ODE reference for this scene"
    return ran[-1].method


def solve(case: Case) -> Result:
    result = Result(case)
    loads = case.loads
    if loads.drive_torque < loads.load_torque:
        result.status = "no-answer"
        result.message = (
            f"the drive torque M₁ = {loads.drive_torque:.6g} N·m is below the load torque "
            f"W = {loads.load_torque:.6g} N·m: the drive cannot lift the cage"
        )
        return result
    try:
        scene = scene_at(case)
    except NoNode as reason:
        result.status, result.message = "no-answer", str(reason)
        return result
    dyn = dynamics(scene, case.analysis.horizon)
    result.scene, result.dynamics = scene, dyn
    methods = [
        Method("modal solution, exact", lambda: first_swing_factors(scene), reference=True),
        Method(
            "simplified (19)-(20)",
            lambda: simplified_from_scratch(scene),
            note="seed 002",
        ),
    ]
    if case.analysis.ode:

        def ladder(rtol: float) -> dict[str, float]:  # the integrator --work-precision sets
            return ode_first_swing(scene, dyn, forced() or "DOP853", rtol, ladder=True)

        for method, kind, rtol in ODE_ROWS:
            methods.append(
                Method(
                    f"ODE {method} ({kind}), rtol {rtol:.0e}".replace("e-0", "e-"),
                    partial(ode_first_swing, scene, dyn, method, rtol),
                    imports=ODE_IMPORTS,
                    ladder=ladder,
                )
            )
    result.methods = compare(
        "Methods: largest μ in the first swing, t ≤ 2π/β₁",
        "first_swing",
        FACTORS,
        methods,
    )
    result.ode_reference = _mark_ode_reference(result.methods, dyn)
    if case.sweep is not None:
        for height in case.sweep.heights:
            try:
                at = scene_at(case, height)
            except NoNode as reason:
                result.status = "no-answer"
                result.message = f"at H = {height:g} m {reason}"
                return result
            result.sweep.append(SweepRow(height, at, dynamics(at)))
    return result
