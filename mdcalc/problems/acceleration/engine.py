"""The engine curve: torque against speed from a catalogue table or the external
characteristic."""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from mdcalc.core.xp import of

#: Rows of a block whose best torque or power is sought at once: (519, 256) arrays
#: of candidates stay in the cache (1.6x the rate of a block's 4096 rows at once).
BEST_ROWS = 256


@dataclass(frozen=True)
class _RowsTable:
    """A table drawn row by row, (B, K - 1) arrays: each row's M[j] (``lower``) and
    M[j + 1] - M[j] (``rise``), the numbers the formula takes, one subtraction each;
    each row's last M (``last``); the speeds (``knots``, K) and their steps
    (``steps``, K - 1)."""

    lower: Any
    rise: Any
    last: Any
    knots: Any
    steps: Any


@dataclass(frozen=True)
class EngineCurve:
    """Full-throttle torque against engine speed ω [rad/s]: Leiderman or a table."""

    speeds: tuple[float, ...]  # table: ω [rad/s]; Leiderman: ()
    torques: tuple[float, ...]
    rated_torque: float = 0.0  # Leiderman: M_N = N_E/ω_E [N·m]
    rated_speed: float = 0.0  # ω_E [rad/s]
    coefficients: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def is_table(self) -> bool:
        return bool(self.speeds)

    @property
    def low(self) -> float:
        """Lowest engine speed the curve covers [rad/s]."""
        return self.speeds[0] if self.is_table else 0.0

    @property
    def high(self) -> float:
        """Highest engine speed with positive torque [rad/s]."""
        if self.is_table:
            return self.speeds[-1]
        a, b, c = self.coefficients
        if c == 0.0:
            return math.inf if b >= 0 else -a / b * self.rated_speed
        # The positive root of a + b·x - c·x² (c > 0: the curve falls to zero there).
        disc = b * b + 4.0 * a * c
        if c < 0.0 or disc < 0.0:
            return math.inf
        return (b + math.sqrt(disc)) / (2.0 * c) * self.rated_speed

    @property
    def rows(self) -> bool:
        """A table whose torques are arrays over a block of scenes (a study draws them)."""
        return any(not isinstance(m, float | int) for m in self.torques)

    def torque(self, omega: Any) -> Any:
        """M_e(ω) [N·m]; a table is interpolated linearly and held at its ends.
        ``omega`` (and the rated torque, or a table's torques) may be numpy arrays
        over a block of scenes (rows on ``omega``'s last axis)."""
        if self.is_table and self.rows:
            return self._table_rows(omega)
        if self.is_table and not isinstance(omega, float | int):
            import numpy as np

            # one C call: 2x the kernel's rate where a fixed table drives its ODE
            # runs; it rounds otherwise than the float path (an ulp, well within
            # the reference's tolerance)
            return np.interp(omega, self.speeds, self.torques)
        if self.is_table:
            s, m = self.speeds, self.torques
            if omega <= s[0]:
                return m[0]
            if omega >= s[-1]:
                return m[-1]
            k = bisect.bisect_right(s, omega)
            w = (omega - s[k - 1]) / (s[k] - s[k - 1])
            return m[k - 1] + w * (m[k] - m[k - 1])
        a, b, c = self.coefficients
        x = omega / self.rated_speed
        return self.rated_torque * (a + b * x - c * x * x)  # (7.37) read as Leiderman's

    @cached_property
    def _rows_table(self) -> _RowsTable:
        """The numbers a table drawn row by row interpolates with (made once a curve)."""
        import numpy as np

        size = max(np.size(m) for m in self.torques)
        torques = [np.broadcast_to(np.asarray(m, dtype=float), (size,)) for m in self.torques]
        return _RowsTable(
            np.stack(torques[:-1], axis=1),
            np.stack([b - a for a, b in zip(torques[:-1], torques[1:], strict=False)], axis=1),
            np.array(torques[-1]),
            np.asarray(self.speeds),
            np.diff(self.speeds),
        )

    def _table_rows(self, omega: Any, rows: slice = slice(None)) -> Any:
        """The table's interpolation over an array of speeds, each row with its own
        torques where they are arrays over the block of B rows (on ``omega``'s last
        axis, as numpy broadcasts them; ``rows``: those of the block ``omega``'s last
        axis holds): the float path's formula, M[k-1] + w·(M[k] - M[k-1]),
        elementwise."""
        import numpy as np

        table = self._rows_table
        if len(table.last) == 1:  # one table for every row: it broadcasts
            rows = slice(None)
        lower, rise, last = table.lower[rows], table.rise[rows], table.last[rows]
        x = np.asarray(omega, dtype=float)
        speeds = self.speeds
        # the cell k - 1 of each speed, clipped to the table's cells, as a count of the
        # inner speeds at or below it (a binary search cost 3x as much), and the same
        # numbers as speeds[k] - speeds[k - 1] by np.take; on the speeds' own shape,
        # which the rows' may broadcast ((C, 1) against (B,))
        cell = np.zeros(x.shape, dtype=np.intp)
        for s in speeds[1:-1]:
            cell += x >= s
        w = (x - np.take(table.knots, cell)) / np.take(table.steps, cell)
        cell = cell + np.arange(0, lower.size, lower.shape[1])  # row·(K - 1) + j: a row's M[j]
        inside = np.take(lower.ravel(), cell) + w * np.take(rise.ravel(), cell)
        # held at its ends: each row's first and last torque (rows on the last axis)
        end = np.where(x >= speeds[-1], last, inside)
        return np.where(x <= speeds[0], lower[:, 0], end)

    def _candidates(self, limit: float) -> list[float]:
        """Table speeds up to ``limit``, ``limit`` itself and a fine grid: where a
        piecewise-linear torque, or the piecewise-quadratic power M·ω, peaks."""
        inside = [w for w in self.speeds if w <= limit]
        grid = [self.low + (limit - self.low) * k / 512 for k in range(513)]
        return sorted({*inside, *grid})

    def _best_rows(self, limit: Any, power: bool) -> Any:
        """ω of the largest torque (or power M·ω) of each row of a block, over the
        candidates of :meth:`_candidates` in rising order, the first of equals: as
        the float path's ``max``."""
        import numpy as np

        limit = np.asarray(limit, dtype=float)
        size = max([np.size(limit)] + [np.size(m) for m in self.torques])
        # one limit for every row (the rev limit not drawn): one column of candidates,
        # the same numbers as each row's, which the rows' torques broadcast
        limits = limit if limit.ndim == 0 else np.broadcast_to(limit, (size,))
        out = np.empty(size)
        for first in range(0, size, BEST_ROWS):  # (C, rows) arrays that stay in the cache
            rows = slice(first, min(first + BEST_ROWS, size))
            out[rows] = self._best_of(limits if limit.ndim == 0 else limits[rows], power, rows)
        return out

    def _best_of(self, limit: Any, power: bool, rows: slice) -> Any:
        """:meth:`_best_rows` of the rows ``rows``, each with its limit (or one for all)."""
        import numpy as np

        width = np.size(limit)
        limit = np.broadcast_to(limit, (width,))
        grid = self.low + (limit[None, :] - self.low) * np.arange(513)[:, None] / 512
        speeds = np.broadcast_to(np.asarray(self.speeds)[:, None], (len(self.speeds), width))
        speeds = np.where(speeds <= limit[None, :], speeds, np.nan)  # past the limit: none
        candidates = np.concatenate([speeds, grid], axis=0)  # (C, rows), unsorted
        score = self._table_rows(candidates, rows)
        score = score * candidates if power else score
        score = np.where(np.isnan(candidates), -np.inf, score)
        # the first of equals in rising order is the least speed of the best score
        # (no sort of the candidates: it took a third of this)
        best = np.max(score, axis=0)
        return np.min(np.where(score == best, candidates, np.inf), axis=0)

    def least(self, low: Any, high: Any) -> tuple[Any, Any]:
        """The least torque over the engine speeds between ``low`` and ``high`` (in
        either order; arrays over a block's rows), and the size of the numbers it is
        made of, against which its rounding is measured: a table's largest |M|,
        Leiderman's M_N·(|a| + |b|·x + |c|·x²) at the higher end. A table is
        piecewise linear (its least value is at an end or a knot), Leiderman's curve
        a parabola (at an end or its vertex)."""
        import numpy as np

        low, high = np.minimum(low, high), np.maximum(low, high)
        ends = np.minimum(self.torque(low), self.torque(high))
        if self.is_table:
            inner = [self.torque(np.clip(s, low, high)) for s in self.speeds]
            scale = np.max(np.abs(np.broadcast_arrays(*self.torques)), axis=0)
            return np.minimum.reduce([ends, *inner]), scale
        a, b, c = self.coefficients
        x = np.asarray(high) / self.rated_speed
        scale = np.abs(self.rated_torque) * (abs(a) + abs(b) * x + abs(c) * x * x)
        if c == 0.0:
            return ends, scale
        vertex = np.clip(b / (2.0 * c) * np.asarray(self.rated_speed), low, high)
        return np.minimum(ends, self.torque(vertex)), scale

    def peak(self, limit: float) -> tuple[float, float]:
        """(ω, M) at the maximum torque on [low, limit]."""
        if self.is_table and (self.rows or not isinstance(limit, float | int)):
            omega = self._best_rows(limit, power=False)
            return omega, self._table_rows(omega)  # the float path's value, to the bit
        if self.is_table:
            omega = max(self._candidates(limit), key=self.torque)
            return omega, self.torque(omega)
        a, b, c = self.coefficients
        x = b / (2.0 * c) if c > 0 else limit / self.rated_speed
        xp = of(x, self.rated_speed, limit)  # (ω_E and the limit arrays in a block)
        omega = xp.minimum(xp.maximum(x * self.rated_speed, self.low), limit)
        return omega, self.torque(omega)

    def max_power_speed(self, limit: float) -> float:
        """ω of the maximum power M·ω on [low, limit]: n_E of Leiderman's curve."""
        if not self.is_table:
            return of(self.rated_speed, limit).minimum(self.rated_speed, limit)
        if self.rows or not isinstance(limit, float | int):
            return self._best_rows(limit, power=True)
        return max(self._candidates(limit), key=lambda w: w * self.torque(w))
