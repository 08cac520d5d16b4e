"""The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study``: every numeric
result of the report over a block of chains at once, by the functions the single
scene runs on a block of one (:func:`~.chain.modal_block`, :func:`~.chain.energy_block`,
:func:`~.chain.forced_block`)."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from mdcalc.input.model import in_tiles, kernel_answer, with_values
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
#: list index).
SWEEP_KEYS = {
    "chain.inertias.N": "Jᵢ",
    "chain.stiffnesses.N": "cᵢ",
    "chain.damping.N": "ξᵢ",
    "resonance.harmonic_torque": "M_k",
    "mathieu.damping": "c of the Mathieu equation",
    "mathieu.points.N.N": "a or q of a Mathieu point",
}

#: The Floquet radii's reference is a DOP853 run at rtol 10⁻¹², atol 10⁻¹⁵; the block
#: runs the same method and control and agrees within 10⁻⁹ relative, or within the
#: run's absolute tolerance where damping near critical leaves a radius of 10⁻¹¹
#: (cases/extreme/resonance_mathieu_critical_damping.toml: 3·10⁻¹⁷ apart).
ODE_REFERENCED = {f"floquet_radius_{k + 1}": (1e-9, 1e-15) for k in range(8)}

#: Chains a call of the modal solution takes at once: its tables of a few (B, n)
#: arrays stay in the cache (2048 chains of inline_six: 1.35x the rate of 65 536).
TILE_ROWS = 2048


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
    if any(key.startswith("chain.") for key in grid) and case.chain is None:
        return None
    if any(key.startswith("resonance.") for key in grid) and case.resonance is None:
        return None
    points = case.mathieu is not None and bool(case.mathieu.points)
    if any(key.startswith("mathieu.") for key in grid) and not points:
        return None
    if case.chain is None and not points:
        return None
    if (
        case.chain is not None
        and any(key.startswith("chain.damping.") for key in grid)
        and case.chain.damping is None
    ):
        return None
    floquet = points and (wanted is None or any(k.startswith("floquet_") for k in wanted))
    if not floquet:  # (the Floquet runs step all their rows at once)
        tiles = in_tiles(sweep, case, grid, wanted, TILE_ROWS)
        if tiles is not None:
            return tiles
    arrays = with_values(case, {key: np.asarray(v, dtype=float) for key, v in grid.items()})
    size = max([np.size(v) for v in grid.values()] + [1])
    values: dict[str, Any] = {}
    declined = np.zeros(size, dtype=bool)
    with np.errstate(all="ignore"):
        if arrays.chain is not None:
            declined = _chain(arrays, size, values)
        if floquet:
            declined = declined | _floquet(arrays.mathieu, size, values)
    for k, m in enumerate(case.measured or []):
        values[f"measured_frequency_{k + 1}"] = m.speed_rpm * m.order / HZ_TO_RPM
        if m.frequency_hz is not None:
            values[f"stated_speed_{k + 1}"] = HZ_TO_RPM * m.frequency_hz / m.order
    return kernel_answer(values, declined, size)


def _floquet(m: Any, size: int, values: dict[str, Any]) -> Any:
    """ρ = max |μ| of every Mathieu point over the block, as the single scene's
    reference (DOP853 at rtol 10⁻¹², the determinant by Liouville where spoiled); the
    rows whose run fails are declined."""
    import numpy as np

    from mdcalc.problems.resonance.mathieu import floquet_block, liouville, spectral_radius

    def spread(value: Any) -> Any:
        return np.broadcast_to(np.asarray(value, dtype=float), (size,))

    columns = [(spread(a), spread(q)) for a, q in m.points]
    a = np.concatenate([col[0] for col in columns])
    q = np.concatenate([col[1] for col in columns])
    c = np.tile(spread(m.damping), len(columns))
    trace, det = floquet_block(a, q, c, 1e-12)
    radius = spectral_radius(trace, liouville(det, c)).reshape(len(columns), size)
    for k in range(len(columns)):
        values[f"floquet_radius_{k + 1}"] = radius[k]
    return ~np.all(np.isfinite(radius), axis=0)


def _chain(arrays: Any, size: int, values: dict[str, Any]) -> Any:
    """The chain's results over the block into ``values``; the rows declined."""
    import numpy as np

    section = arrays.chain
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
            exact = forced_block(section, md, mode, r.order, r.harmonic_torque, beta, damping, size)
            declined |= amp.singular | exact.singular
            values |= {
                "amplitude": amp.reference_amplitude,
                "amplitude_exact": exact.reference_amplitude,
                "max_shaft_torque": amp.max_shaft_torque,
                "max_shaft_torque_exact": exact.max_shaft_torque,
            }
    return declined
