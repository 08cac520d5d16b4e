"""Run a study's samples: the problem's vectorized kernel where it has one, else
every sample as a case of its own (validated, solved under its time limit), on the
process pool or a dask cluster (:mod:`mdcalc.runs.cluster`).

The way is chosen once for the whole study, never per chunk: the kernel when it
takes the study's keys and results, otherwise point by point. Where every corner of
the box of drawn values validates, so does every sample (field bounds and the
problem's rules along the box); where some corner breaks a cross-field rule, each
block validates its rows and declines the invalid ones, which are then solved alone
(their validation says why) while the rest stay vectorized. So a result does not
depend on chunk sizes or on where a chunk ran.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from itertools import product
from typing import Any

from mdcalc.errors import EXIT_BUG, EXIT_INPUT, EXIT_NO_ANSWER, EXIT_OK, InputError
from mdcalc.input.casefile import CaseText, validate
from mdcalc.input.model import DECLINED
from mdcalc.runs.cluster import Mapper
from mdcalc.runs.kernel import (
    BLOCK,
    LOST,
    LOST_REASON,
    KernelChunk,
    LostBlock,
    kernel_parts,
)
from mdcalc.runs.study.spec import Plan

#: Samples per kernel call.
KERNEL_CHUNK = BLOCK
#: Inputs up to this many have their 2^k corners validated before the kernel runs.
MAX_CORNER_INPUTS = 12
#: Reasons kept per kind of failure (the rest are counted).
KEPT_REASONS = 5

#: Kinds of a sample that gave no values, by exit code; "budget" is a no-answer whose
#: reason is the time limit.
KINDS = {EXIT_NO_ANSWER: "no answer", EXIT_INPUT: "invalid scene", EXIT_BUG: "internal error"}
BUDGET = "over the time budget"


@dataclass
class Evaluated:
    """Every sample's results, in sample order."""

    values: dict[str, Any]  # result key -> float array (NaN: no value)
    status: Any  # int array: 0, 2, 3, 70 per sample
    counts: dict[str, int] = field(default_factory=dict)  # kind of failure -> samples
    reasons: dict[str, list[str]] = field(default_factory=dict)  # kind -> first reasons
    vectorized: bool = False
    shipped: str = ""  # where kernel blocks ran when not in this process (the mapper's)
    note: str = ""


def _chunk(plan: Plan, wanted: Sequence[str], check_rows: bool = False) -> KernelChunk:
    return KernelChunk(plan.problem, plan.case.path, plan.scene_data, plan.keys, wanted, check_rows)


class SampleRunner:
    """One sample as a case of its own: (exit code, values of the wanted keys, reason)."""

    def __init__(
        self, plan: Plan, wanted: Sequence[str], time_limit: float | None, alone: bool = False
    ) -> None:
        self.alone = alone  # each Methods table's reference alone (reference_only_fits)
        self.problem = plan.problem
        self.path = str(plan.case.path)
        self.scene = plan.scene_data
        self.locs = [item.loc for item in plan.inputs]
        self.wanted = list(wanted)
        self.time_limit = time_limit

    def __call__(self, row: Sequence[float]) -> tuple[int, list[float], str]:
        from mdcalc.input.casefile import set_key
        from mdcalc.runs.sweep import point_results

        data = copy.deepcopy(self.scene)
        for loc, value in zip(self.locs, row, strict=True):
            set_key(data, loc, float(value))
        code, values, message = point_results(
            (self.path, self.problem, data, self.time_limit, self.alone)
        )
        return code, [float(values.get(k, math.nan)) for k in self.wanted], message


def lost(row: Any, error: BaseException) -> tuple[int, list[float], str]:
    """A sample whose chunk was lost for good (its worker died past the retries)."""
    return EXIT_BUG, [], f"lost on the cluster: {type(error).__name__}: {error}"


def evaluate(
    plan: Plan,
    samples: Any,
    wanted: Sequence[str],
    mapper: Mapper,
    on_done: Callable[[int], None] | None = None,
    time_limit: float | None = None,
) -> Evaluated:
    """Every row of ``samples`` (one column per input): by the kernel where it can,
    else point by point on ``mapper``."""
    fits = _kernel_fits(plan, samples, wanted)
    if fits is not None:
        evaluated = _by_kernel(plan, samples, wanted, mapper, on_done, time_limit, fits)
        if evaluated is not None:
            return evaluated
        note = "the kernel declined some samples: every sample was solved on its own"
    else:
        note = ""
    evaluated = _by_points(plan, samples, wanted, mapper, on_done, time_limit)
    evaluated.note = note
    return evaluated


def _kernel_fits(plan: Plan, samples: Any, wanted: Sequence[str]) -> bool | None:
    """None where the problem has no kernel for these keys and results; else whether
    each row must be validated (False: every corner of the box of the drawn values
    validates, and so does every sample)."""
    from mdcalc.input.casefile import set_key
    from mdcalc.problems import PROBLEMS

    module = PROBLEMS[plan.problem].load()
    if getattr(module, "sweep", None) is None or len(plan.inputs) > MAX_CORNER_INPUTS:
        return None
    if len(samples) == 0:
        return None
    ends = [(float(samples[:, j].min()), float(samples[:, j].max())) for j in range(len(plan.keys))]
    check_rows = False
    for corner in product(*ends):
        data = copy.deepcopy(plan.scene_data)
        for item, value in zip(plan.inputs, corner, strict=True):
            set_key(data, item.loc, value)
        try:
            validate(module.Case, CaseText(plan.case.path, "", data))
        except (InputError, ArithmeticError):
            check_rows = True
            break
    import numpy as np

    if _chunk(plan, wanted, check_rows)(np.array(ends).T) is None:
        return None
    return check_rows


def _by_kernel(
    plan: Plan,
    samples: Any,
    wanted: Sequence[str],
    mapper: Mapper,
    on_done: Callable[[int], None] | None,
    time_limit: float | None,
    check_rows: bool = False,
) -> Evaluated | None:
    import numpy as np

    n = len(samples)
    blocks = [samples[i : i + KERNEL_CHUNK] for i in range(0, n, KERNEL_CHUNK)]
    parts, shipped = kernel_parts(_chunk(plan, wanted, check_rows), blocks, mapper)
    values = {k: np.empty(n) for k in wanted}
    declined = np.zeros(n, dtype=bool)
    lost = np.zeros(n, dtype=bool)
    lost_reasons: list[str] = []
    start = 0
    for block, part in zip(blocks, parts, strict=True):
        if part is None:
            return None
        if isinstance(part, LostBlock):  # its samples count as failed, with the reason
            lost[start : start + len(block)] = True
            for key in wanted:
                values[key][start : start + len(block)] = np.nan
            if len(lost_reasons) < KEPT_REASONS:
                lost_reasons.append(f"samples {start} to {start + len(block) - 1}: {part.reason}")
            start += len(block)
            if on_done is not None:
                on_done(len(block))
            continue
        for key in wanted:
            values[key][start : start + len(block)] = part[key]
        declined[start : start + len(block)] = part[DECLINED]
        if LOST in part:  # a piece of the block lost on the pool: its rows failed
            where = np.flatnonzero(part[LOST])
            lost[start + where] = True
            if len(lost_reasons) < KEPT_REASONS:
                lost_reasons.append(
                    f"samples {start + where[0]} to {start + where[-1]} (in part): "
                    f"{part[LOST_REASON]}"
                )
        start += len(block)
        if on_done is not None:
            on_done(len(block) - int(part[DECLINED].sum()))
    status = np.zeros(n, dtype=int)
    infinite = np.zeros(n, dtype=bool)
    for column in values.values():
        infinite |= np.isinf(column)
    infinite &= ~declined
    evaluated = Evaluated(values, status, vectorized=True, shipped=shipped)
    if infinite.any():  # as the point-by-point run would say: no answer there
        status[infinite] = EXIT_NO_ANSWER
        for column in values.values():
            column[infinite] = np.nan
        evaluated.counts[KINDS[EXIT_NO_ANSWER]] = int(infinite.sum())
        evaluated.reasons[KINDS[EXIT_NO_ANSWER]] = ["a result is not a finite number"]
    if lost.any():
        status[lost] = EXIT_BUG
        evaluated.counts[KINDS[EXIT_BUG]] = int(lost.sum())
        evaluated.reasons[KINDS[EXIT_BUG]] = lost_reasons
    if declined.any():  # each solved alone, the rest of the block stays as it is
        where = np.flatnonzero(declined)
        alone = _by_points(plan, samples[where], wanted, mapper, on_done, time_limit, where)
        status[where] = alone.status
        for key in wanted:
            values[key][where] = alone.values[key]
        for kind, count in alone.counts.items():
            evaluated.counts[kind] = evaluated.counts.get(kind, 0) + count
            kept = evaluated.reasons.setdefault(kind, [])
            kept.extend(alone.reasons[kind][: KEPT_REASONS - len(kept)])
        evaluated.note = f"{len(where)} samples the kernel declined were solved one by one"
    return evaluated


def _by_points(
    plan: Plan,
    samples: Any,
    wanted: Sequence[str],
    mapper: Mapper,
    on_done: Callable[[int], None] | None,
    time_limit: float | None,
    indices: Any = None,
) -> Evaluated:
    """Every sample as a case of its own; ``indices`` numbers them in the study
    (default 0, 1, ...) for the reasons kept."""
    import numpy as np

    n = len(samples)
    values = {k: np.full(n, np.nan) for k in wanted}
    status = np.zeros(n, dtype=int)
    evaluated = Evaluated(values, status)
    rows = [tuple(map(float, row)) for row in samples.tolist()]
    done = (lambda: on_done(1)) if on_done is not None else None
    from mdcalc.problems import PROBLEMS
    from mdcalc.runs.sweep import reference_only_fits

    module = PROBLEMS[plan.problem].load()
    alone = reference_only_fits(plan.problem, module, plan.nominal, wanted, time_limit)
    runner = SampleRunner(plan, wanted, time_limit, alone)
    for index, (code, got, message) in enumerate(mapper(runner, rows, done, lost)):
        status[index] = code
        if code == EXIT_OK:  # a scene without an answer has no values to count
            for key, value in zip(wanted, got, strict=True):
                values[key][index] = value
        else:
            kind = BUDGET if "time budget" in message else KINDS.get(code, KINDS[EXIT_BUG])
            evaluated.counts[kind] = evaluated.counts.get(kind, 0) + 1
            kept = evaluated.reasons.setdefault(kind, [])
            if len(kept) < KEPT_REASONS:
                at = ", ".join(
                    f"{k} = {v:.6g}" for k, v in zip(plan.keys, rows[index], strict=True)
                )
                number = int(indices[index]) if indices is not None else index
                kept.append(f"sample {number} ({at}): {message}")
    return evaluated
