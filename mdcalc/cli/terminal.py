"""What the commands print besides reports: progress bars, batch summaries, sweep
tables (rich, imported only when a command prints)."""

from __future__ import annotations

import sys
from typing import Any

from mdcalc.errors import STATUS_OF_EXIT


def stdout_console(stderr: bool = False) -> Any:
    from rich.console import Console

    stream = sys.stderr if stderr else sys.stdout
    # A pipe gets plain text at a width that keeps the Methods table on one line.
    return Console(file=stream, width=None if stream.isatty() else 140, highlight=False)


def plain_stdout() -> bool:
    """stdout takes text without colour: not a terminal, and no variable asks rich
    for a terminal's codes anyway."""
    return plain_stream(sys.stdout)


def plain_stream(stream: Any) -> bool:
    """``stream`` takes text without colour (see :func:`plain_stdout`)."""
    import os

    forced = ("FORCE_COLOR", "TTY_COMPATIBLE", "TTY_INTERACTIVE")
    return not stream.isatty() and not any(os.environ.get(name) for name in forced)


def print_report(report: Any, width: int, console: Any) -> None:
    """A report on stdout: the plain-text layout where it gives rich's very text
    (a pipe, most reports), else rich."""
    from mdcalc.output.text import render_plain, render_rich

    text = render_plain(report, width) if plain_stdout() else None
    if text is None:
        render_rich(report, console())
    else:
        sys.stdout.write(text)


def print_run_summary(
    counts: Any, failed: list[tuple[str, str]], files: int, seconds: float, how: str, stderr: bool
) -> None:
    head = (
        f"mdcalc run: {files} case files in {seconds:.3g} s "
        f"({files / max(seconds, 1e-9):.4g} files/s, {how})"
    )
    rows = [[status, str(counts[status])] for status in STATUS_OF_EXIT.values()]
    shown = 20
    after = [f"{status}: {path}" for path, status in failed[:shown]]
    if len(failed) > shown:
        after.append(f"... and {len(failed) - shown} more")
    stream = sys.stderr if stderr else sys.stdout
    if plain_stream(stream):  # the very text rich prints, without importing rich
        from mdcalc.output.text import plain_summary

        text = plain_summary([head], ["status", "files"], rows, [False, True], after, 140)
        if text is not None:
            stream.write(text)
            return
    from rich.table import Table

    table = Table()
    table.add_column("status")
    table.add_column("files", justify="right")
    for row in rows:
        table.add_row(*row)
    console = stdout_console(stderr=stderr)
    console.print(head, highlight=False)
    console.print(table)
    for line in after:
        console.print(line, highlight=False, markup=False)


class Progress:
    """A rich progress bar on stderr, only when stderr is a terminal. ``total`` None:
    told later, by the ``total`` attribute of what ``with`` gives."""

    def __init__(self, total: int | None) -> None:
        self.total = total
        self.bar: Any = None

    def __enter__(self) -> Any:
        if not sys.stderr.isatty() or (self.total is not None and self.total < 2):
            return None
        from rich.progress import Progress

        self.bar = Progress(console=stdout_console(stderr=True), transient=True)
        self.bar.start()
        task = self.bar.add_task("running", total=self.total)

        class Advance:
            def __call__(_, n: int) -> None:
                self.bar.advance(task, n)

            def total(_, n: int) -> None:
                self.bar.update(task, total=n)

        return Advance()

    def __exit__(self, *exc: object) -> None:
        if self.bar is not None:
            self.bar.stop()


def progress(total: int | None) -> Progress:
    return Progress(total)


def status_counts(status: Any) -> str:
    """ "points: 9,990 ok, 10 no-answer": how many points ended how, worst last."""
    import numpy as np

    codes, counts = np.unique(np.asarray(status), return_counts=True)
    parts = [
        f"{count:,} {STATUS_OF_EXIT.get(int(code), str(code))}"
        for code, count in zip(codes.tolist(), counts.tolist(), strict=True)
    ]
    return "points: " + ", ".join(parts)


def print_sweep(table: Any, points: int, how: str) -> None:
    from rich.table import Table

    from mdcalc.output.report import format_value
    from mdcalc.output.text import print_titled
    from mdcalc.runs.sweep import summary_rows

    console = stdout_console()
    # A table of points while it fits: at most 200 rows and 8 columns (a scene with
    # many Methods tables has dozens of key results; then each column's range).
    if points <= 200 and len(table.keys) <= 8:
        rich_table = Table(title=f"Sweep: {points} points, {how}", title_justify="left")
        for key in table.keys:
            unit = table.units.get(key, "")
            rich_table.add_column(f"{key} ({unit})" if unit else key, justify="right")
        rich_table.add_column("status")
        for index in range(points):
            cells = [format_value(float(table.columns[k][index]), 6) for k in table.keys]
            status = STATUS_OF_EXIT.get(int(table.status[index]), str(table.status[index]))
            rich_table.add_row(*[c if c != "nan" else "—" for c in cells], status)
        print_titled(console, rich_table)
        return
    rich_table = Table(title=f"Sweep: {points} points, {how}; range of each column")
    for label in ("key", "unit", "min", "max"):
        rich_table.add_column(label, justify="left" if label in ("key", "unit") else "right")
    for row in summary_rows(table):
        rich_table.add_row(*row)
    print_titled(console, rich_table)
    console.print(status_counts(table.status))
    console.print(
        "write every point with --out FILE.csv or FILE.json; pick columns with --result KEY",
        style="dim",
    )
