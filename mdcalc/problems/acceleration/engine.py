"""The engine curve: torque against speed from a catalogue table or the external
characteristic."""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from typing import Any

from mdcalc.core.xp import of


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

    def _table_rows(self, omega: Any) -> Any:
        """The table's interpolation over an array of speeds, each row with its own
        torques where they are arrays over the block of B rows (on ``omega``'s last
        axis, as numpy broadcasts them): the float path's formula,
        M[k-1] + w·(M[k] - M[k-1]), elementwise."""
        import numpy as np

        size, count = max(np.size(m) for m in self.torques), len(self.torques)
        torques = [np.broadcast_to(np.asarray(m, dtype=float), (size,)) for m in self.torques]
        # row by row, flat: a row's M[j] at row·(K - 1) + j, and M[j + 1] - M[j] beside
        # it (the numbers the formula takes, one subtraction each, once a call)
        lower_of = np.empty((size, count - 1))
        rise_of = np.empty((size, count - 1))
        for j in range(count - 1):
            lower_of[:, j] = torques[j]
            rise_of[:, j] = torques[j + 1] - torques[j]
        x = np.asarray(omega, dtype=float)
        speeds = np.asarray(self.speeds)
        # the cell k - 1 of each speed, and the same numbers as speeds[k] - speeds[k - 1],
        # by np.take (fancy indexing cost 3x as much); the cell and weight on the
        # speeds' own shape, which the rows' may broadcast ((C, 1) against (B,))
        cell = np.asarray(np.searchsorted(speeds, x, side="right"))
        cell -= 1
        np.minimum(cell, count - 2, out=cell)
        np.maximum(cell, 0, out=cell)
        w = (x - np.take(speeds, cell)) / np.take(np.diff(speeds), cell)
        cell = cell + np.arange(0, size * (count - 1), count - 1)  # (rows on the last axis)
        inside = np.take(lower_of.ravel(), cell) + w * np.take(rise_of.ravel(), cell)
        # held at its ends: each row's first and last torque (rows on the last axis)
        end = np.where(x >= speeds[-1], torques[-1], inside)
        return np.where(x <= speeds[0], torques[0], end)

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
        width = 1 if limit.ndim == 0 else size
        limit = np.broadcast_to(limit, (width,))
        grid = self.low + (limit[None, :] - self.low) * np.arange(513)[:, None] / 512
        speeds = np.broadcast_to(np.asarray(self.speeds)[:, None], (len(self.speeds), width))
        speeds = np.where(speeds <= limit[None, :], speeds, np.nan)  # past the limit: none
        candidates = np.concatenate([speeds, grid], axis=0)  # (C, rows), unsorted
        score = self._table_rows(candidates)
        score = score * candidates if power else score
        score = np.where(np.isnan(candidates), -np.inf, score)
        # the first of equals in rising order is the least speed of the best score
        # (no sort of the candidates: it took a third of this)
        best = np.max(score, axis=0)
        return np.min(np.where(score == best, candidates, np.inf), axis=0)

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
