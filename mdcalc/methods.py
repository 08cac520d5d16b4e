"""The Methods machinery shared by every problem.

A problem lists the ways it can compute its key results as :class:`Method` values;
:func:`compare` runs each one, measures its run time, and computes the relative
error of each key result against the reference method. The result is a
:class:`~mdcalc.output.report.MethodsTable` ready for the report.

A method returns ``{key: value}`` for the key results it computes, or raises
:class:`NotApplicable` with the reason (the row then shows the reason instead of
numbers: a closed form outside its validity, an ODE run skipped as too long).

Each method runs on a share of the case's time budget (:mod:`mdcalc.core.budget`).
One that runs over is a row "skipped: over the time budget"; if that is the
reference, the finished method of the highest ``accuracy`` stands in for it and
its row says so; with none, :class:`~mdcalc.core.budget.OverBudget` goes up to the
runner (no answer, exit 3).
"""

from __future__ import annotations

import importlib
import math
import threading
import time
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from functools import partial
from typing import Any

from mdcalc.core import budget
from mdcalc.output.report import (
    MethodQuantity,
    MethodRow,
    MethodsTable,
    Table,
    Value,
)

#: Cheap methods are repeated until this much time has passed, so that a
#: microsecond-scale run time is a mean over many calls, not timer noise.
MIN_TIMING_SECONDS = 2e-3
MAX_REPEATS = 2000


class NotApplicable(Exception):
    """A method that cannot give an answer for this scene (the message says why)."""


@dataclass
class Method:
    name: str
    run: Callable[[], Mapping[str, float]]
    reference: bool = False
    note: str = ""
    #: Modules the method imports; loaded before timing so that a one-off import
    #: (scipy.integrate: about 0.5 s) is not charged to the method's run time.
    imports: tuple[str, ...] = ()
    #: May this method stand in for a reference that ran over the time budget, and
    #: how good is it (the finished method of the highest accuracy is taken)? 0: no.
    accuracy: int = 0
    #: An ODE method: the same computation at a relative tolerance ``rtol`` (its
    #: integrator chosen by :func:`mdcalc.core.ode.integrator`), for the
    #: work-precision ladder. The rows of one ODE computation at several tolerances
    #: share one function (one ladder); ``ladder_label`` names it where a table has two.
    ladder: Callable[[float], Mapping[str, float]] | None = None
    ladder_label: str = ""
    #: An ODE method's own rtol (with ``ladder``): where it is the reference, or
    #: stands in for one, the rungs that close to it measure nothing
    #: (:data:`NEAR_REFERENCE`).
    rtol: float | None = None


def timed(run: Callable[[], Mapping[str, float]]) -> tuple[Mapping[str, float], float]:
    """Run ``run`` and return its result and the mean run time of one call [s]."""
    start = time.perf_counter()
    result = run()
    elapsed = time.perf_counter() - start
    if elapsed >= MIN_TIMING_SECONDS:
        return result, elapsed
    repeats = min(MAX_REPEATS, max(1, int(MIN_TIMING_SECONDS / max(elapsed, 1e-9))))
    start = time.perf_counter()
    for _ in range(repeats):
        run()
    return result, (time.perf_counter() - start) / repeats


def _why_not(reason: Exception) -> str:
    if isinstance(reason, NotApplicable):
        return f"not applicable: {reason}"
    return f"failed: {reason}"


def relative_error(value: float, reference: float) -> float:
    """|value - reference| / |reference|; the absolute error where reference is 0."""
    if reference == 0.0:
        return abs(value)
    return abs(value - reference) / abs(reference)


#: Run the reference method alone (a study's or a sweep's sample: only its values
#: are kept); the others run only to stand in for a reference over the budget.
REFERENCE_ONLY = False


def compare(
    title: str, key: str, quantities: list[MethodQuantity], methods: list[Method]
) -> MethodsTable:
    """Run every method, time it, and measure its error against the reference."""
    references = [m for m in methods if m.reference]
    if len(references) != 1:
        raise ValueError(f"methods table {key!r} needs exactly one reference method")
    rows: list[MethodRow] = []
    reference_values: Mapping[str, float] = {}
    over: Method | None = None  # the reference, had it run over the budget
    if REFERENCE_ONLY:
        alone = _reference_alone(methods)
        if alone is not None:
            return MethodsTable(title, key, quantities, alone)
    for method in methods:
        _import(method)
        granted = 0.0
        try:
            with budget.share() as granted:
                values, seconds = timed(method.run)
        except budget.OverBudget:
            note = f"skipped: over the time budget ({_granted(granted)} for this method)"
            _cut(f"{title}: {method.name}: {note}")
            if method.reference:
                over = method
            rows.append(MethodRow(method.name, {}, {}, None, False, note, method.imports))
            continue
        except (NotApplicable, ArithmeticError) as reason:
            # A method that breaks down on this scene (an ODE row that does not
            # settle, say) is a finding of the table, not a failure of the run --
            # unless it is the reference.
            if method.reference:
                raise
            rows.append(
                MethodRow(method.name, {}, {}, None, False, _why_not(reason), method.imports)
            )
            continue
        for k, v in values.items():
            if not math.isfinite(v):
                raise ArithmeticError(f"method {method.name!r} gave {k} = {v}")
        if method.reference:
            reference_values = values
        rows.append(
            MethodRow(
                method.name,
                dict(values),
                {},
                seconds,
                method.reference,
                method.note,
                method.imports,
            )
        )
    if over is not None:
        reference_values = _stand_in(title, over, methods, rows)
    for row in rows:
        for q in quantities:
            value = row.values.get(q.key)
            ref = reference_values.get(q.key)
            if value is not None and ref is not None and not row.reference:
                row.rel_errors[q.key] = relative_error(value, ref)
    if _asked.jobs is not None and any(m.ladder is not None for m in methods):
        keys = [q.key for q in quantities]
        _asked.jobs.append(_Job(title, key, keys, methods, rows, dict(reference_values)))
    return MethodsTable(title, key, quantities, rows)


# ---------------------------------------------------------------- work-precision ladders

#: The rungs of a ladder: rtol from 1e-3 to 1e-12 (each ODE run scales its atol
#: with it).
LADDER_RTOLS = tuple(10.0**-k for k in range(3, 13))
#: What the ladders of a scene may spend, after the scene is solved and reported
#: (so they change none of its numbers): LADDER_SECONDS [s] (without a budget too),
#: and at most LADDER_SHARE of the scene's budget left; every (ladder, integrator)
#: pair gets an equal part of what is left when its turn comes.
LADDER_SHARE = 0.9
LADDER_SECONDS = 30.0
#: A rung is not started when the last one's run time times this is more than the
#: integrator has left: a tighter tolerance costs more.
GROWTH = 2.0
#: A rung this close to an ODE reference's own rtol (or tighter) is the reference's
#: computation again: not measured against it.
NEAR_REFERENCE = 10.0


@dataclass
class Rung:
    """One point of a work-precision diagram: an integrator at a tolerance, or a
    method that has no tolerance (a closed form: ``family`` "single")."""

    method: str
    family: str
    rtol: float | None
    #: The largest relative error of the table's quantities against its reference.
    error: float | None
    seconds: float | None
    evaluations: int | None
    status: str = "ok"


@dataclass
class Ladder:
    """The work-precision diagram of one Methods table."""

    title: str
    key: str
    reference: str
    rungs: list[Rung]


@dataclass
class _Job:
    """A Methods table's ladder, waiting for the scene to be solved."""

    title: str
    key: str
    quantities: list[str]
    methods: list[Method]
    rows: list[MethodRow]
    reference: Mapping[str, float]


class _Asked(threading.local):
    jobs: list[_Job] | None = None


_asked = _Asked()


@contextmanager
def work_precision() -> Iterator[list[_Job]]:
    """Every :func:`compare` in the body with an ODE method notes its ladder in the
    yielded list, for :func:`run_ladders` once the scene is solved."""
    saved = _asked.jobs
    jobs: list[_Job] = []
    _asked.jobs = jobs
    try:
        yield jobs
    finally:
        _asked.jobs = saved


def run_ladders(jobs: list[_Job]) -> list[Ladder]:
    """Each job's ladder: its ODE computations with each of scipy's integrators over
    :data:`LADDER_RTOLS`, within what the budget leaves (:data:`LADDER_SECONDS`)."""
    from mdcalc.core.ode import SOLVERS

    plans = []
    for job in jobs:
        runs: dict[int, Method] = {}  # one ladder per ODE computation
        for method in job.methods:
            if method.ladder is not None:
                runs.setdefault(id(method.ladder), method)
        plans.append((job, list(runs.values())))
    pairs = sum(len(computations) for _, computations in plans) * len(SOLVERS)
    deadline = time.perf_counter() + min(LADDER_SECONDS, budget.remaining() * LADDER_SHARE)
    ladders = []
    for job, computations in plans:
        rungs = _single_points(job)
        near = _near_reference(job)
        for method in computations:
            assert method.ladder is not None
            for solver in SOLVERS:
                left = max(deadline - time.perf_counter(), 0.0) / pairs
                pairs -= 1
                label = f"{method.ladder_label}: {solver}" if method.ladder_label else solver
                rungs += _rungs(label, solver, method.ladder, job, left, near)
        named = [row.method for row in job.rows if row.reference]
        ladders.append(Ladder(job.title, job.key, named[0] if named else "", rungs))
    return ladders


def _single_points(job: _Job) -> list[Rung]:
    """The methods without a tolerance (closed forms, lecture formulas) that ran."""
    return [
        Rung(row.method, "single", None, max(errors), row.seconds, None)
        for method, row in zip(job.methods, job.rows, strict=True)
        if method.ladder is None
        and row.seconds is not None
        and (errors := [e for e in row.rel_errors.values() if e is not None])
    ]


def _near_reference(job: _Job) -> float:
    """The rtol at and below which a rung repeats an ODE reference (0: none): the
    reference row's, a stand-in's too (a row that took the place of a reference
    over the budget). (1 + 1e-9: 1e-11·10 is 9.99…e-11 in floating point.)"""
    for method, row in zip(job.methods, job.rows, strict=True):
        if row.reference and method.ladder is not None and method.rtol is not None:
            return method.rtol * NEAR_REFERENCE * (1.0 + 1e-9)
    return 0.0


def _rungs(
    label: str,
    solver: str,
    run: Callable[[float], Mapping[str, float]],
    job: _Job,
    seconds: float,
    near: float,
) -> list[Rung]:
    """``run`` with ``solver`` at each tolerance, loose to tight, within ``seconds``;
    the rungs after it ran out are said to be skipped."""
    from mdcalc.core.ode import FAMILIES

    family = FAMILIES[solver]
    rungs: list[Rung] = []
    stop = ""
    try:
        with budget.allot(seconds):
            last = 0.0
            for rtol in LADDER_RTOLS:
                if not stop and rtol <= near:
                    stop = "not measured: the reference's own tolerance"
                if not stop and last * GROWTH > budget.remaining():
                    stop = "skipped: would run over the time budget"
                if stop:
                    rungs.append(Rung(label, family, rtol, None, None, None, stop))
                    continue
                start = time.perf_counter()
                rung = _rung(label, solver, run, job, rtol)
                last = time.perf_counter() - start if rung.seconds is None else rung.seconds
                rungs.append(rung)
                if rung.status == "over the time budget":
                    stop = "skipped: a looser tolerance ran over the time budget"
    except budget.OverBudget:  # the alarm, between two rungs
        stop = "skipped: a looser tolerance ran over the time budget"
    done = {r.rtol for r in rungs}
    rungs += [Rung(label, family, rtol, None, None, None, stop or "skipped")
              for rtol in LADDER_RTOLS if rtol not in done]  # fmt: skip
    return rungs


def _rung(
    label: str, solver: str, run: Callable[[float], Mapping[str, float]], job: _Job, rtol: float
) -> Rung:
    from mdcalc.core.ode import FAMILIES, integrator

    family = FAMILIES[solver]
    counts: list[int] = []  # the evaluations after each call: the first's count
    try:
        with integrator(solver) as counter:
            values, seconds = timed(partial(_counted, run, rtol, counter, counts))
    except budget.OverBudget:
        return Rung(label, family, rtol, None, None, None, "over the time budget")
    except (NotApplicable, ArithmeticError, ValueError) as reason:  # (LinAlgError too)
        return Rung(label, family, rtol, None, None, None, _why_not(reason))
    missing = [k for k in job.quantities if k in job.reference and k not in values]
    errors = [relative_error(values[k], job.reference[k])
              for k in job.quantities if k in job.reference and k in values]  # fmt: skip
    if missing or not errors or not all(math.isfinite(e) for e in errors):
        why = f"failed: no value for {', '.join(missing)}" if missing else "failed: no value"
        return Rung(label, family, rtol, None, seconds, counts[0], why)
    return Rung(label, family, rtol, max(errors), seconds, counts[0])


def _counted(
    run: Callable[[float], Mapping[str, float]], rtol: float, counter: Any, counts: list[int]
) -> Mapping[str, float]:
    values = run(rtol)
    counts.append(counter.evaluations)
    return values


def ladder_table(ladder: Ladder) -> Table:
    """A ladder as a report's table (JSON: ``kind`` "table", ``key``
    ``work_precision.<key>``, one row a rung in the order of
    :data:`mdcalc.output.precision.LADDER_COLUMNS`; ""
    where a rung has no number: a closed form's rtol and evaluations, a run that
    did not finish)."""
    from mdcalc.output.precision import LADDER_COLUMNS, LADDER_KEY  # (the charts' reader)

    what = ladder.title.removeprefix("Methods: ")
    rows: list[list[Value]] = [
        [r.method, r.family, *["" if v is None else v for v in
                               (r.rtol, r.error, r.seconds, r.evaluations)], r.status]
        for r in ladder.rungs
    ]  # fmt: skip
    return Table(
        f"Work–precision: {what} (error against {ladder.reference})",
        f"{LADDER_KEY}.{ladder.key}",
        list(LADDER_COLUMNS),
        rows,
    )


def _import(method: Method) -> None:
    """What the method needs (scipy.integrate: 0.3 s the first time in a process), with
    the clock stopped: it is no part of the scene's work."""
    with budget.paused():
        for module in method.imports:
            importlib.import_module(module)


def _reference_alone(methods: list[Method]) -> list[MethodRow] | None:
    """The rows with the reference alone run (timed once), the others not run; None
    when the reference runs over its budget (then every method runs, for a stand-in)."""
    rows = []
    for method in methods:
        if not method.reference:
            rows.append(MethodRow(method.name, {}, {}, None, False, "not run", method.imports))
            continue
        _import(method)
        try:
            with budget.share():
                start = time.perf_counter()
                values = method.run()
                seconds = time.perf_counter() - start
        except budget.OverBudget:
            return None
        for k, v in values.items():
            if not math.isfinite(v):
                raise ArithmeticError(f"method {method.name!r} gave {k} = {v}")
        rows.append(
            MethodRow(method.name, dict(values), {}, seconds, True, method.note, method.imports)
        )
    return rows


def _stand_in(
    title: str, over: Method, methods: list[Method], rows: list[MethodRow]
) -> Mapping[str, float]:
    """Make the most accurate finished method the reference in place of ``over``."""
    finished = [
        (method.accuracy, index)
        for index, (method, row) in enumerate(zip(methods, rows, strict=True))
        if method.accuracy > 0 and row.seconds is not None
    ]
    if not finished:
        raise budget.OverBudget(
            f"{title}: the reference ({over.name}) ran over the time budget and no other "
            "method accurate enough to stand in for it finished"
        )
    _, index = max(finished)
    row = rows[index]
    row.reference = True
    row.note = "; ".join(
        n for n in (row.note, f"reference in place of {over.name} (over the time budget)") if n
    )
    _cut(f"{title}: {row.method} is the reference in place of {over.name}")
    return {k: v for k, v in row.values.items() if v is not None}


def _granted(seconds: float) -> str:
    return "no time left" if seconds <= 0 else f"{seconds:.3g} s"


def _cut(what: str) -> None:
    now = budget.current()
    if now is not None:
        now.cut.append(what)
