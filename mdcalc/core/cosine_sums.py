"""The largest value of cosine sums over a time window, R + Σⱼ Bⱼ·cos(βⱼt): the
moments of a chain's springs after suddenly applied torques (:mod:`.chain`).

* :func:`cosine_sum_maximum` -- one sum, found by sampling at 16 points per period
  of the fastest resolved mode and Newton refinement of every candidate on its slope.
* :func:`maxima` -- the same for a block of rows at once (a study's samples), S sums
  per row sharing its frequencies and window; a single scene is a block of one.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True)
class Maximum:
    """The largest value of a cosine sum over a window and where it is."""

    value: float
    time: float
    # Modes too fast to sample over the window are taken at their full amplitude:
    # ``bound`` is then True and the value exceeds the truth by at most ``error``.
    bound: bool = False
    error: float = 0.0


@dataclass(frozen=True)
class Maxima:
    """:class:`Maximum` of a block of cosine sums: (B, S) arrays, S sums per row."""

    value: np.ndarray
    time: np.ndarray
    bound: np.ndarray
    error: np.ndarray

    def row(self, index: int, which: int) -> Maximum:
        """Sum ``which`` of row ``index``."""
        at = (index, which)
        return Maximum(
            float(self.value[at]), float(self.time[at]), bool(self.bound[at]), float(self.error[at])
        )


SAMPLES_PER_PERIOD = 16
SAMPLE_BUDGET = 1 << 22
#: Samples evaluated at once (rows × times of a tile).
_TILE = 1 << 18
#: Samples of the grid between two exact angles (see ``grid_values``).
RUN = 32
#: Newton steps on a candidate's slope: from the middle of its bracket (two sample
#: steps, an eighth of the fastest period) Newton converges quadratically, and a
#: step it cannot take halves the bracket instead. Its time is then set by the
#: rounding of the slope, about ε of the period; the value is flat to second order.
NEWTON_STEPS = 10


def cosine_sum_maximum(
    constant: float,
    amplitudes: Sequence[float],
    frequencies: Sequence[float],
    start: float,
    end: float,
    budget: int = SAMPLE_BUDGET,
) -> Maximum:
    """max of constant + Σ Bⱼ·cos(βⱼ·t) over start ≤ t ≤ end (see :func:`maxima`)."""
    return maxima(
        np.array([[constant]], dtype=float),
        np.array([amplitudes], dtype=float).reshape(1, 1, -1),
        np.array([frequencies], dtype=float).reshape(1, -1),
        np.array([start], dtype=float),
        np.array([end], dtype=float),
        budget,
    ).row(0, 0)


def maxima(
    constant: np.ndarray,
    amplitudes: np.ndarray,
    frequencies: np.ndarray,
    start: np.ndarray,
    end: np.ndarray,
    budget: int = SAMPLE_BUDGET,
) -> Maxima:
    """max of constant + Σ Bⱼ·cos(βⱼ·t) over start ≤ t ≤ end, for every row at once
    and for S sums per row that share its frequencies and window (the moments of a
    chain's springs): ``constant`` (B, S), ``amplitudes`` (B, S, m), ``frequencies``
    (B, m), ``start`` and ``end`` (B,).

    Sampled at 16 points per period of the fastest mode that fits the budget (and
    that some sum of the row has); every sampled local maximum within the sampling
    error of the best is refined by Newton on its slope between its two neighbouring
    samples. Modes faster than the budget allows are added at their amplitude |Bⱼ|
    (they swing through it within each of their periods), and the result says it is
    a bound with its error ½·Σ|B·β²|·(π/β_fast)². A row's result does not depend on
    the other rows.
    """
    rows, series, modes = amplitudes.shape
    order = np.argsort(frequencies, axis=1, kind="stable")
    w = np.take_along_axis(frequencies, order, axis=1)
    b = np.take_along_axis(amplitudes, order[:, None, :], axis=2)
    span = end - start
    present = b != 0.0
    resolved = (span[:, None] <= 0.0) | (
        span[:, None] * w / (2.0 * math.pi) * SAMPLES_PER_PERIOD <= budget
    )
    slow = present & resolved[:, None, :]
    fast = present & ~resolved[:, None, :]
    b_slow = np.where(slow, b, 0.0)
    sampled = slow.any(axis=1)  # (B, m): the modes the row's grid resolves
    top = np.max(np.where(sampled, w, 0.0), axis=1, initial=0.0)
    with np.errstate(all="ignore"):
        counts = np.ceil(span * top / (2.0 * math.pi) * SAMPLES_PER_PERIOD)
    counts = np.maximum(2, np.where(np.isfinite(counts), counts, 0).astype(np.int64) + 1)
    step = span / (counts - 1)
    curvature = np.zeros((rows, series))
    for k in range(modes):
        curvature = curvature + np.abs(b_slow[:, :, k]) * w[:, k, None] * w[:, k, None]
    slack = curvature * step[:, None] * step[:, None] / 8.0

    def grid_values(at: np.ndarray, index: np.ndarray) -> np.ndarray:
        """The S sums of rows ``at`` at their samples ``index`` (a run of consecutive
        sample numbers, shared by the rows): (G, S, K). The angle w·(t₀ + j·Δt)
        splits at a multiple of RUN samples, w·(t₀ + m·Δt) + w·r·Δt, so that
        B·cos(A + R) = (B·cos A)·cos R - (B·sin A)·sin R: the factors of the anchors
        (m) and of the run (r) are cosines of their own, and each run of RUN samples
        of a sum is one small matrix product over the modes (and the constant),
        where a cosine of each sample cost ten times as much; the split rounds the
        angle no worse than w·t itself."""
        first = int(index[0]) - int(index[0]) % RUN  # a multiple of RUN at or below
        anchors = -(-(int(index[-1]) - first + 1) // RUN)
        size = len(at)
        t0, dt = start[at][:, None], step[at][:, None]
        t_anchor = t0 + dt * (first + RUN * np.arange(anchors))[None, :]  # (G, M)
        t_run = dt * np.arange(RUN)[None, :]  # (G, RUN)
        # each sum's anchor factors (G, S, M, 2·modes + 1) times the run's (G, ·, RUN)
        factors = np.empty((size, series, anchors, 2 * modes + 1))
        runs = np.empty((size, 2 * modes + 1, RUN))
        for k in range(modes):
            wk = w[at, k][:, None]
            a, r = wk * t_anchor, wk * t_run
            bk = b_slow[at, :, k][:, :, None]
            factors[:, :, :, 2 * k] = bk * np.cos(a)[:, None, :]
            factors[:, :, :, 2 * k + 1] = bk * -np.sin(a)[:, None, :]
            runs[:, 2 * k] = np.cos(r)
            runs[:, 2 * k + 1] = np.sin(r)
        factors[:, :, :, -1] = constant[at][:, :, None]
        runs[:, -1] = 1.0
        total = factors.reshape(size, series * anchors, -1) @ runs
        skip = int(index[0]) - first
        return total.reshape(size, series, anchors * RUN)[:, :, skip : skip + len(index)]

    # Candidates (row, sum, sample index), by tiles of rows of like sample counts:
    # rows grouped by the power of two above their count, so that a tile pads a row
    # by at most twice its samples.
    found: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    live = np.flatnonzero(sampled.any(axis=1))
    level = np.ceil(np.log2(counts[live])).astype(np.int64)
    for value in np.unique(level):
        members = live[level == value]
        per = max(1, _TILE // (series * int(np.max(counts[members]))))
        for first in range(0, len(members), per):
            group = members[first : first + per]
            found.append(_candidates(group, counts[group], slack, grid_values))
    at = np.concatenate([f[0] for f in found]) if found else np.array([], dtype=int)
    which = np.concatenate([f[1] for f in found]) if found else np.array([], dtype=int)
    picked = np.concatenate([f[2] for f in found]) if found else np.array([], dtype=int)
    t0, dt, t1 = start[at], step[at], end[at]
    low = np.clip(t0 + dt * (picked - 1), t0, t1)
    high = np.clip(t0 + dt * (picked + 1), t0, t1)
    # The peak between each candidate's neighbours, all candidates of all rows at
    # once: Newton on the slope f' = -Σ b·w·sin(w·t) (f'' = -Σ b·w²·cos(w·t)) inside
    # the bracket, halving it where a step would leave it. A bracket whose slope
    # does not change sign (a window's end) holds its peak at the end that rises.
    bc, wc = b_slow[at, which], w[at]
    g_low, _ = _slopes(bc, wc, low)
    g_high, _ = _slopes(bc, wc, high)
    edge = ~((g_low > 0.0) & (g_high < 0.0))
    x = np.where(edge, np.where(g_high >= 0.0, high, low), 0.5 * (low + high))
    inside = np.flatnonzero(~edge)
    lo, hi, xi = low[inside], high[inside], x[inside]
    bi, wi = bc[inside], wc[inside]
    for _ in range(NEWTON_STEPS):
        g, bend = _slopes(bi, wi, xi)
        rising = g > 0.0
        lo, hi = np.where(rising, xi, lo), np.where(rising, hi, xi)
        with np.errstate(all="ignore"):
            step_to = xi - g / bend
        fine = (bend < 0.0) & (step_to >= lo) & (step_to <= hi)  # (at the root: stays)
        moved = np.where(fine, step_to, 0.5 * (lo + hi))
        # a candidate whose step left it where it was stays there for good (the
        # same slope, the same bracket): it leaves the loop with its time
        still = moved == xi
        x[inside[still]] = xi[still]
        keep = ~still
        inside, lo, hi, xi = inside[keep], lo[keep], hi[keep], moved[keep]
        bi, wi = bi[keep], wi[keep]
        if not inside.size:
            break
    x[inside] = xi
    # Every sum's candidates in time order, then its window's two ends: the first
    # largest value wins.
    row_of = np.repeat(np.arange(rows), series)
    sum_of = np.tile(np.arange(series), rows)
    point_rows = np.concatenate([at, row_of, row_of])
    point_sums = np.concatenate([which, sum_of, sum_of])
    points = np.concatenate([x, start[row_of], end[row_of]])
    values = _sums(
        constant[point_rows, point_sums], b_slow[point_rows, point_sums], w[point_rows], points
    )
    owner = point_rows * series + point_sums
    heads = _first_largest(owner, values, rows * series)
    best_value = values[heads].reshape(rows, series)
    best_time = points[heads].reshape(rows, series)
    fast_amplitude = np.zeros((rows, series))
    for k in range(modes):
        fast_amplitude = fast_amplitude + np.where(fast[:, :, k], np.abs(b[:, :, k]), 0.0)
    bound = fast.any(axis=2)
    # One fast mode: each of its periods brings it to +|B| while the slow sum moves
    # by at most ½·Σ|B·β²|·(π/β_fast)². With several, their phases need not line up:
    # no error is claimed (0), the value is their supremum.
    single = bound & (fast.sum(axis=2) == 1) & slow.any(axis=2)
    w_fast = np.max(np.where(fast, w[:, None, :], 0.0), axis=2, initial=0.0)
    with np.errstate(all="ignore"):
        error = np.where(single, 0.5 * curvature * (math.pi / w_fast) ** 2, 0.0)
    return Maxima(np.where(bound, best_value + fast_amplitude, best_value), best_time, bound, error)


def _first_largest(owner: np.ndarray, values: np.ndarray, owners: int) -> np.ndarray:
    """For each owner 0 … owners - 1 (each owns a point), the index of its largest
    value, the first of equals; NaN counts below every number (an owner of NaN
    alone: its first point). Two scatters, not a sort."""
    best = np.full(owners, -np.inf)
    np.fmax.at(best, owner, values)
    top = values == best[owner]
    none = len(values)
    heads = np.full(owners, none)
    np.minimum.at(heads, owner[top], np.flatnonzero(top))
    first = np.full(owners, none)
    np.minimum.at(first, owner, np.arange(none))
    return np.where(heads == none, first, heads)


def _slopes(b: np.ndarray, w: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """f' = -Σ bⱼ·wⱼ·sin(wⱼ·t) and f'' = -Σ bⱼ·wⱼ²·cos(wⱼ·t), element by element."""
    slope = np.zeros(np.shape(t))
    curvature = np.zeros(np.shape(t))
    for k in range(b.shape[1]):
        angle = w[:, k] * t
        bw = b[:, k] * w[:, k]
        slope = slope - bw * np.sin(angle)
        curvature = curvature - bw * w[:, k] * np.cos(angle)
    return slope, curvature


def _sums(constant: np.ndarray, b: np.ndarray, w: np.ndarray, t: np.ndarray) -> np.ndarray:
    """constant + Σ bⱼ·cos(wⱼ·t), element by element (b and w: one row per element)."""
    total = constant
    for k in range(b.shape[1]):
        total = total + b[:, k] * np.cos(w[:, k] * t)
    return total


def _candidates(
    group: np.ndarray,
    counts: np.ndarray,
    slack: np.ndarray,
    grid_values: Any,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The sampled local maxima within the slack of the best sample of each sum, for
    the rows of ``group`` (a sample past a row's count is no sample): their rows,
    sums and sample indices. The few samples within the slack are found first (a
    comparison and a flat search of the block), the local maxima among them after."""
    width = int(np.max(counts))
    series = slack.shape[1]
    chunk = max(1, _TILE // (series * len(group)))
    limit = counts[:, None]

    def sampled(index: np.ndarray) -> np.ndarray:
        """The sums at ``index``, -inf where a row has no such sample: before its
        first (index -1) and from its count on (the columns past the smallest)."""
        values = grid_values(group, index)
        values[:, :, : int(np.searchsorted(index, 0))] = -np.inf
        cut = int(np.searchsorted(index, np.min(counts)))
        if cut < len(index):
            outside = index[None, cut:] >= limit  # (G, K')
            values[:, :, cut:] += np.where(outside, -np.inf, 0.0)[:, None, :]
        return values

    whole = None
    if width <= chunk:  # one tile: evaluated once for both passes
        whole = sampled(np.arange(-1, width + 1))
        best = np.max(whole, axis=2)
    else:
        best = np.full((len(group), series), -np.inf)
        for first in range(0, width, chunk):  # the best sample of each sum
            index = np.arange(first, min(first + chunk, width))
            best = np.maximum(best, np.max(sampled(index), axis=2))
    floor = (best - slack[group])[:, :, None]
    rows, sums, indices = [], [], []
    for first in range(0, width, chunk):  # the local maxima near it
        index = np.arange(first - 1, min(first + chunk + 1, width + 1))
        values = whole if whole is not None else sampled(index)
        middle = values[:, :, 1:-1]
        row, which, col = np.unravel_index(np.flatnonzero(middle >= floor), middle.shape)
        here = values[row, which, col + 1]
        at = index[col + 1]
        keep = (
            (here >= values[row, which, col])
            & (here >= values[row, which, col + 2])
            & (at >= 0)
            & (at < counts[row])
        )
        rows.append(group[row[keep]])
        sums.append(which[keep])
        indices.append(at[keep])
    return np.concatenate(rows), np.concatenate(sums), np.concatenate(indices)
