"""The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study``: every numeric
result of the report over a block of chains at once, by the functions the single
scene runs on a block of one (:func:`~.chain.modal_block`, :func:`~.chain.energy_block`,
:func:`~.chain.forced_block`)."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from mdcalc.input.model import kernel_answer, with_values
from mdcalc.problems.resonance.case import Case
from mdcalc.problems.resonance.chain import (
    crank_sum,
    dissipation,
    energy_block,
    forced_block,
    geometric_sums,
    modal_block,
    undamped_mode,
    whole,
)
from mdcalc.problems.resonance.report import HZ_TO_RPM, MAX_MODES_SHOWN, TWO_PI

#: Keys ``mdcalc sweep`` and ``mdcalc study`` may vary in the vectorized form (N: any
#: list index). The Mathieu points are not here: their reference is an ODE run.
SWEEP_KEYS = {
    "chain.inertias.N": "Jᵢ",
    "chain.stiffnesses.N": "cᵢ",
    "chain.damping.N": "ξᵢ",
    "resonance.harmonic_torque": "M_k",
}


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result of a chain scene over a block (numpy). A sample without
    an answer (no damping moves in the mode, a forced response singular to working
    precision, modes that cannot be computed) is marked ``DECLINED``, to be solved
    alone. None for a key this form does not know, for a scene without a chain, and
    for one with Mathieu points (their Floquet multipliers are ODE runs)."""
    import numpy as np

    for key in grid:
        pattern = ".".join("N" if p.isdigit() else p for p in key.split("."))
        if pattern not in SWEEP_KEYS:
            return None
    if case.chain is None or (case.mathieu is not None and case.mathieu.points):
        return None
    if any(key.startswith("resonance.") for key in grid) and case.resonance is None:
        return None
    if any(key.startswith("chain.damping.") for key in grid) and case.chain.damping is None:
        return None
    arrays = with_values(case, {key: np.asarray(v, dtype=float) for key, v in grid.items()})
    size = max([np.size(v) for v in grid.values()] + [1])
    section = arrays.chain
    values: dict[str, Any] = {}
    with np.errstate(all="ignore"):
        md = modal_block(section, size)
        declined = ~np.all(np.isfinite(md.frequencies), axis=1)
        for j in range(min(md.frequencies.shape[1], MAX_MODES_SHOWN)):
            values[f"frequency_{j + 1}"] = md.frequencies[:, j] / TWO_PI
        r = arrays.resonance
        if r is not None:
            mode = r.mode - 1
            beta = md.frequencies[:, mode]
            f = beta / TWO_PI
            values["resonance_frequency"] = f
            values["critical_speed_rpm"] = HZ_TO_RPM * f / r.order
            shapes = md.shapes[:, mode, :]
            if section.cranks is not None:
                values["geometric_sum"] = np.abs(geometric_sums(section, shapes, r.order))
                values["algebraic_sum"] = crank_sum(section, shapes)
            if r.harmonic_torque is not None and section.damping is not None:
                damping = whole(section.damping, size)
                work = dissipation(damping, shapes)
                values["modal_damping"] = work
                declined |= undamped_mode(damping, work)
                amp = energy_block(section, md, mode, r.order, r.harmonic_torque, damping)
                exact = forced_block(
                    section, md, mode, r.order, r.harmonic_torque, beta, damping, size
                )
                declined |= amp.singular | exact.singular
                values |= {
                    "amplitude": amp.reference_amplitude,
                    "amplitude_exact": exact.reference_amplitude,
                    "max_shaft_torque": amp.max_shaft_torque,
                    "max_shaft_torque_exact": exact.max_shaft_torque,
                }
    for k, m in enumerate(case.measured or []):
        values[f"measured_frequency_{k + 1}"] = m.speed_rpm * m.order / HZ_TO_RPM
        if m.frequency_hz is not None:
            values[f"stated_speed_{k + 1}"] = HZ_TO_RPM * m.frequency_hz / m.order
    return kernel_answer(values, declined, size)
