"""``--plot`` (issue 9.2), written once for every problem that offers ``charts``.

Every shipped case of such a problem is drawn to PNG (and a few to SVG and PDF); the
file must be a valid image of its kind. The chart data must be finite and plain.
"""

from __future__ import annotations

import math
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
def test_each_case_draws_a_valid_png(name, path, tmp_path):
    # Solved once and drawn by the renderer --plot uses; the CLI path is tested below.
    from mdcalc.output.plot import render

    run = _solve(path)
    charts = run.module.charts(run.result)
    _check_chart_data(charts)
    if not charts:
        pytest.skip("this scene has no curve (the CLI says so and writes nothing)")
    out = tmp_path / "plot.png"
    render(charts, out, title=run.report.title)
    width, height = png_size(out.read_bytes())
    assert width >= 400 and height >= 200 * len(charts)
    assert [p.name for p in tmp_path.iterdir()] == ["plot.png"]  # no temporary file left


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
        [Series("a", [0.0, 1.0], [1.0, 2.0]), Series("b", [0.0, 1.0], [2.0, 1.0], "points")],
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
