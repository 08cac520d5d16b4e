"""The block integrator (core/block_ode.py): scipy's DOP853 for every row of a block,
each with its own steps, end and stop.

Expected values come from scipy's own DOP853 (solve_ivp, the single scene's
integrator) and from closed forms, not from the block integrator."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from mdcalc.core.block_ode import dop853_block

STIFFNESS = np.array([0.5, 1.0, 2.0, 3.5, 7.0])
ENDS = np.array([3.0, 5.0, 8.0, 13.0, 21.0])


def _rhs(rows, t, y):
    # a softening oscillator with quadratic damping: no closed form, smooth
    k = STIFFNESS[rows]
    return np.stack([y[:, 1], -k * np.sin(y[:, 0]) - 0.1 * y[:, 1] * np.abs(y[:, 1])], axis=1)


def _scipy(row: int, rtol: float, atol: float, dense: bool = False):
    def f(t, y):
        return [y[1], -STIFFNESS[row] * math.sin(y[0]) - 0.1 * y[1] * abs(y[1])]

    return solve_ivp(
        f, (0.0, ENDS[row]), [1.0, 0.0], method="DOP853", rtol=rtol, atol=atol, dense_output=dense
    )


def test_each_row_meets_scipys_dop853_within_its_tolerance():
    y0 = np.tile([1.0, 0.0], (5, 1))
    run = dop853_block(_rhs, np.zeros(5), y0, ENDS, rtol=1e-10, atol=1e-13)
    assert run.done.all() and not run.failed.any() and not run.stopped.any()
    for row in range(5):
        tight = _scipy(row, 1e-13, 1e-16)  # the truth, to about 1e-13
        same = _scipy(row, 1e-10, 1e-13)  # the single scene's run
        scale = np.abs(tight.y[:, -1]).max()
        assert np.abs(run.y[row] - tight.y[:, -1]).max() < 1e-8 * scale
        assert np.abs(run.y[row] - same.y[:, -1]).max() < 1e-8 * scale
        # its work is scipy's: the same steps, up to rounding where the error estimate
        # is itself at rounding level
        assert abs(run.evaluations[row] - same.nfev) <= 0.15 * same.nfev


def test_a_row_does_not_depend_on_the_block_it_is_in():
    y0 = np.tile([1.0, 0.0], (5, 1))
    whole = dop853_block(_rhs, np.zeros(5), y0, ENDS, rtol=1e-11, atol=1e-14)
    for row in range(5):
        rows = [row]

        def alone(r, t, y, rows=rows):
            return _rhs(np.asarray(rows)[r], t, y)

        one = dop853_block(alone, np.zeros(1), y0[:1], ENDS[row : row + 1], rtol=1e-11, atol=1e-14)
        assert one.y[0].tolist() == whole.y[row].tolist()  # bit for bit
        assert one.evaluations[0] == whole.evaluations[row]


def test_the_continuous_extension_is_scipys():
    seen = []
    y0 = np.tile([1.0, 0.0], (5, 1))
    dop853_block(
        _rhs,
        np.zeros(5),
        y0,
        ENDS,
        rtol=1e-10,
        atol=1e-13,
        on_step=lambda step: seen.append((step.rows, step.t_old, step.t_new, step.dense())),
    )
    row = 3
    same = _scipy(row, 1e-10, 1e-13, dense=True)
    for rows, t_old, t_new, dense in seen[5:40]:
        j = np.flatnonzero(rows == row)
        if not j.size:
            continue
        mid = 0.5 * (t_old[j] + t_new[j])
        got = dense.take(j).at(mid, 0)[0]
        assert got == pytest.approx(float(same.sol(mid[0])[0]), abs=1e-8)


def test_stop_and_failure_are_per_row():
    # dy/dt = -1 from y = 1, 2, 3 to t = 5: rows cross y = 0 at t = 1, 2, 3 (stopped)
    # unless their end comes first; a row whose slope is NaN fails alone.
    slopes = np.array([-1.0, -1.0, -1.0, np.nan, -1.0])

    def rhs(rows, t, y):
        return np.broadcast_to(slopes[rows], (rows.size,))[:, None] * np.ones_like(y)

    y0 = np.array([[1.0], [2.0], [3.0], [1.0], [9.0]])
    run = dop853_block(
        rhs,
        np.zeros(5),
        y0,
        np.full(5, 5.0),
        rtol=1e-9,
        atol=1e-12,
        stop=lambda step: (step.y_old[:, 0] >= 0.0) & (step.y_new[:, 0] <= 0.0),
    )
    assert run.stopped.tolist() == [True, True, True, False, False]
    assert run.failed.tolist() == [False, False, False, True, False]
    assert run.done.tolist() == [False, False, False, False, True]
    assert run.y[4, 0] == pytest.approx(4.0, abs=1e-12)  # 9 - 5, exact for a constant slope
    assert np.all(run.y[:3, 0] <= 0.0)  # each stopped just past its crossing
