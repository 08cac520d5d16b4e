"""The vectorized kernel of ``mdcalc sweep`` (rope-less scenes): the drive
formulas over a grid at once."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from mdcalc.input.model import with_values
from mdcalc.problems.hoist.case import Case
from mdcalc.problems.hoist.drive import can_start, reduced_inertia, steady, uniform_start

#: Keys ``mdcalc sweep`` may vary in the vectorized form (N: any list index), and what
#: each sets. The rope's keys are not here: its peaks need the ODE runs.
SWEEP_KEYS = {
    "gravity": "g",
    "load.mass": "m",
    "load.lifting_speed": "V",
    "drive.motor_speed_rpm": "ω1",
    "drive.motor_inertia": "J1",
    "drive.stage_efficiencies.N": "η_i",
    "drive.pulley_efficiency": "η of the reeving",
    "drive.brake_safety_factor": "K_t",
    "drive.inertia_estimate_factor": "factor of (7.31)",
    "drive.shafts.N.inertia": "J_k",
    "drive.shafts.N.speed_rpm": "ω_k",
    "drive.shafts.N.ratio": "ω1/ω_k",
    "start.time": "t_p",
    "start.starting_torque": "M_start",
}


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result of a rope-less scene over a grid at once (numpy), by the
    formulas of :func:`solve` run on a copy of the case that holds the grid's arrays.

    None with a rope (its peaks need the ODE runs), for a key this form does not know
    or one that switches an alternative (t_p or M_start, speed_rpm or ratio), and when
    the motor cannot start the load at some point (that point has no answer, exit 3).
    """
    import numpy as np

    if case.rope is not None:
        return None
    for key in grid:
        parts = key.split(".")
        pattern = ".".join("N" if p.isdigit() else p for p in parts)
        if pattern not in SWEEP_KEYS or _value_at(case, parts) is None:
            return None
    case = with_values(case, {key: np.asarray(column, dtype=float) for key, column in grid.items()})
    st = steady(case)
    if not np.all(can_start(case, st)):
        return None
    inertia = reduced_inertia(case, st.motor_speed)
    motion = uniform_start(case, st, inertia.total)
    values: dict[str, Any] = {
        "weight": st.weight,
        "total_efficiency": st.efficiency,
        "useful_power": st.useful_power / 1e3,
        "motor_power": st.motor_power / 1e3,
        "motor_speed": st.motor_speed,
        "static_torque": st.static_torque,
        "brake_torque": st.brake_torque,
        "lowering_torque": st.lowering_torque,
        "brake_margin": st.brake_margin,
        "motor_inertia": inertia.motor,
        "reduced_inertia": inertia.total,
        "start_time": motion.time,
        "angular_acceleration": motion.angular_acceleration,
        "inertia_torque": motion.inertia_torque,
        "starting_torque": motion.starting_torque,
        "load_acceleration": motion.load_acceleration,
    }
    if not inertia.estimated:  # the report shows these with the shafts only
        values["shaft_inertia"] = inertia.shafts
        values["load_inertia"] = inertia.load
        values["inertia_ratio"] = inertia.ratio
    return values


def _value_at(node: Any, parts: list[str]) -> Any:
    for part in parts:
        node = node[int(part)] if isinstance(node, list) else getattr(node, part)
    return node
