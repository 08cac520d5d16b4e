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
    rows = [[format_value(v) for v in row] for row in section.rows]
    roles: list[Role] = ["cell"] * len(section.columns)
    return Grid(section.title, header, rows, right, roles, [False] * len(rows), "table")


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
    return dumps(document, indent)


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


def grid_rich(grid: Grid) -> Any:
    """A rich Table of ``grid``: a heavy box with a header, or none for quantities."""
    from rich.table import Table as RichTable

    if grid.header is None:
        table = RichTable(title=grid.title, title_justify="left", show_header=False, box=None)
    else:
        table = RichTable(title=grid.title, title_justify="left")
    for i, role in enumerate(grid.roles):
        label = grid.header[i] if grid.header is not None else role
        table.add_column(
            label,
            justify="right" if grid.right[i] else "left",
            style="bold" if role == "label" else "dim" if role == "note" else None,
            no_wrap=grid.header is None and role in ("value", "unit"),
        )
    for row, strong in zip(grid.rows, grid.strong, strict=True):
        cells = list(row)
        if strong and grid.roles[0] == "method":
            cells[0] = f"[bold]{cells[0]}[/bold]"
        table.add_row(*cells)
    return table


def render_rich(report: Report, console: Any) -> None:
    """Print the report on a rich Console (colour only on a terminal)."""
    from rich.text import Text

    console.print(Text(report.title, style="bold underline"))
    if report.case:
        console.print(Text(f"{report.problem} · {report.case}", style="dim"))
    for grid in grids(report):
        console.print()
        console.print(grid_rich(grid))
    if report.notes:
        console.print()
        for note in report.notes:
            style = "yellow" if note.level == "warning" else "cyan"
            console.print(Text(f"{note.level}: ", style=f"bold {style}") + Text(note.text))
    if report.status != "ok":
        console.print()
        console.print(Text(f"no answer: {report.message}", style="bold red"))


# ----------------------------------------------------------------------- plain text
#
# A report printed to a pipe or a file has no colour, so rich's work (its import and
# layout: ~45 ms of a 0.3 s scene) buys nothing but the layout itself. render_plain
# makes the very text rich prints for a report on a colourless console, for the
# reports whose layout is simple: every table at its natural width within the
# console, single-width characters, no markup- or emoji-like text. Anything else is
# None, and the caller uses rich. tests/test_plain.py compares the two over every
# shipped case and over made-up reports that reach each fallback.

#: rich's HEAVY_HEAD box: top, header row, header rule, body row, bottom.
_BOX_TOP, _BOX_HEAD, _BOX_RULE, _BOX_ROW, _BOX_BOTTOM = "┏━┳┓", "┃ ┃┃", "┡━╇┩", "│ ││", "└─┴┘"


def _patterns() -> tuple[Any, Any, Any]:
    import re

    # Characters rich gives one cell (its own table; tests/test_plain.py checks each):
    # printable Latin, Greek, Cyrillic, phonetic letters, punctuation, super- and
    # subscripts, arrows, mathematical operators, box drawing and blocks.
    narrow = (
        "\x20-\x7e\xa1-\u02ff\u0370-\u0482\u048a-\u052f\u1d00-\u1dbf\u2010-\u2027"
        "\u2030-\u205e\u2070-\u20cf\u20f1-\u22ff\u2500-\u25fc"
    )
    other = re.compile(f"[^{narrow}]")
    markup = re.compile(r"(\\*)\[([a-z#/@][^[]*?)]")  # rich.markup.RE_TAGS
    emoji = re.compile(r":\S*?:")  # what rich's emoji codes look like
    return other, markup, emoji


_OTHER, _MARKUP, _EMOJI = _patterns()


def _narrow(text: str) -> bool:
    """Every character of ``text`` takes one cell on a terminal (none is a control)."""
    return _OTHER.search(text) is None


def _literal(text: str) -> bool:
    """rich prints a string cell or title as it is: narrow, no markup, no emoji code."""
    return _narrow(text) and not _MARKUP.search(text) and not _EMOJI.search(text)


def _wrap(text: str, width: int) -> list[str] | None:
    """rich's word wrap (rich._wrap.divide_line, then rstrip_end) of one line of
    narrow text; None where a word is longer than the line (rich folds it)."""
    import re

    breaks: list[int] = []
    offset = 0
    for match in re.finditer(r"\s*\S+\s*", text):
        start, word = match.start(), match.group(0)
        length = len(word.rstrip())
        if width - offset >= length:
            offset += len(word)
        elif length > width:
            return None
        elif offset and start:
            breaks.append(start)
            offset = len(word)
    lines = [text[a:b] for a, b in zip([0, *breaks], [*breaks, len(text)], strict=True)]
    out = []
    for line in lines:
        if len(line) > width:  # rich crops trailing blanks beyond the width
            blanks = len(line) - len(line.rstrip())
            line = line[: len(line) - min(blanks, len(line) - width)]
        out.append(line)
    return out


def _plain_table(
    title: str,
    header: list[str] | None,
    rows: list[list[str]],
    right: list[bool],
    boxed: bool,
    width: int,
) -> list[str] | None:
    """A rich Table (padding 1, edges padded) at its natural width, as lines."""
    cells = [header, *rows] if header is not None else rows
    if not rows or any(len(row) != len(right) for row in cells if row is not None):
        return None
    for row in cells:
        for cell, r in zip(row or (), right, strict=True):
            # rich right-justifies a cell stripped of trailing blanks
            if cell != cell.rstrip() or (r and cell != cell.strip()) or not _literal(cell):
                return None
    widths = [max(len(row[i]) for row in cells if row is not None) for i in range(len(right))]
    total = sum(widths) + 2 * len(widths) + (len(widths) + 1 if boxed else 0)
    if total > width or not _literal(title):
        return None

    def line(row: list[str], edge: str) -> str:
        parts = [
            " " + (cell.rjust(w) if r else cell.ljust(w)) + " "
            for cell, w, r in zip(row, widths, right, strict=True)
        ]
        return edge[0] + edge[2].join(parts) + edge[3] if boxed else "".join(parts)

    def rule(edge: str) -> str:
        return edge[0] + edge[2].join(edge[1] * (w + 2) for w in widths) + edge[3]

    title_lines = _wrap(title, total) if title else []
    if title_lines is None:
        return None
    out = [t.ljust(total) for t in title_lines]
    if boxed:
        out.append(rule(_BOX_TOP))
    if header is not None:
        out.append(line(header, _BOX_HEAD))
        if boxed:
            out.append(rule(_BOX_RULE))
    out.extend(line(row, _BOX_ROW) for row in rows)
    if boxed:
        out.append(rule(_BOX_BOTTOM))
    return out


def plain_summary(
    before: list[str],
    header: list[str],
    rows: list[list[str]],
    right: list[bool],
    after: list[str],
    width: int,
) -> str | None:
    """What rich prints on a colourless console ``width`` wide for the lines ``before``
    (rich markup), a boxed table of ``header`` and ``rows``, and the lines ``after``
    (printed with ``markup=False``); None where only rich can lay it out. The summary
    of ``mdcalc run`` on a pipe."""
    table = _plain_table("", header, rows, right, True, width)
    # markup=False still turns ":smile:" into an emoji in rich: such a line goes to rich
    plain = [_literal(line) for line in before]
    plain += [_narrow(line) and not _EMOJI.search(line) for line in after]
    wrapped = [_wrap(line, width) for line in before + after]
    if table is None or not all(plain) or any(w is None for w in wrapped):
        return None
    lines = [line for w in wrapped[: len(before)] for line in w or ()]
    lines += table + [line for w in wrapped[len(before) :] for line in w or ()]
    return "\n".join(lines) + "\n"


def render_plain(report: Report, width: int) -> str | None:
    """The text :func:`render_rich` prints on a colourless console ``width`` wide, or
    None where only rich can lay the report out (see above)."""
    out: list[str] = []

    def text(line: str) -> bool:
        if not _narrow(line):  # a rich Text: no markup, no emoji codes
            return False
        wrapped = _wrap(line, width)
        if wrapped is None:
            return False
        out.extend(wrapped)
        return True

    if not text(report.title):
        return None
    if report.case and not text(f"{report.problem} · {report.case}"):
        return None
    for grid in grids(report):
        boxed = grid.header is not None
        lines = _plain_table(grid.title, grid.header, grid.rows, grid.right, boxed, width)
        if lines is None:
            return None
        out.append("")
        out.extend(lines)
    if report.notes:
        out.append("")
        for note in report.notes:
            if not text(f"{note.level}: {note.text}"):
                return None
    if report.status != "ok":
        out.append("")
        if not text(f"no answer: {report.message}"):
            return None
    return "\n".join(out) + "\n"
