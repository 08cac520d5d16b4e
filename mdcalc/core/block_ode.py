"""ODE runs over a block of scenes: scipy's DOP853 (Dormand–Prince 8(5,3)) stepped for
every row of a block at once, each row with its own step size, error control, end
and stop, as a study's samples need (issue 31).

The method is scipy's, row by row: its Butcher tableau (read from
:class:`scipy.integrate.DOP853`), its initial step (``select_initial_step``), its
error norm (the 5th- and 3rd-order estimates combined) and its step-size control
(safety 0.9, factors 0.2 to 10, no growth right after a rejection). A row's steps
are therefore those :func:`mdcalc.core.ode.advance` takes with ``DOP853`` for the
same scene, and its values agree with that run to within the rounding of the
sums (far inside the tolerance). A row ends at its ``t1``, where its ``stop`` test
holds after a step (the caller's terminal event, such as a stall), or fails: a
value that is not finite, a step below ten units in the last place of t, or more
right-hand-side evaluations than ``budget``. The caller solves the stopped and the
failed rows alone, as single scenes.

``on_step`` sees every accepted step of the rows that took one; its
:meth:`Step.dense` gives DOP853's 7th-order continuous extension on the step
(three more evaluations), for maxima and values between the steps.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: rhs(rows, t, y) -> dy/dt: ``rows`` index the block (for per-row parameters),
#: ``t`` has shape (m,), ``y`` and the result (m, d).
BlockRhs = Callable[[Any, Any, Any], Any]

SAFETY = 0.9
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
#: DOP853's error estimator is of order 7: a step's error scales as h⁸.
EXPONENT = -1.0 / 8.0


def _tableau() -> Any:
    from scipy.integrate import DOP853

    return DOP853


@dataclass
class Dense:
    """DOP853's continuous extension over one step of some rows."""

    t_old: Any  # (m,)
    h: Any  # (m,)
    y_old: Any  # (m, d)
    F: Any  # (7, m, d)

    def at(self, t: Any, component: int) -> Any:
        """One component at ``t``: shape (m,), or (k, m) for k points a row."""
        x = (t - self.t_old) / self.h
        rest = 1.0 - x
        y = np.zeros(np.shape(x))
        F = np.ascontiguousarray(self.F[:, :, component])  # rows next to each other
        for i, f in enumerate(F[::-1]):
            y += f  # in place: (y + f)·x, the same rounding, no temporaries
            y *= x if i % 2 == 0 else rest
        y += self.y_old[:, component]
        return y

    def crossing(self, component: int, level: Any, iterations: int = 56) -> Any:
        """t where the component rises through ``level`` in the step (it is below at
        the step's start and not below at its end), by bisection on the extension to
        2⁻⁵⁶ of the step: the root scipy's event location finds (brentq, 4 ulp)."""
        low = self.t_old
        high = self.t_old + self.h
        for _ in range(iterations):
            middle = 0.5 * (low + high)
            below = self.at(middle, component) < level
            low, high = np.where(below, middle, low), np.where(below, high, middle)
        return high

    def take(self, at: Any) -> Dense:
        """The rows ``at`` (an index or mask) of this extension."""
        return Dense(self.t_old[at], self.h[at], self.y_old[at], self.F[:, at])


@dataclass
class Step:
    """An accepted step of the rows ``rows``: from ``t_old`` to ``t_new``."""

    rows: Any
    t_old: Any
    t_new: Any
    y_old: Any
    y_new: Any
    f_old: Any
    f_new: Any
    K: Any  # (13, m, d) stages
    rhs: BlockRhs
    inputs: int | None = None  # the components rhs reads (None: all)
    _dense: Dense | None = field(default=None, repr=False)

    def dense(self) -> Dense:
        if self._dense is None:
            tableau = _tableau()
            h = (self.t_new - self.t_old)[:, None]
            m, d = self.y_old.shape
            K = np.empty((16, m, d))
            K[:13] = self.K
            for s, (a, c) in enumerate(zip(tableau.A_EXTRA, tableau.C_EXTRA, strict=True), 13):
                dy = _combine(a[:s], K[:s]) * h
                y = (self.y_old + dy)[:, : self.inputs]
                K[s] = self.rhs(self.rows, self.t_old + c * h[:, 0], y)
            delta = self.y_new - self.y_old
            F = np.empty((7, m, d))
            F[0] = delta
            F[1] = h * self.f_old - delta
            F[2] = 2.0 * delta - h * (self.f_new + self.f_old)
            for j in range(4):
                F[3 + j] = h * _combine(tableau.D[j], K)
            self._dense = Dense(self.t_old, h[:, 0], self.y_old, F)
        return self._dense


@dataclass
class BlockRun:
    t: Any  # (n,) where each row ended
    y: Any  # (n, d)
    done: Any  # bool (n,): reached t1
    stopped: Any  # bool: its stop test ended it
    failed: Any  # bool: not finite, too small a step, or over the budget
    evaluations: Any  # int (n,)
    step: Any  # (n,) the step size each row's control proposes next


def _squares(x: Any) -> Any:
    """Σ x² over the components, in index order (a row's sum never depends on the
    block it is in, as a BLAS or pairwise sum over the block could)."""
    total = x[:, 0] * x[:, 0]
    for j in range(1, x.shape[1]):
        total = total + x[:, j] * x[:, j]
    return total


def _finite(x: Any) -> Any:
    """The rows of x (m, d) whose every component is finite (a column at a time:
    a reduction along a short axis is slow)."""
    ok = np.isfinite(x[:, 0])
    for j in range(1, x.shape[1]):
        ok &= np.isfinite(x[:, j])
    return ok


def _rms(x: Any) -> Any:
    return np.sqrt(_squares(x) / x.shape[1])


def _combine(weights: Any, K: Any) -> Any:
    """Σ_j weights[j]·K[j] in index order, zero weights skipped: elementwise, so a
    row's value is the same in a block of any size."""
    total, term = None, None
    for w, k in zip(weights.tolist(), K, strict=False):
        if w == 0.0:
            continue
        if total is None:
            total = w * k
            term = np.empty_like(total)
        else:
            total += np.multiply(w, k, out=term)
    return np.zeros(K.shape[1:]) if total is None else total


def dop853_block(
    rhs: BlockRhs,
    t0: Any,
    y0: Any,
    t1: Any,
    *,
    rtol: float,
    atol: Any,
    stop: Callable[[Step], Any] | None = None,
    on_step: Callable[[Step], None] | None = None,
    budget: Any = 100_000,
    dense_counted: bool = False,
    first_step: Any = None,
    quadratures: int = 0,
) -> BlockRun:
    """Integrate dy/dt = rhs from ``t0`` to ``t1`` (arrays of shape (n,)), y of
    shape (n, d), ``atol`` of shape (n, d) or broadcastable. ``stop(step)`` marks the
    rows of an accepted step that crossed the caller's terminal event (the caller may
    locate the event on ``step.dense()``); those rows end there. ``budget`` (one
    number, or one a row) bounds a row's right-hand-side evaluations as scipy counts
    them: 2 at the start, 12 a step tried, and with ``dense_counted`` 3 more a step
    taken (solve_ivp with ``dense_output``, which builds the extension after every
    step) whether or not this caller asks for the extension: a row's count never
    depends on other rows. ``first_step`` (n,) replaces scipy's initial step (one
    evaluation at the start, not two): a run that goes on from where another ended
    passes that run's :attr:`BlockRun.step`, the size its control proposed next.
    The last ``quadratures`` components are integrals that ``rhs`` does not read:
    it is given y without them, and their stages are not formed."""
    from mdcalc.core import budget as time_budget

    tableau = _tableau()
    A, B, C, E3, E5 = tableau.A, tableau.B, tableau.C, tableau.E3, tableau.E5
    n, d = y0.shape
    t = np.array(t0, dtype=float, copy=True)
    t1 = np.broadcast_to(np.asarray(t1, dtype=float), (n,))
    y = np.array(y0, dtype=float, copy=True)
    atol = np.broadcast_to(np.asarray(atol, dtype=float), (n, d))
    everyone = np.arange(n)
    limit = np.broadcast_to(np.asarray(budget), (n,))  # one for all rows, or each its own
    inputs = d - quadratures
    f = rhs(everyone, t, y[:, :inputs])
    if first_step is not None:
        evaluations = np.full(n, 1, dtype=np.int64)
        # not cut to the end here: the step's end is, and the cut step proposes what
        # was planned (a tiny piece must not shrink the next one's first step)
        h_abs = np.array(first_step, dtype=float, copy=True)
    else:
        evaluations = np.full(n, 2, dtype=np.int64)
        h_abs = _initial_step(rhs, everyone, t, y, f, t1, rtol, atol, inputs)
    rejected = np.zeros(n, dtype=bool)
    # a row already at its end is done whatever its derivative there
    failed = ~(_finite(f) & np.isfinite(h_abs) & _finite(y)) & (t < t1)
    stopped = np.zeros(n, dtype=bool)
    live = (t < t1) & ~failed
    while live.any():
        time_budget.check()
        rows = np.flatnonzero(live)
        whole = rows.size == n  # every row steps: copies, not gathers
        sel = slice(None) if whole else rows  # a view of every row, or a gather
        tr, yr, fr = (t.copy(), y.copy(), f.copy()) if whole else (t[rows], y[rows], f[rows])
        hr, again = h_abs[sel], rejected[sel].copy()
        min_step = 10.0 * np.abs(np.nextafter(tr, np.inf) - tr)
        hr = np.where(again, hr, np.maximum(hr, min_step))
        tiny = again & (hr < min_step)
        planned = hr
        t_new = np.minimum(tr + hr, t1[sel])
        hr = t_new - tr  # the step taken, as scipy's h_abs after the end clips it
        h = hr[:, None]
        K = np.empty((13, rows.size, d))
        K[0] = fr
        with np.errstate(all="ignore"):
            for s in range(1, 12):
                dy = _combine(A[s, :s], K[:s, :, :inputs])
                dy *= h
                dy += yr[:, :inputs]  # y + h·Σ a·K, in that order
                K[s] = rhs(rows, tr + C[s] * h[:, 0], dy)
            y_new = yr + h * _combine(B, K[:12])
            f_new = rhs(rows, t_new, y_new[:, :inputs])
            K[12] = f_new
            scale = atol[sel] + np.maximum(np.abs(yr), np.abs(y_new)) * rtol
            err5 = _squares(_combine(E5, K) / scale)
            err3 = _squares(_combine(E3, K) / scale)
            both_zero = (err5 == 0.0) & (err3 == 0.0)
            error = np.where(
                both_zero,
                0.0,
                h[:, 0] * err5 / np.sqrt(np.where(both_zero, 1.0, err5 + 0.01 * err3) * d),
            )
            grow = SAFETY * error**EXPONENT
        counted = evaluations[sel] + 12  # a new array
        if dense_counted:
            counted += np.where((error < 1.0) & np.isfinite(error), 3, 0)
        evaluations[sel] = counted
        bad = tiny | ~np.isfinite(error) | ~_finite(y_new)
        bad |= ~_finite(f_new) | (counted > limit[sel])
        accept = (error < 1.0) & ~bad
        factor = np.where(error == 0.0, MAX_FACTOR, np.minimum(MAX_FACTOR, grow))
        factor = np.where(again, np.minimum(1.0, factor), factor)
        proposed = hr * factor
        # a last step cut short by the end proposes what its row had planned, at least
        proposed = np.where(t_new >= t1[sel], np.maximum(proposed, planned), proposed)
        h_abs[sel] = np.where(accept, proposed, hr * np.maximum(MIN_FACTOR, grow))
        rejected[sel] = ~accept
        failed[sel] |= bad
        took = np.flatnonzero(accept)
        if took.size == rows.size:  # every row took its step: no copies
            at = rows
            step = Step(at, tr, t_new, yr, y_new, fr, f_new, K, rhs, inputs)
        elif took.size:
            at = rows[took]
            step = Step(
                at,
                tr[took],
                t_new[took],
                yr[took],
                y_new[took],
                fr[took],
                f_new[took],
                K[:, took],
                rhs,
                inputs,
            )
        if took.size:
            if on_step is not None:
                on_step(step)
            if stop is not None:
                stopped[at] = stop(step)
            if whole and took.size == n:
                t[:], y[:], f[:] = t_new, y_new, f_new
            else:
                t[at], y[at], f[at] = t_new[took], y_new[took], f_new[took]
        live = (t < t1) & ~failed & ~stopped
    return BlockRun(t, y, (t >= t1) & ~failed & ~stopped, stopped, failed, evaluations, h_abs)


def _initial_step(
    rhs: BlockRhs,
    rows: Any,
    t: Any,
    y: Any,
    f: Any,
    t1: Any,
    rtol: float,
    atol: Any,
    inputs: int,
) -> Any:
    """scipy's ``select_initial_step``, row by row (one more evaluation)."""
    scale = atol + np.abs(y) * rtol
    d0, d1 = _rms(y / scale), _rms(f / scale)
    h0 = np.where((d0 < 1e-5) | (d1 < 1e-5), 1e-6, 0.01 * d0 / np.where(d1 > 0, d1, 1.0))
    h0 = np.minimum(h0, t1 - t)
    f1 = rhs(rows, t + h0, (y + h0[:, None] * f)[:, :inputs])
    d2 = _rms((f1 - f) / scale) / np.where(h0 > 0, h0, 1.0)
    with np.errstate(divide="ignore"):
        h1 = np.where(
            (d1 <= 1e-15) & (d2 <= 1e-15),
            np.maximum(1e-6, h0 * 1e-3),
            (0.01 / np.maximum(d1, d2)) ** (1.0 / 8.0),
        )
    return np.minimum(np.minimum(100.0 * h0, h1), t1 - t)
