"""Single-degree-of-freedom responses (undamped closed forms), shared by problems."""

from __future__ import annotations

import math


def rectangular_pulse_peak(beta: float, duration: float) -> float:
    """Peak response to a rectangular force pulse, in units of its static response.

    x'' + β²·x = F/m for 0 < t < T, then 0, from rest (seed 000 (7.92)-(7.96)):
    during the pulse the peak is 2 (at t = π/β, reached if T ≥ π/β); after it the
    free vibration has amplitude 2·|sin(β·T/2)|. So the maximum over all time is
    2 when T ≥ π/β, else 2·sin(β·T/2).
    """
    if beta * duration >= math.pi:
        return 2.0
    return 2.0 * math.sin(0.5 * beta * duration)
