"""The bodies of ``mdcalc schema`` (a problem's case-file schema as JSON, or its keys as
a table; :mod:`mdcalc.input.schema` makes both from the problem's pydantic model) and
of ``mdcalc new`` (a starter case beside its schema; :mod:`mdcalc.input.starter`)."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from mdcalc.errors import InputError, Problem
from mdcalc.problems import PROBLEMS


def problem_schema(problem: str) -> dict[str, Any]:
    """The JSON Schema of ``problem``'s case files, study files included."""
    from mdcalc.api import registry

    _known(problem, "mdcalc schema")
    return registry()[problem].schema()


def _known(problem: str, command: str) -> None:
    """Refuse a problem mdcalc does not have, naming the ones it has."""
    if problem not in PROBLEMS:
        allowed = ", ".join(PROBLEMS)
        raise InputError(command, [Problem(f"unknown problem {problem!r}; allowed: {allowed}")])


def schema_text(problem: str) -> str:
    """The schema as a file holds it: indented JSON, units as written (UTF-8)."""
    return json.dumps(problem_schema(problem), indent=2, ensure_ascii=False) + "\n"


def schema_file_name(problem: str) -> str:
    """The file name a starter case's ``#:schema`` line points to."""
    return f"mdcalc-{problem}.schema.json"


def run_schema(problem: str, output: Path | None, keys: bool, force: bool) -> int:
    """``mdcalc schema PROBLEM [-o FILE] [--keys]``."""
    from mdcalc.cli.command import make_console, print_error

    if keys:
        from rich.markup import escape
        from rich.table import Table

        from mdcalc.input.schema import key_rows
        from mdcalc.output.text import print_titled

        rows = key_rows(problem_schema(problem))
        table = Table(title=f"The keys of an mdcalc {problem} case file", title_justify="left")
        table.add_column("key", overflow="fold", no_wrap=True)
        table.add_column("unit", overflow="fold")
        table.add_column("default", overflow="fold", max_width=20)
        table.add_column("allowed", overflow="fold", max_width=24)
        table.add_column("description", overflow="fold", ratio=1)
        for row in rows:
            table.add_row(
                *(
                    escape(cell)
                    for cell in (row.key, row.unit, row.default, row.allowed, row.description)
                )
            )
        print_titled(make_console(), table)
        return 0
    text = schema_text(problem)
    if output is None:
        print(text, end="")
        return 0
    from mdcalc.input.files import write_atomic

    write_atomic(output, text, replace=force)
    print_error(f"wrote {output}")
    return 0


def starter(problem: str) -> str:
    """The starter case of ``problem`` as ``mdcalc new`` writes it."""
    from mdcalc.input.starter import starter_text

    schema = problem_schema(problem)
    spec = PROBLEMS[problem]
    module = spec.load()
    extras: dict[str, Any] = getattr(module, "starter_extras", dict)()
    return starter_text(
        problem,
        spec.summary,
        module.Case,
        schema,
        module.template(),
        extras,
        schema_file_name(problem),
    )


def run_new(problem: str, output: Path | None, minimal: bool, force: bool) -> int:
    """``mdcalc new PROBLEM [-o FILE] [--minimal] [--force]``."""
    import sys

    from mdcalc.cli.command import print_error
    from mdcalc.input.files import write_atomic

    _known(problem, "mdcalc new")
    if minimal:
        import tomli_w

        text = tomli_w.dumps(PROBLEMS[problem].load().template())
    else:
        text = starter(problem)
    if output is None:
        sys.stdout.write(text)
        return 0
    write_atomic(output, text, replace=force)
    print_error(f"wrote {output}")
    if not minimal:
        beside = output.parent / schema_file_name(problem)
        if not os.path.lexists(beside):  # whatever is there (a link too) is left alone
            write_atomic(beside, schema_text(problem), replace=False)
            print_error(f"wrote {beside} (for an editor: Taplo, Even Better TOML)")
    return 0
