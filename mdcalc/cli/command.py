"""What a problem command does once its arguments are read, without typer.

Shared by the typer application (:mod:`mdcalc.cli.app`) and the console script's direct
path for a plain run (:mod:`mdcalc.cli.launch`): the same body, the same exit codes and
messages whichever parsed the command line. Imports nothing heavy: a scene's
modules load inside the body.
"""

import os
import sys
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Any

from mdcalc._version import __version__
from mdcalc.errors import (
    EXIT_BUG,
    EXIT_INPUT,
    EXIT_INTERRUPTED,
    EXIT_NO_ANSWER,
    InputError,
    Problem,
)
from mdcalc.problems import ProblemSpec

#: mdcalc.core.budget.DEFAULT_SECONDS (not imported here: the CLI loads it only to run).
DEFAULT_TIME_LIMIT = 60.0


def limit_of(seconds: float) -> float | None:
    """A --time-limit value as the solvers take it: 0 is none."""
    return seconds if seconds > 0 else None


def print_error(line: str) -> None:
    print(line, file=sys.stderr)


#: The width of text written to a pipe or a file (a terminal's own width otherwise).
PIPE_WIDTH = 140


def make_console(stderr: bool = False) -> Any:
    from rich.console import Console

    stream = sys.stderr if stderr else sys.stdout
    # A pipe gets plain text at a width that keeps the Methods table on one line.
    return Console(file=stream, width=None if stream.isatty() else PIPE_WIDTH, highlight=False)


def guard(body: Callable[[], int], debug: bool, json_case: str | None = None) -> int:
    """Run a command body; map errors to the exit codes of the contract. With
    ``json_case`` (a command's ``--json``), an input error or a bug also writes its
    record on stdout, the one ``run --json`` writes for that file."""
    try:
        return body()
    except InputError as exc:
        print_error(str(exc))
        if json_case is not None:
            from mdcalc.output.jsondoc import error_json, input_errors

            print(error_json(json_case, "input-error", input_errors(exc.problems), indent=2))
        return EXIT_INPUT
    except KeyboardInterrupt:
        import signal

        signal.signal(signal.SIGINT, signal.SIG_DFL)  # a second Ctrl-C ends at once
        print_error("mdcalc: interrupted")
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        # The reader went away (`mdcalc ... | head`): not a bug. Point stdout at
        # devnull so the interpreter's final flush does not complain again.
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    except Exception as exc:
        if debug:
            traceback.print_exc()
        if json_case is not None:
            from mdcalc.output.jsondoc import bug_errors, error_json

            print(error_json(json_case, "internal-error", bug_errors(exc), indent=2))
        print_error(
            f"mdcalc: internal error: {type(exc).__name__}: {exc} -- this is a bug in "
            f"mdcalc {__version__}; please report it with the case file"
            + ("" if debug else " (--debug shows the traceback)")
        )
        return EXIT_BUG


def run_problem(
    spec: ProblemSpec,
    case: Path,
    as_json: bool,
    debug: bool,
    plot: Path | None = None,
    save: Path | None = None,
    force: bool = False,
    time_limit: float | None = DEFAULT_TIME_LIMIT,
    document: Path | None = None,
    work_precision: Path | None = None,
) -> int:
    def body() -> int:
        from mdcalc.output.jsondoc import to_json

        check_outputs(case, plot, save, force, document, work_precision)
        from mdcalc.api import solve  # the one path, as from Python

        ladders = work_precision is not None
        run = solve(case, spec.name, time_limit=time_limit, work_precision=ladders).run
        report = run.report
        charts = _charts(run, plot) if plot is not None else []
        diagrams = _diagrams(run, work_precision) if work_precision is not None else []
        if as_json:
            print(to_json(report))
        else:
            from mdcalc.cli.terminal import print_report

            print_report(report, PIPE_WIDTH, make_console)
        if plot is not None and charts:
            from mdcalc.output.plot import render

            render(charts, plot, title=report.title, replace=force)
            print_error(f"wrote {plot}")
        if work_precision is not None and diagrams:
            from mdcalc.output.plot import render

            render(diagrams, work_precision, title=report.title, replace=force)
            print_error(f"wrote {work_precision}")
        if save is not None:
            _save(run, save, force)
            print_error(f"wrote {save}")
        if document is not None:
            from mdcalc.output.document import write

            for written in write(run, document, force):
                print_error(f"wrote {written}")
        if report.status != "ok":
            if as_json or not _one_stream():  # else the report has just said it
                print_error(f"{case}: error: no answer: {report.message}")
            return EXIT_NO_ANSWER
        return 0

    return guard(body, debug, str(case) if as_json else None)


def _one_stream() -> bool:
    """Are stdout and stderr the same file (one terminal)? Then a no-answer report's
    reason, which the report prints, is not printed twice."""
    import os

    try:
        out, err = os.fstat(sys.stdout.fileno()), os.fstat(sys.stderr.fileno())
    except (OSError, ValueError, AttributeError):  # a stream without a file (a test's)
        return False
    return (out.st_dev, out.st_ino) == (err.st_dev, err.st_ino)


def run_batch(
    paths: list[Path],
    jobs: int = 0,
    out: Path | None = None,
    as_json: bool = False,
    report_dir: Path | None = None,
    time_limit: float | None = DEFAULT_TIME_LIMIT,
    scheduler: str | None = None,
    debug: bool = False,
) -> int:
    """``mdcalc run``: many case files in a process pool (or on a dask cluster), each
    result written as soon as it and the ones before it are done; a summary at the end.
    Exit 0 when every file computed; otherwise the worst file's code."""

    def body() -> int:
        import shutil
        import time
        from collections import Counter

        from mdcalc.cli.terminal import print_run_summary
        from mdcalc.errors import STATUS_OF_EXIT
        from mdcalc.runs.batch import FileRunner, RunOptions, lost_file, worst_exit
        from mdcalc.runs.cluster import executor, scheduler_of
        from mdcalc.runs.pool import collect, jobs_for

        files = collect(paths, outputs=out is not None or report_dir is not None)
        if report_dir is not None and any(
            f.out_name.with_suffix(".html") == Path("index.html") for f in files
        ):
            clash = next(f for f in files if f.out_name.with_suffix(".html") == Path("index.html"))
            why = "its report would be the index page DIR/index.html; rename the case file"
            raise InputError(clash.path, [Problem(f"--report-dir: {why}")])
        if not files:
            raise InputError(" ".join(map(str, paths)), [Problem("no *.toml case files here")])
        workers = jobs_for(jobs, len(files))
        text = not as_json and out is None
        width = shutil.get_terminal_size().columns if sys.stdout.isatty() else 140
        options = RunOptions(
            json=as_json or out is not None,
            text=text,
            color=sys.stdout.isatty() and "NO_COLOR" not in os.environ,
            width=width,
            time_limit=time_limit,
            document=report_dir is not None,
        )
        counts: Counter[str] = Counter()
        index: list[tuple[str, str, str, str, str, str]] = []
        failed: list[tuple[str, str]] = []
        with executor(scheduler_of(scheduler), workers) as mapper:
            start = time.perf_counter()
            flushed = start
            # Streamed: each result is written as soon as it and the ones before it are done.
            outcomes = mapper(FileRunner(options), [str(f.path) for f in files], on_error=lost_file)
            for case, outcome in zip(files, outcomes, strict=True):
                flushed = _write_outcome(case, outcome, out, as_json, text, flushed)
                if report_dir is not None:
                    index.append(_write_document(case, outcome, report_dir))
                counts[outcome.status] += 1
                if outcome.exit_code != 0:
                    failed.append((outcome.path, outcome.status))
        seconds = time.perf_counter() - start
        if report_dir is not None:
            from mdcalc.input.casefile import write_text_atomic
            from mdcalc.output.document import index_html

            write_text_atomic(report_dir / "index.html", index_html(index))
            written = sum(1 for row in index if row[4])
            print_error(f"wrote {report_dir / 'index.html'} and {written} reports")
        how = mapper.description
        print_run_summary(counts, failed, len(files), seconds, how, stderr=as_json)
        return worst_exit(code for code, status in STATUS_OF_EXIT.items() if counts[status])

    return guard(body, debug)


def _write_document(case: Any, outcome: Any, folder: Path) -> tuple[str, str, str, str, str, str]:
    """Write a file's HTML report under ``folder``; its row of the index page (with
    why it has no answer, or no report: its first message, less the file's name)."""
    from mdcalc.input.casefile import write_text_atomic

    name = case.out_name.with_suffix(".html")
    if outcome.document:
        write_text_atomic(folder / name, outcome.document)
    link = name.as_posix() if outcome.document else ""
    lines = [line for message in outcome.messages for line in message.splitlines()]
    why = "; ".join(_reason(line, outcome.path) for line in lines if line.strip())
    row = (str(case.path), outcome.problem or "", outcome.title or "", outcome.status, link, why)
    return row


def _reason(line: str, path: str) -> str:
    """A message line for the index: ``FILE:3: error: key: message`` as ``line 3:
    key: message``, ``FILE: error: no answer: …`` as ``no answer: …``."""
    import re

    line = line.strip().removeprefix(path).removeprefix(":")
    return re.sub(r"^(\d+): error: ", r"line \1: ", line.strip()).removeprefix("error: ")


def _write_outcome(
    case: Any, outcome: Any, out: Path | None, as_json: bool, text: bool, flushed: float
) -> float:
    """Write one file's outcome where it goes; flush stdout every 0.2 s (streaming)."""
    import time

    from mdcalc.input.casefile import write_text_atomic

    if out is not None:
        write_text_atomic(out / case.out_name, outcome.json + "\n")
    if as_json:
        print(outcome.json, flush=False)
    elif text:
        sys.stdout.write(outcome.text)
        print()
    if (now := time.perf_counter()) - flushed > 0.2:
        sys.stdout.flush()
        flushed = now
    for message in outcome.messages:
        print_error(message)
    return flushed


def check_outputs(
    case: Path,
    plot: Path | None,
    save: Path | None,
    force: bool,
    document: Path | None = None,
    work_precision: Path | None = None,
) -> None:
    """Refuse --plot, --work-precision, --save and --report paths before anything is
    computed."""
    problems: list[tuple[Path, str]] = []
    outputs = (
        ("--plot", plot, None),
        ("--work-precision", work_precision, None),
        ("--save", save, (".toml",)),
        ("--report", document, (".html", ".md")),
    )
    for option, path, suffixes in outputs:
        if path is None:
            continue
        if suffixes is None:
            from mdcalc.output.plot import FORMATS, matplotlib_missing

            if path.suffix.lower() not in FORMATS:
                problems.append((path, f"{option}: use a file ending {', '.join(FORMATS)}"))
            elif (missing := matplotlib_missing()) is not None:
                problems.append((path, missing))
        elif path.suffix.lower() not in suffixes:
            problems.append((path, f"{option}: use a file ending {' or '.join(suffixes)}"))
        try:
            path.exists()
        except OSError as exc:  # a name too long, say
            problems.append((path, f"{option}: cannot use this path: {exc.strerror}"))
            continue
        if path.is_dir():
            problems.append((path, f"{option}: is a folder; give a file name"))
        elif path.exists() and not force:
            problems.append((path, f"{option}: the file exists; use --force to overwrite it"))
        elif path.resolve() == case.resolve():
            problems.append((path, f"{option}: would overwrite the case file itself"))
    if (
        plot is not None
        and work_precision is not None
        and plot.resolve() == work_precision.resolve()
    ):
        problems.append((work_precision, "--work-precision: the same file as --plot; give another"))
    if document is not None and document.suffix.lower() == ".md":
        problems += _chart_file_problems(case, plot, document, force, work_precision)
    if problems:  # the first file's problems (an error names one file)
        first = problems[0][0]
        raise InputError(first, [Problem(m) for path, m in problems if path == first])


def _chart_file_problems(
    case: Path, plot: Path | None, document: Path, force: bool, diagram: Path | None = None
) -> list[tuple[Path, str]]:
    """A Markdown report's chart PNGs (NAME-1.png, ...) must not overwrite the case
    file or the --plot picture, nor, without --force, a file that is there."""
    import glob

    from mdcalc.output.document import is_chart_file

    problems: list[tuple[Path, str]] = []
    others = ((case, "the case file"), (plot, "the --plot picture"),
              (diagram, "the --work-precision picture"))  # fmt: skip
    for other, what in others:
        if other is not None and is_chart_file(document, other):
            why = f"--report: its chart pictures ({document.stem}-N.png) would overwrite {what}"
            problems.append((document, f"{why} {other}"))
    if not force:
        pattern = glob.escape(str(document.with_name(document.stem))) + "-*.png"
        there = sorted(Path(p) for p in glob.glob(pattern) if is_chart_file(document, Path(p)))
        if there:
            problems.append((there[0], "--report: file exists; use --force to overwrite it"))
    return problems


def _diagrams(run: Any, path: Path) -> list[Any]:
    from mdcalc.output.precision import charts

    diagrams = charts(run.report)
    if not diagrams:
        why = "this scene runs no ODE method" if run.report.status == "ok" else "no answer"
        print_error(f"{path}: warning: --work-precision: {why}; no file written")
    return diagrams


def _charts(run: Any, plot: Path) -> list[Any]:
    make = getattr(run.module, "charts", None)
    charts = make(run.result) if make is not None and run.result is not None else []
    if not charts:
        why = "this problem draws no plot" if make is None else "this scene has no curve to draw"
        print_error(f"{plot}: warning: --plot: {why}; no file written")
    return list(charts)


def _save(run: Any, path: Path, force: bool) -> None:
    """The case as read, with the results in a [saved] table (tomli-w, atomic)."""
    from mdcalc.input.casefile import write_toml_atomic
    from mdcalc.output.jsondoc import saved_table

    data = {k: v for k, v in run.case.data.items() if k != "saved"}
    data["saved"] = {**saved_table(run.report), "case": str(run.case.path)}
    write_toml_atomic(path, data, force=force)
