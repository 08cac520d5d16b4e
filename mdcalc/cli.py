"""Thin command-line layer: one command per registered problem, plus check and new.

Exit codes: 0 computed, 1 ``check`` mismatch, 2 bad input, 3 valid input without an
answer, 70 a bug (one line; the traceback only with ``--debug``). Messages go to
stderr as ``file:line: error: path: message``; results to stdout. JSON is written
with plain ``print``: a rich Console wraps long lines when piped and breaks it.
"""

from __future__ import annotations

import sys
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

import typer

from mdcalc import __version__
from mdcalc.errors import EXIT_BUG, EXIT_INPUT, EXIT_MISMATCH, EXIT_NO_ANSWER, InputError, Problem
from mdcalc.problems import PROBLEMS, ProblemSpec

app = typer.Typer(
    name="mdcalc",
    help="Machine-dynamics calculator: mdcalc PROBLEM CASE.toml [--json]. "
    "`mdcalc new PROBLEM` writes a starter case.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)

JsonOption = Annotated[bool, typer.Option("--json", help="Write the results as JSON.")]
DebugOption = Annotated[bool, typer.Option("--debug", help="Show the traceback of a bug.")]


def _stderr(line: str) -> None:
    print(line, file=sys.stderr)


def _console(stderr: bool = False) -> Any:
    from rich.console import Console

    stream = sys.stderr if stderr else sys.stdout
    # A pipe gets plain text at a width that keeps the Methods table on one line.
    return Console(file=stream, width=None if stream.isatty() else 140, highlight=False)


def _guard(body: Callable[[], int], debug: bool) -> int:
    """Run a command body; map errors to the exit codes of the contract."""
    try:
        return body()
    except InputError as exc:
        _stderr(str(exc))
        return EXIT_INPUT
    except KeyboardInterrupt:
        _stderr("mdcalc: interrupted")
        return 130
    except BrokenPipeError:
        # The reader went away (`mdcalc ... | head`): not a bug. Point stdout at
        # devnull so the interpreter's final flush does not complain again.
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    except Exception as exc:
        if debug:
            traceback.print_exc()
        _stderr(
            f"mdcalc: internal error: {type(exc).__name__}: {exc} -- this is a bug in "
            f"mdcalc {__version__}; please report it with the case file"
            + ("" if debug else " (--debug shows the traceback)")
        )
        return EXIT_BUG


def run_problem(spec: ProblemSpec, case: Path, as_json: bool, debug: bool) -> int:
    def body() -> int:
        from mdcalc.report import render_rich, to_json
        from mdcalc.runner import run_case

        report = run_case(case, expected_problem=spec.name)
        if as_json:
            print(to_json(report))
        else:
            render_rich(report, _console())
        if report.status != "ok":
            _stderr(f"{case}: error: no answer: {report.message}")
            return EXIT_NO_ANSWER
        return 0

    return _guard(body, debug)


def _make_problem_command(spec: ProblemSpec) -> Callable[..., None]:
    def command(
        case: Annotated[
            Path, typer.Argument(help="Case file (TOML).", show_default=False, metavar="CASE.toml")
        ],
        as_json: JsonOption = False,
        debug: DebugOption = False,
    ) -> None:
        raise typer.Exit(run_problem(spec, case, as_json, debug))

    command.__doc__ = spec.summary
    return command


for _spec in PROBLEMS.values():
    app.command(_spec.name, help=_spec.summary)(_make_problem_command(_spec))


@app.command("check")
def check_command(
    paths: Annotated[list[Path], typer.Argument(help="Case files or folders.")],
    debug: DebugOption = False,
) -> None:
    """Run every case file that has an [expect] table; exit 1 if any value is off."""

    def body() -> int:
        from rich.table import Table

        from mdcalc.check import check_paths

        outcome = check_paths(paths)
        table = Table(title="mdcalc check", title_justify="left")
        for column in ("file", "result", "expected", "got", "tolerance", ""):
            table.add_column(column, overflow="fold")
        for row in outcome.rows:
            mark = "[green]pass[/green]" if row.passed else "[bold red]FAIL[/bold red]"
            table.add_row(row.file, row.key, row.expected, row.got, row.tolerance, mark)
        console = _console()
        if outcome.rows:
            console.print(table)
        for message in outcome.input_errors + outcome.internal_errors:
            _stderr(message)
        print(
            f"{outcome.files_checked} case files checked, {outcome.files_skipped} without "
            f"[expect], {len(outcome.input_errors)} unreadable"
        )
        print(f"{outcome.passed} passed, {outcome.failed} failed")
        if outcome.input_errors:
            return EXIT_INPUT
        return EXIT_MISMATCH if outcome.failed else 0

    raise typer.Exit(_guard(body, debug))


@app.command("new")
def new_command(
    problem: Annotated[str, typer.Argument(help=f"One of: {', '.join(PROBLEMS)}.")],
    output: Annotated[
        Path | None, typer.Option("-o", "--output", help="Write to this file, not stdout.")
    ] = None,
    force: Annotated[bool, typer.Option("--force", help="Overwrite an existing file.")] = False,
    debug: DebugOption = False,
) -> None:
    """Write a starter case file for PROBLEM that runs as it is."""

    def body() -> int:
        if problem not in PROBLEMS:
            raise InputError(
                "mdcalc new",
                [Problem(f"unknown problem {problem!r}; allowed: {', '.join(PROBLEMS)}")],
            )
        data = PROBLEMS[problem].load().template()
        if output is None:
            import tomli_w

            sys.stdout.write(tomli_w.dumps(data))
        else:
            from mdcalc.casefile import write_toml_atomic

            write_toml_atomic(output, data, force=force)
            _stderr(f"wrote {output}")
        return 0

    raise typer.Exit(_guard(body, debug))


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
    app()
