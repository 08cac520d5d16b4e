"""Calculation reports an engineer can file: ``--report FILE.html`` or ``FILE.md``.

One document of the same :class:`~mdcalc.output.report.Report` the terminal shows, laid
out from the same grids (:func:`mdcalc.output.report.grids`: the header, cells and
alignment rich prints, all-empty columns left out), with what a reviewer needs
around it: the case file's name and SHA-256, mdcalc's version and the date, the
inputs as written and as computed with, the notes and warnings set apart before the
results, and the problem's charts (inline SVG in HTML; PNG files beside the
Markdown, linked). The HTML loads nothing from a network (no script, font or style
sheet from elsewhere) and prints on A4.
"""

from __future__ import annotations

import hashlib
import html
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any
from urllib.parse import quote

from mdcalc._version import __version__
from mdcalc.errors import InputError, Problem
from mdcalc.input.casefile import dotted, unit_of
from mdcalc.output import precision
from mdcalc.output.report import (
    UNITS_KEY,
    Grid,
    Report,
    Role,
    exact_text,
    grids,
    pretty_unit,
)

#: The report formats, by file suffix.
FORMATS = (".html", ".md")
#: Case-file keys that are not inputs of the scene.
NOT_INPUTS = ("problem", "title", "expect", "saved")
#: Headers of a list of labelled values (its grid has none), by column role.
QUANTITY_HEADERS = {"label": "quantity", "value": "value", "unit": "unit", "note": "note"}


@dataclass
class Document:
    """Everything a filed report shows, rendered by :func:`to_html` or :func:`to_markdown`."""

    report: Report
    case_name: str
    sha256: str
    date: str
    #: (key, as written, as computed with, unit) of every input value.
    inputs: list[tuple[str, str, str, str]]
    charts: list[Any] = field(default_factory=list)  # plot.Chart
    version: str = __version__
    #: The heading of the inputs table (a study's: its nominal scene's inputs).
    inputs_title: str = "Inputs"
    #: How many of the last charts are each work-precision table's (the last tables
    #: of the report), in order: they stand just above their table.
    ladder_charts: list[int] = field(default_factory=list)


def document_of(run: Any, when: datetime | None = None) -> Document:
    """The document of a finished run (:class:`mdcalc.runs.runner.Run`)."""
    case = run.case
    digest = hashlib.sha256(case.text.encode("utf-8")).hexdigest()
    stamp = (when or datetime.now(UTC)).strftime("%Y-%m-%d %H:%M UTC")
    make = getattr(run.module, "charts", None)
    charts = list(make(run.result)) if make is not None and run.result is not None else []
    inputs = inputs_of(run.module.Case, case, getattr(run, "model", None))
    ladders = [precision.charts_of(table) for table in precision.ladder_tables(run.report)]
    charts += [chart for pair in ladders for chart in pair]
    return Document(
        run.report, case.path.name, digest, stamp, inputs, charts,
        ladder_charts=[len(pair) for pair in ladders],
    )  # fmt: skip


def _parts(document: Document) -> list[tuple[Grid | None, list[tuple[int, int]]]]:
    """The document's body in order: (a grid, []) for a table, (None, figures) for the
    scene's charts as (figure number, index into ``charts``), after its tables; then
    (a grid, figures) for each work-precision table: under its heading, its charts
    just above it."""
    grids = _grids(document)
    ladders = document.ladder_charts
    main = grids[: len(grids) - len(ladders)]
    own = len(document.charts) - sum(ladders)
    parts: list[tuple[Grid | None, list[tuple[int, int]]]] = [(g, []) for g in main]
    if own:
        parts.append((None, [(i + 1, i) for i in range(own)]))
    start = own
    for grid, count in zip(grids[len(main) :], ladders, strict=True):
        parts.append((grid, [(i + 1, i) for i in range(start, start + count)]))
        start += count
    return parts


#: "As written" of a value the case file leaves to its default.
DEFAULT = "(default)"


def inputs_of(model: Any, case: Any, validated: Any = None) -> list[tuple[str, str, str, str]]:
    """Every value of the case file (lists item by item), as written and as the
    solver took it: a quantity string ("1500 kg") converted to the field's unit;
    then, from the ``validated`` case, each value the file left to its default."""
    converted = {c.loc: c for c in case.conversions}
    rows: list[tuple[str, str, str, str]] = []

    def walk(value: Any, loc: tuple[str | int, ...]) -> None:
        if isinstance(value, dict):
            for key, item in value.items():
                walk(item, (*loc, key))
        elif isinstance(value, list) and any(isinstance(v, dict | list) for v in value):
            for index, item in enumerate(value):
                walk(item, (*loc, index))
        elif isinstance(value, list):
            for index, item in enumerate(value):
                leaf(item, (*loc, index))
        else:
            leaf(value, loc)

    def leaf(value: Any, loc: tuple[str | int, ...]) -> None:
        written = _written(case, loc, value)
        conversion = converted.get(loc)
        if conversion is not None:  # a quantity string: its units as a person reads them
            written = pretty_unit(written)
        used = exact_text(conversion.value) if conversion is not None else written
        unit = conversion.unit if conversion is not None else unit_of(model, loc)
        rows.append((dotted(loc), written, used, unit))

    for key, value in case.data.items():
        if key not in NOT_INPUTS:
            walk(value, (key,))
    if validated is not None:
        rows += _defaults(model, case.data, validated.model_dump())
    return rows


def _defaults(model: Any, data: Any, values: Any) -> list[tuple[str, str, str, str]]:
    """(key, "(default)", value, unit) of each value in ``values`` (the validated
    case) that ``data`` (the file) does not have; sections the file leaves out and
    empty values (None) are not inputs."""
    rows: list[tuple[str, str, str, str]] = []

    def walk(value: Any, written: Any, loc: tuple[str | int, ...]) -> None:
        if isinstance(value, dict):
            if not isinstance(written, dict):
                return  # a section the file does not have (or holds as a quantity)
            for key, item in value.items():
                if loc or key not in NOT_INPUTS:
                    walk(item, written.get(key, _MISSING), (*loc, key))
        elif isinstance(value, list) and isinstance(written, list):
            for index, item in enumerate(value):
                if index < len(written):
                    walk(item, written[index], (*loc, index))
        elif written is _MISSING and value is not None and not isinstance(value, list | dict):
            rows.append((dotted(loc), DEFAULT, _toml_text(value), unit_of(model, loc)))

    walk(values, data, ())
    return rows


_MISSING = object()


def _written(case: Any, loc: tuple[str | int, ...], value: Any) -> str:
    """The value's text in the case file (``1e11``, ``10_000``) where it stands alone on
    its key's line; else the value as TOML writes it."""
    if isinstance(value, str) or not isinstance(loc[-1], str):
        return _toml_text(value)
    line = case.line_of(loc)
    lines = case.text.splitlines()
    if line is None or not 0 < line <= len(lines):
        return _toml_text(value)
    key, equals, rest = lines[line - 1].partition("=")
    text = rest.split("#")[0].strip()
    if equals and key.split(".")[-1].strip().strip("\"'") == loc[-1] and text:
        if text[0] not in "[{\"'":
            return text
    return _toml_text(value)


def _toml_text(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return value
    return repr(value) if isinstance(value, float) else str(value)


def _grids(document: Document) -> list[Grid]:
    """The report's grids, less its "Inputs written with units" (the inputs table of
    the document shows each of those values as written and as computed with)."""
    sections = document.report.sections
    if document.inputs:
        sections = [s for s in sections if getattr(s, "key", None) != UNITS_KEY]
    return grids(Report(document.report.problem, document.report.title, sections))


def _inputs_grid(document: Document) -> Grid:
    """The inputs as a grid: a column no input fills (units, where every input is a
    plain number) left out."""
    rows = [list(row) for row in document.inputs]
    header = ["key", "as written", "as computed with", "unit"]
    roles: list[Role] = ["label", "cell", "cell", "unit"]
    grid = Grid(document.inputs_title, header, rows, [False] * 4, roles, [], "table")
    return grid.shown()


def _headers(grid: Grid) -> list[str]:
    return grid.header if grid.header is not None else [QUANTITY_HEADERS[r] for r in grid.roles]


# ----------------------------------------------------------------------------- HTML

STYLE = """
@page { size: A4; margin: 16mm 14mm; }
body { font: 10.5pt/1.4 "DejaVu Sans", "Helvetica Neue", Arial, sans-serif; color: #111;
       max-width: 60em; margin: 1.5em auto; padding: 0 1em; }
h1 { font-size: 1.5em; margin: 0 0 .4em; }
h2 { font-size: 1.1em; margin: 1.4em 0 .4em; border-bottom: 1px solid #bbb; }
table { border-collapse: collapse; margin: .3em 0 .8em; font-variant-numeric: tabular-nums; }
th, td { border: 1px solid #ccc; padding: .2em .55em; vertical-align: top; }
th { background: #f0f0f0; text-align: left; font-weight: 600; }
td.r, th.r { text-align: right; white-space: nowrap; }
td.col-note { color: #555; font-size: .92em; }
td.col-label { white-space: pre-wrap; }
tr.reference td { font-weight: 600; background: #fafaf0; }
table.meta th { width: 8em; }
table.meta td code { font-size: .85em; word-break: break-all; }
.notes { margin: 1em 0; }
.note { border-left: 4px solid #3a7bd5; background: #eef4fc; padding: .45em .8em; margin: .4em 0; }
.note.warning { border-color: #d08a00; background: #fff5df; }
.note.noanswer { border-color: #c0392b; background: #fdecea; font-weight: 600; }
figure { margin: .6em 0 1.2em; break-inside: avoid; }
figure svg { max-width: 100%; height: auto; }
figcaption { font-size: .9em; color: #444; }
footer { margin-top: 2em; font-size: .85em; color: #666; border-top: 1px solid #ddd; }
@media print {
  body { max-width: none; margin: 0; padding: 0; }
  h2 { break-after: avoid; }
  table, tr, .note { break-inside: avoid; }
  table.methods, table.table { font-size: 8pt; }
}
"""


def to_html(document: Document, svgs: list[str] | None = None, missing: str = "") -> str:
    """One self-contained HTML page; ``svgs``: the charts drawn as SVG text, in
    order; ``missing``: why they are not there (no matplotlib)."""
    report, e = document.report, html.escape
    out = [
        "<!DOCTYPE html>",
        '<html lang="en">',
        '<head><meta charset="utf-8">',
        f"<title>{e(report.title)}</title>",
        f"<style>{STYLE}</style></head>",
        "<body>",
        f"<header><h1>{e(report.title)}</h1>",
        '<table class="meta">',
    ]
    for label, value in _meta(document):
        out.append(f"<tr><th>{e(label)}</th><td>{value}</td></tr>")
    out.append("</table></header>")
    notes = _notes(document)
    if notes:
        out.append('<section class="notes">')
        for level, text in notes:
            label = NOTE_LABELS[level]
            out.append(f'<div class="note {level}"><strong>{label}:</strong> {e(text)}</div>')
        out.append("</section>")
    if document.inputs:
        out.append(f'<section class="inputs"><h2>{e(document.inputs_title)}</h2>')
        inputs = _inputs_grid(document)
        out.append(_html_table(_headers(inputs), inputs.rows, inputs.right, [], "inputs"))
        out.append("</section>")
    for grid, figures in _parts(document):
        # the scene's charts; a table; a work-precision table, its charts above it
        kind, heading = ("charts", "Charts") if grid is None else (grid.kind, grid.title)
        out.append(f'<section class="{kind}"><h2>{e(heading)}</h2>')
        if figures and svgs is None:
            out.append(f'<div class="note warning"><strong>charts:</strong> {e(missing)}</div>')
        elif figures and svgs is not None:
            for number, index in figures:
                caption = f"<strong>Figure {number}.</strong> {e(document.charts[index].title)}"
                out.append(
                    f"<figure>{_inline_svg(svgs[index])}<figcaption>{caption}</figcaption></figure>"
                )
        if grid is None:
            out.append("</section>")
            continue
        classes = [
            f"col-{role}{' r' if right else ''}"
            for role, right in zip(grid.roles, grid.right, strict=True)
        ]
        out.append(
            _html_table(_headers(grid), grid.rows, grid.right, grid.strong, grid.kind, classes)
        )
        out.append("</section>")
    out.append(
        f"<footer>mdcalc {e(document.version)} · {e(report.problem)} · "
        f"{e(document.case_name)} · {e(document.date)}</footer>"
    )
    out.append("</body></html>")
    return "\n".join(out) + "\n"


def _meta(document: Document) -> list[tuple[str, str]]:
    e, report = html.escape, document.report
    return [
        ("problem", e(report.problem)),
        ("case file", e(document.case_name)),
        ("SHA-256", f"<code>{document.sha256}</code>"),
        ("mdcalc", e(document.version)),
        ("date", e(document.date)),
        ("status", "ok" if report.status == "ok" else "no answer"),
    ]


def _notes(document: Document) -> list[tuple[str, str]]:
    """The notes and warnings, and why there is no answer or a method was cut."""
    report = document.report
    ordered = sorted(report.notes, key=lambda n: n.level != "warning")  # warnings first
    notes: list[tuple[str, str]] = [(n.level, n.text) for n in ordered]  # cuts among them
    if report.status != "ok":
        notes.insert(0, ("noanswer", report.message or ""))
    return notes


#: How a note is introduced, by its level.
NOTE_LABELS = {"noanswer": "no answer", "warning": "warning", "info": "note"}


def _html_table(
    header: list[str],
    rows: list[list[str]],
    right: list[bool],
    strong: list[bool],
    kind: str,
    classes: list[str] | None = None,
) -> str:
    e = html.escape
    classes = classes or ["r" if r else "" for r in right]
    head = "".join(f'<th class="{c}">{e(h)}</th>' for h, c in zip(header, classes, strict=True))
    body = []
    for index, row in enumerate(rows):
        mark = ' class="reference"' if index < len(strong) and strong[index] else ""
        cells = "".join(f'<td class="{c}">{e(v)}</td>' for v, c in zip(row, classes, strict=True))
        body.append(f"<tr{mark}>{cells}</tr>")
    return (
        f'<table class="{kind}"><thead><tr>{head}</tr></thead>'
        f"<tbody>{''.join(body)}</tbody></table>"
    )


def _inline_svg(svg: str) -> str:
    """matplotlib's SVG file as an element of the page: no XML prolog or DOCTYPE."""
    start = svg.find("<svg")
    return svg[start:] if start >= 0 else svg


# ------------------------------------------------------------------------- Markdown


def to_markdown(document: Document, images: list[str] | None = None, missing: str = "") -> str:
    """GitHub-flavoured Markdown (pipe tables); ``images``: the charts' PNG file
    names beside the document, in order."""
    report = document.report
    out = [f"# {_md(report.title)}", ""]
    out += _md_table(["", ""], [[label, _plain(value)] for label, value in _meta(document)])
    for level, text in _notes(document):
        out += [f"> **{NOTE_LABELS[level].capitalize()}:** {_md(text)}", ""]
    if document.inputs:
        out += [f"## {_md(document.inputs_title)}", ""]
        inputs = _inputs_grid(document)
        out += _md_table(_headers(inputs), inputs.rows)
    for grid, figures in _parts(document):
        # (a work-precision table's charts stand under its heading, above it)
        out += [f"## {_md('Charts' if grid is None else grid.title)}", ""]
        if figures and images is None:
            out += [f"> **Charts:** {_md(missing)}", ""]
        elif figures and images is not None:
            for number, index in figures:
                title = document.charts[index].title
                out += [f"![{_md(title)}]({quote(images[index])})", ""]
                out += [f"*Figure {number}.* {_md(title)}", ""]
        if grid is not None:
            out += _md_table(_headers(grid), grid.rows, grid.right, grid.strong)
    out.append(
        f"*mdcalc {document.version} · {report.problem} · {_md(document.case_name)} · "
        f"{document.date}*"
    )
    return "\n".join(out) + "\n"


def _md(text: str) -> str:
    """Text safe in a Markdown table cell or line: pipes and markup escaped."""
    out = text.replace("\\", "\\\\")
    for char in "|*_`[]<>&~#":
        out = out.replace(char, "\\" + char)
    out = out.replace("\n", " ")
    stripped = out.lstrip(" ")  # an indented label keeps its indent (a sub-row)
    return "&nbsp;" * (len(out) - len(stripped)) + stripped


def _plain(value: str) -> str:
    """A meta value without its HTML (``<code>`` around the hash)."""
    return html.unescape(value.replace("<code>", "").replace("</code>", ""))


def _md_table(
    header: list[str],
    rows: list[list[str]],
    right: list[bool] | None = None,
    strong: list[bool] | None = None,
) -> list[str]:
    """A pipe table; the first cell of a ``strong`` row (the reference) in bold."""
    right = right or [False] * len(header)
    lines = ["| " + " | ".join(_md(h) for h in header) + " |"]
    lines.append("|" + "|".join("---:" if r else "---" for r in right) + "|")
    for index, row in enumerate(rows):
        cells = [_md(cell) for cell in row]
        if strong and strong[index] and cells and cells[0]:
            cells[0] = f"**{cells[0]}**"
        lines.append("| " + " | ".join(cells) + " |")
    return [*lines, ""]


# -------------------------------------------------------------------------- writing


def check_path(path: Path) -> str | None:
    """Why ``--report`` cannot write ``path`` (its suffix), or None."""
    if path.suffix.lower() not in FORMATS:
        return f"--report: use a file ending {' or '.join(FORMATS)}"
    return None


def is_chart_file(report: Path, other: Path) -> bool:
    """Is ``other`` a name a Markdown report at ``report`` gives its chart PNGs?"""
    import re

    pattern = re.escape(report.stem) + r"-[0-9]+\.png"
    return other.parent.resolve() == report.parent.resolve() and bool(
        re.fullmatch(pattern, other.name)
    )


def chart_files(path: Path, count: int) -> list[Path]:
    """The PNG files of a Markdown report's charts: beside it, named after it."""
    return [path.with_name(f"{path.stem}-{index}.png") for index in range(1, count + 1)]


def write(run: Any, path: Path, force: bool) -> list[Path]:
    """Write the report of ``run`` to ``path``: :func:`write_document`."""
    return write_document(document_of(run), path, force)


def write_document(document: Document, path: Path, force: bool) -> list[Path]:
    """Write ``document`` to ``path`` (.html or .md; for Markdown its chart PNGs
    beside it), atomically; an existing file only with ``force``. Returns the files
    written."""
    from mdcalc.input.files import write_atomic
    from mdcalc.output.plot import chart_images, matplotlib_missing

    missing = matplotlib_missing() if document.charts else None
    why = (missing or "").replace("--plot needs", "the charts need")
    markdown = path.suffix.lower() == ".md"
    pictures = chart_files(path, len(document.charts)) if markdown and not missing else []
    if not force:
        for picture in pictures:
            if picture.exists():
                raise InputError(
                    picture, [Problem("--report: file exists; use --force to overwrite it")]
                )
    if markdown:
        images = chart_images(document.charts, "png") if pictures else []
        for picture, image in zip(pictures, images, strict=True):
            write_atomic(picture, image, replace=True, option="--report: ")
        names = [p.name for p in pictures] if not missing else None
        text = to_markdown(document, names, why)
    else:
        text = html_of(document)
    write_atomic(path, text, replace=force, option="--report: ")
    return [*pictures, path]


def html_of(document: Document) -> str:
    """The HTML page of ``document`` with its charts drawn (when matplotlib is there)."""
    from mdcalc.output.plot import chart_images, matplotlib_missing

    missing = matplotlib_missing() if document.charts else None
    if missing:
        return to_html(document, None, missing.replace("--plot needs", "the charts need"))
    svgs = [image.decode("utf-8") for image in chart_images(document.charts, "svg")]
    return to_html(document, svgs)


def index_html(rows: list[tuple[str, str, str, str, str, str]]) -> str:
    """The page of a batch's reports (``run --report-dir``): one row per case file,
    (case, problem, title, status, report file name or "", why it has no answer or
    no report or "")."""
    e = html.escape
    body = []
    for case, problem, title, status, link, why in rows:
        name = f'<a href="{e(quote(link))}">{e(case)}</a>' if link else e(case)
        body.append(
            f'<tr class="{e(status)}"><td>{name}</td><td>{e(problem)}</td>'
            f'<td>{e(title)}</td><td>{e(status)}</td><td class="col-note">{e(why)}</td></tr>'
        )
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head><meta charset="utf-8">'
        f"<title>mdcalc reports</title><style>{STYLE}</style></head>\n<body>\n"
        f"<h1>mdcalc reports</h1>\n<p>{len(rows)} case files · mdcalc {__version__}</p>\n"
        '<table class="index"><thead><tr><th>case file</th><th>problem</th><th>title</th>'
        f"<th>status</th><th>why</th></tr></thead><tbody>{''.join(body)}</tbody></table>\n"
        "</body></html>\n"
    )
