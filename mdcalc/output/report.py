"""The Report value: its sections and the grids every text renderer lays out.

A problem's ``report(result)`` builds a :class:`Report` out of sections:

* :class:`Quantities` -- labelled values with units; every quantity has a stable
  ``key`` that names it in the JSON ``results`` and in ``[expect]`` tables;
* :class:`Table` -- a plain table (a road-surface table, a time history);
* :class:`MethodsTable` -- each method's value, relative error against the reference
  method and measured run time (built by :mod:`mdcalc.methods`).

Two renderings dispatch on the section type (``functools.singledispatch``), so a
new section type adds one function to each and nothing else changes: here
:func:`section_grid`, the cells that rich and plain text (:mod:`mdcalc.output.text`),
HTML and Markdown (:mod:`mdcalc.output.document`) lay out, and in
:mod:`mdcalc.output.jsondoc` the JSON.

JSON layout (``format`` 1, stable; documented in docs/contract.md)::

    {"mdcalc": "0.1.0", "format": 1, "problem": "braking", "case": "x.toml",
     "title": "...", "status": "ok" | "no-answer", "message": null | "...",
     "results": {"<key>": {"value": 35.3, "unit": "m", "label": "..."}, ...},
     "sections": [{"kind": "quantities" | "table" | "methods", ...}, ...],
     "notes": [{"level": "warning" | "info", "text": "..."}],
     "budget": {"time_limit_s": 60.0 | null, "cut": ["<what ran over>", ...]}}
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import singledispatch
from typing import Any, Literal

#: A result's value; a tuple is a list of numbers (gear ratios), an array in JSON.
Value = float | int | str | bool | tuple[float, ...]
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
    if isinstance(value, tuple):
        return " / ".join(format_value(v, digits) for v in value)
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


# ----------------------------------------------------------------------------- grid
#
# What every text renderer (rich, plain text, HTML, Markdown) shows of a section:
# the same header, cells and alignment, so the four never differ in content. A column
# that no row has a value in (a Methods note no method carries, a table column of
# dashes) is left out: a report shows only what its scene needs. JSON keeps every
# field: its format is stable.

#: Column roles: how a renderer styles a column (rich: "label" bold, "note" dim,
#: "value" and "unit" kept on one line; HTML and Markdown: classes and alignment).
Role = Literal["label", "value", "unit", "note", "cell", "method", "number", "error", "time"]


@dataclass
class Grid:
    """A section as cells: ``header`` None for a list of labelled values."""

    title: str
    header: list[str] | None
    rows: list[list[str]]
    right: list[bool]  # each column right-aligned
    roles: list[Role]
    strong: list[bool]  # each row emphasized (the reference method)
    kind: Literal["quantities", "table", "methods"]

    def shown(self) -> Grid:
        """This grid without the columns whose every cell is empty ("" or "—"); a
        Methods "rel. error" column goes with its value column."""
        filled = [
            not self.rows or any(row[i] not in ("", "—") for row in self.rows)
            for i in range(len(self.roles))
        ]
        keep = [
            i
            for i, role in enumerate(self.roles)
            if (filled[i - 1] if role == "error" else filled[i])
        ]
        if len(keep) == len(self.roles):
            return self

        def pick(cells: list[Any]) -> list[Any]:
            return [cells[i] for i in keep]

        header = pick(self.header) if self.header is not None else None
        rows = [pick(row) for row in self.rows]
        return Grid(
            self.title, header, rows, pick(self.right), pick(self.roles), self.strong, self.kind
        )


@singledispatch
def section_grid(section: Any) -> Grid:
    raise TypeError(f"no layout for {type(section).__name__}")


@section_grid.register
def _(section: Quantities) -> Grid:
    rows = [[q.label, format_value(q.value), q.unit, q.note] for q in section.items]
    roles: list[Role] = ["label", "value", "unit", "note"]
    right = [False, True, False, False]
    return Grid(section.title, None, rows, right, roles, [False] * len(rows), "quantities")


@section_grid.register
def _(section: Table) -> Grid:
    first = section.rows[0] if section.rows else []
    right = [
        not (i < len(first) and isinstance(first[i], str)) for i in range(len(section.columns))
    ]
    header = [f"{c.label} ({c.unit})" if c.unit else c.label for c in section.columns]
    scales = _column_scales(section.rows)
    rows = [
        [format_value(_rounding_noise_as_zero(v, k)) for v, k in zip(row, scales, strict=False)]
        for row in section.rows
    ]
    roles: list[Role] = ["cell"] * len(section.columns)
    return Grid(section.title, header, rows, right, roles, [False] * len(rows), "table")


#: A number this much smaller than the largest of its column is rounding noise of a
#: difference (μ₂₃ = 1.88·10⁻¹⁶ at t = 0, where it is 0): it prints as 0.
NOISE = 1e-12


def _column_scales(rows: list[list[Value]]) -> list[float]:
    """The largest magnitude of the numbers of each column (0 where there are none)."""
    width = max((len(row) for row in rows), default=0)
    scales = [0.0] * width
    for row in rows:
        for i, v in enumerate(row):
            if isinstance(v, float) and math.isfinite(v):
                scales[i] = max(scales[i], abs(v))
    return scales


def _rounding_noise_as_zero(value: Value, scale: float) -> Value:
    if isinstance(value, float) and 0.0 < abs(value) < NOISE * scale:
        return 0.0
    return value


@section_grid.register
def _(section: MethodsTable) -> Grid:
    header, right = ["method"], [False]
    roles: list[Role] = ["method"]
    for q in section.quantities:
        header += [f"{q.label} ({q.unit})" if q.unit else q.label, "rel. error"]
        right += [True, True]
        roles += ["number", "error"]
    header += ["run time", "note"]
    right += [True, False]
    roles += ["time", "note"]
    rows = []
    for row in section.rows:
        cells = [row.method]
        for q in section.quantities:
            cells.append(format_value(row.values.get(q.key)))
            cells.append("reference" if row.reference else format_error(row.rel_errors.get(q.key)))
        cells += [format_seconds(row.seconds), row.note]
        rows.append(cells)
    strong = [row.reference for row in section.rows]
    return Grid(section.title, header, rows, right, roles, strong, "methods")


def grids(report: Report) -> list[Grid]:
    """Every section of ``report`` as the grid the renderers show."""
    return [section_grid(section).shown() for section in report.sections]
