"""7c: the clutch loading curve M = c₀·ξⁿ (8.42) and its lines over the working
range. Written once for a scene's floats and a block's arrays."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from mdcalc.core.xp import of
from mdcalc.problems.variator.case import Clutch


@dataclass(frozen=True)
class ClutchLine:
    name: str
    key: str
    stiffness: Any  # slope [N·m/rad]
    offset: Any  # M at ξ = 0 of the line [N·m] (0: through the origin)
    error: Any  # max |line - curve| over the range / M_max [-]


def clutch_lines(c: Clutch) -> tuple[Any, Any, list[ClutchLine]]:
    """ξ range of the working loads and three lines through the curve M = c₀·ξⁿ.

    Written in y = ξ/ξ_max and r = ξ_min/ξ_max so that no power of ξ itself is formed
    (c₀ and ξ may be far from 1): the curve is M_max·yⁿ, the least-squares slope
    through the origin 3·(M_max/ξ_max)·(1 - r^(n+2))/((n + 2)(1 - r³))."""
    n, m1, m2, c0 = c.loading_exponent, c.load_min, c.load_max, c.c0
    xp = of(n, m1, m2, c0)
    x2 = xp.exp((xp.log(m2) - xp.log(c0)) / n)
    # ℓ = ln r = ln(M_min/M_max)/n, and 1 - rᵖ = -expm1(p·ℓ): a narrow range keeps
    # its digits (1 - r would cancel)
    ell = xp.where(m1 == 0.0, lambda: -xp.inf, lambda: xp.log1p((m1 - m2) / m2) / n)
    r = xp.exp(ell)
    x1 = r * x2
    unit = m2 / x2  # slope that reaches M_max at ξ_max
    squares = 3.0 * unit * xp.expm1((n + 2) * ell) / ((n + 2) * xp.expm1(3.0 * ell))
    chord = (m2 - m1) / (-x2 * xp.expm1(ell))
    lines = []
    for name, key, slope, offset in (
        ("secant to the top of the range, M_max/ξ_max", "secant", unit, 0.0),
        ("least squares through the origin", "least_squares", squares, 0.0),
        ("chord over the range (not through the origin)", "chord", chord, m1 - chord * x1),
    ):
        k, b = slope / unit, offset / m2  # the line over M_max, in y
        # the largest error is at an end of the range, or where the slopes match
        # (y* = (k/n)^(1/(n-1)), inside the range); n = 1: the ends alone
        star = xp.where(n != 1.0, lambda k=k: (k / n) ** (1.0 / (n - 1.0)), lambda: 1.0)
        inside = (r < star) & (star < 1.0)
        at_star = xp.where(
            inside, lambda b=b, k=k, star=star: abs(b + k * star - star**n), lambda: 0.0
        )
        error = xp.maximum(xp.maximum(abs(b + k * r - r**n), abs(b + k - 1.0)), at_star)
        lines.append(ClutchLine(name, key, slope, offset, error))
    return x1, x2, lines


def clutch_values(c: Clutch) -> dict[str, Any]:
    """Every number of the clutch's section, by result key (the unloading line and
    the loop's damping ratio where the case gives them)."""
    x1, x2, lines = clutch_lines(c)
    values = {
        "clutch_c0": c.c0,
        "clutch_exponent": c.loading_exponent,
        "clutch_twist_min": x1,
        "clutch_twist_max": x2,
        "clutch_tangent": c.loading_exponent * c.load_max / x2,
    }
    for line in lines:
        values[f"clutch_{line.key}"] = line.stiffness
        values[f"clutch_{line.key}_error"] = line.error
    if c.unloading is not None:
        values["clutch_unloading"] = c.unloading
    if c.loop_area_ratio is not None:
        values["clutch_damping_ratio"] = c.loop_area_ratio / (4.0 * math.pi)
    return values
