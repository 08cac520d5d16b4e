"""The time budget of a run: one deadline, checked where the work loops, enforced by
an alarm where it does not.

Every case runs inside :func:`limit` (``--time-limit``, 60 s by default). Long loops
call :func:`check` (the ODE right-hand sides of :mod:`mdcalc.core.ode` do, on every
evaluation), which raises :class:`OverBudget` once the deadline has passed. A loop
that never checks is stopped by ``SIGALRM`` a moment after the deadline (POSIX, main
thread; elsewhere the checks alone hold the line). The Methods runner gives each
method a :func:`share` of what is left, so that one slow method becomes a row
"skipped: over the time budget" and the rest of the table still runs.

The budget changes what is computed only when it is hit; every cut is recorded
(:attr:`Budget.cut`) and reported.
"""

from __future__ import annotations

import math
import signal
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

#: The default time limit of one case (one sweep point) [s].
DEFAULT_SECONDS = 60.0
#: A method may spend this fraction of the time left; the rest stays for the methods
#: after it and for the report.
METHOD_SHARE = 0.8
#: The alarm fires this long after a deadline, giving the cooperative checks (which
#: stop cleanly) the first chance [s].
GRACE = 0.05


class OverBudget(Exception):
    """The computation ran past its deadline (the whole case's or one method's); the
    message, where there is one, says what could not finish."""


@dataclass
class Budget:
    """One case's time limit and what it cut."""

    seconds: float
    start: float = field(default_factory=time.perf_counter)
    cut: list[str] = field(default_factory=list)
    # Deadlines in force, innermost last (a method's share inside the case's).
    deadlines: list[float] = field(default_factory=list)

    @property
    def deadline(self) -> float:
        return self.deadlines[-1] if self.deadlines else math.inf

    def remaining(self) -> float:
        return self.deadline - time.perf_counter()

    def elapsed(self) -> float:
        return time.perf_counter() - self.start


_local = threading.local()


def current() -> Budget | None:
    """The budget of the case running in this thread (None outside :func:`limit`)."""
    return getattr(_local, "budget", None)


def check() -> None:
    """Raise :class:`OverBudget` when the innermost deadline has passed."""
    budget = current()
    if budget is not None and budget.deadlines and time.perf_counter() > budget.deadlines[-1]:
        raise OverBudget


def remaining() -> float:
    """Seconds left before the innermost deadline (inf without a budget)."""
    budget = current()
    return math.inf if budget is None else budget.remaining()


@contextmanager
def limit(seconds: float | None) -> Iterator[Budget]:
    """Run the body under a time limit of ``seconds`` (None or inf: no limit)."""
    budget = Budget(math.inf if seconds is None else float(seconds))
    outer = current()
    saved = _save_alarm()
    _local.budget = budget
    try:
        with _deadline(budget, budget.start + budget.seconds):
            yield budget
    finally:
        _local.budget = outer
        _restore_alarm(saved)


@contextmanager
def share(fraction: float = METHOD_SHARE) -> Iterator[float]:
    """A deadline for one part of the work: ``fraction`` of the time left. Yields
    the seconds granted (inf without a budget)."""
    budget = current()
    if budget is None or not budget.deadlines:
        yield math.inf
        return
    now = time.perf_counter()
    granted = max(0.0, budget.deadline - now) * fraction
    with _deadline(budget, now + granted):
        yield granted


@contextmanager
def _deadline(budget: Budget, deadline: float) -> Iterator[None]:
    deadline = min(deadline, budget.deadline)
    budget.deadlines.append(deadline)
    armed = _arm(deadline)
    try:
        yield
    finally:
        budget.deadlines.pop()
        if armed:
            _arm(budget.deadline) if budget.deadlines else _disarm()


def _alarm(signum: int, frame: Any) -> None:
    budget = current()
    if budget is None or not budget.deadlines:
        return  # stale: the limit it was set for has ended
    if budget.remaining() > 0:  # stale: its share has ended; re-arm for the one in force
        _arm(budget.deadline)
        return
    raise OverBudget


def _arm(deadline: float) -> bool:
    """Set SIGALRM for ``deadline`` (+ GRACE); False where alarms are not available."""
    if not math.isfinite(deadline) or not _alarms_work():
        return False
    if signal.getsignal(signal.SIGALRM) is not _alarm:
        signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, max(deadline - time.perf_counter(), 0.0) + GRACE)
    return True


def _disarm() -> None:
    if _alarms_work():
        signal.setitimer(signal.ITIMER_REAL, 0.0)


def _save_alarm() -> tuple[Any, float, float] | None:
    """Whoever had SIGALRM before (a test's own watchdog, say): handler, time left, when."""
    if not _alarms_work():
        return None
    return (
        signal.getsignal(signal.SIGALRM),
        signal.getitimer(signal.ITIMER_REAL)[0],
        time.perf_counter(),
    )


def _restore_alarm(saved: tuple[Any, float, float] | None) -> None:
    if saved is None:
        return
    handler, left, when = saved
    signal.setitimer(signal.ITIMER_REAL, 0.0)
    signal.signal(signal.SIGALRM, handler)
    if left > 0.0:  # an alarm that fell due meanwhile fires now
        signal.setitimer(signal.ITIMER_REAL, max(left - (time.perf_counter() - when), 1e-6))


def _alarms_work() -> bool:
    return hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()
