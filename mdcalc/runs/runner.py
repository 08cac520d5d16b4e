"""Run one case file through its problem: read, validate, solve, report.

Shared by the problem commands and ``mdcalc check``; raises
:class:`~mdcalc.errors.InputError` for anything wrong with the input.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mdcalc.core import budget
from mdcalc.errors import InputError, Problem
from mdcalc.input.casefile import CaseText, Conversion, dotted, read_case, validate
from mdcalc.output.report import (
    UNITS_KEY,
    Column,
    Note,
    Report,
    Table,
    first_non_finite,
)
from mdcalc.problems import PROBLEMS, ProblemSpec


def problem_of(case: CaseText) -> ProblemSpec:
    """The problem named by the case file's ``problem = "..."`` key."""
    name = case.data.get("problem")
    if name is None:
        raise InputError(
            case.path,
            [
                Problem(
                    f'missing; a case file starts with problem = "<{"|".join(PROBLEMS)}>"',
                    "problem",
                )
            ],
        )
    if not isinstance(name, str) or name not in PROBLEMS:
        raise InputError(
            case.path,
            [
                Problem(
                    f"got {name!r}; allowed: {', '.join(repr(p) for p in PROBLEMS)}",
                    "problem",
                    case.line_of(("problem",)),
                )
            ],
        )
    return PROBLEMS[name]


@dataclass
class Run:
    """A case run: its report, the solver's result (for plots) and the inputs."""

    report: Report
    result: Any
    module: Any
    case: CaseText
    model: Any = None  # the validated case (None where validation gave up)


def run_case(
    path: Path,
    expected_problem: str | None = None,
    time_limit: float | None = budget.DEFAULT_SECONDS,
) -> Report:
    return run_text(read_case(path), expected_problem, time_limit)


def run_text(
    case: CaseText,
    expected_problem: str | None = None,
    time_limit: float | None = budget.DEFAULT_SECONDS,
) -> Report:
    """Validate, solve and report a case file already read."""
    return solve_text(case, expected_problem, time_limit).report


def solve_text(
    case: CaseText,
    expected_problem: str | None = None,
    time_limit: float | None = budget.DEFAULT_SECONDS,
    work_precision: bool = False,
) -> Run:
    """Validate, solve and report a case file already read, keeping the result
    (:func:`solve_model`: the time limit, and no answer where floats give up;
    ``work_precision``: the ladders of the ODE methods too)."""
    path = case.path
    if "study" in case.data:
        raise InputError(
            path,
            [
                Problem(
                    f"a study file (it has a [study] table): run it with mdcalc study {path}",
                    "study",
                    case.line_of(("study",)),
                )
            ],
        )
    spec = problem_of(case)
    if expected_problem is not None and spec.name != expected_problem:
        raise InputError(
            path,
            [
                Problem(
                    f"this case is for '{spec.name}', not '{expected_problem}' "
                    f"(run: mdcalc {spec.name} {path})",
                    "problem",
                    case.line_of(("problem",)),
                )
            ],
        )
    module = spec.load()
    try:
        model = validate(module.Case, case)
    except ArithmeticError as exc:  # a cross-field rule computing with 5e-324, say
        title = case.data.get("title")
        report = Report(
            spec.name,
            title if isinstance(title, str) else spec.name,
            status="no-answer",
            message=_out_of_range(f"{type(exc).__name__}: {exc}"),
        )
        report.case = str(path)
        return Run(report, None, module, case)
    result, report = solve_model(spec.name, module, model, time_limit, work_precision)
    report.case = str(path)
    if case.conversions:
        report.sections.insert(0, units_section(case.conversions))
    return Run(report, result, module, case, model)


def solve_model(
    problem: str,
    module: Any,
    model: Any,
    time_limit: float | None = budget.DEFAULT_SECONDS,
    work_precision: bool = False,
) -> tuple[Any, Report]:
    """Solve a validated case and build its report, under ``time_limit`` seconds (None:
    no limit) with numpy's and scipy's warnings silenced. A valid scene that overflows,
    runs over the budget or ends in a non-finite number gives (None, a no-answer report
    saying why): exit 3, never an internal error. ``work_precision``: each Methods
    table with ODE methods also runs its work-precision ladder (within the budget),
    reported as a ``work_precision.<key>`` table after the others."""
    from mdcalc import methods

    result: Any = None
    report: Report | None = None
    why: str | None = None
    limit = budget.Budget(math.inf if time_limit is None else time_limit)
    try:
        with budget.limit(time_limit) as limit, warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # overflow in scipy's steps...
            try:
                if work_precision:
                    with methods.work_precision() as jobs:
                        result = module.solve(model)
                else:
                    result = module.solve(model)
                report = module.report(result)
                if (place := first_non_finite(report)) is not None:
                    why = _out_of_range(f"a result is not a finite number: {place}")
                elif work_precision:  # after the scene: its numbers do not depend on them
                    _add_ladders(report, jobs)
            except (ArithmeticError, ValueError) as exc:
                if not out_of_float_range(exc):
                    raise
                why = _out_of_range(f"{type(exc).__name__}: {exc}")
    except budget.OverBudget as exc:
        # Also an alarm that fell due as the limit was being lifted: the report, if
        # it was finished, stands.
        if report is None and why is None:
            where = f" ({exc})" if str(exc) else ""
            why = (
                f"the scene did not finish within the time budget of {limit.seconds:g} s"
                f"{where}; raise it with --time-limit"
            )
    if why is not None or report is None:
        result = None
        title = getattr(model, "title", None) or problem
        report = Report(problem, title, status="no-answer", message=why)
    report.time_limit = time_limit
    report.cut = list(limit.cut)
    report.notes.extend(Note("warning", f"time budget: {what}") for what in limit.cut)
    return result, report


def _add_ladders(report: Report, jobs: list[Any]) -> None:
    """The work-precision tables of a reported scene. Whatever stops them (the
    deadline between two rungs, a failure outside a rung) leaves the scene's report
    as it is, with a warning."""
    from mdcalc import methods

    try:
        ladders = methods.run_ladders(jobs)
        report.sections += [methods.ladder_table(ladder) for ladder in ladders]
    except (budget.OverBudget, ArithmeticError, ValueError) as exc:
        why = f"{type(exc).__name__}: {exc}" if str(exc) else "over the time budget"
        report.notes.append(Note("warning", f"work-precision ladders not finished ({why})"))


def out_of_float_range(exc: BaseException) -> bool:
    """Is ``exc`` floating point giving up on a valid scene's magnitudes: an overflow,
    a division by a number that underflowed to 0, math's domain error (a square root
    of a difference that rounding made negative), math.fsum meeting inf - inf?"""
    if isinstance(exc, ArithmeticError):
        return True
    text = str(exc)
    return isinstance(exc, ValueError) and (
        text in ("math domain error", "cannot convert float NaN to integer")
        or text.endswith(" in fsum")
    )


def _out_of_range(what: str) -> str:
    return (
        f"the scene's numbers leave the range of floating-point arithmetic ({what}); "
        "an input is far outside this problem's physical range"
    )


def units_section(conversions: list[Conversion]) -> Table:
    """The numbers the case file wrote with units, as written and as computed with."""
    return Table(
        "Inputs written with units",
        UNITS_KEY,
        [
            Column("key"),
            Column("as written", kind="quantity"),
            Column("value", kind="exact"),
            Column("unit", kind="unit"),
        ],
        [[dotted(c.loc), c.written, c.value, c.unit] for c in conversions],
    )
