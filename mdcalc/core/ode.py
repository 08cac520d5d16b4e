"""ODE reference runs: one place that calls scipy's solve_ivp, with timing.

scipy is imported inside the functions, so a closed-form scene never pays for it.
Problems integrate piecewise-smooth models segment by segment (a force switched
off, a load lifting off the ground): :func:`advance` integrates one smooth segment
up to its end time or to the first terminal event, and returns where it stopped.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np

# numpy and scipy are imported inside the functions: importing this module (for
# IMPORTS or pick_solver) costs a closed-form scene nothing.
Rhs = Callable[[float, "np.ndarray"], "np.ndarray"]
Event = Callable[[float, "np.ndarray"], float]

#: Solvers by stiffness: explicit for oscillatory non-stiff models, implicit for
#: stiff ones (stiffness ratios of 1e3 and more).
EXPLICIT_LOOSE = "RK45"
EXPLICIT_TIGHT = "DOP853"
IMPLICIT = "Radau"

#: What an ODE method imports (see mdcalc.methods.Method.imports).
IMPORTS = ("scipy.integrate",)

#: scipy's integrators, explicit first, and their families (how a work-precision
#: diagram draws them): the methods of a work-precision ladder.
FAMILIES = {
    "RK23": "explicit",
    "RK45": "explicit",
    "DOP853": "explicit",
    "Radau": "implicit",
    "BDF": "implicit",
    "LSODA": "switching",  # to its implicit BDF when stiff
}
SOLVERS = tuple(FAMILIES)
#: Those that take a Jacobian (LSODA switches to its implicit BDF when stiff).
TAKES_JACOBIAN = ("Radau", "BDF", "LSODA")


class _Forced(threading.local):
    """The integrator every :func:`advance` of this thread uses (None: each run's
    own choice), and the right-hand-side evaluations counted meanwhile."""

    method: str | None = None
    evaluations: int = 0


_forced = _Forced()


def forced() -> str | None:
    """The integrator :func:`integrator` imposes here (None outside it)."""
    return _forced.method


@contextmanager
def integrator(method: str) -> Iterator[_Forced]:
    """Run the body's ODE runs with ``method`` whatever they would pick (a rung of a
    work-precision ladder), counting their right-hand-side evaluations in the
    yielded value's ``evaluations``: every call, those of a finite-difference
    Jacobian included (scipy's ``nfev`` leaves Radau's and BDF's out)."""
    if method not in SOLVERS:
        raise ValueError(f"unknown integrator {method!r}")
    saved = _forced.method, _forced.evaluations
    _forced.method, _forced.evaluations = method, 0
    try:
        yield _forced
    finally:
        _forced.method, _forced.evaluations = saved


def pick_solver(rtol: float, stiff: bool = False) -> str:
    """The solver an ODE reference run uses for this tolerance and stiffness."""
    if stiff:
        return IMPLICIT
    return EXPLICIT_TIGHT if rtol < 1e-7 else EXPLICIT_LOOSE


@dataclass
class Segment:
    """Where :func:`advance` stopped: time, state, which terminal event (or None)."""

    t: float
    y: np.ndarray
    event: int | None
    nfev: int
    # Non-terminal event hits of the segment: (event index, time, state).
    hits: list[tuple[int, float, np.ndarray]]
    # Continuous solution over the segment (``dense=True``): state at a time in it.
    sol: Callable[[float], np.ndarray] | None = None


def advance(
    rhs: Rhs,
    t0: float,
    y0: np.ndarray,
    t1: float,
    *,
    rtol: float,
    atol: float | np.ndarray,
    method: str,
    terminal: Sequence[tuple[Event, int]] = (),
    watch: Sequence[tuple[Event, int]] = (),
    dense: bool = False,
    jac: np.ndarray | None = None,
) -> Segment:
    """Integrate from ``t0`` to ``t1`` or to the first ``terminal`` event.

    ``terminal`` and ``watch`` hold (event function, direction) pairs; ``watch``
    events are recorded (for maxima: a zero of the derivative) without stopping.
    ``dense`` keeps the continuous solution (for tables of the state over time).
    ``jac`` is a constant Jacobian for the implicit solvers of linear systems.
    Inside :func:`integrator`, that integrator runs instead of ``method``.
    """
    import numpy as np
    from scipy.integrate import solve_ivp as _solve_ivp

    from mdcalc.core import budget

    y0 = np.asarray(y0, dtype=float)
    if not (np.all(np.isfinite(y0)) and math.isfinite(t0)):
        raise ArithmeticError(f"the state at t = {t0:.6g} s is not a finite number")
    if _forced.method is not None:
        method = _forced.method
    if method not in TAKES_JACOBIAN:
        jac = None  # (an explicit method would warn that it has no use for it)
    if jac is not None and not np.all(np.isfinite(jac)):
        raise ArithmeticError("the Jacobian is not a finite number")

    def checked(t: float, y: np.ndarray) -> Any:  # the budget, at every evaluation
        budget.check()
        _forced.evaluations += 1  # (scipy's nfev leaves out Radau's and BDF's Jacobians)
        return rhs(t, y)

    events: list[Any] = []
    for function, direction in terminal:
        events.append(_event(function, direction, True))
    for function, direction in watch:
        events.append(_event(function, direction, False))
    if t1 <= t0:
        return Segment(t0, np.array(y0, dtype=float), None, 0, [])
    constant = jac
    jacobian: Any = (lambda t, y: constant) if method == "LSODA" and jac is not None else jac
    try:
        solution = _solve_ivp(
            checked,
            (t0, t1),
            y0,
            method=method,
            rtol=rtol,
            atol=atol,
            events=events or None,
            dense_output=dense,
            **({"jac": jacobian} if jacobian is not None else {}),  # LSODA: a function
        )
    except ValueError as exc:  # scipy giving up on a valid problem (an event's root)
        raise ArithmeticError(f"{method} failed: {exc}") from None
    if solution.status < 0:
        raise ArithmeticError(f"{method} failed at t = {solution.t[-1]:.6g} s: {solution.message}")
    hits: list[tuple[int, float, np.ndarray]] = []
    stopped: int | None = None
    for index, (times, states) in enumerate(
        zip(solution.t_events or [], solution.y_events or [], strict=True)
    ):
        if index < len(terminal):
            if len(times) and solution.status == 1:
                stopped = index
        else:
            hits.extend(
                (index - len(terminal), float(t), s) for t, s in zip(times, states, strict=True)
            )
    return Segment(
        float(solution.t[-1]),
        solution.y[:, -1].copy(),
        stopped,
        solution.nfev,
        hits,
        solution.sol if dense else None,
    )


def _event(function: Event, direction: int, terminal: bool) -> Event:
    def event(t: float, y: np.ndarray) -> float:
        return function(t, y)

    event.terminal = terminal  # type: ignore[attr-defined]
    event.direction = direction  # type: ignore[attr-defined]
    return event


def oscillator_peak(
    beta: float,
    zeta: float,
    knots: Sequence[tuple[float, float]],
    horizon: float,
    rtol: float,
    stiff: bool = False,
) -> tuple[float, float]:
    """ODE reference for :mod:`mdcalc.core.sdof`: the largest |x| and its time for
    x'' + 2ζβx' + β²x = β²·f(t) from rest, f linear between ``knots`` (t, f) and held
    after the last. Integrated knot to knot (a kink or jump of the load is a segment
    end), extrema located by events on x' = 0."""
    import numpy as np

    points = list(knots)  # in time order; a repeated time is a jump
    if points[-1][0] < horizon:
        points.append((horizon, points[-1][1]))
    scale = max(abs(f) for _, f in points) or 1.0
    atol = np.array([scale, scale * beta]) * rtol * 1e-3
    method = pick_solver(rtol, stiff)
    jac = np.array([[0.0, 1.0], [-beta * beta, -2.0 * zeta * beta]])  # (implicit methods')
    y = np.zeros(2)
    best = (0.0, points[0][0])
    for (t0, f0), (t1, f1) in zip(points, points[1:], strict=False):
        t1 = min(t1, horizon)
        if t1 <= t0:
            continue
        slope = (f1 - f0) / (t1 - t0)

        def rhs(t: float, z: np.ndarray, t0: float = t0, f0: float = f0, s: float = slope) -> Any:
            load = f0 + s * (t - t0)
            return np.array([z[1], beta * beta * (load - z[0]) - 2.0 * zeta * beta * z[1]])

        segment = advance(
            rhs,
            t0,
            y,
            t1,
            rtol=rtol,
            atol=atol,
            method=method,
            watch=[(lambda t, z: z[1], 0)],
            jac=jac,
        )
        for _, t_hit, state in segment.hits:
            if abs(state[0]) > best[0]:
                best = (abs(float(state[0])), t_hit)
        y = segment.y
        if abs(y[0]) > best[0]:
            best = (abs(float(y[0])), segment.t)
        if t1 >= horizon:
            break
    return best


class TooManySteps(ArithmeticError):
    """An ODE run stopped at its budget of right-hand-side evaluations."""


def linear_oscillator_maxima(
    stiffness: np.ndarray,
    load: np.ndarray,
    end: float,
    rtol: float,
    method: str,
    max_evaluations: int = 400_000,
) -> tuple[list[float], list[float], int]:
    """ODE reference for an undamped linear system x'' = -A·x + f from rest (the
    spring moments of a chain, seed 002 (6)): the largest value of each component
    of x over 0 ≤ t ≤ ``end`` and its time, found by events on x' = 0, and the
    number of right-hand-side evaluations. x and f should be scaled to order one.
    The implicit methods get the constant Jacobian. Raises :class:`TooManySteps` past
    ``max_evaluations``."""
    import numpy as np

    n = len(load)
    jacobian = np.zeros((2 * n, 2 * n))
    jacobian[:n, n:] = np.eye(n)
    jacobian[n:, :n] = -stiffness
    forcing = np.concatenate([np.zeros(n), load])
    count = [0]

    def rhs(t: float, y: np.ndarray) -> Any:
        count[0] += 1
        if count[0] > max_evaluations:
            raise TooManySteps(f"{method} stopped after {max_evaluations} evaluations")
        return jacobian @ y + forcing

    fastest = float(np.sqrt(np.max(np.abs(np.linalg.eigvals(stiffness)))))
    atol = np.concatenate([np.ones(n), np.full(n, fastest)]) * rtol * 1e-3
    watch = [(lambda t, y, k=k: y[n + k], -1) for k in range(n)]
    segment = advance(
        rhs,
        0.0,
        np.zeros(2 * n),
        end,
        rtol=rtol,
        atol=atol,
        method=method,
        watch=watch,
        jac=jacobian,  # (taken by the implicit methods alone)
    )
    peaks, times = [0.0] * n, [0.0] * n  # x(0) = 0
    for k in range(n):
        if segment.y[k] > 0.0:
            peaks[k], times[k] = float(segment.y[k]), segment.t
    for k, t, state in segment.hits:
        if state[k] > peaks[k]:
            peaks[k], times[k] = float(state[k]), t
    return peaks, times, count[0]
