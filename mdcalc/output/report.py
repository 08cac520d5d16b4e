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

JSON layout (``format`` 2, stable; documented in docs/contract.md; units in the
ASCII form pint reads, :func:`ascii_unit`)::

    {"mdcalc": "0.1.0", "format": 2, "problem": "braking", "case": "x.toml",
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
#: 2: units in ASCII (``kg*m^2``); 1 wrote them as shown (``kg·m²``).
JSON_FORMAT = 2


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
    #: How a cell is shown: "exact", a number with every digit that matters
    #: (:func:`exact_text`), not five (a value converted from what a case file wrote,
    #: checked by eye against it); "quantity", a quantity string as written, its units
    #: as a person reads them (:func:`pretty_unit`); "unit", a unit (the JSON writes
    #: it in ASCII, :func:`ascii_unit`). The cells themselves keep the data.
    #: For a method's numbers: "tolerance" (``1e-5``), "error" (``1.7e-05``, as in a
    #: Methods table), "seconds" (a run time, ``2.42 ms``: the header carries no unit).
    kind: Literal["", "exact", "quantity", "unit", "tolerance", "error", "seconds"] = ""


#: The key of a report's table of the values a case file wrote with units.
UNITS_KEY = "units"


@dataclass
class Table:
    title: str
    key: str
    columns: list[Column]
    rows: list[list[Value]]
    #: Each row is another quantity (a study's results): a column holds numbers of
    #: different units, so none is rounding noise of another.
    rows_differ: bool = False


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


#: Superscript digits and signs, as a person reads a power (kg·m², 1/s²).
_SUPERSCRIPT = str.maketrans("0123456789-+n", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺ⁿ")
_PLAIN = {v: k for k, v in zip("0123456789-+n", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺ⁿ", strict=True)}
#: Units whose shown form pint reads otherwise: "g" is the gram to pint.
_ASCII_NAMES = {"g": "g_0", "×": ""}


#: The one JSON unit pint cannot read: a power law's stiffness, n being the case's
#: exponent, not a unit (docs/contract.md).
NO_PINT_UNIT = "N*m/rad^n"


def ascii_unit(unit: str) -> str:
    """A unit as the JSON writes it: ASCII that pint parses to the same unit
    (``kg·m²`` → ``kg*m^2``, ``1/s²`` → ``1/s^2``, ``N·m/radⁿ`` → ``N*m/rad^n``,
    ``g`` (standard gravity) → ``g_0``, ``×`` (a ratio) → ``""``)."""
    import re

    if unit in _ASCII_NAMES:
        return _ASCII_NAMES[unit]
    text = unit.replace("·", "*")
    return re.sub("[⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺ⁿ]+", lambda m: "^" + "".join(_PLAIN[c] for c in m.group(0)), text)


def pretty_unit(text: str) -> str:
    """A unit (or a quantity string) written in ASCII as a person reads it, in the
    order written: ``t*m**2`` → ``t·m²``, ``N * m/deg`` → ``N·m/deg``, ``s^-1`` → ``s⁻¹``
    (a power that is not a whole number stays ``^0.5``)."""
    import re

    if text == "g_0":  # the JSON's standard gravity
        return "g"

    def power(match: re.Match[str]) -> str:
        return match.group(1).translate(_SUPERSCRIPT)

    out = re.sub(r"\s*(?:\*\*|\^)\s*([-+]?\d+)(?![\d.])", power, text)
    out = re.sub(r"\s*\*\*\s*", "^", out)
    return re.sub(r"\s*\*\s*", "·", out)


def exact_text(value: float) -> str:
    """A number with the digits to check a conversion by eye (12 significant, float
    noise gone): ``18609.2 kN·m/rad`` → ``18609200``, not ``1.8609e+07``."""
    return f"{value:.12g}"


def format_error(error: float | None) -> str:
    if error is None:
        return "—"
    if error == 0:
        return "0"
    return f"{error:.1e}"


def format_seconds(seconds: float | None) -> str:
    if seconds is None:
        return "—"
    seconds = float(f"{seconds:.3g}")  # 999.7 µs is 1 ms, not "1e+03 µs"
    if seconds < 1e-3:
        return f"{seconds * 1e6:.3g} µs"
    if seconds < 1:
        return f"{seconds * 1e3:.3g} ms"
    if seconds >= 1e3:  # a long study: whole seconds, not "1.23e+03 s"
        return f"{seconds:.0f} s"
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
    # a column of numbers is right-aligned: its first cell that is not empty says
    firsts = [next((r[i] for r in section.rows if i < len(r) and r[i] != ""), "")
              for i in range(len(section.columns))]  # fmt: skip
    right = [not isinstance(first, str) for first in firsts]
    header = [
        f"{c.label} ({c.unit})" if c.unit and c.kind != "seconds" else c.label
        for c in section.columns
    ]
    scales = [0.0] * len(section.columns) if section.rows_differ else _column_scales(section.rows)
    kinds = [c.kind for c in section.columns]
    rows = [[_cell(v, k, kind) for v, k, kind in zip(row, scales, kinds, strict=False)]
            for row in section.rows]  # fmt: skip
    roles: list[Role] = ["cell"] * len(section.columns)
    return Grid(section.title, header, rows, right, roles, [False] * len(rows), "table")


def _cell(value: Value, scale: float, kind: str) -> str:
    if kind == "exact" and isinstance(value, float):
        return exact_text(value)
    if isinstance(value, int | float) and not isinstance(value, bool):
        if kind == "tolerance":
            return f"{value:.0e}".replace("e-0", "e-")
        if kind == "error":
            return format_error(float(value))
        if kind == "seconds":
            return format_seconds(float(value))
    if kind == "quantity" and isinstance(value, str):
        return pretty_unit(value)
    return format_value(_rounding_noise_as_zero(value, scale))


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
