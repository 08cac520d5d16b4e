"""Thin command-line layer: one command per registered problem, plus check and new.

Exit codes: 0 computed, 1 ``check`` mismatch, 2 bad input, 3 valid input without an
answer, 70 a bug (one line; the traceback only with ``--debug``), 130 Ctrl-C. Messages go to
stderr as ``file:line: error: path: message``; results to stdout. JSON is written
with plain ``print``: a rich Console wraps long lines when piped and breaks it.

The console script is :func:`mdcalc.cli.launch.main`: a plain problem run skips this
module; the command bodies both use are in :mod:`mdcalc.cli.command`.
"""

# No `from __future__ import annotations` here: typer would eval every string
# annotation of every command at start-up (~260 evals, 10 ms of `--help`).

from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

import typer

from mdcalc._version import __version__
from mdcalc.cli.command import (
    DEFAULT_TIME_LIMIT,
    check_outputs,
    guard,
    limit_of,
    make_console,
    print_error,
    run_batch,
    run_problem,
)
from mdcalc.cli.startup import prepare
from mdcalc.errors import (
    EXIT_INPUT,
    EXIT_MISMATCH,
    EXIT_NO_ANSWER,
    InputError,
    Problem,
)
from mdcalc.problems import PROBLEMS, ProblemSpec

app = typer.Typer(
    name="mdcalc",
    help="Machine-dynamics calculator: mdcalc PROBLEM CASE.toml [--json], or mdcalc "
    "CASE.toml (the problem the file names; a study file runs its study). "
    "`mdcalc new PROBLEM -o case.toml` writes a starter case, `mdcalc schema PROBLEM --keys` "
    "lists its keys.",
    no_args_is_help=True,
    add_completion=True,
    pretty_exceptions_enable=False,
    # Plain click help: typer's rich help imports rich and markdown-it (~100 ms).
    rich_markup_mode=None,
    context_settings={"help_option_names": ["-h", "--help"]},
)

JsonOption = Annotated[bool, typer.Option("--json", help="Write the results as JSON.")]
DebugOption = Annotated[bool, typer.Option("--debug", help="Show the traceback of a bug.")]


def _time_limit(what: str) -> Any:
    """The --time-limit option, its help saying what it stops."""
    return typer.Option("--time-limit", min=0.0, metavar="SECONDS", help=f"{what} 0: no limit.")


TimeLimitOption = Annotated[
    float,
    _time_limit(
        "Stop the case after this long: a slow method is skipped, a scene that cannot "
        "finish is no answer (exit 3)."
    ),
]
EachCaseTimeLimitOption = Annotated[
    float,
    _time_limit(
        "Stop each case file after this long: a slow method is skipped, a scene that "
        "cannot finish is no answer."
    ),
]
PointTimeLimitOption = Annotated[
    float,
    _time_limit("Stop each point run one by one after this long (it has no answer then)."),
]


SchedulerOption = Annotated[
    str | None,
    typer.Option(
        "--scheduler",
        metavar="ADDRESS",
        help="Run on a dask.distributed cluster: tcp://HOST:PORT, or local:N for N worker "
        "processes here (needs mdcalc[dask]). Default: $MDCALC_SCHEDULER, else the process pool.",
    ),
]


def complete_case(incomplete: str) -> list[str]:
    """Shell completion of a case argument: folders and *.toml files."""
    import os

    folder, slash, stem = incomplete.rpartition("/")
    folder = folder or ("/" if slash else ".")  # "/e" lists the root, "e" this folder
    base = incomplete[: len(incomplete) - len(stem)]
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        return []
    out = []
    for name in names:
        if not name.startswith(stem) or (name.startswith(".") and not stem.startswith(".")):
            continue
        if os.path.isdir(os.path.join(folder, name)):
            out.append(f"{base}{name}/")
        elif name.endswith(".toml"):
            out.append(f"{base}{name}")
    # Folders alone: nothing, so the shell completes them itself (bash would put a
    # space after a lone "cases/").
    return out if any(name.endswith(".toml") for name in out) else []


def complete_problem(incomplete: str) -> list[str]:
    return [name for name in PROBLEMS if name.startswith(incomplete)]


PlotOption = Annotated[
    Path | None,
    typer.Option(
        "--plot",
        help="Draw the scene's curves into FILE.png, .svg or .pdf (needs mdcalc[plot]).",
        metavar="FILE",
    ),
]
SaveOption = Annotated[
    Path | None,
    typer.Option(
        "--save",
        help="Write the case with its results (a [saved] table) to FILE.toml.",
        metavar="FILE.toml",
    ),
]
CaseArgument = Annotated[
    Path,
    typer.Argument(
        help="Case file (TOML).",
        show_default=False,
        metavar="CASE.toml",
        autocompletion=complete_case,
    ),
]


def _force_option(options: str) -> Any:
    return Annotated[bool, typer.Option("--force", help=f"Let {options} overwrite a file.")]


ForceOption = Annotated[
    bool,
    typer.Option(
        "--force", help="Let --plot, --work-precision, --save and --report overwrite a file."
    ),
]
ReportOption = Annotated[
    Path | None,
    typer.Option(
        "--report",
        help="Write a calculation report to FILE.html (charts inline) or FILE.md (chart "
        "PNGs beside it): inputs, results, Methods tables, notes, case file SHA-256.",
        metavar="FILE",
    ),
]


WorkPrecisionOption = Annotated[
    Path | None,
    typer.Option(
        "--work-precision",
        help="Run each ODE method with every scipy integrator over rtol 1e-3 ... 1e-12 and "
        "draw error against run time and evaluations into FILE.png, .svg or .pdf "
        "(needs mdcalc[plot]); the tables go into the report and the JSON.",
        metavar="FILE",
    ),
]


def _make_problem_command(spec: ProblemSpec) -> Callable[..., None]:
    def command(
        case: CaseArgument,
        as_json: JsonOption = False,
        plot: PlotOption = None,
        work_precision: WorkPrecisionOption = None,
        save: SaveOption = None,
        report: ReportOption = None,
        force: ForceOption = False,
        time_limit: TimeLimitOption = DEFAULT_TIME_LIMIT,
        debug: DebugOption = False,
    ) -> None:
        limit = limit_of(time_limit)
        raise typer.Exit(
            run_problem(
                spec,
                case,
                as_json,
                debug,
                plot,
                save,
                force,
                limit,
                document=report,
                work_precision=work_precision,
            )  # fmt: skip
        )

    command.__doc__ = spec.summary
    dropped = {"plot"} if not spec.draws else set()
    if not spec.ladders:
        dropped.add("work_precision")
    if not dropped:
        return command

    # A scene that draws nothing (braking) or has no ODE method (clutch): the same
    # command without --plot or --work-precision.
    import inspect

    signature = inspect.signature(command)
    pictures = [o for o, n in (("--plot", "plot"), ("--work-precision", "work_precision"))
                if n not in dropped]  # fmt: skip
    force = _force_option(", ".join([*pictures, "--save"]) + " and --report")
    parameters = [
        p.replace(annotation=force) if p.name == "force" else p
        for p in signature.parameters.values()
        if p.name not in dropped
    ]

    def without(**given: object) -> None:
        command(**dict.fromkeys(dropped), **given)  # type: ignore[arg-type]

    without.__signature__ = signature.replace(parameters=parameters)  # type: ignore[attr-defined]
    without.__doc__ = spec.summary
    return without


for _spec in PROBLEMS.values():
    app.command(
        _spec.name,
        help=_spec.summary,
        short_help=_spec.summary,
        epilog=f"The keys of its case file, their units and ranges: mdcalc schema {_spec.name} "
        f"--keys. A starter case: mdcalc new {_spec.name} -o case.toml.",
    )(_make_problem_command(_spec))


JobsOption = Annotated[
    int,
    typer.Option(
        "--jobs", "-j", min=0, help="Worker processes; 0: one per core (at most one per file)."
    ),
]
PointJobsOption = Annotated[
    int,
    typer.Option(
        "--jobs",
        "-j",
        min=0,
        help="Worker processes for the points run one by one (a vectorized sweep runs in "
        "this process); 0: one per core.",
    ),
]
SampleJobsOption = Annotated[
    int,
    typer.Option(
        "--jobs",
        "-j",
        min=0,
        help="Worker processes for the samples (blocks of a vectorized study, or samples "
        "run one by one); 0: one per core.",
    ),
]


@app.command(
    "check", short_help="Run the case files that have an [expect] table; exit 1 if a value is off."
)
def check_command(
    paths: Annotated[
        list[Path], typer.Argument(help="Case files or folders.", autocompletion=complete_case)
    ],
    jobs: JobsOption = 1,
    time_limit: EachCaseTimeLimitOption = DEFAULT_TIME_LIMIT,
    debug: DebugOption = False,
) -> None:
    """Run every case file that has an [expect] table; exit 1 if any value is off, 2 if
    a file cannot be read or validated."""

    def body() -> int:
        from rich.table import Table

        from mdcalc.output.text import print_titled
        from mdcalc.runs.check import check_paths, collect
        from mdcalc.runs.pool import jobs_for

        workers = jobs_for(jobs, len(collect(paths)))
        outcome = check_paths(paths, workers, limit_of(time_limit))
        table = Table(title="mdcalc check", title_justify="left")
        for column in ("file", "result", "expected", "got", "tolerance", ""):
            table.add_column(column, overflow="fold")
        for row in outcome.rows:
            mark = "[green]pass[/green]" if row.passed else "[bold red]FAIL[/bold red]"
            table.add_row(row.file, row.key, row.expected, row.got, row.tolerance, mark)
        console = make_console()
        if outcome.rows:
            print_titled(console, table)
        for message in outcome.input_errors + outcome.internal_errors:
            print_error(message)
        print(
            f"{outcome.files_checked} case files checked, {outcome.files_skipped} without "
            f"[expect], {len(outcome.input_errors)} unreadable"
        )
        print(f"{outcome.passed} passed, {outcome.failed} failed")
        if outcome.input_errors:
            return EXIT_INPUT
        return EXIT_MISMATCH if outcome.failed else 0

    raise typer.Exit(guard(body, debug))


@app.command("run", short_help="Run many case files in a process pool or on a dask cluster.")
def run_command(
    paths: Annotated[
        list[Path],
        typer.Argument(
            help="Case files or folders (searched for *.toml).", autocompletion=complete_case
        ),
    ],
    jobs: JobsOption = 0,
    out: Annotated[
        Path | None,
        typer.Option("--out", help="Write each result to DIR/<name>.json (atomically)."),
    ] = None,
    as_json: Annotated[
        bool, typer.Option("--json", help="Write each result as one JSON line on stdout.")
    ] = False,
    report_dir: Annotated[
        Path | None,
        typer.Option(
            "--report-dir",
            help="Write each file's calculation report to DIR/<name>.html and an index.html.",
            metavar="DIR",
        ),
    ] = None,
    time_limit: EachCaseTimeLimitOption = DEFAULT_TIME_LIMIT,
    scheduler: SchedulerOption = None,
    debug: DebugOption = False,
) -> None:
    """Run many case files in a process pool (or on a dask cluster); a summary at the end.

    Exit 0 when every file computed; otherwise the worst file's code: 70 a bug,
    2 bad input, 3 no answer.
    """

    raise typer.Exit(
        run_batch(paths, jobs, out, as_json, report_dir, limit_of(time_limit), scheduler, debug)
    )


@app.command("sweep", short_help="Run one case over a grid of values of its keys.")
def sweep_command(
    case: CaseArgument,
    vary: Annotated[
        list[str],
        typer.Option(
            "--vary", help="KEY=START:STOP:N, e.g. vehicle.mass=800:3000:12; repeat for a grid."
        ),
    ],
    result: Annotated[
        list[str] | None,
        typer.Option("--result", help="A result key to tabulate (default: the key results)."),
    ] = None,
    out: Annotated[
        Path | None, typer.Option("--out", help="Write the table to FILE.csv or FILE.json.")
    ] = None,
    jobs: PointJobsOption = 0,
    time_limit: PointTimeLimitOption = DEFAULT_TIME_LIMIT,
    scheduler: SchedulerOption = None,
    debug: DebugOption = False,
) -> None:
    """Run one case over a grid of values: vectorized for closed forms, else in a pool
    (or on a dask cluster).

    Without --out: the table (up to 200 points) or the range of each result.
    """

    def body() -> int:
        from mdcalc.cli.terminal import print_sweep, progress
        from mdcalc.runs.pool import jobs_for
        from mdcalc.runs.sweep import evaluate, parse_vary, plan, to_csv, to_json

        if out is not None and out.suffix.lower() not in (".csv", ".json"):
            raise InputError(out, [Problem("--out takes a .csv or a .json file")])
        from mdcalc.runs.cluster import executor, scheduler_of

        sweep = plan(case, [parse_vary(v) for v in vary])
        workers = jobs_for(jobs, sweep.points)
        with (
            executor(scheduler_of(scheduler), workers) as mapper,
            progress(sweep.points) as advance,
        ):
            table = evaluate(sweep, result or [], workers, advance, limit_of(time_limit), mapper)
        for message in table.messages[:20]:
            print_error(message)
        if len(table.messages) > 20:
            print_error(f"{case}: error: ... and {len(table.messages) - 20} more points")
        how = "vectorized" if table.vectorized else "point by point"
        if out is not None:
            from mdcalc.input.casefile import write_text_atomic

            text = to_csv(table) if out.suffix.lower() == ".csv" else to_json(table, sweep)
            write_text_atomic(out, text)
            print_error(f"wrote {out}: {sweep.points} points, {how}")
        else:
            print_sweep(table, sweep.points, how)
        return table.exit_code

    raise typer.Exit(guard(body, debug))


@app.command(
    "study", short_help="Run a scene over the scatter of its inputs: statistics, limits, Sobol."
)
def study_command(
    case: Annotated[
        Path,
        typer.Argument(
            help="Study file: a case file with a [study] table.",
            show_default=False,
            metavar="STUDY.toml",
            autocompletion=complete_case,
        ),
    ],
    as_json: JsonOption = False,
    plot: Annotated[
        Path | None,
        typer.Option(
            "--plot",
            metavar="FILE",
            help="Draw a histogram and a CDF of each result (limits marked) and the Sobol "
            "indices or rank correlations into FILE.png, .svg or .pdf (needs mdcalc[plot]).",
        ),
    ] = None,
    out: Annotated[
        Path | None,
        typer.Option(
            "--out",
            metavar="FILE",
            help="Keep every sample's inputs and results: FILE.csv, or FILE.parquet "
            "(needs pyarrow).",
        ),
    ] = None,
    report: Annotated[
        Path | None,
        typer.Option(
            "--report",
            help="Write the study's report to FILE.html (charts inline) or FILE.md (chart "
            "PNGs beside it): inputs and their distributions, statistics, limits, Sobol "
            "indices, charts, and the nominal scene's calculation report.",
            metavar="FILE",
        ),
    ] = None,
    force: Annotated[
        bool, typer.Option("--force", help="Let --plot, --out and --report overwrite a file.")
    ] = False,
    jobs: SampleJobsOption = 0,
    time_limit: Annotated[
        float,
        typer.Option(
            "--time-limit",
            min=0.0,
            metavar="SECONDS",
            help="Stop a sample after this long (it counts as over the time budget). 0: no limit.",
        ),
    ] = DEFAULT_TIME_LIMIT,
    scheduler: SchedulerOption = None,
    debug: DebugOption = False,
) -> None:
    """Run a scene over the scatter of its inputs: statistics of each result, the
    probability of exceeding each limit, Sobol indices; on this machine or a dask cluster.

    Exit 0 when the study ran (failed samples are counted in it), 2 bad input, 3 when
    no sample answered.
    """

    def body() -> int:
        from mdcalc.cli.terminal import progress
        from mdcalc.input.casefile import read_case
        from mdcalc.runs.cluster import executor, scheduler_of
        from mdcalc.runs.pool import default_jobs
        from mdcalc.runs.study import run as run_study
        from mdcalc.runs.study.output import (
            charts,
            check_out_path,
            render_rich,
            to_json,
            write_samples,
        )

        check_outputs(case, plot, None, force, report)
        check_out_path(case, out, force)
        study_case = read_case(case)
        if "study" not in study_case.data:
            raise InputError(
                case,
                [
                    Problem(
                        "no [study] table: this is a case file (run: mdcalc "
                        f"{study_case.data.get('problem', 'PROBLEM')} {case})"
                    )
                ],
            )
        with executor(scheduler_of(scheduler), jobs or default_jobs(1 << 30)) as mapper:
            with progress(None) as advance:
                result = run_study(
                    study_case,
                    mapper,
                    limit_of(time_limit),
                    advance,
                    getattr(advance, "total", None),
                )
        if as_json:
            print(to_json(result))
        else:
            render_rich(result, make_console())
        if out is not None:
            write_samples(result, out, force)
            print_error(f"wrote {out}: {len(result.samples):,} samples")
        answered = any(s is not None for s in result.stats.values())
        if plot is not None and answered:
            from mdcalc.output.plot import render

            render(
                charts(result),
                plot,
                title=f"Study: {study_case.data.get('title') or result.plan.problem}",
                replace=force,
            )
            print_error(f"wrote {plot}")
        if report is not None:
            from mdcalc.output.document import write_document
            from mdcalc.runs.study.output import study_document

            for written in write_document(study_document(result), report, force):
                print_error(f"wrote {written}")
        if not answered:
            print_error(f"{case}: error: no answer: no sample gave a value")
            return EXIT_NO_ANSWER
        return 0

    raise typer.Exit(guard(body, debug, str(case) if as_json else None))


@app.command("new", short_help="Write a starter case file for PROBLEM, with its schema.")
def new_command(
    problem: Annotated[
        str, typer.Argument(help=f"One of: {', '.join(PROBLEMS)}.", autocompletion=complete_problem)
    ],
    output: Annotated[
        Path | None,
        typer.Option(
            "-o",
            "--output",
            help="Write to this file (and the schema beside it, mdcalc-PROBLEM.schema.json, "
            "unless one is there), not stdout.",
        ),
    ] = None,
    minimal: Annotated[
        bool, typer.Option("--minimal", help="Only the keys the scene needs, no comments.")
    ] = False,
    force: Annotated[bool, typer.Option("--force", help="Overwrite an existing file.")] = False,
    debug: DebugOption = False,
) -> None:
    """Write a starter case file for PROBLEM that runs as it is: every key with its unit
    and meaning, optional sections commented out."""

    def body() -> int:
        from mdcalc.cli.schema import run_new

        return run_new(problem, output, minimal, force)

    raise typer.Exit(guard(body, debug))


@app.command(
    "schema", short_help="Write PROBLEM's case-file JSON Schema, or list its keys (--keys)."
)
def schema_command(
    problem: Annotated[
        str, typer.Argument(help=f"One of: {', '.join(PROBLEMS)}.", autocompletion=complete_problem)
    ],
    output: Annotated[
        Path | None,
        typer.Option("-o", "--output", help="Write to this file, not stdout.", metavar="FILE"),
    ] = None,
    keys: Annotated[
        bool,
        typer.Option(
            "--keys", help="Print the keys as a table: key, unit, default, allowed, description."
        ),
    ] = False,
    force: Annotated[bool, typer.Option("--force", help="Overwrite an existing file.")] = False,
    debug: DebugOption = False,
) -> None:
    """Write the JSON Schema of PROBLEM's case files (for an editor), or list its keys."""

    def body() -> int:
        from mdcalc.cli.schema import run_schema

        return run_schema(problem, output, keys, force)

    raise typer.Exit(guard(body, debug))


def _version(value: bool) -> None:
    if value:
        print(f"mdcalc {__version__}")
        raise typer.Exit()


@app.callback()
def _main(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Show version.")
    ] = False,
) -> None:
    """Machine-dynamics calculator: mdcalc PROBLEM CASE.toml [--json]."""


def main() -> None:
    """The typer application (every command and option); the console script is
    :func:`mdcalc.cli.launch.main`, which takes a plain problem run past typer."""
    prepare()
    app()
