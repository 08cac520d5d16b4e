"""``variator``: anti-resonance in an impulse-variator drive and the centrifugal
pendulum absorber (seed 000 §8.2–8.5, brief §7a–7g).

Each part is a section of the case file and appears in the report only when its
section is there:

* ``[absorber]`` (7a) -- disk J₁ on a shaft c to the ground, torque M₀·cos ωt,
  absorber disk J₂ on a shaft c_g (8.36): amplitudes (8.38), the tuning c_g = J₂ω²
  (8.39) that makes A₁ = 0, the two resonances of the tuned system (Δ = 0), the band
  where the absorber helps, A₁(ω) and A₂(ω); with damping b_g across the absorber
  shaft, the depth of the minimum.
* ``[motor]`` (7b) -- the induction motor as a spring-damper (8.40)–(8.41), slip
  relative to the synchronous speed, the seed's correction of the critical slip
  beside plain Kloss. Note c_D = 1/(T_D·ν·ω₀) = 2·P·M_K whatever the critical slip.
* ``[clutch]`` (7c) -- the loading curve M = c₀·ξⁿ (8.42), its lines over the
  working range (secant, least squares through the origin, chord) with their errors.
* ``[mechanism]`` (7d) -- the transfer functions (8.46) of one working stroke
  Δα = 2π/z and the check that the mean of Π′ is 1/i_c.
* ``[drive]`` (7e) -- the clutch deformation q of the two-mass model,
  J·q'' + b·q' + c·q = M_c + J·ω²·Π″(ωt), in its periodic state; χ = q_max/q_c (8.47).
* ``[antiresonance]`` (7f) -- an elastic coupling c₂ (b₂) and the machine J₃ behind
  a ratio i = ω₃/ω₂. Reduced to the variator's output shaft (J₃' = i²J₃, c₂' = i²c₂,
  b₂' = i²b₂) with q₂ the coupling's twist:
  J₂q₁'' + b₁q₁' + c₁q₁ - (c₂'q₂ + b₂'q₂') = J₂u,
  J₃'(q₁'' + q₂'') + c₂'q₂ + b₂'q₂' = M_c + J₃'u, u = ω²Π″.
  The clutch has no load at the frequency where J₂ and J₃' swing against each other
  on c₂ with the clutch at rest: c₂' = (zω)²·J₂J₃'/(J₂ + J₃'). The report compares
  χ before (J₃ rigid on the output shaft) and after.
* ``[pendulum]`` (7g) -- L = R/n², the mass (8.56), whether the bob fits on so
  short a pendulum, the detuning at the design swing, the bifilar alternative.

The periodic states come from :mod:`mdcalc.core.periodic` (closed form, Fourier
series and time integration, compared in the Methods tables).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from pydantic import Field, model_validator

from mdcalc.core import periodic
from mdcalc.core.chain import Chain, harmonic_response
from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.units import rpm_to_rad_s
from mdcalc.methods import Method, NotApplicable, compare
from mdcalc.model import CaseBase, CaseModel, FieldError, exactly_one
from mdcalc.report import (
    Column,
    MethodQuantity,
    MethodsTable,
    Note,
    Quantities,
    Quantity,
    Report,
    Table,
)

if TYPE_CHECKING:
    from mdcalc.plot import Chart, Style

KGF_M = 9.80665  # N·m per kgf·m
STEEL_DENSITY = 7850.0  # kg/m³
RAD_S_TO_RPM = 30.0 / math.pi
#: An ODE run predicted to need more right-hand-side evaluations is skipped.
EVALUATION_BUDGET = 200_000

# ------------------------------------------------------------------------ the case


class Absorber(CaseModel):
    inertia: float = Field(ge=1e-9, le=1e9, description="J₁, the disk that is shaken [kg·m^2]")
    stiffness: float = Field(ge=1e-6, le=1e15, description="c, its shaft to the ground [N·m/rad]")
    absorber_inertia: float = Field(ge=1e-9, le=1e9, description="J₂, the absorber disk [kg·m^2]")
    absorber_stiffness: float | None = Field(
        default=None,
        ge=1e-6,
        le=1e15,
        description="c_g, the absorber's shaft (default: tuned) [N·m/rad]",
    )
    tuning_frequency: float | None = Field(
        default=None, ge=1e-6, le=1e9, description="ω_t, tune c_g = J₂·ω_t² (default: ω) [rad/s]"
    )
    absorber_damping: float = Field(
        default=0.0, ge=0, le=1e12, description="b_g, across the absorber's shaft [N·m·s/rad]"
    )
    torque_amplitude: float = Field(ge=1e-9, le=1e12, description="M₀ [N·m]")
    frequency: float = Field(ge=1e-6, le=1e9, description="ω, of the torque [rad/s]")
    curve_points: int = Field(default=25, ge=3, le=2001, description="rows of the A(ω) table [-]")

    @model_validator(mode="after")
    def _tuning(self) -> Absorber:
        if self.absorber_stiffness is not None and self.tuning_frequency is not None:
            raise ValueError(
                "give absorber_stiffness or tuning_frequency in [absorber], not both "
                "(neither: tuned to the frequency)"
            )
        return self


class Motor(CaseModel):
    mains_frequency: float = Field(default=50.0, gt=0, le=1000, description="f_c [Hz]")
    pole_pairs: int = Field(ge=1, le=64, description="P [-]")
    synchronous_speed_rpm: float | None = Field(
        default=None, gt=0, description="n (default 60·f_c/P) [rpm]"
    )
    nominal_speed_rpm: float = Field(gt=0, description="n_H, catalogue [rpm]")
    nominal_torque: float | None = Field(default=None, gt=0, le=1e9, description="M_H [N·m]")
    nominal_power: float | None = Field(default=None, gt=0, le=1e10, description="P_H [W]")
    overload_ratio: float = Field(gt=1, le=10, description="λ_m = M_K/M_H [-]")

    @model_validator(mode="after")
    def _check(self) -> Motor:
        exactly_one("motor", nominal_torque=self.nominal_torque, nominal_power=self.nominal_power)
        if self.nominal_speed_rpm >= self.synchronous:
            raise FieldError(
                ("nominal_speed_rpm",),
                f"got {self.nominal_speed_rpm:g}; must be below the synchronous speed "
                f"{self.synchronous:g} rpm (an induction motor runs with slip)",
            )
        return self

    @property
    def synchronous(self) -> float:
        return self.synchronous_speed_rpm or 60.0 * self.mains_frequency / self.pole_pairs


class Clutch(CaseModel):
    loading_coefficient: float | None = Field(
        default=None, ge=1e-6, le=1e15, description="c₀ of M = c₀·ξⁿ [N·m/rad^n]"
    )
    loading_coefficient_kgfm: float | None = Field(
        default=None, ge=1e-6, le=1e15, description="c₀ as the seed gives it [kgf·m/rad^n]"
    )
    loading_exponent: float = Field(ge=0.5, le=10, description="n of M = c₀·ξⁿ [-]")
    load_min: float = Field(default=0.0, ge=0, le=1e12, description="working range from [N·m]")
    load_max: float = Field(ge=1e-6, le=1e12, description="working range to [N·m]")
    unloading_stiffness: float | None = Field(
        default=None, gt=0, le=1e15, description="c of the linearized unloading [N·m/rad]"
    )
    unloading_stiffness_kgfm: float | None = Field(
        default=None, gt=0, le=1e15, description="the same in the seed's unit [kgf·m/rad]"
    )
    loop_area_ratio: float | None = Field(
        default=None, ge=0, le=1, description="ψ = S₁/S of the loading loop (8.43) [-]"
    )

    @model_validator(mode="after")
    def _check(self) -> Clutch:
        exactly_one(
            "clutch",
            loading_coefficient=self.loading_coefficient,
            loading_coefficient_kgfm=self.loading_coefficient_kgfm,
        )
        if self.unloading_stiffness is not None and self.unloading_stiffness_kgfm is not None:
            raise ValueError("give unloading_stiffness or unloading_stiffness_kgfm, not both")
        if self.load_min >= self.load_max:
            raise FieldError(
                ("load_min",),
                f"got {self.load_min:g}; must be below load_max {self.load_max:g} N·m",
            )
        return self

    @property
    def c0(self) -> float:
        if self.loading_coefficient is not None:
            return self.loading_coefficient
        return (self.loading_coefficient_kgfm or 0.0) * KGF_M

    @property
    def unloading(self) -> float | None:
        if self.unloading_stiffness_kgfm is not None:
            return self.unloading_stiffness_kgfm * KGF_M
        return self.unloading_stiffness


class Mechanism(CaseModel):
    mechanisms: int = Field(ge=2, le=64, description="z, elementary mechanisms [-]")
    input_speed_rpm: float = Field(ge=1e-3, le=1e6, description="n₁, input shaft [rpm]")
    mean_ratio: float | None = Field(default=None, ge=1e-6, le=1e6, description="i_c [-]")
    output_speed_rpm: float | None = Field(
        default=None, ge=1e-6, le=1e6, description="n₂, mean output speed: i_c = n₁/n₂ [rpm]"
    )

    @model_validator(mode="after")
    def _one(self) -> Mechanism:
        exactly_one("mechanism", mean_ratio=self.mean_ratio, output_speed_rpm=self.output_speed_rpm)
        return self

    @property
    def ratio(self) -> float:
        return self.mean_ratio or self.input_speed_rpm / (self.output_speed_rpm or 1.0)


class Drive(CaseModel):
    driven_inertia: float = Field(ge=1e-9, le=1e9, description="J₂, on the output shaft [kg·m^2]")
    load_torque: float = Field(ge=1e-6, le=1e12, description="M_c, on the output shaft [N·m]")
    clutch_stiffness: float | None = Field(
        default=None, ge=1e-6, le=1e15, description="c, linearized clutch [N·m/rad]"
    )
    clutch_stiffness_kgfm: float | None = Field(
        default=None, ge=1e-6, le=1e15, description="c in the seed's unit [kgf·m/rad]"
    )
    clutch_damping: float | None = Field(
        default=None, ge=0, le=1e12, description="b of the clutch [N·m·s/rad]"
    )
    clutch_loop_area_ratio: float | None = Field(
        default=None,
        ge=0,
        le=1,
        description="ψ = S₁/S, b = ψ/(2π)·√(J·c) (8.44) (default: [clutch] loop_area_ratio) [-]",
    )
    harmonics: list[int] = Field(
        default=[1, 10, 100, 1000], description="Fourier rows of the Methods table [-]"
    )
    ode: bool = Field(default=True, description="time-integration rows in the Methods table")
    points: int = Field(default=13, ge=3, le=1001, description="rows of the q(τ) table [-]")

    @model_validator(mode="after")
    def _check(self) -> Drive:
        exactly_one(
            "drive",
            clutch_stiffness=self.clutch_stiffness,
            clutch_stiffness_kgfm=self.clutch_stiffness_kgfm,
        )
        if self.clutch_damping is not None and self.clutch_loop_area_ratio is not None:
            raise ValueError("give clutch_damping or clutch_loop_area_ratio in [drive], not both")
        for index, k in enumerate(self.harmonics):
            if not 1 <= k <= 100_000:
                raise FieldError(("harmonics", index), f"got {k}; must be 1 to 100000 harmonics")
        return self

    @property
    def stiffness(self) -> float:
        if self.clutch_stiffness is not None:
            return self.clutch_stiffness
        return (self.clutch_stiffness_kgfm or 0.0) * KGF_M


class Antiresonance(CaseModel):
    machine_inertia: float = Field(ge=1e-9, le=1e9, description="J₃, the machine [kg·m^2]")
    ratio: float = Field(
        default=1.0, gt=0, le=1e4, description="i = ω₃/ω₂, machine over output speed [-]"
    )
    coupling_stiffness: float | None = Field(
        default=None, ge=1e-6, le=1e15, description="c₂ (default: tuned) [N·m/rad]"
    )
    coupling_damping: float = Field(default=0.0, ge=0, le=1e12, description="b₂ [N·m·s/rad]")


class Pendulum(CaseModel):
    pivot_radius: float = Field(ge=1e-4, le=100, description="R, disk centre to pivot [m]")
    order: float = Field(ge=1e-3, le=1000, description="n, oscillations per revolution [-]")
    speed: float | None = Field(default=None, ge=1e-3, le=1e6, description="ω, disk [rad/s]")
    speed_rpm: float | None = Field(default=None, ge=1e-3, le=1e7, description="disk [rpm]")
    inertia_torque: float | None = Field(
        default=None, ge=1e-9, le=1e12, description="M_ин, torque amplitude to absorb [N·m]"
    )
    max_swing: float | None = Field(
        default=None, ge=1e-6, lt=math.pi, description="θ_max, allowed swing [rad]"
    )
    bob_density: float = Field(
        default=STEEL_DENSITY, ge=1.0, le=1e5, description="bob material [kg/m^3]"
    )
    bifilar_pin_diameter: float | None = Field(
        default=None, gt=0, le=10, description="d, pin of a bifilar design [m]"
    )

    @model_validator(mode="after")
    def _check(self) -> Pendulum:
        if self.speed is not None and self.speed_rpm is not None:
            raise ValueError("give speed or speed_rpm in [pendulum], not both")
        given = {
            "speed": self.speed or self.speed_rpm,
            "inertia_torque": self.inertia_torque,
            "max_swing": self.max_swing,
        }
        if self.inertia_torque is not None and None in given.values():
            missing = [k for k, v in given.items() if v is None]
            raise FieldError(
                (missing[0],), "the mass (8.56) needs speed, inertia_torque and max_swing"
            )
        return self

    @property
    def omega(self) -> float | None:
        if self.speed is not None:
            return self.speed
        return rpm_to_rad_s(self.speed_rpm) if self.speed_rpm is not None else None


class Case(CaseBase):
    problem: Literal["variator"] = Field(description="Problem name [-]")
    absorber: Absorber | None = None
    motor: Motor | None = None
    clutch: Clutch | None = None
    mechanism: Mechanism | None = None
    drive: Drive | None = None
    antiresonance: Antiresonance | None = None
    pendulum: Pendulum | None = None

    @model_validator(mode="after")
    def _sections(self) -> Case:
        parts = ("absorber", "motor", "clutch", "mechanism", "drive", "antiresonance", "pendulum")
        if all(getattr(self, p) is None for p in parts):
            raise ValueError(f"give at least one section: {', '.join(f'[{p}]' for p in parts)}")
        if self.drive is not None and self.mechanism is None:
            raise FieldError(("drive",), "[drive] needs [mechanism] (the stroke and its speed)")
        if self.antiresonance is not None and self.drive is None:
            raise FieldError(("antiresonance",), "[antiresonance] needs [drive]")
        return self


# ------------------------------------------------------------ 7a: absorber


@dataclass(frozen=True)
class AbsorberScene:
    j1: float
    c: float
    j2: float
    cg: float
    bg: float
    m0: float
    omega: float
    tuned: bool  # c_g = J₂·ω² (A₁ is exactly 0 without damping)

    def amplitudes(self, omega: float) -> tuple[complex, complex]:
        """Complex A₁, A₂ [rad] at ω: (8.38) with k_g = c_g + iω·b_g."""
        w2 = omega * omega
        kg = complex(self.cg, omega * self.bg)
        numerator = kg - self.j2 * w2
        # (c + k_g - J₁ω²)(k_g - J₂ω²) - k_g², written without the k_g² - k_g² cancellation
        det = (self.c - self.j1 * w2) * (kg - self.j2 * w2) - kg * self.j2 * w2
        if det == 0:
            raise ZeroDivisionError
        return self.m0 * numerator / det, self.m0 * kg / det

    def determinant_is_zero(self, omega: float) -> bool:
        """Δ = 0 to round-off (undamped resonance of the two-disk system)."""
        if self.bg != 0.0:
            return False
        w2 = omega * omega
        first = (self.c - self.j1 * w2) * (self.cg - self.j2 * w2)
        second = self.cg * self.j2 * w2
        return abs(first - second) <= 1e-12 * max(abs(first), second)

    def untuned(self, omega: float) -> float | None:
        """|A| of J₁ without the absorber, M₀/|c - J₁ω²| (None: resonance)."""
        gap = self.c - self.j1 * omega * omega
        if abs(gap) <= 1e-12 * self.c:
            return None
        return self.m0 / abs(gap)

    def resonances(self) -> tuple[float, float]:
        """Roots of Δ = 0: ω⁴ - (a + b + d)·ω² + a·d = 0, a = c/J₁, b = c_g/J₁,
        d = c_g/J₂ [rad/s] (discriminant (a + b - d)² + 4bd > 0)."""
        a, b, d = self.c / self.j1, self.cg / self.j1, self.cg / self.j2
        high = 0.5 * ((a + b + d) + math.sqrt((a + b - d) ** 2 + 4.0 * b * d))
        return math.sqrt(a * d / high), math.sqrt(high)

    def band(self) -> tuple[float, float]:
        """Where the undamped absorber lowers |A₁| below M₀/|c - J₁ω²|:
        (d - ω²)(a - ω²) < ω²·b/2, between the roots of ω⁴ - (a + d + b/2)ω² + ad."""
        a, b, d = self.c / self.j1, self.cg / self.j1, self.cg / self.j2
        s = a + d + 0.5 * b
        high = 0.5 * (s + math.sqrt((a - d) ** 2 + b * (a + d) + 0.25 * b * b))
        return math.sqrt(a * d / high), math.sqrt(high)


def absorber_scene(a: Absorber) -> AbsorberScene:
    w2 = a.frequency * a.frequency
    if a.absorber_stiffness is not None:
        cg, tuned = (
            a.absorber_stiffness,
            abs(a.absorber_stiffness - a.absorber_inertia * w2) <= (4e-16 * a.absorber_stiffness),
        )
    else:
        tune = a.tuning_frequency if a.tuning_frequency is not None else a.frequency
        # J₂·(ω·ω): the same product amplitudes() forms, so tuned means A₁ = 0 exactly
        cg, tuned = a.absorber_inertia * (tune * tune), tune == a.frequency
    return AbsorberScene(
        a.inertia,
        a.stiffness,
        a.absorber_inertia,
        cg,
        a.absorber_damping,
        a.torque_amplitude,
        a.frequency,
        tuned,
    )


def seed_amplitudes(s: AbsorberScene) -> dict[str, float]:
    """(8.38) as printed: A₁ = M₀(c_g/J₂ - ω²)/(J₁Δ), A₂ = M₀(c_g/J₂)/(J₁Δ)."""
    if s.bg != 0.0:
        raise NotApplicable("(8.38) has no damping")
    w2 = s.omega * s.omega
    d = s.cg / s.j2
    delta = d * (s.c / s.j1 - w2) - w2 * ((s.c + s.cg) / s.j1 - w2)
    top = d - w2
    terms = (abs(d * (s.c / s.j1 - w2)), abs(w2 * ((s.c + s.cg) / s.j1 - w2)))
    if abs(delta) <= 1e-8 * max(terms):
        raise NotApplicable("Δ as printed loses its digits to cancellation at these scales")
    return {"a1": abs(s.m0 * top / (s.j1 * delta)), "a2": abs(s.m0 * d / (s.j1 * delta))}


def chain_amplitudes(s: AbsorberScene) -> dict[str, float]:
    """The shared chain core: J₁ - c_g - J₂ with c from J₁ to the ground."""
    try:
        angles, _ = harmonic_response(
            Chain((s.j1, s.j2), (s.cg,)),
            s.omega,
            [s.m0, 0.0],
            spring_damping=[s.bg],
            ground_stiffness=[s.c, 0.0],
        )
    except ArithmeticError as reason:
        raise NotApplicable(f"the 2×2 system is too ill-conditioned ({reason})") from None
    return {"a1": float(abs(angles[0])), "a2": float(abs(angles[1]))}


def absorber_minimum(s: AbsorberScene) -> tuple[float, float] | None:
    """Smallest |A₁| between the two resonances and where [rad, rad/s]: a log grid,
    then golden section; None when there is no minimum inside (heavy damping)."""
    low, high = s.resonances()

    def value(omega: float) -> float:
        return abs(s.amplitudes(omega)[0])

    grid = np.geomspace(low, high, 2001)[1:-1]
    values = [value(float(w)) for w in grid]
    k = int(np.argmin(values))
    if k in (0, len(grid) - 1):  # |A₁| falls all the way to a resonance: no notch
        return None
    a, b = float(grid[k - 1]), float(grid[k + 1])
    ratio = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(200):
        x1, x2 = b - ratio * (b - a), a + ratio * (b - a)
        if value(x1) < value(x2):
            b = x2
        else:
            a = x1
        if b - a <= 1e-15 * b:
            break
    where = 0.5 * (a + b)
    return value(where), where


# ------------------------------------------------------------ 7b: motor


@dataclass(frozen=True)
class MotorModel:
    name: str
    slip: float  # S_H
    a: float
    critical_slip: float  # S_K
    nu: float
    time_constant: float  # T_D [s]
    stiffness: float  # c_D [N·m/rad]
    damping: float  # b_D [N·m·s/rad]


def motor_models(m: Motor) -> tuple[float, float, list[MotorModel]]:
    """(8.40)–(8.41): ω_c, ω₀ and the motor as a spring-damper three ways."""
    omega_c = 2.0 * math.pi * m.mains_frequency
    omega_0 = omega_c / m.pole_pairs
    n, n_h, lam = m.synchronous, m.nominal_speed_rpm, m.overload_ratio
    torque = m.nominal_torque or (m.nominal_power or 0.0) / rpm_to_rad_s(n_h)
    m_k = lam * torque
    slip, seed_slip = (n - n_h) / n, (n - n_h) / n_h
    models = []
    for name, s_h, a in (
        ("plain Kloss, a = λ_m", slip, lam),
        ("seed's correction, a = λ_m + 5(λ_m - 1)S_H", slip, lam + 5.0 * (lam - 1.0) * slip),
        (
            "seed as printed: S_H = (n - n_H)/n_H",
            seed_slip,
            lam + 5.0 * (lam - 1.0) * seed_slip,
        ),
    ):
        s_k = s_h * (a + math.sqrt(a * a - 1.0))
        nu = s_k / (2.0 * m_k)
        t_d = 1.0 / (omega_c * s_k)
        models.append(
            MotorModel(name, s_h, a, s_k, nu, t_d, 1.0 / (t_d * nu * omega_0), 1.0 / (nu * omega_0))
        )
    return omega_c, omega_0, models


# ------------------------------------------------------------ 7c: clutch


@dataclass(frozen=True)
class ClutchLine:
    name: str
    key: str
    stiffness: float  # slope [N·m/rad]
    offset: float  # M at ξ = 0 of the line [N·m] (0: through the origin)
    error: float  # max |line - curve| over the range / M_max [-]


def clutch_lines(c: Clutch) -> tuple[float, float, list[ClutchLine]]:
    """ξ range of the working loads and three lines through the curve M = c₀·ξⁿ.

    Written in y = ξ/ξ_max and r = ξ_min/ξ_max so that no power of ξ itself is formed
    (c₀ and ξ may be far from 1): the curve is M_max·yⁿ, the least-squares slope
    through the origin 3·(M_max/ξ_max)·(1 - r^(n+2))/((n + 2)(1 - r³))."""
    n, m1, m2 = c.loading_exponent, c.load_min, c.load_max
    x2 = math.exp((math.log(m2) - math.log(c.c0)) / n)
    # ℓ = ln r = ln(M_min/M_max)/n, and 1 - rᵖ = -expm1(p·ℓ): a narrow range keeps
    # its digits (1 - r would cancel)
    ell = -math.inf if m1 == 0.0 else math.log1p((m1 - m2) / m2) / n
    r = math.exp(ell)
    x1 = r * x2
    unit = m2 / x2  # slope that reaches M_max at ξ_max
    squares = 3.0 * unit * math.expm1((n + 2) * ell) / ((n + 2) * math.expm1(3.0 * ell))
    chord = (m2 - m1) / (-x2 * math.expm1(ell))
    lines = []
    for name, key, slope, offset in (
        ("secant to the top of the range, M_max/ξ_max", "secant", unit, 0.0),
        ("least squares through the origin", "least_squares", squares, 0.0),
        ("chord over the range (not through the origin)", "chord", chord, m1 - chord * x1),
    ):
        k, b = slope / unit, offset / m2  # the line over M_max, in y
        candidates = [r, 1.0]
        if n != 1.0:
            star = (k / n) ** (1.0 / (n - 1.0))
            if r < star < 1.0:
                candidates.append(star)
        error = max(abs(b + k * y - y**n) for y in candidates)
        lines.append(ClutchLine(name, key, slope, offset, error))
    return x1, x2, lines


# ------------------------------------------------------------ 7d: mechanism


@dataclass(frozen=True)
class Transfer:
    stroke: float  # Δα [rad]
    ratio: float  # i_c
    a0: float
    b0: float

    def first(self, x: float) -> float:
        """Π′ at α - α_c = x."""
        return self.a0 * x * x + self.b0

    def position(self, x: float) -> float:
        """Π - φ_c."""
        return self.a0 * x**3 / 3.0 + self.b0 * x

    def second(self, x: float) -> float:
        return 2.0 * self.a0 * x

    def mean_first(self) -> float:
        """Mean of Π′ over the stroke by 3-point Gauss–Legendre (exact for Π′)."""
        h = 0.5 * self.stroke
        r = math.sqrt(3.0 / 5.0)
        return (5.0 * self.first(-r * h) + 8.0 * self.first(0.0) + 5.0 * self.first(r * h)) / 18.0


def transfer_of(m: Mechanism) -> Transfer:
    """(8.46) with Δα = 2π/z."""
    d = 2.0 * math.pi / m.mechanisms
    i_c = m.ratio
    half_sine = math.sin(0.5 * d)
    a0 = -12.0 / (d * d * i_c) * (d / (2.0 * half_sine) - 1.0)
    b0 = d / (2.0 * i_c * half_sine)
    return Transfer(d, i_c, a0, b0)


# ------------------------------------------------------------ 7e, 7f: drive


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


# ------------------------------------------------------------ 7g: pendulum


def agm(a: float, b: float) -> float:
    """Arithmetic–geometric mean."""
    for _ in range(64):
        a, b = 0.5 * (a + b), math.sqrt(a * b)
        if abs(a - b) <= 1e-16 * a:
            break
    return a


# ------------------------------------------------------------------------- result


@dataclass
class Result:
    case: Case
    absorber: AbsorberScene | None = None
    absorber_methods: MethodsTable | None = None
    drive: DriveScene | None = None
    two_mass: periodic.Periodic | None = None
    two_mass_methods: MethodsTable | None = None
    three_mass: ThreeMass | None = None
    three_mass_state: periodic.Periodic | None = None
    three_mass_methods: MethodsTable | None = None
    chi_after_kept_damping: float | None = None  # b₁ of the two-mass model kept
    motor_methods: MethodsTable | None = None
    notes: list[Note] = field(default_factory=list)
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


AMPLITUDES = [
    MethodQuantity("a1", "|A₁|", "rad"),
    MethodQuantity("a2", "|A₂|", "rad"),
]
MOTOR = [
    MethodQuantity("critical_slip", "S_K", ""),
    MethodQuantity("damping", "b_D", "N·m·s/rad"),
]


def drive_scene(case: Case, with_machine: bool) -> DriveScene:
    assert case.mechanism is not None and case.drive is not None
    d = case.drive
    inertia = d.driven_inertia
    if with_machine and case.antiresonance is not None:
        inertia += case.antiresonance.ratio**2 * case.antiresonance.machine_inertia
    psi = d.clutch_loop_area_ratio
    if psi is None and case.clutch is not None:
        psi = case.clutch.loop_area_ratio
    if d.clutch_damping is not None:
        damping = d.clutch_damping
    elif psi is not None:  # (8.44) with the two-mass model's J
        damping = psi / (2.0 * math.pi) * math.sqrt(inertia * d.stiffness)
    else:
        damping = 0.0
    return DriveScene(
        rpm_to_rad_s(case.mechanism.input_speed_rpm),
        transfer_of(case.mechanism),
        inertia,
        d.stiffness,
        damping,
        d.load_torque,
    )


def solve(case: Case) -> Result:
    result = Result(case)
    try:
        if case.absorber is not None:
            _solve_absorber(case.absorber, result)
        if case.motor is not None:
            result.motor_methods = _motor_methods(case.motor)
        if case.drive is not None:
            _solve_drive(case, result)
    except (periodic.Unbounded, periodic.Unresolved) as reason:
        result.status, result.message = "no-answer", str(reason)
    return result


def _motor_methods(motor: Motor) -> MethodsTable:
    def method(index: int) -> Method:
        def run() -> dict[str, float]:
            m = motor_models(motor)[2][index]
            return {"critical_slip": m.critical_slip, "damping": m.damping}

        return Method(motor_models(motor)[2][index].name, run, reference=index == 0)

    return compare(
        "Motor as a spring-damper: the seed's forms beside plain Kloss (differences, not errors)",
        "motor",
        MOTOR,
        [method(index) for index in range(3)],
    )


def _solve_absorber(a: Absorber, result: Result) -> None:
    s = absorber_scene(a)
    result.absorber = s
    if s.determinant_is_zero(s.omega):
        low, high = s.resonances()
        raise periodic.Unbounded(
            f"undamped resonance of the two-disk system: ω = {s.omega:.6g} rad/s is one of its "
            f"natural frequencies {low:.6g} and {high:.6g} rad/s (Δ = 0 in (8.38)), the "
            "amplitudes are unbounded; retune the absorber or give it absorber_damping"
        )
    result.absorber_methods = compare(
        "Methods: absorber amplitudes at ω",
        "absorber",
        AMPLITUDES,
        [
            Method(
                "closed form, complex (8.38) with damping",
                lambda: {"a1": abs(s.amplitudes(s.omega)[0]), "a2": abs(s.amplitudes(s.omega)[1])},
                reference=True,
            ),
            Method("(8.38) as printed", lambda: seed_amplitudes(s), note="no damping"),
            Method("linear solve, shared chain core", lambda: chain_amplitudes(s)),
        ],
    )
    if s.tuned and s.bg == 0.0:
        result.absorber_methods.rows[0].note = "tuned: A₁ = 0 exactly"


def _solve_drive(case: Case, result: Result) -> None:
    assert case.drive is not None
    drive = drive_scene(case, with_machine=True)
    result.drive = drive
    system = drive.two_mass()
    exact = periodic.exact_periodic(system)
    result.two_mass = exact
    result.two_mass_methods = compare(
        "Methods: χ of the two-mass model, periodic state",
        "two_mass",
        [MethodQuantity("chi", "χ = q_max/q_c", "")],
        _drive_methods(system, exact, [("chi", CLUTCH, drive.static)], case.drive),
    )
    if case.antiresonance is None:
        return
    ar = case.antiresonance
    # (8.44) with the J the clutch faces: J₂ alone now (J₂ + i²J₃ before); a clutch
    # damping given as b is the same in both
    base = drive_scene(case, with_machine=False)
    j3 = ar.ratio**2 * ar.machine_inertia
    if ar.coupling_stiffness is not None:
        c2 = ar.ratio**2 * ar.coupling_stiffness
    else:
        c2 = base.fundamental**2 * base.inertia * j3 / (base.inertia + j3)
    three = ThreeMass(base, j3, c2, ar.ratio**2 * ar.coupling_damping, ar.ratio)
    result.three_mass = three
    system3 = three.system()
    exact3 = periodic.exact_periodic(system3)
    result.three_mass_state = exact3
    observables = [
        ("chi_after", np.array([1.0, 0.0, 0.0, 0.0]), base.static),
        ("coupling_factor", np.array([0.0, three.c2, 0.0, three.b2]), base.load),
    ]
    if base.damping != drive.damping:  # from ψ: show the other reading of (8.44)
        kept = DriveScene(
            base.omega, base.transfer, base.inertia, base.stiffness, drive.damping, base.load
        )
        variant = ThreeMass(kept, j3, c2, three.b2, ar.ratio)
        state = periodic.exact_periodic(variant.system())
        clutch = periodic.maximum_of(state, observables[0][1], state.fastest).value
        result.chi_after_kept_damping = clutch / base.static
    result.three_mass_methods = compare(
        "Methods: the three-mass model, periodic state",
        "three_mass",
        [
            MethodQuantity("chi_after", "χ on the clutch", ""),
            MethodQuantity("coupling_factor", "coupling M_max/M_c", ""),
        ],
        _drive_methods(system3, exact3, observables, case.drive),
    )


# ------------------------------------------------------------------------- report


def report(result: Result) -> Report:
    case = result.case
    title = case.title or "Impulse variator: anti-resonance and absorbers"
    sections: list[Any] = []
    notes = list(result.notes)
    if case.absorber is not None and result.absorber is not None:
        sections.extend(_absorber_sections(result.absorber, result, notes))
    if result.status != "ok":
        return Report("variator", title, sections, notes, result.status, result.message)
    if case.motor is not None:
        sections.extend(_motor_sections(case.motor, result))
    if case.clutch is not None:
        sections.append(_clutch_section(case.clutch, case.drive, notes))
    if case.mechanism is not None:
        sections.extend(_mechanism_sections(case.mechanism))
    if result.drive is not None and result.two_mass is not None:
        sections.extend(_drive_sections(result, notes))
    if result.three_mass is not None and result.three_mass_state is not None:
        sections.extend(_three_mass_sections(result, notes))
    if case.pendulum is not None:
        sections.append(_pendulum_section(case.pendulum, notes))
    return Report("variator", title, sections, notes)


def _absorber_sections(s: AbsorberScene, result: Result, notes: list[Note]) -> list[Any]:
    low, high = s.resonances()
    items = [
        Quantity(
            "absorber_stiffness",
            "Absorber shaft c_g",
            s.cg,
            "N·m/rad",
            "tuned: c_g = J₂·ω² (8.39)" if s.tuned else "",
        ),
        Quantity("absorber_tuning", "Absorber tuned to √(c_g/J₂)", math.sqrt(s.cg / s.j2), "rad/s"),
        Quantity(
            "absorber_partial",
            "Disk alone √(c/J₁)",
            math.sqrt(s.c / s.j1),
            "rad/s",
            "(8.35): resonance without the absorber when it equals ω",
        ),
        Quantity("absorber_resonance_low", "Lower resonance of the two-disk system", low, "rad/s"),
        Quantity(
            "absorber_resonance_high", "Upper resonance of the two-disk system", high, "rad/s"
        ),
    ]
    sections: list[Any] = [Quantities("Anti-resonance absorber (8.36)–(8.39)", items)]
    if result.status != "ok":
        return sections
    a1, a2 = s.amplitudes(s.omega)
    alone = s.untuned(s.omega)
    static = s.m0 / s.c
    amp = [
        Quantity(
            "absorber_a1",
            "|A₁|, the disk",
            abs(a1),
            "rad",
            "exactly 0: the absorber takes the whole torque" if a1 == 0 else "",
        ),
        Quantity("absorber_a2", "|A₂|, the absorber disk", abs(a2), "rad"),
        Quantity(
            "absorber_moment",
            "Moment in the absorber shaft",
            abs(complex(s.cg, s.omega * s.bg) * (a2 - a1)),
            "N·m",
            "= M₀ when tuned" if s.tuned and s.bg == 0.0 else "",
        ),
        Quantity("absorber_static", "Static twist M₀/c", static, "rad"),
    ]
    if alone is None:
        amp.append(
            Quantity(
                "absorber_untuned",
                "|A| of the disk without the absorber",
                "unbounded",
                "",
                "c/J₁ = ω² (8.35): resonance",
            )
        )
    else:
        amp.append(
            Quantity("absorber_untuned", "|A| of the disk without the absorber", alone, "rad")
        )
    if s.bg == 0.0:
        b_low, b_high = s.band()
        amp += [
            Quantity(
                "absorber_band_low",
                "Absorber helps from",
                b_low,
                "rad/s",
                "|A₁| < M₀/|c - J₁ω²| between these",
            ),
            Quantity("absorber_band_high", "Absorber helps up to", b_high, "rad/s"),
        ]
    elif (minimum := absorber_minimum(s)) is not None:
        depth, where = minimum
        amp += [
            Quantity(
                "absorber_minimum",
                "Smallest |A₁| (damped minimum)",
                depth,
                "rad",
                f"at {where:.6g} rad/s",
            ),
            Quantity("absorber_minimum_frequency", "at", where, "rad/s"),
            Quantity("absorber_minimum_depth", "Its depth, |A₁|min/(M₀/c)", depth / static, ""),
        ]
    else:
        notes.append(
            Note(
                "warning",
                "the absorber is damped so heavily that |A₁| has no minimum between the two "
                "resonances: it no longer works as an anti-resonance absorber",
            )
        )
    sections.append(Quantities(f"Amplitudes at ω = {s.omega:.6g} rad/s", amp))
    assert result.case.absorber is not None
    sections.append(_absorber_curve(s, high, result.case.absorber.curve_points))
    assert result.absorber_methods is not None
    sections.append(result.absorber_methods)
    if s.tuned and s.bg > 0.0 and absorber_minimum(s) is not None:
        notes.append(Note("info", "with absorber damping the zero of A₁ becomes a minimum"))
    return sections


def _absorber_curve(s: AbsorberScene, high: float, points: int) -> Table:
    """|A₁|, |A₂| from ω/points up to max(2ω, 1.25 × the upper resonance)."""
    span = max(2.0, 1.25 * high / s.omega)
    rows: list[list[Any]] = []
    for k in range(1, points + 1):
        w = s.omega * span * k / points
        alone = s.untuned(w)
        try:
            if s.determinant_is_zero(w):
                raise ZeroDivisionError
            a1, a2 = s.amplitudes(w)
            cells: list[Any] = [abs(a1), abs(a2)]
        except ZeroDivisionError:
            cells = ["unbounded", "unbounded"]
        rows.append([w, w / s.omega, alone if alone is not None else "unbounded", *cells])
    return Table(
        "A₁(ω) and A₂(ω)",
        "absorber_curve",
        [
            Column("ω", "rad/s"),
            Column("ω/ω of the torque"),
            Column("|A| without absorber", "rad"),
            Column("|A₁|", "rad"),
            Column("|A₂|", "rad"),
        ],
        rows,
    )


def _motor_sections(m: Motor, result: Result) -> list[Any]:
    omega_c, omega_0, models = motor_models(m)
    kloss, seed, printed = models
    torque = m.nominal_torque or (m.nominal_power or 0.0) / rpm_to_rad_s(m.nominal_speed_rpm)
    items = [
        Quantity("motor_mains", "ω_c = 2π·f_c", omega_c, "rad/s"),
        Quantity("motor_field_speed", "ω₀ = ω_c/P", omega_0, "rad/s"),
        Quantity("motor_synchronous_rpm", "Synchronous speed n", m.synchronous, "rpm"),
        Quantity("motor_nominal_torque", "M_H", torque, "N·m"),
        Quantity("motor_critical_torque", "M_K = λ_m·M_H", m.overload_ratio * torque, "N·m"),
        Quantity(
            "motor_slip",
            "S_H = (n - n_H)/n",
            kloss.slip,
            "",
            f"the seed's (8.41) divides by n_H: {printed.slip:.5g}",
        ),
        Quantity(
            "motor_critical_slip",
            "S_K, seed's correction",
            seed.critical_slip,
            "",
            f"plain Kloss: {kloss.critical_slip:.5g}",
        ),
        Quantity("motor_critical_slip_kloss", "S_K, plain Kloss", kloss.critical_slip, ""),
        Quantity(
            "motor_time_constant",
            "T_D = 1/(ω_c·S_K), seed's correction",
            seed.time_constant,
            "s",
            f"plain Kloss: {kloss.time_constant:.5g} s",
        ),
        Quantity(
            "motor_stiffness",
            "c_D = 1/(T_D·ν·ω₀) = 2·P·M_K",
            seed.stiffness,
            "N·m/rad",
            "the same for every S_K",
        ),
        Quantity(
            "motor_damping",
            "b_D = 1/(ν·ω₀), seed's correction",
            seed.damping,
            "N·m·s/rad",
            f"plain Kloss: {kloss.damping:.5g}",
        ),
        Quantity("motor_damping_kloss", "b_D, plain Kloss", kloss.damping, "N·m·s/rad"),
    ]
    assert result.motor_methods is not None
    return [
        Quantities("Induction motor as a spring-damper (8.40)–(8.41)", items),
        result.motor_methods,
    ]


def _clutch_section(c: Clutch, drive: Drive | None, notes: list[Note]) -> Quantities:
    x1, x2, lines = clutch_lines(c)
    n = c.loading_exponent
    items = [
        Quantity(
            "clutch_c0", "c₀ of M = c₀·ξⁿ", c.c0, "N·m/rad^n", f"{c.c0 / KGF_M:.5g} kgf·m/rad^n"
        ),
        Quantity("clutch_exponent", "n", n, ""),
        Quantity("clutch_twist_min", "ξ at the lowest working load", x1, "rad"),
        Quantity("clutch_twist_max", "ξ at the highest working load", x2, "rad"),
        Quantity(
            "clutch_tangent",
            "Tangent stiffness at the top, n·M_max/ξ_max",
            n * c.load_max / x2,
            "N·m/rad",
        ),
    ]
    for line in lines:
        items.append(
            Quantity(
                f"clutch_{line.key}",
                f"{line.name}",
                line.stiffness,
                "N·m/rad",
                f"{line.stiffness / KGF_M:.5g} kgf·m/rad",
            )
        )
        items.append(
            Quantity(f"clutch_{line.key}_error", "  its largest error / M_max", line.error, "")
        )
    if c.unloading is not None:
        ls = lines[1].stiffness
        items.append(
            Quantity(
                "clutch_unloading",
                "Unloading line (linearized)",
                c.unloading,
                "N·m/rad",
                f"{c.unloading / ls:.4g} × the least-squares loading line",
            )
        )
        if not 0.2 < c.unloading / ls < 5:
            notes.append(
                Note(
                    "warning",
                    f"the clutch's unloading line is {c.unloading / ls:.3g} times its loading "
                    "line over the working range: the loading curve and the linear stiffness "
                    "do not describe the same clutch at these loads",
                )
            )
    if c.loop_area_ratio is not None:
        psi = c.loop_area_ratio
        items.append(
            Quantity(
                "clutch_damping_ratio",
                "Damping ratio ζ = ψ/(4π) from the loop (8.43)–(8.44)",
                psi / (4.0 * math.pi),
                "",
                f"ψ = {psi:g}; b = ψ/(2π)·√(J·c)",
            )
        )
    if drive is not None:
        ratio = drive.stiffness / lines[1].stiffness
        if not 0.2 < ratio < 5:
            notes.append(
                Note(
                    "info",
                    f"[drive] uses c = {drive.stiffness:.5g} N·m/rad, {ratio:.3g} times the "
                    "least-squares line of [clutch]",
                )
            )
    return Quantities("Overrunning clutch: loading curve (8.42) and its lines", items)


def _mechanism_sections(m: Mechanism) -> list[Any]:
    t = transfer_of(m)
    mean = t.mean_first()
    items = [
        Quantity(
            "mechanism_stroke",
            "Working stroke Δα = 2π/z",
            t.stroke,
            "rad",
            f"{math.degrees(t.stroke):.4g}°",
        ),
        Quantity("mechanism_ratio", "Mean ratio i_c", t.ratio, ""),
        Quantity(
            "mechanism_output_rpm", "Mean output speed n₁/i_c", m.input_speed_rpm / t.ratio, "rpm"
        ),
        Quantity("mechanism_a0", "a₀", t.a0, ""),
        Quantity("mechanism_b0", "b₀ = Π′max", t.b0, ""),
        Quantity(
            "mechanism_first_end", "Π′ at the ends of the stroke", t.first(0.5 * t.stroke), ""
        ),
        Quantity(
            "mechanism_second_end",
            "|Π″| at the ends of the stroke",
            abs(t.second(0.5 * t.stroke)),
            "1/rad",
        ),
        Quantity(
            "mechanism_mean_first",
            "Mean of Π′ over the stroke",
            mean,
            "",
            f"1/i_c = {1.0 / t.ratio:.10g}",
        ),
        Quantity("mechanism_mean_check", "(mean Π′)·i_c - 1", mean * t.ratio - 1.0, "", "check: 0"),
    ]
    rows: list[list[Any]] = []
    for k in range(9):
        x = t.stroke * (k / 8.0 - 0.5)
        rows.append([math.degrees(x), t.position(x), t.first(x), t.second(x)])
    table = Table(
        "Transfer functions over the stroke (8.46)",
        "mechanism_transfer",
        [Column("α - α_c", "deg"), Column("Π - φ_c", "rad"), Column("Π′"), Column("Π″", "1/rad")],
        rows,
    )
    return [Quantities("Elementary mechanism (8.46)", items), table]


def _drive_sections(result: Result, notes: list[Note]) -> list[Any]:
    d, exact = result.drive, result.two_mass
    assert d is not None and exact is not None and result.two_mass_methods is not None
    beta = math.sqrt(d.stiffness / d.inertia)
    zeta = d.damping / (2.0 * math.sqrt(d.stiffness * d.inertia))
    top = periodic.maximum_of(exact, CLUTCH, exact.fastest)
    u0, _ = d.excitation()
    machine = result.three_mass is not None
    items = [
        Quantity(
            "drive_inertia",
            "J of the two-mass model" + (", J₂ + i²J₃" if machine else ""),
            d.inertia,
            "kg·m^2",
        ),
        Quantity("drive_stiffness", "Clutch c", d.stiffness, "N·m/rad"),
        Quantity("drive_damping", "Clutch b", d.damping, "N·m·s/rad", f"ζ = {zeta:.4g}"),
        Quantity("drive_fundamental", "Excitation Ω = z·ω", d.fundamental, "rad/s"),
        Quantity("drive_natural", "β = √(c/J)", beta, "rad/s"),
        Quantity("drive_frequency_ratio", "β/Ω", beta / d.fundamental, ""),
        Quantity("drive_acceleration", "Peak of J·ω²·Π″", d.inertia * abs(u0), "N·m"),
        Quantity("drive_static", "q_c = M_c/c", d.static, "rad"),
        Quantity("drive_q_max", "q_max", top.value, "rad"),
        Quantity(
            "drive_chi",
            "χ = q_max/q_c (8.47)",
            top.value / d.static,
            "",
            f"peak at {top.time / d.period * math.degrees(d.transfer.stroke):.4g}° into the stroke",
        ),
        Quantity("drive_moment_max", "Peak clutch moment c·q_max", d.stiffness * top.value, "N·m"),
    ]
    title = "Two-mass model, periodic state" + (" (before: J₃ rigid on J₂)" if machine else "")
    points = result.case.drive.points if result.case.drive else 13
    tau = np.linspace(0.0, d.period, points)
    q = exact.observe(CLUTCH, tau)
    table = Table(
        "q(τ) over one stroke",
        "drive_history",
        [Column("τ", "s"), Column("α - α₁", "deg"), Column("q", "rad"), Column("q/q_c")],
        [
            [
                float(t),
                float(t) / d.period * math.degrees(d.transfer.stroke),
                float(v),
                float(v) / d.static,
            ]
            for t, v in zip(tau, q, strict=True)
        ],
    )
    _resolution_note(exact, d.period, notes)
    return [Quantities(title, items), table, result.two_mass_methods]


def _three_mass_sections(result: Result, notes: list[Note]) -> list[Any]:
    three, exact = result.three_mass, result.three_mass_state
    assert three is not None and exact is not None and result.drive is not None
    assert result.two_mass is not None and result.three_mass_methods is not None
    d = three.drive
    before = periodic.maximum_of(result.two_mass, CLUTCH, result.two_mass.fastest).value / d.static
    clutch = periodic.maximum_of(exact, np.array([1.0, 0.0, 0.0, 0.0]), exact.fastest).value
    after = clutch / d.static
    coupling = periodic.maximum_of(exact, np.array([0.0, three.c2, 0.0, three.b2]), exact.fastest)
    low, high = three.natural_frequencies()
    i = three.ratio
    items = [
        Quantity("antiresonance_machine", "J₃' = i²·J₃", three.j3, "kg·m^2"),
        Quantity(
            "antiresonance_coupling",
            "Coupling c₂",
            three.c2 / i**2,
            "N·m/rad",
            "tuned: (zω)²·J₂J₃'/(J₂ + J₃')/i²"
            if result.case.antiresonance and result.case.antiresonance.coupling_stiffness is None
            else "as given",
        ),
        Quantity(
            "antiresonance_frequency",
            "Clutch anti-resonance √(c₂'(J₂ + J₃')/(J₂J₃'))",
            three.antiresonance,
            "rad/s",
            f"excitation Ω = {d.fundamental:.6g} rad/s",
        ),
        Quantity("antiresonance_natural_low", "Natural frequency, lower", low, "rad/s"),
        Quantity("antiresonance_natural_high", "Natural frequency, upper", high, "rad/s"),
        Quantity("antiresonance_chi_before", "χ before (J₃ rigid on J₂)", before, ""),
        Quantity("antiresonance_chi_after", "χ after", after, ""),
        Quantity(
            "antiresonance_reduction",
            "Dynamic load on the clutch reduced",
            (before - 1.0) / (after - 1.0),
            "×",
            "(χ_before - 1)/(χ_after - 1); seed: 30 calculated, 29 measured",
        ),
        Quantity("antiresonance_chi_ratio", "χ_before/χ_after", before / after, ""),
        Quantity(
            "antiresonance_coupling_max",
            "Peak coupling moment (at the coupling)",
            coupling.value / i,
            "N·m",
        ),
        Quantity(
            "antiresonance_coupling_factor",
            "Coupling M_max/M_c, the load moved onto c₂",
            coupling.value / d.load,
            "",
        ),
        Quantity("antiresonance_clutch_damping", "Clutch b₁ in this model", d.damping, "N·m·s/rad"),
    ]
    kept = result.chi_after_kept_damping
    if kept is not None:
        items += [
            Quantity(
                "antiresonance_chi_after_kept_damping",
                "χ after, had the clutch kept b₁ of the two-mass model",
                kept,
                "",
                "(8.44) read with J₂ + i²J₃ instead of J₂",
            ),
            Quantity(
                "antiresonance_reduction_kept_damping",
                "Reduction then",
                (before - 1.0) / (kept - 1.0),
                "×",
            ),
        ]
        notes.append(
            Note(
                "info",
                "b₁ follows (8.44) with the inertia the clutch faces (J₂ + i²J₃ before, J₂ "
                f"after); with b₁ kept from the two-mass model the reduction would be "
                f"{(before - 1.0) / (kept - 1.0):.3g}×",
            )
        )
    _resolution_note(exact, d.period, notes)
    return [
        Quantities("Three-mass anti-resonance design (Fig. 8.10)", items),
        result.three_mass_methods,
    ]


def _resolution_note(exact: periodic.Periodic, period: float, notes: list[Note]) -> None:
    samples, resolved = periodic.samples_for(period, exact.fastest)
    if not resolved:
        notes.append(
            Note(
                "warning",
                f"the fastest mode ({exact.fastest:.4g} rad/s) has fewer than 16 of the "
                f"{samples} samples per period: maxima may be short by its amplitude",
            )
        )


def _pendulum_section(p: Pendulum, notes: list[Note]) -> Quantities:
    r, n = p.pivot_radius, p.order
    length = r / (n * n)
    items = [
        Quantity(
            "pendulum_length", "Tuned length L = R/n² (8.55)", length, "m", f"{length * 1e3:.4g} mm"
        ),
        Quantity("pendulum_length_ratio", "L/R", length / r, ""),
    ]
    omega = p.omega
    if omega is not None:
        items.append(Quantity("pendulum_frequency", "Pendulum frequency n·ω", n * omega, "rad/s"))
    if p.max_swing is not None:
        factor = agm(1.0, math.cos(0.5 * p.max_swing))
        items += [
            Quantity(
                "pendulum_order_at_swing",
                "Order at the full swing, n·AGM(1, cos(θ/2))",
                n * factor,
                "",
                "a large swing detunes the pendulum downwards",
            ),
            Quantity(
                "pendulum_length_at_swing", "L tuned at the full swing", length * factor**2, "m"
            ),
        ]
    if p.inertia_torque is not None and omega is not None and p.max_swing is not None:
        mass = p.inertia_torque / (omega * omega * (r + length) * r * p.max_swing)
        bob = (3.0 * mass / (4.0 * math.pi * p.bob_density)) ** (1.0 / 3.0)
        items += [
            Quantity("pendulum_mass", "Mass m = M/(ω²(R + L)·R·θ_max) (8.56)", mass, "kg"),
            Quantity("pendulum_bob_radius", "Radius of a ball of that mass", bob, "m"),
            Quantity(
                "pendulum_buildable", "Fits on the pendulum (ball radius < L)", bob < length, ""
            ),
        ]
        if bob >= length:
            notes.append(
                Note(
                    "warning",
                    f"L = {length * 1e3:.4g} mm is too short to build: a bob of {mass:.4g} kg "
                    f"is a ball of radius {bob * 1e3:.4g} mm; use a bifilar or bushing design "
                    "(Fig. 8.16), where L is the difference of two diameters",
                )
            )
    else:
        notes.append(
            Note(
                "info",
                "give speed, inertia_torque and max_swing in [pendulum] to size the bob "
                "(8.56) and check that it fits on so short a pendulum",
            )
        )
    if p.bifilar_pin_diameter is not None:
        items.append(
            Quantity(
                "pendulum_bifilar_hole",
                "Bifilar: hole diameter d + L",
                p.bifilar_pin_diameter + length,
                "m",
                f"pin {p.bifilar_pin_diameter * 1e3:.4g} mm",
            )
        )
    return Quantities("Centrifugal pendulum absorber (8.49)–(8.56)", items)


# ------------------------------------------------------------------------- charts

#: Points of a curve over its whole range, before refinement at a notch.
CURVE_POINTS = 601
#: Samples of q(τ) over one stroke at most, uniform and again after the jump.
STROKE_SAMPLES = 4096


def charts(result: Result) -> list[Chart]:
    """The curves behind the report (``--plot``), closed forms and the periodic states
    already solved, no ODE run:

    * 7a: |A₁|, |A₂| and the disk without the absorber against ω/ω of the torque;
    * 7c: the loading curve M = c₀·ξⁿ and its three lines;
    * 7d: Π - φ_c, Π′, Π″ over a stroke;
    * 7e/7f: q/q_c over one stroke, before and after the coupling;
    * 7f: the clutch under one harmonic of u, before and after, against ν/(zω);
    * 7g: the pendulum's swing against its order (its backbone).

    With no answer only the absorber's curve, which shows ω on a resonance."""
    case = result.case
    out: list[Chart] = []
    if result.absorber is not None:
        out.append(_absorber_chart(result.absorber))
    if result.status != "ok":
        return out
    if case.clutch is not None:
        out.append(_clutch_chart(case.clutch))
    if case.mechanism is not None:
        out.append(_mechanism_chart(case.mechanism))
    if result.drive is not None and result.two_mass is not None:
        out.append(_stroke_chart(result))
    if result.drive is not None and result.three_mass is not None:
        out.append(_antiresonance_chart(result.drive, result.three_mass))
    if case.pendulum is not None:
        out.append(_pendulum_chart(case.pendulum))
    return out


def _refined(grid: np.ndarray, notches: list[float]) -> list[float]:
    """``grid`` with the neighbours 10⁻²…10⁻⁴ away (relative) of each notch added
    within the grid's range: the dip of an amplitude to 0 shows on a log axis (the
    notch itself would give 0, or round-off far below the rest of the curve)."""
    low, high = float(grid[0]), float(grid[-1])
    points = {float(v) for v in grid}
    for notch in notches:
        for step in (1e-2, 1e-3, 1e-4):
            for v in (notch * (1.0 - step), notch * (1.0 + step)):
                if low <= v <= high:
                    points.add(v)
    return sorted(points)


def _absorber_chart(s: AbsorberScene) -> Chart:
    from mdcalc.plot import Chart, Mark, Series

    _, high = s.resonances()
    span = max(2.0, 1.25 * high / s.omega)  # the range of the A₁(ω) table
    tuning = math.sqrt(s.cg / s.j2) / s.omega  # undamped, A₁ = 0 there
    curves: dict[str, tuple[list[float], list[float]]] = {
        "without the absorber, M₀/|c - J₁ω²|": ([], []),
        "|A₁|, the disk": ([], []),
        "|A₂|, the absorber disk": ([], []),
    }
    alone, first, second = curves.values()
    # and the design ratio itself, where the report gives the amplitudes
    for ratio in sorted({1.0, *_refined(np.linspace(0.0, span, CURVE_POINTS), [1.0, tuning])}):
        w = ratio * s.omega
        untuned = s.untuned(w)
        if untuned is not None:  # None at the disk's own resonance
            alone[0].append(ratio)
            alone[1].append(untuned)
        if s.determinant_is_zero(w):
            continue
        try:
            a1, a2 = s.amplitudes(w)
        except ZeroDivisionError:
            continue
        # |k_g - J₂ω²| at round-off: A₁ is 0 there (the notch), which no log axis shows
        notch = abs(complex(s.cg, w * s.bg) - s.j2 * w * w) <= 1e-9 * s.cg
        for (x, y), value in ((first, abs(a1)), (second, abs(a2))):
            if math.isfinite(value) and not (notch and x is first[0]):
                x.append(ratio)
                y.append(value)
    styles: tuple[Style, ...] = ("dotted", "line", "dashed")
    series = [
        Series(label, x, y, style)
        for (label, (x, y)), style in zip(curves.items(), styles, strict=True)
    ]
    if s.bg > 0.0 and (minimum := absorber_minimum(s)) is not None:
        depth, where = minimum
        series.append(Series("damped minimum of |A₁|", [where / s.omega], [depth], "points"))
    marks = [Mark("x", 1.0, f"ω of the torque, {s.omega:.4g} rad/s")]
    if abs(tuning - 1.0) > 1e-9:
        marks.append(Mark("x", tuning, f"absorber tuned to √(c_g/J₂) = {tuning * s.omega:.4g}"))
    return Chart(
        "Anti-resonance absorber (8.38): |A| against ω"
        + (f", b_g = {s.bg:g} N·m·s/rad" if s.bg > 0.0 else ", undamped (peaks cut by the grid)"),
        "ω/ω of the torque [-]",
        "amplitude |A| [rad]",
        [c for c in series if c.x],
        marks,
        y_log=True,
    )


def _clutch_chart(c: Clutch) -> Chart:
    from mdcalc.plot import Chart, Mark, Series

    x1, x2, lines = clutch_lines(c)
    n = c.loading_exponent
    twist = np.linspace(0.0, 1.1 * x2, 221)
    # M_max·(ξ/ξ_max)ⁿ: no power of ξ itself (c₀ and ξ may be far from 1)
    series = [
        Series("loading curve M = c₀·ξⁿ", twist.tolist(), (c.load_max * (twist / x2) ** n).tolist())
    ]
    styles: tuple[Style, ...] = ("dashed", "dotted", "dashed")
    for line, style in zip(lines, styles, strict=True):
        # the chord is a line over the working range only (it misses the origin)
        x = twist if line.offset == 0.0 else np.linspace(x1, 1.1 * x2, 101)
        series.append(
            Series(
                f"{line.key.replace('_', ' ')}: {line.stiffness:.4g} N·m/rad",
                x.tolist(),
                (line.offset + line.stiffness * x).tolist(),
                style,
            )
        )
    marks = [Mark("x", x2, "working range")]
    if x1 > 0.0:
        marks.append(Mark("x", x1))
    return Chart(
        f"Overrunning clutch: loading curve (8.42), n = {n:g}, and its lines over "
        f"{c.load_min:g} … {c.load_max:g} N·m",
        "clutch twist ξ [rad]",
        "moment M [N·m]",
        series,
        marks,
    )


def _mechanism_chart(m: Mechanism) -> Chart:
    from mdcalc.plot import Chart, Mark, Series

    t = transfer_of(m)
    x = np.linspace(-0.5 * t.stroke, 0.5 * t.stroke, 121).tolist()
    degrees = [math.degrees(v) for v in x]
    return Chart(
        f"Elementary mechanism (8.46): transfer functions over a stroke, z = {m.mechanisms}, "
        f"i_c = {t.ratio:.4g}",
        "α - α_c [deg]",
        "Π - φ_c [rad], Π′ [-], Π″ [1/rad]",
        [
            Series("Π′", degrees, [t.first(v) for v in x]),
            Series("Π″", degrees, [t.second(v) for v in x], "dashed"),
            Series("Π - φ_c", degrees, [t.position(v) for v in x], "dotted"),
        ],
        [Mark("y", 1.0 / t.ratio, "mean of Π′ = 1/i_c")],
    )


def _stroke_times(state: periodic.Periodic, period: float) -> tuple[np.ndarray, bool]:
    """Times over [0, T] for q(τ), and whether they resolve the fastest mode: 16
    samples per its period, up to STROKE_SAMPLES; a mode too fast for that rings only
    after each jump of the load, so its first 8 decay times get their own samples."""
    fastest = state.fastest
    wanted = 16.0 * fastest * period / (2.0 * math.pi)
    uniform = np.linspace(0.0, period, int(min(max(wanted, 512.0), STROKE_SAMPLES)) + 1)
    if wanted <= STROKE_SAMPLES:
        return uniform, True
    decay = -float(np.max(state.eigenvalues.real[np.abs(state.eigenvalues) >= 0.5 * fastest]))
    if decay <= 0.0:
        return uniform, False
    span = min(period, 8.0 / decay)
    wanted = 16.0 * fastest * span / (2.0 * math.pi)
    dense = np.linspace(0.0, span, int(min(wanted, STROKE_SAMPLES)) + 1)
    return np.union1d(uniform, dense), wanted <= STROKE_SAMPLES


def _stroke_chart(result: Result) -> Chart:
    from mdcalc.plot import Chart, Mark, Series

    d, before = result.drive, result.two_mass
    assert d is not None and before is not None
    three = result.three_mass_state
    states = [
        (
            "before: J₃ rigid on J₂" if three is not None else "q/q_c",
            before,
            CLUTCH,
        )
    ]
    if three is not None:
        states.append(("after: coupling c₂ and J₃", three, np.array([1.0, 0.0, 0.0, 0.0])))
    series, resolved = [], True
    stroke = math.degrees(d.transfer.stroke)
    for label, state, w in states:
        tau, ok = _stroke_times(state, d.period)
        resolved = resolved and ok
        series.append(
            Series(
                label,
                (tau / d.period * stroke).tolist(),
                (state.observe(w, tau) / d.static).tolist(),
            )
        )
    return Chart(
        "Clutch deformation over one stroke, periodic state; χ = max q/q_c (8.47)"
        + ("" if resolved else " (the fastest mode's ringing is not resolved)"),
        "α - α₁, into the stroke [deg]",
        "q/q_c [-]",
        series,
        [Mark("y", 1.0, "static q_c = M_c/c")],
    )


def _antiresonance_chart(before: DriveScene, three: ThreeMass) -> Chart:
    """|q₁| under u = U·e^(iνt), in units of its static value (J₂ + J₃')·U/c₁ (the
    same in both models): J·q″ + b·q′ + c·q = J·u before, the system of (7f) after."""
    from mdcalc.plot import Chart, Mark, Series

    fundamental = three.drive.fundamental  # Ω = zω
    j, c, b = before.inertia, before.stiffness, before.damping
    natural = max(math.sqrt(c / j), *three.natural_frequencies())
    top = max(4.0, 1.5 * natural / fundamental)
    zero = three.antiresonance / fundamental
    ratios = np.array(_refined(np.geomspace(0.05, top, CURVE_POINTS), [1.0, zero]))
    nu = ratios * fundamental
    static = j / c
    old = np.abs(j / (c - j * nu * nu + 1j * nu * b)) / static
    s = three.system()
    m = (
        s.stiffness[None, :, :]
        - (nu * nu)[:, None, None] * s.mass
        + 1j * nu[:, None, None] * s.damping
    )
    det = m[:, 0, 0] * m[:, 1, 1] - m[:, 0, 1] * m[:, 1, 0]
    one, two = s.shape[0] * m[:, 1, 1], m[:, 0, 1] * s.shape[1]
    with np.errstate(divide="ignore", invalid="ignore"):
        new = np.abs((one - two) / det) / static
    # q₁ = 0 to round-off (the anti-resonance itself), which no log axis shows
    new[np.abs(one - two) <= 1e-9 * (np.abs(one) + np.abs(two))] = np.nan
    series = []
    pairs: tuple[tuple[str, np.ndarray, Style], ...] = (
        ("before: J₃ rigid on J₂", old, "dashed"),
        ("after: coupling c₂ and J₃", new, "line"),
    )
    for label, values, style in pairs:
        keep = np.isfinite(values)
        series.append(Series(label, ratios[keep].tolist(), values[keep].tolist(), style))
    marks = [Mark("x", 1.0, f"Ω = zω = {fundamental:.4g} rad/s, the design")]
    if abs(zero - 1.0) > 1e-9:
        marks.append(Mark("x", zero, f"clutch anti-resonance {three.antiresonance:.4g} rad/s"))
    return Chart(
        "Anti-resonance (7f): the clutch under one harmonic ν of u = ω²Π″, before and after",
        "ν/Ω [-]",
        "|q₁| / ((J₂ + i²J₃)·|u|/c₁) [-]",
        series,
        marks,
        x_log=True,
        y_log=True,
    )


def _pendulum_chart(p: Pendulum) -> Chart:
    from mdcalc.plot import Chart, Mark, Series

    n = p.order
    top = (
        math.pi / 2
        if p.max_swing is None
        else min(0.95 * math.pi, max(2.0 * p.max_swing, math.pi / 3))
    )
    swings = np.linspace(0.0, top, 181).tolist()
    series = [
        Series(
            "free swing, n(θ)/n = AGM(1, cos(θ/2))",
            [agm(1.0, math.cos(0.5 * t)) for t in swings],
            [math.degrees(t) for t in swings],
        )
    ]
    marks = [Mark("x", 1.0, f"tuned: L = R/n² = {p.pivot_radius / n**2 * 1e3:.4g} mm")]
    if p.max_swing is not None:
        factor = agm(1.0, math.cos(0.5 * p.max_swing))
        series.append(
            Series(
                f"at θ_max: order {n * factor:.4g}",
                [factor],
                [math.degrees(p.max_swing)],
                "points",
            )
        )
        marks.append(Mark("y", math.degrees(p.max_swing), "θ_max"))
    return Chart(
        f"Centrifugal pendulum, order n = {n:g}: swing against its frequency ratio (backbone)",
        "n(θ)/n, the pendulum's order over its design order [-]",
        "swing amplitude θ [deg]",
        series,
        marks,
    )


def template() -> dict[str, Any]:
    return {
        "problem": "variator",
        "title": "Two-disk anti-resonance absorber",
        "absorber": {
            "inertia": 2.0,
            "stiffness": 800.0,
            "absorber_inertia": 0.2,
            "torque_amplitude": 100.0,
            "frequency": 20.0,
        },
        "pendulum": {"pivot_radius": 0.1, "order": 4.0},
    }
