"""7g: the centrifugal pendulum absorber: the arithmetic-geometric mean of its
large-swing period."""

from __future__ import annotations

import math


def agm(a: float, b: float) -> float:
    """Arithmetic–geometric mean."""
    for _ in range(64):
        a, b = 0.5 * (a + b), math.sqrt(a * b)
        if abs(a - b) <= 1e-16 * a:
            break
    return a
