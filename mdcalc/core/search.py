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


def highest_fall(slopes: Any, values: Any) -> tuple[Any, Any]:
    """Of each row's scan of a bracket (a function's slopes and values at its points,
    (rows, points)), the step whose slope falls from + to - (or to 0) with the
    highest value at its ends, where a peak lies: its index, and whether the row has
    such a step."""
    import numpy as np

    change = (slopes[:, :-1] > 0.0) & (slopes[:, 1:] <= 0.0)
    score = np.where(change, np.maximum(values[:, :-1], values[:, 1:]), -np.inf)
    return np.argmax(score, axis=1), change.any(axis=1)
