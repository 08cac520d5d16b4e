"""Longitudinal motion of a vehicle under constant forces and quadratic drag.

Closed forms shared by ``braking`` (reaction, build-up and braking phases) and
``acceleration`` (the gear shift: no traction, resistances acting). ``mass`` is
the effective mass: the vehicle mass times its rotating-mass factor where the
problem has one. Each takes floats (one scene, pure Python) or numpy arrays (a
sweep's grid of scenes) through the same formula (:mod:`mdcalc.core.xp`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from mdcalc.core.xp import FLOATS, of


@dataclass(frozen=True)
class Phase:
    """Motion over one phase: speed at its end, distance and time it took (floats, or
    arrays over a grid)."""

    speed: Any
    distance: Any
    time: Any

    @property
    def stopped(self) -> Any:
        return self.speed == 0.0


def constant_force_phase(v0: Any, force: Any, drag: Any, mass: Any, duration: Any | None) -> Phase:
    """m·dv/dt = -(force + drag·v²) from v0 for ``duration`` or until the stop.

    Closed forms: without drag, uniform deceleration; with drag and force > 0,
    v = s·tan(θ0 - ω·t), s = √(F/k), ω = √(F·k)/m; with drag alone, v = v0/(1 + k·v0·t/m).
    ``duration`` None (until the stop) needs force > 0 wherever the car moves: with
    no force the car never stops.
    """
    xp = of(v0, force, drag, mass, duration)
    span = xp.inf if duration is None else duration

    def coasting() -> tuple[Any, Any, Any]:
        # A float takes this branch only where it applies; an array blends it away.
        assert duration is not None or xp is not FLOATS, "no force, no drag: never stops"
        return v0, v0 * span, span

    def uniform() -> tuple[Any, Any, Any]:
        a = force / mass
        t_stop = v0 / a
        return xp.where(
            span >= t_stop,
            lambda: (0.0, v0 * v0 / (2.0 * a), t_stop),
            lambda: (v0 - a * span, v0 * span - 0.5 * a * span**2, span),
        )

    def drag_alone() -> tuple[Any, Any, Any]:
        assert duration is not None or xp is not FLOATS, "drag alone never stops the car"
        u = drag * v0 * span / mass
        return v0 / (1.0 + u), mass / drag * xp.log1p(u), span

    def drag_and_force() -> tuple[Any, Any, Any]:
        s = xp.sqrt(force / drag)
        omega = xp.sqrt(force * drag) / mass
        theta0 = xp.atan(v0 / s)
        t_stop = theta0 / omega

        def moving() -> tuple[Any, Any, Any]:
            theta = theta0 - omega * span
            distance = mass / drag * xp.log(xp.cos(theta) / xp.cos(theta0))
            return s * xp.tan(theta), distance, span

        # x = (m/k)·ln(cos(θ0 - ωt)/cos θ0) at the stop: (m/2k)·ln(1 + k·v0²/F)
        return xp.where(
            span >= t_stop,
            lambda: (0.0, mass / (2.0 * drag) * xp.log1p(drag * v0 * v0 / force), t_stop),
            moving,
        )

    speed, distance, time = xp.where(
        v0 == 0.0,
        lambda: (0.0, 0.0, 0.0),
        lambda: xp.where(
            drag == 0.0,
            lambda: xp.where(force == 0.0, coasting, uniform),
            lambda: xp.where(force == 0.0, drag_alone, drag_and_force),
        ),
    )
    return Phase(speed, distance, time)


def ramp_phase(v0: Any, base: Any, rise: Any, mass: Any, duration: Any) -> Phase:
    """m·dv/dt = -(base + rise·t/duration), no drag: the brake build-up phase."""
    xp = of(v0, base, rise, mass, duration)

    def ramp() -> tuple[Any, Any, Any]:
        a0 = base / mass
        jerk = rise / (mass * duration)
        v_end = v0 - a0 * duration - 0.5 * jerk * duration**2

        def through() -> tuple[Any, Any, Any]:
            distance = v0 * duration - 0.5 * a0 * duration**2 - jerk * duration**3 / 6.0
            return v_end, distance, duration

        def stops() -> tuple[Any, Any, Any]:
            # Stop inside the ramp: jerk/2·τ² + a0·τ - v0 = 0, the root in a
            # cancellation-free form.
            tau = 2.0 * v0 / (a0 + xp.sqrt(a0 * a0 + 2.0 * jerk * v0))
            distance = v0 * tau - 0.5 * a0 * tau**2 - jerk * tau**3 / 6.0
            return 0.0, distance, tau

        return xp.where(v_end > 0.0, through, stops)

    speed, distance, time = xp.where((v0 == 0.0) | (duration == 0.0), lambda: (v0, 0.0, 0.0), ramp)
    return Phase(speed, distance, time)
