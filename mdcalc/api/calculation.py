"""A calculation as Python hands it back: the report's numbers with their units, its
Methods tables, and the same JSON, HTML, Markdown and charts as the command line."""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import cached_property
from typing import Any


@dataclass(frozen=True)
class MethodsView:
    """One Methods table: each method's value, relative error against the reference
    method and measured run time (``rows``: one dict per method)."""

    key: str
    title: str
    quantities: list[str]
    units: dict[str, str]
    rows: list[dict[str, Any]]

    def to_frame(self) -> Any:
        """The table as a pandas DataFrame (pandas must be installed), one row per
        method: ``<quantity>``, ``<quantity>_rel_error``, ``seconds``, ``reference``."""
        import pandas as pd

        return pd.DataFrame(self.rows).set_index("method")


class Calculation:
    """One case solved: what ``mdcalc PROBLEM CASE`` prints, as values."""

    def __init__(self, run: Any) -> None:
        #: The command line's run of the case (:class:`mdcalc.runs.runner.Run`: the
        #: report, the solver's result, the problem's module, the case as read).
        self.run = run
        report = run.report
        self.problem: str = report.problem
        self.title: str = report.title
        self.case: str = report.case
        #: "ok" or "no-answer" (then ``message`` says why).
        self.status: str = report.status
        self.message: str | None = report.message
        #: The report's notes and warnings, in order ("warning: ...", "info: ...").
        self.notes: list[str] = [f"{n.level}: {n.text}" for n in report.notes]

    def __repr__(self) -> str:
        return f"<mdcalc.Calculation {self.problem} {self.title!r}: {self.status}>"

    @cached_property
    def results(self) -> dict[str, Any]:
        """Every result by its key: a pint Quantity in the JSON's unit (the registry
        of :mod:`mdcalc.input.quantities`, where the radian is a unit of its own), a
        plain number where there is no unit, a bool or a string as it is, a list of
        numbers as a numpy array. Built when first read (pint takes ~0.3 s to load)."""
        from mdcalc.output.report import NO_PINT_UNIT, ascii_unit

        out: dict[str, Any] = {}
        units = None
        for key, q in self.run.report.results().items():
            if key == "status":
                continue
            value: Any = q.value
            if isinstance(value, tuple):
                import numpy as np

                value = np.asarray(value, dtype=float)
            unit = ascii_unit(q.unit)
            if unit and not isinstance(value, bool | str) and unit != NO_PINT_UNIT:
                if units is None:
                    from mdcalc.input.quantities import registry

                    units = registry()
                value = units.Quantity(value, unit)
            out[key] = value
        return out

    @cached_property
    def methods(self) -> dict[str, MethodsView]:
        """The Methods tables by key."""
        from mdcalc.output.report import MethodsTable

        tables: dict[str, MethodsView] = {}
        for section in self.run.report.sections:
            if isinstance(section, MethodsTable):
                rows = []
                for row in section.rows:
                    cells: dict[str, Any] = {"method": row.method, "reference": row.reference}
                    for q in section.quantities:
                        cells[q.key] = row.values.get(q.key)
                        cells[f"{q.key}_rel_error"] = row.rel_errors.get(q.key)
                    cells["seconds"] = row.seconds
                    cells["note"] = row.note
                    rows.append(cells)
                quantities = [q.key for q in section.quantities]
                units = {q.key: q.unit for q in section.quantities}
                tables[section.key] = MethodsView(
                    section.key, section.title, quantities, units, rows
                )
        return tables

    def to_json(self, indent: int | None = 2) -> str:
        """The JSON of ``mdcalc PROBLEM CASE --json`` (format 2)."""
        from mdcalc.output.jsondoc import to_json

        return to_json(self.run.report, indent)

    def to_dict(self) -> dict[str, Any]:
        """:meth:`to_json` read back: plain dicts, lists and numbers."""
        loaded: dict[str, Any] = json.loads(self.to_json(None))
        return loaded

    def to_html(self) -> str:
        """The calculation report of ``--report FILE.html`` (charts inline)."""
        from mdcalc.output.document import document_of, html_of

        return html_of(document_of(self.run))

    def to_markdown(self) -> str:
        """The report of ``--report FILE.md``, without its chart pictures (a text has
        no files beside it: :meth:`charts` draws them)."""
        from mdcalc.output.document import document_of, to_markdown

        why = "not in a Markdown text; draw them with Calculation.charts()"
        document = document_of(self.run)
        return to_markdown(document, None, why)

    def charts(self) -> list[Any]:
        """The scene's charts as matplotlib Figures, one a chart (``--plot``'s; needs
        matplotlib), then the work-precision diagrams where they were asked for
        (``solve(..., work_precision=True)``). An empty list where there is none."""
        from mdcalc.output import precision
        from mdcalc.output.plot import figure_of

        make = getattr(self.run.module, "charts", None)
        scene = make(self.run.result) if make is not None and self.run.result is not None else []
        return [figure_of([chart]) for chart in [*scene, *precision.charts(self.run.report)]]

    def _repr_html_(self) -> str:
        """A notebook shows the calculation report."""
        return self.to_html()
