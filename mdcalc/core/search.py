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
    The inner point that stays in the bracket keeps its value, so that an iteration
    evaluates ``f`` once (at the new point), 2 + iterations - 1 evaluations in all.
    Floats, or arrays of brackets searched at once (``f`` then takes an array)."""
    xp = of(low, high)
    a = high - GOLDEN * (high - low)
    b = low + GOLDEN * (high - low)
    fa, fb = f(a), f(b)
    for i in range(iterations):
        left = fa > fb  # the maximum is in [low, b], where a stays; else in [a, high]
        low, high, kept, f_kept = xp.where(
            left,
            lambda low=low, a=a, b=b, fa=fa: (low, b, a, fa),
            lambda a=a, b=b, high=high, fb=fb: (a, high, b, fb),
        )
        if i == iterations - 1:
            break
        new = xp.where(
            left,
            lambda low=low, high=high: high - GOLDEN * (high - low),
            lambda low=low, high=high: low + GOLDEN * (high - low),
        )
        f_new = f(new)
        a, b, fa, fb = xp.where(
            left,
            lambda new=new, kept=kept, f_new=f_new, f_kept=f_kept: (new, kept, f_new, f_kept),
            lambda new=new, kept=kept, f_new=f_new, f_kept=f_kept: (kept, new, f_kept, f_new),
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
