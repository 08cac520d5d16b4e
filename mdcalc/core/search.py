"""Searches shared by the problems: on floats (pure Python, no numpy) or, the same
steps, on arrays of brackets (one search a row)."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from mdcalc.core.xp import of

GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def golden_maximum(f: Callable[[Any], Any], low: Any, high: Any, iterations: int) -> Any:
    """The argument of a maximum of a unimodal ``f`` on [low, high], by golden section
    (the bracket shrinks by 0.618 an iteration); the midpoint of the last bracket.
    Floats, or arrays of brackets searched at once (``f`` then takes an array)."""
    xp = of(low, high)
    for _ in range(iterations):
        a = high - GOLDEN * (high - low)
        b = low + GOLDEN * (high - low)
        low, high = xp.where(
            f(a) > f(b), lambda low=low, b=b: (low, b), lambda a=a, high=high: (a, high)
        )
    return 0.5 * (low + high)
