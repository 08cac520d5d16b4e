"""The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study``: every numeric
result of the report over a block of scenes at once, by the functions the single
scene runs on a block of one (:func:`~.modal.block_dynamics`, :func:`~.scene.reduce_rope`)."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from mdcalc.core.chain import supremum
from mdcalc.input.model import in_tiles, kernel_answer, with_values
from mdcalc.problems.mine_hoist.case import Case
from mdcalc.problems.mine_hoist.modal import block_dynamics
from mdcalc.problems.mine_hoist.scene import reduce_rope, seed_formula_1, stiffnesses_at

#: Keys ``mdcalc sweep`` and ``mdcalc study`` may vary in the vectorized form.
SWEEP_KEYS = {
    "hoist.drum_inertia": "J₁",
    "hoist.sheave_inertia": "J₂",
    "hoist.cage_inertia": "J₃",
    "hoist.chord_stiffness": "c₁₂",
    "hoist.rope_stiffness": "c₂₃",
    "loads.drive_torque": "M₁",
    "loads.load_torque": "W",
    "rope.mass_per_metre": "ρ",
    "rope.drum_radius": "R",
    "rope.chord_length": "L₁",
    "rope.length": "H",
    "rope.axial_stiffness": "EA",
    "rope.sheave_radius": "R_ns",
    "analysis.horizon": "horizon",
}

#: The results that need the maxima over the whole horizon (many samples per scene).
HORIZON_KEYS = {"mu12_horizon", "mu23_horizon"}
#: Rows a call computes at most (a larger block runs in tiles): the maxima's arrays
#: stay in the cache.
TILE_ROWS = 8192


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result of the report over a block of scenes (numpy), or those of
    ``wanted`` and what they need (the maxima over the horizon only when asked).

    A scene without an answer (the drive cannot lift the cage, the lowest mode's node
    off the vertical rope, at the case's height or one of its sweep's) is marked in
    the answer's ``DECLINED`` mask, to be solved alone. None for a key this form does
    not know, or a [rope] key where the case has no [rope].
    """
    import numpy as np

    if any(key not in SWEEP_KEYS for key in grid):
        return None
    if case.rope is None and any(key.startswith("rope.") for key in grid):
        return None
    tiles = in_tiles(sweep, case, grid, wanted, TILE_ROWS)
    if tiles is not None:
        return tiles
    arrays = with_values(case, {key: np.asarray(v, dtype=float) for key, v in grid.items()})
    size = max([np.size(v) for v in grid.values()] + [1])

    def whole(value: Any) -> Any:
        return np.broadcast_to(np.asarray(value, dtype=float), (size,))

    hoist, loads, rope = arrays.hoist, arrays.loads, arrays.rope
    values: dict[str, Any] = {}
    declined = whole(loads.drive_torque) < whole(loads.load_torque)
    with np.errstate(all="ignore"):
        if rope is None:
            c12, c23 = (whole(v) for v in stiffnesses_at(arrays, 1.0))
            inertias = [whole(v) for v in (hoist.drum_inertia, hoist.sheave_inertia)]
            inertias.append(whole(hoist.cage_inertia))
        else:
            c12, c23 = (whole(v) for v in stiffnesses_at(arrays, rope.length))
            red = reduce_rope(hoist, rope, whole(rope.length), c12, c23)
            declined = declined | ~red.node_on_rope
            for height in case.sweep.heights if case.sweep is not None else []:
                at = stiffnesses_at(arrays, height)
                declined = declined | ~reduce_rope(hoist, rope, height, *at).node_on_rope
            inertias = list(red.reduced)
            values |= {
                "rope_chord_mass": red.chord_mass,
                "rope_vertical_mass": red.vertical_mass,
                "bare_beta1": red.bare_beta1,
                "mode_a2": red.a2,
                "mode_a3": red.a3,
                "node_from_sheave": red.upper,
                "node_to_cage": red.lower,
                "drum_inertia_reduced": red.reduced[0],
                "sheave_inertia_reduced": red.reduced[1],
                "cage_inertia_reduced": red.reduced[2],
            }
        j = np.stack(inertias, axis=1)
        c = np.stack([c12, c23], axis=1)
        drive, load = whole(loads.drive_torque), whole(loads.load_torque)
        torques = np.stack([drive, np.zeros(size), -load], axis=1)
        horizon = arrays.analysis.horizon
        over = wanted is None or bool(HORIZON_KEYS & set(wanted))
        dyn = block_dynamics(j, c, torques, None if horizon is None else whole(horizon), over)
        declined = declined | ~dyn.step.consistent
        r12, r23 = dyn.step.static[:, 0], dyn.step.static[:, 1]
        beta1, beta2 = dyn.frequencies[:, 0], dyn.frequencies[:, 1]
        sup = supremum(dyn.step.static, dyn.step.amplitudes)
        sup12, sup23 = sup[:, 0] / r12, sup[:, 1] / r23
        values |= {
            "drum_inertia": j[:, 0],
            "sheave_inertia": j[:, 1],
            "cage_inertia": j[:, 2],
            "chord_stiffness": c12,
            "rope_stiffness": c23,
            "partial_beta12": np.sqrt(c12 * (1.0 / j[:, 0] + 1.0 / j[:, 1])),
            "partial_beta23": np.sqrt(c23 * (1.0 / j[:, 1] + 1.0 / j[:, 2])),
            "beta1": beta1,
            "beta2": beta2,
            "period1": dyn.period,
            "frequency_ratio": beta2 / beta1,
            "beta1_squared_seed_formula": seed_formula_1(j[:, 0], j[:, 1], j[:, 2], c12, c23),
            "drive_torque": drive,
            "load_torque": load,
            "acceleration": dyn.step.acceleration,
            "static_moment_12": r12,
            "static_moment_23": r23,
            "mu12_first_swing": dyn.first_swing.value[:, 0] / r12,
            "mu12_first_swing_time": dyn.first_swing.time[:, 0],
            "mu23_first_swing": dyn.first_swing.value[:, 1] / r23,
            "mu23_first_swing_time": dyn.first_swing.time[:, 1],
            "horizon": dyn.horizon,
            "mu12_supremum": sup12,
            "mu23_supremum": sup23,
            "mu12_simplified": dyn.simplified[0],
            "mu23_simplified": dyn.simplified[1],
            "peak_moment_12": sup12 * r12,
            "peak_moment_23": sup23 * r23,
        }
        if dyn.over_horizon is not None:
            values["mu12_horizon"] = dyn.over_horizon.value[:, 0] / r12
            values["mu23_horizon"] = dyn.over_horizon.value[:, 1] / r23
    return kernel_answer(values, declined, size)
