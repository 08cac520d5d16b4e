"""Parametric excitation: the Mathieu equation, its stability by Floquet theory."""

from __future__ import annotations

import math
from typing import Any

from mdcalc.core.xp import of

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


def floquet_block(a: Any, q: Any, c: Any, rtol: float) -> tuple[Any, Any]:
    """Trace and determinant of the period-π map for a block of (a, q, c) (arrays of
    one shape): :func:`monodromy_ode`'s DOP853 at its rtol and atol, both columns of
    every row stepped at once by :func:`mdcalc.core.block_ode.dop853_block`. NaN
    where a row's run fails (its single scene then runs alone)."""
    import numpy as np

    from mdcalc.core.block_ode import dop853_block

    a, q, c = np.broadcast_arrays(*(np.asarray(v, dtype=float).ravel() for v in (a, q, c)))
    n = a.size
    # rows 0..n-1 start at (1, 0), rows n..2n-1 at (0, 1)
    aa, qq, cc = (np.concatenate([v, v]) for v in (a, q, c))

    def rhs(rows: Any, t: Any, y: Any) -> Any:
        x, v = y[:, 0], y[:, 1]
        return np.stack([v, -cc[rows] * v - (aa[rows] - 2.0 * qq[rows] * np.cos(2.0 * t)) * x], 1)

    start = np.zeros((2 * n, 2))
    start[:n, 0] = 1.0
    start[n:, 1] = 1.0
    run = dop853_block(
        rhs, np.zeros(2 * n), start, math.pi, rtol=rtol, atol=rtol * 1e-3, budget=10**6
    )
    ends = np.where(run.done[:, None], run.y, np.nan)
    (x1, v1), (x2, v2) = ends[:n].T, ends[n:].T
    return x1 + v2, x1 * v2 - x2 * v1


def liouville(det: Any, c: Any) -> Any:
    """The determinant to use: the computed one (its error goes with the trace's,
    which matters where the multipliers nearly coincide), unless cancellation has
    spoiled it (multipliers far apart); then e^(-cπ), exact by Liouville. Floats or
    arrays."""
    xp = of(det, c)
    exact = xp.exp(-c * math.pi)
    return xp.where(xp.abs(det - exact) <= 1e-6 * exact, lambda: det, lambda: exact)


def spectral_radius(trace: Any, det: Any) -> Any:
    """Largest |μ| of μ² - trace·μ + det = 0; floats or arrays."""
    xp = of(trace, det)
    disc = trace * trace - 4.0 * det
    return xp.where(
        disc < 0.0,
        lambda: xp.sqrt(xp.maximum(det, 0.0)),
        lambda: (xp.abs(trace) + xp.sqrt(disc)) / 2.0,
    )


def verdict(trace: float, c: float) -> str:
    """stable / unstable / boundary by |trace| against 1 + e^(-cπ)."""
    edge = 1.0 + math.exp(-c * math.pi)
    if abs(abs(trace) - edge) <= BOUNDARY * edge:
        return "boundary"
    return "stable" if abs(trace) < edge else "unstable"


def first_approximation(a: float, q: float, c: float) -> str:
    """Harmonic balance in the principal region: unstable when q² > (a - 1)² + c²."""
    return "unstable" if q * q > (a - 1.0) ** 2 + c * c else "stable"
