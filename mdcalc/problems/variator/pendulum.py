"""7g: the centrifugal pendulum absorber (8.49)-(8.56): its tuned length, the
arithmetic-geometric mean of its large-swing period, the mass and whether its bob
fits. Written once for a scene's floats and a block's arrays."""

from __future__ import annotations

import math
from typing import Any

from mdcalc.core.xp import of
from mdcalc.problems.variator.case import Pendulum


def agm(a: Any, b: Any) -> Any:
    """Arithmetic–geometric mean (of each row of a block; a row stops where it has
    converged, as one alone would)."""
    import numpy as np

    xp = of(a, b)
    done: Any = False
    for _ in range(64):
        a, b = xp.where(
            done, lambda a=a, b=b: (a, b), lambda a=a, b=b: (0.5 * (a + b), xp.sqrt(a * b))
        )
        done = done | (abs(a - b) <= 1e-16 * a)
        if np.all(done):
            break
    return a


def pendulum_values(p: Pendulum) -> dict[str, Any]:
    """Every number of the pendulum's section, by result key (those the case's
    fields allow)."""
    r, n = p.pivot_radius, p.order
    length = r / (n * n)
    values: dict[str, Any] = {"pendulum_length": length, "pendulum_length_ratio": length / r}
    omega = p.omega
    if omega is not None:
        values["pendulum_frequency"] = n * omega
    if p.max_swing is not None:
        factor = agm(1.0, of(p.max_swing).cos(0.5 * p.max_swing))
        values["pendulum_order_at_swing"] = n * factor
        values["pendulum_length_at_swing"] = length * factor**2
    if p.inertia_torque is not None and omega is not None and p.max_swing is not None:
        mass = p.inertia_torque / (omega * omega * (r + length) * r * p.max_swing)
        values["pendulum_mass"] = mass
        values["pendulum_bob_radius"] = (3.0 * mass / (4.0 * math.pi * p.bob_density)) ** (
            1.0 / 3.0
        )
    if p.bifilar_pin_diameter is not None:
        values["pendulum_bifilar_hole"] = p.bifilar_pin_diameter + length
    return values
