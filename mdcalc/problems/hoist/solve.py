"""The solver: the Methods, and the result."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from mdcalc.domain.tables import HOIST_ACCELERATION, Range
from mdcalc.output.report import MethodsTable
from mdcalc.problems.hoist.case import Case
from mdcalc.problems.hoist.drive import (
    Inertia,
    StartMotion,
    Steady,
    inertia_methods,
    reduced_inertia,
    start_motion,
    steady,
)
from mdcalc.problems.hoist.rope import RopeScene, rope_methods


@dataclass
class Result:
    case: Case
    steady: Steady
    inertia: Inertia
    start: StartMotion | None
    allowable: Range | None
    inertia_table: MethodsTable | None
    rope: RopeScene | None
    rope_hanging: MethodsTable | None
    rope_ground: MethodsTable | None
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


def solve(case: Case) -> Result:
    st = steady(case)
    inertia = reduced_inertia(case, st.motor_speed)
    motion = start_motion(case, st, inertia.total)
    allowable = None
    if case.start.allowable_acceleration is None:
        allowable = HOIST_ACCELERATION[case.start.machine]
    result = Result(case, st, inertia, motion, allowable, None, None, None, None)
    if not inertia.estimated:
        result.inertia_table = inertia_methods(case, st, inertia)
    if motion is None:
        result.status = "no-answer"
        result.message = (
            f"the motor cannot start the load: starting torque {case.start.starting_torque:g} N·m "
            f"does not exceed the static torque M_c = {st.static_torque:.4g} N·m"
        )
        return result
    if case.rope is not None:
        rope = rope_scene(case, st, inertia, motion)
        result.rope = rope
        result.rope_hanging = rope_methods(rope, hanging=True)
        result.rope_ground = rope_methods(rope, hanging=False)
    return result


def _reference(table: MethodsTable, key: str) -> float:
    value = next(row for row in table.rows if row.reference).values[key]
    assert value is not None
    return value


def rope_scene(case: Case, st: Steady, inertia: Inertia, motion: StartMotion) -> RopeScene:
    """The two-mass model of the rope at start (floats, or arrays over a block)."""
    assert case.rope is not None
    m1 = case.rope.drive_mass
    if m1 is None:
        m1 = inertia.drive * (st.motor_speed / case.load.lifting_speed) ** 2
    return RopeScene(
        c=case.rope.c,
        m1=m1,
        m2=case.load.mass,
        weight=st.weight,
        acceleration=motion.load_acceleration,
        start_time=motion.time,
        slack=case.rope.slack_length,
    )
