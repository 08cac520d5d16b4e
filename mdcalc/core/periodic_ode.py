"""The periodic state of a ramp-loaded linear system by time integration
(shooting): the third way of :mod:`mdcalc.core.periodic`, the one with an ODE
solver's own error, that the variator's Methods table sets against the closed form."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mdcalc.core.periodic import Observable, RampSystem

#: solve_ivp methods that take a Jacobian.
IMPLICIT = ("Radau", "BDF", "LSODA")


@dataclass(frozen=True)
class OdePeriodic:
    maxima: list[float]  # per observable, over the periodic state's period
    evaluations: int


def ode_periodic(
    system: RampSystem,
    observables: list[Observable],
    rtol: float,
    method: str,
) -> OdePeriodic:
    """Periodic state by shooting: the period map of a linear system is affine,
    y(T) = Φ·y(0) + γ. One integration over a period from y = 0 (γ) and from the
    2n unit states (the columns of Φ) gives the periodic start from
    (I - Φ)·y₀ = γ; one more period from y₀ gives the maxima, from events on the
    derivative of each observable. No transient has to die out: lightly damped
    and undamped systems cost the same."""
    from mdcalc.core.ode import advance

    a = system.first_order()
    t = system.period
    n2 = 2 * system.size
    g0, g1 = system.load(0.0), system.load(t) - system.load(0.0)
    g1 = g1 / t

    def bundle(tau: float, z: np.ndarray) -> np.ndarray:
        columns = a @ z.reshape(n2, n2 + 1)
        columns[:, 0] += g0 + g1 * tau
        return columns.ravel()

    # the response's scale: the static part, or the swing of the ramp's own part
    swing = np.linalg.solve(system.stiffness, system.shape * system.start)
    scale = max(float(np.max(np.abs(system.static()))), float(np.max(np.abs(swing))), 1e-300)
    # the forced column is on the scale of the response, the unit columns on 1
    atol = np.tile(np.concatenate([[scale], np.ones(n2)]), n2) * rtol * 1e-3
    starts = np.zeros((n2, n2 + 1))
    starts[:, 1:] = np.eye(n2)
    jac = np.kron(a, np.eye(n2 + 1)) if method in IMPLICIT else None
    segment = advance(bundle, 0.0, starts.ravel(), t, rtol=rtol, atol=atol, method=method, jac=jac)
    end = segment.y.reshape(n2, n2 + 1)
    gamma, phi = end[:, 0], end[:, 1:]
    y0 = np.linalg.solve(np.eye(n2) - phi, gamma)

    def rhs(tau: float, y: np.ndarray) -> np.ndarray:
        return a @ y + g0 + g1 * tau

    watch = [(_rate_event(a, g0, g1, w), -1) for w in observables]
    last = advance(
        rhs,
        0.0,
        y0,
        t,
        rtol=rtol,
        atol=scale * rtol * 1e-3,
        method=method,
        watch=watch,
        jac=a if method in IMPLICIT else None,
    )
    maxima = [max(float(w @ y0), float(w @ last.y)) for w in observables]
    for index, _time, state in last.hits:
        maxima[index] = max(maxima[index], float(observables[index] @ state))
    return OdePeriodic(maxima, segment.nfev + last.nfev)


def _rate_event(
    a: np.ndarray, g0: np.ndarray, g1: np.ndarray, w: Observable
) -> Callable[[float, np.ndarray], float]:
    def event(tau: float, y: np.ndarray) -> float:
        return float(w @ (a @ y + g0 + g1 * tau))

    return event
