"""The charts of ``--plot``: the Campbell diagram and the Ince-Strutt chart of
the Mathieu equation (data only)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from mdcalc.problems.resonance.case import Case, Mathieu
from mdcalc.problems.resonance.chain import Modal
from mdcalc.problems.resonance.mathieu import monodromy_rk4
from mdcalc.problems.resonance.report import HZ_TO_RPM, MAX_MODES_SHOWN, TWO_PI, default_orders
from mdcalc.problems.resonance.solve import Result

if TYPE_CHECKING:
    from mdcalc.output.plot import Chart, Series


#: The Ince–Strutt map of ``--plot``: a coarse grid of RK4 monodromies, vectorized
#: (a few tenths of a second); the report's own chart (``chart = true``) is a table.
MAP_COLUMNS = 61  # q values

MAP_ROWS = 81  # a values

MAP_STEPS = 400

#: Orders drawn as rays each with its own legend entry; more share one entry.
LABELLED_ORDERS = 6


def charts(result: Result) -> list[Chart]:
    """``--plot``: the Campbell diagram (natural frequencies against engine speed, the
    orders k·n/60 as rays, the critical speeds where they meet, measured resonances),
    and with [mathieu] the Ince–Strutt chart with the case's points."""
    out: list[Chart] = []
    campbell = _campbell_chart(result.case, result.modal)
    if campbell is not None:
        out.append(campbell)
    if result.case.mathieu is not None:
        out.append(_ince_strutt_chart(result.case.mathieu))
    return out


def _campbell_chart(case: Case, md: Modal | None) -> Chart | None:
    """Over the [campbell] range and orders; without it, from 0 to 1.25 times the
    critical speed of [resonance] and the measured speeds, with their orders."""
    from mdcalc.output.plot import Chart, Mark, Series

    c, cb, r, measured = case.chain, case.campbell, case.resonance, case.measured or []
    orders = {m.order for m in measured}
    speeds = [m.speed_rpm for m in measured]
    marks: list[Mark] = []
    if md is not None and c is not None and cb is not None:
        orders |= set(cb.orders or default_orders(c.strokes))
        low, high = cb.from_rpm, cb.to_rpm
        marks = [Mark("x", low, "speed range of the Campbell table", "range"), Mark("x", high)]
    else:
        if md is not None and r is not None:
            orders.add(r.order)
            speeds.append(HZ_TO_RPM * md.frequencies[r.mode - 1] / TWO_PI / r.order)
        if not speeds:
            return None
        low, high = 0.0, 1.25 * max(speeds)
    ks = sorted(orders)
    series: list[Series] = []
    if md is not None:
        top = ks[-1] * high / HZ_TO_RPM  # the highest ray's frequency at the top speed
        fs = [beta / TWO_PI for beta in md.frequencies]
        shown = [j for j, f in enumerate(fs) if f <= top][:MAX_MODES_SHOWN] or [0]
        for j in shown:
            series.append(Series(f"mode {j + 1}: f = {fs[j]:.4g} Hz", [0.0, high], [fs[j]] * 2))
    if len(ks) <= LABELLED_ORDERS:
        for k in ks:
            series.append(
                Series(f"order k = {k:g}", [0.0, high], [0.0, k * high / HZ_TO_RPM], "excitation")
            )
    else:  # a ray per order in one colour, one legend entry for the fan
        for k in ks:
            label = f"orders k·n/60, k = {ks[0]:g} … {ks[-1]:g}" if k == ks[0] else ""
            y = [0.0, k * high / HZ_TO_RPM]
            series.append(Series(label, [0.0, high], y, "excitation", group="orders"))
    if md is not None:
        critical = [
            (HZ_TO_RPM * fs[j] / k, fs[j])
            for j in shown
            for k in ks
            if low <= HZ_TO_RPM * fs[j] / k <= high
        ]
        if critical:
            series.append(
                Series(
                    "critical speeds n = 60·f/k",
                    [n for n, _ in critical],
                    [f for _, f in critical],
                    "event",
                )
            )
    if measured:
        series.append(
            Series(
                "measured: f = n·k/60",
                [m.speed_rpm for m in measured],
                [m.speed_rpm * m.order / HZ_TO_RPM for m in measured],
                "event",
            )
        )
        stated = [m for m in measured if m.frequency_hz is not None]
        if stated:
            series.append(
                Series(
                    "measured: the f stated",
                    [m.speed_rpm for m in stated],
                    [m.frequency_hz or 0.0 for m in stated],
                    "measured",
                )
            )
    return Chart(
        "Campbell diagram: natural frequencies, engine orders f = k·n/60, "
        "critical speeds n = 60·f/k",
        "engine speed n [rpm]",
        "frequency f [Hz]",
        series,
        marks,
    )


def _widened(low: float, high: float, points: list[float]) -> tuple[float, float]:
    """[low, high] widened to hold the points, with a margin beyond those outside."""
    lowest, highest = min([low, *points]), max([high, *points])
    pad = 0.05 * (highest - lowest)
    return (low if lowest >= low else lowest - pad), (high if highest <= high else highest + pad)


def _ince_strutt_chart(m: Mathieu) -> Chart:
    """Stable and unstable regions of x″ + c·x′ + (a - 2q·cos 2t)·x = 0 over (q, a):
    |trace| of the period-π map against 1 + e^(-cπ) (RK4, vectorized over the grid),
    over the chart's range widened to the case's points, which are marked."""
    import numpy as np

    from mdcalc.output.plot import Chart, Series, Shade

    c = m.damping
    a_low, a_high = _widened(m.a_from, m.a_to, [p[0] for p in m.points])
    q_low, q_high = _widened(0.0, m.q_to, [p[1] for p in m.points])
    q_values = np.linspace(q_low, q_high, MAP_COLUMNS)
    a_values = np.linspace(a_low, a_high, MAP_ROWS)
    q_grid, a_grid = np.meshgrid(q_values, a_values)  # [i, j] at (q_j, a_i)
    with np.errstate(all="ignore"):
        trace, _ = monodromy_rk4(a_grid, q_grid, c, MAP_STEPS)
        ratio = np.abs(trace) / (1.0 + math.exp(-c * math.pi))
    # 0 … 1 stable, 1 … 2 unstable (a growth too fast for floats is unstable too)
    z = np.where(np.isfinite(ratio), np.minimum(ratio, 2.0), 2.0)
    series = []
    # first approximation (harmonic balance): the principal tongue a = 1 ± √(q² - c²)
    start = max(q_low, c)
    edge = np.linspace(start, q_high, 201).tolist() if start < q_high else []
    tongue = [(q, 1.0 - math.sqrt(q * q - c * c)) for q in reversed(edge)]
    tongue += [(q, 1.0 + math.sqrt(q * q - c * c)) for q in edge]
    tongue = [(q, a) for q, a in tongue if a_low <= a <= a_high]
    if tongue:
        series.append(
            Series(
                "first approximation, a = 1 ± √(q² - c²)",
                [q for q, _ in tongue],
                [a for _, a in tongue],
                "comparison",
            )
        )
    if m.points:
        series.append(
            Series(
                "the case's (q, a)",
                [p[1] for p in m.points],
                [p[0] for p in m.points],
                "this-case",
            )
        )
    return Chart(
        f"Ince–Strutt chart of x″ + c·x′ + (a - 2q·cos 2t)·x = 0, c = {c:g} "
        "(dark: unstable, Floquet)",
        "q [-]",
        "a [-]",
        series,
        shade=Shade(
            q_values.tolist(), a_values.tolist(), z.tolist(), "unstable", levels=[0.0, 1.0, 2.0]
        ),
    )
