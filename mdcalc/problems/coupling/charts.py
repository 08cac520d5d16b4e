"""The charts of ``--plot``: step response with its envelope, response curve over
λ = ω/β, transient histories (data only)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from mdcalc.core import sdof
from mdcalc.problems.coupling.case import Harmonic
from mdcalc.problems.coupling.scene import Scene, harmonic_numbers, resonance
from mdcalc.problems.coupling.solve import Result
from mdcalc.problems.coupling.transients import Transient, duhamel_response

if TYPE_CHECKING:
    from mdcalc.output.plot import Chart


#: Points of the response curve over λ (λ = 1, the resonance and the case's λ added).
CHART_POINTS = 300

#: An undamped resonance is clipped at this many times the static twist M/β².
CHART_CLIP = 100.0

#: A logarithmic y axis when the positive values span more than this factor.
CHART_DECADE = 100.0

#: Step response: samples per undamped period τ (at most STEP_MAX_POINTS of them),
#: and a fine grid over its first 8·τ whatever the horizon.
STEP_SAMPLES_PER_PERIOD = 64

STEP_MAX_POINTS = 4000

#: At most this many points of a Duhamel response are drawn; beyond, each of half as
#: many buckets keeps its lowest and highest sample (a fast oscillation stays a band).
CHART_MAX_POINTS = 8000


def charts(result: Result) -> list[Chart]:
    """``--plot``, in the report's order: with [step], the dynamic factor φ/φ_st of a
    suddenly applied torque against t from the closed form (:func:`sdof.step_response`,
    any damping) over :func:`step_chart_horizon`, the lecture's envelope 1 ± e^(-pt/2)
    when under-damped (through the peaks, not a bound), the first peak and the
    envelope at τ and 1.5·τ as the report gives them; with [harmonic], the steady twist
    amplitude (8.27)-(8.28) against λ = ω/β from :func:`harmonic_numbers` on a numpy
    grid, the case's point, the resonance (8.31)-(8.32) and the λ > 1.5 advice (an
    undamped resonance clipped at :data:`CHART_CLIP`·M/β²); per pulse, ramp and table,
    φ/φ_st against t from the exact Duhamel response over the peak search's horizon,
    the torque M(t)/M_max and the reported peak. At an undamped resonance (no answer)
    only the response curve, the case's λ marked unbounded."""
    case, s = result.case, result.scene
    if result.status != "ok":
        return [] if case.harmonic is None else [_harmonic_chart(case.harmonic, s, False)]
    out: list[Chart] = []
    if case.step is not None:
        out.append(_step_chart(s))
    if case.harmonic is not None:
        out.append(_harmonic_chart(case.harmonic, s, True))
    for transient, _, (factor, when) in result.transient_methods:
        out.append(_transient_chart(s, transient, factor, when))
    return out


def _damping_words(s: Scene) -> str:
    if s.p == 0.0:
        return "undamped"
    if s.zeta < 1.0:
        return f"ζ = {s.zeta:.4g}"
    return f"ζ = {s.zeta:.4g}, {'critically damped' if s.zeta == 1.0 else 'over-damped'}"


def step_chart_horizon(s: Scene) -> float:
    """The step chart's end: 4·τ, or 1.25 times the first peak's time when later;
    without overshoot, 6 time constants of the slow decay e^(-β·t/(ζ + √(ζ² - 1)))."""
    zeta = s.zeta
    peak_time = sdof.step_peak_time(s.beta, zeta)
    if peak_time is not None:
        return max(4.0 * s.period, 1.25 * peak_time)
    slow = s.beta / (zeta + math.sqrt(zeta * zeta - 1.0))
    return max(4.0 * s.period, 6.0 / slow)


def _step_chart(s: Scene) -> Chart:
    import numpy as np

    from mdcalc.output.plot import Chart, Mark, Series

    zeta, beta, tau = s.zeta, s.beta, s.period
    horizon = step_chart_horizon(s)
    count = min(STEP_MAX_POINTS, math.ceil(STEP_SAMPLES_PER_PERIOD * horizon / tau) + 1)
    peak_time = sdof.step_peak_time(beta, zeta)
    fine = np.linspace(0.0, min(horizon, 8.0 * tau), 8 * STEP_SAMPLES_PER_PERIOD + 1)
    extra = [] if peak_time is None else [peak_time]
    times = np.unique(np.concatenate([np.linspace(0.0, horizon, count), fine, extra]))
    x = times.tolist()
    series = [
        Series(
            "φ/φ_st = 1 - e^(-pt/2)·(cos β₁t + p/(2β₁)·sin β₁t)"
            if zeta < 1.0
            else "φ/φ_st, closed form (no overshoot)",
            x,
            sdof.step_response(times, beta, zeta).tolist(),
        )
    ]
    if zeta < 1.0:
        upper = sdof.step_envelope(times, beta, zeta)
        # the upper and the lower edge: two curves, one legend entry
        envelope = "envelope 1 ± e^(-pt/2), through the peaks"
        series.append(Series(envelope, x, upper.tolist(), "envelope"))
        series.append(Series("", x, (2.0 - upper).tolist(), "envelope"))
        at = [tau, 1.5 * tau]
        series.append(
            Series(
                "envelope at τ, 1.5·τ (report)",
                at,
                [sdof.step_envelope(t, beta, zeta) for t in at],
                "event",
            )
        )
    if peak_time is not None:
        factor = sdof.step_peak(zeta)
        series.append(
            Series(
                f"first peak {factor:.5g} at π/β₁ = {peak_time:.4g} s (report)",
                [peak_time],
                [factor],
                "this-case",
            )
        )
    words = _damping_words(s)
    if peak_time is None:
        words += ": factor 1"
    return Chart(
        f"Suddenly applied torque (8.15)-(8.16), φ/φ_st against t ({words})",
        "t [s]",
        "φ/φ_st, φ_st = M₀/c [-]",
        series,
        [Mark("y", 1.0, "static, φ/φ_st = 1", "static")],
    )


def _harmonic_chart(h: Harmonic, s: Scene, ok: bool) -> Chart:

    import numpy as np

    from mdcalc.output.plot import Chart, Mark, Series

    lam = h.omega / s.beta
    gamma = s.p / s.beta
    resonant = s.p > 0.0 and gamma * gamma < 2.0
    x_log = not 0.1 <= lam <= 8.0
    if x_log:
        grid = np.geomspace(min(0.05, lam / 3.0), max(3.0, 3.0 * lam), CHART_POINTS)
    else:
        grid = np.linspace(0.0, max(3.0, 1.25 * lam), CHART_POINTS)
    # (8.21), also at an undamped resonance: the speed as an array, numpy's arithmetic
    at_speed = h.model_copy(update={"speed": np.array([h.omega]), "speed_rpm": None})
    with np.errstate(all="ignore"):
        m = float(np.ravel(harmonic_numbers(at_speed, s)["combined_amplitude"])[0])
    ratio, peak = resonance(m, s) if resonant else (1.0, math.inf)
    lams = np.unique(np.concatenate([grid, [1.0, lam, ratio]]))
    omega: Any = lams * s.beta
    omega[lams == lam] = h.omega  # the case's own point, to the last digit
    swept = h.model_copy(update={"speed": omega, "speed_rpm": None})
    with np.errstate(all="ignore"):
        twist = harmonic_numbers(swept, s)["steady_twist"]
    static = m / s.beta**2  # the twist at λ = 0, M/β²
    own = [float(harmonic_numbers(h, s)["steady_twist"])] if ok else []
    ceiling = max([CHART_CLIP * static, *own, *([float(peak)] if resonant else [])])
    curve = np.where(np.isfinite(twist), np.minimum(twist, ceiling), ceiling)
    x = lams.tolist()
    series = [Series("φ_max(λ) = M/√((β² - ω²)² + p²ω²) (8.27)", x, curve.tolist())]
    marks = [Mark("y", static, f"static twist M/β² = {static:.4g} rad", "static")]
    if resonant:
        series.append(
            Series(
                f"resonance peak {float(peak):.4g} rad, M/(β²γ√(1 - γ²/4))",
                [float(ratio)],
                [float(peak)],
                "event",
            )
        )
        marks.append(
            Mark("x", float(ratio), f"resonance λ = √(1 - γ²/2) = {float(ratio):.4g}", "resonance")
        )
    elif s.p == 0.0:
        marks.append(Mark("x", 1.0, "resonance λ = 1 (undamped: unbounded)", "resonance"))
    if ok:
        series.append(
            Series(f"this case: λ = {lam:.4g}, φ_max = {own[0]:.4g} rad", [lam], own, "this-case")
        )
    else:
        marks.append(Mark("x", lam, f"this case: λ = {lam:.4g}, unbounded", "this-case"))
    marks.append(Mark("x", 1.5, "advice: λ > 1.5", "advice"))
    words = f"undamped, clipped at {CHART_CLIP:g}·M/β²" if s.p == 0.0 else f"γ = p/β = {gamma:.4g}"
    y_log = float(curve.min()) > 0.0 and float(curve.max()) > CHART_DECADE * float(curve.min())
    return Chart(
        f"Steady twist (8.27) against λ = ω/β (β = {s.beta:.4g} rad/s; {words})",
        "frequency ratio λ = ω/β [-]",
        "twist amplitude φ_max [rad]",
        series,
        marks,
        x_log=x_log,
        y_log=y_log,
    )


def _transient_chart(s: Scene, transient: Transient, factor: float, when: float) -> Chart:
    import numpy as np

    from mdcalc.output.plot import Chart, Mark, Series

    response = duhamel_response(s, transient)
    times = np.asarray(response.times, dtype=float)
    factors = np.asarray(response.displacements, dtype=float)
    nearest = int(np.argmin(np.abs(times - when)))
    peak = factor if factors[nearest] >= 0.0 else -factor
    if times[nearest] != when:  # the peak refined between samples, on the curve
        k = int(np.searchsorted(times, when))
        times, factors = np.insert(times, k, when), np.insert(factors, k, peak)
    times, factors = _thinned(times, factors)
    load_t, load = _load_line(transient)
    static = transient.peak_torque / s.stiffness
    return Chart(
        f"{transient.title} (φ_st = {static:.4g} rad; {_damping_words(s)})",
        "t [s]",
        "φ/φ_st, φ_st = M_max/c [-]",
        [
            Series("φ/φ_st, exact Duhamel response", times.tolist(), factors.tolist()),
            Series("torque M(t)/M_max", load_t, load, "load"),
            Series(f"peak {factor:.5g} at t = {when:.4g} s (report)", [when], [peak], "this-case"),
        ],
        [Mark("y", 1.0, "static, φ/φ_st = 1", "static")],
    )


def _load_line(transient: Transient) -> tuple[list[float], list[float]]:
    """The torque over M_max through its knots, held after the last, cut at the horizon."""
    scale, horizon = transient.peak_torque, transient.horizon
    knots = [(t, m / scale) for t, m in transient.knots]
    inside = [(t, f) for t, f in knots if t <= horizon]
    after = [(t, f) for t, f in knots if t > horizon]
    if after:  # linear up to the next knot, as the response reads it
        (t0, f0), (t1, f1) = inside[-1], after[0]
        inside.append((horizon, f0 + (f1 - f0) * (horizon - t0) / (t1 - t0)))
    elif inside[-1][0] < horizon:
        inside.append((horizon, inside[-1][1]))
    return [t for t, _ in inside], [f for _, f in inside]


def _thinned(times: Any, values: Any) -> tuple[Any, Any]:
    """At most about :data:`CHART_MAX_POINTS` samples (numpy): each bucket's lowest
    and highest, and the ends."""
    import numpy as np

    n = len(times)
    if n <= CHART_MAX_POINTS:
        return times, values
    edges = np.linspace(0, n, CHART_MAX_POINTS // 2 + 1).astype(int)
    keep = {0, n - 1}
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        if b > a:
            keep.add(a + int(np.argmin(values[a:b])))
            keep.add(a + int(np.argmax(values[a:b])))
    index = np.array(sorted(keep))
    return times[index], values[index]
