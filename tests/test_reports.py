"""Issue 33: every shipped case and study files as a report without retouching.

Each case is solved once, in this process; its HTML and Markdown reports are written
and read back: every table has no column that is empty in every row, every chart is
there (a figure per chart in the HTML, a picture link per chart in the Markdown), and
no unit a person reads is spelt with ``*`` or ``^``. The charts themselves are drawn
and checked for every case by tests/test_plots.py, which files those cases too
(:func:`assert_files_as_a_report`); here the rest, and the studies, whose charts are
drawn (one figure, as ``study --plot`` writes it) and checked the same way.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.conftest import CASES
from tests.test_document import page
from tests.test_plots import CASE_FILES

FILES = sorted(CASES.rglob("*.toml"))
#: A unit as a person reads it: no ASCII product or power.
ASCII_UNIT = re.compile(r"[*^]")
#: A header "label (unit)" of a table column.
HEADER_UNIT = re.compile(r"\(([^()]*)\)$")
#: Columns whose cells are units or end in one (a study's distributions and limits,
#: the inputs as written: quantity strings).
UNIT_COLUMNS = ("unit", "distribution", "exceeded when")
#: A quantity string (a number, then its unit), not a formula of a case's parameters.
QUANTITY = re.compile(r"^[-+]?[\d.]+(?:e[-+]?\d+)?\s*[^\W\d_][^+(]*$")
SVG = '<svg xmlns="http://www.w3.org/2000/svg" width="1" height="1"></svg>'


def _document(path: Path):
    """The filed document of a case or study file (every shipped file is valid: an
    input error fails the test), and the study's result (None for a case)."""
    from mdcalc.input.casefile import read_case
    from mdcalc.output.document import document_of
    from mdcalc.runs.cluster import PoolMapper
    from mdcalc.runs.runner import solve_text
    from mdcalc.runs.study import run as run_study
    from mdcalc.runs.study.output import study_document

    case = read_case(path)
    if "study" in case.data:
        result = run_study(case, PoolMapper(1))
        return study_document(result), result
    return document_of(solve_text(case)), None


def _check_tables(tables: list[list[list[str]]], where: str) -> None:
    for table in tables:
        header, *rows = table
        if not rows or not header[0] or header == ["", ""]:  # the meta table
            continue
        for column, name in enumerate(header):
            cells = [row[column] for row in rows if column < len(row)]
            assert any(c not in ("", "—") for c in cells), f"{where}: column {name!r} empty"
            unit = HEADER_UNIT.search(name)
            if unit:
                assert not ASCII_UNIT.search(unit.group(1)), f"{where}: header {name!r}"
            if name in UNIT_COLUMNS:  # cells that are, or end in, units
                spelt = [c for c in cells if ASCII_UNIT.search(c)]
                assert not spelt, f"{where}: units {spelt}"
            if name == "as written":  # quantity strings, their units as a person reads them
                spelt = [c for c in cells if QUANTITY.match(c) and ASCII_UNIT.search(c)]
                assert not spelt, f"{where}: quantities {spelt}"


def _markdown_tables(text: str) -> list[list[list[str]]]:
    tables: list[list[list[str]]] = []
    rows: list[list[str]] = []
    for line in [*text.splitlines(), ""]:
        if line.startswith("|"):
            cells = re.split(r"(?<!\\)\|", line.strip())[1:-1]
            if not all(re.fullmatch(r"-+:?", c.strip()) for c in cells):
                rows.append([c.strip().replace("\\", "").replace("&nbsp;", "") for c in cells])
        elif rows:
            tables.append(rows)
            rows = []
    return tables


def assert_files_as_a_report(document, where: str) -> None:
    """``document``'s HTML and Markdown, read back: no empty column, a figure and a
    picture link per chart, the units a person reads."""
    from mdcalc.output.document import to_html, to_markdown

    charts = document.charts
    html = page(to_html(document, [SVG] * len(charts)))
    _check_tables(html.tables, f"{where} (HTML)")
    assert html.tags.count("figure") == len(charts) == html.svgs
    assert not any(t.startswith("Inputs written with units") for t in html.text)  # once
    names = [f"chart-{k}.png" for k in range(1, len(charts) + 1)]
    markdown = to_markdown(document, names)
    _check_tables(_markdown_tables(markdown), f"{where} (Markdown)")
    assert re.findall(r"!\[[^\]]*\]\(([^)]+)\)", markdown) == names
    _check_json_units(document.report, where)


def _check_json_units(report, where: str) -> None:
    """Every unit of the report, in the JSON's ASCII form, reads back with pint as a
    unit (``N*m/rad^n``, a power law's stiffness, is the one documented exception)."""
    from mdcalc.input.quantities import registry
    from mdcalc.output.report import (
        NO_PINT_UNIT,
        MethodsTable,
        Quantities,
        Table,
        ascii_unit,
    )

    units = set()
    for section in report.sections:
        if isinstance(section, Quantities):
            units |= {q.unit for q in section.items}
        elif isinstance(section, Table):
            units |= {c.unit for c in section.columns}
        elif isinstance(section, MethodsTable):
            units |= {q.unit for q in section.quantities}
    ureg = registry()
    for unit in sorted(units):
        text = ascii_unit(unit)
        if text and text != NO_PINT_UNIT:
            ureg.Unit(text)  # raises on a unit pint cannot read
            assert not re.search(r"[^\x20-\x7e]", text), f"{where}: {text!r} is not ASCII"


#: The case files tests/test_plots.py solves and files (those with charts) are left
#: to it: each case solved once in the suite.
PLOTTED = {path for _, path in CASE_FILES}
REST = [path for path in FILES if path not in PLOTTED]


@pytest.mark.parametrize("path", REST, ids=[str(p.relative_to(CASES)) for p in REST])
def test_every_case_and_study_files_as_html_and_markdown(path):
    document, study = _document(path)
    assert_files_as_a_report(document, path.name)
    if study is not None and document.charts:
        from mdcalc.output.plot import figure_of
        from mdcalc.runs.study.output import charts as study_charts
        from tests.test_plots import assert_reads_at_a_glance

        figure = figure_of(study_charts(study), title=document.report.title)
        assert_reads_at_a_glance(figure)


def test_the_plotted_cases_are_filed_by_the_plot_test():
    assert PLOTTED and PLOTTED <= set(FILES) and len(REST) + len(PLOTTED) == len(FILES)


@pytest.mark.parametrize(
    ("seconds", "shown"),
    [
        (9.996e-4, "1 ms"),  # rounds up across the unit: not "1e+03 µs"
        (0.9996, "1 s"),
        (1.234e-5, "12.3 µs"),
        (0.0421, "42.1 ms"),
        (12.34, "12.3 s"),
        (1234.0, "1230 s"),  # three digits, in whole seconds
        (None, "—"),
    ],
)
def test_run_times_read_in_their_unit(seconds, shown):
    from mdcalc.output.report import format_seconds

    assert format_seconds(seconds) == shown
