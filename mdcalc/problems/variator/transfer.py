"""7d: the transfer functions (8.46) of one working stroke of the mechanism."""

from __future__ import annotations

import math
from dataclasses import dataclass

from mdcalc.problems.variator.case import Mechanism


@dataclass(frozen=True)
class Transfer:
    stroke: float  # Δα [rad]
    ratio: float  # i_c
    a0: float
    b0: float

    def first(self, x: float) -> float:
        """Π′ at α - α_c = x."""
        return self.a0 * x * x + self.b0

    def position(self, x: float) -> float:
        """Π - φ_c."""
        return self.a0 * x**3 / 3.0 + self.b0 * x

    def second(self, x: float) -> float:
        return 2.0 * self.a0 * x

    def mean_first(self) -> float:
        """Mean of Π′ over the stroke by 3-point Gauss–Legendre (exact for Π′)."""
        h = 0.5 * self.stroke
        r = math.sqrt(3.0 / 5.0)
        return (5.0 * self.first(-r * h) + 8.0 * self.first(0.0) + 5.0 * self.first(r * h)) / 18.0


def transfer_of(m: Mechanism) -> Transfer:
    """(8.46) with Δα = 2π/z."""
    d = 2.0 * math.pi / m.mechanisms
    i_c = m.ratio
    half_sine = math.sin(0.5 * d)
    a0 = -12.0 / (d * d * i_c) * (d / (2.0 * half_sine) - 1.0)
    b0 = d / (2.0 * i_c * half_sine)
    return Transfer(d, i_c, a0, b0)
