"""Periodic steady state of a linear system under a periodic ramp load.

The system is M·x'' + C·x' + K·x = F + s·u(τ) with constant loads F, a load shape s
and a scalar excitation u that rises linearly over each period and jumps back at
its end: u(τ) = u₀ + u₁·τ for τ in [0, T) (a sawtooth; the impulse variator's Π″).
K must be invertible (the system is held to the ground or to a driver).

Three ways to the periodic state, each with its own error:

* :func:`exact_periodic` -- closed form. A linear load has the particular solution
  x = a + b·τ (K·b = s·u₁, K·a = F + s·u₀ - C·b); the rest is e^{Aτ}·d in the first-
  order form, with the periodicity (I - e^{AT})·d = (b, 0)·T solved mode by mode,
  dᵢ = T·(V⁻¹p)ᵢ/(1 - e^{λᵢT}). Exact up to the eigensolver's round-off; a mode with
  e^{λT} = 1 (an undamped resonance with a harmonic of the load) has no periodic
  state and raises :class:`Unbounded`. Where two eigenvalues (nearly) meet -- a
  mode damped (nearly) critically, whose first-order matrix has no (well-
  conditioned) basis of eigenvectors -- e^{Aτ} is taken whole instead, by
  ``scipy.linalg.expm`` of the balanced B = S⁻¹·A·S: d = (I - e^{AT})⁻¹·(b, 0)·T,
  y = p₀ + p₁τ + S·e^{Bτ}·S⁻¹·d. Its error is then about the state's own
  sensitivity to an ulp of C and K (7·10⁻⁹ against 6·10⁻⁹ with modes 10⁴ apart).
* :func:`fourier_periodic` -- the static part plus K harmonics of the sawtooth,
  u - ū = -u₁·(T/π)·Σ sin(kΩτ)/k, each through the frequency response
  (K - k²Ω²M + ikΩC)⁻¹. The forcing's harmonics fall off as 1/k only, so a stiff
  system (natural frequencies far above Ω) needs many of them.
* :func:`~mdcalc.core.periodic_ode.ode_periodic` (its own module) -- time
  integration by shooting: the period map of a linear system is affine, so one
  period integrated from 2n + 1 starts gives the periodic start, and one more
  period its maxima (events on the derivative).

Maxima of an observable w·(x, x') over a period come from samples that resolve the
fastest mode, refined by regula falsi on the derivative (:func:`periodic_maximum`).

The parts: :mod:`.system` (the system and its errors), :mod:`.modes` (its modes),
:mod:`.closed` (the closed form, one system or a block), :mod:`.fourier`,
:mod:`.peaks` (maxima over a period).
"""

from __future__ import annotations

import numpy as np

from mdcalc.core.periodic.closed import (
    AS_GOOD_AS_FREE,
    BLOCK_CELLS,
    MEET,
    RESONANT,
    RUN,
    SOLVED,
    SPREAD,
    UNSEPARATED,
    Periodic,
    PeriodicBlock,
    exact_block,
    exact_periodic,
)
from mdcalc.core.periodic.fourier import FourierSeries, fourier_periodic
from mdcalc.core.periodic.peaks import (
    MAX_SAMPLES,
    REGULA_FALSI_STEPS,
    SAMPLES_PER_MODE_PERIOD,
    PeriodicMaximum,
    Sampler,
    periodic_maxima,
    periodic_maximum,
    samples_for,
)
from mdcalc.core.periodic.system import Observable, RampSystem, Unbounded, Unresolved

__all__ = [
    "AS_GOOD_AS_FREE",
    "BLOCK_CELLS",
    "MAX_SAMPLES",
    "MEET",
    "REGULA_FALSI_STEPS",
    "RESONANT",
    "RUN",
    "SAMPLES_PER_MODE_PERIOD",
    "SOLVED",
    "SPREAD",
    "UNSEPARATED",
    "FourierSeries",
    "Observable",
    "Periodic",
    "PeriodicBlock",
    "PeriodicMaximum",
    "RampSystem",
    "Sampler",
    "Unbounded",
    "Unresolved",
    "exact_block",
    "exact_periodic",
    "fourier_periodic",
    "maximum_of",
    "periodic_maxima",
    "periodic_maximum",
    "samples_for",
]


def maximum_of(
    solution: Periodic | FourierSeries, w: Observable, fastest: float
) -> PeriodicMaximum:
    """Maximum of w·y over a period of an exact or Fourier periodic state."""
    samples, resolved = samples_for(solution.period, fastest)
    sampled = None
    if isinstance(solution, FourierSeries):
        while samples <= 2 * solution.harmonics:
            samples *= 2
        sampled = solution.sampled(w, samples)
    # a Fourier series costs K complex exponentials per point: a long series refines
    # fewer candidates (it is never the reference; a missed peak is part of its error)
    candidates = 4096
    if isinstance(solution, FourierSeries):
        candidates = max(16, min(4096, 20_000 // solution.harmonics))
    if isinstance(solution, Periodic):  # the block path, on a block of one
        values, times, _, _ = solution.block().maxima(w, np.array([fastest]))
        return PeriodicMaximum(float(values[0]), float(times[0]), samples, resolved)
    value, time = periodic_maximum(
        lambda tau: solution.observe(w, tau),
        lambda tau: solution.rate(w, tau),
        solution.period,
        samples,
        sampled,
        candidates,
    )
    return PeriodicMaximum(value, time, samples, resolved)
