"""Scalar searches shared by the problems (pure Python, no numpy)."""

from __future__ import annotations

import math
from collections.abc import Callable

GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def golden_maximum(f: Callable[[float], float], low: float, high: float, iterations: int) -> float:
    """The argument of a maximum of a unimodal ``f`` on [low, high], by golden section
    (the bracket shrinks by 0.618 an iteration); the midpoint of the last bracket."""
    for _ in range(iterations):
        a = high - GOLDEN * (high - low)
        b = low + GOLDEN * (high - low)
        if f(a) > f(b):
            high = b
        else:
            low = a
    return 0.5 * (low + high)
