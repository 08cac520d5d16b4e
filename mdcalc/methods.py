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
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from mdcalc.core import budget
from mdcalc.output.report import MethodQuantity, MethodRow, MethodsTable

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
    return MethodsTable(title, key, quantities, rows)


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
