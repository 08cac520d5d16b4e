"""A study's outcome as a rich report, JSON, a table of every sample (CSV or
Parquet) and charts (histogram and CDF of each result, Sobol or rank-correlation
bars)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from mdcalc.errors import InputError, Problem
from mdcalc.output.report import format_seconds, format_value
from mdcalc.runs.study import StudyResult
from mdcalc.runs.study.summary import PERCENTILES, Sobol

#: Version of the study JSON document (``"kind": "study"``).
FORMAT = 1


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
                "unit": item.unit,
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
                "unit": s.unit,
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
                "unit": e.unit,
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


def render_rich(result: StudyResult, console: Any) -> None:
    from rich.table import Table

    from mdcalc.output.text import print_titled

    plan, spec, ev = result.plan, result.plan.spec, result.evaluated
    title = plan.case.data.get("title") or plan.problem
    n = len(result.samples)
    console.print(f"[bold]Study: {title}[/bold]")
    console.print(
        f"{plan.problem}, {n:,} samples ({spec.sampler}, seed {spec.seed}), {result.how}\n"
        f"{format_seconds(result.seconds)} in all: set-up {format_seconds(result.setup_seconds)}, "
        f"samples {format_seconds(result.sampling_seconds)} "
        f"({result.samples_per_second:,.0f} samples/s)"
        + (
            f", Sobol {format_seconds(result.sensitivity_seconds)}"
            if result.sensitivity_runs
            else ""
        ),
        highlight=False,
    )
    inputs = Table(title="Inputs", title_justify="left")
    for label in ("key", "distribution", "drawn min", "drawn max"):
        inputs.add_column(label, justify="left" if label in ("key", "distribution") else "right")
    for j, item in enumerate(plan.inputs):
        column = result.samples[:, j]
        inputs.add_row(
            item.key,
            item.dist.describe(item.unit),
            format_value(float(column.min())),
            format_value(float(column.max())),
        )
    print_titled(console, inputs)
    table = Table(title="Results", title_justify="left")
    labels = ["result", "unit", "mean", "sd", *(f"P{p}" for p in PERCENTILES), "min", "max"]
    for label in labels:
        table.add_column(label, justify="left" if label in ("result", "unit") else "right")
    for key, s in result.stats.items():
        if s is None:
            table.add_row(key, result.units.get(key, ""), *["—"] * (len(labels) - 2))
            continue
        numbers = [s.mean, s.sd, *s.percentiles.values(), s.low, s.high]
        table.add_row(key, s.unit, *(format_value(v) for v in numbers))
    print_titled(console, table)
    if result.limits:
        limits = Table(title="Limits", title_justify="left")
        for label in ("result", "exceeded when", "samples", "probability", "95 % interval", ""):
            limits.add_column(label, justify="right" if label in ("samples",) else "left")
        for e in result.limits:
            limits.add_row(
                e.key,
                f"{e.text} {e.unit}".strip(),
                f"{e.exceeded:,} of {e.of:,}",
                format_value(e.probability, 4) if math.isfinite(e.probability) else "—",
                f"{format_value(e.low, 3)} … {format_value(e.high, 3)}",
                e.note,
            )
        print_titled(console, limits)
    if result.sensitivity:
        per_design = spec.sensitivity_samples // max(result.sensitivity_replicates, 1)
        sens = Table(
            title=(
                f"Sobol indices ({result.sensitivity_runs:,} runs, SALib: "
                f"{result.sensitivity_replicates} designs × {per_design:,} base samples; ± 95 %)"
            ),
            title_justify="left",
        )
        for label in ("result", "input", "first order S1", "total ST"):
            sens.add_column(label, justify="left" if label in ("result", "input") else "right")
        for sob in result.sensitivity:
            for name in sob.first:
                sens.add_row(
                    sob.key,
                    name,
                    f"{sob.first[name]:.3f} ± {sob.first_conf[name]:.3f}",
                    f"{sob.total[name]:.3f} ± {sob.total_conf[name]:.3f}",
                )
            if sob.note:  # no indices, or indices from fewer designs
                sens.add_row(sob.key, "—", sob.note, "")
        print_titled(console, sens)
    failed = sum(ev.counts.values())
    if failed:
        console.print(f"[yellow]{failed:,} of {n:,} samples gave no values:[/yellow]")
        for kind, count in ev.counts.items():
            console.print(f"  {kind}: {count:,}", highlight=False, markup=False)
            for reason in ev.reasons.get(kind, []):
                console.print(f"    {reason}", highlight=False, markup=False)
    else:
        console.print(f"every sample answered ({n:,})", style="dim")
    if ev.note:
        console.print(ev.note, style="dim")


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
            for bound in (limits[key].above, limits[key].below):
                if bound is not None:
                    marks.append(Mark("x", bound, "limit"))
        out.append(
            Chart(
                f"{key}: histogram of {finite.size:,} samples",
                f"{key}{unit}",
                "probability density",
                [Series("", edges.tolist(), [*density.tolist(), 0.0], "step")],
                marks,
            )
        )
        step = max(1, finite.size // 2000)
        xs = finite[::step]
        ys = (np.arange(finite.size)[::step] + 1) / finite.size
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
