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


def test_a_row_at_its_end_is_done_whatever_its_slope_there():
    # A caller running pieces in lockstep passes rows already at their end with
    # whatever right-hand side the piece has for them: they are done, not failed.
    def rhs(rows, t, y):
        return np.where(rows[:, None] == 1, np.nan, -y)

    run = dop853_block(rhs, np.zeros(3), np.ones((3, 1)), np.array([1.0, 0.0, 1.0]), rtol=1e-9,
                       atol=1e-12)  # fmt: skip
    assert run.done.tolist() == [True, True, True]
    assert not run.failed.any()
    assert run.y[1, 0] == 1.0 and run.y[0, 0] == pytest.approx(math.exp(-1.0), rel=1e-8)


def test_a_run_goes_on_with_the_step_the_last_one_proposed():
    # The pendulums of the tests above run in 100 pieces, shorter than their steps
    # (as a table's pieces are), each taken up where the last ended with the step it
    # proposed: fewer evaluations than pieces started afresh, each of which picks an
    # initial step again (two evaluations, and a cautious step), and as exact.
    y0 = np.tile([1.0, 0.0], (5, 1))
    cuts = [ENDS * k / 100 for k in range(101)]
    carried, fresh = y0, y0
    proposal = None
    cost_carried, cost_fresh = np.zeros(5), np.zeros(5)
    for low, high in zip(cuts, cuts[1:], strict=False):
        run = dop853_block(_rhs, low, carried, high, rtol=1e-10, atol=1e-13, first_step=proposal)
        carried, proposal, cost_carried = run.y, run.step, cost_carried + run.evaluations
        again = dop853_block(_rhs, low, fresh, high, rtol=1e-10, atol=1e-13)
        fresh, cost_fresh = again.y, cost_fresh + again.evaluations
    for row in range(5):
        tight = _scipy(row, 1e-13, 1e-16)
        scale = np.abs(tight.y[:, -1]).max()
        assert np.abs(carried[row] - tight.y[:, -1]).max() < 1e-8 * scale
    assert np.all(cost_carried < cost_fresh)


def test_a_quadrature_is_not_read_and_its_stages_not_formed():
    # y₀' = -k·sin y₀ ... (the pendulum) and y₂ = ∫ y₀² dt beside it: with
    # quadratures=1 the right-hand side sees two components, and the run is the
    # one that forms all three, bit for bit (the stages of y₂ feed nothing).
    seen = []

    def rhs(rows, t, y):
        seen.append(y.shape[1])
        return np.concatenate([_rhs(rows, t, y[:, :2]), y[:, :1] ** 2], axis=1)

    y0 = np.tile([1.0, 0.0, 0.0], (5, 1))
    full = dop853_block(rhs, np.zeros(5), y0, ENDS, rtol=1e-10, atol=1e-13)
    seen.clear()
    lean = dop853_block(rhs, np.zeros(5), y0, ENDS, rtol=1e-10, atol=1e-13, quadratures=1)
    assert set(seen) == {2}
    assert np.array_equal(full.y, lean.y) and np.array_equal(full.evaluations, lean.evaluations)
    step = []
    dop853_block(rhs, np.zeros(5), y0, ENDS, rtol=1e-10, atol=1e-13, quadratures=1,
                 on_step=lambda s: step.append(s.dense().at(s.t_new, 2)))  # fmt: skip
    assert set(seen) == {2}  # the continuous extension's stages as well


def test_a_tiny_piece_keeps_the_step_planned_for_the_next():
    # A piece 1e-14 long between two near knots: its step is cut to the piece and
    # proposes what was planned, not ten times the piece (which cost the next piece
    # a climb back, step by step).
    y0 = np.tile([1.0, 0.0], (5, 1))
    run = dop853_block(_rhs, np.zeros(5), y0, np.full(5, 1e-14), rtol=1e-10, atol=1e-13,
                       first_step=np.full(5, 0.3))  # fmt: skip
    assert run.done.all() and np.all(run.step >= 0.3)
