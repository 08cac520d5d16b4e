"""7e, 7f: the clutch deformation in the periodic state of the two-mass drive, χ
(8.47), and the three-mass anti-resonance design."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mdcalc.core import periodic
from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.methods import Method, NotApplicable
from mdcalc.problems.variator.case import Drive
from mdcalc.problems.variator.transfer import Transfer

#: An ODE run predicted to need more right-hand-side evaluations is skipped.
EVALUATION_BUDGET = 200_000


@dataclass(frozen=True)
class DriveScene:
    omega: float  # input speed [rad/s]
    transfer: Transfer
    inertia: float  # J of the two-mass model (J₂, or J₂ + i²J₃) [kg·m²]
    stiffness: float  # c₁ [N·m/rad]
    damping: float  # b₁ [N·m·s/rad]
    load: float  # M_c [N·m]

    @property
    def period(self) -> float:
        return self.transfer.stroke / self.omega

    @property
    def fundamental(self) -> float:
        """Ω = zω = 2π/T [rad/s]."""
        return 2.0 * math.pi / self.period

    @property
    def static(self) -> float:
        return self.load / self.stiffness

    def excitation(self) -> tuple[float, float]:
        """u = ω²·Π″(α) = 2a₀ω²·(ωτ - Δα/2) over τ in [0, T): u₀ and du/dτ."""
        a0, w = self.transfer.a0, self.omega
        return -a0 * w * w * self.transfer.stroke, 2.0 * a0 * w**3

    def two_mass(self) -> periodic.RampSystem:
        u0, u1 = self.excitation()
        j = self.inertia
        return periodic.RampSystem(
            np.array([[j]]),
            np.array([[self.damping]]),
            np.array([[self.stiffness]]),
            np.array([self.load]),
            np.array([j]),
            u0,
            u1,
            self.period,
        )


@dataclass(frozen=True)
class ThreeMass:
    drive: DriveScene  # with J₂ only
    j3: float  # reduced J₃' = i²J₃
    c2: float  # reduced c₂'
    b2: float  # reduced b₂'
    ratio: float  # i

    def system(self) -> periodic.RampSystem:
        d = self.drive
        u0, u1 = d.excitation()
        j2, j3, c1, b1, c2, b2 = d.inertia, self.j3, d.stiffness, d.damping, self.c2, self.b2
        return periodic.RampSystem(
            np.array([[j2, 0.0], [j3, j3]]),
            np.array([[b1, -b2], [0.0, b2]]),
            np.array([[c1, -c2], [0.0, c2]]),
            np.array([0.0, d.load]),
            np.array([j2, j3]),
            u0,
            u1,
            d.period,
        )

    @property
    def antiresonance(self) -> float:
        """Where the clutch carries no load: √(c₂'(J₂ + J₃')/(J₂J₃')) [rad/s]."""
        j2 = self.drive.inertia
        return math.sqrt(self.c2 * (j2 + self.j3) / (j2 * self.j3))

    def natural_frequencies(self) -> tuple[float, float]:
        """Undamped, of q₁ and q₂ with the driver held [rad/s]."""
        s = self.system()
        values = np.linalg.eigvals(np.linalg.solve(s.mass, s.stiffness)).real
        low, high = sorted(float(v) for v in values)
        return math.sqrt(low), math.sqrt(high)


CLUTCH = np.array([1.0, 0.0])  # q of the two-mass state (q, q')


def _drive_methods(
    system: periodic.RampSystem,
    exact: periodic.Periodic,
    observables: list[tuple[str, np.ndarray, float]],
    drive: Drive,
) -> list[Method]:
    """Exact (reference), Fourier series, time integration; values over scales."""

    def values(maxima: list[float]) -> dict[str, float]:
        return {key: m / scale for (key, _, scale), m in zip(observables, maxima, strict=True)}

    def exact_run() -> dict[str, float]:
        return values(
            [periodic.maximum_of(exact, w, exact.fastest).value for _, w, _ in observables]
        )

    methods = [Method("exact periodic state (modal, closed form)", exact_run, reference=True)]
    for k in drive.harmonics:

        def fourier_run(k: int = k) -> dict[str, float]:
            series = periodic.fourier_periodic(system, k)
            top = max(exact.fastest, 2.0 * math.pi * k / system.period)
            return values([periodic.maximum_of(series, w, top).value for _, w, _ in observables])

        highest = 2.0 * math.pi * k / system.period
        # the jumps of the load ring every mode: a series that stops short of the
        # fastest mode's harmonic cannot show its ringing
        order = exact.fastest * system.period / (2.0 * math.pi)
        note = f"the fastest mode is harmonic {order:.3g}" if highest < 10.0 * exact.fastest else ""
        methods.append(
            Method(f"Fourier series, {k} harmonic{'s' if k > 1 else ''}", fourier_run, note=note)
        )
    if not drive.ode:
        return methods
    cycles = max(1.0, exact.fastest * system.period / (2.0 * math.pi))
    # The jumps of the load excite every mode, so any solver must follow the fastest
    # one through its turns: an implicit solver saves no steps and costs a Newton
    # solve each (Radau took 20 s where DOP853 took 1 s), and the budget decides.
    solver = "DOP853"
    # the shooting bundle has 2n + 1 columns of 2n states, then one more period
    columns = 2 * system.size + 2
    for rtol in (1e-6, 1e-9):
        estimate = columns * (cycles * 40.0 + 50.0)

        def ode_run(rtol: float = rtol, estimate: float = estimate) -> dict[str, float]:
            if estimate > EVALUATION_BUDGET:
                raise NotApplicable(
                    f"about {estimate:.2g} evaluations: the fastest mode turns "
                    f"{cycles:.3g} times a period (budget {EVALUATION_BUDGET:.0e})"
                )
            run = periodic.ode_periodic(system, [w for _, w, _ in observables], rtol, solver)
            return values(run.maxima)

        methods.append(
            Method(
                f"ODE {solver}, shooting, rtol {rtol:.0e}".replace("e-0", "e-"),
                ode_run,
                note="one period from 2n + 1 starts",
                imports=ODE_IMPORTS,
            )
        )
    return methods
