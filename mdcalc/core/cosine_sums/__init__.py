"""The largest value of cosine sums over a time window, R + Σⱼ Bⱼ·cos(βⱼt): the
moments of a chain's springs after suddenly applied torques (:mod:`.chain`).

* :func:`cosine_sum_maximum` -- one sum, found by sampling at 16 points per period
  of the fastest resolved mode and Newton refinement on its slope of every candidate
  that can still win.
* :func:`maxima` -- the same for a block of rows at once (a study's samples), S sums
  per row sharing its frequencies and window; a single scene is a block of one.

Its parts: :mod:`.samples` (the sums' samples, by products of exponentials, not
cosines) and :mod:`.candidates` (the sampled local maxima near which the largest
value may lie, found on the whole grid or in the windows that hold them, and which
of them are worth refining).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from mdcalc.core.cosine_sums import candidates
from mdcalc.core.cosine_sums.samples import Sums
from mdcalc.core.search import highest_fall


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
#: Newton steps on a candidate's slope: from the middle of its bracket (two sample
#: steps, an eighth of the fastest period) Newton converges quadratically, and a
#: step it cannot take halves the bracket instead. Its time is then set by the
#: rounding of the slope, about ε of the period; the value is flat to second order.
NEWTON_STEPS = 10
#: Parts a bracket without a root is scanned in for one (an "M" top).
SCAN_STEPS = 16


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
    error of the best that can still win (:func:`.candidates.worth_refining`) is
    refined by Newton on its slope between its two neighbouring samples. A long row
    is sampled only where such a maximum can lie (:func:`.candidates.windows`).
    Modes faster than the budget allows are added at their amplitude |Bⱼ|
    (they swing through it within each of their periods), and the result says it is
    a bound with its error ½·Σ|B·β²|·(π/β_fast)². A row's result does not depend on
    the other rows. It is never below the best sample; a peak that rises between two
    samples without making either a sampled local maximum (a nearly flat top of two
    humps closer than two samples) is found only to within the sampling error.
    """
    rows, series, modes = amplitudes.shape
    frequencies = np.abs(frequencies)  # cos is even: a negative β is its |β|
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
    sums = Sums(constant, b_slow, w, start, step)
    found = candidates.find(sums, np.flatnonzero(sampled.any(axis=1)), counts, slack)
    kept = candidates.worth_refining(sums, found)
    at, which, picked = found[0][kept], found[1][kept], found[2][kept]
    t0, dt, t1 = start[at], step[at], end[at]
    low = np.clip(t0 + dt * (picked - 1), t0, t1)
    high = np.clip(t0 + dt * (picked + 1), t0, t1)
    # The peak between each candidate's neighbours, all candidates of all rows at
    # once: Newton on the slope f' = -Σ b·w·sin(w·t) (f'' = -Σ b·w²·cos(w·t)) inside
    # the bracket, halving it where a step would leave it (a slope of 0 at an end,
    # as at t = 0, takes the sign of the slope just inside it: f''s). A bracket
    # whose slope does not change sign (two peaks close together, an "M", or a peak
    # at the row's end) is scanned at SCAN_STEPS points, and its change from + to -
    # of the highest value is refined; with none, the peak is at the end that rises
    # (and the sample itself is a point below).
    bc, wc = b_slow[at, which], w[at]
    g_low, bend_low = _slopes(bc, wc, low)
    g_high, bend_high = _slopes(bc, wc, high)
    g_low = np.where(g_low == 0.0, bend_low, g_low)
    g_high = np.where(g_high == 0.0, -bend_high, g_high)
    edge = ~((g_low > 0.0) & (g_high < 0.0))
    middle = np.clip(t0 + dt * picked, t0, t1)
    scan = np.flatnonzero(edge & (high > low))
    if scan.size:
        parts = np.arange(SCAN_STEPS + 1) / SCAN_STEPS
        at_scan = low[scan, None] + (high - low)[scan, None] * parts  # (E, SCAN_STEPS + 1)
        bs, ws = bc[scan], wc[scan]
        g_scan = np.stack([_slopes(bs, ws, at_scan[:, j])[0] for j in range(len(parts))], 1)
        g_scan[:, 0], g_scan[:, -1] = g_low[scan], g_high[scan]  # (a zero end's own sign)
        zero = np.zeros(len(scan))
        f_scan = np.stack([_sums(zero, bs, ws, at_scan[:, j]) for j in range(len(parts))], 1)
        j, rooted = highest_fall(g_scan, f_scan)
        pick, line = scan[rooted], np.arange(len(scan))[rooted]
        low[pick], high[pick] = at_scan[line, j[rooted]], at_scan[line, j[rooted] + 1]
        g_low[pick], g_high[pick] = g_scan[line, j[rooted]], g_scan[line, j[rooted] + 1]
        edge[pick] = False
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
    # Every sum's refined candidates in time order, its window's two ends, then the
    # samples of the candidates whose bracket held no root (so never below a sample:
    # a candidate left unrefined is below another's sample): the first largest wins.
    row_of = np.repeat(np.arange(rows), series)
    sum_of = np.tile(np.arange(series), rows)
    # (a refined bracket's peak is at least its sample; the row's ends are points)
    inner = np.flatnonzero(edge & (picked > 0) & (picked < counts[at] - 1))
    point_rows = np.concatenate([at, row_of, row_of, at[inner]])
    point_sums = np.concatenate([which, sum_of, sum_of, which[inner]])
    points = np.concatenate([x, start[row_of], end[row_of], middle[inner]])
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
