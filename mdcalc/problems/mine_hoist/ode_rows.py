"""The ODE rows of the Methods table: their evaluation budget and the runs."""

from __future__ import annotations

import math

import numpy as np

from mdcalc.core import chain as chains
from mdcalc.methods import NotApplicable
from mdcalc.problems.mine_hoist.modal import Dynamics
from mdcalc.problems.mine_hoist.scene import Scene

#: Right-hand-side evaluations per period of the fastest mode, measured on the
#: seed's case, to predict an ODE row's cost before running it.
EVALUATIONS_PER_FAST_PERIOD = {
    ("DOP853", 1e-3): 45,
    ("DOP853", 1e-6): 105,
    ("DOP853", 1e-9): 205,
    ("Radau", 1e-3): 90,
    ("Radau", 1e-6): 420,
    ("Radau", 1e-9): 2200,
}

EVALUATION_BUDGET = 60_000

#: β_max/β_min from which the scene counts as stiff (and Radau is the ODE reference).
STIFF_RATIO = 100.0


def ode_evaluations(dyn: Dynamics, method: str, rtol: float) -> int:
    """Predicted right-hand-side evaluations of an ODE row over the first swing."""
    return int(followed_periods(dyn, method, rtol) * EVALUATIONS_PER_FAST_PERIOD[(method, rtol)])


def followed_frequency(dyn: Dynamics, method: str, rtol: float) -> float:
    """The fastest mode a solver has to follow: for an explicit one the fastest of
    all (its stability demands it); an implicit one steps over modes whose
    amplitude in μ is below its tolerance."""
    frequencies = dyn.modes.frequencies
    if method != "Radau":
        return frequencies[-1]
    b12, b23 = dyn.coefficients(0), dyn.coefficients(1)
    return max(
        (w for j, w in enumerate(frequencies) if max(abs(b12[j]), abs(b23[j])) > rtol),
        default=frequencies[0],
    )


def followed_periods(dyn: Dynamics, method: str, rtol: float) -> float:
    return dyn.period * followed_frequency(dyn, method, rtol) / (2.0 * math.pi) + 5.0


def ode_first_swing(
    scene: Scene, dyn: Dynamics, method: str, rtol: float, ladder: bool = False
) -> dict[str, float]:
    """μ₁₂ and μ₂₃ in the first swing by ``method`` at ``rtol``: a row of the Methods
    table (not run where its predicted cost is over EVALUATION_BUDGET), or with
    ``ladder`` a rung of --work-precision (any integrator and tolerance, bounded by
    the time budget alone)."""
    from mdcalc.core.ode import TooManySteps, linear_oscillator_maxima

    estimate = 0 if ladder else ode_evaluations(dyn, method, rtol)
    if estimate > EVALUATION_BUDGET:
        raise NotApplicable(
            f"about {estimate:,} evaluations (the budget is {EVALUATION_BUDGET:,}): the "
            f"solver must follow the mode at {followed_frequency(dyn, method, rtol):.5g} "
            f"rad/s through {followed_periods(dyn, method, rtol):,.0f} periods in the first "
            "swing"
        )
    a, f = chains.moment_equations(scene.chain, scene.torques)
    r = np.array(dyn.static)
    try:
        peaks, _, _ = linear_oscillator_maxima(
            a * r[None, :] / r[:, None],  # in units of R: μ'' = -D⁻¹AD·μ + D⁻¹f
            f / r,
            dyn.period,
            rtol,
            method,
            max_evaluations=2 * EVALUATION_BUDGET if not ladder else 10**9,
        )
    except TooManySteps as stopped:
        raise NotApplicable(str(stopped)) from None
    return {"mu12": peaks[0], "mu23": peaks[1]}
