"""A study's outcome as a rich report, JSON, a table of every sample (CSV or
Parquet) and charts (histogram and CDF of each result, Sobol or rank-correlation
bars)."""

from __future__ import annotations

import json
import math
from datetime import datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mdcalc.errors import InputError, Problem
from mdcalc.output.report import (
    JSON_FORMAT,
    Column,
    Note,
    Quantities,
    Quantity,
    Report,
    Table,
    Value,
    ascii_unit,
    format_seconds,
    format_value,
)
from mdcalc.runs.study import StudyResult
from mdcalc.runs.study.summary import PERCENTILES, Sobol

if TYPE_CHECKING:
    from mdcalc.output.document import Document

#: Version of the study JSON document (``"kind": "study"``): a report's
#: (2: units in ASCII, :func:`mdcalc.output.report.ascii_unit`).
FORMAT = JSON_FORMAT


def _finite(value: float) -> float | None:
    return value if math.isfinite(value) else None


def to_dict(result: StudyResult) -> dict[str, Any]:
    from mdcalc._version import __version__

    plan, spec, ev = result.plan, result.plan.spec, result.evaluated
    title = plan.case.data.get("title")
    return {
        "mdcalc": __version__,
        "format": FORMAT,
        "kind": "study",
        "problem": plan.problem,
        "case": str(plan.case.path),
        "title": title if isinstance(title, str) else None,
        "status": "ok" if any(s is not None for s in result.stats.values()) else "no-answer",
        "samples": len(result.samples),
        "sampler": spec.sampler,
        "seed": spec.seed,
        "how": result.how,
        "seconds": result.seconds,
        "setup_seconds": result.setup_seconds,
        "sampling_seconds": result.sampling_seconds,
        "sensitivity_seconds": result.sensitivity_seconds,
        "samples_per_second": result.samples_per_second,
        "budget": {"time_limit_s": result.time_limit},
        "inputs": [
            {
                "key": item.key,
                "unit": ascii_unit(item.unit),
                "distribution": item.dist.describe(item.unit),
                "kind": item.dist.kind,
                "drawn_min": float(result.samples[:, j].min()),
                "drawn_max": float(result.samples[:, j].max()),
            }
            for j, item in enumerate(plan.inputs)
        ],
        "results": {
            key: None
            if s is None
            else {
                "unit": ascii_unit(s.unit),
                "count": s.count,
                "mean": s.mean,
                "sd": s.sd,
                **{f"p{p}": v for p, v in s.percentiles.items()},
                "min": s.low,
                "max": s.high,
            }
            for key, s in result.stats.items()
        },
        "limits": [
            {
                "result": e.key,
                "unit": ascii_unit(e.unit),
                "above": e.above,
                "below": e.below,
                "exceeded": e.exceeded,
                "of": e.of,
                "probability": _finite(e.probability),
                "ci95": [e.low, e.high],
                "note": e.note or None,
            }
            for e in result.limits
        ],
        "failed": {
            "samples": sum(ev.counts.values()),
            "by_kind": dict(ev.counts),
            "first_reasons": {kind: list(reasons) for kind, reasons in ev.reasons.items()},
        },
        "sensitivity": None
        if not spec.sensitivity
        else {
            "method": (
                "Sobol (SALib: scrambled Saltelli designs, sobol.analyze); indices the mean "
                "over independent replicates, 95 % Student-t intervals from their spread"
            ),
            "base_samples": spec.sensitivity_samples,
            "replicates": result.sensitivity_replicates,
            "runs": result.sensitivity_runs,
            "how": result.sensitivity_how,
            "indices": {x.key: _indices(x) for x in result.sensitivity},
            "notes": {x.key: x.note for x in result.sensitivity if x.note},
        },
        "notes": [ev.note] if ev.note else [],
    }


def _indices(sobol: Sobol) -> dict[str, dict[str, float]] | None:
    if not sobol.first:  # a note says why there are none
        return None
    return {
        name: {
            "S1": sobol.first[name],
            "S1_conf": sobol.first_conf[name],
            "ST": sobol.total[name],
            "ST_conf": sobol.total_conf[name],
        }
        for name in sobol.first
    }


def to_json(result: StudyResult, indent: int | None = 2) -> str:
    return json.dumps(to_dict(result), indent=indent, ensure_ascii=False, allow_nan=False)


def study_report(result: StudyResult) -> Report:
    """The study as a :class:`~mdcalc.output.report.Report`: the one value the
    terminal, HTML and Markdown renderers draw (``to_dict`` is its JSON)."""
    plan, spec, ev = result.plan, result.plan.spec, result.evaluated
    title = plan.case.data.get("title")
    n = len(result.samples)
    answered = any(s is not None for s in result.stats.values())
    report = Report(
        plan.problem,
        f"Study: {title if isinstance(title, str) else plan.problem}",
        status="ok" if answered else "no-answer",
        message=None if answered else "no sample gave a value",
        case=str(plan.case.path),
        time_limit=result.time_limit,
    )
    failed = sum(ev.counts.values())
    how = [
        Quantity("samples", "Samples", n),
        Quantity("sampler", "Sampler", spec.sampler),
        Quantity("seed", "Seed", spec.seed),
        Quantity("how", "Run by", result.how),
        Quantity("failed", "Samples without a value", failed),
        Quantity("seconds", "Run time, in all", format_seconds(result.seconds)),
        Quantity("setup_seconds", "Run time, set-up", format_seconds(result.setup_seconds),
                 note="imports, the plan, the nominal scene, the draws"),
        Quantity("sampling_seconds", "Run time, samples", format_seconds(result.sampling_seconds)),
        Quantity("rate", "Samples per second", f"{result.samples_per_second:,.0f}"),
    ]  # fmt: skip
    if result.sensitivity_runs:
        seconds = format_seconds(result.sensitivity_seconds)
        how.append(Quantity("sensitivity_seconds", "Run time, Sobol design", seconds))
    report.sections.append(Quantities("Study", how))
    report.sections.append(
        Table(
            "Inputs drawn",
            "inputs",
            [
                Column("key"),
                Column("as written", kind="quantity"),
                Column("distribution"),
                Column("drawn min"),
                Column("drawn max"),
            ],
            [
                [
                    item.key,
                    _written(plan.case, item.key),
                    item.dist.describe(item.unit),
                    float(result.samples[:, j].min()),
                    float(result.samples[:, j].max()),
                ]
                for j, item in enumerate(plan.inputs)
            ],
            rows_differ=True,
        )
    )
    labels = ["mean", "sd", *(f"P{p}" for p in PERCENTILES), "min", "max"]
    rows: list[list[Value]] = []
    for key, s in result.stats.items():
        if s is None:
            rows.append([key, result.units.get(key, ""), *["—"] * len(labels)])
        else:
            rows.append([key, s.unit, s.mean, s.sd, *s.percentiles.values(), s.low, s.high])
    columns = [Column("result"), Column("unit"), *map(Column, labels)]
    report.sections.append(Table("Results", "results", columns, rows, rows_differ=True))
    if result.limits:
        report.sections.append(
            Table(
                "Limits",
                "limits",
                [
                    Column("result"),
                    Column("exceeded when"),
                    Column("samples exceeding"),
                    Column("of"),
                    Column("probability"),
                    Column("95 % interval, low"),
                    Column("high"),
                    Column("note"),
                ],
                [
                    [
                        e.key,
                        f"{e.text} {e.unit}".strip(),
                        e.exceeded,
                        e.of,
                        e.probability if math.isfinite(e.probability) else "—",
                        e.low,
                        e.high,
                        e.note,
                    ]
                    for e in result.limits
                ],
                rows_differ=True,
            )
        )
    if result.sensitivity:
        per_design = spec.sensitivity_samples // max(result.sensitivity_replicates, 1)
        sobol_rows: list[list[Value]] = []
        for sob in result.sensitivity:
            for name in sob.first:
                sobol_rows.append(
                    [sob.key, name, *(round(v, 3) for v in (sob.first[name],
                     sob.first_conf[name], sob.total[name], sob.total_conf[name]))]
                )  # fmt: skip
        notes = [f"{sob.key}: {sob.note}" for sob in result.sensitivity if sob.note]
        report.sections.append(
            Table(
                f"Sobol indices ({result.sensitivity_runs:,} runs, SALib: "
                f"{result.sensitivity_replicates} designs × {per_design:,} base samples)",
                "sobol",
                [
                    Column("result"),
                    Column("input"),
                    Column("first order S1"),
                    Column("± 95 %"),
                    Column("total ST"),
                    Column("± 95 %"),
                ],
                sobol_rows,
                rows_differ=True,
            )  # fmt: skip
        )
        report.notes += [Note("info", f"Sobol indices of {note}") for note in notes]
    for kind, count in ev.counts.items():
        reasons = "; ".join(ev.reasons.get(kind, []))
        text = f"{count:,} of {n:,} samples gave no value: {kind}"
        report.notes.append(Note("warning", f"{text} ({reasons})" if reasons else text))
    if ev.note:
        report.notes.append(Note("info", ev.note))
    return report


def _written(case: Any, key: str) -> str:
    """The ``[study.inputs]`` entry of ``key`` as the file writes it, where it stands on
    its own line (``{ nominal = "893.45 kN*m/rad", tol = "±15 %" }``); else ""."""
    line = case.line_of(("study", "inputs", key))
    lines = case.text.splitlines()
    if line is None or not 0 < line <= len(lines):
        return ""
    _, equals, rest = lines[line - 1].partition("=")
    text = rest.strip()
    return text if equals and text.startswith("{") and text.endswith("}") else ""


def render_rich(result: StudyResult, console: Any) -> None:
    """The study's report on a rich Console (colour only on a terminal)."""
    from mdcalc.output.text import render_rich as render

    render(study_report(result), console)


def study_document(result: StudyResult, when: datetime | None = None) -> Document:
    """The filed report of a study (``study --report``, ``run --report-dir``): the
    study's report, then the nominal scene's report, with the charts of both and the
    scene's inputs as written and as computed with."""
    from dataclasses import replace

    from mdcalc.output.document import document_of
    from mdcalc.problems import PROBLEMS
    from mdcalc.runs.runner import Run

    plan = result.plan
    report = study_report(result)
    assert result.scene is not None and plan.scene_case is not None  # run() keeps them
    scene_result, scene = result.scene
    module = PROBLEMS[plan.problem].load()
    nominal = document_of(Run(scene, scene_result, module, plan.scene_case, plan.nominal), when)
    report.sections += [
        replace(section, title=f"Nominal scene: {section.title}") for section in scene.sections
    ]
    report.notes += [replace(note, text=f"nominal scene: {note.text}") for note in scene.notes]
    if scene.status != "ok":
        report.notes.append(Note("warning", f"nominal scene: no answer: {scene.message}"))
    study_charts = charts(result) if report.status == "ok" else []
    scene_charts = [replace(c, title=f"Nominal scene: {c.title}") for c in nominal.charts]
    nominal.report, nominal.charts = report, [*study_charts, *scene_charts]
    nominal.inputs_title = "Inputs of the nominal scene"
    return nominal


def to_columns(result: StudyResult) -> tuple[list[str], list[Any]]:
    """Every sample's inputs, results and exit status: headers and columns."""
    plan = result.plan
    headers = [f"{i.key} [{i.unit}]" if i.unit else i.key for i in plan.inputs]
    columns = [result.samples[:, j] for j in range(len(plan.inputs))]
    for key in result.keys:
        unit = result.units.get(key, "")
        headers.append(f"{key} [{unit}]" if unit else key)
        columns.append(result.evaluated.values[key])
    headers.append("status")
    columns.append(result.evaluated.status)
    return headers, columns


def to_csv(result: StudyResult) -> str:
    """One row per sample, values with 17 significant digits (they read back exactly)."""
    headers, columns = to_columns(result)
    lines = [",".join(headers)]
    body = [["" if math.isnan(v) else repr(v) for v in column.tolist()] for column in columns[:-1]]
    body.append([str(s) for s in columns[-1].tolist()])
    lines += map(",".join, zip(*body, strict=True))
    return "\n".join(lines) + "\n"


def write_parquet(result: StudyResult, path: str) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    headers, columns = to_columns(result)
    pq.write_table(pa.table(dict(zip(headers, columns, strict=True))), path)


def charts(result: StudyResult) -> list[Any]:
    """A histogram and an empirical CDF per result (limits marked), and the Sobol
    total indices (or, without them, Spearman rank correlations: a tornado)."""
    import numpy as np

    from mdcalc.output.plot import Chart, Mark, Series

    out = []
    limits = {e.key: e for e in result.limits}
    for key, s in result.stats.items():
        if s is None:
            continue
        column = result.evaluated.values[key]
        finite = np.sort(column[np.isfinite(column)])
        unit = f" [{s.unit}]" if s.unit else ""
        counts, edges = np.histogram(finite, bins=min(60, max(10, int(math.sqrt(finite.size)))))
        density = counts / max(finite.size, 1) / np.diff(edges)
        marks = []
        if key in limits:
            limit = limits[key]
            chance = (
                f"P(exceed) = {format_value(limit.probability, 3)}"
                if math.isfinite(limit.probability)
                else "no sample"
            )
            for bound, side in ((limit.above, ">"), (limit.below, "<")):
                if bound is not None:
                    text = f"limit {side} {format_value(bound)} {s.unit}".rstrip()
                    marks.append(Mark("x", bound, f"{text}: {chance}", "limit"))
        out.append(
            Chart(
                f"{key}: histogram of {finite.size:,} samples",
                f"{key}{unit}",
                "probability density",
                [Series("", edges.tolist(), [*density.tolist(), 0.0], "histogram")],
                marks,
            )
        )
        step = max(1, finite.size // 2000)
        index = np.unique(np.append(np.arange(0, finite.size, step), finite.size - 1))
        xs = finite[index]  # every step-th sample and the largest
        ys = (index + 1) / finite.size
        out.append(
            Chart(
                f"{key}: CDF",
                f"{key}{unit}",
                "P(result ≤ x)",
                [Series("", xs.tolist(), ys.tolist())],
                marks,
            )
        )
    names = result.plan.keys
    for key in result.keys:
        sens = next((s for s in result.sensitivity if s.key == key and s.first), None)
        if sens is not None:
            values = [sens.total[n] for n in names]
            label, what = "Sobol total index ST", "sensitivity"
        else:
            values = [_rank_correlation(result.samples[:, j], result.evaluated.values[key])
                      for j in range(len(names))]  # fmt: skip
            label, what = "Spearman rank correlation", "tornado"
        if not any(math.isfinite(v) for v in values):
            continue
        order = sorted(
            range(len(names)), key=lambda j: abs(values[j]) if math.isfinite(values[j]) else 0
        )
        out.append(
            Chart(
                f"{key}: {what}",
                label,
                "",
                [Series("", [values[j] for j in order], list(range(len(order))), "bars")],
                ticks=[names[j] for j in order],
            )
        )
    return out


def _rank_correlation(x: Any, y: Any) -> float:
    """Spearman's rank correlation over the samples with a value (average ranks for
    ties); NaN where either side does not vary."""
    import numpy as np
    from scipy.stats import rankdata

    keep = np.isfinite(y)
    if keep.sum() < 3:
        return math.nan
    rx, ry = rankdata(x[keep]), rankdata(y[keep])
    if rx.std() == 0.0 or ry.std() == 0.0:
        return math.nan
    return float(np.corrcoef(rx, ry)[0, 1])


def check_out_path(case: Path, out: Path | None, force: bool) -> None:
    """Refuse an --out path before anything is computed."""
    if out is None:
        return
    problem = None
    if out.suffix.lower() not in (".csv", ".parquet"):
        problem = "--out: use a file ending .csv or .parquet"
    elif out.suffix.lower() == ".parquet":
        import importlib.util

        if importlib.util.find_spec("pyarrow") is None:
            problem = (
                "--out: .parquet needs pyarrow, which is not installed "
                "(pip install pyarrow); use .csv"
            )
    if problem is None and out.is_dir():
        problem = "--out: is a folder; give a file name"
    elif problem is None and out.exists() and not force:
        problem = "--out: the file exists; use --force to overwrite it"
    elif problem is None and out.resolve() == case.resolve():
        problem = "--out: would overwrite the study file itself"
    if problem is not None:
        raise InputError(out, [Problem(problem)])


def write_samples(result: StudyResult, out: Path, force: bool) -> None:
    """Every sample to ``out``: CSV, or Parquet (pyarrow), atomically."""
    from mdcalc.input.files import write_atomic

    if out.suffix.lower() == ".csv":
        write_atomic(out, to_csv(result), replace=force, option="--out: ")
    else:
        write_atomic(out, lambda tmp: write_parquet(result, tmp), replace=force, option="--out: ")
