"""``--plot`` (issue 9.2), written once for every problem that offers ``charts``.

Every shipped case of such a problem is drawn to PNG (and a few to SVG and PDF); the
file must be a valid image of its kind. The chart data must be finite and plain.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from mdcalc.problems import PROBLEMS
from tests.conftest import CASES, assert_no_traceback

matplotlib = pytest.importorskip("matplotlib", reason="the plot extra is not installed")

PLOTTED = [name for name, spec in PROBLEMS.items() if hasattr(spec.load(), "charts")]

#: The problems issue 9 names as having curves; each must offer charts.
CURVES = {
    "acceleration", "coupling", "mine-hoist", "hoist", "mount", "variator",
    "mechanism", "resonance", "clutch",
}  # fmt: skip

CASE_FILES = [
    (name, path)
    for name in PLOTTED
    for path in sorted((CASES / name).glob("*.toml"))
    + sorted((CASES / "extreme").glob(f"{name}_*.toml"))
]

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == PNG_SIGNATURE, "not a PNG"
    assert data[12:16] == b"IHDR"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


def test_every_problem_with_curves_draws_them():
    assert set(PLOTTED) >= CURVES & set(PROBLEMS), sorted(CURVES - set(PLOTTED))


def _solve(path: Path):
    from mdcalc.input.casefile import read_case
    from mdcalc.runs.runner import solve_text

    return solve_text(read_case(path))


def _check_chart_data(charts) -> None:
    from mdcalc.output.plot import Chart

    for chart in charts:
        assert isinstance(chart, Chart)
        assert chart.title and chart.x_label and chart.y_label
        assert chart.series or chart.shade is not None
        for series in chart.series:
            assert len(series.x) == len(series.y) > 0, series.label
            points = [(x, y) for x, y in zip(series.x, series.y, strict=True)]
            assert all(math.isfinite(x) and math.isfinite(y) for x, y in points), series.label


@pytest.mark.parametrize(("name", "path"), CASE_FILES, ids=[f"{n}:{p.name}" for n, p in CASE_FILES])
def test_each_case_draws_a_valid_png_that_reads_at_a_glance(name, path, tmp_path):
    """Issue 33.3: solved once, drawn once by the figure --plot writes, and checked from
    matplotlib's artists: no text over text, no legend over a drawn line, all inside."""
    from mdcalc.output.plot import figure_of

    run = _solve(path)
    charts = run.module.charts(run.result)
    _check_chart_data(charts)
    from mdcalc.output.document import document_of
    from tests.test_reports import assert_files_as_a_report

    assert_files_as_a_report(document_of(run), path.name)  # solved once for both
    if not charts:
        pytest.skip("this scene has no curve (the CLI says so and writes nothing)")
    figure = figure_of(charts, title=run.report.title)  # what render writes (tested below)
    assert_reads_at_a_glance(figure)
    width, height = figure.canvas.get_width_height()
    assert width >= 400 and height >= 200 * len(charts)


def assert_reads_at_a_glance(figure) -> None:
    """No title, axis label, legend or annotation over another (or over tick labels),
    none outside the figure, and no legend box over a drawn line or point."""
    from mdcalc.output.plot import covers, drawn_shapes

    figure.draw_without_rendering()  # every position laid out, at the figure's own dpi
    renderer = figure.canvas.get_renderer()
    page = figure.bbox
    texts = []  # (what, box, is a tick label)
    if figure._suptitle is not None and figure._suptitle.get_text():
        texts.append(("figure title", figure._suptitle.get_window_extent(renderer), False))
    for n, ax in enumerate(figure.axes):
        for what, artist in (
            ("title", ax.title),
            ("x label", ax.xaxis.label),
            ("y label", ax.yaxis.label),
            *(("annotation", t) for t in ax.texts),
        ):
            if artist.get_visible() and artist.get_text():
                texts.append((f"chart {n + 1} {what}", artist.get_window_extent(renderer), False))
        legend = ax.get_legend()
        if legend is not None:
            box = legend.get_window_extent(renderer)
            texts.append((f"chart {n + 1} legend", box, False))
            assert not covers(box, drawn_shapes(ax)), f"chart {n + 1}: a legend covers a line"
        for axis in (ax.xaxis, ax.yaxis):
            for tick in axis._update_ticks():  # the ticks drawn: those within the view
                label = tick.label1
                if label.get_visible() and label.get_text():
                    box = label.get_window_extent(renderer)
                    texts.append((f"chart {n + 1} tick {label.get_text()}", box, True))
    for what, box, _ in texts:
        assert box.x0 >= page.x0 - 1 and box.x1 <= page.x1 + 1, f"{what} cut off at a side"
        assert box.y0 >= page.y0 - 1 and box.y1 <= page.y1 + 1, f"{what} cut off"
    for i, (one, a, tick_a) in enumerate(texts):
        for two, b, tick_b in texts[i + 1 :]:
            if not (tick_a and tick_b):
                assert not a.overlaps(b), f"{one} over {two}"


def test_plot_through_the_cli(tmp_path, cli):
    out = tmp_path / "plot.png"
    result = cli("mine-hoist", CASES / "mine-hoist" / "seed_1025.toml", "--plot", out)
    assert result.exit_code == 0, result.stderr
    assert_no_traceback(result)
    assert result.stderr == f"wrote {out}\n"
    png_size(out.read_bytes())


@pytest.mark.parametrize("suffix", [".svg", ".pdf"])
def test_svg_and_pdf(suffix, tmp_path, cli):
    name, path = "coupling", CASES / "coupling" / "example_8_1.toml"
    out = tmp_path / f"plot{suffix}"
    result = cli(name, path, "--plot", out)
    assert result.exit_code == 0, result.stderr
    data = out.read_bytes()
    if suffix == ".svg":
        root = ET.fromstring(data)
        assert root.tag.endswith("svg")
    else:
        assert data.startswith(b"%PDF-")


def test_a_plot_is_not_overwritten_without_force(tmp_path, cli):
    name, path = "coupling", CASES / "coupling" / "example_8_1.toml"
    out = tmp_path / "plot.png"
    out.write_bytes(b"keep")
    result = cli(name, path, "--plot", out)
    assert result.exit_code == 2
    assert "use --force" in result.stderr
    assert out.read_bytes() == b"keep"
    assert cli(name, path, "--plot", out, "--force").exit_code == 0
    png_size(out.read_bytes())


def test_an_unknown_format_is_refused_before_solving(tmp_path, cli):
    result = cli("coupling", CASES / "coupling" / "example_8_1.toml", "--plot", tmp_path / "p.gif")
    assert result.exit_code == 2
    assert "--plot: use a file ending .png, .svg, .pdf" in result.stderr
    assert result.stdout == ""  # refused before the report


def test_a_scene_without_curves_says_so(tmp_path, cli):
    out = tmp_path / "p.png"
    result = cli("hoist", CASES / "hoist" / "lift.toml", "--plot", out)  # no rope
    assert result.exit_code == 0
    assert "this scene has no curve to draw; no file written" in result.stderr
    assert not out.exists()


def test_a_problem_without_curves_offers_no_plot(tmp_path, cli):
    """braking draws nothing: its command has no --plot (issue 32.5), and says so as any
    unknown option; every problem that draws has one."""
    for name, spec in PROBLEMS.items():
        assert spec.draws == hasattr(spec.load(), "charts"), name
        assert ("--plot" in cli(name, "--help").stdout) == spec.draws, name
    out = tmp_path / "p.png"
    result = cli("braking", CASES / "braking" / "lecture.toml", "--plot", out)
    assert result.exit_code == 2
    assert "No such option: --plot" in result.stderr
    assert not out.exists()


def test_missing_matplotlib_is_a_clear_message(tmp_path, cli, monkeypatch):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda n, *a: None if n == "matplotlib" else real(n, *a)
    )
    result = cli("coupling", CASES / "coupling" / "example_8_1.toml", "--plot", tmp_path / "p.png")
    assert result.exit_code == 2
    assert "pip install 'mdcalc[plot]'" in result.stderr
    assert_no_traceback(result)


def test_render_uses_agg_and_writes_atomically(tmp_path):
    from mdcalc.output.plot import Chart, Mark, Series, Shade, render

    chart = Chart(
        "t", "x", "y",
        [Series("a", [0.0, 1.0], [1.0, 2.0]), Series("b", [0.0, 1.0], [2.0, 1.0], "event")],
        [Mark("y", 1.5, "m")],
        Shade([0.0, 1.0], [0.0, 1.0], [[0.0, 1.0], [1.0, 0.0]], levels=[0.5, 2.0]),
    )  # fmt: skip
    out = tmp_path / "sub" / "c.png"
    render([chart, chart], out, title="two")
    assert matplotlib.get_backend().lower() == "agg"
    one = tmp_path / "sub" / "one.png"
    render([chart], one)
    assert matplotlib.get_backend().lower() == "agg"
    width, height = png_size(out.read_bytes())
    assert png_size(one.read_bytes()) == (width, pytest.approx(height / 2, rel=0.1))
    assert sorted(p.name for p in out.parent.iterdir()) == ["c.png", "one.png"]


def test_unwritable_and_folder_paths_are_input_errors(tmp_path, cli):
    case = CASES / "coupling" / "example_8_1.toml"
    folder = cli("coupling", case, "--plot", tmp_path)
    assert folder.exit_code == 2 and "--plot: is a folder; give a file name" in folder.stderr
    nowhere = cli("coupling", case, "--plot", "/proc/mdcalc-test/p.png")
    assert nowhere.exit_code == 2, nowhere.stderr
    assert "/proc/mdcalc-test/p.png: error: --plot: cannot write:" in nowhere.stderr
    assert_no_traceback(nowhere)


def test_a_path_too_long_is_an_input_error(tmp_path, cli):
    long = tmp_path / ("p" * 300 + ".png")
    result = cli("coupling", CASES / "coupling" / "example_8_1.toml", "--plot", long)
    assert result.exit_code == 2, result.stderr
    assert "cannot use this path" in result.stderr


def test_every_look_comes_from_the_mapping_by_meaning():
    """Issue 33.3: no chart sets a colour or line style of its own: only
    mdcalc/output/plot.py names one, and each meaning has a look of its own."""
    import ast
    import typing

    from mdcalc.output import plot

    looks = {"color", "colour", "colors", "c", "linestyle", "ls", "linewidth", "lw", "marker",
             "markersize", "ms", "alpha", "drawstyle", "cmap", "style"}  # fmt: skip
    root = Path(plot.__file__).parents[1]
    drawing = [
        module
        for module in sorted(root.rglob("*.py"))
        if re.search(r"output\.plot import .*\b(Chart|Series|Mark)\b", module.read_text("utf-8"))
    ]
    assert len(drawing) >= 10  # every problem's charts, the study's
    for module in drawing:
        for node in ast.walk(ast.parse(module.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call):
                own = [k.arg for k in node.keywords if k.arg in looks]
                assert not own, f"{module.relative_to(root)}:{node.lineno} sets {own}"
            if isinstance(node, ast.ImportFrom) and node.module:
                assert not node.module.startswith("matplotlib"), module
    assert set(typing.get_args(plot.Role)) == set(plot.SERIES_STYLES)
    assert set(typing.get_args(plot.MarkRole)) == set(plot.MARK_STYLES)

    def look(style):
        return (str(style.get("linestyle")), style.get("color"), style.get("marker"))

    # Every fixed look, of a curve or of a reference line, is one meaning's own; the
    # cycle's colours are none of theirs; the cycled meanings differ by line style.
    kinds = ("histogram", "bars")  # chart kinds, not curves among others
    meanings: dict[tuple, set[str]] = {}  # a look: the roles that have it
    for role, style in [*plot.SERIES_STYLES.items(), *plot.MARK_STYLES.items()]:
        if "color" in style and role not in kinds:
            meanings.setdefault(look(style), set()).add(role)
    alike = [roles for roles in meanings.values() if len(roles) > 1]
    assert not alike, f"two meanings look alike: {alike}"  # (a limit curve and line: one)
    styles = [*plot.SERIES_STYLES.values(), *plot.MARK_STYLES.values()]
    colours = {style["color"] for style in styles if "color" in style}
    assert not colours & set(plot.CYCLE), "a cycle colour also means something"
    cycled = [look(style) for style in plot.SERIES_STYLES.values() if "color" not in style]
    assert len(set(cycled)) == len(cycled), "two cycled meanings look alike"
    points = [tuple(sorted(v.items())) for v in plot.ONE_POINT.values()]
    assert len(set(points)) == len(points), "two meanings of one point look alike"


@pytest.mark.parametrize(
    ("problem", "case"),
    [("coupling", "coupling/example_8_1.toml"), ("mine-hoist", "mine-hoist/stiff_chord.toml")],
)
def test_an_envelope_is_two_curves_not_one_closed_outline(problem, case):
    """Issue 33.3: the upper and the lower envelope are separate series (a closed
    outline drew a vertical line at its end that read as a jump of the response),
    each running forward in time, one legend entry between them."""
    run = _solve(CASES / case)
    for chart in run.module.charts(run.result):
        edges = [s for s in chart.series if s.role == "envelope"]
        if not edges:
            continue
        assert len(edges) == 2 and [bool(s.label) for s in edges] == [True, False]
        upper, lower = edges
        for edge in edges:
            assert all(b > a for a, b in zip(edge.x, edge.x[1:], strict=False)), "runs back"
        assert all(u >= w for u, w in zip(upper.y, lower.y, strict=True))
        break
    else:
        raise AssertionError(f"no {problem} chart of {case} has an envelope")
