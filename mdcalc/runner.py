"""Run one case file through its problem: read, validate, solve, report.

Shared by the problem commands and ``mdcalc check``; raises
:class:`~mdcalc.errors.InputError` for anything wrong with the input.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mdcalc.casefile import CaseText, Conversion, dotted, read_case, validate
from mdcalc.errors import InputError, Problem
from mdcalc.problems import PROBLEMS, ProblemSpec
from mdcalc.report import Column, Report, Table


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


def run_case(path: Path, expected_problem: str | None = None) -> Report:
    return run_text(read_case(path), expected_problem)


def run_text(case: CaseText, expected_problem: str | None = None) -> Report:
    """Validate, solve and report a case file already read."""
    return solve_text(case, expected_problem).report


def solve_text(case: CaseText, expected_problem: str | None = None) -> Run:
    """Validate, solve and report a case file already read, keeping the result."""
    path = case.path
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
    model = validate(module.Case, case)
    result: Any
    try:
        result = module.solve(model)
        report = module.report(result)
    except (ArithmeticError, ValueError) as exc:
        if not out_of_float_range(exc):
            raise
        # A valid scene whose numbers leave double precision: no answer, said plainly
        # (exit 3), never an internal error.
        result = None
        title = getattr(model, "title", None) or spec.name
        report = Report(spec.name, title, status="no-answer", message=_out_of_range(exc))
    report.case = str(path)
    if case.conversions:
        report.sections.insert(0, units_section(case.conversions))
    return Run(report, result, module, case)


def out_of_float_range(exc: BaseException) -> bool:
    """Is ``exc`` floating point giving up on a valid scene's magnitudes: an overflow,
    a division by a number that underflowed to 0, math's domain error (a square root
    of a difference that rounding made negative)?"""
    if isinstance(exc, ArithmeticError):
        return True
    return isinstance(exc, ValueError) and str(exc) == "math domain error"


def _out_of_range(exc: BaseException) -> str:
    return (
        "the scene's numbers leave the range of floating-point arithmetic "
        f"({type(exc).__name__}: {exc}); an input is far outside this problem's "
        "physical range"
    )


def units_section(conversions: list[Conversion]) -> Table:
    """The numbers the case file wrote with units, as written and as computed with."""
    return Table(
        "Inputs written with units",
        "units",
        [Column("key"), Column("as written"), Column("value"), Column("unit")],
        [[dotted(c.loc), c.written, c.value, c.unit or "-"] for c in conversions],
    )
