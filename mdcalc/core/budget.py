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

try:  # signal's own functions without the enum wrappers (7 µs a call with a handler set)
    from _signal import getsignal as _getsignal
    from _signal import signal as _setsignal
except ImportError:  # pragma: no cover - another Python implementation
    _getsignal, _setsignal = signal.getsignal, signal.signal

#: The default time limit of one case (one sweep point) [s].
DEFAULT_SECONDS = 60.0
#: A method may spend this fraction of the time left; the rest stays for the methods
#: after it and for the report.
METHOD_SHARE = 0.8
#: The alarm stops a loop this long after a deadline, giving the cooperative checks
#: (which stop cleanly) the first chance [s].
GRACE = 0.05
#: While a limited case runs, SIGALRM ticks this often and looks at the innermost
#: deadline: one timer a case, none per method (a share costs no system call) [s].
TICK = 0.025


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
    # Inside :func:`paused` (nested: a count): the alarm raises nothing.
    paused: int = 0

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
def paused() -> Iterator[None]:
    """The clock stopped for the body: every deadline in force moves on by the time it
    took, and the alarm leaves it alone. For the one-time imports a method needs
    (scipy.integrate: 0.3 s in a fresh process, nothing after): what a scene may
    spend does not depend on what the process had loaded before it."""
    budget = current()
    if budget is None or not budget.deadlines:
        yield
        return
    start = time.perf_counter()
    budget.paused += 1
    try:
        yield
    finally:
        budget.paused -= 1
        took = time.perf_counter() - start
        budget.deadlines[:] = [d + took for d in budget.deadlines]


@contextmanager
def limit(seconds: float | None) -> Iterator[Budget]:
    """Run the body under a time limit of ``seconds`` (None or inf: no limit)."""
    budget = Budget(math.inf if seconds is None else float(seconds))
    _watch_collector()
    outer = current()
    saved = _save_alarm()
    _local.budget = budget
    budget.deadlines.append(budget.start + budget.seconds)
    if math.isfinite(budget.deadline) and saved is not None:
        _setsignal(signal.SIGALRM, _alarm)
        signal.setitimer(signal.ITIMER_REAL, TICK, TICK)
    try:
        yield budget
    finally:
        budget.deadlines.pop()
        _local.budget = outer
        _restore_alarm(saved)


@contextmanager
def share(fraction: float = METHOD_SHARE) -> Iterator[float]:
    """A deadline for one part of the work: ``fraction`` of the time left. Yields
    the seconds granted (inf without a budget). No system call: the alarm that ticks
    through a limited case looks at whichever deadline is innermost."""
    budget = current()
    if budget is None or not budget.deadlines:
        yield math.inf
        return
    now = time.perf_counter()
    granted = max(0.0, budget.deadline - now) * fraction
    budget.deadlines.append(min(now + granted, budget.deadline))
    try:
        yield granted
    finally:
        budget.deadlines.pop()


@contextmanager
def allot(seconds: float) -> Iterator[float]:
    """A deadline ``seconds`` from now for one part of the work (never past the one
    in force; without a budget, the part's own). Yields the seconds granted."""
    budget = current()
    if budget is None or not budget.deadlines:
        with limit(seconds) as own:
            yield own.seconds
        return
    now = time.perf_counter()
    deadline = min(now + max(seconds, 0.0), budget.deadline)
    budget.deadlines.append(deadline)
    try:
        yield deadline - now
    finally:
        budget.deadlines.pop()


def _alarm(signum: int, frame: Any) -> None:
    """SIGALRM, every TICK seconds of a limited case: stop a loop that does not check
    once the innermost deadline is GRACE behind it."""
    budget = current()
    if budget is None or not budget.deadlines:
        return  # stale: the limit it was set for has ended
    late = time.perf_counter() > budget.deadline + GRACE and not budget.paused
    if late and not _collecting[0] and not _in_finalizer(frame) and not _importing(frame):
        raise OverBudget


#: Is the garbage collector running? What it runs meanwhile (a weakref's callback, a
#: finalizer) cannot pass an exception on: Python prints it and drops it.
_collecting = [False]


def _collector(phase: str, info: dict[str, Any]) -> None:
    _collecting[0] = phase == "start"


def _watch_collector() -> None:
    import gc

    if _collector not in gc.callbacks:
        gc.callbacks.insert(0, _collector)  # before any other: its time is the collector's


#: Code where an exception cannot stop anything: Python swallows it with an
#: "Exception ignored in ..." on stderr and goes on. The next tick raises outside.
_FINALIZERS = frozenset({"__del__", "unraisablehook", "unraisable_hook", "excepthook"})


def _in_finalizer(frame: Any) -> bool:
    """Is the interrupted code (or what called it) a finalizer, an error hook or a
    garbage collector's callback (``gc.callbacks``: a test tool's, say)?"""
    import gc

    callbacks = {getattr(callback, "__code__", None) for callback in gc.callbacks}
    while frame is not None:
        if frame.f_code.co_name in _FINALIZERS or frame.f_code in callbacks:
            return True
        frame = frame.f_back
    return False


def _importing(frame: Any) -> bool:
    """Is the interrupted code an import (a method's scipy.integrate, say)? An import
    stopped half way leaves modules half made; it finishes, and the next check after
    it (the method's own) stops the work it was for."""
    while frame is not None:
        if frame.f_code.co_filename.startswith("<frozen importlib"):
            return True
        frame = frame.f_back
    return False


def _save_alarm() -> tuple[Any, tuple[float, float], float] | None:
    """Whoever had SIGALRM before (a test's own watchdog, an outer limit): handler,
    timer (time left, interval), when; None where alarms are not available."""
    if not _alarms_work():
        return None
    return (_getsignal(signal.SIGALRM), signal.getitimer(signal.ITIMER_REAL), time.perf_counter())


def _restore_alarm(saved: tuple[Any, tuple[float, float], float] | None) -> None:
    if saved is None:
        return
    handler, (left, interval), when = saved
    signal.setitimer(signal.ITIMER_REAL, 0.0)
    _setsignal(signal.SIGALRM, handler)
    if left > 0.0:  # an alarm that fell due meanwhile fires now
        signal.setitimer(
            signal.ITIMER_REAL, max(left - (time.perf_counter() - when), 1e-6), interval
        )


_HAVE_ALARMS = hasattr(signal, "setitimer")


def _alarms_work() -> bool:
    return _HAVE_ALARMS and threading.current_thread() is threading.main_thread()
