"""mdcalc from Python: the calculations of the command line in scripts and notebooks.

``import mdcalc`` loads none of numpy, scipy, pint, rich or pydantic; the first call
does. The functions here read, validate, solve and report exactly as the commands do
(:func:`mdcalc.runs.runner.solve_text`, the one path), and hand back a
:class:`~mdcalc.api.calculation.Calculation`::

    >>> import mdcalc
    >>> calc = mdcalc.solve({"problem": "braking", "vehicle": {...}, ...})
    >>> calc.results["stopping_distance"]          # a pint Quantity, in m

Errors are exceptions, never ``SystemExit`` and never output: an input the command
line refuses with exit 2 raises :class:`~mdcalc.errors.InputError` carrying the same
problems (file, line, key path, message); a valid scene without an answer is a
calculation with ``status == "no-answer"`` (or :class:`~mdcalc.errors.NoAnswer` with
``raise_on_no_answer=True``).

The time budget: on the main thread a scene is stopped by an alarm signal at
``time_limit`` (the handler and timer the caller had are put back after); on any
other thread (a notebook's executor, a web server's worker) signals cannot be used,
and the budget is cooperative only: the solvers' loops check it, a single long
library call is not interrupted.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mdcalc.api.calculation import Calculation, MethodsView
from mdcalc.api.cases import DICT, case_of, lineless
from mdcalc.api.many import StudyResult, SweepResult, study, sweep
from mdcalc.errors import InputError, NoAnswer, Problem

__all__ = [
    "Calculation",
    "MethodsView",
    "ProblemInfo",
    "StudyResult",
    "SweepResult",
    "registry",
    "solve",
    "study",
    "sweep",
]


def solve(
    case: Path | str | Mapping[str, Any],
    problem: str | None = None,
    *,
    time_limit: float | None = 60.0,
    raise_on_no_answer: bool = False,
    work_precision: bool = False,
) -> Calculation:
    """Read, validate, solve and report one case, as ``mdcalc PROBLEM CASE --json``.

    ``case``: a :class:`pathlib.Path` (a case file), a ``str`` (the TOML text of one)
    or a ``dict`` (the same keys and quantity strings as a file). A relative path in
    a text or dict (``base = "other.toml"``) is taken from the current directory.
    ``problem`` may be left out when the case names it; given, it must agree.
    ``time_limit`` in seconds (None: none). ``work_precision``: also run each ODE
    method's work-precision ladder, as ``--work-precision`` does (its tables in the
    report, its charts in :meth:`Calculation.charts`). Raises :class:`InputError`
    for what the command line refuses with exit 2."""
    from mdcalc.runs.runner import solve_text

    read = case_of(case, problem)
    if "study" in read.data and not isinstance(case, Path):  # (a file: the command's)
        where = read.line_of(("study",))
        why = "a study file (it has a [study] table): run it with mdcalc.study(...)"
        raise InputError(read.path, [Problem(why, "study", where)])
    try:
        run = solve_text(read, problem, time_limit, work_precision)
    except InputError as exc:
        if isinstance(case, Mapping):  # the lines of a text the caller never saw
            raise InputError(DICT, [lineless(p) for p in exc.problems]) from None
        raise
    calculation = Calculation(run)
    if raise_on_no_answer and calculation.status != "ok":
        raise NoAnswer(calculation.message or "no answer", calculation)
    return calculation


@dataclass(frozen=True)
class ProblemInfo:
    """One problem of mdcalc: its name, what it solves, its case model and schema."""

    name: str
    summary: str

    @property
    def case_model(self) -> Any:
        """The pydantic model a case of this problem is validated with."""
        from mdcalc.problems import PROBLEMS

        return PROBLEMS[self.name].load().Case

    def schema(self) -> dict[str, Any]:
        """The JSON Schema of a case file (``mdcalc schema PROBLEM``)."""
        from mdcalc.input.schema import case_schema
        from mdcalc.runs.study.spec import StudySpec

        return case_schema(self.case_model, self.name, {"study": StudySpec})

    def template(self) -> dict[str, Any]:
        """A starter case (``mdcalc new PROBLEM --minimal``), as a dict."""
        from mdcalc.problems import PROBLEMS

        return dict(PROBLEMS[self.name].load().template())


def registry() -> dict[str, ProblemInfo]:
    """Every problem by name, with its one-line summary."""
    from mdcalc.problems import PROBLEMS

    return {name: ProblemInfo(name, spec.summary) for name, spec in PROBLEMS.items()}
