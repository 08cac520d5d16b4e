"""Transient torques (pulse, ramp, table) as piecewise-linear knots, their exact
Duhamel response and the ODE runs that check it."""

from __future__ import annotations

import math
from dataclasses import dataclass

from mdcalc.core import sdof
from mdcalc.problems.coupling.case import Case
from mdcalc.problems.coupling.scene import Scene


@dataclass(frozen=True)
class Transient:
    """A torque history M(t) through the coupling, as piecewise-linear knots."""

    key: str
    title: str
    knots: list[tuple[float, float]]
    horizon: float
    closed_form: float | None = None  # an exact peak factor where one exists
    closed_form_name: str = ""

    @property
    def peak_torque(self) -> float:
        return max(abs(m) for _, m in self.knots)


def transients(case: Case, scene: Scene) -> list[Transient]:
    tau = scene.period
    out: list[Transient] = []
    if case.pulse is not None:
        p = case.pulse
        knots = [(0.0, 0.0), (0.0, p.torque), (p.duration, p.torque), (p.duration, 0.0)]
        exact = sdof.rectangular_pulse_peak(scene.beta, p.duration) if scene.p == 0.0 else None
        out.append(
            Transient(
                "pulse",
                f"Rectangular pulse, {p.torque:g} N·m for {p.duration:g} s",
                knots,
                p.horizon or p.duration + 2.0 * tau,
                exact,
                "closed form 2·sin(β·T/2) or 2 (7.96)",
            )
        )
    if case.ramp is not None:
        r = case.ramp
        exact = None
        if scene.p == 0.0:  # undamped ramp-and-hold: 1 + |sin(β·t_r/2)|/(β·t_r/2)
            half = 0.5 * scene.beta * r.rise_time
            exact = 1.0 + abs(math.sin(half)) / half
        out.append(
            Transient(
                "ramp",
                f"Ramp to {r.torque:g} N·m in {r.rise_time:g} s, then held",
                [(0.0, 0.0), (r.rise_time, r.torque)],
                r.horizon or r.rise_time + 2.0 * tau,
                exact,
                "closed form 1 + |sin(β·t_r/2)|/(β·t_r/2)",
            )
        )
    if case.torque_table is not None:
        t = case.torque_table
        knots = list(zip(t.time, t.torque, strict=True))
        if knots[0][0] > 0.0:
            knots.insert(0, (0.0, 0.0))
        out.append(
            Transient(
                "table",
                "Tabulated torque",
                knots,
                t.horizon or t.time[-1] + 2.0 * tau,
            )
        )
    return out


def duhamel_response(scene: Scene, transient: Transient) -> sdof.Response:
    """The exact response, twist over static-under-peak-torque, sampled to the horizon."""
    scale = transient.peak_torque
    return sdof.piecewise_linear_response(
        [t for t, _ in transient.knots],
        [m / scale for _, m in transient.knots],
        scene.beta,
        scene.zeta,
        transient.horizon,
    )


def duhamel_peak(scene: Scene, transient: Transient) -> tuple[float, float]:
    """Peak twist over static-under-peak-torque, and its time: the exact response."""
    response = duhamel_response(scene, transient)
    return response.peak, response.peak_time


#: An explicit ODE row covering more natural periods than this is not run (it would
#: take minutes: 10⁵ periods of a stiff coupling under a 0.3 s pulse).
MAX_ODE_PERIODS = 2000.0


def ode_peak(scene: Scene, transient: Transient, rtol: float, stiff: bool = False) -> float:
    from mdcalc.core.ode import oscillator_peak
    from mdcalc.methods import NotApplicable

    periods = transient.horizon * scene.beta / (2.0 * math.pi)
    if not stiff and periods > MAX_ODE_PERIODS:
        raise NotApplicable(
            f"the load spans {periods:.3g} natural periods (more than {MAX_ODE_PERIODS:g})"
        )

    scale = transient.peak_torque
    knots = [(t, m / scale) for t, m in transient.knots]
    return oscillator_peak(scene.beta, scene.zeta, knots, transient.horizon, rtol, stiff)[0]
