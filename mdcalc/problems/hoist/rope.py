"""The rope at start: the two-mass model, its closed forms (7.92)-(7.98), the ODE
reference with lift-off and touch-down."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import partial
from typing import Any

from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.sdof import rectangular_pulse_peak
from mdcalc.core.xp import of
from mdcalc.methods import Method, NotApplicable, compare
from mdcalc.output.report import MethodQuantity, MethodsTable

#: The ODE methods are not run past this many rope oscillation periods.
MAX_ODE_PERIODS = 3000


@dataclass(frozen=True)
class RopeScene:
    """The two-mass model at start. Its numbers are floats for one scene, or numpy
    arrays over a block of scenes (a study's samples): the closed forms below run
    on either (:mod:`mdcalc.core.xp`)."""

    c: Any  # rope stiffness [N/m]
    m1: Any  # drive mass on the rope line [kg]
    m2: Any  # load mass [kg]
    weight: Any  # G [N]
    acceleration: Any  # V/t_p [m/s²]
    start_time: Any  # t_p [s]
    slack: Any  # [m]

    @property
    def beta(self) -> Any:
        """Two-mass natural frequency √(c·(1/m1 + 1/m2)) [rad/s]."""
        return of(self.c, self.m1, self.m2).sqrt(self.c * (1.0 / self.m1 + 1.0 / self.m2))

    @property
    def drive_force(self) -> Any:
        """Drive force during the start: G + (m1 + m2)·a [N]."""
        return self.weight + (self.m1 + self.m2) * self.acceleration


def hanging_closed_form(r: RopeScene, beta: Any) -> dict[str, Any]:
    """(7.92)-(7.96) corrected: a rectangular force pulse m2·a of length t_p."""
    peak = r.weight + r.m2 * r.acceleration * rectangular_pulse_peak(beta, r.start_time)
    return {"peak_force": peak, "dynamic_factor": peak / r.weight}


def ground_closed_form(r: RopeScene, heavy_drive: bool) -> dict[str, float]:
    """Load lying on the ground: slack taken up, load lifts off, first peak
    (:func:`ground_peak`); raises NotApplicable where the closed form does not hold."""
    peak, limits = ground_peak(r, heavy_drive)
    for outside, reason in limits:
        if outside:
            raise NotApplicable(reason)
    return {"peak_force": peak, "dynamic_factor": peak / r.weight}


def ground_peak(r: RopeScene, heavy_drive: bool) -> tuple[Any, list[tuple[Any, str]]]:
    """The first peak of the rope force after lift-off, and the limits of the closed
    form in order, each (where it is broken, why); over arrays the peak is NaN or
    meaningless where a limit is broken.

    Exact for the two-mass model while the start lasts past the first peak. With
    ``heavy_drive`` the drive follows the uniform start exactly (m1 → ∞).
    """
    g_force, c, a = r.weight, r.c, r.acceleration
    xp = of(g_force, c, a, r.m1, r.m2, r.start_time, r.slack)
    if heavy_drive:
        # Drum end moves as a·t²/2: taut at s, lift-off at s + G/c.
        speed = xp.sqrt(2.0 * a * (r.slack + g_force / c))
        t_lift = speed / a
        beta = xp.sqrt(c / r.m2)
    else:
        force = r.drive_force
        t_slack = xp.sqrt(2.0 * r.slack * r.m1 / force)
        v_slack = force / r.m1 * t_slack
        beta1 = xp.sqrt(c / r.m1)
        # Drive on the rope with the load grounded: c·ξ = F - R·cos(β1·τ + θ).
        amplitude = xp.hypot(force, c * v_slack / beta1)
        theta = xp.atan2(c * v_slack / beta1, force)
        tau = (xp.acos((force - g_force) / amplitude) - theta) / beta1
        speed = amplitude * beta1 / c * xp.sin(beta1 * tau + theta)
        t_lift = t_slack + tau
        beta = r.beta
    # After lift-off the rope force oscillates about G + m2·a at β.
    w0 = -r.m2 * a / c
    phase = xp.atan2(speed / beta, w0)
    swing = c * xp.hypot(w0, speed / beta)
    limits = [
        (t_lift > r.start_time, "the load lifts off after the start has ended"),
        (t_lift + phase / beta > r.start_time, "the first peak comes after the start has ended"),
        # The rope goes slack after the peak and re-tightens with a jerk: later
        # peaks are not bounded by the first one.
        (swing > g_force + r.m2 * a, "the rope goes slack after the first peak"),
    ]
    # After the start the force swings about G with at most swing + m2·a: never higher.
    return g_force + r.m2 * a + swing, limits


#: Smooth pieces of one rope ODE run (each lift-off or touch-down starts one); the
#: shipped cases need 3. A load that keeps bouncing is a row that did not settle.
MAX_SEGMENTS = 200


def rope_ode(
    r: RopeScene, hanging: bool, rtol: float, max_periods: float | None = MAX_ODE_PERIODS
) -> dict[str, float]:
    """Integrate the two-mass model with ground contact, slack rope and the drive switch.

    State [x1, v1, y, vy]: drive and load positions on the rope line; rope force
    c·max(x1 - y - s, 0). Hanging: the rope starts stretched by G/c and there is no
    ground. On the ground: the load rests until the rope force reaches G.
    """
    import numpy as np

    from mdcalc.core.ode import advance, pick_solver

    c, m1, m2, s, gw = r.c, r.m1, r.m2, r.slack, r.weight
    t_p, beta = r.start_time, r.beta
    period = 2.0 * math.pi / beta
    if max_periods is not None and periods_to_integrate(r) > max_periods:
        raise NotApplicable(f"more than {max_periods:g} rope periods to integrate")

    def drive(t: float) -> float:
        return r.drive_force if t < t_p else gw

    def tension(y: np.ndarray) -> float:
        return c * max(y[0] - y[2] - s, 0.0)

    def air(t: float, y: np.ndarray) -> np.ndarray:
        f = tension(y)
        return np.array([y[1], (drive(t) - f) / m1, y[3], (f - gw) / m2])

    def ground(t: float, y: np.ndarray) -> np.ndarray:
        return np.array([y[1], (drive(t) - tension(y)) / m1, 0.0, 0.0])

    def stretch_rate(t: float, y: np.ndarray) -> float:
        return float(y[1] - y[3])

    method = pick_solver(rtol)
    scale = max(r.drive_force / c + s, 1e-12)
    atol = np.array([scale, scale * beta, scale, scale * beta]) * rtol * 1e-2
    if hanging:
        t, y, on_ground = 0.0, np.array([s + gw / c, 0.0, 0.0, 0.0]), False
    else:
        t, y, on_ground = 0.0, np.zeros(4), True
    peak = tension(y)
    t_lift = 0.0 if hanging else math.inf
    for _ in range(MAX_SEGMENTS):
        t_end = t_p if t < t_p else max(t_p, t_lift) + 2.0 * period
        if on_ground and t >= t_p:
            t_end = t + 4.0 * math.pi * math.sqrt(m1 / c) + 2.0 * period
        if t >= t_end and not on_ground:
            return {"peak_force": peak, "dynamic_factor": peak / gw}
        if on_ground:
            segment = advance(
                ground,
                t,
                y,
                t_end,
                rtol=rtol,
                atol=atol,
                method=method,
                terminal=[(lambda t, y: tension(y) - gw, 1)],
                watch=[(stretch_rate, -1)],
            )
        else:
            segment = advance(
                air,
                t,
                y,
                t_end,
                rtol=rtol,
                atol=atol,
                method=method,
                terminal=[(lambda t, y: y[2], -1)] if not hanging else [],
                watch=[(stretch_rate, -1)],
            )
        for _, _, state in segment.hits:
            peak = max(peak, tension(state))
        t, y = segment.t, segment.y
        peak = max(peak, tension(y))
        if segment.event is not None:
            if on_ground:  # lift-off
                on_ground, t_lift = False, t
            else:  # touch-down: the load stops on the ground
                on_ground, y = True, np.array([y[0], y[1], 0.0, 0.0])
    raise ArithmeticError(
        f"the rope ODE run did not settle: the load lifted off and touched down again "
        f"more than {MAX_SEGMENTS // 2} times"
    )


def periods_to_integrate(r: RopeScene) -> float:
    """Rope periods an ODE run covers: the start and two periods after it."""
    return r.start_time * r.beta / (2.0 * math.pi) + 2.0


ROPE_QUANTITIES = [
    MethodQuantity("peak_force", "F_max", "N"),
    MethodQuantity("dynamic_factor", "ψ", ""),
]


def rope_methods(r: RopeScene, hanging: bool) -> MethodsTable:
    heavy_beta = math.sqrt(r.c / r.m2)

    def hanging_run(rtol: float) -> dict[str, float]:  # (the ladder of --work-precision)
        return rope_ode(r, True, rtol)

    if hanging:
        methods = [
            Method(
                "lecture (7.95): G + 2·m2·V/t_p",
                lambda: _factor(r, r.weight + 2.0 * r.m2 * r.acceleration),
            ),
            Method(
                "closed form, heavy drive β = √(c/m2)", lambda: hanging_closed_form(r, heavy_beta)
            ),
            Method(
                "closed form, two-mass β (exact)",
                lambda: hanging_closed_form(r, r.beta),
                reference=True,
            ),
            *(
                Method(f"ODE RK45, rtol {rtol:.0e}".replace("e-0", "e-"),
                       partial(hanging_run, rtol), imports=ODE_IMPORTS, ladder=hanging_run)
                for rtol in (1e-3, 1e-6)
            ),
        ]  # fmt: skip
        title, key = "Methods: rope, load hanging at start", "rope_hanging"
    else:
        # The reference is the tight ODE run; when it would cover too many rope
        # periods and the two-mass closed form is valid, the closed form is exact
        # and takes its place (and the long run is not made).
        closed_form_valid = True
        try:
            ground_closed_form(r, False)
        except NotApplicable:
            closed_form_valid = False
        ode_reference = not closed_form_valid or periods_to_integrate(r) <= MAX_ODE_PERIODS

        def ground(rtol: float, periods: float | None = MAX_ODE_PERIODS) -> dict[str, float]:
            return rope_ode(r, False, rtol, periods)

        # the ladder: as the tight run, up to MAX_ODE_PERIODS where the closed form rules
        ladder = partial(ground, periods=None if ode_reference else MAX_ODE_PERIODS)
        methods = [
            Method(
                "lecture (7.98): 2·(G + m2·V/t_p)",
                lambda: _factor(r, 2.0 * (r.weight + r.m2 * r.acceleration)),
            ),
            Method("closed form, heavy drive", lambda: ground_closed_form(r, True)),
            Method(
                "closed form, two-mass",
                lambda: ground_closed_form(r, False),
                reference=not ode_reference,
                accuracy=3 if closed_form_valid else 0,
            ),
            Method(
                "ODE RK45, rtol 1e-3",
                partial(ground, 1e-3),
                imports=ODE_IMPORTS,
                accuracy=1,
                ladder=ladder,
                rtol=1e-3,
            ),
            Method(
                "ODE RK45, rtol 1e-6",
                partial(ground, 1e-6),
                imports=ODE_IMPORTS,
                accuracy=2,
                ladder=ladder,
                rtol=1e-6,
            ),
            Method(
                "ODE DOP853, rtol 1e-10",
                partial(ladder, 1e-10),
                imports=ODE_IMPORTS,
                reference=ode_reference,
                ladder=ladder,
                rtol=1e-10,
            ),
        ]
        title, key = "Methods: rope, load lying on the ground", "rope_ground"
    return compare(title, key, ROPE_QUANTITIES, methods)


def _factor(r: RopeScene, peak: float) -> dict[str, float]:
    return {"peak_force": peak, "dynamic_factor": peak / r.weight}
