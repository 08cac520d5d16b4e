"""The extremes of ω over a mechanism block's last revolution (:mod:`~.kernel`),
from the reference's steps, kept as they are taken and sampled where they can hold
one."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from mdcalc.problems.mechanism.case import TWO_PI
from mdcalc.problems.mechanism.fluctuation import GRID_POINTS
from mdcalc.problems.mechanism.pieces import Piece

#: Points of each step's continuous extension where the extremes of ω are sought:
#: at least this many a step; more where the step's curvature could hide a hump of
#: ω more than SAMPLING_TOLERANCE above the samples (a step as long as a table's
#: piece at nine points passed over one), but never closer than the single scene's
#: grid (GRID_POINTS a revolution), whose spacing is taken where I is a formula and
#: no bound is.
SAMPLES_A_STEP = 8
#: A step is sampled so closely that ω²/2 = E/I between two samples cannot exceed
#: the larger by more than this fraction of E/I at the step's start (ω by half of
#: it), by the bound on (E/I)'' from the extension's terms (:func:`_curvature`).
SAMPLING_TOLERANCE = 2e-7
#: Sample points × rows evaluated at a time (arrays that stay in the cache).
SAMPLE_CELLS = 32_768
#: Numbers kept of the steps not yet sampled (their rows × KEPT_A_ROW): a turn of
#: thousands of small steps is sampled in parts, each by the best ends seen so far
#: (no larger than the turn's: as rigorous, if less sparing).
KEPT_CELLS = 2**22
KEPT_A_ROW = 16
#: Every this many samples of a kept step are taken first, the rest only between
#: those where ω may pass their best (:meth:`Extremes._sample`).
COARSE_STRIDE = 8
#: Golden-section iterations of an extreme (the single scene takes 60): its bracket,
#: from the best sample's neighbour to neighbour (a few hundredths of a radian at
#: most), shrinks 0.618⁴⁰ = 4·10⁻⁹ times, to about 2·10⁻¹⁰ rad, where ω is flat
#: to far below its rounding.
GOLDEN_ITERATIONS = 40

FLUCTUATION_KEYS = ("max_speed", "min_speed", "mean_speed_revolution", "fluctuation")


def _basis_bounds() -> Any:
    """max |b|, |b'|, |b''| over x in [0, 1] of the basis of DOP853's extension,
    y = y_old + Σ F_j·b_j(x) with b_j = x^⌈(j+1)/2⌉·(1-x)^⌊(j+1)/2⌋ (the nesting of
    :meth:`~mdcalc.core.block_ode.Dense.at`): (3, 7), from 20 001 points with a 1 %
    margin (the grid misses a maximum by far less)."""
    import numpy as np
    from numpy.polynomial import Polynomial as P

    x = np.linspace(0.0, 1.0, 20_001)
    out = np.empty((3, 7))
    for j in range(7):
        b = P([0.0, 1.0]) ** ((j + 2) // 2) * P([1.0, -1.0]) ** ((j + 1) // 2)
        for order in range(3):
            out[order, j] = 1.01 * np.max(np.abs(b.deriv(order)(x)))
    return out


def _curvature(dense: Any, inertia: Any, slope: Any) -> Any:
    """A bound on |d²(E/I)/dx²| over each row's step (x = (φ - φ_old)/h), E its
    extension and I = inertia + slope·(φ - φ_old) linear over the step (I > 0)."""
    import numpy as np

    global _BOUNDS
    if _BOUNDS is None:
        _BOUNDS = _basis_bounds()
    terms = np.abs(dense.F[:, :, 0])  # (7, m)

    def total(weights: Any) -> Any:  # in index order: a row's sum is its own
        out = weights[0] * terms[0]
        for w, term in zip(weights[1:].tolist(), terms[1:], strict=True):
            out += w * term
        return out

    e0 = np.abs(dense.y_old[:, 0]) + total(_BOUNDS[0])
    e1, e2 = total(_BOUNDS[1]), total(_BOUNDS[2])
    i_x = np.abs(slope) * dense.h
    low = np.minimum(inertia, inertia + slope * dense.h)
    return e2 / low + 2.0 * e1 * i_x / low**2 + 2.0 * e0 * i_x**2 / low**3


_BOUNDS: Any = None


def speed(
    formulas: Any, base: Any, start: Any, rows: Any, dense: Any, angle: Any, inertia: Any = None
) -> Any:
    """ω = √(2E/I) of the reference at ``angle`` (shape (m,) or (k, m)), as the
    single scene's ``speed_at``: ω₀ up to its (shifted) start. ``inertia``: I at
    ``angle`` where the caller has it (a piece's line), else the scene's."""
    import numpy as np

    if inertia is None:
        inertia = formulas.scene(rows, base).inertia(angle)
    energy = np.maximum(dense.at(angle, 0), 0.0)
    omega = np.sqrt(2.0 * energy / inertia)
    return np.where(angle <= start[rows], base.start_speed[rows], omega)


class Best:
    """The running extreme of ω (``sign`` +1 the largest, -1 the smallest) over the
    sampled points, with the step that holds it and that step's neighbours."""

    def __init__(self, n: int, sign: float) -> None:
        import numpy as np

        self.sign = sign
        self.value = np.full(n, np.nan)
        self.angle = np.full(n, np.nan)
        # the spacing of the samples below and above the best one: its step's, or
        # at an end of its step, the neighbouring step's (the extreme may lie there,
        # beyond the best step's spacing but closer than the neighbour's samples)
        self.below = np.full(n, np.nan)
        self.above = np.full(n, np.nan)
        self.at_end = np.zeros(n, dtype=bool)
        self.pieces: dict[str, Any] = {}
        self.waits = np.zeros(n, dtype=bool)  # for the step after the best one

    def _store(self, which: str, rows: Any, dense: Any) -> None:
        keep(self.pieces, which, self.value.size, rows, dense)

    def fill_next(self, rows: Any, here: Any, width: Any) -> None:
        import numpy as np

        waiting = np.flatnonzero(self.waits[rows])
        if waiting.size:
            r = rows[waiting]
            self._store("next", r, here.take(waiting))
            self.waits[r] = False
            self.above[r] = np.where(self.at_end[r], width[waiting], self.above[r])

    def offer(
        self,
        rows: Any,
        candidate: Any,
        angle: Any,
        index: Any,
        count: Any,
        width: Any,
        here: Any,
        last: Any,
    ) -> None:
        """A step's best sample of each row: its ω and angle, and its index among
        the step's ``count + 1`` samples (each row's), ``width`` apart."""
        import numpy as np

        current = self.value[rows]
        better = np.isnan(current) | (self.sign * candidate > self.sign * current)
        at = np.flatnonzero(better)
        if not at.size:
            return
        r = rows[at]
        self.value[r], self.angle[r] = candidate[at], angle[at]
        self.below[r] = self.above[r] = width[at]
        self.at_end[r] = index[at] == count[at]
        self._store("best", r, here.take(at))
        if "next" in self.pieces:  # an earlier best's, until the step after this one
            self.pieces["next"].h[r] = np.nan
        if "last" in last.pieces:
            previous = last.pieces["last"].take(r)
            self._store("previous", r, previous)
            first = (index[at] == 0) & np.isfinite(last.width[r])
            self.below[r] = np.where(first, last.width[r], self.below[r])
        self.waits[r] = True

    def around(self, rows: Any) -> Any:
        """A function of an angle a row: the extension that holds it, the best
        step's, or a neighbour's just outside it (for the golden search: the three
        are gathered once)."""
        import numpy as np

        from mdcalc.core.block_ode import Dense

        best = self.pieces["best"].take(rows)
        nothing = Dense(np.full(rows.size, np.nan), np.full(rows.size, np.nan), best.y_old, best.F)
        previous, after = (
            self.pieces[which].take(rows) if which in self.pieces else nothing
            for which in ("previous", "next")
        )
        stack = [previous, best, after]
        t_old = np.stack([d.t_old for d in stack])
        h = np.stack([d.h for d in stack])
        y_old = np.stack([d.y_old for d in stack])  # (3, m, 1)
        F = np.stack([d.F for d in stack])  # (3, 7, m, 1)
        line = np.arange(rows.size)
        before, beyond = np.isfinite(previous.h), np.isfinite(after.h)

        def extension(angle: Any) -> Any:
            which = np.where(
                (angle < best.t_old) & before,
                0,
                np.where((angle > best.t_old + best.h) & beyond, 2, 1),
            )
            if not np.any(which != 1):  # every angle in its best step: no gathers
                return best
            return Dense(
                t_old[which, line],
                h[which, line],
                y_old[which, line],
                F[which, :, line].swapaxes(0, 1),
            )

        return extension


def keep(pieces: dict[str, Any], which: str, n: int, rows: Any, dense: Any) -> None:
    """Keep ``dense`` (energy only) as ``pieces[which]`` of the rows ``rows`` of n."""
    import numpy as np

    from mdcalc.core.block_ode import Dense

    if which not in pieces:
        pieces[which] = Dense(
            np.full(n, np.nan),
            np.full(n, np.nan),
            np.full((n, 1), np.nan),
            np.full((7, n, 1), np.nan),
        )
    kept = pieces[which]
    kept.t_old[rows], kept.h[rows] = dense.t_old, dense.h
    kept.y_old[rows], kept.F[:, rows] = dense.y_old, dense.F


class Last:
    """The last accepted step's extension of each row (energy only)."""

    def __init__(self, n: int) -> None:
        import numpy as np

        self.n = n
        self.pieces: dict[str, Any] = {}
        self.width = np.full(n, np.nan)  # its samples' spacing

    def put(self, rows: Any, dense: Any, width: Any) -> None:
        keep(self.pieces, "last", self.n, rows, dense)
        self.width[rows] = width


def energy_only(dense: Any) -> Any:
    """The extension of the energy alone, copied (a view would keep the time's
    numbers of every kept step alive)."""
    import numpy as np

    from mdcalc.core.block_ode import Dense

    return Dense(
        dense.t_old,
        dense.h,
        np.ascontiguousarray(dense.y_old[:, :1]),
        np.ascontiguousarray(dense.F[:, :, :1]),
    )


@dataclass(frozen=True)
class _Step:
    """A step of the last revolution kept for sampling: its rows, their extension
    (energy only) and piece, the span sampled and its samples' count, ω at its ends
    (2, m), and how far ω²/2 may rise above the higher end between them (inf where
    no bound is)."""

    rows: Any
    dense: Any
    piece: Piece | None
    low: Any
    high: Any
    count: Any
    at_ends: Any
    reach: Any


class Extremes:
    """The largest and smallest ω over [first, end] and t at ``first``, from the
    steps' continuous extensions: sampled at SAMPLES_A_STEP + 1 points a step or
    more (see SAMPLING_TOLERANCE), then refined by golden section on the best step
    and its neighbours, as the single scene refines its grid of GRID_POINTS on its
    dense solution."""

    def __init__(self, formulas: Any, base: Any, first: Any, end: Any, start: Any) -> None:
        import numpy as np

        n = np.size(first)
        self.formulas, self.base = formulas, base
        self.first, self.end, self.start = first, end, start
        self.has = first >= base.start_angle - 1e-9
        self.t_first = np.where(first <= start, 0.0, np.nan)
        self.best = {sign: Best(n, sign) for sign in (1.0, -1.0)}
        self.last = Last(n)
        self.steps: list[_Step] = []  # the last revolution's, as taken, not yet sampled
        self.kept = 0  # their cells
        # the largest and least ω at the ends of the steps seen so far
        self.top, self.bottom = np.full(n, -np.inf), np.full(n, np.inf)
        fixed = formulas.inertia_formula is None and formulas.inertia_table is None
        value = formulas.inertia_value
        self.constant = np.broadcast_to(np.asarray(value, dtype=float), (n,)) if fixed else None

    def see(self, step: Any) -> None:
        """Keep a step of the last revolution, to be sampled once the revolution is
        done (:meth:`values`), with ω at its ends and, where I is a line over it, the
        bounds of ω between them."""
        import numpy as np

        rows = step.rows
        inside = self.has[rows] & (step.t_new > self.first[rows])
        if not inside.any():
            return
        at = np.flatnonzero(inside)
        r = rows[at]
        dense = step.dense().take(at)
        crossing = (step.t_old[at] <= self.first[r]) & (self.first[r] > self.start[r])
        if crossing.any():
            c = np.flatnonzero(crossing)
            self.t_first[r[c]] = dense.take(c).at(self.first[r[c]], 1)
        low = np.maximum(step.t_old[at], self.first[r])
        high = step.t_new[at]
        # each row's own count (a row's samples never depend on its block): the
        # grid's, or fewer where the step's curvature is proven small enough
        count = np.ceil((high - low) / (TWO_PI / GRID_POINTS) * (1.0 - 1e-12))
        piece = step.rhs if isinstance(step.rhs, Piece) else None
        line = self._inertia(r, piece, dense.t_old)
        here = energy_only(dense)
        ends = np.stack([low, high])
        at_ends = speed(self.formulas, self.base, self.start, r, here, ends,
                        None if piece is None else piece.inertia_at(r, ends))  # fmt: skip
        reach = np.full(r.size, np.inf)  # ω²/2 above the higher end (below the lower)
        if line is not None:
            inertia, slope = line
            bound = _curvature(dense, inertia, slope)
            scale = np.maximum(dense.y_old[:, 0], 0.0) / inertia
            x = np.sqrt(8.0 * SAMPLING_TOLERANCE * scale / bound)  # samples apart in x
            needed = np.ceil((high - low) / dense.h / x)
            count = np.where(np.isfinite(needed), np.minimum(needed, count), count)
            with np.errstate(all="ignore"):
                reach = np.where(
                    np.isfinite(bound), bound / 8.0 * ((high - low) / dense.h) ** 2, np.inf
                )
        count = np.maximum(count, SAMPLES_A_STEP).astype(np.int64)
        self.top[r] = np.fmax(self.top[r], np.max(at_ends, axis=0))
        self.bottom[r] = np.fmin(self.bottom[r], np.min(at_ends, axis=0))
        self.steps.append(_Step(r, here, piece, low, high, count, at_ends, reach))
        self.kept += r.size * KEPT_A_ROW
        if self.kept > KEPT_CELLS:  # many small steps: sampled by what is known so far
            self._replay()

    def _sample(self, step: _Step, chosen: Any) -> dict[float, tuple[Any, Any]]:
        """The best sample of each chosen row of a kept step (the index into its
        rows), the largest and the smallest ω: value and index among its samples (the
        first of equal ones). Every COARSE_STRIDE-th sample first; then the samples
        between two of them only where the curvature's bound lets ω there pass the
        best of those (every sample where there is no bound): the same best sample,
        bit for bit, as all of them (where ω is a NaN, the first NaN of the coarse
        samples, not of all: such a row is left to the single scene)."""
        import numpy as np

        r, count = step.rows[chosen], step.count[chosen]
        low, high, dense = step.low[chosen], step.high[chosen], step.dense.take(chosen)
        width = (high - low) / count
        spans = (count + COARSE_STRIDE - 1) // COARSE_STRIDE
        coarse = np.minimum(
            np.arange(int(spans.max(initial=0)) + 1)[:, None] * COARSE_STRIDE, count
        )
        omega = self._speeds(step, r, dense, low, high, width, count, coarse)
        found = {sign: _first_best(omega, coarse, sign) for sign in self.best}
        # ω²/2 between two coarse samples rises above the higher (falls below the
        # lower) by at most the bound's reach over a stride; a hair of room for the
        # rounding of the squares
        with np.errstate(all="ignore"):
            stride = np.minimum(COARSE_STRIDE / count, 1.0)
            reach = step.reach[chosen] * stride**2
            ends = omega[:-1], omega[1:]
            most = 0.5 * np.maximum(*ends) ** 2 + reach
            least = 0.5 * np.minimum(*ends) ** 2 - reach
            top, bottom = found[1.0][0], found[-1.0][0]
            may = ~(most < 0.5 * top**2 * (1.0 - 1e-12)) | ~(
                least > 0.5 * bottom**2 * (1.0 + 1e-12)
            )
        # a row sampled before its start takes ω₀ there, which the bound does not know
        may |= low <= self.start[r]
        may &= coarse[1:] - coarse[:-1] > 1  # a span with samples inside it
        span, row = np.nonzero(may.T)[::-1]
        if not row.size:
            return found
        inside = np.minimum(coarse[span, row] + np.arange(1, COARSE_STRIDE)[:, None], count[row])
        omega = self._speeds(step, r[row], dense.take(row), low[row], high[row], width[row],
                             count[row], inside)  # fmt: skip
        for sign, (value, where) in found.items():
            v, i = _first_best(omega, inside, sign)
            best = value.copy()
            (np.maximum if sign > 0 else np.minimum).at(best, row, v)
            # the first index of the best value: the coarse one's where it still is
            # (and where a NaN is, which no sample passes)
            passed = (best != value) & ~np.isnan(best)
            where[passed] = np.iinfo(np.int64).max
            tie = v == best[row]
            np.minimum.at(where, row[tie], i[tie])
            value[:] = np.where(np.isnan(value), value, best)
        return found

    def _speeds(
        self, step: _Step, r: Any, dense: Any, low: Any, high: Any, width: Any, count: Any,
        index: Any,
    ) -> Any:  # fmt: skip
        """ω at the samples ``index`` (k, m) of the rows ``r`` of a kept step, in
        parts that stay in the cache."""
        import numpy as np

        omega = np.empty(index.shape)
        chunk = max(1, SAMPLE_CELLS // max(r.size, 1))
        for begin in range(0, index.shape[0], chunk):
            part = index[begin : begin + chunk]
            angles = np.where(part == count, high, low + width * part)  # (k, m)
            inertia = None if step.piece is None else step.piece.inertia_at(r, angles)  # its line
            omega[begin : begin + chunk] = speed(
                self.formulas, self.base, self.start, r, dense, angles, inertia
            )
        return omega

    def _replay(self) -> None:
        """Each kept step in turn, as the integration took them: sampled where it may
        hold the largest or the smallest ω of its row's revolution, that is where ω²/2
        between its ends may rise above (fall below) the best of the steps' ends seen
        so far (all of the revolution's, unless KEPT_CELLS was reached) by its
        curvature's bound; every step kept in the best's neighbours and spacings. A
        step that is not sampled holds no sample as good as a step's end, so the
        best sample, and all that follows from it, are those of every step
        sampled."""
        import numpy as np

        top, bottom = self.top, self.bottom
        for step in self.steps:
            r = step.rows
            with np.errstate(all="ignore"):
                # ω²/2 at most and at least over the step, as the bound has it; a hair
                # of room for the rounding of the squares
                most = 0.5 * np.max(step.at_ends, axis=0) ** 2 + step.reach
                least = 0.5 * np.min(step.at_ends, axis=0) ** 2 - step.reach
                chosen = ~(most < 0.5 * top[r] ** 2 * (1.0 - 1e-12)) | ~(
                    least > 0.5 * bottom[r] ** 2 * (1.0 + 1e-12)
                )
            width = (step.high - step.low) / step.count
            for best in self.best.values():
                best.fill_next(r, step.dense, width)
            picked = np.flatnonzero(chosen)
            if picked.size:
                found = self._sample(step, picked)
                for sign, best in self.best.items():
                    value, where = found[sign]
                    count, low, high = step.count[picked], step.low[picked], step.high[picked]
                    angle = np.where(where == count, high, low + width[picked] * where)
                    best.offer(r[picked], value, angle, where, count, width[picked],
                               step.dense.take(picked), self.last)  # fmt: skip
            self.last.put(r, step.dense, width)
        self.steps, self.kept = [], 0

    def _inertia(self, rows: Any, piece: Piece | None, at: Any) -> tuple[Any, Any] | None:
        """I at ``at`` and its slope in φ over the step of each row: the piece's line,
        or a constant I; None where I is a formula."""
        import numpy as np

        if piece is not None:
            a, g = piece.inertia
            return a[rows] + g[rows] * (at - piece.left[rows]), g[rows]
        if self.constant is not None:
            return self.constant[rows], np.zeros(rows.size)
        return None

    def values(self, t_end: Any) -> dict[str, Any]:
        import numpy as np

        from mdcalc.core.search import golden_maximum

        self._replay()
        n = np.size(self.first)
        rows = np.flatnonzero(self.has & np.isfinite(self.best[1.0].value))
        out: dict[str, Any] = {}
        if not rows.size:
            nothing = np.full(n, np.nan)
            return dict.fromkeys(FLUCTUATION_KEYS, nothing)
        scene = self.formulas.scene(rows, self.base)
        for key, best in (("max_speed", self.best[1.0]), ("min_speed", self.best[-1.0])):
            sign = best.sign
            low = np.maximum(best.angle[rows] - best.below[rows], self.first[rows])
            high = np.minimum(best.angle[rows] + best.above[rows], self.end[rows])

            extension = best.around(rows)

            def f(angle: Any, extension: Any = extension, sign: float = sign) -> Any:
                inertia = scene.inertia(angle)
                return sign * speed(
                    self.formulas, self.base, self.start, rows, extension(angle), angle, inertia
                )

            refined = golden_maximum(f, low, high, GOLDEN_ITERATIONS)
            result = np.full(n, np.nan)
            result[rows] = sign * np.maximum(f(refined), sign * best.value[rows])
            out[key] = result
        mean = np.where(self.has, TWO_PI / (t_end - self.t_first), np.nan)
        out["mean_speed_revolution"] = mean
        out["fluctuation"] = (out["max_speed"] - out["min_speed"]) / mean
        return out


def _first_best(omega: Any, index: Any, sign: float) -> tuple[Any, Any]:
    """The largest (``sign`` +1) or smallest ω of each column of ``omega`` (k, m) and
    its sample index from ``index`` (k, m): the first of equal ones (a NaN, if any)."""
    import numpy as np

    j = np.argmax(omega if sign > 0 else -omega, axis=0)
    m = np.arange(omega.shape[1])
    return omega[j, m], index[j, m]
