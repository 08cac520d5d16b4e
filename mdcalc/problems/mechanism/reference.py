"""The ODE reference: the energy equation integrated over the angle, with a
budget and a dense solution."""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from mdcalc.problems.mechanism.case import TWO_PI
from mdcalc.problems.mechanism.kovylin import Stall
from mdcalc.problems.mechanism.scene import Scene

#: Right-hand-side evaluations an ODE row may use before it is reported as too long.
EVALUATION_BUDGET = 400_000


@dataclass
class Reference:
    final_speed: float
    final_time: float
    evaluations: int
    solver: str
    speed_at: Callable[[float], float]  # ω(φ)
    time_at: Callable[[float], float]  # t(φ)
    speeds_at: Callable[[list[float]], list[float]]  # ω at many angles, vectorized


def stiffness_of(scene: Scene) -> float:
    """|∂(dE/dφ)/∂E|·span = |C|/(I·ω)·span at the start (an estimate)."""
    if not scene.depends_on_speed:
        return 0.0
    i0 = scene.inertia(scene.start_angle)
    # speeds typical of the run: the start, and what the start torque gives over it
    gained = math.sqrt(
        2.0 * abs(scene.torque(scene.start_angle, scene.start_speed)) * scene.span / i0
    )
    candidates = [w for w in (scene.start_speed, 0.1 * gained, gained) if w > 0.0]
    worst = 0.0
    for omega in candidates:
        try:
            c = scene.slope(scene.start_angle, omega)
        except ArithmeticError:
            continue
        worst = max(worst, abs(c) / (i0 * omega) * scene.span)
    return worst


def reference(scene: Scene, rtol: float, method: str, budget: int = EVALUATION_BUDGET) -> Reference:
    """Integrate dE/dφ = M, dt/dφ = 1/ω from φ₀ to the end angle; raise :class:`Stall`
    where E reaches zero."""
    import numpy as np

    from mdcalc.core.ode import TooManySteps, advance

    count = [0]
    phi0 = scene.start_angle
    i0 = scene.inertia(phi0)
    e0 = 0.5 * i0 * scene.start_speed**2
    m0 = scene.torque(phi0, scene.start_speed)
    e_scale = max(e0, abs(m0) * scene.span, 1e-300)
    t_offset = 0.0
    if e0 == 0.0:
        # From rest E ≈ M₀·ε, t ≈ √(2·I₀·ε/M₀): start a hair after φ₀.
        if m0 <= 0.0:
            raise Stall(phi0, 0.0)
        eps = 1e-12 * scene.span
        phi0, e0 = phi0 + eps, m0 * eps
        t_offset = math.sqrt(2.0 * i0 * eps / m0)
    floor = 1e-13 * e_scale

    def rhs(phi: float, y: np.ndarray) -> Any:
        count[0] += 1
        if count[0] > budget:
            raise TooManySteps(f"{method} stopped after {budget} evaluations")
        energy = max(y[0], floor)
        omega = math.sqrt(2.0 * energy / scene.inertia(phi))
        return np.array([scene.torque(phi, omega), 1.0 / omega])

    t_scale = scene.span / max(scene.start_speed, math.sqrt(2 * e_scale / i0))
    atol = np.array([e_scale, t_scale]) * rtol * 1e-3
    # Integrate from kink to kink of the tables: a step across a kink of M or I is
    # rejected again and again and leaves an error no tolerance controls.
    ends = [*knots_between(scene, phi0, scene.end_angle), scene.end_angle]
    starts: list[float] = []
    pieces: list[Callable[[Any], Any]] = []
    y = np.array([e0, t_offset])
    at = phi0
    for end in ends:
        segment = advance(
            rhs,
            at,
            y,
            end,
            rtol=rtol,
            atol=atol,
            method=method,
            terminal=[(lambda phi, y: y[0] - floor, -1)],
            dense=True,
        )
        if segment.sol is not None:
            starts.append(at)
            pieces.append(segment.sol)
        at, y = segment.t, segment.y
        if segment.event is not None:
            break
    if segment.event is not None:
        # E falls linearly to zero with slope M, t as 2·Δφ/ω: extrapolate the last hair
        phi_s, (e_s, t_s) = segment.t, segment.y
        omega_s = math.sqrt(2.0 * max(e_s, 0.0) / scene.inertia(phi_s))
        m_s = scene.torque(phi_s, omega_s)
        rest = max(e_s, 0.0) / -m_s if m_s < 0.0 else 0.0
        raise Stall(phi_s + rest, t_s + (2.0 * rest / omega_s if omega_s > 0 else 0.0))
    start = phi0

    def sol(phi: Any) -> Any:
        """The dense solution, piece by piece; ``phi`` a number or an array."""
        if np.ndim(phi) == 0:
            k = max(bisect.bisect_right(starts, float(phi)) - 1, 0)
            return pieces[k](phi)
        angles = np.asarray(phi, dtype=float)
        index = np.clip(np.searchsorted(starts, angles, side="right") - 1, 0, len(pieces) - 1)
        out = np.empty((2, angles.size))
        for k in np.unique(index).tolist():
            chosen = index == k
            out[:, chosen] = pieces[k](angles[chosen])
        return out

    def speed_at(phi: float) -> float:
        if phi <= start:
            return scene.start_speed
        return math.sqrt(2.0 * max(float(sol(phi)[0]), 0.0) / scene.inertia(phi))

    def time_at(phi: float) -> float:
        return 0.0 if phi <= start else float(sol(phi)[1])

    def speeds_at(angles: list[float]) -> list[float]:
        energies = sol(np.clip(np.array(angles), start, scene.end_angle))[0]
        return [
            scene.start_speed if a <= start else math.sqrt(2.0 * max(e, 0.0) / scene.inertia(a))
            for a, e in zip(angles, energies.tolist(), strict=True)
        ]

    e_end, t_end = segment.y
    return Reference(
        math.sqrt(2.0 * e_end / scene.inertia(scene.end_angle)),
        float(t_end),
        count[0],
        method,
        speed_at,
        time_at,
        speeds_at,
    )


#: Beyond this many table kinks over the run the reference integrates across them.
MAX_SEGMENTS = 4000


def knots_between(scene: Scene, start: float, end: float) -> list[float]:
    """The tables' knots strictly between ``start`` and ``end``, in order."""
    if not scene.breaks:
        return []
    first = math.floor(start / TWO_PI)
    out: list[float] = []
    turn = first
    while turn * TWO_PI < end:
        for b in scene.breaks:
            angle = turn * TWO_PI + b
            if start + 1e-12 * TWO_PI < angle < end - 1e-12 * TWO_PI:
                out.append(angle)
                if len(out) > MAX_SEGMENTS:
                    return []
        turn += 1
    return out
