"""The console script ``mdcalc``.

A plain run of one scene, ``mdcalc PROBLEM CASE.toml [--json] [--debug]`` (what a
shell loop over case files types), goes straight to the problem's command body
(:func:`mdcalc.cli.command.run_problem`) without importing typer: its parser and the
building of every command are most of what such a run spends above the stack's
floor. So does a plain batch, ``mdcalc run PATH... [--jobs N] [--json] [--debug]``
(:func:`mdcalc.cli.command.run_batch`). Any other command line, an option more, a
misspelling, ``--help``, shell completion, goes through the typer application
(:mod:`mdcalc.cli.app`) as before; the body, its output, its messages and exit codes are
the same either way (tests/test_launch.py).

``mdcalc CASE.toml [options]`` runs the problem the file names (``problem = ...``; a
study file, one with a ``[study]`` table, runs as ``mdcalc study``): the command line
is read as ``mdcalc PROBLEM CASE.toml [options]`` and goes the same ways
(:func:`named_problem`).
"""

import os
import re
import stat
import sys

from mdcalc.cli.startup import prepare
from mdcalc.errors import InputError, Problem

#: The flags a direct run takes (each a bool, False when absent).
DIRECT_FLAGS = ("--json", "--debug")


def direct_run(argv: list[str]) -> tuple[str, str, bool, bool] | None:
    """(problem, case, as_json, debug) when ``argv`` is a plain problem run the direct
    path takes; None for anything the typer application must parse."""
    from mdcalc.problems import PROBLEMS

    if not argv or argv[0] not in PROBLEMS:
        return None
    if _completing():
        return None
    cases = [arg for arg in argv[1:] if not arg.startswith("-")]
    flags = [arg for arg in argv[1:] if arg.startswith("-")]
    if len(cases) != 1 or not cases[0] or any(flag not in DIRECT_FLAGS for flag in flags):
        return None
    if not _readable_or_missing(cases[0]):
        return None
    return argv[0], cases[0], "--json" in flags, "--debug" in flags


def direct_batch(argv: list[str]) -> tuple[list[str], int, bool, bool] | None:
    """(paths, jobs, as_json, debug) when ``argv`` is a plain ``run`` the direct path
    takes (``--jobs N``, ``-j N`` or ``--jobs=N`` with N digits; ``--json``;
    ``--debug``; at least one path); None for anything typer must parse."""
    if not argv or argv[0] != "run" or _completing():
        return None
    paths: list[str] = []
    jobs, as_json, debug = 0, False, False
    rest = iter(argv[1:])
    for arg in rest:
        if arg in ("--jobs", "-j") or arg.startswith("--jobs="):
            value = arg.partition("=")[2] if "=" in arg else next(rest, "")
            if not (value.isascii() and value.isdigit()) or len(value) > 9:
                return None  # typer says what is wrong with it (or takes a huge number)
            jobs = int(value)
        elif arg in DIRECT_FLAGS:
            as_json, debug = as_json or arg == "--json", debug or arg == "--debug"
        elif arg.startswith("-") or not arg or not _readable_or_missing(arg):
            return None
        else:
            paths.append(arg)
    return (paths, jobs, as_json, debug) if paths else None


#: The commands that are not problems: a file of the same name does not take their
#: place (tests/test_launch.py checks the list against the typer app).
COMMANDS = ("check", "run", "sweep", "study", "new", "schema")


def named_problem(argv: list[str]) -> list[str] | InputError | None:
    """``argv`` with the command the case file names put before it, when ``argv``
    starts with a case file instead of a command (``mdcalc case.toml --json``); an
    error message when that file names no problem (or none of mdcalc's); None for a
    command line that starts with a command (or an option).

    A regular file whose own lines name its problem (``problem = "..."`` before its
    first table, no ``base``) is read without a TOML parser; any other (a base, a pipe,
    no such line) is read by the case loader, whose messages are the commands'."""
    from mdcalc.problems import PROBLEMS

    if not argv or argv[0].startswith("-") or _completing():
        return None
    first = argv[0]
    if first in PROBLEMS or first in COMMANDS:
        return None
    if not first.endswith(".toml") and not os.path.isfile(first):
        return None  # a misspelt command: typer says which
    try:
        regular = stat.S_ISREG(os.stat(first).st_mode)
    except FileNotFoundError:
        return InputError(first, [Problem("no such file")])
    except OSError as exc:
        return InputError(first, [Problem(f"cannot read: {exc.strerror}")])
    name, base, study = _top_lines(first) if regular else (None, None, False)
    if name is None or base is not None:
        loaded = _loaded(first)
        if isinstance(loaded, InputError):
            return loaded
        name, study = loaded
    allowed = ", ".join(PROBLEMS)
    if name is None:
        message = (
            'the file names no problem (problem = "NAME" before its first table); run: '
            f"mdcalc PROBLEM {first}, PROBLEM one of: {allowed}"
        )
        return InputError(first, [Problem(message, "problem")])
    if name not in PROBLEMS:
        message = f"unknown problem {name!r}; allowed: {allowed}"
        return InputError(first, [Problem(message, "problem")])
    return ["study" if study else name, *argv]


def _loaded(path: str) -> tuple[str | None, bool] | InputError:
    """(problem, is a study) as the case loader reads the file (its base followed), or
    what the loader found wrong."""
    from pathlib import Path

    from mdcalc.input.casefile import read_case

    try:
        case = read_case(Path(path))
    except InputError as exc:
        return exc
    problem = case.data.get("problem")
    return (problem if isinstance(problem, str) else None), "study" in case.data


def _top_lines(path: str) -> tuple[str | None, str | None, bool]:
    """(problem, base, has a [study] table) as a case file's own lines say, read
    without a TOML parser: ``problem = "..."`` and ``base = "..."`` before the first
    table; ``[study]``, ``[study.inputs...]`` or a top-level ``study.`` key."""
    try:
        with open(path, encoding="utf-8", errors="replace") as handle:
            text = handle.read(1 << 20)
    except OSError:
        return None, None, False  # the loader says why
    found: dict[str, str] = {}
    tables, study = False, False
    for line in text.splitlines():
        stripped = line.strip()
        if stripped.startswith("["):
            tables = True
            study = study or stripped.replace(" ", "").startswith(("[study]", "[study."))
            continue
        match = _TOP_LINE.match(stripped)
        if match and not tables:
            found.setdefault(match.group(1), match.group(2))
        study = study or (not tables and _STUDY_KEY.match(stripped) is not None)
    return found.get("problem"), found.get("base"), study


#: A top-level key of the [study] table written dotted or inline (``study.samples``).
_STUDY_KEY = re.compile(r"""^(study|"study"|'study')\s*[.=]""")
#: A top-level line that names a case file's problem or its base.
_TOP_LINE = re.compile(r"""^(problem|base)\s*=\s*["']([^"']*)["']\s*(#.*)?$""")


def _readable_or_missing(path: str) -> bool:
    """What typer's path arguments let through (click.Path(readable=True)): a path that
    is not there (the body says so), or one this process may read; an unreadable one
    goes to typer, which refuses it before anything runs."""
    try:
        os.stat(path)
    except OSError:
        return True
    return os.access(path, os.R_OK)


def _completing() -> bool:
    """click's shell completion is asking (it goes through typer)."""
    return any(name.startswith("_") and name.endswith("_COMPLETE") for name in os.environ)


def main() -> None:
    prepare()
    named = named_problem(sys.argv[1:])
    if isinstance(named, InputError):
        from mdcalc.errors import EXIT_INPUT

        print(named, file=sys.stderr)
        if "--json" in sys.argv[2:]:  # the record run --json writes for such a file
            from mdcalc.output.jsondoc import error_json, input_errors

            print(error_json(sys.argv[1], "input-error", input_errors(named.problems), 2))
        sys.exit(EXIT_INPUT)
    if named is not None:
        sys.argv[1:] = named
    try:
        plain = direct_run(sys.argv[1:])
        if plain is not None:
            from pathlib import Path

            from mdcalc.cli.command import DEFAULT_TIME_LIMIT, run_problem
            from mdcalc.problems import PROBLEMS

            problem, case, as_json, debug = plain
            spec = PROBLEMS[problem]
            sys.exit(run_problem(spec, Path(case), as_json, debug, time_limit=DEFAULT_TIME_LIMIT))
        batch = direct_batch(sys.argv[1:])
        if batch is not None:
            from pathlib import Path

            from mdcalc.cli.command import run_batch

            paths, jobs, as_json, debug = batch
            sys.exit(run_batch([Path(p) for p in paths], jobs, as_json=as_json, debug=debug))
    except KeyboardInterrupt:  # before the body's own guard: as it would say
        from mdcalc.errors import EXIT_INTERRUPTED

        print("mdcalc: interrupted", file=sys.stderr)
        sys.exit(EXIT_INTERRUPTED)
    from mdcalc.cli.app import app

    app()
