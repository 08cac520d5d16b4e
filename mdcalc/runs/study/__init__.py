"""``mdcalc study``: a scene's results over the scatter of its inputs.

A study file is a case file of its problem with a ``[study]`` table
(:mod:`.spec`); the samples are drawn up front (:mod:`.sample`), run by the
problem's kernel or one by one on a pool or a dask cluster (:mod:`.evaluate`) and
summarized (:mod:`.summary`); :mod:`.output` renders the outcome.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from mdcalc.errors import InputError, Problem
from mdcalc.input.casefile import CaseText
from mdcalc.runs.cluster import Mapper
from mdcalc.runs.study.evaluate import Evaluated, evaluate
from mdcalc.runs.study.spec import Plan, is_study, plan
from mdcalc.runs.study.summary import Exceedance, Sobol, Stats, exceedance, sobol, stats

__all__ = ["StudyResult", "is_study", "plan", "run", "Plan"]


@dataclass
class StudyResult:
    plan: Plan
    keys: list[str]  # the results summarized
    units: dict[str, str]
    samples: Any  # (samples, inputs)
    evaluated: Evaluated
    how: str
    seconds: float  # the whole study, from reading the plan to the last summary [s]
    stats: dict[str, Stats | None] = field(default_factory=dict)
    limits: list[Exceedance] = field(default_factory=list)
    sensitivity: list[Sobol] = field(default_factory=list)
    sensitivity_runs: int = 0
    sensitivity_replicates: int = 0
    sensitivity_how: str = ""
    time_limit: float | None = None
    #: Imports, quantity strings, the plan, the nominal scene and the draws [s].
    setup_seconds: float = 0.0
    #: The samples' evaluation [s] (the Sobol design's is sensitivity_seconds).
    sampling_seconds: float = 0.0
    #: The Sobol design's evaluation and the indices [s].
    sensitivity_seconds: float = 0.0
    #: The nominal scene solved: (the solver's result or None, its report).
    scene: tuple[Any, Any] | None = None

    @property
    def samples_per_second(self) -> float:
        """The study's samples (not the Sobol design's runs) over their evaluation."""
        return len(self.samples) / max(self.sampling_seconds, 1e-9)

    def values(self) -> dict[str, float]:
        """Every summary number by a flat key (what ``[expect]`` may name):
        ``<result>.mean``, ``.sd``, ``.p1`` … ``.p99``, ``.min``, ``.max``,
        ``<result>.exceedance``, ``<result>.S1.<input>``, ``<result>.ST.<input>``,
        ``failed`` (samples without an answer)."""
        out: dict[str, float] = {}
        for key, s in self.stats.items():
            if s is None:
                continue
            out |= {f"{key}.mean": s.mean, f"{key}.sd": s.sd, f"{key}.min": s.low}
            out |= {f"{key}.p{p}": v for p, v in s.percentiles.items()}
            out[f"{key}.max"] = s.high
        for limit in self.limits:
            out[f"{limit.key}.exceedance"] = limit.probability
        for indices in self.sensitivity:
            out |= {f"{indices.key}.S1.{k}": v for k, v in indices.first.items()}
            out |= {f"{indices.key}.ST.{k}": v for k, v in indices.total.items()}
        out["failed"] = float(sum(self.evaluated.counts.values()))
        return out


def run(
    case: CaseText,
    mapper: Mapper,
    time_limit: float | None = None,
    on_done: Callable[[int], None] | None = None,
    on_total: Callable[[int], None] | None = None,
) -> StudyResult:
    """Plan, draw, run and summarize a study file already read. ``time_limit``
    applies to each sample; ``on_done(n)`` is told of samples finished and
    ``on_total(n)`` of the samples to come (for a progress bar)."""
    from mdcalc.problems import PROBLEMS
    from mdcalc.runs.runner import solve_model
    from mdcalc.runs.study.sample import draws, salib_problem, saltelli
    from mdcalc.runs.sweep import key_results

    start = time.perf_counter()
    study = plan(case)
    spec = study.spec
    module = PROBLEMS[study.problem].load()
    nominal = study.nominal
    scene = solve_model(study.problem, module, nominal, time_limit)
    asked = list(spec.results or [])
    if asked:
        asked += [k for k in spec.limits if k not in asked]
    where = str(case.path)
    keys, units = key_results(
        study.problem, module, nominal, asked, where, time_limit, report=scene[1]
    )
    if spec.results is None:  # the key results, and each limit's result
        unknown = [k for k in spec.limits if k not in units]
        if unknown:
            key_results(study.problem, module, nominal, unknown, where, report=scene[1])
        keys += [k for k in spec.limits if k not in keys]
    if not keys:
        raise InputError(
            case.path, [Problem("the nominal scene has no numeric result to study", "study")]
        )
    samples = draws(study)
    design, replicates = saltelli(study) if spec.sensitivity else (None, 0)
    if on_total is not None:
        on_total(len(samples) + (0 if design is None else len(design)))
    sampling = time.perf_counter()
    evaluated = evaluate(study, samples, keys, mapper, on_done, time_limit)
    done = time.perf_counter()
    how = _how(evaluated, mapper)
    result = StudyResult(study, keys, units, samples, evaluated, how, 0.0, time_limit=time_limit)
    result.scene = scene
    result.setup_seconds, result.sampling_seconds = sampling - start, done - sampling
    for key in keys:
        result.stats[key] = stats(key, units.get(key, ""), evaluated.values[key])
    for key, limit in spec.limits.items():
        column = evaluated.values[key]
        result.limits.append(exceedance(key, units.get(key, ""), column, limit.above, limit.below))
    if design is not None:
        sensitivity = time.perf_counter()
        on_design = evaluate(study, design, keys, mapper, on_done, time_limit)
        result.sensitivity_runs = len(design)
        result.sensitivity_replicates = replicates
        result.sensitivity_how = _how(on_design, mapper)
        problem = salib_problem(study)
        for key in keys:
            result.sensitivity.append(
                sobol(key, study.keys, problem, on_design.values[key], replicates)
            )
        result.sensitivity_seconds = time.perf_counter() - sensitivity
    result.seconds = time.perf_counter() - start
    return result


def _how(evaluated: Evaluated, mapper: Mapper) -> str:
    """How the samples ran: the kernel (here, or in blocks on the pool or a cluster),
    or one by one."""
    if not evaluated.vectorized:
        return f"one by one, {mapper.description}"
    return (
        f"vectorized kernel, blocks on {evaluated.shipped}"
        if evaluated.shipped
        else ("vectorized kernel")
    )
