"""The right-hand side of a mechanism's block on one piece between the tables'
knots (:mod:`~.kernel`): there I and every speed column of M are straight lines,
read once from the tables' values at the knots."""

from __future__ import annotations

from typing import Any

from mdcalc.problems.mechanism.scene import across_speeds, speed_cell


def at_knots(f: Any, breaks: tuple[float, ...], n: int) -> Any:
    """f(φ) of a block's n rows at each knot: (knots, n)."""
    import numpy as np

    return np.array([np.broadcast_to(f(np.full(n, b)), (n,)) for b in breaks])


class Lines:
    """The tables at their knots, each row's values once: on a piece between two
    knots I is linear in φ, and so is each speed column of M, so a piece's lines
    are read from the values at its two knots (:meth:`piece`)."""

    def __init__(self, formulas: Any, base: Any, breaks: tuple[float, ...]) -> None:
        import numpy as np

        scene = formulas.scene(None, base)
        n = np.size(base.start_angle)
        speeds = formulas.case_speeds
        self.speeds = None if speeds is None else np.array(speeds)
        self.inertia = at_knots(scene.inertia, breaks, n)
        columns = [0.0] if speeds is None else speeds
        self.columns = [
            at_knots(lambda phi, w=w: scene.torque(phi, np.full(n, w)), breaks, n) for w in columns
        ]
        self.rows = np.arange(n)

    def piece(self, knots: Any, index: Any, left: Any, floor: Any) -> Piece:
        """The right-hand side on each row's piece from ``left`` on, between the
        knots ``index - 1`` and ``index`` of ``knots`` (the tables' knots over the
        run, :func:`_knots`)."""
        nb = self.inertia.shape[0]
        low, high = knots[index - 1], knots[index]
        c0, c1 = (index - 1) % nb, index % nb
        offset = left - low
        width = high - low

        same = c0.min() == c0.max()  # every row on the same cell: slices

        def line(values: Any) -> tuple[Any, Any]:
            """a, g of a + g·(φ - left) through the values at the two knots"""
            if same:
                v0, v1 = values[c0[0]], values[c1[0]]
            else:
                v0, v1 = values[c0, self.rows], values[c1, self.rows]
            g = (v1 - v0) / width
            return v0 + g * offset, g

        inertia = line(self.inertia)
        if self.speeds is None:
            return Piece(left, floor, inertia, line(self.columns[0]), None)
        if self.speeds.size == 2:  # M = P + Q·ω in the one cell of speeds, lines P and Q
            (a0, g0), (a1, g1) = line(self.columns[0]), line(self.columns[1])
            span = self.speeds[1] - self.speeds[0]
            q = (a1 - a0) / span, (g1 - g0) / span
            p = a0 - self.speeds[0] * q[0], g0 - self.speeds[0] * q[1]
            return Piece(left, floor, inertia, p, q)
        return Piece(
            left, floor, inertia, (0.0, 0.0), None, self.speeds, [line(c) for c in self.columns]
        )


class Piece:
    """dE/dφ = M, dt/dφ = 1/ω on one piece between the tables' knots: I and M's
    parts are lines a + g·(φ - left) — M = P + Q·ω over two speeds (or none, Q
    absent), or each speed column's line, bilinear in the cell of ω, over more —
    so that a right-hand side is a few array operations. (A value that is not
    finite makes the step's, and the row fails there.)"""

    def __init__(
        self,
        left: Any,
        floor: Any,
        inertia: tuple[Any, Any],
        p: tuple[Any, Any],
        q: tuple[Any, Any] | None,
        speeds: Any = None,
        columns: list[tuple[Any, Any]] | None = None,
    ) -> None:
        self.left, self.floor = left, floor
        self.inertia, self.p, self.q = inertia, p, q
        self.speeds, self.columns = speeds, columns

    def inertia_at(self, rows: Any, phi: Any) -> Any:
        """I of the rows ``rows`` at φ (m,) or (k, m)."""
        a, g = self.inertia
        return a[rows] + g[rows] * (phi - self.left[rows])

    def __call__(self, rows: Any, phi: Any, y: Any) -> Any:
        import numpy as np

        whole = rows.size == self.left.size

        def at(line: tuple[Any, Any], s: Any) -> Any:
            a, g = line
            return a + g * s if whole else a[rows] + g[rows] * s

        s = phi - (self.left if whole else self.left[rows])
        energy = np.maximum(y[:, 0], self.floor if whole else self.floor[rows])
        out = np.empty((rows.size, 2))
        omega = np.sqrt(2.0 * energy / at(self.inertia, s))
        np.divide(1.0, omega, out=out[:, 1])
        if self.columns is None:
            torque = at(self.p, s)
            if self.q is not None:
                torque += at(self.q, s) * omega
        else:
            j = speed_cell(self.speeds, omega)
            values = np.stack([at(c, s) for c in self.columns])
            m0 = np.take_along_axis(values, j[None], 0)[0]
            m1 = np.take_along_axis(values, j[None] + 1, 0)[0]
            torque = across_speeds(self.speeds, omega, j, m0, m1)
        out[:, 0] = torque
        return out
