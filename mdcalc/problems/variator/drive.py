"""7e, 7f: the clutch deformation in the periodic state of the two-mass drive, χ
(8.47), and the three-mass anti-resonance design. A scene's numbers are floats, or
numpy arrays over a block of scenes (a study's samples): the systems are then one
per row, solved together by :func:`~mdcalc.core.periodic.exact_block`."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from mdcalc.core import periodic
from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.ode import forced
from mdcalc.core.periodic_ode import ode_periodic
from mdcalc.methods import Method, NotApplicable
from mdcalc.problems.variator.case import Drive
from mdcalc.problems.variator.transfer import Transfer

#: An ODE run predicted to need more right-hand-side evaluations is skipped.
EVALUATION_BUDGET = 200_000


@dataclass(frozen=True)
class DriveScene:
    omega: Any  # input speed [rad/s]
    transfer: Transfer
    inertia: Any  # J of the two-mass model (J₂, or J₂ + i²J₃) [kg·m²]
    stiffness: Any  # c₁ [N·m/rad]
    damping: Any  # b₁ [N·m·s/rad]
    load: Any  # M_c [N·m]

    @property
    def period(self) -> Any:
        return self.transfer.stroke / self.omega

    @property
    def fundamental(self) -> Any:
        """Ω = zω = 2π/T [rad/s]."""
        return 2.0 * math.pi / self.period

    @property
    def static(self) -> Any:
        return self.load / self.stiffness

    def excitation(self) -> tuple[Any, Any]:
        """u = ω²·Π″(α) = 2a₀ω²·(ωτ - Δα/2) over τ in [0, T): u₀ and du/dτ."""
        a0, w = self.transfer.a0, self.omega
        # w·w·w, not w**3: a power of a float (libm pow) and of an array may round apart
        return -a0 * w * w * self.transfer.stroke, 2.0 * a0 * (w * w * w)

    def two_mass(self) -> periodic.RampSystem:
        u0, u1 = self.excitation()
        j = self.inertia
        return periodic.RampSystem(
            _matrix([j]),
            _matrix([self.damping]),
            _matrix([self.stiffness]),
            _vector(self.load),
            _vector(j),
            u0,
            u1,
            self.period,
        )


@dataclass(frozen=True)
class ThreeMass:
    drive: DriveScene  # with J₂ only
    j3: Any  # reduced J₃' = i²J₃
    c2: Any  # reduced c₂'
    b2: Any  # reduced b₂'
    ratio: Any  # i

    def system(self) -> periodic.RampSystem:
        d = self.drive
        u0, u1 = d.excitation()
        j2, j3, c1, b1, c2, b2 = d.inertia, self.j3, d.stiffness, d.damping, self.c2, self.b2
        return periodic.RampSystem(
            _matrix([j2, 0.0], [j3, j3]),
            _matrix([b1, -b2], [0.0, b2]),
            _matrix([c1, -c2], [0.0, c2]),
            _vector(0.0, d.load),
            _vector(j2, j3),
            u0,
            u1,
            d.period,
        )

    @property
    def antiresonance(self) -> Any:
        """Where the clutch carries no load: √(c₂'(J₂ + J₃')/(J₂J₃')) [rad/s]."""
        j2 = self.drive.inertia
        return np.sqrt(self.c2 * (j2 + self.j3) / (j2 * self.j3))

    def natural_frequencies(self) -> tuple[Any, Any]:
        """Undamped, of q₁ and q₂ with the driver held [rad/s]: the roots x = ω² of
        det(K - xM) = a·x² - b·x + c, the larger by (b + √(b² - 4ac))/2a and the
        smaller by c over a and it (no cancellation: here a = J₂J₃', b = J₂c₂' +
        J₃'c₁ + J₃'c₂', c = c₁c₂'; numpy's batched eigvals of M⁻¹K cost 3 ms a
        4096-row block)."""
        s = self.system()
        m, k = s.mass, s.stiffness
        a = m[..., 0, 0] * m[..., 1, 1] - m[..., 0, 1] * m[..., 1, 0]
        b = m[..., 0, 0] * k[..., 1, 1] + m[..., 1, 1] * k[..., 0, 0]
        b = b - m[..., 0, 1] * k[..., 1, 0] - m[..., 1, 0] * k[..., 0, 1]
        c = k[..., 0, 0] * k[..., 1, 1] - k[..., 0, 1] * k[..., 1, 0]
        high = (b + np.sqrt(np.maximum(b * b - 4.0 * a * c, 0.0))) / (2.0 * a)
        return np.sqrt(c / (a * high)), np.sqrt(high)

    def coupling(self) -> np.ndarray:
        """The observable c₂'·q₂ + b₂'·q₂' of the coupling's moment."""
        return _vector(0.0, self.c2, 0.0, self.b2)


def _vector(*entries: Any) -> np.ndarray:
    """A vector of entries that are floats (a scene) or arrays over a block's rows
    (then one vector per row, on a leading axis)."""
    return np.stack(np.broadcast_arrays(*[np.asarray(e, dtype=float) for e in entries]), axis=-1)


def _matrix(*rows: list[Any]) -> np.ndarray:
    """A matrix of such entries (one per row of a block, on a leading axis)."""
    flat = _vector(*[e for row in rows for e in row])
    return flat.reshape(*flat.shape[:-1], len(rows), len(rows[0]))


def drive_values(d: DriveScene, q_max: Any) -> dict[str, Any]:
    """Every number of the two-mass model's section, by result key, from its
    periodic state's largest clutch deformation q_max."""
    beta = np.sqrt(d.stiffness / d.inertia)
    u0, _ = d.excitation()
    return {
        "drive_inertia": d.inertia,
        "drive_stiffness": d.stiffness,
        "drive_damping": d.damping,
        "drive_fundamental": d.fundamental,
        "drive_natural": beta,
        "drive_frequency_ratio": beta / d.fundamental,
        "drive_acceleration": d.inertia * abs(u0),
        "drive_static": d.static,
        "drive_q_max": q_max,
        "drive_chi": q_max / d.static,
        "drive_moment_max": d.stiffness * q_max,
    }


def three_mass_values(
    three: ThreeMass, before: Any, clutch: Any, coupling: Any, kept: Any = None
) -> dict[str, Any]:
    """Every number of the anti-resonance design's section, by result key: from the
    largest clutch deformation of the two-mass model (``before``) and of the
    three-mass one (``clutch``), the coupling's largest moment (reduced), and χ had
    the clutch kept the two-mass model's damping (``kept``, where it differs)."""
    d, i = three.drive, three.ratio
    low, high = three.natural_frequencies()
    chi_before, chi_after = before / d.static, clutch / d.static
    values = {
        "antiresonance_machine": three.j3,
        "antiresonance_coupling": three.c2 / (i * i),
        "antiresonance_frequency": three.antiresonance,
        "antiresonance_natural_low": low,
        "antiresonance_natural_high": high,
        "antiresonance_chi_before": chi_before,
        "antiresonance_chi_after": chi_after,
        "antiresonance_reduction": (chi_before - 1.0) / (chi_after - 1.0),
        "antiresonance_chi_ratio": chi_before / chi_after,
        "antiresonance_coupling_max": coupling / i,
        "antiresonance_coupling_factor": coupling / d.load,
        "antiresonance_clutch_damping": d.damping,
    }
    if kept is not None:
        values["antiresonance_chi_after_kept_damping"] = kept
        values["antiresonance_reduction_kept_damping"] = (chi_before - 1.0) / (kept - 1.0)
    return values


CLUTCH = np.array([1.0, 0.0])  # q of the two-mass state (q, q')
CLUTCH_OF_THREE = np.array([1.0, 0.0, 0.0, 0.0])  # q₁ of the three-mass state


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

    # where two eigenvalues meet (a mode damped critically) there is no basis of modes
    meet = exact.matrix is not None
    methods = [
        Method(
            f"exact periodic state ({'e^{Aτ}' if meet else 'modal'}, closed form)",
            exact_run,
            reference=True,
            note="eigenvalues meet: e^{Aτ} by expm" if meet else "",
        )
    ]
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

    def ladder(rtol: float) -> dict[str, float]:  # --work-precision: any integrator
        run = ode_periodic(system, [w for _, w, _ in observables], rtol, forced() or solver)
        return values(run.maxima)

    for rtol in (1e-6, 1e-9):
        estimate = columns * (cycles * 40.0 + 50.0)

        def ode_run(rtol: float = rtol, estimate: float = estimate) -> dict[str, float]:
            if estimate > EVALUATION_BUDGET:
                raise NotApplicable(
                    f"about {estimate:.2g} evaluations: the fastest mode turns "
                    f"{cycles:.3g} times a period (budget {EVALUATION_BUDGET:.0e})"
                )
            run = ode_periodic(system, [w for _, w, _ in observables], rtol, solver)
            return values(run.maxima)

        methods.append(
            Method(
                f"ODE {solver}, shooting, rtol {rtol:.0e}".replace("e-0", "e-"),
                ode_run,
                note="one period from 2n + 1 starts",
                imports=ODE_IMPORTS,
                ladder=ladder,
            )
        )
    return methods
