"""The largest value of a smooth periodic function over a period, for a block of
rows at once: samples that resolve the fastest mode, every sampled peak within
reach of the best refined by regula falsi on the derivative."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mdcalc.core.search import highest_fall

#: Newton steps that locate a sampled peak from its samples' parabola: the first
#: TOGETHER for every candidate at once, the rest for those still going.
NEWTON_STEPS, TOGETHER = 4, 3
#: Regula falsi (Illinois) steps that locate a sampled peak on its slope.
REGULA_FALSI_STEPS = 16
#: Parts a bracket whose slope keeps its sign is scanned in for a peak.
SCAN_STEPS = 16
#: Samples per period of the fastest mode when searching for a maximum.
SAMPLES_PER_MODE_PERIOD = 16
MAX_SAMPLES = 2**20


@dataclass(frozen=True)
class PeriodicMaximum:
    value: float
    time: float  # τ in [0, T) where it occurs [s]
    samples: int
    resolved: bool  # False: the fastest mode had fewer than 16 samples per period


def samples_for(period: float, fastest: float) -> tuple[int, bool]:
    """Samples per load period that give every mode of |λ| ≤ ``fastest`` 16 samples
    per its period: the least count of the ladder 256, 320, 384, 448, 512, 640, …
    (four an octave: 5/8, 6/8, 7/8 and all of a power of two; whole runs of 32) at or
    above that, at most 2²⁰."""
    samples, resolved = _samples(np.array([period]), np.array([fastest]))
    return int(samples[0]), bool(resolved[0])


def _samples(period: np.ndarray, fastest: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`samples_for` of every row. (A power of two alone would spend up to
    twice the samples a row needs, 1.44 times on average; the ladder 1.09.)"""
    wanted = SAMPLES_PER_MODE_PERIOD * fastest * period / (2.0 * math.pi)
    wanted = np.where(np.isfinite(wanted), wanted, 0.0)  # (a row without a state)
    with np.errstate(all="ignore"):
        power = np.ceil(np.log2(np.clip(wanted, 256.0, float(MAX_SAMPLES))))
    top = np.exp2(power)  # the least power of two at or above, from 256 to 2²⁰
    # log2 rounds: one step up or down where it missed the least power of two
    top = np.where((top < wanted) & (top < MAX_SAMPLES), 2.0 * top, top)
    top = np.where((0.5 * top >= wanted) & (top > 256), 0.5 * top, top)
    # then the least of 5/8, 6/8, 7/8 and 8/8 of it at or above (one eighth more
    # where the division rounded low)
    eighth = top / 8.0
    with np.errstate(all="ignore"):
        count = np.clip(np.ceil((wanted - 0.5 * top) / eighth), 1.0, 4.0)
    rung = 0.5 * top + count * eighth
    rung = np.where(rung < wanted, rung + eighth, rung)
    samples = np.where(top > 256, np.minimum(rung, top), top)
    return samples.astype(np.int64), samples >= wanted


def periodic_maximum(
    observe: Callable[[np.ndarray], np.ndarray],
    rate: Callable[[np.ndarray], np.ndarray],
    period: float,
    samples: int,
    sampled: np.ndarray | None = None,
    candidates: int = 4096,
) -> tuple[float, float]:
    """Largest value of one smooth periodic function over [0, T): :func:`periodic_maxima`
    on a block of one."""
    values, times = periodic_maxima(
        lambda rows, tau: observe(tau.ravel()).reshape(tau.shape),
        lambda rows, tau: rate(tau.ravel()).reshape(tau.shape),
        np.array([period]),
        samples,
        np.array([0]),
        None if sampled is None else sampled[None, :],
        candidates,
    )
    return float(values[0]), float(times[0])


Sampler = Callable[[np.ndarray, np.ndarray], np.ndarray]  # (rows (k,), τ (k, s)) -> (k, s)


def periodic_maxima(
    observe: Sampler,
    rate: Sampler,
    period: np.ndarray,
    samples: int,
    rows: np.ndarray,
    sampled: np.ndarray | None = None,
    candidates: int = 4096,
    bounds: tuple[np.ndarray, np.ndarray] | None = None,
    bend: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Largest value of a smooth periodic function over [0, T) for each of a block
    of rows (``rows`` names them to ``observe`` and ``rate``): values and times.

    Every sampled local maximum within reach of the best sample is refined, all at
    once, by regula falsi on the derivative between its neighbours (the state is
    continuous across the period's end, its rate need not be: a peak at τ = 0 is
    sought on either side of it); when many ringing peaks tie, all of them are
    refined (up to ``candidates`` a row, the largest first). Given ``bend`` (the rate
    and its own rate at times of given rows), a peak between two samples inside the
    period is found by Newton's steps from the parabola through its three samples
    (:func:`_newton`), where they settle; the others as above.

    Within reach: ``bounds``, each row's bound of |f''| over the period and a size
    (of |f|, scaled to its samples' rounding), give it exactly. A peak lies at most
    half a sample step from a sample, and above it by at most |f''|·h²/8, so a peak
    beside samples lower than the best by more than that (and 1e-12 of the size,
    for the samples' rounding) cannot win. Without
    them: with 16 samples per period of the fastest mode a sample lies at most
    1 - cos(π/16) ≈ 2 % of that mode's amplitude below its peak, and peaks more
    than 5 % of the sampled range below the best are taken not to win."""
    line = np.arange(len(rows))
    step = period / samples
    if sampled is None:
        values = observe(rows, np.arange(samples)[None, :] * step[:, None])
    else:
        values = sampled
    top = np.argmax(values, axis=1)  # a local maximum of its row, or a row of NaN
    best_value, best_time = values[line, top], top * step
    if bounds is None:
        margin = 0.05 * (best_value - np.min(values, axis=1))
        size = np.abs(best_value) + 20.0 * margin
    else:
        curvature, size = bounds
        margin = curvature * step * step / 8.0 + 1e-12 * size
    # the samples within reach of the best (few: one comparison and a flat search),
    # then the local maxima among them, neighbours taken across the period's end
    # (a broad peak holds many such samples: they take one flat index each, and only
    # a row's first and last sample look across its period's end for a neighbour)
    near = np.flatnonzero(values >= (best_value - margin)[:, None])
    flat = values.ravel()
    here = flat[near]
    left, right = flat.take(near - 1, mode="clip"), flat.take(near + 1, mode="clip")
    where = near % samples
    first, last = np.flatnonzero(where == 0), np.flatnonzero(where == samples - 1)
    left[first] = flat[near[first] + samples - 1]
    right[last] = flat[near[last] - (samples - 1)]
    peak = np.flatnonzero((here >= left) & (here >= right))
    owner, where, here = near[peak] // samples, where[peak], here[peak]
    crowded = np.flatnonzero(np.bincount(owner, minlength=len(rows)) > candidates)
    if crowded.size:  # many ringing ties: a row's largest ``candidates``
        keep = np.ones(len(owner), dtype=bool)
        for i in crowded:
            mine = np.flatnonzero(owner == i)
            keep[mine] = False
            keep[mine[np.argsort(here[mine])[::-1][:candidates]]] = True
        owner, where = owner[keep], where[keep]
    settled_owner, settled_time = owner[:0], np.empty(0)
    if bend is not None:  # the peaks between two samples by Newton steps, the rest by brackets
        settled_owner, settled_time, left = _newton(bend, rows, owner, where, flat, samples, step)
        owner, where = owner[left], where[left]
    owner, middle = _bracketed(observe, rate, rows, owner, where, samples, step, period, size)
    owner, middle = np.concatenate([settled_owner, owner]), np.concatenate([settled_time, middle])
    refined = observe(rows[owner], middle[:, None])[:, 0]
    if np.any(owner[1:] <= owner[:-1]):  # a row with several (the usual: one a row)
        order = np.lexsort((-refined, owner))  # each row's best refined peak first
        first = order[np.r_[True, owner[order][1:] != owner[order][:-1]]]
        owner, middle, refined = owner[first], middle[first], refined[first]
    clear = None if bounds is None else refined > best_value[owner] + 1e-12 * size[owner]
    return _best(observe, rows, best_value, best_time, owner, middle, refined, clear)


def _best(
    observe: Sampler,
    rows: np.ndarray,
    sampled: np.ndarray,
    time: np.ndarray,
    owner: np.ndarray,
    middle: np.ndarray,
    refined: np.ndarray,
    clear: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Each row's best sample (``sampled`` its value, at ``time``) or its best
    refined peak (``refined`` at ``middle``, of the rows ``owner``), whichever is
    higher: the sample's value taken exactly (the grid's carries its products'
    rounding; a row of NaN stays NaN), but where its peak is ``clear`` of it by
    more than that rounding."""
    best, time = sampled.copy(), time.copy()
    exact = np.ones(len(rows), dtype=bool)
    if clear is not None:
        exact[owner[clear]] = False
    exact &= ~np.isnan(sampled)
    at = np.flatnonzero(exact)
    best[at] = observe(rows[at], time[at, None])[:, 0]
    better = refined > best[owner]
    best[owner[better]], time[owner[better]] = refined[better], middle[better]
    return best, time


def _bracketed(
    observe: Sampler,
    rate: Sampler,
    rows: np.ndarray,
    owner: np.ndarray,
    where: np.ndarray,
    samples: int,
    step: np.ndarray,
    period: np.ndarray,
    size: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """The peaks beside sampled local maxima (of the rows ``owner``, at samples
    ``where``) by regula falsi on the rate between the neighbours: the rows that
    have one and its time."""
    if not owner.size:
        return owner, np.empty(0)
    # Each peak's bracket is its two neighbours, within [0, T]: the rate may jump
    # at τ = 0 (a velocity's rate is the acceleration, and the load jumps there),
    # and regula falsi across a jump need not settle. A peak at the sample τ = 0 has
    # two brackets, [0, h] and [T - h, T]; the rate at T is its left limit.
    wraps = where == 0
    owner = np.concatenate([owner, owner[wraps]])
    start = np.concatenate(
        [np.maximum(where - 1, 0), np.full(np.count_nonzero(wraps), samples - 1)]
    )
    end = np.concatenate([where + 1, np.full(np.count_nonzero(wraps), samples)])
    h, p = step[owner], period[owner]
    low, high = start * h, np.where(end < samples, end * h, p)

    who = rows[owner]  # one array for the calls that follow (a sampler may keep its rows)

    def slope(at: np.ndarray) -> np.ndarray:
        return rate(who, at[:, None])[:, 0]

    g_low, g_high = slope(low), slope(high)
    # A bracket whose slope keeps its sign (a trough and then a peak within it, as
    # where the rate jumps at τ = 0; two peaks close together) is scanned at
    # SCAN_STEPS points, and its change from + to - of the highest value refined;
    # not where its slopes move the value by less than 1e-12 of the row's size (a
    # flat state, whose every sample ties: a resolved state with both end slopes
    # that small is flat between them)
    moves = np.maximum(np.abs(g_low), np.abs(g_high)) * (high - low) > 1e-12 * size[owner]
    scan = np.flatnonzero(
        ~((g_low > 0.0) & (g_high < 0.0)) & np.isfinite(g_low) & np.isfinite(g_high) & moves
    )
    if scan.size:
        parts = np.arange(SCAN_STEPS + 1) / SCAN_STEPS
        at = low[scan, None] + (high - low)[scan, None] * parts
        at[:, -1] = high[scan]
        scanned = rows[owner[scan]]
        g_scan, f_scan = rate(scanned, at), observe(scanned, at)
        g_scan[:, 0], g_scan[:, -1] = g_low[scan], g_high[scan]
        j, rooted = highest_fall(g_scan, f_scan)
        pick, line, j = scan[rooted], np.flatnonzero(rooted), j[rooted]
        low[pick], high[pick] = at[line, j], at[line, j + 1]
        g_low[pick], g_high[pick] = g_scan[line, j], g_scan[line, j + 1]
    inside = (g_low > 0.0) & (g_high < 0.0)
    owner, low, high, p = owner[inside], low[inside], high[inside], p[inside]
    g_low, g_high = g_low[inside], g_high[inside]
    who = rows[owner]
    if len(owner) == 0:
        return owner, low
    # The slope's root by regula falsi, Illinois' way (the end that stays twice has
    # its slope halved): superlinear, a rate evaluation a step, and never outside
    # the bracket; from a bracket of two sample steps 16 steps reach the rounding.
    # A candidate leaves once its slope is within 1e-12 of its bracket's end slopes
    # (about 5 steps): its time is then off by about 1e-12 of a sample step, and its
    # value by the square of that (those left take the rest of the steps).
    done = np.empty(len(owner))  # each candidate's time
    active = np.arange(len(owner))
    settled_at = 1e-12 * np.maximum(g_low, -g_high)
    was_up = np.zeros(len(owner), dtype=bool)  # the last step moved the low end
    was_down = np.zeros(len(owner), dtype=bool)  # ... the high end
    for _ in range(REGULA_FALSI_STEPS):
        with np.errstate(all="ignore"):
            middle = high - g_high * (high - low) / (g_high - g_low)
        middle = np.where(np.isfinite(middle), np.clip(middle, low, high), low)
        g = slope(middle)
        settled = np.abs(g) <= settled_at
        if settled.any():
            done[active[settled]] = middle[settled]
            go = ~settled
            active, middle, g, low, high = active[go], middle[go], g[go], low[go], high[go]
            g_low, g_high, was_up, was_down = g_low[go], g_high[go], was_up[go], was_down[go]
            settled_at, p, who = settled_at[go], p[go], who[go]
            if not active.size:
                break
        up = g > 0.0
        g_high = np.where(up & was_up, 0.5 * g_high, g_high)  # the high end kept twice
        g_low = np.where(~up & was_down, 0.5 * g_low, g_low)  # the low end kept twice
        low, g_low = np.where(up, middle, low), np.where(up, g, g_low)
        high, g_high = np.where(up, high, middle), np.where(up, g_high, g)
        was_up, was_down = up, ~up
    done[active] = np.where(np.abs(g_low) <= np.abs(g_high), low, high)
    return owner, done % period[owner]


def _newton(
    bend: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
    rows: np.ndarray,
    owner: np.ndarray,
    where: np.ndarray,
    flat: np.ndarray,
    samples: int,
    step: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The peaks beside sampled local maxima inside the period (the rows ``owner``,
    at samples ``where`` of ``flat``, the rows' samples end to end) by Newton's steps
    on the rate, from the vertex of the parabola through the three samples: the
    rows whose peak settled, its time, and which candidates are left to the
    brackets (at the period's ends, where the rate may jump; a flat top; a step
    that finds the rate rising, leaves the two samples either side or does not
    settle within :data:`NEWTON_STEPS`).

    The vertex is near the peak (its error shrinks with (hλ)², for a mode of λ), and
    each step squares the error. A candidate settles once its step is under 1e-7 of
    a sample step, and takes that step: its time is then within some 1e-14 of a
    step (regula falsi's 1e-12). Three steps (:data:`TOGETHER`), which settle
    nearly every candidate, are taken for all at once, a fourth for those still
    going: three evaluations of the rate and its rate where regula falsi took six
    or seven of the rate."""
    inner = np.flatnonzero((where >= 1) & (where <= samples - 2))
    if not inner.size:
        return owner[:0], np.empty(0), np.ones(len(owner), dtype=bool)
    at = owner[inner] * samples + where[inner]
    before, top, after = flat[at - 1], flat[at], flat[at + 1]
    h = step[owner[inner]]
    with np.errstate(all="ignore"):
        tau = (where[inner] + 0.5 * (before - after) / (before - 2.0 * top + after)) * h
    low, high = (where[inner] - 1) * h, (where[inner] + 1) * h
    who = rows[owner[inner]]  # (one array for the first steps: a sampler may keep its rows)
    bad = ~np.isfinite(tau)
    for _ in range(TOGETHER):  # (most settle in these)
        tau, move, refused = _step(bend, who, tau, low, high)
        bad |= refused
    done = np.full(len(inner), np.nan)
    settled = ~bad & (np.abs(move) <= 1e-7 * h)
    done[settled] = tau[settled]
    active = np.flatnonzero(~bad & ~settled)
    tau, low, high, h = tau[active], low[active], high[active], h[active]
    for _ in range(NEWTON_STEPS - TOGETHER if active.size else 0):
        tau, move, bad = _step(bend, rows[owner[inner[active]]], tau, low, high)
        settled = ~bad & (np.abs(move) <= 1e-7 * h)
        done[active[settled]] = tau[settled]
        go = ~bad & ~settled
        active, tau, low, high, h = active[go], tau[go], low[go], high[go], h[go]
        if not active.size:
            break
    ok = np.isfinite(done)
    left_out = np.ones(len(owner), dtype=bool)
    left_out[inner[ok]] = False
    return owner[inner[ok]], done[ok], left_out


def _step(
    bend: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
    who: np.ndarray,
    tau: np.ndarray,
    low: np.ndarray,
    high: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One Newton step on the rate at times ``tau`` of the rows ``who``: the new
    times, the steps, and where a step is refused (the curvature not below 0, the
    new time outside [low, high], or NaN)."""
    with np.errstate(all="ignore"):
        g, curve = bend(who, tau[:, None])
        move = -g[:, 0] / curve[:, 0]
    tau = tau + move
    return tau, move, ~((curve[:, 0] < 0.0) & (tau >= low) & (tau <= high))
