"""A report as text: rich on a terminal, and the very same text without rich on a
pipe (:func:`render_plain`)."""

from __future__ import annotations

from typing import Any

from mdcalc.output.report import Grid, Report, grids


def grid_rich(grid: Grid) -> Any:
    """A rich Table of ``grid``: a heavy box with a header, or none for quantities."""
    from rich.table import Table as RichTable

    # (render_rich prints the title on a line of its own: print_titled)
    if grid.header is None:
        table = RichTable(title=grid.title or None, show_header=False, box=None)
    else:
        table = RichTable(title=grid.title or None)
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


def print_titled(console: Any, table: Any) -> None:
    """A rich Table with its title on a line of its own above it: a table's own title
    wraps to the table's width ("Lecture method (7.48): constant force, no / resistance")."""
    from rich.text import Text

    title, table.title = table.title, None
    if title:
        console.print(Text(str(title), style="italic"), soft_wrap=True)
    console.print(table)


def render_rich(report: Report, console: Any) -> None:
    """Print the report on a rich Console (colour only on a terminal)."""
    from rich.text import Text

    console.print(Text(report.title, style="bold underline"))
    if report.case:
        console.print(Text(f"{report.problem} · {report.case}", style="dim"))
    for grid in grids(report):
        console.print()
        print_titled(console, grid_rich(grid))
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
        lines = _plain_table("", grid.header, grid.rows, grid.right, boxed, width)
        if lines is None or not (_narrow(grid.title) and _literal(grid.title)):
            return None
        out.append("")
        if grid.title:  # on its own line, as render_rich prints it
            out.append(grid.title)
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
