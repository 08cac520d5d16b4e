"""The time budget (issue 20): one deadline per case, cooperative checks at every ODE
evaluation, an alarm for loops that never check, each method's share in a Methods
table, a stand-in for a reference that ran over, and what the user sees of it."""

from __future__ import annotations

import json
import signal
import time

import pytest

from mdcalc.core import budget
from mdcalc.methods import Method, compare
from mdcalc.output.report import MethodQuantity
from tests.conftest import CASES

Q = [MethodQuantity("x", "x", "m")]


def spin(seconds: float) -> None:
    """A loop that never calls budget.check(): only the alarm can stop it."""
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        pass


def checking(seconds: float) -> dict[str, float]:
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        budget.check()
    return {"x": 1.0}


def test_check_raises_only_past_the_deadline():
    budget.check()  # no budget: nothing to check
    with budget.limit(0.2) as b:
        budget.check()
        assert 0.0 < b.remaining() <= 0.2
        start = time.perf_counter()
        with pytest.raises(budget.OverBudget):
            checking(5.0)
        assert time.perf_counter() - start < 0.3
    assert budget.current() is None


def test_no_limit_never_raises():
    with budget.limit(None) as b:
        assert b.remaining() == float("inf")
        checking(0.05)


@pytest.mark.skipif(not hasattr(signal, "setitimer"), reason="POSIX alarms")
def test_the_alarm_stops_a_loop_that_never_checks_and_the_old_alarm_comes_back():
    fired = []
    previous = signal.signal(signal.SIGALRM, lambda *a: fired.append(True))
    signal.setitimer(signal.ITIMER_REAL, 0.6)  # someone else's watchdog
    try:
        start = time.perf_counter()
        with pytest.raises(budget.OverBudget), budget.limit(0.1):
            spin(5.0)
        assert time.perf_counter() - start < 0.5
        assert signal.getitimer(signal.ITIMER_REAL)[0] > 0.0  # the watchdog is re-armed
        spin(0.8)
        assert fired == [True]
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)


@pytest.mark.skipif(not hasattr(signal, "setitimer"), reason="POSIX alarms")
def test_the_alarm_does_not_raise_inside_a_finalizer(monkeypatch):
    # An exception raised in a __del__ (an object collected while the deadline
    # passes) is swallowed with "Exception ignored in ..." on stderr and stops
    # nothing; the alarm waits for the loop outside it.
    swallowed: list[object] = []
    monkeypatch.setattr("sys.unraisablehook", swallowed.append)

    class SlowToCollect:
        def __del__(self) -> None:
            spin(0.3)

    start = time.perf_counter()
    with pytest.raises(budget.OverBudget), budget.limit(0.05):
        slow = SlowToCollect()
        del slow  # its __del__ runs past the deadline and the grace
        assert time.perf_counter() - start >= 0.3
        spin(5.0)
    assert time.perf_counter() - start < 2.0  # (not the 5 s spin: it raised after)
    assert swallowed == []


@pytest.mark.skipif(not hasattr(signal, "setitimer"), reason="POSIX alarms")
def test_the_alarm_does_not_raise_inside_a_garbage_collector_callback(monkeypatch):
    # hypothesis times the collector with a gc callback; one that runs past the
    # deadline must not get the OverBudget (it would be swallowed and printed).
    import gc

    swallowed: list[object] = []
    monkeypatch.setattr("sys.unraisablehook", swallowed.append)

    def slow_callback(phase: str, info: dict) -> None:
        if phase == "start":
            spin(0.3)

    gc.callbacks.append(slow_callback)
    try:
        start = time.perf_counter()
        with pytest.raises(budget.OverBudget), budget.limit(0.05):
            gc.collect()
            assert time.perf_counter() - start >= 0.3
            spin(5.0)
    finally:
        gc.callbacks.remove(slow_callback)
    assert time.perf_counter() - start < 2.0  # (not the 5 s spin: it raised after)
    assert swallowed == []


def test_the_alarm_does_not_raise_inside_a_weakref_callback_the_collector_runs(monkeypatch):
    # a cycle's weakref callback (a WeakKeyDictionary's remove, after matplotlib has
    # drawn) runs inside gc.collect(): an OverBudget there would be printed and lost
    import gc
    import weakref

    swallowed: list[object] = []
    monkeypatch.setattr("sys.unraisablehook", swallowed.append)

    class Node:
        pass

    node = Node()
    node.me = node  # type: ignore[attr-defined]  # a cycle: only the collector frees it
    watch = weakref.ref(node, lambda _: spin(0.3))
    del node
    start = time.perf_counter()
    with pytest.raises(budget.OverBudget), budget.limit(0.05):
        gc.collect()
        assert watch() is None and time.perf_counter() - start >= 0.3
        spin(5.0)
    assert time.perf_counter() - start < 2.0  # (not the 5 s spin: it raised after)
    assert swallowed == []


def test_a_finished_limit_leaves_no_alarm_behind():
    with budget.limit(0.05):
        pass
    if hasattr(signal, "getitimer"):
        assert signal.getitimer(signal.ITIMER_REAL)[0] == 0.0
    spin(0.1)  # an alarm left behind would raise here


def test_an_ode_run_stops_at_the_deadline():
    import numpy as np
    import scipy.integrate  # noqa: F401  # (its first import, 0.4 s, is not the run's)

    from mdcalc.core.ode import advance

    def rhs(t, y):
        time.sleep(1e-3)
        return np.array([y[1], -y[0]])

    start = time.perf_counter()
    with pytest.raises(budget.OverBudget), budget.limit(0.2):
        advance(rhs, 0.0, np.array([1.0, 0.0]), 1e6, rtol=1e-10, atol=1e-12, method="DOP853")
    assert time.perf_counter() - start < 0.5


def test_a_slow_method_is_a_skipped_row_and_the_table_goes_on():
    with budget.limit(0.5) as b:
        table = compare(
            "t",
            "k",
            Q,
            [
                Method("slow", lambda: checking(30.0)),
                Method("exact", lambda: {"x": 2.0}, reference=True),
                Method("late", lambda: {"x": 2.2}),
            ],
        )
    slow, exact, late = table.rows
    assert slow.seconds is None and slow.values == {}
    assert slow.note.startswith("skipped: over the time budget (")
    assert exact.reference and exact.values == {"x": 2.0}
    assert late.rel_errors["x"] == pytest.approx(0.1)  # the rest still ran
    assert b.cut == [f"t: slow: {slow.note}"]


def test_a_reference_over_budget_hands_over_to_the_most_accurate_finished_method():
    with budget.limit(0.5) as b:
        table = compare(
            "t",
            "k",
            Q,
            [
                Method("rough", lambda: {"x": 2.4}, accuracy=1),
                Method("good", lambda: {"x": 2.1}, accuracy=2),
                Method("plain", lambda: {"x": 9.0}),
                Method("exact", lambda: checking(30.0), reference=True),
            ],
        )
    rough, good, plain, exact = table.rows
    assert good.reference and not exact.reference and exact.seconds is None
    assert "reference in place of exact (over the time budget)" in good.note
    assert rough.rel_errors["x"] == pytest.approx(0.3 / 2.1)
    assert plain.rel_errors["x"] == pytest.approx(6.9 / 2.1)
    assert b.cut[-1] == "t: good is the reference in place of exact"


def test_without_a_stand_in_the_table_cannot_be_made():
    with budget.limit(0.3), pytest.raises(budget.OverBudget, match="no other method"):
        compare(
            "t",
            "k",
            Q,
            [
                Method("plain", lambda: {"x": 9.0}),
                Method("exact", lambda: checking(30.0), reference=True),
            ],
        )


def test_each_method_gets_a_share_of_what_is_left():
    grants = []

    def note_share() -> dict[str, float]:
        grants.append(budget.remaining())
        return {"x": 1.0}

    with budget.limit(10.0):
        compare("t", "k", Q, [Method("a", note_share, reference=True)])
    assert 0.0 < grants[0] <= 10.0 * budget.METHOD_SHARE


# ------------------------------------------------------------------ what the user sees


def never_ends(case):
    return checking(1e9)


def test_a_scene_that_cannot_finish_is_exit_3_within_the_limit(cli, monkeypatch):
    from mdcalc.problems import braking

    monkeypatch.setattr(braking, "solve", never_ends)
    start = time.perf_counter()
    result = cli("braking", CASES / "braking/lecture.toml", "--time-limit", "0.5", "--json")
    assert time.perf_counter() - start < 1.5
    assert result.exit_code == 3, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1
    assert "did not finish within the time budget of 0.5 s" in lines[0]
    assert "--time-limit" in lines[0]
    document = json.loads(result.stdout)
    assert document["status"] == "no-answer"
    assert document["budget"]["time_limit_s"] == 0.5


def test_a_skipped_row_is_reported_in_text_and_json(cli, monkeypatch):
    # The braking ODE rows of a scene with drag never finish; the exact closed form
    # is the reference, so the scene still answers (exit 0) and says what it cut.
    from mdcalc.problems import braking

    monkeypatch.setattr(braking, "ode_stop", lambda scene, rtol: checking(1e9))
    start = time.perf_counter()
    result = cli("braking", CASES / "braking/drag.toml", "--time-limit", "1", "--json")
    assert time.perf_counter() - start < 2.0
    assert result.exit_code == 0, result.stderr
    document = json.loads(result.stdout)
    cut = document["budget"]["cut"]
    assert cut and all("over the time budget" in c or "in place of" in c for c in cut)
    rows = [r for s in document["sections"] if s["kind"] == "methods" for r in s["rows"]]
    assert any(r["note"].startswith("skipped: over the time budget") for r in rows)
    warnings = [n["text"] for n in document["notes"] if n["level"] == "warning"]
    assert any(w.startswith("time budget: ") for w in warnings)
    text = cli("braking", CASES / "braking/drag.toml", "--time-limit", "1")
    assert "skipped: over the time budget" in text.stdout


def test_the_budget_is_in_every_json_and_zero_means_none(cli):
    result = cli("braking", CASES / "braking/lecture.toml", "--json")
    assert json.loads(result.stdout)["budget"] == {"time_limit_s": 60.0, "cut": []}
    result = cli("braking", CASES / "braking/lecture.toml", "--json", "--time-limit", "0")
    assert json.loads(result.stdout)["budget"] == {"time_limit_s": None, "cut": []}


def test_a_negative_time_limit_is_exit_2(cli):
    result = cli("braking", CASES / "braking/lecture.toml", "--time-limit", "-1")
    assert result.exit_code == 2


@pytest.mark.parametrize("command", ["run", "check"])
def test_run_and_check_take_the_limit(cli, command, monkeypatch):
    from mdcalc.problems import braking

    monkeypatch.setattr(braking, "solve", never_ends)
    start = time.perf_counter()
    result = cli(command, CASES / "braking/lecture.toml", "--time-limit", "0.3", "--jobs", "1")
    assert time.perf_counter() - start < 1.5
    if command == "run":
        assert result.exit_code == 3
        assert "time budget of 0.3 s" in result.stderr
    else:  # no results: every [expect] value is off
        assert result.exit_code == 1


def test_sweep_points_take_the_limit(cli, monkeypatch):
    from mdcalc.problems import mechanism

    def sweep(limit: str):
        case = CASES / "mechanism/linear_torque.toml"  # (the crank press: 10 s more)
        vary = ("--vary", "motion.steps_per_revolution=16:32:2")
        return cli("sweep", case, *vary, "--jobs", "1", "--time-limit", limit)

    monkeypatch.setattr(mechanism, "sweep", None)  # the points one by one, each budgeted
    result = sweep("0")
    assert result.exit_code == 0, result.stderr
    monkeypatch.setattr(mechanism, "solve", never_ends)
    start = time.perf_counter()
    result = sweep("0.2")
    assert time.perf_counter() - start < 2.0
    assert result.exit_code == 3
    assert "time budget of 0.2 s" in result.stderr
