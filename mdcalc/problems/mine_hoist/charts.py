"""The charts of ``--plot``: the dynamic factors against time, and over the
height sweep (data only)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from mdcalc.problems.mine_hoist.modal import Dynamics
from mdcalc.problems.mine_hoist.solve import Result, SweepRow

if TYPE_CHECKING:
    from mdcalc.output.plot import Chart


#: Samples per period of a mode drawn in μ(t) (the line between them is straight).
CHART_SAMPLES_PER_PERIOD = 16

#: Points of one μ(t) curve at most, and at least (the slow mode stays smooth).
CHART_POINTS = (1001, 8001)

#: A mode too fast to draw over the horizon is drawn as an envelope above this Σ|b|.
CHART_ENVELOPE = 1e-4


def charts(result: Result) -> list[Chart]:
    """μ₁₂(t) and μ₂₃(t) over the report's horizon from the modal solution, with the
    supremum 1 + Σ|b|, the static level 1 and the first swing's maximum; and with a
    height sweep, the sweep's maxima against H. [] for a scene without an answer."""
    if result.status != "ok" or result.dynamics is None:
        return []
    dyn = result.dynamics
    out = [_factor_chart(dyn, spring) for spring in (0, 1)]
    if len(result.sweep) > 0:
        out.append(_sweep_chart(result.sweep))
    return out


def _factor_chart(dyn: Dynamics, spring: int) -> Chart:
    """μ(t) = 1 + Σ bⱼ·cos(βⱼt) on a grid of 16 points per period of the fastest mode
    that fits :data:`CHART_POINTS` over the horizon. Faster modes swing through ±|b|
    within each of their periods: above :data:`CHART_ENVELOPE` they are drawn as the
    envelope (drawn curve) ± Σ|b|, below it they are left out and the label says so."""
    from mdcalc.output.plot import Chart, Mark, Series

    name = ("μ₁₂", "μ₂₃")[spring]
    frequencies = list(dyn.modes.frequencies)
    coefficients = dyn.coefficients(spring)
    horizon = dyn.horizon
    low, high = CHART_POINTS

    def points_for(beta: float) -> int:
        return math.ceil(horizon * beta / (2.0 * math.pi) * CHART_SAMPLES_PER_PERIOD) + 1

    drawn = [j for j, beta in enumerate(frequencies) if points_for(beta) <= high]
    left_out = [j for j in range(len(frequencies)) if j not in drawn]
    count = max([low, *(points_for(frequencies[j]) for j in drawn)])
    times = np.linspace(0.0, horizon, count)
    mu = np.ones(count)
    for j in drawn:
        mu += coefficients[j] * np.cos(frequencies[j] * times)
    fast = math.fsum(abs(coefficients[j]) for j in left_out)
    x = times.tolist()
    label = f"{name}(t)"
    series: list[Series] = []
    if left_out:
        cut = frequencies[left_out[0]]
        modes = "mode" if len(left_out) == 1 else "modes"
        without = f" without the {modes} from {cut:.4g} rad/s"
        if fast > CHART_ENVELOPE:
            # the upper and the lower edge, two curves with one legend entry
            series.append(Series(label + without, x, mu.tolist()))
            envelope = f"envelope ± {fast:.3g} of the {modes} too fast to draw"
            series.append(Series(envelope, x, (mu + fast).tolist(), "envelope"))
            series.append(Series("", x, (mu - fast).tolist(), "envelope"))
        else:
            series.append(Series(f"{label}{without} (Σ|b| = {fast:.1e})", x, mu.tolist()))
    else:
        series.append(Series(label, x, mu.tolist()))
    first = dyn.first_swing[spring]
    peak = dyn.factor(first, spring)
    series.append(
        Series(
            f"first-swing maximum {peak:.5g} at t = {first.time:.4g} s",
            [first.time],
            [peak],
            "this-case",
        )
    )
    supremum = dyn.supremum(spring)
    return Chart(
        f"Dynamic factor {name} = M/R over the horizon {horizon:.4g} s "
        f"(R = {dyn.static[spring]:.6g} N·m)",
        "t [s]",
        f"{name} [-]",
        series,
        [
            Mark("y", supremum, f"supremum 1 + Σ|b| = {supremum:.5g}", "reported"),
            Mark("y", 1.0, "static, μ = 1", "static"),
            Mark("x", dyn.period, f"first swing ends, 2π/β₁ = {dyn.period:.4g} s", "event"),
        ],
    )


def _sweep_chart(rows: list[SweepRow]) -> Chart:
    """The seed's Table 1: the suprema and the simplified (19)-(20) against H."""
    from mdcalc.output.plot import Chart, Series

    heights = [row.height for row in rows]
    series = []
    for spring, (name, formula) in enumerate((("μ₁₂", "(19)"), ("μ₂₃", "(20)"))):
        suprema = [r.dynamics.supremum(spring) for r in rows]
        simplified = [r.dynamics.simplified[spring] for r in rows]
        series.append(Series(f"{name} supremum", heights, suprema, group=name))
        series.append(Series(f"{name} by {formula}", heights, simplified, "comparison", name))
    return Chart(
        "Height sweep: the undamped suprema and the simplified formulas (19)-(20)",
        "H [m]",
        "μ [-]",
        series,
    )
