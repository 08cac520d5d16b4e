"""Calculation reports (``--report FILE.html|.md``, issue 23): the same content as the
JSON, charts inline (SVG) or beside (PNG), nothing loaded from a network, the file
rules of --save; and no renderer prints a column that is empty in every row."""

from __future__ import annotations

import hashlib
import json
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest

from mdcalc.output.report import Report, format_value, grids, pretty_unit
from mdcalc.output.text import render_rich
from tests.conftest import CASES

CRANE = CASES / "hoist" / "crane.toml"  # two charts
LECTURE = CASES / "braking" / "lecture.toml"  # a warning note, Methods tables
UNITS = CASES / "coupling" / "example_8_1_units.toml"  # quantity strings
NO_START = CASES / "hoist" / "cannot_start.toml"  # no answer


class Page(HTMLParser):
    """The tables (cells as text), SVG elements, resource links and text of a page."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.tables: list[list[list[str]]] = []
        self.svgs = 0
        self.links: list[str] = []
        self.tags: list[str] = []
        self.text: list[str] = []
        self._cell: list[str] | None = None

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags.append(tag)
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self.tables[-1].append([])
        elif tag in ("td", "th"):
            self._cell = []
        elif tag == "svg":
            self.svgs += 1
        for name, value in attrs:
            if name in ("src", "href", "xlink:href", "action", "data") and value:
                self.links.append(value)

    def handle_endtag(self, tag: str) -> None:
        if tag in ("td", "th") and self._cell is not None:
            self.tables[-1][-1].append("".join(self._cell).strip())
            self._cell = None

    def handle_data(self, data: str) -> None:
        self.text.append(data)
        if self._cell is not None:
            self._cell.append(data)


def page(text: str) -> Page:
    parsed = Page()
    parsed.feed(text)
    parsed.close()
    return parsed


def markdown_tables(text: str) -> list[list[list[str]]]:
    """Every pipe table as a Markdown parser reads it (markdown-it, GFM tables)."""
    from markdown_it import MarkdownIt

    tokens = MarkdownIt("commonmark").enable("table").parse(text)
    tables: list[list[list[str]]] = []
    for token in tokens:
        if token.type == "table_open":
            tables.append([])
        elif token.type == "tr_open":
            tables[-1].append([])
        elif token.type == "inline" and tables and tables[-1] and _in_cell(tokens, token):
            tables[-1][-1].append(_inline_text(token))
    return tables


def _in_cell(tokens, token) -> bool:
    index = tokens.index(token)
    return index > 0 and tokens[index - 1].type in ("th_open", "td_open")


def _inline_text(token) -> str:
    return "".join(child.content for child in token.children or [] if child.type == "text")


def _report(cli, tmp_path: Path, case: Path, suffix: str, *more: str) -> tuple[str, dict]:
    out = tmp_path / f"report{suffix}"
    done = cli(_problem(case), case, "--report", out)
    assert done.exit_code in (0, 3), done.stderr
    assert f"wrote {out}" in done.stderr
    document = json.loads(cli(_problem(case), case, "--json", *more).stdout)
    return out.read_text(encoding="utf-8"), document


def _problem(case: Path) -> str:
    import tomllib

    return tomllib.loads(case.read_text(encoding="utf-8"))["problem"]


def _shown(value) -> str:
    return format_value(value)


@pytest.mark.parametrize("case", [CRANE, LECTURE, UNITS, NO_START], ids=lambda p: p.name)
def test_the_html_report_holds_what_the_json_holds(cli, tmp_path, case):
    text, document = _report(cli, tmp_path, case, ".html")
    html = page(text)
    cells = {cell for table in html.tables for row in table for cell in row}
    words = " ".join(html.text)
    assert document["title"] in words
    assert hashlib.sha256(case.read_bytes()).hexdigest() in cells
    for key, result in document["results"].items():
        assert result["label"] in cells, key
        assert _shown(result["value"]) in cells, key
        if result["unit"]:  # the JSON's ASCII form, shown as a person reads it
            assert pretty_unit(result["unit"]) in cells, key
    for section in document["sections"]:
        if section.get("key") == "units":  # its rows are in the inputs table (one table)
            assert section["title"] not in words
            continue
        assert section["title"] in words
        if section["kind"] == "methods":
            for row in section["rows"]:
                assert row["method"] in cells
                for value in row["values"].values():
                    assert _shown(value) in cells
    for note in document["notes"]:
        assert note["text"] in words
    if document["status"] != "ok":
        assert "no answer:" in words and document["message"] in words
    assert "<script" not in text and "@import" not in text


def test_html_charts_are_inline_svg_and_nothing_comes_from_a_network(cli, tmp_path):
    from mdcalc.input.casefile import read_case
    from mdcalc.problems import PROBLEMS
    from mdcalc.runs.runner import solve_text

    text, _ = _report(cli, tmp_path, CRANE, ".html")
    html = page(text)
    run = solve_text(read_case(CRANE))
    charts = PROBLEMS["hoist"].load().charts(run.result)
    assert len(charts) == 2
    assert html.svgs == len(charts)
    # Links only inside the page (an SVG's own #ids); no url() to fetch.
    assert all(link.startswith("#") for link in html.links), html.links[:5]
    assert not re.search(r"url\(\s*['\"]?(https?:|//)", text)
    # No URL at all but the SVG namespaces (names, never fetched).
    assert "http" not in re.sub(r'xmlns(:\w+)?="[^"]*"', "", text)
    assert not re.search(r"<(link|img|iframe|object|embed)\b", text)
    assert "@page { size: A4" in text  # prints on A4


def test_markdown_tables_read_back_with_the_same_cells(cli, tmp_path):
    from mdcalc.runs.runner import run_case

    text, _ = _report(cli, tmp_path, LECTURE, ".md")
    tables = markdown_tables(text)
    report = run_case(LECTURE)
    expected = grids(report)
    # The meta table, the inputs, then one table per section in order.
    assert len(tables) == 2 + len(expected)
    assert tables[0][3] == ["SHA-256", hashlib.sha256(LECTURE.read_bytes()).hexdigest()]
    for table, grid in zip(tables[2:], expected, strict=True):
        rows = table[1:]
        assert len(rows) == len(grid.rows), grid.title
        timed = grid.roles.index("time") if "time" in grid.roles else None
        rows = [[cell.replace("\u00a0", " ") for cell in row] for row in rows]  # indents
        for got, want in zip(rows, grid.rows, strict=True):
            if timed is not None:  # run times differ between two runs
                got, want = got[:timed] + got[timed + 1 :], want[:timed] + want[timed + 1 :]
            assert got == want, grid.title


def test_markdown_charts_are_pngs_beside_it(cli, tmp_path):
    text, _ = _report(cli, tmp_path, CRANE, ".md")
    names = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert names == ["report-1.png", "report-2.png"]
    assert not re.search(r"\]\(\s*(https?:|//)|<(img|script|link)\b", text)  # nothing remote
    for name in names:
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_inputs_as_written_and_as_computed_with(cli, tmp_path):
    text, _ = _report(cli, tmp_path, UNITS, ".md")
    inputs = markdown_tables(text)[1]
    assert inputs[0] == ["key", "as written", "as computed with", "unit"]
    rows = {row[0]: row for row in inputs[1:]}
    # As the case file writes them, and in the field's unit (4000 g·m² is 4 kg·m²).
    assert rows["coupling.driven_inertia"][1:] == ["4000 g·m²", "4", "kg·m²"]
    assert rows["coupling.absorption"][1:] == ["0.63", "0.63", ""]
    # 52.5 N*m/deg in N·m/rad: 52.5 · 180/π (the case file's stiffness).
    stiffness = [r for k, r in rows.items() if "deg" in r[1]]
    assert [row[0] for row in stiffness] == ["coupling.stiffness"]
    for row in stiffness:
        value = float(row[1].split()[0])
        # 12 significant digits: the conversion checks by eye (issue 33.2)
        assert float(row[2]) == pytest.approx(value * 180 / 3.141592653589793, rel=1e-11)


@pytest.mark.parametrize(
    ("name", "problem"),
    [
        ("report.pdf", "use a file ending .html or .md"),
        ("", "is a folder; give a file name"),
    ],
)
def test_bad_report_paths_are_exit_2_before_solving(cli, tmp_path, name, problem):
    target = tmp_path / name if name else tmp_path
    done = cli("braking", LECTURE, "--report", target)
    assert done.exit_code == 2
    assert problem in done.stderr and "Traceback" not in done.stderr


def test_an_existing_report_needs_force_and_so_do_its_pictures(cli, tmp_path):
    out = tmp_path / "report.html"
    out.write_text("old")
    done = cli("braking", LECTURE, "--report", out)
    assert done.exit_code == 2 and "--force" in done.stderr
    assert out.read_text() == "old"
    assert cli("braking", LECTURE, "--report", out, "--force").exit_code == 0
    assert out.read_text().startswith("<!DOCTYPE html>")
    (tmp_path / "crane-2.png").write_bytes(b"mine")
    done = cli("hoist", CRANE, "--report", tmp_path / "crane.md")
    assert done.exit_code == 2 and "crane-2.png" in done.stderr
    assert (tmp_path / "crane-2.png").read_bytes() == b"mine"
    assert not (tmp_path / "crane.md").exists()


# ------------------------------------------------------- no column empty in every row


def _rich_columns(text: str) -> list[list[str]]:
    """The columns of every boxed table rich printed, as the text of their cells."""
    columns: list[list[str]] = []
    table: list[list[str]] = []
    for line in [*text.splitlines(), ""]:
        if line.startswith(("┃", "│")):
            table.append([cell.strip() for cell in line.rstrip()[1:-1].split(line[0])])
        elif line.startswith(("┏", "┡", "└")):
            continue  # the box's rules
        elif table:
            width = len(table[0])
            columns += [[row[i] for row in table if len(row) == width] for i in range(width)]
            table = []
    return columns


def assert_no_empty_column(report: Report) -> None:
    """No renderer shows a column that no row has a value in (rich, HTML, Markdown)."""
    import io

    from rich.console import Console

    from mdcalc.output.document import Document, to_html, to_markdown

    for grid in grids(report):
        for index in range(len(grid.roles)):
            assert any(row[index] not in ("", "—") for row in grid.rows), grid.title
    buffer = io.StringIO()
    render_rich(report, Console(file=buffer, width=400, highlight=False))
    for column in _rich_columns(buffer.getvalue()):
        assert any(cell not in ("", "—") for cell in column[1:]), column[0]
    document = Document(report, "case.toml", "0" * 64, "today", [])
    for table in page(to_html(document)).tables[1:]:
        for index in range(len(table[0])):
            assert any(row[index] not in ("", "—") for row in table[1:]), table[0][index]
    for table in markdown_tables(to_markdown(document))[1:]:
        for index in range(len(table[0])):
            assert any(row[index] not in ("", "—") for row in table[1:]), table[0][index]


def test_a_methods_note_no_method_has_is_not_a_column():
    from mdcalc.output.report import MethodQuantity, MethodRow, MethodsTable

    table = MethodsTable(
        "Methods",
        "m",
        [MethodQuantity("x", "x", "m")],
        [MethodRow("exact", {"x": 1.0}, {}, 1e-6, True), MethodRow("rough", {"x": 1.1}, {}, 2e-6)],
    )
    report = Report("braking", "t", sections=[table])
    (grid,) = grids(report)
    assert grid.header == ["method", "x (m)", "rel. error", "run time"]
    assert_no_empty_column(report)
    table.rows[1].note = "a note"
    assert grids(report)[0].header == ["method", "x (m)", "rel. error", "run time", "note"]


def test_run_writes_a_report_per_file_and_an_index(cli, tmp_path):
    cases = tmp_path / "cases"
    cases.mkdir()
    for case in (LECTURE, NO_START):
        (cases / case.name).write_bytes(case.read_bytes())
    (cases / "broken.toml").write_text('problem = "braking"\n[vehicle\n')
    out = tmp_path / "reports"
    done = cli("run", cases, "--report-dir", out, "--jobs", "1")
    assert done.exit_code == 2, done.stderr  # the worst file: bad input
    index = page((out / "index.html").read_text(encoding="utf-8"))
    rows = {row[0]: row for row in index.tables[0][1:]}
    assert [
        rows[str(cases / n)][3] for n in ("broken.toml", "cannot_start.toml", "lecture.toml")
    ] == [
        "input-error",
        "no-answer",
        "ok",
    ]
    assert sorted(index.links) == ["cannot_start.html", "lecture.html"]
    lecture = page((out / "lecture.html").read_text(encoding="utf-8"))
    assert hashlib.sha256(LECTURE.read_bytes()).hexdigest() in {
        cell for table in lecture.tables for row in table for cell in row
    }
    assert "no answer" in " ".join(page((out / "cannot_start.html").read_text()).text)


def test_a_methods_error_column_goes_with_its_value_column():
    from mdcalc.output.report import MethodQuantity, MethodRow, MethodsTable

    table = MethodsTable(
        "M",
        "m",
        [MethodQuantity("x", "x", "m"), MethodQuantity("y", "y", "s")],
        [
            MethodRow("exact", {"x": 1.0, "y": None}, {}, 1e-6, True),
            MethodRow("rough", {"x": 1.1}, {"x": 0.1}, 2e-6),
        ],
    )
    (grid,) = grids(Report("braking", "t", sections=[table]))
    assert grid.header == ["method", "x (m)", "rel. error", "run time"]


def test_markdown_picture_links_survive_spaces_and_parentheses(cli, tmp_path):
    from markdown_it import MarkdownIt

    out = tmp_path / "my report (v2).md"
    assert cli("hoist", CRANE, "--report", out).exit_code == 0
    tokens = MarkdownIt("commonmark").parse(out.read_text(encoding="utf-8"))
    images = [
        child.attrs["src"]
        for token in tokens
        if token.type == "inline"
        for child in token.children or []
        if child.type == "image"
    ]
    from urllib.parse import unquote

    assert [unquote(str(src)) for src in images] == ["my report (v2)-1.png", "my report (v2)-2.png"]
    assert all((tmp_path / unquote(str(src))).exists() for src in images)


def test_chart_pictures_never_overwrite_the_case_or_the_plot(cli, tmp_path):
    case = tmp_path / "r-1.png"
    case.write_bytes(CRANE.read_bytes())
    done = cli("hoist", case, "--report", tmp_path / "r.md", "--force")
    assert done.exit_code == 2 and "would overwrite the case file" in done.stderr
    assert case.read_bytes() == CRANE.read_bytes()
    other = tmp_path / "other"
    other.mkdir()
    done = cli("hoist", CRANE, "--plot", other / "r-1.png", "--report", other / "r.md")
    assert done.exit_code == 2 and "would overwrite the --plot picture" in done.stderr
    assert list(other.iterdir()) == []
    (tmp_path / "q-1.png").write_bytes(b"mine")
    done = cli("hoist", CRANE, "--report", tmp_path / "q.md")
    assert done.exit_code == 2 and "q-1.png" in done.stderr and "--force" in done.stderr
    assert (tmp_path / "q-1.png").read_bytes() == b"mine"


def test_notes_appear_once_and_markdown_text_stays_literal():
    from mdcalc.output.document import Document, to_markdown
    from mdcalc.output.report import Note

    report = Report("braking", "A &amp; ~~b~~ <c> #", notes=[Note("warning", "time budget: ode")])
    report.cut = ["ode"]
    text = to_markdown(Document(report, "c.toml", "0" * 64, "today", []))
    assert text.count("time budget: ode") == 1
    from markdown_it import MarkdownIt

    tokens = MarkdownIt("commonmark").parse(text)
    heading = next(t for i, t in enumerate(tokens) if i and tokens[i - 1].type == "heading_open")
    assert heading.content and _inline_text(heading) == "A &amp; ~~b~~ <c> #"


def test_the_index_cannot_take_a_cases_place_and_links_are_encoded(cli, tmp_path):
    cases = tmp_path / "cases"
    cases.mkdir()
    (cases / "index.toml").write_bytes(LECTURE.read_bytes())
    done = cli("run", cases, "--report-dir", tmp_path / "out")
    assert done.exit_code == 2 and "index page" in done.stderr
    (cases / "index.toml").rename(cases / "a#1 50%.toml")
    assert cli("run", cases, "--report-dir", tmp_path / "out").exit_code == 0
    index = page((tmp_path / "out" / "index.html").read_text(encoding="utf-8"))
    assert index.links == ["a%231%2050%25.html"]
    assert (tmp_path / "out" / "a#1 50%.html").exists()


def test_values_left_to_their_defaults_are_listed_as_such(cli, tmp_path):
    text, _ = _report(cli, tmp_path, LECTURE, ".md")
    rows = {row[0]: row[1:] for row in markdown_tables(text)[1][1:]}
    assert rows["vehicle.mass"] == ["1500.0", "1500.0", "kg"]  # written
    assert rows["gravity"] == ["(default)", "9.80665", "m/s²"]  # standard gravity
    assert "driver.reaction_time" not in rows  # a section the case leaves out
