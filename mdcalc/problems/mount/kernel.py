"""The vectorized kernel of ``mdcalc sweep``: the scene formulas over a grid at once."""

from __future__ import annotations

import math
from typing import Any

from mdcalc.core import sdof
from mdcalc.problems.mount.case import Case
from mdcalc.problems.mount.scene import (
    QUASI_STATIC_RATIO,
    RAD_S_TO_RPM,
    SWEEP_KEYS,
    _inputs,
    dynamic_factor,
    peak_of_two_harmonics_array,
    scene_from,
    stiffness_for,
)

#: Inputs of which a case gives exactly one.
ALTERNATIVES = [
    ("engine_mass", "engine_weight"),
    ("piston_mass", "piston_weight"),
    ("speed", "speed_rpm"),
    ("stiffness", "static_deflection"),
]


def sweep(case: Case, grid: dict[str, Any]) -> dict[str, Any] | None:
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

        results = {
            "engine_mass": s.engine_mass,
            "piston_mass": s.piston_mass,
            "crank_radius": s.radius,
            "rod_ratio": s.rod_ratio,
            "crank_speed": s.omega,
            "crank_speed_rpm": s.omega * RAD_S_TO_RPM,
            "stiffness": s.stiffness,
            "static_deflection": s.engine_mass * s.g / s.stiffness,
            "natural_frequency": beta,
            "natural_frequency_hz": beta / (2.0 * math.pi),
            "resonant_speed_1": beta,
            "resonant_speed_2": beta / 2.0,
            "frequency_ratio": ratio,
            "force_1": s.force(1),
            "force_2": s.force(2),
            "amplitude_1": np.abs(first),
            "amplitude_2": np.abs(second),
            "peak_displacement": peak_of_two_harmonics_array(first, second),
            "dynamic_factor": dynamic_factor(ratio, zeta),
            "quasi_static_ratio": QUASI_STATIC_RATIO,
            "quasi_static_speed": QUASI_STATIC_RATIO * beta,
            "quasi_static_period_ratio": 1.0 / QUASI_STATIC_RATIO,
        }
        if given["zeta"] is not None:  # as in _transmission_section
            forces = s.transmitted(1), s.transmitted(2)
            results |= {
                "damping_ratio": zeta,
                "damping_coefficient": s.damping,
                "transmitted_force_peak": peak_of_two_harmonics_array(*forces),
            }
            for order, force in zip((1, 2), forces, strict=True):
                r = order * s.omega / beta
                results[f"transmissibility_{order}"] = sdof.transmissibility(r, zeta)
                results[f"transmitted_force_{order}"] = np.abs(force)
        if given["target"] is not None:  # as in _isolation_section
            stiffness = stiffness_for(s, given["target"])
            results |= {
                "target_transmissibility": given["target"],
                "required_stiffness": stiffness,
                "required_static_deflection": s.engine_mass * s.g / stiffness,
                "required_natural_frequency": np.sqrt(stiffness / s.engine_mass),
            }
    return results
