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
    else:
        from scipy.stats import qmc

        engine: Any = (
            qmc.LatinHypercube(dims, rng=seed) if sampler == "lhs" else qmc.Sobol(dims, rng=seed)
        )
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # "balance properties" of n != 2^k
            u = engine.random(samples)
    return np.clip(u, U_MIN, U_MAX)


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


def saltelli(plan: Plan) -> Any:
    """The Saltelli design of the Sobol analysis (SALib), N·(D + 2) samples, in the
    inputs' values."""
    import numpy as np

    try:
        from SALib.sample import sobol
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
    problem = salib_problem(plan)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        u = sobol.sample(
            problem, plan.spec.sensitivity_samples, calc_second_order=False, seed=plan.spec.seed
        )
    return values(plan, np.clip(u, U_MIN, U_MAX))


def salib_problem(plan: Plan) -> dict[str, Any]:
    """SALib's problem in probability space: each input uniform on [0, 1], mapped
    through its own inverse CDF by :func:`values`."""
    return {
        "num_vars": len(plan.inputs),
        "names": plan.keys,
        "bounds": [[0.0, 1.0]] * len(plan.inputs),
    }
