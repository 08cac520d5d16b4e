"""Longitudinal motion of a vehicle under constant forces and quadratic drag.

Closed forms shared by ``braking`` (reaction, build-up and braking phases) and
``acceleration`` (the gear shift: no traction, resistances acting). ``mass`` is
the effective mass: the vehicle mass times its rotating-mass factor where the
problem has one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Phase:
    """Motion over one phase: speed at its end, distance and time it took."""

    speed: float
    distance: float
    time: float

    @property
    def stopped(self) -> bool:
        return self.speed == 0.0


def constant_force_phase(
    v0: float, force: float, drag: float, mass: float, duration: float | None
) -> Phase:
    """m·dv/dt = -(force + drag·v²) from v0 for ``duration`` or until the stop.

    Closed forms: without drag, uniform deceleration; with drag and force > 0,
    v = s·tan(θ0 - ω·t), s = √(F/k), ω = √(F·k)/m; with drag alone, v = v0/(1 + k·v0·t/m).
    """
    if v0 == 0.0:
        return Phase(0.0, 0.0, 0.0)
    if drag == 0.0:
        if force == 0.0:
            assert duration is not None, "no force and no drag: the car never stops"
            return Phase(v0, v0 * duration, duration)
        a = force / mass
        t_stop = v0 / a
        if duration is None or duration >= t_stop:
            return Phase(0.0, v0 * v0 / (2.0 * a), t_stop)
        return Phase(v0 - a * duration, v0 * duration - 0.5 * a * duration**2, duration)
    if force == 0.0:
        assert duration is not None, "drag alone never stops the car"
        u = drag * v0 * duration / mass
        return Phase(v0 / (1.0 + u), mass / drag * math.log1p(u), duration)
    s = math.sqrt(force / drag)
    omega = math.sqrt(force * drag) / mass
    theta0 = math.atan(v0 / s)
    t_stop = theta0 / omega
    if duration is None or duration >= t_stop:
        # x = (m/k)·ln(cos(θ0 - ωt)/cos θ0) at the stop: (m/2k)·ln(1 + k·v0²/F)
        return Phase(0.0, mass / (2.0 * drag) * math.log1p(drag * v0 * v0 / force), t_stop)
    theta = theta0 - omega * duration
    distance = mass / drag * math.log(math.cos(theta) / math.cos(theta0))
    return Phase(s * math.tan(theta), distance, duration)


def ramp_phase(v0: float, base: float, rise: float, mass: float, duration: float) -> Phase:
    """m·dv/dt = -(base + rise·t/duration), no drag: the brake build-up phase."""
    if v0 == 0.0 or duration == 0.0:
        return Phase(v0, 0.0, 0.0)
    a0 = base / mass
    jerk = rise / (mass * duration)
    v_end = v0 - a0 * duration - 0.5 * jerk * duration**2
    if v_end > 0.0:
        distance = v0 * duration - 0.5 * a0 * duration**2 - jerk * duration**3 / 6.0
        return Phase(v_end, distance, duration)
    # Stop inside the ramp: jerk/2·τ² + a0·τ - v0 = 0, the root in a cancellation-free form.
    tau = 2.0 * v0 / (a0 + math.sqrt(a0 * a0 + 2.0 * jerk * v0))
    distance = v0 * tau - 0.5 * a0 * tau**2 - jerk * tau**3 / 6.0
    return Phase(0.0, distance, tau)


# ------------------------------------------------------------------ array forms
#
# The same closed forms over numpy arrays, for ``mdcalc sweep``: every branch is
# evaluated where it applies (np.where), so one call covers a grid of scenes. The
# scalar functions above stay numpy-free: a single braking run must not pay
# numpy's import. tests/test_sweep.py holds the two forms together point by point.


@dataclass(frozen=True)
class Phases:
    """:class:`Phase` over arrays."""

    speed: Any
    distance: Any
    time: Any


def constant_force_phase_array(
    v0: Any, force: Any, drag: Any, mass: Any, duration: Any | None
) -> Phases:
    """:func:`constant_force_phase` over arrays; ``duration`` None: until the stop.

    The caller guarantees a stop where ``duration`` is None (force > 0 there).
    """
    import numpy as np

    v0, force, drag, mass = np.broadcast_arrays(*map(np.asarray, (v0, force, drag, mass)))
    span = np.full(v0.shape, np.inf) if duration is None else np.broadcast_to(duration, v0.shape)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        no_drag = drag == 0.0
        no_force = force == 0.0
        # No drag: uniform deceleration a = F/m (a = 0: coasting).
        a = force / mass
        t_stop_uniform = np.where(no_force, np.inf, v0 / a)
        # Drag and force: v = s·tan(θ0 - ω·t).
        s = np.sqrt(force / drag)
        omega = np.sqrt(force * drag) / mass
        theta0 = np.arctan(v0 / s)
        t_stop_drag = np.where(no_force, np.inf, theta0 / omega)
        t_stop = np.where(no_drag, t_stop_uniform, t_stop_drag)
        stops = span >= t_stop
        t = np.where(stops, t_stop, span)
        # Speeds and distances of each branch at t.
        uniform_v = np.where(stops, 0.0, v0 - a * t)
        uniform_x = np.where(stops, v0 * v0 / (2.0 * a), v0 * t - 0.5 * a * t * t)
        coast_x = v0 * t
        u = drag * v0 * t / mass
        drag_only_v = v0 / (1.0 + u)
        drag_only_x = mass / drag * np.log1p(u)
        theta = theta0 - omega * t
        both_v = np.where(stops, 0.0, s * np.tan(theta))
        both_x = np.where(
            stops,
            mass / (2.0 * drag) * np.log1p(drag * v0 * v0 / force),
            mass / drag * np.log(np.cos(theta) / np.cos(theta0)),
        )
        speed = np.where(
            no_drag, np.where(no_force, v0, uniform_v), np.where(no_force, drag_only_v, both_v)
        )
        distance = np.where(
            no_drag, np.where(no_force, coast_x, uniform_x), np.where(no_force, drag_only_x, both_x)
        )
    moving = v0 != 0.0
    return Phases(
        np.where(moving, speed, 0.0), np.where(moving, distance, 0.0), np.where(moving, t, 0.0)
    )


def ramp_phase_array(v0: Any, base: Any, rise: Any, mass: Any, duration: Any) -> Phases:
    """:func:`ramp_phase` over arrays."""
    import numpy as np

    v0, base, rise, mass, duration = np.broadcast_arrays(
        *map(np.asarray, (v0, base, rise, mass, duration))
    )
    with np.errstate(divide="ignore", invalid="ignore"):
        a0 = base / mass
        jerk = rise / (mass * duration)
        v_end = v0 - a0 * duration - 0.5 * jerk * duration**2
        through = v_end > 0.0
        tau = np.where(through, duration, 2.0 * v0 / (a0 + np.sqrt(a0 * a0 + 2.0 * jerk * v0)))
        distance = v0 * tau - 0.5 * a0 * tau**2 - jerk * tau**3 / 6.0
        speed = np.where(through, v_end, 0.0)
    idle = (v0 == 0.0) | (duration == 0.0)
    return Phases(
        np.where(idle, v0, speed), np.where(idle, 0.0, distance), np.where(idle, 0.0, tau)
    )
