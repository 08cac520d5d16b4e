"""Parametric excitation: the Mathieu equation, its stability by Floquet theory."""

from __future__ import annotations

import math
from typing import Any

#: A Floquet verdict within this of the boundary |trace| = 1 + det is "boundary".
BOUNDARY = 1e-9


def monodromy_rk4(a: Any, q: Any, c: float, steps: int) -> tuple[Any, Any]:
    """Trace and determinant of the period-π map by classical RK4 with ``steps``
    steps; ``a``, ``q`` may be numpy arrays (the chart) or floats."""
    h = math.pi / steps

    def f(t: float, x: Any, v: Any) -> tuple[Any, Any]:
        return v, -c * v - (a - 2.0 * q * math.cos(2.0 * t)) * x

    columns = []
    for x, v in ((1.0 + 0.0 * a, 0.0 * a), (0.0 * a, 1.0 + 0.0 * a)):
        t = 0.0
        for _ in range(steps):
            k1 = f(t, x, v)
            k2 = f(t + h / 2, x + h / 2 * k1[0], v + h / 2 * k1[1])
            k3 = f(t + h / 2, x + h / 2 * k2[0], v + h / 2 * k2[1])
            k4 = f(t + h, x + h * k3[0], v + h * k3[1])
            x = x + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            v = v + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            t += h
        columns.append((x, v))
    (x1, v1), (x2, v2) = columns
    return x1 + v2, x1 * v2 - x2 * v1


def monodromy_ode(a: float, q: float, c: float, rtol: float) -> tuple[float, float]:
    """Trace and determinant of the period-π map by DOP853."""
    import numpy as np

    from mdcalc.core.ode import advance

    def rhs(t: float, y: np.ndarray) -> Any:
        return np.array([y[1], -c * y[1] - (a - 2.0 * q * math.cos(2.0 * t)) * y[0]])

    ends = []
    for start in ((1.0, 0.0), (0.0, 1.0)):
        segment = advance(
            rhs, 0.0, np.array(start), math.pi, rtol=rtol, atol=rtol * 1e-3, method="DOP853"
        )
        ends.append(segment.y)
    (x1, v1), (x2, v2) = ends
    return float(x1 + v2), float(x1 * v2 - x2 * v1)


def liouville(det: float, c: float) -> float:
    """The determinant to use: the computed one (its error goes with the trace's,
    which matters where the multipliers nearly coincide), unless cancellation has
    spoiled it (multipliers far apart); then e^(-cπ), exact by Liouville."""
    exact = math.exp(-c * math.pi)
    return det if abs(det - exact) <= 1e-6 * exact else exact


def spectral_radius(trace: float, det: float) -> float:
    """Largest |μ| of μ² - trace·μ + det = 0."""
    disc = trace * trace - 4.0 * det
    if disc < 0.0:
        return math.sqrt(max(det, 0.0))
    return (abs(trace) + math.sqrt(disc)) / 2.0


def verdict(trace: float, c: float) -> str:
    """stable / unstable / boundary by |trace| against 1 + e^(-cπ)."""
    edge = 1.0 + math.exp(-c * math.pi)
    if abs(abs(trace) - edge) <= BOUNDARY * edge:
        return "boundary"
    return "stable" if abs(trace) < edge else "unstable"


def first_approximation(a: float, q: float, c: float) -> str:
    """Harmonic balance in the principal region: unstable when q² > (a - 1)² + c²."""
    return "unstable" if q * q > (a - 1.0) ** 2 + c * c else "stable"
