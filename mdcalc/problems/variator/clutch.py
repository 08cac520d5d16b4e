"""7c: the clutch loading curve M = c₀·ξⁿ (8.42) and its lines over the working
range."""

from __future__ import annotations

import math
from dataclasses import dataclass

from mdcalc.problems.variator.case import Clutch


@dataclass(frozen=True)
class ClutchLine:
    name: str
    key: str
    stiffness: float  # slope [N·m/rad]
    offset: float  # M at ξ = 0 of the line [N·m] (0: through the origin)
    error: float  # max |line - curve| over the range / M_max [-]


def clutch_lines(c: Clutch) -> tuple[float, float, list[ClutchLine]]:
    """ξ range of the working loads and three lines through the curve M = c₀·ξⁿ.

    Written in y = ξ/ξ_max and r = ξ_min/ξ_max so that no power of ξ itself is formed
    (c₀ and ξ may be far from 1): the curve is M_max·yⁿ, the least-squares slope
    through the origin 3·(M_max/ξ_max)·(1 - r^(n+2))/((n + 2)(1 - r³))."""
    n, m1, m2 = c.loading_exponent, c.load_min, c.load_max
    x2 = math.exp((math.log(m2) - math.log(c.c0)) / n)
    # ℓ = ln r = ln(M_min/M_max)/n, and 1 - rᵖ = -expm1(p·ℓ): a narrow range keeps
    # its digits (1 - r would cancel)
    ell = -math.inf if m1 == 0.0 else math.log1p((m1 - m2) / m2) / n
    r = math.exp(ell)
    x1 = r * x2
    unit = m2 / x2  # slope that reaches M_max at ξ_max
    squares = 3.0 * unit * math.expm1((n + 2) * ell) / ((n + 2) * math.expm1(3.0 * ell))
    chord = (m2 - m1) / (-x2 * math.expm1(ell))
    lines = []
    for name, key, slope, offset in (
        ("secant to the top of the range, M_max/ξ_max", "secant", unit, 0.0),
        ("least squares through the origin", "least_squares", squares, 0.0),
        ("chord over the range (not through the origin)", "chord", chord, m1 - chord * x1),
    ):
        k, b = slope / unit, offset / m2  # the line over M_max, in y
        candidates = [r, 1.0]
        if n != 1.0:
            star = (k / n) ** (1.0 / (n - 1.0))
            if r < star < 1.0:
                candidates.append(star)
        error = max(abs(b + k * y - y**n) for y in candidates)
        lines.append(ClutchLine(name, key, slope, offset, error))
    return x1, x2, lines
