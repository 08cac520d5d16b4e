"""The vectorized kernel of ``mdcalc sweep``: the closed forms over a grid at once."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from mdcalc.input.model import with_values
from mdcalc.problems.coupling.case import Case
from mdcalc.problems.coupling.scene import (
    harmonic_numbers,
    resonance,
    scene_of,
    step_numbers,
)

#: Keys ``mdcalc sweep`` may vary in the vectorized form, and the scene input each sets.
SWEEP_KEYS = {
    "coupling.driving_inertia": "j1",
    "coupling.driven_inertia": "j2",
    "coupling.stiffness": "stiffness",
    "coupling.stiffness_nm_per_deg": "stiffness",
    "coupling.absorption": "p",
    "coupling.log_decrement": "p",
    "coupling.damping": "p",
    "step.torque": "step_torque",
    "harmonic.driving_torque": "combined_amplitude",
    "harmonic.driving_phase_deg": "combined_amplitude",
    "harmonic.driven_torque": "combined_amplitude",
    "harmonic.driven_phase_deg": "combined_amplitude",
    "harmonic.speed": "omega",
    "harmonic.speed_rpm": "omega",
}


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """The closed-form results over a grid of scenes at once (numpy): the coupling,
    the suddenly applied torque and the harmonic torques, by the formulas of the
    report; missing (NaN) where the report does not show a value. Without the pulse,
    ramp and table results (Duhamel: point by point). None for another key, or where
    a point is at undamped resonance (no answer)."""
    import numpy as np

    if any(key not in SWEEP_KEYS for key in grid):
        return None
    # The case with the grid's arrays in it (the sweep has validated the grid's
    # corners), so that scene_of picks the alternatives it does.
    arrays = with_values(
        case, {key: np.asarray(values, dtype=float) for key, values in grid.items()}
    )
    s = scene_of(arrays)
    damped = s.p > 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        out: dict[str, Any] = {
            "driving_inertia": s.j1,
            "driven_inertia": s.j2,
            "stiffness": s.stiffness,
            "reduced_inertia": s.reduced_inertia,
            "natural_frequency": s.beta,
            "period": s.period,
            "damping_p": np.where(damped, s.p, np.nan),
            "damping_alpha": np.where(damped, s.alpha, np.nan),
            "log_decrement": np.where(damped, s.log_decrement, np.nan),
            "absorption": np.where(damped, s.absorption, np.nan),
            "damping_ratio": np.where(damped, s.zeta, np.nan),
        }
        if arrays.step is not None:
            out |= step_numbers(arrays.step.torque, s)
        if arrays.harmonic is not None:
            numbers = harmonic_numbers(arrays.harmonic, s)
            if np.any((s.p == 0.0) & (numbers["frequency_ratio"] == 1.0)):
                return None  # no answer there, as the point-by-point status says
            resonant = damped & (numbers["gamma"] * numbers["gamma"] < 2.0)
            ratio, peak = resonance(numbers["combined_amplitude"], s)
            out |= numbers | {
                "steady_torque_total": np.where(damped, numbers["steady_torque_total"], np.nan),
                "gamma": np.where(damped, numbers["gamma"], np.nan),
                "resonance_ratio": np.where(resonant, ratio, np.nan),
                "resonance_twist": np.where(resonant, peak, np.nan),
            }
    return out
