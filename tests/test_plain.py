"""The plain-text report (a pipe, a file) is rich's very text, made without rich.

render_plain either gives exactly what render_rich prints on a colourless console of
the same width, or None (and the caller uses rich). Both halves are checked: equal
text over every shipped case and over made-up reports, and None where rich would do
something render_plain does not (narrow a wide table, read markup, fold a long word).
"""

from __future__ import annotations

import io
import json
import sys
from pathlib import Path

import pytest
from rich.cells import get_character_cell_size
from rich.console import Console

from mdcalc.input.casefile import read_case
from mdcalc.output.report import (
    Column,
    MethodQuantity,
    MethodRow,
    MethodsTable,
    Note,
    Quantities,
    Quantity,
    Report,
    Table,
    grids,
)
from mdcalc.output.text import _OTHER, render_plain, render_rich
from mdcalc.runs.runner import solve_text
from tests.conftest import CASES, run_script
from tests.test_document import assert_no_empty_column

WIDTH = 140


def rich_text(report: Report, width: int = WIDTH) -> str:
    buffer = io.StringIO()
    render_rich(report, Console(file=buffer, width=width, highlight=False))
    return buffer.getvalue()


SHIPPED = sorted(
    path
    for path in CASES.rglob("*.toml")
    if path.parent.name != "studies" and "[study]" not in path.read_text(encoding="utf-8")
)


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: str(p.relative_to(CASES)))
def test_shipped_case_plain_text_is_riches_text(path: Path):
    report = solve_text(read_case(path)).report
    plain = render_plain(report, WIDTH)
    text = rich_text(report)
    if plain is not None:
        assert plain == text
    assert_no_empty_column(report)  # issue 23: a report shows only what its scene needs
    lines = text.splitlines()
    for grid in grids(report):  # issue 33: a section's title is one line, never wrapped
        assert not grid.title or grid.title in lines, grid.title
    for unit in _units(report):  # issue 33: a unit as a person reads it (kg·m², m/s²)
        assert "*" not in unit and "^" not in unit, unit


def _units(report: Report) -> list[str]:
    """Every unit a report shows: of its quantities, table columns, Methods quantities."""
    out = []
    for section in report.sections:
        out += [q.unit for q in getattr(section, "items", [])]
        out += [c.unit for c in getattr(section, "columns", [])]
        out += [q.unit for q in getattr(section, "quantities", [])]
    return out


def test_most_shipped_cases_take_the_plain_path():
    plain = sum(
        render_plain(solve_text(read_case(p)).report, WIDTH) is not None for p in SHIPPED[::3]
    )
    assert plain >= len(SHIPPED[::3]) // 2


def test_every_character_taken_as_narrow_is_one_cell_in_rich():
    narrow = [chr(c) for c in range(0x20, 0x3000) if _OTHER.search(chr(c)) is None]
    assert len(narrow) > 1500
    assert all(get_character_cell_size(c) == 1 for c in narrow)


def report_of(*sections, notes=(), **kw) -> Report:
    return Report(
        problem="braking",
        title=kw.pop("title", "A made-up report"),
        sections=list(sections),
        notes=list(notes),
        case="made/up.toml",
        **kw,
    )


QUANTITIES = Quantities(
    "Scene",
    [
        Quantity("v0", "Initial speed V0", 27.8, "m/s"),
        Quantity("phi", "Adhesion coefficient φ", 0.7, "", "dry asphalt"),
        Quantity("lock", "  indented label", True),
        Quantity("r12", "R₁₂ = [M₁(J₂ + J₃) + W·J₁]/ΣJ", 1.25e-7, "N·m"),
    ],
)
TABLE = Table(
    "Road surfaces",
    "roads",
    [Column("surface"), Column("φ low"), Column("distance", "m")],
    [["dry", 0.7, 56.291], ["ice", 0.01, 3940.4], ["████··", 0.5, None]],
)
METHODS = MethodsTable(
    "Methods: stopping distance",
    "methods",
    [MethodQuantity("distance", "distance", "m")],
    [
        MethodRow("lecture (7.48)", {"distance": 35.257}, {"distance": 0.37}, 3.5e-7),
        MethodRow("exact", {"distance": 56.291}, {"distance": None}, 1e-5, reference=True),
        MethodRow("ode", {"distance": None}, {"distance": None}, None, note="not applicable"),
    ],
)
LONG = (
    "the brakes demand 10.96 m/s² = 1.12·g, more than adhesion allows on this road "
    "(φ·g = 6.865 m/s²): the wheels lock and the car slides; the braking distance is at "
    "least 56.3 m, not the 35.3 m in 2.54 s of (7.48); no road surface gives more than φ = 0.9"
)


@pytest.mark.parametrize(
    "report",
    [
        report_of(QUANTITIES, TABLE, METHODS),
        report_of(QUANTITIES, notes=[Note("warning", LONG), Note("info", "[road] is fine")]),
        report_of(TABLE, title="A title far longer than the table it stands over, " * 4),
        report_of(QUANTITIES, status="no-answer", message=LONG),
        report_of(Quantities("A title longer than its narrow table", [Quantity("a", "a", 1)])),
        report_of(METHODS, notes=[Note("info", "x" * 60 + " " + "y" * 79)]),
    ],
    ids=["all sections", "notes", "long title", "no answer", "title wraps", "exact fit"],
)
def test_made_up_report_plain_is_riches_text(report: Report):
    plain = render_plain(report, WIDTH)
    assert plain is not None
    assert plain == rich_text(report)


def test_narrow_console_wraps_like_rich():
    report = report_of(QUANTITIES, notes=[Note("warning", LONG)])
    assert render_plain(report, 80) == rich_text(report, 80)


@pytest.mark.parametrize(
    "report",
    [
        # wider than the console: rich narrows the columns and wraps the cells
        report_of(Table("wide", "w", [Column("a"), Column("b")], [["x" * 80, "y" * 70]])),
        # markup rich would read as a style
        report_of(Quantities("Scene", [Quantity("a", "[bold]mass[/bold]", 1.0)])),
        # an emoji code rich would replace
        report_of(Quantities("Scene", [Quantity("a", "speed :warning:", 1.0)])),
        # a wide character (two cells)
        report_of(Quantities("Scene", [Quantity("a", "质量", 1.0)])),
        # a word longer than a line: rich folds it
        report_of(notes=[Note("info", "z" * 200)]),
        # a control character
        report_of(notes=[Note("info", "two\nlines")]),
        # blanks a right-justified cell would lose
        report_of(Table("t", "t", [Column("n")], [[1.0], [" 2"]])),
    ],
    ids=["too wide", "markup", "emoji", "wide character", "long word", "newline", "blank"],
)
def test_what_only_rich_lays_out_is_left_to_rich(report: Report):
    assert render_plain(report, WIDTH) is None
    rich_text(report)  # and rich takes it


def test_piped_command_prints_riches_text_without_importing_rich():
    lecture = CASES / "braking" / "lecture.toml"
    done = run_script("braking", lecture)
    assert done.returncode == 0
    # The same text but for the measured run times (and the widths they set).
    expected = rich_text(solve_text(read_case(lecture)).report).splitlines()
    got = done.stdout.splitlines()
    assert len(got) == len(expected)
    timed = [i for i, line in enumerate(expected) if " µs " in line or " ms " in line]
    assert 0 < len(timed) <= 4
    assert [g for i, g in enumerate(got) if i not in timed] == [
        e for i, e in enumerate(expected) if i not in timed
    ]
    probe = (
        "import sys\n"
        f"sys.argv = ['mdcalc', 'braking', {str(lecture)!r}]\n"
        "from mdcalc.cli.launch import main\n"
        "try:\n    main()\nexcept SystemExit:\n    pass\n"
        "print(sorted(m for m in sys.modules if m == 'rich'"
        " or m.startswith(('rich.', 'importlib.metadata'))), file=sys.stderr)\n"
    )
    import subprocess

    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=60)
    assert out.stderr.strip().splitlines()[-1] == "[]"


def test_forced_colour_still_goes_through_rich():
    import os

    env = {**os.environ, "FORCE_COLOR": "1"}
    done = run_script("braking", CASES / "braking" / "lecture.toml", env=env)
    assert done.returncode == 0
    assert "\x1b[" in done.stdout


def _summary(monkeypatch, rich: bool, failed: list[tuple[str, str]], how: str) -> str:
    from collections import Counter

    from mdcalc.cli import terminal

    out = io.StringIO()
    monkeypatch.setattr(sys, "stdout", out)
    monkeypatch.setattr(terminal, "plain_stream", lambda stream: not rich)
    counts = Counter(status for _, status in failed) + Counter({"ok": 7})
    terminal.print_run_summary(counts, failed, 7 + len(failed), 0.0123, how, stderr=False)
    return out.getvalue()


@pytest.mark.parametrize(
    ("failed", "how", "plain"),
    [
        ([], "process pool, 2 jobs", True),
        ([(f"cases/f_{i}.toml", "input-error") for i in range(25)], "in-process", True),
        ([("cases/α β/x.toml", "no-answer"), ("[red]x[/red].toml", "input-error")], "p", True),
        ([("x" * 300 + ".toml", "internal-error")], "p", False),  # a word over the width: rich
        # "://127.0.0.1:" looks like an emoji code to the plain path: rich lays it out
        ([("x.toml", "internal-error")], "dask tcp://127.0.0.1:8786, 4 workers", False),
        ([("cases/日本.toml", "no-answer")], "p", False),  # wide characters: rich lays out
        ([], "[bold]pool[/bold]", False),  # markup in the first line: rich
        ([("cases/:smile:.toml", "input-error")], "p", False),  # rich makes it an emoji
    ],
)
def test_the_run_summary_on_a_pipe_is_riches_text(monkeypatch, failed, how, plain):
    from mdcalc.output.text import plain_summary

    assert _summary(monkeypatch, False, failed, how) == _summary(monkeypatch, True, failed, how)
    files = 7 + len(failed)
    head = f"mdcalc run: {files} case files in 0.0123 s ({files / 0.0123:.4g} files/s, {how})"
    lines = [f"{status}: {path}" for path, status in failed[:20]]
    text = plain_summary([head], ["status", "files"], [["ok", "7"]], [False, True], lines, 140)
    assert (text is not None) == plain


def test_rounding_noise_of_a_column_prints_as_zero():
    """Issue 33: μ₂₃ at t = 0 printed 1.8834e-16 (a difference of equal numbers); a
    value below 1e-12 of its column's largest is 0, but a column of small numbers
    keeps them, and JSON keeps every value as computed."""
    from mdcalc.output.jsondoc import to_json

    table = Table(
        "μ(t)",
        "mu",
        [Column("t", "s"), Column("μ₂₃"), Column("small")],
        [[0.0, 1.8834e-16, 1e-16], [0.1, 1.2, 2e-16]],
    )
    grid = grids(Report("mine-hoist", "noise", [table]))[0]
    assert [row[1] for row in grid.rows] == ["0", "1.2"]
    assert [row[2] for row in grid.rows] == ["1.0000e-16", "2.0000e-16"]
    rows = json.loads(to_json(Report("mine-hoist", "noise", [table])))["sections"][0]["rows"]
    assert rows[0][1] == 1.8834e-16
