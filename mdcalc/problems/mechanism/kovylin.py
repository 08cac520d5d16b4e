"""Kovylin's linearized step (seed 001) and the energy step: the path over the angle."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from mdcalc.core.xp import of
from mdcalc.problems.mechanism.scene import Scene

#: Largest number of halvings of one Kovylin step (2⁻³⁰ of the user's step).
MAX_REFINEMENT = 30

#: Kovylin's assumption (3) needs a small increment: a step whose |Δω| exceeds this
#: fraction of ω_i is halved.
MAX_INCREMENT = 0.5


class Stall(ArithmeticError):
    """ω reaches zero: the torque cannot carry the mechanism on."""

    def __init__(self, angle: float, time: float) -> None:
        super().__init__(f"stalls at φ = {angle:.6g} rad")
        self.angle = angle
        self.time = time


@dataclass
class Path:
    """ω and t at the nodes φ₀ + k·Δφ."""

    angles: list[float]
    speeds: list[float]
    times: list[float]
    refined: int = 0  # steps that had to be halved


def kovylin_step(scene: Scene, phi: Any, omega: Any, dphi: Any) -> Any:
    """ω_k after one step by (5), or from rest by the quadratic; missing (None for
    a float, NaN in an array) when the step is not acceptable (denominator or ω_k
    not positive, increment too large). Floats or arrays over a block of scenes."""
    xp = of(phi, omega, dphi)
    phi_k = phi + dphi
    i_i, i_k = scene.inertia(phi), scene.inertia(phi_k)
    m_mean = 0.5 * (scene.torque(phi, omega) + scene.torque(phi_k, omega))
    c = scene.slope(phi_k, omega) if scene.depends_on_speed else 0.0

    def from_rest() -> Any:
        # (1) with M′ + ½·C·ω_k over the step: I_k·ω_k² - C·Δφ·ω_k - 2·M′·Δφ = 0
        disc = (c * dphi) ** 2 + 8.0 * i_k * m_mean * dphi
        return xp.where(
            (m_mean > 0.0) & (disc > 0.0),
            lambda: (c * dphi + xp.sqrt(disc)) / (2.0 * i_k),
            lambda: xp.missing,
        )

    def moving() -> Any:
        denominator = 2.0 * i_k * omega - c * dphi

        def stepped() -> Any:
            delta = (2.0 * m_mean * dphi + (i_i - i_k) * omega * omega) / denominator
            return xp.where(
                (xp.abs(delta) > MAX_INCREMENT * omega) | (omega + delta <= 0.0),
                lambda: xp.missing,
                lambda: omega + delta,
            )

        return xp.where(denominator > 0.0, stepped, lambda: xp.missing)

    return xp.where(omega == 0.0, from_rest, moving)


def energy_step(scene: Scene, phi: Any, omega: Any, dphi: Any) -> Any:
    """ω_k from (1) with the torque of (4) but without (3): the root of
    I_k·ω_k² - C·Δφ·ω_k - (I_i·ω_i² + 2·M′·Δφ - C·Δφ·ω_i) = 0; missing without a
    positive root."""
    xp = of(phi, omega, dphi)
    phi_k = phi + dphi
    i_i, i_k = scene.inertia(phi), scene.inertia(phi_k)
    m_mean = 0.5 * (scene.torque(phi, omega) + scene.torque(phi_k, omega))
    c = scene.slope(phi_k, omega) if scene.depends_on_speed else 0.0
    b = c * dphi
    free = i_i * omega * omega + 2.0 * m_mean * dphi - b * omega
    disc = b * b + 4.0 * i_k * free

    def root() -> Any:
        r = xp.sqrt(disc)
        # the larger root, without cancellation when b > 0
        value = xp.where(b >= 0.0, lambda: (b + r) / (2.0 * i_k), lambda: 2.0 * free / (r - b))
        return xp.where(value > 0.0, lambda: value, lambda: xp.missing)

    return xp.where(disc < 0.0, lambda: xp.missing, root)


def kovylin(scene: Scene, steps_per_revolution: int, quadratic: bool = False) -> Path:
    """ω(φ) and t(φ) by (5) at ``steps_per_revolution`` nodes a revolution (or by
    :func:`energy_step`, ``quadratic``)."""
    count = max(1, math.ceil(scene.revolutions * steps_per_revolution - 1e-9))
    dphi = scene.span / count
    phi, omega, t = scene.start_angle, scene.start_speed, 0.0
    path = Path([phi], [omega], [t])
    for _ in range(count):
        phi, omega, t, halved = _advance(scene, phi, omega, t, dphi, quadratic)
        path.refined += halved
        path.angles.append(phi)
        path.speeds.append(omega)
        path.times.append(t)
    return path


def _advance(
    scene: Scene, phi: float, omega: float, t: float, dphi: float, quadratic: bool
) -> tuple[float, float, float, int]:
    """One node step, halved where (5) cannot take it whole."""
    end = phi + dphi
    h, halved = dphi, 0
    while phi < end:
        h = min(h, end - phi)
        step = energy_step if quadratic else kovylin_step
        nxt = step(scene, phi, omega, h)
        if nxt is None:
            if h < dphi * 2.0**-MAX_REFINEMENT:
                raise Stall(phi, t)
            h *= 0.5
            halved = 1
            continue
        t += 2.0 * h / (omega + nxt)  # ω linear in t over the step
        phi = phi + h if end - phi > h * (1 + 1e-12) else end
        omega = nxt
        h = min(2.0 * h, dphi)  # grow back after a refined stretch
    return end, omega, t, halved
