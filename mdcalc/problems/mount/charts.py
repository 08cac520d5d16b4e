"""The charts of ``--plot``: amplitudes and transmissibility against the crank
speed (data only)."""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from mdcalc.core import sdof
from mdcalc.problems.mount.scene import RAD_S_TO_RPM, peak_of_two_harmonics_array, stiffness_for
from mdcalc.problems.mount.solve import Result

if TYPE_CHECKING:
    from mdcalc.output.plot import Chart, Role, Series


#: Points of each curve of ``--plot`` (and the case's ratio, 1/2 and 1 added).
CHART_POINTS = 600

#: An undamped curve is unbounded at its resonance: drawn clipped at this many times
#: its level (amplitude m·r/M, transmissibility 1), or at the case's value if higher.
CHART_CLIP = 100.0

#: A chart's y axis is logarithmic when its values span more than this factor.
CHART_DECADE = 20.0


def charts(result: Result) -> list[Chart]:
    """``--plot``: against the frequency ratio ω/β (β kept, the crank speed varied, so
    the forces m·r·ω² grow with it), the amplitudes |A₁|, |A₂| of :meth:`Scene.response`
    and the peak |x| of their sum (:func:`peak_of_two_harmonics_array`); with a
    damping ratio or an [isolation] target, the transmissibility of both harmonics
    (:meth:`Scene.transmitted`) with the √2 line and the target, met at the ratio of
    :func:`stiffness_for`. The case's point lies on the curves (undamped ones clipped);
    the resonances ω = β and β/2 are marked. Linear in ω/β from 0.05 to 3 (or 1.25
    times the case's ratio), logarithmic when the case lies below 0.1 or above 8."""
    import numpy as np

    from mdcalc.output.plot import Chart, Mark, Series

    case, s = result.case, result.scene
    ratio = s.omega / s.beta
    target = case.isolation.transmissibility if case.isolation is not None else None
    needed = (
        None if target is None else math.sqrt(s.engine_mass / stiffness_for(s, target)) * s.omega
    )
    ratios, x_log = _chart_ratios([ratio] if needed is None else [ratio, needed])
    omega: Any = ratios * s.beta
    omega[ratios == ratio] = s.omega  # the case's own point, to the last digit
    swept = replace(s, omega=omega)
    ok = result.status == "ok"
    # an undamped resonance is unbounded: the curves are clipped there
    clip = CHART_CLIP if s.zeta == 0.0 else max(CHART_CLIP, 1.0 / s.zeta)

    level = s.piston_mass * s.radius / s.engine_mass  # m·r/M, the high-speed limit
    own = [result.peak[0], abs(s.response(1)), abs(s.response(2))] if ok else []
    ceiling = max([clip * level, *own])
    with np.errstate(all="ignore"):
        first, second = swept.response(1), swept.response(2)
        curves: list[tuple[str, Any, Role]] = [
            ("peak |x|", peak_of_two_harmonics_array(first, second), "result"),
            ("|A₁| (ω)", np.abs(first), "secondary"),
            ("|A₂| (2ω)", np.abs(second), "secondary"),
        ]
    x = ratios.tolist()
    series = [
        Series(label, x, (1e3 * _clipped(values, ceiling)).tolist(), role)
        for label, values, role in curves
    ]
    speed = f"this case: ω = {s.omega:.4g} rad/s = {s.omega * RAD_S_TO_RPM:.4g} rpm"
    marks = [
        Mark("x", 1.0, "resonances ω = β, β/2", "resonance"),
        Mark("x", 0.5, role="resonance"),
        Mark("y", 1e3 * level, "m·r/M (lecture, high speed)", "reported"),
    ]
    if ok:
        series.append(Series(speed, [ratio] * 3, [1e3 * a for a in own], "this-case"))
    else:
        marks.append(Mark("x", ratio, f"{speed}: unbounded", "this-case"))
    damping = "undamped, clipped at resonance" if s.zeta == 0.0 else f"ζ = {s.zeta:g}"
    out = [
        Chart(
            f"Engine amplitude against ω/β (β = {s.beta:.4g} rad/s; {damping})",
            "frequency ratio ω/β [-]",
            "amplitude [mm]",
            series,
            marks,
            x_log=x_log,
            y_log=_spread(series),
        )
    ]
    if case.mounts.damping_ratio is None and target is None:
        return out

    clip_t = max([clip, *(sdof.transmissibility(k * ratio, s.zeta) for k in (1, 2) if ok)])
    with np.errstate(all="ignore"):
        passed = [np.abs(swept.transmitted(k)) / swept.force(k) for k in (1, 2)]
    series = [
        Series("1st harmonic, T(ω/β)", x, _clipped(passed[0], clip_t).tolist()),
        Series("2nd harmonic, T(2ω/β)", x, _clipped(passed[1], clip_t).tolist(), "secondary"),
    ]
    if ok:
        own_t = [sdof.transmissibility(k * ratio, s.zeta) for k in (1, 2)]
        series.append(Series(f"this case: ω/β = {ratio:.4g}", [ratio] * 2, own_t, "this-case"))
    marks = [
        Mark("x", math.sqrt(2.0), "T = 1 at any ζ: ω/β = √2, √2/2", "advice"),
        Mark("x", math.sqrt(0.5), role="advice"),
    ]
    if target is not None and needed is not None:
        stiffness = stiffness_for(s, target)
        series.append(
            Series(
                f"target met with c = {stiffness:.4g} N/m (ω/β = {needed:.4g})",
                [needed],
                [target],
                "event",
            )
        )
        marks.append(Mark("y", target, f"target T = {target:g} (1st harmonic)", "limit"))
    out.append(
        Chart(
            f"Force transmissibility of the mounts against ω/β "
            f"({'undamped, clipped at resonance' if s.zeta == 0.0 else f'ζ = {s.zeta:g}'})",
            "frequency ratio ω/β [-]",
            "transmissibility T = |F_frame|/|F| [-]",
            series,
            marks,
            x_log=x_log,
            y_log=_spread(series),
        )
    )
    return out


def _chart_ratios(points: list[float]) -> tuple[Any, bool]:
    """The ω/β grid of :func:`charts` (numpy) holding ``points``, 1/2 and 1, and
    whether it is logarithmic."""
    import numpy as np

    low, high = min(points), max(points)
    if low >= 0.1 and high <= 8.0:
        grid, log = np.linspace(0.05, max(3.0, 1.25 * high), CHART_POINTS), False
    else:
        grid, log = np.geomspace(min(0.05, low / 3.0), max(3.0, 3.0 * high), CHART_POINTS), True
    return np.unique(np.concatenate([grid, [0.5, 1.0, *points]])), log


def _spread(series: list[Series]) -> bool:
    """Whether the series' values, all positive, span more than :data:`CHART_DECADE`."""
    values = [y for s in series for y in s.y]
    return min(values) > 0.0 and max(values) > CHART_DECADE * min(values)


def _clipped(values: Any, ceiling: float) -> Any:
    """``values`` (numpy) at most ``ceiling``; an unbounded one (inf, nan) at it."""
    import numpy as np

    return np.where(np.isfinite(values), np.minimum(values, ceiling), ceiling)
