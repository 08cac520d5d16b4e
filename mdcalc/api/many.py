"""Many scenes from Python: a study over the scatter of a case's inputs and a sweep
over a grid, as ``mdcalc study`` and ``mdcalc sweep`` run them (the same plans,
kernels, pool or dask cluster)."""

from __future__ import annotations

import json
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from typing import Any


@contextmanager
def _mapper(scheduler: str | None, jobs: int) -> Iterator[Any]:
    """This machine's process pool (``jobs`` 0: one per core), or a dask cluster."""
    from mdcalc.runs.cluster import executor, scheduler_of
    from mdcalc.runs.pool import default_jobs

    with executor(scheduler_of(scheduler), jobs or default_jobs(1 << 30)) as mapper:
        yield mapper


class StudyResult:
    """A study run: every sample's inputs and results, the statistics, the limits'
    exceedance probabilities and the Sobol indices, as ``mdcalc study --json``."""

    def __init__(self, result: Any) -> None:
        #: The command line's result (:class:`mdcalc.runs.study.StudyResult`).
        self.result = result
        self.problem: str = result.plan.problem
        self.keys: list[str] = list(result.keys)
        self.units: dict[str, str] = dict(result.units)

    def __repr__(self) -> str:
        return f"<mdcalc.StudyResult {self.problem}: {len(self.result.samples):,} samples>"

    @property
    def samples(self) -> dict[str, Any]:
        """Each drawn input and each result over the samples (numpy arrays; NaN where
        a sample gave no value), and ``status`` (each sample's exit code)."""
        from mdcalc.runs.study.output import to_columns

        _, columns = to_columns(self.result)
        names = [i.key for i in self.result.plan.inputs] + self.keys + ["status"]
        return dict(zip(names, columns, strict=True))

    def to_frame(self) -> Any:
        """:attr:`samples` as a pandas DataFrame (pandas must be installed)."""
        import pandas as pd

        return pd.DataFrame(self.samples)

    def to_dict(self) -> dict[str, Any]:
        """The JSON of ``mdcalc study --json``: statistics, limits, Sobol indices."""
        from mdcalc.runs.study.output import to_json

        loaded: dict[str, Any] = json.loads(to_json(self.result, None))
        return loaded

    @property
    def statistics(self) -> dict[str, Any]:
        """Per result: unit, count, mean, sd, p1 … p99, min, max (None: no value)."""
        stats: dict[str, Any] = self.to_dict()["results"]
        return stats

    @property
    def limits(self) -> list[dict[str, Any]]:
        limits: list[dict[str, Any]] = self.to_dict()["limits"]
        return limits

    @property
    def sobol(self) -> dict[str, Any] | None:
        """The Sobol indices by result and input (``S1``, ``ST`` and their 95 %
        half-widths), or None without ``sensitivity``."""
        sensitivity = self.to_dict()["sensitivity"]
        return None if sensitivity is None else dict(sensitivity["indices"])

    def to_html(self) -> str:
        """The report of ``mdcalc study --report FILE.html``."""
        from mdcalc.output.document import html_of
        from mdcalc.runs.study.output import study_document

        return html_of(study_document(self.result))

    def charts(self) -> list[Any]:
        """The study's charts as matplotlib Figures (``--plot``'s, one a chart)."""
        from mdcalc.output.plot import figure_of
        from mdcalc.runs.study.output import charts

        return [figure_of([chart]) for chart in charts(self.result)]

    def _repr_html_(self) -> str:
        return self.to_html()


def study(
    case: Any,
    *,
    samples: int | None = None,
    seed: int | None = None,
    sampler: str | None = None,
    jobs: int = 0,
    scheduler: str | None = None,
    time_limit: float | None = 60.0,
) -> StudyResult:
    """Run a study file (a case with a ``[study]`` table: a Path, TOML text or a
    dict), as ``mdcalc study``; ``samples``, ``seed`` and ``sampler`` replace the
    table's. ``time_limit`` applies to each sample."""
    from mdcalc.api.cases import case_of
    from mdcalc.errors import InputError, Problem
    from mdcalc.runs.study import run

    read = case_of(case, None)
    table = read.data.get("study")
    if not isinstance(table, dict):
        raise InputError(read.path, [Problem("no [study] table: this is a case; mdcalc.solve")])
    given = {"samples": samples, "seed": seed, "sampler": sampler}
    read.data["study"] = {**table, **{k: v for k, v in given.items() if v is not None}}
    with _mapper(scheduler, jobs) as mapper:
        return StudyResult(run(read, mapper, time_limit))


class SweepResult:
    """A sweep: one row per grid point, the varied keys then the results."""

    def __init__(self, table: Any, vectorized: bool) -> None:
        self.table = table
        self.vectorized = vectorized
        #: Each column (numpy arrays; NaN where a point has no value) by key.
        self.columns: dict[str, Any] = dict(table.columns)
        self.units: dict[str, str] = dict(table.units)
        #: Each point's exit code (0 computed, 3 no answer, 2 invalid, 70 a bug).
        self.status: Any = table.status

    def __repr__(self) -> str:
        return f"<mdcalc.SweepResult {len(self.status):,} points>"

    def to_frame(self) -> Any:
        import pandas as pd

        return pd.DataFrame({**self.columns, "status": self.status})


def sweep(
    case: Any,
    vary: Mapping[str, Sequence[float]],
    *,
    results: Sequence[str] = (),
    jobs: int = 0,
    scheduler: str | None = None,
    time_limit: float | None = 60.0,
) -> SweepResult:
    """Run ``case`` (a Path, TOML text or a dict) over the grid of the values given
    for each key (``{"vehicle.initial_speed_kmh": [40, 60, 80]}``; the last key
    varies fastest), as ``mdcalc sweep``; ``results``: the result keys (default:
    the key results)."""
    import math

    from mdcalc.api.cases import case_of
    from mdcalc.errors import InputError, Problem
    from mdcalc.runs.sweep import Vary, evaluate, plan

    varies = []
    for key, values in vary.items():
        try:
            listed = tuple(float(v) for v in values)
        except (TypeError, ValueError):
            listed = ()
        if not listed or not all(math.isfinite(v) for v in listed):
            raise InputError(f"vary {key}", [Problem("give one or more finite numbers")])
        varies.append(Vary(key, listed[0], listed[-1], len(listed), listed))
    grid = plan(case_of(case, None), varies)
    from mdcalc.runs.pool import jobs_for

    workers = jobs_for(jobs, grid.points)
    with _mapper(scheduler, workers) as mapper:
        table = evaluate(grid, list(results), workers, None, time_limit, mapper)
    return SweepResult(table, table.vectorized)
