"""The candidates for each sum's largest value: the sampled local maxima within the
slack (the sampling error) of its best sample, found on the whole grid or in the
windows that can hold them; and which of them are worth refining."""

from __future__ import annotations

import math

import numpy as np

from mdcalc.core.cosine_sums.samples import Sums
from mdcalc.core.powers import powers

#: Samples evaluated at once (rows × times of a tile).
TILE = 1 << 18
EPS = float(np.finfo(float).eps)
#: Rows of at least this many samples are sampled in windows (:func:`windows`)...
WINDOW_SAMPLES = 1024
#: ... where each sum has at least this many samples per peak of its largest term...
WINDOW_SPACING = 64
#: ... and its windows cover at most this share of the row's samples.
WINDOW_SHARE = 0.5

Candidates = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]
"""Candidates' rows, sums and sample indices, and the values of the samples before,
at and after each."""


def find(sums: Sums, live: np.ndarray, counts: np.ndarray, slack: np.ndarray) -> Candidates:
    """The candidates of the rows ``live``, by tiles of rows of like sample counts:
    rows grouped by the power of two above their count, so that a tile pads a row by
    at most twice its samples. A long row is sampled only in the windows where a sum
    may come within its slack of its best (:func:`windows`): the same candidates."""
    series = sums.series
    found: list[Candidates] = []
    level = np.ceil(np.log2(counts[live])).astype(np.int64)
    for value in np.unique(level):
        members = live[level == value]
        if int(np.max(counts[members])) >= WINDOW_SAMPLES:
            whole: list[np.ndarray] = []
            per = max(1, TILE // (series * (int(np.max(counts[members])) // WINDOW_SPACING)))
            for first in range(0, len(members), per):
                group = members[first : first + per]
                use, low, high, wide = windows(sums, group, counts, slack)
                whole.append(group[~use])
                order = np.argsort(wide[use])  # like with like
                group, wide = group[use][order], wide[use][order]
                low, high = low[use][order], high[use][order]
                sub = max(1, TILE // max(1, series * low.shape[2] * int(np.max(wide, initial=1))))
                for part in range(0, len(group), sub):
                    rows = slice(part, part + sub)
                    candidates, lost = in_windows(
                        sums, group[rows], counts, slack, low[rows], high[rows],
                        int(np.max(wide[rows])),
                    )  # fmt: skip
                    found.append(candidates)
                    whole.append(lost)
            members = np.concatenate(whole)
            if not members.size:
                continue
        per = max(1, TILE // (series * int(np.max(counts[members]))))
        for first in range(0, len(members), per):
            group = members[first : first + per]
            found.append(on_grid(sums, group, counts, slack))
    return joined(found)


def joined(found: list[Candidates]) -> Candidates:
    """The candidates of many tiles as one."""
    if not found:
        empty = np.array([], dtype=np.int64)
        return empty, empty, empty, np.array([]), np.array([]), np.array([])
    return tuple(np.concatenate([f[i] for f in found]) for i in range(6))  # type: ignore[return-value]


def on_grid(sums: Sums, group: np.ndarray, counts: np.ndarray, slack: np.ndarray) -> Candidates:
    """The sampled local maxima within the slack of the best sample of each sum, for
    the rows of ``group`` (a sample past a row's count is no sample; ``counts`` and
    ``slack`` of every row, as for :func:`windows` and :func:`in_windows`). The few
    samples within the slack are found first (a comparison and a flat search of the
    block), the local maxima among them after."""
    counts, slack = counts[group], slack[group]
    width = int(np.max(counts))
    series = sums.series
    chunk = max(1, TILE // (series * len(group)))
    limit = counts[:, None]

    def sampled(index: np.ndarray) -> np.ndarray:
        """The sums at ``index``, -inf where a row has no such sample: before its
        first (index -1) and from its count on (the columns past the smallest)."""
        values = sums.grid(group, index)
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
    floor = (best - slack)[:, :, None]
    found: list[Candidates] = []
    for first in range(0, width, chunk):  # the local maxima near it
        index = np.arange(first - 1, min(first + chunk + 1, width + 1))
        values = whole if whole is not None else sampled(index)
        middle = values[:, :, 1:-1]
        row, which, col = np.unravel_index(np.flatnonzero(middle >= floor), middle.shape)
        before, here, after = (values[row, which, col + i] for i in range(3))
        at = index[col + 1]
        keep = (here >= before) & (here >= after) & (at >= 0) & (at < counts[row])
        found.append(
            (group[row[keep]], which[keep], at[keep], before[keep], here[keep], after[keep])
        )
    return joined(found)


def windows(
    sums: Sums, group: np.ndarray, counts: np.ndarray, slack: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The windows of samples that hold every candidate of a sum and its two
    neighbours, for the rows of ``group``: whether a row is sampled in its windows,
    their first and last samples (G, S, P; a peak's window outside the row is
    clipped to its first or last sample) and each row's longest window.

    A candidate lies within its sum's slack of the best sample, so at or above
    L - slack, L a lower bound of the best sample. A sum R + Σ Bₖ·cos(βₖt) is there
    at most R + Bⱼ·cos(βⱼt) + Σ_{k≠j}|Bₖ|, so its largest term j reaches at least
    L - slack - R - Σ_{k≠j}|Bₖ| there: within arccos of that over |Bⱼ| of a peak of
    βⱼt. L: the sum's largest value at those peaks less the slack (the best sample
    is within the slack of the sum's largest value). Allowances for rounding: on
    the sum, 10⁻⁹ of its scale plus 8ε·w·t of it (a sample's angle w·t rounds by
    ε·w·t); on a window's edges, 10⁻⁹ of the angle and two samples. A row is
    windowed where it has at least WINDOW_SAMPLES samples, at least WINDOW_SPACING
    samples per peak of that term in each sum, and windows that cover at most
    WINDOW_SHARE of its samples in each sum."""
    constant, b, w = sums.constant[group], sums.amplitudes[group], sums.frequencies[group]
    counts, slack = counts[group], slack[group]
    rows, series, modes = b.shape
    magnitude = np.abs(b)
    j = np.argmax(magnitude, axis=2)  # (G, S): each sum's largest term
    bj = np.take_along_axis(b, j[:, :, None], axis=2)[:, :, 0]
    wj = np.take_along_axis(w, j, axis=1)
    top = np.where(bj >= 0.0, 0.0, math.pi)  # its peaks at βⱼt = top + 2πn
    t0, dt = sums.start[group][:, None], sums.step[group][:, None]
    with np.errstate(all="ignore"):
        first = np.ceil((wj * t0 - top) / (2.0 * math.pi))
        last = np.floor((wj * (t0 + dt * (counts - 1)[:, None]) - top) / (2.0 * math.pi))
        peaks = last - first + 1.0
    spaced = np.isfinite(peaks) & (WINDOW_SPACING * peaks <= counts[:, None])
    fit = (counts >= WINDOW_SAMPLES) & np.all(spaced, axis=1)
    if not fit.any():
        none = np.zeros((rows, series, 0), dtype=np.int64)
        return fit, none, none, np.zeros(rows, dtype=np.int64)
    # L at the peaks, by powers of e^{iβₖ·2π/βⱼ}: (P, G, S)
    inside = np.where(fit[:, None], peaks, 0.0)
    turns = np.arange(int(np.max(inside)))
    with np.errstate(all="ignore"):
        at = (top + 2.0 * math.pi * first) / wj  # the first peak's time
    value = np.broadcast_to(constant, (len(turns), rows, series))
    for k in range(modes):
        wk = w[:, k, None]
        with np.errstate(all="ignore"):
            phase = np.exp(1j * wk * at) * powers(np.exp(2j * math.pi * wk / wj), len(turns))
        value = value + b[:, :, k] * phase.real
    value = np.where(turns[:, None, None] < inside, value, -np.inf)
    lower = np.max(value, axis=0, initial=-np.inf) - slack
    angles = np.max(w, axis=1) * np.maximum(np.abs(t0[:, 0]), np.abs(t0[:, 0] + dt[:, 0] * counts))
    allowance = (1e-9 + 8.0 * EPS * angles[:, None]) * (np.abs(constant) + magnitude.sum(axis=2))
    below = lower - slack - constant - (magnitude.sum(axis=2) - np.abs(bj)) - allowance
    with np.errstate(all="ignore"):
        reach = np.arccos(np.clip(below / np.abs(bj), -1.0, 1.0))
    reach = np.where(np.isfinite(reach) & (below > -np.abs(bj)), reach, math.pi)
    # every peak's window (one more each side: their windows may reach in)
    n = first[:, :, None] + np.arange(-1, len(turns) + 1)  # (G, S, P)
    angle = top[:, :, None] + 2.0 * math.pi * n
    with np.errstate(all="ignore"):
        half = (reach[:, :, None] + 1e-9 * (1.0 + np.abs(angle))) / wj[:, :, None]
        low = np.floor((angle / wj[:, :, None] - half - t0[:, :, None]) / dt[:, :, None]) - 2.0
        high = np.ceil((angle / wj[:, :, None] + half - t0[:, :, None]) / dt[:, :, None]) + 2.0
    last_sample = (counts - 1)[:, None, None]
    low, high = np.clip(low, 0, last_sample), np.clip(high, 0, last_sample)
    lengths = np.where(fit[:, None, None], high - low + 1.0, 0.0)
    wide = np.max(lengths, axis=(1, 2)).astype(np.int64)
    use = fit & np.all(np.sum(lengths, axis=2) <= WINDOW_SHARE * counts[:, None], axis=1)
    return use, low.astype(np.int64), high.astype(np.int64), wide


def in_windows(
    sums: Sums,
    group: np.ndarray,
    counts: np.ndarray,
    slack: np.ndarray,
    low: np.ndarray,
    high: np.ndarray,
    width: int,
) -> tuple[Candidates, np.ndarray]:
    """:func:`on_grid` of the rows of ``group`` from their windows only (samples
    ``low`` to ``high`` (G, S, P)), and the rows that need the whole grid (a sample
    within the slack beside one not sampled, not past the row's end: never, unless
    the windows' allowance for rounding was too small). Each window is sampled
    ``width`` long, moved inside its row where it would cross its end (past that
    end where the row is shorter: no samples there); a candidate counts in the
    window whose own samples hold it (the best sample is the best of them all)."""
    ends, slack = counts[group] - 1, slack[group]
    starts = np.clip(low, 0, np.maximum(ends + 1 - width, 0)[:, None, None])
    values = sums.windows(group, starts, width)  # (G, S, P, W)
    if int(np.max(starts + (width - 1) - ends[:, None, None])) > 0:
        values[starts[..., None] + np.arange(width) > ends[:, None, None, None]] = -np.inf
    size, series = values.shape[:2]
    values = values.reshape(size, series, -1)
    floor = (np.max(values, axis=2) - slack)[:, :, None]
    row, which, col = np.unravel_index(np.flatnonzero(values >= floor), values.shape)
    window, place = np.divmod(col, width)
    at = starts[row, which, window] + place
    own = (at >= low[row, which, window]) & (at <= high[row, which, window])
    row, which, col, place, at = row[own], which[own], col[own], place[own], at[own]
    here, last = values[row, which, col], values.shape[2] - 1
    before = np.where(place > 0, values[row, which, np.maximum(col - 1, 0)], -np.inf)
    after = np.where(place < width - 1, values[row, which, np.minimum(col + 1, last)], -np.inf)
    missing = ((place == 0) & (at > 0)) | ((place == width - 1) & (at < ends[row]))
    lost = np.zeros(size, dtype=bool)
    lost[row[missing]] = True
    keep = (here >= before) & (here >= after) & ~lost[row]
    found = (group[row[keep]], which[keep], at[keep], before[keep], here[keep], after[keep])
    return found, group[lost]


def worth_refining(sums: Sums, found: Candidates) -> np.ndarray:
    """Which candidates may hold their sum's largest value. Between its neighbours a
    sum is at most the parabola through the three samples plus Σ|B·w³|·Δt³/(9√3)
    (the interpolation's error), and a candidate's peak is at least its sample: a
    candidate whose bound is below another's sample is not refined (an allowance
    for rounding of 10⁻⁹ of the sum's scale). A candidate at a row's end is kept."""
    at, which, _, before, here, after = found
    b, w = sums.amplitudes[at, which], sums.frequencies[at]
    cubic = np.sum(np.abs(b) * w**3, axis=1) * sums.step[at] ** 3 / (9.0 * math.sqrt(3.0))
    scale = 1e-9 * (np.abs(sums.constant[at, which]) + np.sum(np.abs(b), axis=1))
    with np.errstate(all="ignore"):
        bend = 2.0 * here - before - after
        rise = np.where(bend > 0.0, (after - before) ** 2 / (8.0 * bend), 0.0)
    bound = np.where(np.isfinite(before) & np.isfinite(after), here + rise + cubic + scale, np.inf)
    owner = at * sums.series + which
    surely = np.full(len(sums.start) * sums.series, -np.inf)
    np.fmax.at(surely, owner, here - scale)
    return ~(bound < surely[owner])
