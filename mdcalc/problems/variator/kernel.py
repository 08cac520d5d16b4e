"""The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study``: every numeric
result of every section over a block of scenes, by the functions the single scene
runs (on floats there, on arrays here): the absorber's
:class:`~.absorber.AbsorberScene` methods and :func:`~.absorber.absorber_minima`,
the closed forms of the motor, clutch, mechanism and pendulum, and the drive's
periodic states, one per row, by :func:`~mdcalc.core.periodic.exact_block`."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from mdcalc.input.model import in_tiles, kernel_answer, value_at, with_values
from mdcalc.problems.variator.case import Case

#: Keys ``mdcalc sweep`` and ``mdcalc study`` may vary in the vectorized form.
SWEEP_KEYS = {
    "absorber.inertia": "J₁",
    "absorber.stiffness": "c",
    "absorber.absorber_inertia": "J₂",
    "absorber.absorber_stiffness": "c_g",
    "absorber.tuning_frequency": "ω_g",
    "absorber.absorber_damping": "b_g",
    "absorber.torque_amplitude": "M₀",
    "absorber.frequency": "ω",
    "motor.mains_frequency": "f_c",
    "motor.pole_pairs": "P",
    "motor.synchronous_speed_rpm": "n",
    "motor.nominal_speed_rpm": "n_H",
    "motor.nominal_torque": "M_H",
    "motor.nominal_power": "P_H",
    "motor.overload_ratio": "λ_m",
    "clutch.loading_coefficient": "c₀",
    "clutch.loading_coefficient_kgfm": "c₀ [kgf·m]",
    "clutch.loading_exponent": "n",
    "clutch.load_min": "M_min",
    "clutch.load_max": "M_max",
    "clutch.unloading_stiffness": "c",
    "clutch.unloading_stiffness_kgfm": "c [kgf·m]",
    "clutch.loop_area_ratio": "ψ",
    "mechanism.mechanisms": "z",
    "mechanism.input_speed_rpm": "n₁",
    "mechanism.mean_ratio": "i_c",
    "mechanism.output_speed_rpm": "n₂",
    "drive.driven_inertia": "J₂",
    "drive.load_torque": "M_c",
    "drive.clutch_stiffness": "c",
    "drive.clutch_stiffness_kgfm": "c [kgf·m]",
    "drive.clutch_damping": "b",
    "drive.clutch_loop_area_ratio": "ψ",
    "antiresonance.machine_inertia": "J₃",
    "antiresonance.ratio": "i",
    "antiresonance.coupling_stiffness": "c₂",
    "antiresonance.coupling_damping": "b₂",
    "pendulum.pivot_radius": "R",
    "pendulum.order": "n",
    "pendulum.speed": "ω",
    "pendulum.speed_rpm": "n",
    "pendulum.inertia_torque": "M_ин",
    "pendulum.max_swing": "θ_max",
    "pendulum.bob_density": "ρ",
    "pendulum.bifilar_pin_diameter": "d",
}


#: The keys the drive's periodic states depend on (ψ of [clutch] gives its damping).
DRIVE_INPUTS = ("drive.", "mechanism.", "antiresonance.", "clutch.loop_area_ratio")
#: Samples a call solves at once where each has its own drive: the periodic states'
#: arrays stay in the cache (4096 rows of vk_variator: 1.4x the rate of 65 536).
TILE_ROWS = 4096


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result of the case's sections over a block (numpy); with
    ``wanted``, only the sections those keys come from. A sample without an answer
    (an undamped resonance of the absorber or of the drive, a drive outside the
    closed form's range) is marked ``DECLINED``, to be solved alone. None for a key
    the case does not hold (one that would switch an alternative: c_g or its tuning,
    M_H or P_H), or an absorber some of whose samples are damped and some not."""
    import numpy as np

    if any(key not in SWEEP_KEYS or value_at(case, key) is None for key in grid):
        return None
    if case.drive is not None and any(key.startswith(DRIVE_INPUTS) for key in grid):
        tiles = in_tiles(sweep, case, grid, wanted, TILE_ROWS)
        if tiles is not None:
            return tiles
    arrays = with_values(case, {key: np.asarray(v, dtype=float) for key, v in grid.items()})
    size = max([np.size(v) for v in grid.values()] + [1])

    def asked(prefix: str) -> bool:
        return wanted is None or any(key.startswith(prefix) for key in wanted)

    values: dict[str, Any] = {}
    declined: Any = np.zeros(size, dtype=bool)
    with np.errstate(all="ignore"):
        if arrays.absorber is not None:  # (its resonances decide the status)
            from mdcalc.problems.variator.absorber import absorber_values

            found = absorber_values(arrays.absorber, size)
            if found is None:
                return None
            if asked("absorber_"):
                values |= found[0]
            declined = declined | found[1]
        if arrays.motor is not None and asked("motor_"):
            from mdcalc.problems.variator.motor import motor_values

            values |= motor_values(arrays.motor)
        if arrays.clutch is not None and asked("clutch_"):
            from mdcalc.problems.variator.clutch import clutch_values

            values |= clutch_values(arrays.clutch)
        if arrays.mechanism is not None and asked("mechanism_"):
            from mdcalc.problems.variator.transfer import mechanism_values

            values |= mechanism_values(arrays.mechanism)
        if arrays.drive is not None:  # (its periodic states decide the status)
            from mdcalc.problems.variator.solve import drive_block

            # a study that draws nothing of the drive solves its one drive once
            shared = not any(key.startswith(DRIVE_INPUTS) for key in grid)
            found = drive_block(case, 1, asked) if shared else drive_block(arrays, size, asked)
            values |= found[0]
            declined = declined | found[1]
        if arrays.pendulum is not None and asked("pendulum_"):
            from mdcalc.problems.variator.pendulum import pendulum_values

            values |= pendulum_values(arrays.pendulum)
    return kernel_answer(values, declined, size)
