"""A report as JSON (``--json``, format 2; the layout is in :mod:`mdcalc.output.report`)
and as the TOML table of ``--save``."""

from __future__ import annotations

import math
from functools import singledispatch
from typing import Any

from mdcalc._version import __version__
from mdcalc.output.report import (
    JSON_FORMAT,
    MethodRow,
    MethodsTable,
    Quantities,
    Report,
    Table,
    Value,
    ascii_unit,
)


def _json_value(value: Value | None) -> Any:
    # Solvers never hand out NaN or inf; this is the last guard, so that the JSON
    # stays valid (json.dumps would write the non-standard token NaN).
    if isinstance(value, tuple):
        return [_json_value(v) for v in value]  # a list of numbers: a JSON array
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
        "columns": [{"label": c.label, "unit": ascii_unit(c.unit)} for c in section.columns],
        "rows": [
            [
                ascii_unit(v) if c.kind == "unit" and isinstance(v, str) else _json_value(v)
                for v, c in zip(row, section.columns, strict=False)
            ]
            for row in section.rows
        ],
    }


@section_json.register
def _(section: MethodsTable) -> dict[str, Any]:
    return {
        "kind": "methods",
        "title": section.title,
        "key": section.key,
        "quantities": [
            {"key": q.key, "label": q.label, "unit": ascii_unit(q.unit)} for q in section.quantities
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
            key: {"value": _json_value(q.value), "unit": ascii_unit(q.unit), "label": q.label}
            for key, q in report.results().items()
            if key != "status"
        },
        "sections": [section_json(s) for s in report.sections],
        "notes": [{"level": n.level, "text": n.text} for n in report.notes],
        "budget": {"time_limit_s": report.time_limit, "cut": list(report.cut)},
    }
    return dumps(document, indent)


def error_json(
    case: str, status: str, errors: list[dict[str, Any]], indent: int | None = None
) -> str:
    """The record of a file without a report (``status`` "input-error" or
    "internal-error"): what ``run --json`` writes for it, and ``--json`` of a problem
    command. ``errors``: one object a problem (``line``, ``column``, ``path``,
    ``message``; a bug's ``message`` and ``traceback``)."""
    document = {
        "mdcalc": __version__,
        "format": JSON_FORMAT,
        "case": case,
        "status": status,
        "errors": errors,
    }
    return dumps(document, indent)


def bug_errors(exc: BaseException) -> list[dict[str, Any]]:
    """The ``errors`` of an internal-error record: the exception and its traceback (the
    one being handled)."""
    import traceback

    return [{"message": f"{type(exc).__name__}: {exc}", "traceback": traceback.format_exc()}]


def input_errors(problems: Any) -> list[dict[str, Any]]:
    """The ``errors`` of an input-error record, from an InputError's problems."""
    return [
        {"line": p.line, "column": p.column, "path": p.path, "message": p.message} for p in problems
    ]


def dumps(document: Any, indent: int | None = None) -> str:
    """JSON text of ``document`` (``indent`` None: one line; else indented by 2) with
    orjson: a batch's encoding costs a tenth of the standard library's. Floats are written in their
    shortest round-trip form (``0.00001``, where json writes ``1e-05``); NaN and inf are
    stopped before (:func:`_json_value` on every value of a report); orjson would
    write them as null."""
    import orjson

    try:
        text = orjson.dumps(
            document,
            default=_plain_number,
            option=0 if indent is None else orjson.OPT_INDENT_2,
        ).decode()
    except orjson.JSONEncodeError as exc:
        raise ValueError(str(exc)) from None
    return text


def _plain_number(value: Any) -> Any:
    """numpy's float64 and other float subclasses, as json.dumps takes them."""
    if isinstance(value, float):
        return float(value)
    raise TypeError(f"Object of type {type(value).__name__} is not JSON serializable")


def saved_table(report: Report) -> dict[str, Any]:
    """The report's results and Methods tables as a TOML table (``--save``): values
    under ``results``, their units under ``units``, one table per Methods row with
    ``<key>`` and ``<key>_rel_error``; empty values left out (TOML has no null)."""
    quantities = [q for key, q in report.results().items() if key != "status"]
    table: dict[str, Any] = {"mdcalc": __version__, "status": report.status}
    if report.message:
        table["message"] = report.message
    table["results"] = {q.key: q.value for q in quantities}
    table["units"] = {q.key: ascii_unit(q.unit) for q in quantities if ascii_unit(q.unit)}
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
