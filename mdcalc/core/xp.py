"""One formula for floats and numpy arrays.

A closed form in ``core/`` (and a problem's scene) is written once against a
namespace ``xp = of(*inputs)``: the single scene of a command passes floats and gets
:data:`FLOATS` (the ``math`` module and a plain ``if``), so it imports no numpy; a
sweep passes numpy arrays over its grid and gets numpy, the same formula evaluated
point by point at once. The two agree to round-off (tests/test_sweep_kernels.py).

``xp.where(condition, then, otherwise)`` takes its branches as functions: for a
float only the branch that applies runs (so ``math.sqrt`` of a negative number in
the other one never raises); for arrays both run under ``np.errstate(all="ignore")``
and are blended, so the branch that does not apply may produce inf or nan freely
(a condition that holds everywhere, or nowhere, on the grid runs only its branch).
A branch may give a tuple of results: they are blended one by one. A condition that
is one value (the inputs it depends on are not varied) runs one branch, as for a
float: a branch's arithmetic on plain floats would raise where numpy's gives inf.
``xp.missing`` is what a branch without a value gives: None for a float, nan in an
array.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import cache
from typing import Any

#: Types that take the float path (numpy's float64 is a float subclass: it does too).
SCALARS = (float, int, complex)


class Floats:
    """The namespace of a single scene: ``math`` and plain conditionals."""

    missing: Any = None
    pi = math.pi
    inf = math.inf
    sqrt = staticmethod(math.sqrt)
    exp = staticmethod(math.exp)
    log = staticmethod(math.log)
    log1p = staticmethod(math.log1p)
    expm1 = staticmethod(math.expm1)
    cos = staticmethod(math.cos)
    sin = staticmethod(math.sin)
    tan = staticmethod(math.tan)
    acos = staticmethod(math.acos)
    atan = staticmethod(math.atan)
    atan2 = staticmethod(math.atan2)
    hypot = staticmethod(math.hypot)
    degrees = staticmethod(math.degrees)
    abs = staticmethod(abs)
    minimum = staticmethod(min)
    maximum = staticmethod(max)

    @staticmethod
    def where(condition: Any, then: Callable[[], Any], otherwise: Callable[[], Any]) -> Any:
        return then() if condition else otherwise()


class Arrays:
    """The namespace of a grid of scenes: numpy, errors silenced inside branches."""

    missing: Any = math.nan
    pi = math.pi
    inf = math.inf

    def __init__(self) -> None:
        import numpy as np

        self._np = np
        self.sqrt = np.sqrt
        self.exp = np.exp
        self.log = np.log
        self.log1p = np.log1p
        self.expm1 = np.expm1
        self.cos = np.cos
        self.sin = np.sin
        self.tan = np.tan
        self.acos = np.arccos
        self.atan = np.arctan
        self.atan2 = np.arctan2
        self.hypot = np.hypot
        self.degrees = np.degrees
        self.abs = np.abs
        self.minimum = np.minimum
        self.maximum = np.maximum

    def where(self, condition: Any, then: Callable[[], Any], otherwise: Callable[[], Any]) -> Any:
        np = self._np
        with np.errstate(all="ignore"):
            if np.ndim(condition) == 0:  # one scene's condition: one branch, as for floats
                return then() if condition else otherwise()
            everywhere = bool(np.all(condition))
            if everywhere or not np.any(condition):
                # One branch holds over the whole grid: only it runs, spread over the
                # grid's shape as a blend would be (a read-only view, not a copy).
                chosen = then() if everywhere else otherwise()
                if isinstance(chosen, tuple):
                    return tuple(_spread(np, a, np.shape(condition)) for a in chosen)
                return _spread(np, chosen, np.shape(condition))
            chosen, other = then(), otherwise()
            if isinstance(chosen, tuple):  # several results of one branch, blended alike
                return tuple(np.where(condition, a, b) for a, b in zip(chosen, other, strict=True))
            return np.where(condition, chosen, other)


def _spread(np: Any, value: Any, shape: tuple[int, ...]) -> Any:
    """``value`` over ``shape`` (and its own), as ``np.where`` would shape it."""
    return np.broadcast_to(value, np.broadcast_shapes(np.shape(value), shape))


FLOATS = Floats()


@cache
def arrays() -> Arrays:
    return Arrays()


def of(*values: Any) -> Any:
    """:data:`FLOATS` when every value is a plain number (or None), else numpy's
    namespace. Typed ``Any``: both namespaces have the same attributes."""
    for value in values:
        if value is not None and not isinstance(value, SCALARS):
            return arrays()
    return FLOATS
