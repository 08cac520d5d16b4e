"""The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study``: the drive
formulas over a grid at once, and the rope's closed forms."""

from __future__ import annotations

import math
from collections.abc import Collection
from typing import Any

from mdcalc.input.model import kernel_answer, value_at, with_values
from mdcalc.problems.hoist.case import Case
from mdcalc.problems.hoist.drive import can_start, reduced_inertia, steady, uniform_start
from mdcalc.problems.hoist.rope import ground_peak, hanging_closed_form
from mdcalc.problems.hoist.solve import rope_scene

#: Results whose single-scene reference is an ODE run (DOP853, rtol 10⁻¹⁰ a step)
#: that the kernel's exact closed form meets within this relative tolerance: the
#: run's own error, measured up to 2.5·10⁻⁸ near the shipped cases (the closed form
#: agrees with a run at rtol 10⁻¹² to 2·10⁻¹² there).
ODE_REFERENCED = {"ground_peak_force": 1e-7, "ground_dynamic_factor": 1e-7}

#: Keys ``mdcalc sweep`` may vary in the vectorized form (N: any list index), and what
#: each sets.
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
    "rope.stiffness": "c",
    "rope.elastic_modulus": "E",
    "rope.area": "A",
    "rope.length": "L",
    "rope.branches": "branches",
    "rope.drive_mass": "m1",
    "rope.slack_length": "slack",
}


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result of the scene over a grid at once (numpy), by the
    formulas of :func:`solve` run on a copy of the case that holds the grid's arrays.

    The rope's peaks are the closed forms of the two-mass model: the hanging load's
    is the reference; the grounded load's reference is the ODE run (rtol 10⁻¹⁰),
    which the exact closed form meets within that tolerance where it holds. A point
    where it does not (the load lifts off after the start, the rope goes slack after
    the peak), or where the motor cannot start the load, is marked ``DECLINED``, to
    be solved alone. None for a key this form does not know, one that switches an
    alternative (t_p or M_start, speed_rpm or ratio, stiffness or E·A/L), or a rope
    key where the case has no rope.
    """
    import numpy as np

    for key in grid:
        parts = key.split(".")
        pattern = ".".join("N" if p.isdigit() else p for p in parts)
        if pattern not in SWEEP_KEYS or value_at(case, key) is None:
            return None
    case = with_values(case, {key: np.asarray(column, dtype=float) for key, column in grid.items()})
    size = max([np.size(v) for v in grid.values()] + [1])
    st = steady(case)
    declined = ~np.broadcast_to(np.asarray(can_start(case, st)), (size,))
    inertia = reduced_inertia(case, st.motor_speed)
    with np.errstate(all="ignore"):
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
    if case.rope is not None:
        rope = rope_scene(case, st, inertia, motion)
        with np.errstate(all="ignore"):
            beta = rope.beta
            hanging = hanging_closed_form(rope, beta)
            peak, limits = ground_peak(rope, heavy_drive=False)
        for outside, _ in limits:
            declined = declined | np.broadcast_to(outside, (size,))
        values |= {
            "rope_stiffness": rope.c,
            "drive_mass": rope.m1,
            "rope_frequency": beta,
            "half_period": math.pi / beta,
            "hanging_peak_force": hanging["peak_force"],
            "hanging_dynamic_factor": hanging["dynamic_factor"],
            "ground_peak_force": peak,
            "ground_dynamic_factor": peak / rope.weight,
        }
    return kernel_answer(values, declined, size)
