"""The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study`` for the
anti-resonance absorber (7a): every numeric result of its sections over a block of
scenes, by the :class:`~.absorber.AbsorberScene` methods the single scene runs (on
floats there, on arrays here) and :func:`~.absorber.absorber_minima`."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from mdcalc.input.model import kernel_answer, with_values
from mdcalc.problems.variator.absorber import absorber_minima, absorber_scene
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
}

#: The sections this kernel covers; a case with any other (the motor, the clutch,
#: the mechanism and its periodic states, the pendulum) runs point by point.
OTHER_SECTIONS = ("motor", "clutch", "mechanism", "drive", "antiresonance", "pendulum")


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result of an absorber scene over a block (numpy). A sample at an
    undamped resonance of the two-disk system (no answer) is marked ``DECLINED``, to
    be solved alone. None for another key, a case without ``[absorber]``, or one
    with another section."""
    import numpy as np

    if any(key not in SWEEP_KEYS for key in grid) or case.absorber is None:
        return None
    if any(getattr(case, name) is not None for name in OTHER_SECTIONS):
        return None
    given = case.absorber
    if any(getattr(given, key.split(".")[1]) is None for key in grid):
        return None  # a key that switches an alternative (c_g or its tuning)
    arrays = with_values(case, {key: np.asarray(v, dtype=float) for key, v in grid.items()})
    size = max([np.size(v) for v in grid.values()] + [1])
    assert arrays.absorber is not None
    s = absorber_scene(arrays.absorber)
    with np.errstate(all="ignore"):
        declined = np.broadcast_to(s.determinant_is_zero(s.omega), (size,))
        low, high = s.resonances()
        a1, a2 = s.amplitudes(s.omega)
        static = s.m0 / s.c
        values: dict[str, Any] = {
            "absorber_stiffness": s.cg,
            "absorber_tuning": np.sqrt(s.cg / s.j2),
            "absorber_partial": np.sqrt(s.c / s.j1),
            "absorber_resonance_low": low,
            "absorber_resonance_high": high,
            "absorber_a1": np.abs(a1),
            "absorber_a2": np.abs(a2),
            "absorber_moment": np.abs((s.cg + 1j * (s.omega * s.bg)) * (a2 - a1)),
            "absorber_static": static,
            "absorber_untuned": s.untuned(s.omega),
        }
        undamped = np.broadcast_to(np.asarray(s.bg) == 0.0, (size,))
        if undamped.all():
            values["absorber_band_low"], values["absorber_band_high"] = s.band()
        elif not undamped.any():
            depth, where = absorber_minima(s, size)
            values |= {
                "absorber_minimum": depth,
                "absorber_minimum_frequency": where,
                "absorber_minimum_depth": depth / static,
            }
        else:
            return None  # some samples undamped, some damped: point by point
    return kernel_answer(values, declined, size)
