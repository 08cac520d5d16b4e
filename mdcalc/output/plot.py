"""Plots of a problem's curves (``--plot FILE.png|.svg|.pdf``).

A problem module that has curves offers ``charts(result) -> list[Chart]``: plain
data (this module's dataclasses, no matplotlib). :func:`render` draws the charts one
under another with matplotlib's Agg backend; matplotlib is imported only here, and
only when ``--plot`` is given. It is an optional extra: ``pip install 'mdcalc[plot]'``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

from mdcalc.errors import InputError, Problem
from mdcalc.input.files import write_atomic

FORMATS = (".png", ".svg", ".pdf")

#: What a series is, which decides how it is drawn (:data:`SERIES_STYLES`).
Role = Literal[
    "result",  # this case's curve (solid; colours from the cycle)
    "comparison",  # a simpler method's curve, or the state before (dashed)
    "secondary",  # a further quantity or family on the same axes (dotted)
    "envelope",  # a bound the response keeps within
    "limit",  # a limit the result is held against (a curve)
    "load",  # a load or resistance the scene works against
    "excitation",  # what drives the scene at a frequency (engine orders)
    "this-case",  # the case's own point(s)
    "event",  # points where something happens (slack, lift-off): a group per kind
    "nodes",  # a method's values at its nodes (Kovylin's (5))
    "measured",  # measured points
    "histogram",  # a histogram's steps
    "bars",  # horizontal bars (indices)
    "explicit",  # an explicit integrator over its tolerances (work-precision)
    "implicit",  # an implicit integrator over its tolerances
    "switching",  # an integrator that switches to an implicit method when stiff
    "single",  # a method without a tolerance (a closed form): one point
]
#: What a reference line is (:data:`MARK_STYLES`).
MarkRole = Literal[
    "static",  # the static value
    "reported",  # a value the report gives
    "limit",  # a limit the result is held against
    "this-case",  # the case's own value
    "design",  # a design or operating point
    "resonance",  # a resonance
    "advice",  # a rule of thumb
    "range",  # the edges of a range or span
    "event",  # the time of an event
    "mean",  # a mean level (of a fluctuating speed)
]

#: Every look of a chart, keyed by meaning: the one place a colour or line style is
#: set (``tests/test_plots.py`` fails on any other). Series without a colour take the
#: cycle's (:data:`CYCLE`: none of the colours below, which mean something here).
SERIES_STYLES: dict[str, dict[str, Any]] = {
    "result": {"linestyle": "-", "linewidth": 1.5},
    "comparison": {"linestyle": "--", "linewidth": 1.3},
    "secondary": {"linestyle": ":", "linewidth": 1.6},
    "envelope": {"linestyle": "--", "linewidth": 1.0, "color": "darkorange"},
    "limit": {"linestyle": ":", "linewidth": 1.6, "color": "firebrick"},
    "load": {"linestyle": "-", "linewidth": 1.3, "color": "saddlebrown"},
    "excitation": {"linestyle": (0, (6, 2, 1, 2)), "linewidth": 1.0},
    "this-case": {"linestyle": "none", "marker": "o", "markersize": 7, "color": "crimson",
                  "zorder": 5},
    "event": {"linestyle": "none", "marker": "D", "markersize": 5, "zorder": 4},
    "nodes": {"linestyle": "none", "marker": "o", "markersize": 3, "zorder": 4},
    "measured": {"linestyle": "none", "marker": "x", "markersize": 7, "color": "black",
                 "zorder": 4},
    "histogram": {"drawstyle": "steps-post", "linewidth": 1.2, "color": "steelblue"},
    "bars": {"color": "steelblue"},
    "explicit": {"linestyle": "-", "linewidth": 1.3, "marker": "o", "markersize": 4},
    "implicit": {"linestyle": "--", "linewidth": 1.3, "marker": "s", "markersize": 4},
    "switching": {"linestyle": "-.", "linewidth": 1.3, "marker": "^", "markersize": 5},
    "single": {"linestyle": "none", "marker": "*", "markersize": 12, "zorder": 5},
}  # fmt: skip
MARK_STYLES: dict[str, dict[str, Any]] = {
    "static": {"linestyle": "-.", "color": "dimgrey", "linewidth": 1.0},
    "reported": {"linestyle": "--", "color": "black", "linewidth": 1.0},
    "limit": {"linestyle": ":", "color": "firebrick", "linewidth": 1.6},
    "this-case": {"linestyle": "--", "color": "crimson", "linewidth": 1.0},
    "design": {"linestyle": "-", "color": "black", "linewidth": 0.8, "alpha": 0.7},
    "resonance": {"linestyle": "-", "color": "tab:red", "linewidth": 1.0, "alpha": 0.5},
    "advice": {"linestyle": ":", "color": "seagreen", "linewidth": 1.6},
    "range": {"linestyle": ":", "color": "grey", "linewidth": 1.0},
    "event": {"linestyle": "-.", "color": "teal", "linewidth": 1.0},
    "mean": {"linestyle": (0, (1, 2)), "color": "black", "linewidth": 1.2},
}
CYCLE = ("tab:blue", "tab:purple", "tab:olive", "tab:pink", "tab:cyan", "navy")
#: How a curve of one point is drawn (a sweep of one height), by its role.
ONE_POINT = {
    "result": {"marker": "o"},
    "comparison": {"marker": "o", "markerfacecolor": "none"},
    "secondary": {"marker": "s", "markerfacecolor": "none"},
}


@dataclass(frozen=True)
class Series:
    """One curve (or point set) of a chart."""

    label: str
    x: Sequence[float]
    y: Sequence[float]
    role: Role = "result"
    #: Series of one group share a colour (a quantity and its approximation).
    group: str = ""


@dataclass(frozen=True)
class Mark:
    """A horizontal (``axis="y"``) or vertical (``axis="x"``) reference line."""

    axis: Literal["x", "y"]
    value: float
    label: str = ""
    role: MarkRole = "range"


@dataclass(frozen=True)
class Shade:
    """A map over a grid, drawn as filled regions: ``z[i][j]`` at ``(x[j], y[i])``.
    With ``levels`` given, the regions between those levels (a stability chart)."""

    x: Sequence[float]
    y: Sequence[float]
    z: Sequence[Sequence[float]]
    label: str = ""
    levels: Sequence[float] | None = None


@dataclass(frozen=True)
class Chart:
    title: str
    x_label: str
    y_label: str
    series: list[Series] = field(default_factory=list)
    marks: list[Mark] = field(default_factory=list)
    shade: Shade | None = None
    x_log: bool = False
    y_log: bool = False
    #: Names of the bars of a ``"bars"`` series, at y = 0, 1, 2 ...
    ticks: list[str] | None = None


def check_path(path: Path) -> None:
    """Refuse a plot path matplotlib cannot write, before anything is computed."""
    if path.suffix.lower() not in FORMATS:
        raise InputError(
            path,
            [Problem(f"--plot: unknown image format {path.suffix or '(none)'!r}; "
                     f"use {', '.join(FORMATS)}")],
        )  # fmt: skip


def matplotlib_missing() -> str | None:
    """None if matplotlib can be imported, else what to do about it."""
    import importlib.util

    if importlib.util.find_spec("matplotlib") is None:
        return (
            "--plot needs matplotlib, which is not installed; "
            "install it with: pip install 'mdcalc[plot]'"
        )
    return None


def render(charts: Sequence[Chart], path: Path, title: str = "", replace: bool = True) -> None:
    """Draw ``charts`` one under another into ``path`` (its suffix is the format),
    atomically (:func:`mdcalc.input.files.write_atomic`); ``replace`` False: only if no
    file is there."""
    figure = figure_of(charts, title)
    fmt = path.suffix.lower().lstrip(".")
    write_atomic(
        path,
        lambda tmp: figure.savefig(tmp, format=fmt, dpi=120),
        replace=replace,
        option="--plot: ",
    )


def figure_of(charts: Sequence[Chart], title: str = "", titled: bool = True) -> Any:
    """A matplotlib Figure of ``charts`` one under another (Agg), laid out by
    matplotlib's constrained layout: a figure title keeps its own space, and each
    legend stands where it covers no drawn line (:func:`_place_legend`). ``titled``
    False: no chart titles (a document's caption gives them)."""
    import matplotlib  # no matplotlib.use: a notebook keeps its own backend
    from cycler import cycler
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    height = 3.6 if len(charts) == 1 else 3.4 * len(charts)
    with matplotlib.rc_context({"axes.prop_cycle": cycler(color=list(CYCLE))}):
        figure = Figure(figsize=(7.5, height + (0.4 if title else 0.0)), layout="constrained")
        axes = figure.subplots(len(charts), 1, squeeze=False)[:, 0]
        groups: dict[str, str] = {}  # a group's colour, the same in every chart
        for ax, chart in zip(axes, charts, strict=True):
            _draw(ax, chart, titled, groups)
    if title:
        figure.suptitle(title, fontsize=11)
    renderer = FigureCanvasAgg(figure).get_renderer()
    # (a shaded map has no free area: its legend stands below it)
    legends = [
        (ax, chart.shade is None)
        for ax, chart in zip(axes, charts, strict=True)
        if any(s.label for s in chart.series) or any(m.label for m in chart.marks)
    ]
    # A legend placed below its axes shrinks the axes, which may bring a line under a
    # legend placed inside another: placed again until none covers a line.
    for _ in range(3):
        figure.draw_without_rendering()  # the layout settled before the legends are placed
        misplaced = [(ax, free) for ax, free in legends if _misplaced(ax, renderer, free)]
        if not misplaced:
            break
        below = [_place_legend(ax, renderer, free) for ax, free in misplaced]
        if not any(below):  # legends inside change no layout: nothing has moved
            break
    return figure


def _misplaced(ax: Any, renderer: Any, free: bool) -> bool:
    """Has ``ax`` no legend yet, or one inside that covers a line or point (or any
    legend inside where the axes have no ``free`` area)?"""
    legend = ax.get_legend()
    if legend is None:
        return True
    inside = legend.get_bbox_to_anchor() is ax.bbox  # (one below has its own anchor)
    if inside and not free:
        return True
    return inside and covers(legend.get_window_extent(renderer), drawn_shapes(ax))


def chart_images(charts: Sequence[Chart], fmt: Literal["svg", "png"]) -> list[bytes]:
    """Each chart drawn on its own, without its title (the document's caption gives
    it), as SVG (text as paths, no date, no external resource: it goes inline into an
    HTML report) or PNG bytes."""
    import io

    import matplotlib

    images = []
    for chart in charts:
        figure = figure_of([chart], titled=False)
        buffer = io.BytesIO()
        with matplotlib.rc_context({"svg.hashsalt": "mdcalc", "svg.fonttype": "path"}):
            figure.savefig(
                buffer,
                format=fmt,
                dpi=120,
                # No date, no creator's or Dublin Core's URLs: nothing external.
                metadata=dict.fromkeys(("Date", "Creator", "Format", "Type"))
                if fmt == "svg"
                else None,
            )
        images.append(buffer.getvalue())
    return images


def _draw(ax: Any, chart: Chart, titled: bool, groups: dict[str, str]) -> None:
    if chart.shade is not None:
        s = chart.shade
        if s.levels is not None:
            ax.contourf(s.x, s.y, s.z, levels=list(s.levels), cmap="Greys", alpha=0.5)
        else:
            filled = ax.pcolormesh(s.x, s.y, s.z, shading="auto", cmap="viridis")
            ax.figure.colorbar(filled, ax=ax, label=s.label)
    # Colours from the cycle: a chart's series from its start, a named group (a kind of
    # event, a quantity and its approximation) from its end, the same in every chart.
    plain = 0
    for series in chart.series:
        look = dict(SERIES_STYLES[series.role])
        if "color" not in look and series.group:
            look["color"] = groups.setdefault(series.group, CYCLE[-1 - len(groups) % len(CYCLE)])
        elif "color" not in look:
            look["color"] = CYCLE[plain % len(CYCLE)]
            plain += 1
        if len(series.x) == 1 and "marker" not in look:
            look |= ONE_POINT.get(series.role, {})
        if series.role == "bars":  # horizontal: x the lengths, y the positions
            ax.barh(series.y, series.x, label=series.label or None, **look)
        else:
            ax.plot(series.x, series.y, label=series.label, **look)
    labelled: set[str] = set()  # one legend entry per label (upshift, upshift, ...)
    for mark in chart.marks:
        line = ax.axhline if mark.axis == "y" else ax.axvline
        label = mark.label if mark.label and mark.label not in labelled else None
        labelled.add(mark.label)
        line(mark.value, label=label, **MARK_STYLES[mark.role])
    if chart.ticks is not None:
        ax.set_yticks(range(len(chart.ticks)), chart.ticks, fontsize=8)
    if chart.x_log:
        ax.set_xscale("log")
    if chart.y_log:
        ax.set_yscale("log")
    if titled:
        ax.set_title(chart.title, fontsize=10, wrap=True)
    ax.set_xlabel(chart.x_label)
    ax.set_ylabel(chart.y_label)
    ax.grid(True, alpha=0.3)


#: Where a legend may stand inside its axes, in the order tried.
_INSIDE = (
    "upper right", "upper left", "lower right", "lower left",
    "center right", "center left", "upper center", "lower center", "center",
)  # fmt: skip


def _place_legend(ax: Any, renderer: Any, free: bool = True) -> bool:
    """A legend inside the axes where it covers no drawn line or point (if the axes
    have ``free`` area at all), else below the axes (the constrained layout makes
    room; True)."""
    if ax.get_legend() is not None:
        ax.get_legend().remove()
    if free:
        shapes = drawn_shapes(ax)
        legend = ax.legend(loc=_INSIDE[0], fontsize=8, framealpha=0.9)
        for loc in _INSIDE:
            legend.set_loc(loc)
            if not covers(legend.get_window_extent(renderer), shapes):
                return False
        legend.remove()
    from matplotlib.transforms import offset_copy

    # Below the tick labels and the axis label, a fixed distance in points from the
    # axes (the layout may still change the axes' height).
    below = ax.get_tightbbox(renderer).y0
    drop = (ax.get_window_extent(renderer).y0 - below) / renderer_points(ax) + 4.0
    for columns in (2, 1) if len(ax.get_legend_handles_labels()[0]) > 3 else (1,):
        legend = ax.legend(
            loc="upper center",
            bbox_to_anchor=(0.5, 0.0),
            bbox_transform=offset_copy(ax.transAxes, ax.figure, y=-drop, units="points"),
            fontsize=8,
            framealpha=0.9,
            ncols=columns,
        )
        if legend.get_window_extent(renderer).width <= 0.96 * ax.figure.bbox.width:
            break
    return True


def drawn_shapes(ax: Any) -> list[tuple[Any, float]]:
    """Each line of ``ax`` as a path in display units, with the half-size of its
    markers (0 for a plain line); a step line as the steps drawn."""
    import numpy as np
    from matplotlib.path import Path as MplPath

    shapes = []
    for line in ax.get_lines():
        xy = line.get_xydata()
        if len(xy) == 0:
            continue
        points = line.get_transform().transform(np.asarray(xy, dtype=float))
        if str(line.get_drawstyle()).startswith("steps"):
            points = np.repeat(points, 2, axis=0)[1:-1]
            points[1::2, 1] = points[0::2, 1]
        points = points[np.all(np.isfinite(points), axis=1)]
        if len(points) == 0:
            continue
        marker = line.get_marker() not in (None, "None", "none", "", " ")
        size = line.get_markersize() * renderer_points(ax) / 2.0 if marker else 0.0
        if line.get_linestyle() in ("None", "none", "", " "):
            shapes += [(MplPath(points[k : k + 1]), size) for k in range(len(points))]
        else:
            shapes.append((MplPath(points), size))
    return shapes


def renderer_points(ax: Any) -> float:
    """Display units (pixels) per typographic point of the figure of ``ax``."""
    return float(ax.figure.dpi) / 72.0


def covers(box: Any, shapes: list[tuple[Any, float]]) -> bool:
    """Does the display box ``box`` (a legend's) cover any of ``shapes``?"""
    for path, size in shapes:
        grown = box.padded(size) if size else box
        if len(path.vertices) == 1:
            if grown.contains(*path.vertices[0]):
                return True
        elif path.intersects_bbox(grown, filled=False):
            return True
    return False
