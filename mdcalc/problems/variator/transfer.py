"""7d: the transfer functions (8.46) of one working stroke of the mechanism.
Written once for a scene's floats and a block's arrays."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from mdcalc.core.xp import of
from mdcalc.problems.variator.case import Mechanism


@dataclass(frozen=True)
class Transfer:
    stroke: Any  # Δα [rad]
    ratio: Any  # i_c
    a0: Any
    b0: Any

    def first(self, x: Any) -> Any:
        """Π′ at α - α_c = x."""
        return self.a0 * x * x + self.b0

    def position(self, x: Any) -> Any:
        """Π - φ_c."""
        return self.a0 * x**3 / 3.0 + self.b0 * x

    def second(self, x: Any) -> Any:
        return 2.0 * self.a0 * x

    def mean_first(self) -> Any:
        """Mean of Π′ over the stroke by 3-point Gauss–Legendre (exact for Π′)."""
        h = 0.5 * self.stroke
        r = math.sqrt(3.0 / 5.0)
        return (5.0 * self.first(-r * h) + 8.0 * self.first(0.0) + 5.0 * self.first(r * h)) / 18.0


def transfer_of(m: Mechanism) -> Transfer:
    """(8.46) with Δα = 2π/z."""
    d = 2.0 * math.pi / m.mechanisms
    i_c = m.ratio
    half_sine = of(d).sin(0.5 * d)
    a0 = -12.0 / (d * d * i_c) * (d / (2.0 * half_sine) - 1.0)
    b0 = d / (2.0 * i_c * half_sine)
    return Transfer(d, i_c, a0, b0)


def mechanism_values(m: Mechanism) -> dict[str, Any]:
    """Every number of the mechanism's section, by result key."""
    t = transfer_of(m)
    mean = t.mean_first()
    return {
        "mechanism_stroke": t.stroke,
        "mechanism_ratio": t.ratio,
        "mechanism_output_rpm": m.input_speed_rpm / t.ratio,
        "mechanism_a0": t.a0,
        "mechanism_b0": t.b0,
        "mechanism_first_end": t.first(0.5 * t.stroke),
        "mechanism_second_end": abs(t.second(0.5 * t.stroke)),
        "mechanism_mean_first": mean,
        "mechanism_mean_check": mean * t.ratio - 1.0,
    }
