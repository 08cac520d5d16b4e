"""The draws of a study: all of them up front, from the seed alone.

Every sample's inputs are fixed before anything runs, so the results do not depend
on how the samples are split into chunks or where a chunk runs.
"""

from __future__ import annotations

import warnings
from typing import Any

from mdcalc.errors import InputError, Problem
from mdcalc.runs.study.spec import U_MAX, U_MIN, Plan


def unit_draws(sampler: str, samples: int, dims: int, seed: int) -> Any:
    """(samples, dims) probabilities in [U_MIN, U_MAX]: ``random`` (numpy's PCG64),
    ``lhs`` (Latin hypercube) or ``sobol`` (scrambled Sobol' points, scipy.stats.qmc)."""
    import numpy as np

    if sampler == "random":
        u = np.random.default_rng(seed).random((samples, dims))
    elif sampler == "lhs":
        u = latin_hypercube(samples, dims, seed)
    else:
        from scipy.stats import qmc

        engine = qmc.Sobol(dims, rng=seed)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # "balance properties" of n != 2^k
            u = engine.random(samples)
    return np.clip(u, U_MIN, U_MAX)


def latin_hypercube(samples: int, dims: int, seed: int) -> Any:
    """``scipy.stats.qmc.LatinHypercube(dims, rng=seed).random(samples)`` (scrambled,
    strength 1), its few lines in numpy: each column a random permutation of the
    strata 1 … n, less a uniform draw in each, over n, from the same generator.
    Importing scipy.stats for it took 0.5 s, a third of a 10⁶-sample braking study;
    tests/test_study.py holds the draws to scipy's bit for bit."""
    import numpy as np

    # scipy's engine takes a child of the seed's sequence (a Generator it may own)
    rng = np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])
    jitter = rng.uniform(size=(samples, dims))
    strata = np.tile(np.arange(1, samples + 1), (dims, 1))
    for column in strata:
        rng.shuffle(column)
    return (strata.T - jitter) / samples


def values(plan: Plan, u: Any) -> Any:
    """The inputs' values at probabilities ``u``: one column per input."""
    import numpy as np

    out = np.empty_like(u)
    for j, item in enumerate(plan.inputs):
        out[:, j] = item.dist.ppf(u[:, j])
    return out


def draws(plan: Plan) -> Any:
    """The Monte Carlo samples of the study: (samples, inputs)."""
    spec = plan.spec
    return values(plan, unit_draws(spec.sampler, spec.samples, len(plan.inputs), spec.seed))


#: Independent scrambled designs of a Sobol analysis, at most; the spread of their
#: estimates is the interval (randomized QMC). SALib's bootstrap treats the points of
#: one Sobol' design as independent draws: its intervals came out 3 to 51 times the
#: real scatter of the indices over seeds (docs/studies.md, Sensitivity).
SOBOL_REPLICATES = 16
#: Base samples of one replicate, at least (the estimators standardize by the
#: replicate's own variance).
MIN_REPLICATE_SAMPLES = 8


def sobol_replicates(base_samples: int) -> int:
    """How many independent designs ``base_samples`` (a power of 2) divides into:
    SOBOL_REPLICATES, fewer where a replicate would get under MIN_REPLICATE_SAMPLES
    (at least 2: one design has no spread)."""
    return max(2, min(SOBOL_REPLICATES, base_samples // MIN_REPLICATE_SAMPLES))


def saltelli(plan: Plan) -> tuple[Any, int]:
    """The design of the Sobol analysis and its number of replicates R: R independent
    scrambled Saltelli designs (SALib), each of N/R base samples and N/R·(D + 2) runs,
    one after the other, in the inputs' values (N = ``sensitivity_samples``, D
    inputs). The replicates' seeds come from the study's seed alone."""
    try:
        import SALib  # noqa: F401
    except ImportError:
        raise InputError(
            plan.case.path,
            [
                Problem(
                    "sensitivity = true needs SALib, which is not installed: "
                    "pip install 'mdcalc[sensitivity]'",
                    "study.sensitivity",
                    plan.case.line_of(("study", "sensitivity")),
                )
            ],
        ) from None
    u, replicates = sobol_design(salib_problem(plan), plan.spec.sensitivity_samples, plan.spec.seed)
    return values(plan, u), replicates


def sobol_design(problem: dict[str, Any], base_samples: int, seed: int) -> tuple[Any, int]:
    """(probabilities, R): R independent scrambled Saltelli designs of SALib in the
    unit cube of ``problem``, one after the other, ``base_samples`` // R base samples
    each; the designs' seeds from ``seed`` alone (numpy's SeedSequence)."""
    import numpy as np
    from SALib.sample import sobol

    replicates = sobol_replicates(base_samples)
    seeds = np.random.SeedSequence(seed).generate_state(replicates).tolist()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        designs = [
            sobol.sample(problem, base_samples // replicates, calc_second_order=False, seed=s)
            for s in seeds
        ]
    return np.clip(np.concatenate(designs), U_MIN, U_MAX), replicates


def salib_problem(plan: Plan) -> dict[str, Any]:
    """SALib's problem in probability space: each input uniform on [0, 1], mapped
    through its own inverse CDF by :func:`values`."""
    return {
        "num_vars": len(plan.inputs),
        "names": plan.keys,
        "bounds": [[0.0, 1.0]] * len(plan.inputs),
    }
