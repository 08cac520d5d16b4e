"""The charts of ``--plot``: absorber amplitudes, the clutch's loading curve and its lines,
the transfer functions, the clutch load over a stroke, the anti-resonance design and
the pendulum (data only)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from mdcalc.core import periodic
from mdcalc.problems.variator.absorber import AbsorberScene, absorber_minimum
from mdcalc.problems.variator.case import Clutch, Mechanism, Pendulum
from mdcalc.problems.variator.clutch import clutch_lines
from mdcalc.problems.variator.drive import CLUTCH, DriveScene, ThreeMass
from mdcalc.problems.variator.pendulum import agm
from mdcalc.problems.variator.solve import Result
from mdcalc.problems.variator.transfer import transfer_of

if TYPE_CHECKING:
    from mdcalc.output.plot import Chart, Role


#: Points of a curve over its whole range, before refinement at a notch.
CURVE_POINTS = 601

#: Samples of q(τ) over one stroke at most, uniform and again after the jump.
STROKE_SAMPLES = 4096


def charts(result: Result) -> list[Chart]:
    """The curves behind the report (``--plot``), closed forms and the periodic states
    already solved, no ODE run:

    * 7a: |A₁|, |A₂| and the disk without the absorber against ω/ω of the torque;
    * 7c: the loading curve M = c₀·ξⁿ and its three lines;
    * 7d: Π - φ_c, Π′, Π″ over a stroke;
    * 7e/7f: q/q_c over one stroke, before and after the coupling;
    * 7f: the clutch under one harmonic of u, before and after, against ν/(zω);
    * 7g: the pendulum's swing against its order (its backbone).

    With no answer only the absorber's curve, which shows ω on a resonance."""
    case = result.case
    out: list[Chart] = []
    if result.absorber is not None:
        out.append(_absorber_chart(result.absorber))
    if result.status != "ok":
        return out
    if case.clutch is not None:
        out.append(_clutch_chart(case.clutch))
    if case.mechanism is not None:
        out.append(_mechanism_chart(case.mechanism))
    if result.drive is not None and result.two_mass is not None:
        out.append(_stroke_chart(result))
    if result.drive is not None and result.three_mass is not None:
        out.append(_antiresonance_chart(result.drive, result.three_mass))
    if case.pendulum is not None:
        out.append(_pendulum_chart(case.pendulum))
    return out


def _refined(grid: np.ndarray, notches: list[float]) -> list[float]:
    """``grid`` with the neighbours 10⁻²…10⁻⁴ away (relative) of each notch added
    within the grid's range: the dip of an amplitude to 0 shows on a log axis (the
    notch itself would give 0, or round-off far below the rest of the curve)."""
    low, high = float(grid[0]), float(grid[-1])
    points = {float(v) for v in grid}
    for notch in notches:
        for step in (1e-2, 1e-3, 1e-4):
            for v in (notch * (1.0 - step), notch * (1.0 + step)):
                if low <= v <= high:
                    points.add(v)
    return sorted(points)


def _absorber_chart(s: AbsorberScene) -> Chart:
    from mdcalc.output.plot import Chart, Mark, Series

    _, high = s.resonances()
    span = max(2.0, 1.25 * high / s.omega)  # the range of the A₁(ω) table
    tuning = math.sqrt(s.cg / s.j2) / s.omega  # undamped, A₁ = 0 there
    curves: dict[str, tuple[list[float], list[float]]] = {
        "without the absorber, M₀/|c - J₁ω²|": ([], []),
        "|A₁|, the disk": ([], []),
        "|A₂|, the absorber disk": ([], []),
    }
    alone, first, second = curves.values()
    # and the design ratio itself, where the report gives the amplitudes
    for ratio in sorted({1.0, *_refined(np.linspace(0.0, span, CURVE_POINTS), [1.0, tuning])}):
        w = ratio * s.omega
        untuned = s.untuned(w)
        if untuned is not None:  # None at the disk's own resonance
            alone[0].append(ratio)
            alone[1].append(untuned)
        if s.determinant_is_zero(w):
            continue
        try:
            a1, a2 = s.amplitudes(w)
        except ZeroDivisionError:
            continue
        # |k_g - J₂ω²| at round-off: A₁ is 0 there (the notch), which no log axis shows
        notch = abs(complex(s.cg, w * s.bg) - s.j2 * w * w) <= 1e-9 * s.cg
        for (x, y), value in ((first, abs(a1)), (second, abs(a2))):
            if math.isfinite(value) and not (notch and x is first[0]):
                x.append(ratio)
                y.append(value)
    roles: tuple[Role, ...] = ("comparison", "result", "secondary")
    series = [
        Series(label, x, y, role)
        for (label, (x, y)), role in zip(curves.items(), roles, strict=True)
    ]
    if s.bg > 0.0 and (minimum := absorber_minimum(s)) is not None:
        depth, where = minimum
        series.append(Series("damped minimum of |A₁|", [where / s.omega], [depth], "event"))
    marks = [Mark("x", 1.0, f"ω of the torque, {s.omega:.4g} rad/s", "this-case")]
    if abs(tuning - 1.0) > 1e-9:
        marks.append(
            Mark("x", tuning, f"absorber tuned to √(c_g/J₂) = {tuning * s.omega:.4g}", "design")
        )
    return Chart(
        "Anti-resonance absorber (8.38): |A| against ω"
        + (f", b_g = {s.bg:g} N·m·s/rad" if s.bg > 0.0 else ", undamped (peaks cut by the grid)"),
        "ω/ω of the torque [-]",
        "amplitude |A| [rad]",
        [c for c in series if c.x],
        marks,
        y_log=True,
    )


def _clutch_chart(c: Clutch) -> Chart:
    from mdcalc.output.plot import Chart, Mark, Series

    x1, x2, lines = clutch_lines(c)
    n = c.loading_exponent
    twist = np.linspace(0.0, 1.1 * x2, 221)
    # M_max·(ξ/ξ_max)ⁿ: no power of ξ itself (c₀ and ξ may be far from 1)
    series = [
        Series("loading curve M = c₀·ξⁿ", twist.tolist(), (c.load_max * (twist / x2) ** n).tolist())
    ]
    roles: tuple[Role, ...] = ("comparison", "secondary", "comparison")
    for line, role in zip(lines, roles, strict=True):
        # the chord is a line over the working range only (it misses the origin)
        x = twist if line.offset == 0.0 else np.linspace(x1, 1.1 * x2, 101)
        series.append(
            Series(
                f"{line.key.replace('_', ' ')}: {line.stiffness:.4g} N·m/rad",
                x.tolist(),
                (line.offset + line.stiffness * x).tolist(),
                role,
            )
        )
    marks = [Mark("x", x2, "working range")]
    if x1 > 0.0:
        marks.append(Mark("x", x1))
    return Chart(
        f"Overrunning clutch: loading curve (8.42), n = {n:g}, and its lines over "
        f"{c.load_min:g} … {c.load_max:g} N·m",
        "clutch twist ξ [rad]",
        "moment M [N·m]",
        series,
        marks,
    )


def _mechanism_chart(m: Mechanism) -> Chart:
    from mdcalc.output.plot import Chart, Mark, Series

    t = transfer_of(m)
    x = np.linspace(-0.5 * t.stroke, 0.5 * t.stroke, 121).tolist()
    degrees = [math.degrees(v) for v in x]
    return Chart(
        f"Elementary mechanism (8.46): transfer functions over a stroke, z = {m.mechanisms}, "
        f"i_c = {t.ratio:.4g}",
        "α - α_c [deg]",
        "Π - φ_c [rad], Π′ [-], Π″ [1/rad]",
        [
            Series("Π′", degrees, [t.first(v) for v in x]),
            Series("Π″", degrees, [t.second(v) for v in x], "secondary"),
            Series("Π - φ_c", degrees, [t.position(v) for v in x], "secondary"),
        ],
        [Mark("y", 1.0 / t.ratio, "mean of Π′ = 1/i_c", "static")],
    )


def _stroke_times(state: periodic.Periodic, period: float) -> tuple[np.ndarray, bool]:
    """Times over [0, T] for q(τ), and whether they resolve the fastest mode: 16
    samples per its period, up to STROKE_SAMPLES; a mode too fast for that rings only
    after each jump of the load, so its first 8 decay times get their own samples."""
    fastest = state.fastest
    wanted = 16.0 * fastest * period / (2.0 * math.pi)
    uniform = np.linspace(0.0, period, int(min(max(wanted, 512.0), STROKE_SAMPLES)) + 1)
    if wanted <= STROKE_SAMPLES:
        return uniform, True
    decay = -float(np.max(state.eigenvalues.real[np.abs(state.eigenvalues) >= 0.5 * fastest]))
    if decay <= 0.0:
        return uniform, False
    span = min(period, 8.0 / decay)
    wanted = 16.0 * fastest * span / (2.0 * math.pi)
    dense = np.linspace(0.0, span, int(min(wanted, STROKE_SAMPLES)) + 1)
    return np.union1d(uniform, dense), wanted <= STROKE_SAMPLES


def _stroke_chart(result: Result) -> Chart:
    from mdcalc.output.plot import Chart, Mark, Series

    d, before = result.drive, result.two_mass
    assert d is not None and before is not None
    three = result.three_mass_state
    states = [
        (
            "before: J₃ rigid on J₂" if three is not None else "q/q_c",
            before,
            CLUTCH,
        )
    ]
    if three is not None:
        states.append(("after: coupling c₂ and J₃", three, np.array([1.0, 0.0, 0.0, 0.0])))
    series, resolved = [], True
    stroke = math.degrees(d.transfer.stroke)
    for label, state, w in states:
        tau, ok = _stroke_times(state, d.period)
        resolved = resolved and ok
        series.append(
            Series(
                label,
                (tau / d.period * stroke).tolist(),
                (state.observe(w, tau) / d.static).tolist(),
                "comparison" if label.startswith("before") else "result",
            )
        )
    return Chart(
        "Clutch deformation over one stroke, periodic state; χ = max q/q_c (8.47)"
        + ("" if resolved else " (the fastest mode's ringing is not resolved)"),
        "α - α₁, into the stroke [deg]",
        "q/q_c [-]",
        series,
        [Mark("y", 1.0, "static q_c = M_c/c", "static")],
    )


def _antiresonance_chart(before: DriveScene, three: ThreeMass) -> Chart:
    """|q₁| under u = U·e^(iνt), in units of its static value (J₂ + J₃')·U/c₁ (the
    same in both models): J·q″ + b·q′ + c·q = J·u before, the system of (7f) after."""
    from mdcalc.output.plot import Chart, Mark, Series

    fundamental = three.drive.fundamental  # Ω = zω
    j, c, b = before.inertia, before.stiffness, before.damping
    natural = max(math.sqrt(c / j), *three.natural_frequencies())
    top = max(4.0, 1.5 * natural / fundamental)
    zero = three.antiresonance / fundamental
    ratios = np.array(_refined(np.geomspace(0.05, top, CURVE_POINTS), [1.0, zero]))
    nu = ratios * fundamental
    static = j / c
    old = np.abs(j / (c - j * nu * nu + 1j * nu * b)) / static
    s = three.system()
    m = (
        s.stiffness[None, :, :]
        - (nu * nu)[:, None, None] * s.mass
        + 1j * nu[:, None, None] * s.damping
    )
    det = m[:, 0, 0] * m[:, 1, 1] - m[:, 0, 1] * m[:, 1, 0]
    one, two = s.shape[0] * m[:, 1, 1], m[:, 0, 1] * s.shape[1]
    with np.errstate(divide="ignore", invalid="ignore"):
        new = np.abs((one - two) / det) / static
    # q₁ = 0 to round-off (the anti-resonance itself), which no log axis shows
    new[np.abs(one - two) <= 1e-9 * (np.abs(one) + np.abs(two))] = np.nan
    series = []
    pairs: tuple[tuple[str, np.ndarray, Role], ...] = (
        ("before: J₃ rigid on J₂", old, "comparison"),
        ("after: coupling c₂ and J₃", new, "result"),
    )
    for label, values, role in pairs:
        keep = np.isfinite(values)
        series.append(Series(label, ratios[keep].tolist(), values[keep].tolist(), role))
    marks = [Mark("x", 1.0, f"Ω = zω = {fundamental:.4g} rad/s, the design", "design")]
    if abs(zero - 1.0) > 1e-9:
        marks.append(
            Mark("x", zero, f"clutch anti-resonance {three.antiresonance:.4g} rad/s", "resonance")
        )
    return Chart(
        "Anti-resonance (7f): the clutch under one harmonic ν of u = ω²Π″, before and after",
        "ν/Ω [-]",
        "|q₁| / ((J₂ + i²J₃)·|u|/c₁) [-]",
        series,
        marks,
        x_log=True,
        y_log=True,
    )


def _pendulum_chart(p: Pendulum) -> Chart:
    from mdcalc.output.plot import Chart, Mark, Series

    n = p.order
    top = (
        math.pi / 2
        if p.max_swing is None
        else min(0.95 * math.pi, max(2.0 * p.max_swing, math.pi / 3))
    )
    swings = np.linspace(0.0, top, 181).tolist()
    series = [
        Series(
            "free swing, n(θ)/n = AGM(1, cos(θ/2))",
            [agm(1.0, math.cos(0.5 * t)) for t in swings],
            [math.degrees(t) for t in swings],
        )
    ]
    marks = [Mark("x", 1.0, f"tuned: L = R/n² = {p.pivot_radius / n**2 * 1e3:.4g} mm", "design")]
    if p.max_swing is not None:
        factor = agm(1.0, math.cos(0.5 * p.max_swing))
        series.append(
            Series(
                f"at θ_max: order {n * factor:.4g}",
                [factor],
                [math.degrees(p.max_swing)],
                "this-case",
            )
        )
        marks.append(Mark("y", math.degrees(p.max_swing), "θ_max", "this-case"))
    return Chart(
        f"Centrifugal pendulum, order n = {n:g}: swing against its frequency ratio (backbone)",
        "n(θ)/n, the pendulum's order over its design order [-]",
        "swing amplitude θ [deg]",
        series,
        marks,
    )
