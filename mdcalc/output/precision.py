"""Work-precision diagrams (``--work-precision FILE``): each ODE integrator's error
against its run time, and against its right-hand-side evaluations, over a ladder of
tolerances (:func:`mdcalc.methods.work_precision`), log-log, one style per family of
methods; the methods without a tolerance (closed forms, lecture methods) as single
points. Drawn from the report's ``work_precision.*`` tables: data only, no
matplotlib."""

from __future__ import annotations

import sys

from mdcalc.output.plot import Chart, Mark, Role, Series
from mdcalc.output.report import Column, Report, Table, Value

#: A work-precision table's key, ``work_precision.<its Methods table's key>``, and
#: its columns (filled by :func:`mdcalc.methods.ladder_table`, read here).
LADDER_KEY = "work_precision"
LADDER_COLUMNS = [
    Column("method"),
    Column("family"),
    Column("rtol", kind="tolerance"),
    Column("error", kind="error"),
    Column("run time", "s", kind="seconds"),
    Column("evaluations"),
    Column("status"),
]
#: An error of exactly 0 (a closed form that is the reference's formula) is drawn
#: here, below double precision's epsilon, on a log axis.
FLOOR = 1e-17
EPSILON = sys.float_info.epsilon
ROLES: dict[str, Role] = {
    "explicit": "explicit",
    "implicit": "implicit",
    "switching": "switching",
    "single": "single",
}


def ladder_tables(report: Report) -> list[Table]:
    return [
        s for s in report.sections if isinstance(s, Table) and s.key.startswith(f"{LADDER_KEY}.")
    ]


def charts(report: Report) -> list[Chart]:
    """Two charts a work-precision table: error against run time, and against
    right-hand-side evaluations (the closed forms have none)."""
    return [chart for table in ladder_tables(report) for chart in charts_of(table)]


def _number(value: Value | None) -> float | None:
    return float(value) if isinstance(value, int | float) and not isinstance(value, bool) else None


def charts_of(table: Table) -> list[Chart]:
    """The charts of one work-precision table."""
    label = [c.label for c in table.columns]
    at = {
        name: label.index(name)
        for name in ("method", "family", "error", "run time", "evaluations", "status")
    }
    methods: list[str] = []
    for row in table.rows:
        if row[at["method"]] not in methods:
            methods.append(str(row[at["method"]]))
    by_time: list[Series] = []
    by_work: list[Series] = []
    for method in methods:
        rows = [r for r in table.rows if r[at["method"]] == method and r[at["status"]] == "ok"]
        points = [
            (_number(r[at["run time"]]), _number(r[at["evaluations"]]), _number(r[at["error"]]))
            for r in rows
        ]
        points = [p for p in points if p[0] is not None and p[2] is not None]
        if not points:
            continue
        family = str(rows[0][at["family"]])
        role = ROLES.get(family, "single")
        errors = [max(e, FLOOR) for _, _, e in points if e is not None]
        by_time.append(
            Series(method, [t for t, _, _ in points if t is not None], errors, role, method)
        )
        counted = [(n, max(e, FLOOR)) for _, n, e in points if n is not None and e is not None]
        if counted:
            by_work.append(
                Series(method, [n for n, _ in counted], [e for _, e in counted], role, method)
            )
    what = table.title.removeprefix("Work–precision: ")
    floor = [Mark("y", EPSILON, "double precision ε", "range")]
    charts = [Chart(f"Work–precision: {what}", "run time of one run [s]", "relative error [-]",
                    by_time, floor, x_log=True, y_log=True)]  # fmt: skip
    if by_work:
        charts.append(
            Chart(
                "The same against right-hand-side evaluations",
                "evaluations of the ODE's right-hand side",
                "relative error [-]",
                by_work,
                floor,
                x_log=True,
                y_log=True,
            )  # fmt: skip
        )
    return charts
