"""What a study's samples say: statistics of each result, the probability of
exceeding each limit with its interval, and Sobol indices (SALib)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

#: The percentiles of each result's summary.
PERCENTILES = (1, 5, 50, 95, 99)
#: Fewer exceedances than this (or fewer samples within the limit): the interval
#: rests on a handful of samples and the report says so.
FEW = 10
Z95 = 1.959963984540054  # the 97.5 % point of the standard normal


@dataclass
class Stats:
    key: str
    unit: str
    count: int  # samples with a value
    mean: float
    sd: float
    percentiles: dict[int, float]
    low: float
    high: float


def stats(key: str, unit: str, column: Any) -> Stats | None:
    """Mean, standard deviation (n - 1), percentiles (linear interpolation), min and
    max over the samples that have a value; None if none has."""
    import numpy as np

    finite = column[np.isfinite(column)]
    if finite.size == 0:
        return None
    sd = float(np.std(finite, ddof=1)) if finite.size > 1 else 0.0
    points = np.percentile(finite, PERCENTILES)
    return Stats(
        key,
        unit,
        int(finite.size),
        float(np.mean(finite)),
        sd,
        {p: float(v) for p, v in zip(PERCENTILES, points, strict=True)},
        float(finite.min()),
        float(finite.max()),
    )


@dataclass
class Exceedance:
    key: str
    unit: str
    above: float | None
    below: float | None
    exceeded: int
    of: int  # samples with a value
    probability: float
    low: float  # 95 % Wilson interval
    high: float
    note: str = ""

    @property
    def text(self) -> str:
        parts = []
        if self.below is not None:
            parts.append(f"< {self.below:g}")
        if self.above is not None:
            parts.append(f"> {self.above:g}")
        return " or ".join(parts)


def wilson(k: int, n: int, z: float = Z95) -> tuple[float, float]:
    """The Wilson score interval of a proportion k/n (good at k = 0 and k = n too)."""
    if n == 0:
        return 0.0, 1.0
    p = k / n
    denominator = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / denominator
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / denominator
    return max(0.0, centre - half), min(1.0, centre + half)


def exceedance(
    key: str, unit: str, column: Any, above: float | None, below: float | None
) -> Exceedance:
    """The share of the samples with a value that lie outside the limit. Samples
    without a value are not counted (the report notes how many there were)."""
    import numpy as np

    finite = column[np.isfinite(column)]
    out = np.zeros(finite.size, dtype=bool)
    if above is not None:
        out |= finite > above
    if below is not None:
        out |= finite < below
    k, n = int(out.sum()), int(finite.size)
    low, high = wilson(k, n)
    result = Exceedance(key, unit, above, below, k, n, k / n if n else math.nan, low, high)
    if n == 0:
        result.note = "no sample has this result"
    elif k == 0:
        result.note = f"no sample exceeded: below {high:.2g} (95 %); more samples narrow it"
    elif k < FEW:
        result.note = f"only {k} samples exceeded: too few to trust the estimate; more samples"
    elif n - k < FEW:
        result.note = f"only {n - k} samples stayed within: too few to trust the estimate"
    if 0 < n < column.size:
        missing = f"of the {n:,} samples with a value; {column.size - n:,} had none"
        result.note = f"{result.note}; {missing}" if result.note else missing
    return result


@dataclass
class Sobol:
    """First-order and total indices of one result with their 95 % intervals."""

    key: str
    first: dict[str, float] = field(default_factory=dict)
    first_conf: dict[str, float] = field(default_factory=dict)
    total: dict[str, float] = field(default_factory=dict)
    total_conf: dict[str, float] = field(default_factory=dict)
    note: str = ""


def sobol(
    key: str, names: list[str], problem: dict[str, Any], column: Any, replicates: int
) -> Sobol:
    """First-order and total indices from ``replicates`` independent Saltelli designs
    laid one after the other in ``column``: SALib's ``sobol.analyze`` (Saltelli 2010
    and Jansen estimators) on each, their mean, and a 95 % Student-t interval from
    their spread (randomized quasi-Monte Carlo); a note instead where a sample has no
    value or the result does not vary."""
    import statistics
    import warnings

    import numpy as np

    out = Sobol(key)
    missing = int((~np.isfinite(column)).sum())
    if missing:
        out.note = f"{missing} samples of the design have no value: no indices"
        return out
    spread = float(np.std(column))
    if spread <= 1e-12 * max(float(np.max(np.abs(column))), 1e-300):  # rounding only
        out.note = "the result does not vary over the inputs: no indices"
        return out
    from SALib.analyze import sobol as analyze
    from scipy.stats import t as student

    first, total = [], []
    flat = 0  # designs whose result varies by rounding only: their indices are 0/0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for part in np.split(np.asarray(column, dtype=float), replicates):
            if float(np.std(part)) <= 1e-12 * max(float(np.max(np.abs(part))), 1e-300):
                flat += 1
                continue
            # The bootstrap's intervals are not used: num_resamples at its least.
            found = analyze.analyze(problem, part, calc_second_order=False, num_resamples=2, seed=0)
            first.append(np.asarray(found["S1"], dtype=float))
            total.append(np.asarray(found["ST"], dtype=float))
    used = replicates - flat
    if used < 2:
        out.note = (
            f"the result changed in {used} of the {replicates} designs: no indices "
            "(a rare change needs more sensitivity_samples)"
        )
        return out
    if flat:
        out.note = (
            f"the result did not change within {flat} of the {replicates} designs: the "
            f"indices rest on the other {used} and may be off (more sensitivity_samples)"
        )
    scale = float(student.ppf(0.975, used - 1)) / math.sqrt(used)
    for j, name in enumerate(names):
        s1 = [float(r[j]) for r in first]
        st = [float(r[j]) for r in total]
        out.first[name] = statistics.fmean(s1)
        out.first_conf[name] = scale * statistics.stdev(s1)
        out.total[name] = statistics.fmean(st)
        out.total_conf[name] = scale * statistics.stdev(st)
    return out
