"""The body of ``mdcalc schema``: a problem's case-file schema as JSON, or its keys as a
table (:mod:`mdcalc.input.schema` makes both from the problem's pydantic model)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from mdcalc.errors import InputError, Problem
from mdcalc.problems import PROBLEMS


def problem_schema(problem: str) -> dict[str, Any]:
    """The JSON Schema of ``problem``'s case files, study files included."""
    from mdcalc.input.schema import case_schema
    from mdcalc.runs.study.spec import StudySpec

    if problem not in PROBLEMS:
        raise InputError(
            "mdcalc schema",
            [Problem(f"unknown problem {problem!r}; allowed: {', '.join(PROBLEMS)}")],
        )
    return case_schema(PROBLEMS[problem].load().Case, problem, {"study": StudySpec})


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
        make_console().print(table)
        return 0
    text = schema_text(problem)
    if output is None:
        print(text, end="")
        return 0
    from mdcalc.input.files import write_atomic

    write_atomic(output, text, replace=force)
    print_error(f"wrote {output}")
    return 0
