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
from typing import Literal

from mdcalc.errors import InputError, Problem
from mdcalc.input.files import write_atomic

FORMATS = (".png", ".svg", ".pdf")

Style = Literal["line", "dashed", "dotted", "points", "step", "bars"]


@dataclass(frozen=True)
class Series:
    """One curve (or point set) of a chart."""

    label: str
    x: Sequence[float]
    y: Sequence[float]
    style: Style = "line"


@dataclass(frozen=True)
class Mark:
    """A horizontal (``axis="y"``) or vertical (``axis="x"``) reference line."""

    axis: Literal["x", "y"]
    value: float
    label: str = ""


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
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7.5, 3.4 * len(charts) + (0.4 if title else 0.0)), layout="tight")
    axes = figure.subplots(len(charts), 1, squeeze=False)[:, 0]
    for ax, chart in zip(axes, charts, strict=True):
        _draw(ax, chart)
    if title:
        figure.suptitle(title, fontsize=11)
    fmt = path.suffix.lower().lstrip(".")
    write_atomic(
        path,
        lambda tmp: figure.savefig(tmp, format=fmt, dpi=120),
        replace=replace,
        option="--plot: ",
    )


def chart_images(charts: Sequence[Chart], fmt: Literal["svg", "png"]) -> list[bytes]:
    """Each chart drawn on its own, as SVG (text as paths, no date, no external
    resource: it goes inline into an HTML report) or PNG bytes."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    images = []
    for chart in charts:
        figure = Figure(figsize=(7.0, 3.6), layout="tight")
        _draw(figure.subplots(), chart)
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


_STYLES = {"line": "-", "dashed": "--", "dotted": ":"}


def _draw(ax: object, chart: Chart) -> None:
    from typing import Any

    a: Any = ax
    if chart.shade is not None:
        s = chart.shade
        if s.levels is not None:
            filled = a.contourf(s.x, s.y, s.z, levels=list(s.levels), cmap="Greys", alpha=0.5)
        else:
            filled = a.pcolormesh(s.x, s.y, s.z, shading="auto", cmap="viridis")
            a.figure.colorbar(filled, ax=a, label=s.label)
    for series in chart.series:
        if series.style == "points":
            a.plot(series.x, series.y, "o", markersize=3, label=series.label)
        elif series.style == "bars":  # horizontal: x the lengths, y the positions
            a.barh(series.y, series.x, color="steelblue", label=series.label or None)
        elif series.style == "step":
            a.step(series.x, series.y, where="post", label=series.label)
        else:
            a.plot(series.x, series.y, _STYLES[series.style], label=series.label)
    labelled: set[str] = set()  # one legend entry per label (upshift, upshift, ...)
    for mark in chart.marks:
        line = a.axhline if mark.axis == "y" else a.axvline
        look = ("-.", "firebrick") if mark.axis == "y" else (":", "dimgrey")
        label = mark.label if mark.label and mark.label not in labelled else None
        labelled.add(mark.label)
        line(mark.value, linestyle=look[0], color=look[1], linewidth=1, alpha=0.8, label=label)
    if chart.ticks is not None:
        a.set_yticks(range(len(chart.ticks)), chart.ticks, fontsize=8)
    if chart.x_log:
        a.set_xscale("log")
    if chart.y_log:
        a.set_yscale("log")
    a.set_title(chart.title, fontsize=10)
    a.set_xlabel(chart.x_label)
    a.set_ylabel(chart.y_label)
    a.grid(True, alpha=0.3)
    if any(s.label for s in chart.series) or any(m.label for m in chart.marks):
        a.legend(fontsize=8, framealpha=0.7)  # see the curve under a legend
