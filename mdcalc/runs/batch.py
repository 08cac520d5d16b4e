"""Batch runs: many case files through a process pool (``mdcalc run``, ``check --jobs``).

The pool and the file list are :mod:`mdcalc.runs.pool`'s. Each file's outcome comes back
as text (a JSON line or a rendered report); the parent writes it in input order, so
a run's output does not depend on the number of jobs. One bad file is reported and
the rest run on.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mdcalc.errors import (
    EXIT_BUG,
    EXIT_INPUT,
    EXIT_NO_ANSWER,
    EXIT_OK,
    STATUS_OF_EXIT,
    InputError,
)

#: Worse outcomes first: the exit code of a batch is the worst of its files'.
SEVERITY = (EXIT_BUG, EXIT_INPUT, EXIT_NO_ANSWER, EXIT_OK)


def worst_exit(codes: Iterable[int]) -> int:
    seen = set(codes)
    return next((code for code in SEVERITY if code in seen), EXIT_OK)


# ------------------------------------------------------------------------- one file


@dataclass
class Outcome:
    """What one case file gave: its exit code, the rendered result, the messages."""

    path: str
    exit_code: int
    problem: str | None = None
    title: str | None = None
    json: str = ""  # one line
    text: str = ""  # the rendered report (text mode)
    messages: list[str] = field(default_factory=list)  # for stderr
    seconds: float = 0.0
    document: str = ""  # the HTML calculation report (run --report-dir)

    @property
    def status(self) -> str:
        return STATUS_OF_EXIT[self.exit_code]


@dataclass(frozen=True)
class RunOptions:
    json: bool  # render JSON (for stdout or --out)
    text: bool  # render the report as text (stdout without --json)
    color: bool
    width: int
    #: Cheap methods are repeated for this long to time them (``methods.timed``);
    #: a batch takes 5 µs, not the 2 ms of a single run: the mean of a few calls of a
    #: microsecond method (its timer reads cost 0.05 µs), not of hundreds.
    timing_budget: float = 5e-6
    #: Each file's time limit [s] (None: none).
    time_limit: float | None = 60.0
    #: Make each file's HTML calculation report (``run --report-dir``).
    document: bool = False


def _error_json(path: str, status: str, problems: list[dict[str, object]]) -> str:
    from mdcalc.output.jsondoc import error_json

    return error_json(path, status, problems)


def run_file(path: str, options: RunOptions) -> Outcome:
    """Run one case file; never raises (a bug becomes an outcome with exit 70)."""
    from mdcalc import methods
    from mdcalc.input.casefile import read_case
    from mdcalc.output.jsondoc import to_json
    from mdcalc.output.text import render_plain, render_rich
    from mdcalc.runs.runner import solve_text

    methods.MIN_TIMING_SECONDS = options.timing_budget
    start = time.perf_counter()
    try:
        case = read_case(Path(path))
        if "study" in case.data:
            outcome = run_study_file(case, options)
            outcome.seconds = time.perf_counter() - start
            return outcome
        run = solve_text(case, time_limit=options.time_limit)
        report = run.report
        outcome = Outcome(
            path,
            EXIT_OK if report.status == "ok" else EXIT_NO_ANSWER,
            report.problem,
            report.title,
        )
        if report.status != "ok":
            outcome.messages.append(f"{path}: error: no answer: {report.message}")
        if options.json:
            outcome.json = to_json(report, indent=None)
        if options.document:
            from mdcalc.output.document import document_of, html_of

            outcome.document = html_of(document_of(run))
        if options.text:
            plain = None if options.color else render_plain(report, options.width)
            outcome.text = plain or _rendered(lambda c: render_rich(report, c), options)
    except InputError as exc:
        from mdcalc.output.jsondoc import input_errors

        outcome = Outcome(path, EXIT_INPUT, messages=[str(exc)])
        outcome.json = _error_json(path, "input-error", input_errors(exc.problems))
    except Exception as exc:
        from mdcalc.output.jsondoc import bug_errors

        line = f"{path}: internal error: {type(exc).__name__}: {exc}"
        outcome = Outcome(path, EXIT_BUG, messages=[line])
        outcome.json = _error_json(path, "internal-error", bug_errors(exc))
    outcome.seconds = time.perf_counter() - start
    return outcome


def _rendered(render: Callable[[Any], None], options: RunOptions) -> str:
    from io import StringIO

    from rich.console import Console

    buffer = StringIO()
    console = Console(
        file=buffer,
        width=options.width,
        force_terminal=options.color,
        no_color=not options.color,
        highlight=False,
    )
    render(console)
    return buffer.getvalue()


def run_study_file(case: Any, options: RunOptions) -> Outcome:
    """A study file in a batch: the study runs in this worker, its samples one after
    another (or by the kernel); its outcome is the study's JSON or report."""
    from mdcalc.runs.cluster import PoolMapper
    from mdcalc.runs.study import run
    from mdcalc.runs.study.output import render_rich, to_json

    path = str(case.path)
    result = run(case, PoolMapper(1), options.time_limit)
    answered = any(s is not None for s in result.stats.values())
    outcome = Outcome(path, EXIT_OK if answered else EXIT_NO_ANSWER, result.plan.problem)
    outcome.title = case.data.get("title") if isinstance(case.data.get("title"), str) else None
    if not answered:
        outcome.messages.append(f"{path}: error: no answer: no sample gave a value")
    if options.json:
        outcome.json = to_json(result, indent=None)
    if options.text:
        outcome.text = _rendered(lambda console: render_rich(result, console), options)
    if options.document:
        from mdcalc.output.document import html_of
        from mdcalc.runs.study.output import study_document

        outcome.document = html_of(study_document(result))
    return outcome


def lost_file(path: str, error: BaseException) -> Outcome:
    """A file whose worker died under it (the system killed it) or was lost on a
    cluster: an internal error of that file; the batch goes on."""
    line = f"{path}: internal error: its worker process died ({type(error).__name__}: {error})"
    outcome = Outcome(path, EXIT_BUG, messages=[line])
    outcome.json = _error_json(path, "internal-error", [{"message": line}])
    return outcome


class FileRunner:
    """A picklable ``run_file`` with its options bound (for the pool)."""

    def __init__(self, options: RunOptions) -> None:
        self.options = options

    def __call__(self, path: str) -> Outcome:
        return run_file(path, self.options)
