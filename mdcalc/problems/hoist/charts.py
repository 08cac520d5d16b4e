"""The charts of ``--plot``: the rope dynamic factor against time from the exact
piecewise solution of the rope model (:mod:`.history`; data only)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from mdcalc.output.report import MethodsTable
from mdcalc.problems.hoist.history import (
    MAX_ROPE_PIECES,
    RopeHistory,
    _frequency,
    _stretch,
    rope_history,
    rope_peak,
)
from mdcalc.problems.hoist.rope import RopeScene
from mdcalc.problems.hoist.solve import Result

if TYPE_CHECKING:
    from mdcalc.output.plot import Chart


#: Points per rope period on the charts' curves.
CHART_SAMPLES_PER_PERIOD = 48

#: A horizon longer than this many rope periods is drawn only over its opening
#: (the lift-off and the first peak, and :data:`CHART_WINDOW_PERIODS` periods after).
CHART_PERIODS = 60

CHART_WINDOW_PERIODS = 6


def charts(result: Result) -> list[Chart]:
    """``--plot``: with a [rope] section, the rope dynamic factor ψ = F/G against time
    at the start, load hanging and load lying on the ground, from the exact piecewise
    solution of the two-mass model (:func:`rope_history`) -- the closed forms
    (7.92)-(7.98) phase by phase, including the slack rope and lift-off; with the
    reported ψ, the static ψ = 1 and the time of the peak. [] for a scene without a
    rope (the uniform start has no curve worth a chart) or without an answer."""
    if result.status != "ok" or result.rope is None:
        return []
    if result.rope_hanging is None or result.rope_ground is None:
        return []
    r = result.rope
    return [
        _rope_chart(r, result.rope_hanging, hanging=True),
        _rope_chart(r, result.rope_ground, hanging=False),
    ]


def _rope_chart(r: RopeScene, table: MethodsTable, hanging: bool) -> Chart:
    import numpy as np

    from mdcalc.output.plot import Chart, Mark, Series

    history = rope_history(r, hanging)
    t_peak, f_peak = rope_peak(history, r)
    period = 2.0 * math.pi / r.beta
    lifts = [t for t, what in history.events if what == "lift-off"]
    first = 0.0 if hanging or not lifts else lifts[0]
    shown = history.horizon
    if shown > CHART_PERIODS * period:
        shown = min(shown, max(first, t_peak) + CHART_WINDOW_PERIODS * period)
    times: list[float] = []
    forces: list[float] = []
    for p in history.pieces:
        if p.t0 > shown:
            break
        span = min(p.t1, shown) - p.t0
        if p.taut:
            count = math.ceil(span / (2.0 * math.pi / _frequency(r, p)) * CHART_SAMPLES_PER_PERIOD)
            tau = np.linspace(0.0, span, max(count, 1) + 1)
            if p.t0 <= t_peak <= p.t0 + span:
                tau = np.union1d(tau, [t_peak - p.t0])
            force = r.c * np.asarray(_stretch(r, p, tau)[0])
        else:
            tau, force = np.array([0.0, span]), np.zeros(2)
        start = 1 if times else 0  # a piece starts where the last one ended
        times += (p.t0 + tau[start:]).tolist()
        forces += force[start:].tolist()
    psi = [f / r.weight for f in forces]
    series = [Series("ψ(t), exact two-mass solution", times, psi)]
    events = [(t, what) for t, what in history.events if t <= shown]
    if r.slack > 0.0 and not hanging and events and events[0][1] == "taut":
        t_taut = events.pop(0)[0]
        series.append(
            Series(f"slack taken up, t = {t_taut:.4g} s", [t_taut], [0.0], "event", "taut")
        )
    lifts_shown = [t for t, what in events if what == "lift-off"]
    if not hanging and lifts_shown:
        many = f" ({len(lifts_shown)}×)" if len(lifts_shown) > 1 else ""
        label = f"load lifts off, t = {lifts_shown[0]:.4g} s{many}"
        series.append(Series(label, lifts_shown, [1.0] * len(lifts_shown), "event", "lift-off"))
    slack = [t for t, what in events if what in ("slack", "taut")]
    if slack:
        episodes = sum(1 for _, what in events if what == "slack")
        if len(slack) == 2:
            label = f"rope slack from {slack[0]:.4g} to {slack[1]:.4g} s"
        else:
            label = f"rope goes slack {episodes}× (first at {slack[0]:.4g} s)"
        series.append(Series(label, slack, [0.0] * len(slack), "event", "slack"))
    downs = [t for t, what in events if what == "touch-down"]
    if downs:
        label = f"load touches down, t = {downs[0]:.4g} s" + (
            f" ({len(downs)}×)" if len(downs) > 1 else ""
        )
        series.append(
            Series(label, downs, [_psi_at(r, history, t) for t in downs], "event", "down")
        )
    if r.start_time <= shown:
        t_p = r.start_time
        series.append(
            Series(
                f"start ends, t_p = {t_p:.4g} s",
                [t_p],
                [_psi_at(r, history, t_p)],
                "event",
                "start",
            )
        )
    scene = "load hanging" if hanging else "load lifting off the ground"
    if r.slack > 0.0 and not hanging:
        scene += f", {r.slack:g} m of slack"
    title = f"Rope dynamic factor ψ = F/G at the start, {scene} (t_p = {r.start_time:.4g} s)"
    if shown < history.horizon:
        title += f"\nfirst {shown:.3g} s of {history.horizon:.4g} s "
        title += f"({history.horizon / period:.3g} rope periods) shown"
    if not history.complete:
        title += f"\nstopped after {MAX_ROPE_PIECES} pieces (a chattering rope)"
    reference = next(row for row in table.rows if row.reference)
    reported = reference.values["dynamic_factor"]
    assert reported is not None
    peak = f_peak / r.weight
    return Chart(
        title,
        "t [s]",
        "ψ = F/G [-]",
        series,
        [
            Mark(
                "y",
                reported,
                f"reported ψ = {_psi_text(reported)} ({reference.method})",
                "reported",
            ),
            Mark("y", 1.0, "static, ψ = 1", "static"),
            Mark(
                "x",
                t_peak,
                f"peak of the curve ψ = {_psi_text(peak)} at t = {t_peak:.4g} s",
                "event",
            ),
        ],
    )


def _psi_text(psi: float) -> str:
    """ψ to 5 digits, or as 1 + δ when it is within 1e-3 of 1 (a slow start)."""
    if 0.0 < abs(psi - 1.0) < 1e-3:
        return f"1 {'+' if psi > 1.0 else '−'} {abs(psi - 1.0):.4g}"
    return f"{psi:.5g}"


def _psi_at(r: RopeScene, history: RopeHistory, t: float) -> float:
    for p in history.pieces:
        if p.t0 <= t <= p.t1:
            return r.c * max(float(_stretch(r, p, t - p.t0)[0]), 0.0) / r.weight
    return 0.0
