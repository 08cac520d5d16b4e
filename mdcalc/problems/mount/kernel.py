"""The vectorized kernel of ``mdcalc sweep``: the scene formulas over a grid at once."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from mdcalc.problems.mount.case import Case
from mdcalc.problems.mount.scene import (
    SWEEP_KEYS,
    _inputs,
    isolation_numbers,
    peak_of_two_harmonics_array,
    response_numbers,
    scene_from,
    scene_numbers,
    transmission_numbers,
)

#: Inputs of which a case gives exactly one.
ALTERNATIVES = [
    ("engine_mass", "engine_weight"),
    ("piston_mass", "piston_weight"),
    ("speed", "speed_rpm"),
    ("stiffness", "static_deflection"),
]


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result over a grid of scenes at once (numpy), by the formulas of
    :func:`solve` and :func:`report`; None for a key it does not know, or where a point
    has no answer (an undamped resonance: point by point says so)."""
    import numpy as np

    if any(key not in SWEEP_KEYS for key in grid):
        return None
    varied = {SWEEP_KEYS[key]: np.asarray(values, dtype=float) for key, values in grid.items()}
    shape = np.broadcast_shapes(*(values.shape for values in varied.values()))
    given: dict[str, Any] = {
        name: None if value is None else np.broadcast_to(value, shape)
        for name, value in (_inputs(case) | varied).items()
    }
    if any(given[a] is not None and given[b] is not None for a, b in ALTERNATIVES):
        return None  # not a valid case (the sweep's plan refuses it)
    s = scene_from(given)
    beta, zeta = s.beta, s.zeta
    ratio = s.omega / beta
    if np.any((zeta == 0.0) & ((ratio == 1.0) | (ratio == 0.5))):
        return None
    with np.errstate(divide="ignore", invalid="ignore"):
        first, second = s.response(1), s.response(2)
        if not (np.all(np.isfinite(first)) and np.all(np.isfinite(second))):
            return None  # c = M·ω² to round-off: point by point says what happens

        results = (
            scene_numbers(s)
            | response_numbers(s)
            | {"peak_displacement": peak_of_two_harmonics_array(first, second)}
        )
        if given["zeta"] is not None:  # as in _transmission_section
            results |= transmission_numbers(s) | {
                "transmitted_force_peak": peak_of_two_harmonics_array(
                    s.transmitted(1), s.transmitted(2)
                )
            }
        if given["target"] is not None:  # as in _isolation_section
            results |= isolation_numbers(s, given["target"])
    return results
