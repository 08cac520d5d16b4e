"""The Report value and its two renderers, rich (terminal) and JSON.

A problem's ``report(result)`` builds a :class:`Report` out of sections:

* :class:`Quantities` -- labelled values with units; every quantity has a stable
  ``key`` that names it in the JSON ``results`` and in ``[expect]`` tables;
* :class:`Table` -- a plain table (a road-surface table, a time history);
* :class:`MethodsTable` -- each method's value, relative error against the reference
  method and measured run time (built by :mod:`mdcalc.methods`).

Renderers dispatch on the section type (``functools.singledispatch``), so a new
section type adds one function per renderer and nothing else changes.

JSON layout (``format`` 1, stable; documented in the README)::

    {"mdcalc": "0.1.0", "format": 1, "problem": "braking", "case": "x.toml",
     "title": "...", "status": "ok" | "no-answer", "message": null | "...",
     "results": {"<key>": {"value": 35.3, "unit": "m", "label": "..."}, ...},
     "sections": [{"kind": "quantities" | "table" | "methods", ...}, ...],
     "notes": [{"level": "warning" | "info", "text": "..."}],
     "budget": {"time_limit_s": 60.0 | null, "cut": ["<what ran over>", ...]}}
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from functools import singledispatch
from typing import Any, Literal

from mdcalc import __version__

Value = float | int | str | bool
Status = Literal["ok", "no-answer"]
JSON_FORMAT = 1


@dataclass(frozen=True)
class Quantity:
    """One result: ``key`` is its stable name in JSON and in ``[expect]`` tables."""

    key: str
    label: str
    value: Value
    unit: str = ""
    note: str = ""


@dataclass
class Quantities:
    title: str
    items: list[Quantity]


@dataclass(frozen=True)
class Column:
    label: str
    unit: str = ""


@dataclass
class Table:
    title: str
    key: str
    columns: list[Column]
    rows: list[list[Value]]


@dataclass(frozen=True)
class MethodQuantity:
    """A key result compared across methods."""

    key: str
    label: str
    unit: str


@dataclass
class MethodRow:
    method: str
    values: dict[str, float | None]
    rel_errors: dict[str, float | None]
    seconds: float | None  # None: the method did not run (not applicable)
    reference: bool = False
    note: str = ""
    #: Modules the method loads (``Method.imports``); not shown, not in the JSON: the
    #: import test checks that a scene loads scipy only where a method asks for it.
    imports: tuple[str, ...] = ()


@dataclass
class MethodsTable:
    title: str
    key: str
    quantities: list[MethodQuantity]
    rows: list[MethodRow]


Section = Quantities | Table | MethodsTable


@dataclass(frozen=True)
class Note:
    level: Literal["info", "warning"]
    text: str


@dataclass
class Report:
    problem: str
    title: str
    sections: list[Section] = field(default_factory=list)
    notes: list[Note] = field(default_factory=list)
    status: Status = "ok"
    message: str | None = None
    case: str = ""
    #: The time limit the case ran under [s] (None: none) and what it cut.
    time_limit: float | None = None
    cut: list[str] = field(default_factory=list)

    def results(self) -> dict[str, Quantity]:
        """Every quantity by key, plus ``status`` (for ``[expect] status = ...``)."""
        out: dict[str, Quantity] = {"status": Quantity("status", "Status", self.status)}
        for section in self.sections:
            if isinstance(section, Quantities):
                for q in section.items:
                    out[q.key] = q
        return out


# --------------------------------------------------------------------------- numbers


def format_value(value: Value | None, digits: int = 5) -> str:
    """Human form of a value: ``digits`` significant figures, no float noise."""
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return value
    if value == 0:
        return "0"
    magnitude = abs(value)
    if 1e-4 <= magnitude < 1e7:
        decimals = max(0, digits - 1 - math.floor(math.log10(magnitude)))
        text = f"{value:.{decimals}f}"
        return text.rstrip("0").rstrip(".") if "." in text else text
    return f"{value:.{digits - 1}e}"


def format_error(error: float | None) -> str:
    if error is None:
        return "—"
    if error == 0:
        return "0"
    return f"{error:.1e}"


def format_seconds(seconds: float | None) -> str:
    if seconds is None:
        return "—"
    if seconds < 1e-3:
        return f"{seconds * 1e6:.3g} µs"
    if seconds < 1:
        return f"{seconds * 1e3:.3g} ms"
    return f"{seconds:.3g} s"


def first_non_finite(report: Report) -> str | None:
    """The first place of ``report`` holding NaN or an infinity ("key = inf"), or None."""

    def bad(value: Any) -> bool:
        return isinstance(value, float) and not math.isfinite(value)

    for section in report.sections:
        if isinstance(section, Quantities):
            for q in section.items:
                if bad(q.value):
                    return f"{q.key} = {q.value}"
        elif isinstance(section, Table):
            for row in section.rows:
                for column, value in zip(section.columns, row, strict=False):
                    if bad(value):
                        return f"{section.key}: {column.label} = {value}"
        else:
            for method in section.rows:
                for key, number in (*method.values.items(), *method.rel_errors.items()):
                    if bad(number):
                        return f"{section.key}: {method.method}: {key} = {number}"
    return None


# ----------------------------------------------------------------------------- JSON


def _json_value(value: Value | None) -> Any:
    # Solvers never hand out NaN or inf; this is the last guard, so that the JSON
    # stays valid (json.dumps would write the non-standard token NaN).
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError(f"non-finite value {value!r} reached the report")
    return value


@singledispatch
def section_json(section: Any) -> dict[str, Any]:
    raise TypeError(f"no JSON renderer for {type(section).__name__}")


@section_json.register
def _(section: Quantities) -> dict[str, Any]:
    return {"kind": "quantities", "title": section.title, "keys": [q.key for q in section.items]}


@section_json.register
def _(section: Table) -> dict[str, Any]:
    return {
        "kind": "table",
        "title": section.title,
        "key": section.key,
        "columns": [{"label": c.label, "unit": c.unit} for c in section.columns],
        "rows": [[_json_value(v) for v in row] for row in section.rows],
    }


@section_json.register
def _(section: MethodsTable) -> dict[str, Any]:
    return {
        "kind": "methods",
        "title": section.title,
        "key": section.key,
        "quantities": [
            {"key": q.key, "label": q.label, "unit": q.unit} for q in section.quantities
        ],
        "rows": [
            {
                "method": row.method,
                "reference": row.reference,
                "values": {k: _json_value(v) for k, v in row.values.items()},
                "rel_errors": {k: _json_value(v) for k, v in row.rel_errors.items()},
                "seconds": row.seconds,
                "note": row.note,
            }
            for row in section.rows
        ],
    }


def to_json(report: Report, indent: int | None = 2) -> str:
    """The report as JSON; ``indent=None`` gives one line (JSON lines)."""
    document = {
        "mdcalc": __version__,
        "format": JSON_FORMAT,
        "problem": report.problem,
        "case": report.case,
        "title": report.title,
        "status": report.status,
        "message": report.message,
        "results": {
            key: {"value": _json_value(q.value), "unit": q.unit, "label": q.label}
            for key, q in report.results().items()
            if key != "status"
        },
        "sections": [section_json(s) for s in report.sections],
        "notes": [{"level": n.level, "text": n.text} for n in report.notes],
        "budget": {"time_limit_s": report.time_limit, "cut": list(report.cut)},
    }
    separators = (",", ":") if indent is None else None
    return json.dumps(
        document, indent=indent, separators=separators, ensure_ascii=False, allow_nan=False
    )


def saved_table(report: Report) -> dict[str, Any]:
    """The report's results and Methods tables as a TOML table (``--save``): values
    under ``results``, their units under ``units``, one table per Methods row with
    ``<key>`` and ``<key>_rel_error``; empty values left out (TOML has no null)."""
    quantities = [q for key, q in report.results().items() if key != "status"]
    table: dict[str, Any] = {"mdcalc": __version__, "status": report.status}
    if report.message:
        table["message"] = report.message
    table["results"] = {q.key: q.value for q in quantities}
    table["units"] = {q.key: q.unit for q in quantities if q.unit}
    methods = {
        s.key: [_saved_row(row) for row in s.rows]
        for s in report.sections
        if isinstance(s, MethodsTable)
    }
    if methods:
        table["methods"] = methods
    return table


def _saved_row(row: MethodRow) -> dict[str, Any]:
    out: dict[str, Any] = {"method": row.method}
    if row.reference:
        out["reference"] = True
    for key, value in row.values.items():
        if value is not None:
            out[key] = value
        error = row.rel_errors.get(key)
        if error is not None:
            out[f"{key}_rel_error"] = error
    if row.seconds is not None:
        out["seconds"] = row.seconds
    if row.note:
        out["note"] = row.note
    return out


# ----------------------------------------------------------------------------- rich


@singledispatch
def section_rich(section: Any) -> Any:
    raise TypeError(f"no rich renderer for {type(section).__name__}")


@section_rich.register
def _(section: Quantities) -> Any:
    from rich.table import Table as RichTable

    table = RichTable(title=section.title, title_justify="left", show_header=False, box=None)
    table.add_column("quantity", style="bold", no_wrap=False)
    table.add_column("value", justify="right", no_wrap=True)
    table.add_column("unit", no_wrap=True)
    table.add_column("note", style="dim")
    for q in section.items:
        table.add_row(q.label, format_value(q.value), q.unit, q.note)
    return table


@section_rich.register
def _(section: Table) -> Any:
    from rich.table import Table as RichTable

    table = RichTable(title=section.title, title_justify="left")
    first = section.rows[0] if section.rows else []
    for i, c in enumerate(section.columns):
        text = i < len(first) and isinstance(first[i], str)
        label = f"{c.label} ({c.unit})" if c.unit else c.label
        table.add_column(label, justify="left" if text else "right")
    for row in section.rows:
        table.add_row(*(format_value(v) for v in row))
    return table


@section_rich.register
def _(section: MethodsTable) -> Any:
    from rich.table import Table as RichTable

    table = RichTable(title=section.title, title_justify="left")
    table.add_column("method")
    for q in section.quantities:
        table.add_column(f"{q.label} ({q.unit})" if q.unit else q.label, justify="right")
        table.add_column("rel. error", justify="right")
    table.add_column("run time", justify="right")
    table.add_column("note", style="dim")
    for row in section.rows:
        cells = [f"[bold]{row.method}[/bold]" if row.reference else row.method]
        for q in section.quantities:
            cells.append(format_value(row.values.get(q.key)))
            cells.append("reference" if row.reference else format_error(row.rel_errors.get(q.key)))
        cells.append(format_seconds(row.seconds))
        cells.append(row.note)
        table.add_row(*cells)
    return table


def render_rich(report: Report, console: Any) -> None:
    """Print the report on a rich Console (colour only on a terminal)."""
    from rich.text import Text

    console.print(Text(report.title, style="bold underline"))
    if report.case:
        console.print(Text(f"{report.problem} · {report.case}", style="dim"))
    for section in report.sections:
        console.print()
        console.print(section_rich(section))
    if report.notes:
        console.print()
        for note in report.notes:
            style = "yellow" if note.level == "warning" else "cyan"
            console.print(Text(f"{note.level}: ", style=f"bold {style}") + Text(note.text))
    if report.status != "ok":
        console.print()
        console.print(Text(f"no answer: {report.message}", style="bold red"))
