"""``acceleration``: time for a car to reach a target speed through its gears
(seed 000 §7.3, brief §2).

Lecture method (7.40)-(7.42): constant acceleration A·U_i/m - ψ in each gear, each
gear ending where the engine reaches ω_D: v_end = ω_D·r/(U_i·U_K), capped at the
target; t_i = Δv/(A·U_i/m - ψ); total = Σ t_i + shifts·t_shift. Its conventions (ψ
subtracted as an acceleration in m/s², weight taken as mass, A/m = 1.1 given) are
kept so that it reproduces the lecture's 17.49 s; the report says so.

Physical model: δ·m·dv/dt = F_t - ψ·m·g - k·v², k = ½·ρ·C_x·A, with
F_t = M_e(n)·U_i·U_K·η/r and n the engine speed the road speed gives in gear i,
the engine torque M_e from Leiderman's curve (the brief's reading of (7.37)) or a
table, δ_i = δ_0 + δ_e·U_i² unless given. Adhesion limits the tyre force on the
driven axle to φ·N (N with load transfer when the centre-of-gravity height is
given); then δ_0·m·dv/dt = φ·N - R, the engine's surplus spinning the engine and
driveline, and the acceleration is the lesser of the two. The launch
and any gear whose road speed is below the launch engine speed start with the
clutch slipping: the engine held at the launch speed passes its torque there, the
engine's inertia is not accelerated (δ_0). Upshift at the shift engine speed: for
t_shift no traction, resistances acting (closed form, :mod:`mdcalc.core.motion`).
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

from pydantic import Field, model_validator

from mdcalc.core.motion import constant_force_phase
from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.units import STANDARD_GRAVITY, rpm_to_rad_s
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
from mdcalc.vehicle import Drag, SurfaceName, adhesion_of, speed_of

if TYPE_CHECKING:
    import numpy as np

    from mdcalc.plot import Chart

RAD_S_TO_RPM = 30.0 / math.pi

# ------------------------------------------------------------------------ the case


class TorqueCurve(CaseModel):
    speed_rpm: list[float] = Field(
        min_length=2, description="Engine speeds of the table, increasing [rpm]"
    )
    torque: list[float] = Field(min_length=2, description="Engine torque at full throttle [N·m]")

    @model_validator(mode="after")
    def _table(self) -> TorqueCurve:
        if len(self.speed_rpm) != len(self.torque):
            raise FieldError(
                ("torque",),
                f"speed_rpm has {len(self.speed_rpm)} values and torque {len(self.torque)}: "
                "they pair up",
            )
        if any(b <= a for a, b in zip(self.speed_rpm, self.speed_rpm[1:], strict=False)):
            raise FieldError(("speed_rpm",), f"got {self.speed_rpm}; must increase strictly")
        if self.speed_rpm[0] <= 0:
            raise FieldError(("speed_rpm",), f"got {self.speed_rpm[0]:g}; must be > 0 rpm")
        if any(t <= 0 for t in self.torque):
            raise FieldError(("torque",), "must be > 0 N·m at every speed of the table")
        return self


class Engine(CaseModel):
    max_power: float | None = Field(default=None, gt=0, description="N_E, maximum power [W]")
    max_power_speed_rpm: float | None = Field(
        default=None, gt=0, description="n_E, engine speed at maximum power [rpm]"
    )
    max_torque: float | None = Field(
        default=None, gt=0, description="M_E, maximum torque as published (checked) [N·m]"
    )
    max_torque_speed_rpm: float | None = Field(
        default=None, gt=0, description="n_M, engine speed at maximum torque [rpm]"
    )
    leiderman: list[float] = Field(
        default=[0.91, 0.9, 0.81],
        min_length=3,
        max_length=3,
        description="a, b, c of M = M_N·(a + b·n/n_E - c·(n/n_E)²), seed (7.37) [-]",
    )
    torque_curve: TorqueCurve | None = Field(
        default=None, description="Full-throttle torque table; replaces Leiderman's curve"
    )
    max_speed_rpm: float | None = Field(
        default=None,
        gt=0,
        description="Rev limit; default n_E, or the last speed of the torque table [rpm]",
    )

    @model_validator(mode="after")
    def _curve(self) -> Engine:
        if self.max_torque is not None and self.max_torque_speed_rpm is None:
            raise FieldError(
                ("max_torque_speed_rpm",), "required with max_torque (the point checked)"
            )
        if self.torque_curve is None and (
            self.max_power is None or self.max_power_speed_rpm is None
        ):
            raise ValueError(
                "give max_power and max_power_speed_rpm (Leiderman's curve) or a torque_curve"
            )
        return self


class Transmission(CaseModel):
    gear_ratios: list[float] = Field(
        min_length=1, max_length=20, description="U_i, gearbox ratios from first gear up [-]"
    )
    final_drive: float = Field(gt=0, description="U_K, final drive ratio [-]")
    efficiency: float = Field(gt=0, le=1, description="η, driveline efficiency [-]")
    shift_time: float = Field(
        default=1.0, ge=0, le=10, description="t_shift, time without traction per shift [s]"
    )
    shift_speed_rpm: float | None = Field(
        default=None, gt=0, description="Upshift engine speed; default n_E [rpm]"
    )
    launch_speed_rpm: float | None = Field(
        default=None,
        gt=0,
        description="Engine speed held while the clutch slips; default the peak-torque speed [rpm]",
    )

    @model_validator(mode="after")
    def _ratios(self) -> Transmission:
        ratios = self.gear_ratios
        if any(u <= 0 for u in ratios):
            raise FieldError(("gear_ratios",), f"got {ratios}; each must be > 0")
        if any(b >= a for a, b in zip(ratios, ratios[1:], strict=False)):
            raise FieldError(
                ("gear_ratios",), f"got {ratios}; must decrease from first gear up (upshifts only)"
            )
        return self


class Vehicle(CaseModel):
    mass: float = Field(gt=0, description="m, vehicle mass with driver and load [kg]")
    wheel_radius: float = Field(
        gt=0, le=5, description="r, rolling radius of the driven wheels [m]"
    )
    rotating_mass_base: float = Field(
        default=1.04, ge=1, le=3, description="δ_0 of δ_i = δ_0 + δ_e·U_i²: wheels, driveline [-]"
    )
    rotating_mass_engine: float = Field(
        default=0.04, ge=0, le=1, description="δ_e of δ_i = δ_0 + δ_e·U_i²: engine, flywheel [-]"
    )
    rotating_mass_factors: list[float] | None = Field(
        default=None, description="δ_i per gear; replaces δ_0 + δ_e·U_i² [-]"
    )

    @model_validator(mode="after")
    def _deltas(self) -> Vehicle:
        if self.rotating_mass_factors is not None and any(
            d < self.rotating_mass_base or d > 10 for d in self.rotating_mass_factors
        ):
            raise FieldError(
                ("rotating_mass_factors",),
                f"got {self.rotating_mass_factors}; each must be in "
                f"[rotating_mass_base = {self.rotating_mass_base:g}, 10]: the engine adds inertia",
            )
        return self


class Road(CaseModel):
    resistance: float = Field(
        ge=0, lt=1, description="ψ, road resistance coefficient, rolling + grade [-]"
    )


class Adhesion(CaseModel):
    """Traction limit of the driven axle; without this section traction is unlimited."""

    surface: SurfaceName | None = Field(
        default=None, description="Road surface; φ is the low end of its range [-]"
    )
    coefficient: float | None = Field(
        default=None, gt=0, le=2, description="φ, tyre-road adhesion coefficient [-]"
    )
    driven_axle_load: float = Field(
        gt=0, le=1, description="Share of the car's weight on the driven wheels at rest [-]"
    )
    drive: Literal["front", "rear", "all"] = Field(
        default="rear", description="Driven axle: load transfer adds to rear, takes from front"
    )
    cg_height: float | None = Field(
        default=None, gt=0, le=5, description="h, height of the centre of gravity [m]"
    )
    wheelbase: float | None = Field(default=None, gt=0, le=20, description="L, wheelbase [m]")

    @model_validator(mode="after")
    def _adhesion(self) -> Adhesion:
        exactly_one("adhesion", surface=self.surface, coefficient=self.coefficient)
        if (self.cg_height is None) != (self.wheelbase is None):
            missing = "wheelbase" if self.wheelbase is None else "cg_height"
            raise FieldError((missing,), "cg_height and wheelbase go together (load transfer h/L)")
        if self.drive == "rear" and self.cg_height is not None and self.wheelbase is not None:
            if self.phi * self.cg_height / self.wheelbase >= 1:
                raise FieldError(
                    ("cg_height",),
                    f"φ·h/L = {self.phi * self.cg_height / self.wheelbase:.3g} >= 1: the front "
                    "wheels would lift before the rear tyres slip",
                )
        return self

    @property
    def phi(self) -> float:
        return adhesion_of(self.surface, self.coefficient)


class Target(CaseModel):
    speed: float | None = Field(default=None, gt=0, description="Target speed [m/s]")
    speed_kmh: float | None = Field(default=None, gt=0, description="Target speed [km/h]")
    measured_time: float | None = Field(
        default=None, gt=0, description="Published or measured time to the target, compared [s]"
    )
    table_step: float | None = Field(
        default=None, gt=0, description="Time step of the speed-time table; default about 1/20 [s]"
    )

    @model_validator(mode="after")
    def _one_speed(self) -> Target:
        exactly_one("target", speed=self.speed, speed_kmh=self.speed_kmh)
        return self

    @property
    def value(self) -> float:
        return speed_of(self.speed, self.speed_kmh)


class Lecture(CaseModel):
    """The lecture's own coefficients for (7.40)-(7.42)."""

    traction_coefficient: float | None = Field(
        default=None,
        gt=0,
        description="A/m in (7.42), traction per unit gear ratio; lecture 1.1 [m/s^2]",
    )
    shift_angular_speed: float | None = Field(
        default=None, gt=0, description="ω_D in (7.40), engine speed ending each gear [rad/s]"
    )


class Case(CaseBase):
    problem: Literal["acceleration"] = Field(description="Problem name [-]")
    gravity: float = Field(default=STANDARD_GRAVITY, gt=0, description="Gravity g [m/s^2]")
    vehicle: Vehicle
    engine: Engine
    transmission: Transmission
    road: Road
    target: Target
    adhesion: Adhesion | None = None
    drag: Drag | None = None
    lecture: Lecture | None = None

    @model_validator(mode="after")
    def _consistent(self) -> Case:
        factors = self.vehicle.rotating_mass_factors
        gears = len(self.transmission.gear_ratios)
        if factors is not None and len(factors) != gears:
            raise FieldError(
                ("vehicle", "rotating_mass_factors"),
                f"got {len(factors)} values for {gears} gears; give one per gear",
            )
        curve = engine_curve(self.engine)
        limit = engine_speeds(self, curve)[2]
        if limit <= curve.low:
            raise FieldError(
                ("engine", "max_speed_rpm"),
                f"rev limit {limit * RAD_S_TO_RPM:.0f} rpm is not above the torque table's "
                f"first speed ({curve.low * RAD_S_TO_RPM:.0f} rpm)",
            )
        if default_launch_at_an_end(self, curve, limit):
            omega = curve.peak(limit)[0]
            raise FieldError(
                ("transmission", "launch_speed_rpm"),
                f"required here: the torque curve peaks at the end of its range "
                f"({omega * RAD_S_TO_RPM:.0f} rpm), which is no launch speed",
            )
        launch, shift, limit = engine_speeds(self, curve)
        if not launch <= shift <= limit:
            raise FieldError(
                ("transmission",),
                f"engine speeds must satisfy launch <= shift <= rev limit; got "
                f"{launch * RAD_S_TO_RPM:.0f} <= {shift * RAD_S_TO_RPM:.0f} <= "
                f"{limit * RAD_S_TO_RPM:.0f} rpm",
            )
        if not curve.low <= launch:
            raise FieldError(
                ("transmission", "launch_speed_rpm"),
                f"launch speed {launch * RAD_S_TO_RPM:.0f} rpm is below the torque table "
                f"({curve.low * RAD_S_TO_RPM:.0f} rpm)",
            )
        if limit > curve.high or (not curve.is_table and limit >= curve.high):
            raise FieldError(
                ("engine", "max_speed_rpm"),
                f"rev limit {limit * RAD_S_TO_RPM:.0f} rpm is beyond the torque curve, which ends "
                f"at {curve.high * RAD_S_TO_RPM:.0f} rpm",
            )
        if any(curve.torque(launch + (limit - launch) * k / 64) <= 0 for k in range(65)):
            raise FieldError(
                ("engine",), "the torque curve is not positive between launch and rev limit"
            )
        return self


# ----------------------------------------------------------------- the engine curve


@dataclass(frozen=True)
class EngineCurve:
    """Full-throttle torque against engine speed ω [rad/s]: Leiderman or a table."""

    speeds: tuple[float, ...]  # table: ω [rad/s]; Leiderman: ()
    torques: tuple[float, ...]
    rated_torque: float = 0.0  # Leiderman: M_N = N_E/ω_E [N·m]
    rated_speed: float = 0.0  # ω_E [rad/s]
    coefficients: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def is_table(self) -> bool:
        return bool(self.speeds)

    @property
    def low(self) -> float:
        """Lowest engine speed the curve covers [rad/s]."""
        return self.speeds[0] if self.is_table else 0.0

    @property
    def high(self) -> float:
        """Highest engine speed with positive torque [rad/s]."""
        if self.is_table:
            return self.speeds[-1]
        a, b, c = self.coefficients
        if c == 0.0:
            return math.inf if b >= 0 else -a / b * self.rated_speed
        # The positive root of a + b·x - c·x² (c > 0: the curve falls to zero there).
        disc = b * b + 4.0 * a * c
        if c < 0.0 or disc < 0.0:
            return math.inf
        return (b + math.sqrt(disc)) / (2.0 * c) * self.rated_speed

    def torque(self, omega: float) -> float:
        """M_e(ω) [N·m]; a table is interpolated linearly and held at its ends."""
        if self.is_table:
            s, m = self.speeds, self.torques
            if omega <= s[0]:
                return m[0]
            if omega >= s[-1]:
                return m[-1]
            k = bisect.bisect_right(s, omega)
            w = (omega - s[k - 1]) / (s[k] - s[k - 1])
            return m[k - 1] + w * (m[k] - m[k - 1])
        a, b, c = self.coefficients
        x = omega / self.rated_speed
        return self.rated_torque * (a + b * x - c * x * x)  # (7.37) read as Leiderman's

    def _candidates(self, limit: float) -> list[float]:
        """Table speeds up to ``limit``, ``limit`` itself and a fine grid: where a
        piecewise-linear torque, or the piecewise-quadratic power M·ω, peaks."""
        inside = [w for w in self.speeds if w <= limit]
        grid = [self.low + (limit - self.low) * k / 512 for k in range(513)]
        return sorted({*inside, *grid})

    def peak(self, limit: float) -> tuple[float, float]:
        """(ω, M) at the maximum torque on [low, limit]."""
        if self.is_table:
            omega = max(self._candidates(limit), key=self.torque)
            return omega, self.torque(omega)
        a, b, c = self.coefficients
        x = b / (2.0 * c) if c > 0 else limit / self.rated_speed
        omega = min(max(x * self.rated_speed, self.low), limit)
        return omega, self.torque(omega)

    def max_power_speed(self, limit: float) -> float:
        """ω of the maximum power M·ω on [low, limit]: n_E of Leiderman's curve."""
        if not self.is_table:
            return min(self.rated_speed, limit)
        return max(self._candidates(limit), key=lambda w: w * self.torque(w))


def engine_curve(engine: Engine) -> EngineCurve:
    if engine.torque_curve is not None:
        return EngineCurve(
            tuple(rpm_to_rad_s(n) for n in engine.torque_curve.speed_rpm),
            tuple(engine.torque_curve.torque),
        )
    assert engine.max_power is not None and engine.max_power_speed_rpm is not None
    omega_e = rpm_to_rad_s(engine.max_power_speed_rpm)
    a, b, c = engine.leiderman
    return EngineCurve((), (), engine.max_power / omega_e, omega_e, (a, b, c))


def engine_speeds(case: Case, curve: EngineCurve) -> tuple[float, float, float]:
    """(launch, shift, rev-limit) engine speeds [rad/s] with their defaults."""
    engine, gearbox = case.engine, case.transmission
    if engine.max_speed_rpm is not None:
        limit = rpm_to_rad_s(engine.max_speed_rpm)
    elif curve.is_table:
        limit = curve.high
    else:
        limit = curve.rated_speed
    if gearbox.shift_speed_rpm is not None:
        shift = rpm_to_rad_s(gearbox.shift_speed_rpm)
    else:  # n_E, the speed of maximum power
        shift = curve.max_power_speed(limit)
    if gearbox.launch_speed_rpm is not None:
        launch = rpm_to_rad_s(gearbox.launch_speed_rpm)
    elif engine.max_torque_speed_rpm is not None:
        launch = rpm_to_rad_s(engine.max_torque_speed_rpm)
    else:
        launch = curve.peak(limit)[0]
    return launch, shift, limit


def default_launch_at_an_end(case: Case, curve: EngineCurve, limit: float) -> bool:
    """Whether the default launch speed (peak torque) falls at an end of the curve's
    range: a flat, rising or falling curve gives no sensible launch speed by itself."""
    if case.transmission.launch_speed_rpm or case.engine.max_torque_speed_rpm:
        return False
    omega = curve.peak(limit)[0]
    span = limit - curve.low
    return omega <= curve.low + 1e-9 * span or omega >= limit - 1e-9 * span


# ------------------------------------------------------------------------ the scene


@dataclass(frozen=True)
class Scene:
    """The case reduced to SI numbers the methods share."""

    mass: float
    g: float
    radius: float
    ratios: tuple[float, ...]
    final_drive: float
    efficiency: float
    deltas: tuple[float, ...]  # δ_i, clutch engaged
    delta_free: float  # δ_0: clutch slipping or disengaged, engine not accelerated
    psi: float
    drag: float  # k [kg/m]
    phi: float | None  # adhesion coefficient; None: traction unlimited
    axle_load: float  # static normal force on the driven wheels [N]
    transfer: float  # ±h/L: +1 rear drive, -1 front, 0 all-wheel or not given
    curve: EngineCurve
    launch: float  # ω held while the clutch slips [rad/s]
    shift: float  # upshift ω [rad/s]
    limit: float  # rev limit ω [rad/s]
    shift_time: float
    target: float  # [m/s]

    @property
    def gears(self) -> int:
        return len(self.ratios)

    def overall(self, gear: int) -> float:
        return self.ratios[gear] * self.final_drive

    def engine_speed(self, gear: int, v: float) -> float:
        return v * self.overall(gear) / self.radius

    def road_speed(self, gear: int, omega: float) -> float:
        return omega * self.radius / self.overall(gear)

    def resistance(self, v: float) -> float:
        """ψ·m·g + k·v² [N]."""
        return self.psi * self.mass * self.g + self.drag * v * v

    def engine_force(self, gear: int, v: float, slipping: bool) -> float:
        """(7.35) with the engine curve: M_e·U_i·U_K·η/r [N]."""
        omega = self.launch if slipping else self.engine_speed(gear, v)
        return self.curve.torque(omega) * self.overall(gear) * self.efficiency / self.radius

    def adhesion_force(self, v: float) -> float:
        """φ·N on the driven axle; N shifts by m·a·h/L, a = (F - R)/(δ_0·m)."""
        assert self.phi is not None
        resistance = self.resistance(v)
        s = self.transfer / self.delta_free
        return self.phi * (self.axle_load - s * resistance) / (1.0 - s * self.phi)

    def delta(self, gear: int, slipping: bool) -> float:
        return self.delta_free if slipping else self.deltas[gear]

    def engine_acceleration(self, gear: int, v: float, slipping: bool) -> float:
        """(F_t - R)/(δ·m): what the engine gives if the tyres pass it."""
        force = self.engine_force(gear, v, slipping)
        return (force - self.resistance(v)) / (self.delta(gear, slipping) * self.mass)

    def adhesion_acceleration(self, v: float) -> float:
        """(φ·N - R)/(δ_0·m): the most the tyres allow. When they limit the car, the
        engine's surplus turns the engine and driveline, so their inertia (δ_e·U_i²)
        is not charged to the tyre force; δ_0 keeps the wheels'. With rear drive, no
        more than the acceleration at which the front wheels lift:
        m·a·h/L = m·g - N_0."""
        a = (self.adhesion_force(v) - self.resistance(v)) / (self.delta_free * self.mass)
        if self.transfer > 0.0:
            a = min(a, (self.mass * self.g - self.axle_load) / (self.mass * self.transfer))
        return a

    def adhesion_limited(self, gear: int, v: float, slipping: bool) -> bool:
        if self.phi is None:
            return False
        return self.adhesion_acceleration(v) < self.engine_acceleration(gear, v, slipping)

    def acceleration(self, gear: int, v: float, slipping: bool) -> float:
        a = self.engine_acceleration(gear, v, slipping)
        if self.phi is None:
            return a
        return min(a, self.adhesion_acceleration(v))

    def engine_speed_at(self, gear: int, v: float) -> float:
        """The engine's actual speed: held at the launch speed while the clutch slips."""
        return max(self.engine_speed(gear, v), self.launch)

    def slipping_at(self, gear: int, v: float) -> bool:
        """The clutch slips while the road speed gives less than the launch engine speed."""
        return self.engine_speed(gear, v) < self.launch

    def coast(self, v: float, duration: float) -> tuple[float, float]:
        """Speed after a shift of ``duration`` and the distance covered (closed form)."""
        phase = constant_force_phase(
            v, self.psi * self.mass * self.g, self.drag, self.delta_free * self.mass, duration
        )
        return phase.speed, phase.distance


def scene_of(case: Case) -> Scene:
    curve = engine_curve(case.engine)
    launch, shift, limit = engine_speeds(case, curve)
    vehicle, gearbox = case.vehicle, case.transmission
    ratios = tuple(gearbox.gear_ratios)
    if vehicle.rotating_mass_factors is not None:
        deltas = tuple(vehicle.rotating_mass_factors)
    else:
        deltas = tuple(
            vehicle.rotating_mass_base + vehicle.rotating_mass_engine * u * u for u in ratios
        )
    weight = vehicle.mass * case.gravity
    adhesion = case.adhesion
    transfer = 0.0
    if adhesion is not None and adhesion.cg_height is not None and adhesion.wheelbase is not None:
        sign = {"rear": 1.0, "front": -1.0, "all": 0.0}[adhesion.drive]
        transfer = sign * adhesion.cg_height / adhesion.wheelbase
    return Scene(
        mass=vehicle.mass,
        g=case.gravity,
        radius=vehicle.wheel_radius,
        ratios=ratios,
        final_drive=gearbox.final_drive,
        efficiency=gearbox.efficiency,
        deltas=deltas,
        delta_free=vehicle.rotating_mass_base,
        psi=case.road.resistance,
        drag=case.drag.factor if case.drag is not None else 0.0,
        phi=adhesion.phi if adhesion is not None else None,
        axle_load=(adhesion.driven_axle_load if adhesion is not None else 1.0) * weight,
        transfer=transfer,
        curve=curve,
        launch=launch,
        shift=shift,
        limit=limit,
        shift_time=gearbox.shift_time,
        target=case.target.value,
    )


# ------------------------------------------------------------------------- the plan


#: Relative distance below a resistance-limited top speed inside which a target
#: counts as not reached (see :meth:`GearLimit.allows`).
ASYMPTOTE_MARGIN = 1e-6


@dataclass(frozen=True)
class GearLimit:
    """How fast a gear can take the car: to the rev limit or to where F_t = R."""

    speed: float
    reason: Literal["rev limit", "resistance"]

    def allows(self, v: float) -> bool:
        """Whether the gear gets the car to speed ``v``. Where traction equals
        resistance the car only approaches the speed (the time grows as the log of
        1/(v_top - v)); a target within ASYMPTOTE_MARGIN of it counts as not reached."""
        if self.reason == "rev limit":
            return v <= self.speed
        return v < self.speed * (1.0 - ASYMPTOTE_MARGIN)


def gear_limit(scene: Scene, gear: int, v_in: float, samples: int = 256) -> GearLimit:
    """The first speed above ``v_in`` where the gear stops accelerating the car."""
    v_rev = scene.road_speed(gear, scene.limit)

    def pulls(v: float) -> bool:
        return scene.acceleration(gear, v, scene.slipping_at(gear, v)) > 0.0

    if v_in >= v_rev:
        return GearLimit(v_in, "rev limit")
    if not pulls(v_in):
        return GearLimit(v_in, "resistance")
    previous = v_in
    for k in range(1, samples + 1):
        v = v_in + (v_rev - v_in) * k / samples
        if not pulls(v):
            low, high = previous, v
            for _ in range(100):
                middle = 0.5 * (low + high)
                if middle in (low, high):
                    break
                low, high = (middle, high) if pulls(middle) else (low, middle)
            return GearLimit(high, "resistance")
        previous = v
    return GearLimit(v_rev, "rev limit")


def crossover(
    scene: Scene, gear: int, v_in: float, v_top: float, samples: int = 256
) -> float | None:
    """The first speed in [v_in, v_top) where the next gear accelerates the car
    harder than ``gear`` does, or None."""
    nxt = gear + 1

    def better(v: float) -> bool:
        here = scene.acceleration(gear, v, scene.slipping_at(gear, v))
        return scene.acceleration(nxt, v, scene.slipping_at(nxt, v)) > here

    if better(v_in):
        return v_in
    previous = v_in
    for k in range(1, samples):
        v = v_in + (v_top - v_in) * k / samples
        if better(v):
            low, high = previous, v
            for _ in range(60):
                middle = 0.5 * (low + high)
                low, high = (low, middle) if better(middle) else (middle, high)
            return high
        previous = v
    return None


@dataclass(frozen=True)
class Stint:
    """Drive in ``gear`` up to ``v_end``, then shift up if ``shift_after``."""

    gear: int
    v_end: float
    shift_after: bool


@dataclass(frozen=True)
class Plan:
    stints: list[Stint]
    reached: bool
    limit: GearLimit  # where the last gear stops accelerating the car
    limit_gear: int


def plan(scene: Scene, target: float) -> Plan:
    """Gears, shift speeds and whether the target is reached.

    Upshift at the shift engine speed while the target lies beyond it; where the
    gear stops pulling before that speed, upshift early at the speed where the next
    gear pulls harder. Do not upshift when the next gear cannot pull at the speed it
    lands at, or tops out below what the present gear reaches: then the present gear
    is held to the rev limit.
    """
    stints: list[Stint] = []
    v, gear = 0.0, 0
    while True:
        limit = gear_limit(scene, gear, v)
        last = gear == scene.gears - 1
        v_shift = scene.road_speed(gear, scene.shift)
        candidate: float | None = None
        if last:
            pass
        elif v_shift < target and limit.allows(v_shift):
            candidate = v_shift
        elif not limit.allows(min(target, v_shift)):
            # The gear stops pulling before the shift speed and the target: shift
            # early, where the next gear pulls harder.
            candidate = crossover(scene, gear, v, limit.speed)
        if candidate is not None:
            v_land, _ = scene.coast(candidate, scene.shift_time)
            nxt = gear + 1
            if scene.acceleration(nxt, v_land, scene.slipping_at(nxt, v_land)) > 0.0:
                next_limit = gear_limit(scene, nxt, v_land)
                if next_limit.speed > min(target, limit.speed) or next_limit.allows(target):
                    stints.append(Stint(gear, candidate, True))
                    v, gear = v_land, nxt
                    continue
        if limit.allows(target):
            stints.append(Stint(gear, target, False))
            return Plan(stints, True, limit, gear)
        return Plan(stints, False, limit, gear)


# ----------------------------------------------------------------------- the methods


@dataclass(frozen=True)
class PhaseRecord:
    label: str
    gear: int  # 0-based
    kind: Literal["slip", "drive", "shift"]
    v0: float
    v1: float
    duration: float
    distance: float
    t_end: float
    engine_speed: float | None  # at the end [rad/s]; None during a shift
    adhesion_limited: bool = False


@dataclass
class Run:
    """One method's run through the plan: phase by phase, with totals."""

    phases: list[PhaseRecord] = field(default_factory=list)
    # Dense solution pieces of an ODE run: (t0, t1, gear, slipping or None, sol).
    pieces: list[tuple[float, float, int, bool | None, Callable[[float], Any]]] = field(
        default_factory=list
    )

    @property
    def time(self) -> float:
        return self.phases[-1].t_end if self.phases else 0.0

    @property
    def distance(self) -> float:
        return sum(p.distance for p in self.phases)

    def values(self) -> dict[str, float]:
        return {"time_to_target": self.time, "distance_to_target": self.distance}


DriveStep = Callable[[Scene, int, bool, float, float, float, float, Run], tuple[float, float]]
ShiftStep = Callable[[Scene, int, float, float, float, Run], tuple[float, float]]


def drive_through(scene: Scene, stints: list[Stint], drive: DriveStep, shift: ShiftStep) -> Run:
    """Walk the plan: slip and drive phases per gear, shifts between; the method's
    ``drive`` and ``shift`` steps say how long each phase takes and how far it goes.
    """
    run = Run()
    t, x, v = 0.0, 0.0, 0.0
    for stint in stints:
        gear = stint.gear
        v_lock = scene.road_speed(gear, scene.launch)
        label = f"gear {gear + 1}"
        if v < v_lock and v < stint.v_end:
            v1 = min(v_lock, stint.v_end)
            dt, dx = drive(scene, gear, True, v, v1, t, x, run)
            t, x = t + dt, x + dx
            run.phases.append(
                PhaseRecord(
                    f"{label}, clutch slipping",
                    gear,
                    "slip",
                    v,
                    v1,
                    dt,
                    dx,
                    t,
                    scene.launch,
                    _adhesion_limited(scene, gear, True, v, v1),
                )
            )
            v = v1
        if v < stint.v_end:
            dt, dx = drive(scene, gear, False, v, stint.v_end, t, x, run)
            t, x = t + dt, x + dx
            run.phases.append(
                PhaseRecord(
                    label,
                    gear,
                    "drive",
                    v,
                    stint.v_end,
                    dt,
                    dx,
                    t,
                    scene.engine_speed(gear, stint.v_end),
                    _adhesion_limited(scene, gear, False, v, stint.v_end),
                )
            )
            v = stint.v_end
        if stint.shift_after:
            v1, dx = shift(scene, gear, v, t, x, run)
            t, x = t + scene.shift_time, x + dx
            run.phases.append(
                PhaseRecord(
                    f"shift {gear + 1}→{gear + 2}",
                    gear,
                    "shift",
                    v,
                    v1,
                    scene.shift_time,
                    dx,
                    t,
                    None,
                )
            )
            v = v1
    return run


def _adhesion_limited(scene: Scene, gear: int, slipping: bool, v0: float, v1: float) -> bool:
    return any(scene.adhesion_limited(gear, v, slipping) for v in (v0, 0.5 * (v0 + v1), v1))


def lecture_run(scene: Scene, traction_coefficient: float, omega_d: float) -> dict[str, Any]:
    """(7.40)-(7.42): per gear v_end = ω_D·r/(U_i·U_K) capped at the target and
    t_i = Δv/(A·U_i/m - ψ), ψ taken as m/s² (the lecture's convention)."""
    gears: list[tuple[float, float, float]] = []  # (v_start, v_end, t)
    v = 0.0
    for gear, u in enumerate(scene.ratios):
        v_end = min(omega_d * scene.radius / (u * scene.final_drive), scene.target)
        if gear == scene.gears - 1:
            v_end = scene.target  # top gear runs on to the target
        if v_end <= v:
            continue
        a = traction_coefficient * u - scene.psi  # (7.42) denominator
        if a <= 0.0:
            raise NotApplicable(f"A·U_{gear + 1}/m - ψ = {a:.3g} m/s² is not positive")
        gears.append((v, v_end, (v_end - v) / a))
        v = v_end
        if v >= scene.target:
            break
    shifts = len(gears) - 1
    time = sum(g[2] for g in gears) + shifts * scene.shift_time
    distance = sum(0.5 * (g[0] + g[1]) * g[2] for g in gears) + sum(
        g[1] * scene.shift_time for g in gears[:-1]
    )
    return {"gears": gears, "time": time, "distance": distance}


def _piecewise_drive(
    scene: Scene, gear: int, slipping: bool, v0: float, v1: float, t: float, x: float, run: Run
) -> tuple[float, float]:
    """Constant acceleration over the phase: the physical one at its mid-speed."""
    v_mid = 0.5 * (v0 + v1)
    a = scene.acceleration(gear, v_mid, slipping)
    if a <= 0.0:
        raise NotApplicable(f"acceleration at the mid-speed of gear {gear + 1} is not positive")
    dt = (v1 - v0) / a
    return dt, v_mid * dt


def _piecewise_shift(
    scene: Scene, gear: int, v0: float, t: float, x: float, run: Run
) -> tuple[float, float]:
    """Constant deceleration over the shift at its value at the shift speed."""
    d = scene.resistance(v0) / (scene.delta_free * scene.mass)
    duration = scene.shift_time
    if d * duration >= v0:  # the car stops within the shift
        return 0.0, v0 * v0 / (2.0 * d)
    v1 = v0 - d * duration
    return v1, 0.5 * (v0 + v1) * duration


def phase_time_estimate(scene: Scene, gear: int, slipping: bool, v0: float, v1: float) -> float:
    """∫ dv/a from v0 to v1 by the trapezoid rule on nodes crowded towards v1, where
    a target close to a top speed makes 1/a large: a bound for the ODE runs."""
    nodes = [v1 - (v1 - v0) * 10.0 ** (-k / 4) for k in range(49)] + [v1]
    inverse = [1.0 / max(scene.acceleration(gear, v, slipping), 1e-300) for v in nodes]
    return sum(
        0.5 * (inverse[k] + inverse[k + 1]) * (nodes[k + 1] - nodes[k])
        for k in range(len(nodes) - 1)
    )


def piecewise_run(scene: Scene, stints: list[Stint]) -> Run:
    return drive_through(scene, stints, _piecewise_drive, _piecewise_shift)


def ode_run(scene: Scene, stints: list[Stint], rtol: float, dense: bool = False) -> Run:
    """Integrate δ·m·v' = F_t - R, x' = v phase by phase; events end each phase."""
    import numpy as np

    from mdcalc.core.ode import advance, pick_solver

    method = pick_solver(rtol)
    atol = np.array([scene.target, scene.target]) * rtol * 1e-3

    def drive(
        scene: Scene, gear: int, slipping: bool, v0: float, v1: float, t: float, x: float, run: Run
    ) -> tuple[float, float]:
        def rhs(time: float, y: np.ndarray) -> np.ndarray:
            return np.array([scene.acceleration(gear, y[0], slipping), y[0]])

        span = 2.0 * phase_time_estimate(scene, gear, slipping, v0, v1) + 1e-3
        y = np.array([v0, x])
        t0 = t
        for _ in range(4):
            segment = advance(
                rhs,
                t,
                y,
                t + span,
                rtol=rtol,
                atol=atol,
                method=method,
                terminal=[(lambda time, y: y[0] - v1, 1)],
                dense=dense,
            )
            if dense and segment.sol is not None:
                run.pieces.append((t, segment.t, gear, slipping, segment.sol))
            t, y = segment.t, segment.y
            if segment.event is not None:
                return t - t0, float(y[1]) - x
            span *= 4.0
        raise NotApplicable(
            f"{method} did not reach {v1 * 3.6:.6g} km/h in gear {gear + 1} within "
            f"{t - t0:.3g} s: the target is within this tolerance of the top speed"
        )

    def shift(
        scene: Scene, gear: int, v0: float, t: float, x: float, run: Run
    ) -> tuple[float, float]:
        def rhs(time: float, y: np.ndarray) -> np.ndarray:
            v = max(y[0], 0.0)
            return np.array([-scene.resistance(v) / (scene.delta_free * scene.mass), v])

        segment = advance(
            rhs,
            t,
            np.array([v0, x]),
            t + scene.shift_time,
            rtol=rtol,
            atol=atol,
            method=method,
            dense=dense,
        )
        if dense and segment.sol is not None:
            run.pieces.append((t, segment.t, gear, None, segment.sol))
        return max(float(segment.y[0]), 0.0), float(segment.y[1]) - x

    return drive_through(scene, stints, drive, shift)


# ------------------------------------------------------------------------- result


@dataclass
class Result:
    case: Case
    scene: Scene
    plan: Plan
    top: Plan  # the plan with no target: the top speed
    run: Run | None = None  # the reference run (dense)
    methods: MethodsTable | None = None
    lecture: dict[str, Any] | None = None
    lecture_coefficients: tuple[float, float] = (0.0, 0.0)
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


QUANTITIES = [
    MethodQuantity("time_to_target", "time", "s"),
    MethodQuantity("distance_to_target", "distance", "m"),
]

REFERENCE_RTOL = 1e-11


def lecture_coefficients(case: Case, scene: Scene) -> tuple[float, float]:
    """(A/m, ω_D) for the lecture method: the lecture's values or the physical ones."""
    lecture = case.lecture or Lecture()
    peak_speed, peak_torque = scene.curve.peak(scene.limit)
    if lecture.traction_coefficient is not None:
        a_per_ratio = lecture.traction_coefficient
    else:  # (7.35): A = M_max·U_K·η/r
        a_per_ratio = peak_torque * scene.final_drive * scene.efficiency / scene.radius / scene.mass
    if lecture.shift_angular_speed is not None:
        omega_d = lecture.shift_angular_speed
    elif case.engine.max_torque_speed_rpm is not None:  # ω_D: the speed of maximum torque
        omega_d = rpm_to_rad_s(case.engine.max_torque_speed_rpm)
    else:
        omega_d = peak_speed
    return a_per_ratio, omega_d


def solve(case: Case) -> Result:
    scene = scene_of(case)
    top = plan(scene, math.inf)
    the_plan = plan(scene, scene.target)
    result = Result(case, scene, the_plan, top)
    if not the_plan.reached:
        result.status = "no-answer"
        result.message = _no_answer(scene, the_plan)
        return result
    coefficients = lecture_coefficients(case, scene)
    result.lecture_coefficients = coefficients
    stints = the_plan.stints
    reference: dict[str, Run] = {}

    def reference_run() -> dict[str, float]:
        reference["run"] = ode_run(scene, stints, REFERENCE_RTOL, dense=True)
        return reference["run"].values()

    def lecture_values() -> dict[str, float]:
        run = lecture_run(scene, *coefficients)
        return {"time_to_target": run["time"], "distance_to_target": run["distance"]}

    lecture_note = "ψ as m/s², A/m = {:.3g} m/s², ω_D = {:.4g} rad/s".format(*coefficients)
    methods = [
        Method("lecture (7.42)", lecture_values, note=lecture_note),
        Method(
            "piecewise-constant acceleration",
            lambda: piecewise_run(scene, stints).values(),
            note="physical a at each phase's mid-speed",
        ),
        Method(
            "ODE RK45, rtol 1e-3",
            lambda: ode_run(scene, stints, 1e-3).values(),
            imports=ODE_IMPORTS,
        ),
        Method(
            "ODE RK45, rtol 1e-6",
            lambda: ode_run(scene, stints, 1e-6).values(),
            imports=ODE_IMPORTS,
        ),
        Method(
            "ODE DOP853, rtol 1e-11",
            reference_run,
            reference=True,
            imports=ODE_IMPORTS,
            note="with dense output for the tables",
        ),
    ]
    result.methods = compare(
        "Methods: time and distance to the target speed", "target", QUANTITIES, methods
    )
    result.run = reference["run"]
    try:
        result.lecture = lecture_run(scene, *coefficients)
    except NotApplicable:
        result.lecture = None
    return result


def _no_answer(scene: Scene, the_plan: Plan) -> str:
    if not the_plan.stints and the_plan.limit.speed == 0.0:
        return _cannot_move(scene)
    limit, gear = the_plan.limit, the_plan.limit_gear
    if scene.target < limit.speed:
        return (
            f"target speed {scene.target * 3.6:.7g} km/h lies within {ASYMPTOTE_MARGIN:g} of "
            f"the top speed {limit.speed * 3.6:.7g} km/h (gear {gear + 1}), which the car only "
            "approaches: traction equals resistance there and the time to it is unbounded"
        )
    engine_rpm = scene.engine_speed_at(gear, limit.speed) * RAD_S_TO_RPM
    where = (
        f"gear {gear + 1} at the rev limit, {engine_rpm:.0f} rpm"
        if limit.reason == "rev limit"
        else f"gear {gear + 1} at {engine_rpm:.0f} rpm, where traction equals resistance"
    )
    return (
        f"target speed {scene.target * 3.6:.4g} km/h is not reachable: top speed is "
        f"{limit.speed * 3.6:.4g} km/h ({where})"
    )


def _cannot_move(scene: Scene) -> str:
    resistance = scene.resistance(0.0)
    engine = scene.engine_force(0, 0.0, True)
    text = (
        f"the car cannot move off: road resistance ψ·m·g = {resistance:.5g} N is not less than "
        f"the first-gear traction"
    )
    if scene.phi is not None:
        grip = scene.adhesion_force(0.0)
        if grip < engine:
            return (
                f"{text} the tyres can pass, φ·N = {grip:.5g} N (the engine gives {engine:.5g} N)"
            )
    launch_rpm = scene.launch * RAD_S_TO_RPM
    return f"{text}, {engine:.5g} N with the engine at the launch speed {launch_rpm:.0f} rpm"


# ------------------------------------------------------------------------- report


def report(result: Result) -> Report:
    case, scene = result.case, result.scene
    title = case.title or "Acceleration"
    sections: list[Any] = [_scene_section(case, scene), _engine_section(case, scene)]
    notes: list[Note] = []
    top = result.top
    top_rpm = scene.engine_speed_at(top.limit_gear, top.limit.speed) * RAD_S_TO_RPM
    where = f"gear {top.limit_gear + 1}, {top_rpm:.0f} rpm, {top.limit.reason}"
    if top.limit.speed == 0.0:
        where = "the car cannot move off"
    top_items = [Quantity("top_speed_kmh", "Top speed", top.limit.speed * 3.6, "km/h", where)]
    if result.status != "ok":
        sections.append(Quantities("Limits", top_items))
        sections.append(_gear_limits_table(scene))
        return Report("acceleration", title, sections, notes, result.status, result.message)

    assert result.run is not None and result.methods is not None
    if case.lecture is not None and result.lecture is not None:
        sections.append(_lecture_section(result))
        notes.append(Note("info", _lecture_conventions(result)))
    run = result.run
    outcome = [
        Quantity("time_to_target", "Time to the target speed", run.time, "s"),
        Quantity("distance_to_target", "Distance to the target speed", run.distance, "m"),
        Quantity("gear_at_target", "Gear at the target speed", run.phases[-1].gear + 1, ""),
        Quantity(
            "launch_acceleration",
            "Acceleration at launch",
            scene.acceleration(0, 0.0, scene.slipping_at(0, 0.0)),
            "m/s²",
            "adhesion-limited" if scene.adhesion_limited(0, 0.0, True) else "",
        ),
        *top_items,
    ]
    measured = case.target.measured_time
    if measured is not None:
        outcome += [
            Quantity("measured_time", "Published/measured time", measured, "s"),
            Quantity(
                "difference_from_measured",
                "Model minus measured",
                (run.time - measured) / measured * 100.0,
                "%",
            ),
        ]
    sections.append(
        Quantities(f"Reaching {scene.target * 3.6:.4g} km/h (reference method)", outcome)
    )
    sections.append(_phases_table(scene, run))
    sections.append(_speed_table(scene, run, case.target.table_step))
    sections.append(result.methods)
    if any(p.adhesion_limited for p in run.phases):
        notes.append(
            Note(
                "info",
                "traction is limited by adhesion in part of the run (phases marked): the engine "
                "could pass more torque than the driven tyres can",
            )
        )
    return Report("acceleration", title, sections, notes, result.status, result.message)


def _ratios_text(ratios: tuple[float, ...]) -> str:
    return " / ".join(f"{u:g}" for u in ratios)


def _scene_section(case: Case, scene: Scene) -> Quantities:
    items = [
        Quantity("mass", "Mass m", scene.mass, "kg"),
        Quantity("wheel_radius", "Wheel radius r", scene.radius, "m"),
        Quantity("gear_ratios", "Gear ratios U_i", _ratios_text(scene.ratios), ""),
        Quantity("final_drive", "Final drive U_K", scene.final_drive, ""),
        Quantity("efficiency", "Driveline efficiency η", scene.efficiency, ""),
        Quantity(
            "rotating_mass_factors",
            "Rotating-mass factors δ_i",
            " / ".join(f"{d:.4g}" for d in scene.deltas),
            "",
            f"δ_0 = {scene.delta_free:g} while the clutch is open or slips",
        ),
        Quantity("road_resistance", "Road resistance ψ", scene.psi, ""),
        Quantity("target_speed", "Target speed", scene.target, "m/s"),
        Quantity("target_speed_kmh", "Target speed", scene.target * 3.6, "km/h"),
        Quantity("shift_time", "Shift time", scene.shift_time, "s"),
    ]
    if case.drag is not None:
        items.append(Quantity("drag_factor", "Drag factor ½·ρ·C_x·A", scene.drag, "kg/m"))
    if case.adhesion is not None:
        assert scene.phi is not None
        items += [
            Quantity(
                "adhesion", "Adhesion coefficient φ", scene.phi, "", case.adhesion.surface or ""
            ),
            Quantity("driven_axle_load", "Driven-axle load at rest", scene.axle_load, "N"),
        ]
    return Quantities("Scene", items)


def _engine_section(case: Case, scene: Scene) -> Quantities:
    curve = scene.curve
    peak_speed, peak_torque = curve.peak(scene.limit)
    items: list[Quantity] = []
    if not curve.is_table:
        items.append(
            Quantity(
                "rated_torque",
                "Torque at maximum power M_N = N_E/ω_E",
                curve.rated_torque,
                "N·m",
            )
        )
    items.append(
        Quantity(
            "peak_torque",
            "Peak torque of the curve",
            peak_torque,
            "N·m",
            f"at {peak_speed * RAD_S_TO_RPM:.0f} rpm",
        )
    )
    engine = case.engine
    if engine.max_torque is not None and engine.max_torque_speed_rpm is not None:
        at = curve.torque(rpm_to_rad_s(engine.max_torque_speed_rpm))
        items.append(
            Quantity(
                "torque_at_n_m",
                f"Curve torque at n_M = {engine.max_torque_speed_rpm:g} rpm",
                at,
                "N·m",
                f"{(at - engine.max_torque) / engine.max_torque * 100:+.2g} % against the "
                f"published {engine.max_torque:g} N·m",
            )
        )
    items += [
        Quantity(
            "launch_speed_rpm",
            "Launch engine speed (clutch slips)",
            scene.launch * RAD_S_TO_RPM,
            "rpm",
        ),
        Quantity("shift_speed_rpm", "Upshift engine speed", scene.shift * RAD_S_TO_RPM, "rpm"),
        Quantity("rev_limit_rpm", "Rev limit", scene.limit * RAD_S_TO_RPM, "rpm"),
    ]
    title = "Engine (Leiderman curve, (7.37))" if not curve.is_table else "Engine (torque table)"
    return Quantities(title, items)


def _lecture_section(result: Result) -> Quantities:
    assert result.lecture is not None
    scene = result.scene
    a_per_ratio, omega_d = result.lecture_coefficients
    items = [
        Quantity("lecture_traction_coefficient", "A/m in (7.42)", a_per_ratio, "m/s²"),
        Quantity("lecture_shift_angular_speed", "ω_D in (7.40)", omega_d, "rad/s"),
    ]
    for k, (v0, v1, t) in enumerate(result.lecture["gears"], start=1):
        items.append(Quantity(f"lecture_v_end_{k}", f"Gear {k}: v_end (7.40)", v1, "m/s"))
        items.append(
            Quantity(
                f"lecture_time_{k}",
                f"Gear {k}: t = Δv/(A·U/m - ψ) (7.42)",
                t,
                "s",
                f"from {v0:.4g} m/s",
            )
        )
    shifts = len(result.lecture["gears"]) - 1
    items.append(
        Quantity(
            "lecture_total_time",
            f"Total, with {shifts} shifts of {scene.shift_time:g} s",
            result.lecture["time"],
            "s",
        )
    )
    return Quantities("Lecture method (7.40)-(7.42)", items)


def _lecture_conventions(result: Result) -> str:
    scene = result.scene
    a_per_ratio, omega_d = result.lecture_coefficients
    peak_speed, peak_torque = scene.curve.peak(scene.limit)
    physical = peak_torque * scene.final_drive * scene.efficiency / scene.radius / scene.mass
    lecture_source = ""
    if math.isclose(a_per_ratio, 1.1):
        lecture_source = (
            "the lecture's 1.1 rests on a garbled M_max = 206 N·m and on its weight of "
            "15 000 N taken as a mass of 1500 kg; "
        )
    return (
        "the lecture method keeps the lecture's conventions so that it reproduces its numbers, "
        f"not physics: ψ = {scene.psi:g} is subtracted as an acceleration in m/s² (physically "
        f"ψ·g = {scene.psi * scene.g:.4g} m/s²); A/m = {a_per_ratio:.4g} m/s² per unit ratio "
        f"is taken as given ({lecture_source}the curve's peak "
        f"{peak_torque:.4g} N·m with η = {scene.efficiency:g} gives {physical:.3g}); the rotating "
        "masses, drag, adhesion and the speed lost in shifts are left out; each gear ends at "
        f"ω_D = {omega_d:.4g} rad/s = {omega_d * RAD_S_TO_RPM:.0f} rpm"
    )


def _phases_table(scene: Scene, run: Run) -> Table:
    rows: list[list[Any]] = []
    for p in run.phases:
        engine = None if p.engine_speed is None else round(p.engine_speed * RAD_S_TO_RPM)
        rows.append(
            [
                p.label + (" (adhesion-limited)" if p.adhesion_limited else ""),
                p.v0 * 3.6,
                p.v1 * 3.6,
                engine,
                p.duration,
                p.distance,
                p.t_end,
            ]
        )
    return Table(
        "Phases (reference run)",
        "phases",
        [
            Column("phase"),
            Column("from", "km/h"),
            Column("to", "km/h"),
            Column("engine at end", "rpm"),
            Column("time", "s"),
            Column("distance", "m"),
            Column("clock", "s"),
        ],
        rows,
    )


def _nice_step(span: float) -> float:
    raw = span / 20.0
    exponent = math.floor(math.log10(raw))
    for mantissa in (1.0, 2.0, 5.0, 10.0):
        step = mantissa * 10.0**exponent
        if step >= raw:
            return step
    return 10.0 ** (exponent + 1)


#: Most rows of the speed-time table; a finer table_step is widened to fit.
MAX_TABLE_ROWS = 2000


def _speed_table(scene: Scene, run: Run, step: float | None) -> Table:
    step = max(step or _nice_step(run.time), run.time / MAX_TABLE_ROWS)
    rows: list[list[Any]] = []
    times = [k * step for k in range(int(run.time / step) + 1)]
    if times[-1] < run.time:
        times.append(run.time)
    for t in times:
        piece = next((p for p in run.pieces if p[0] <= t <= p[1]), run.pieces[-1])
        t0, t1, gear, slipping, sol = piece
        v, x = (float(c) for c in sol(min(max(t, t0), t1)))
        engine: int | None = None
        if slipping is None:
            label = f"shift {gear + 1}→{gear + 2}"
            v = max(v, 0.0)  # a car stopped within the shift stays stopped
            a = -scene.resistance(v) / (scene.delta_free * scene.mass) if v > 0.0 else 0.0
        else:
            label = f"{gear + 1}"
            a = scene.acceleration(gear, v, slipping)
            omega = scene.launch if slipping else scene.engine_speed(gear, v)
            engine = round(omega * RAD_S_TO_RPM)
        rows.append([t, v * 3.6, x, a, label, engine])
    return Table(
        "Speed against time (reference run)",
        "speed_time",
        [
            Column("time", "s"),
            Column("speed", "km/h"),
            Column("distance", "m"),
            Column("acceleration", "m/s²"),
            Column("gear"),
            Column("engine", "rpm"),
        ],
        rows,
    )


def _gear_limits_table(scene: Scene) -> Table:
    rows: list[list[Any]] = []
    for gear in range(scene.gears):
        limit = gear_limit(scene, gear, 0.0)
        rows.append(
            [
                f"{gear + 1}",
                scene.ratios[gear],
                limit.speed * 3.6,
                round(scene.engine_speed_at(gear, limit.speed) * RAD_S_TO_RPM)
                if limit.speed > 0.0
                else None,
                limit.reason,
            ]
        )
    return Table(
        "How fast each gear can go from rest",
        "gear_limits",
        [
            Column("gear"),
            Column("ratio"),
            Column("top speed", "km/h"),
            Column("engine", "rpm"),
            Column("limited by"),
        ],
        rows,
    )


# ------------------------------------------------------------------------- charts

#: Points of the speed-time curve over the whole run, and of each gear's curve.
CHART_POINTS = 400
GEAR_POINTS = 200


def charts(result: Result) -> list[Chart]:
    """``--plot``: the speed-time curve of the reference run (with the lecture
    method's, when it applies), and the traction diagram. The diagram needs no run,
    so a car that cannot reach the target, or cannot move off, still gets it."""
    charts: list[Chart] = []
    if result.run is not None and result.run.pieces:
        charts.append(_speed_chart(result, result.run))
    charts.append(_traction_chart(result))
    return charts


def _speed_chart(result: Result, run: Run) -> Chart:
    """v(t) from the reference run's dense output, piece by piece; marks at the
    upshifts and at the target speed."""
    from mdcalc.plot import Chart, Mark, Series

    scene = result.scene
    times: list[float] = []
    speeds: list[float] = []
    for t0, t1, _gear, _slipping, sol in run.pieces:
        n = max(8, math.ceil(CHART_POINTS * (t1 - t0) / run.time))
        for k in range(n + 1):
            if times and k == 0:
                continue  # the piece starts where the last one ended
            t = t0 + (t1 - t0) * k / n
            v = max(float(sol(t)[0]), 0.0)  # a car stopped within a shift stays stopped
            times.append(t)
            speeds.append(v * 3.6)
    series = [Series("reference run (DOP853)", times, speeds)]
    if result.lecture is not None:
        lecture_t, lecture_v, clock = [0.0], [0.0], 0.0
        gears = result.lecture["gears"]
        for k, (_v0, v1, dt) in enumerate(gears):
            clock += dt
            lecture_t.append(clock)
            lecture_v.append(v1 * 3.6)
            if k < len(gears) - 1:  # (7.42): the speed is kept through the shift
                clock += scene.shift_time
                lecture_t.append(clock)
                lecture_v.append(v1 * 3.6)
        series.append(Series("lecture method (7.40)-(7.42)", lecture_t, lecture_v, "dashed"))
    shifts = [p for p in run.phases if p.kind == "shift"]
    marks = [
        Mark("x", p.t_end - p.duration, "upshift" if k == 0 else "") for k, p in enumerate(shifts)
    ]
    marks.append(Mark("y", scene.target * 3.6, f"target {scene.target * 3.6:.4g} km/h"))
    return Chart(
        f"Speed against time: {scene.target * 3.6:.4g} km/h in {run.time:.4g} s "
        f"(gear {run.phases[-1].gear + 1} at the target)",
        "time t [s]",
        "speed v [km/h]",
        series,
        marks,
    )


def _traction_chart(result: Result) -> Chart:
    """Per gear, F_t = M_e·U_i·U_K·η/r over the engine speeds from the launch speed
    to the rev limit (first gear with the slipping launch from rest); the road
    resistance ψ·m·g + k·v², the adhesion limit φ·N and the planned upshifts."""
    from mdcalc.plot import Chart, Mark, Series

    scene = result.scene
    curve = scene.curve
    span = scene.limit - scene.launch
    nodes = sorted(
        {scene.launch + span * k / GEAR_POINTS for k in range(GEAR_POINTS + 1)}
        | {w for w in curve.speeds if scene.launch < w < scene.limit}  # the table's corners
    )
    series: list[Series] = []
    for gear in range(scene.gears):
        speeds = [scene.road_speed(gear, omega) * 3.6 for omega in nodes]
        forces = [scene.engine_force(gear, speed / 3.6, False) for speed in speeds]
        if gear == 0:  # from rest, the clutch slips with the engine at the launch speed
            speeds.insert(0, 0.0)
            forces.insert(0, scene.engine_force(0, 0.0, True))
        series.append(Series(f"gear {gear + 1} (U = {scene.ratios[gear]:g})", speeds, forces))
    v_end = max(scene.road_speed(scene.gears - 1, scene.limit), scene.target)
    road = [v_end * k / GEAR_POINTS for k in range(GEAR_POINTS + 1)]
    name = "resistance ψ·m·g + k·v²" if scene.drag > 0.0 else "resistance ψ·m·g"
    series.append(
        Series(name, [v * 3.6 for v in road], [scene.resistance(v) for v in road], "dashed")
    )
    if scene.phi is not None:
        grip = [scene.adhesion_force(v) for v in road]
        series.append(Series("adhesion limit φ·N", [v * 3.6 for v in road], grip, "dotted"))
    upshifts = [s for s in result.plan.stints if s.shift_after]
    if upshifts:
        series.append(
            Series(
                "upshifts (plan)",
                [s.v_end * 3.6 for s in upshifts],
                [
                    scene.engine_force(s.gear, s.v_end, scene.slipping_at(s.gear, s.v_end))
                    for s in upshifts
                ],
                "points",
            )
        )
    marks = [Mark("x", scene.target * 3.6, f"target {scene.target * 3.6:.4g} km/h")]
    top = result.top.limit.speed
    if result.status != "ok" and top > 0.0:
        marks.append(Mark("x", top * 3.6, f"top speed {top * 3.6:.4g} km/h"))
    return Chart(
        f"Traction diagram: F_t = M_e·U_i·U_K·η/r, engine {scene.launch * RAD_S_TO_RPM:.0f}"
        f"–{scene.limit * RAD_S_TO_RPM:.0f} rpm",
        "road speed v [km/h]",
        "force [N]",
        series,
        marks,
    )


def template() -> dict[str, Any]:
    return {
        "problem": "acceleration",
        "title": "VAZ-2106, 0-100 km/h",
        "vehicle": {"mass": 1120.0, "wheel_radius": 0.27},
        "engine": {
            "max_power": 57000.0,
            "max_power_speed_rpm": 5400.0,
            "max_torque": 116.0,
            "max_torque_speed_rpm": 3000.0,
        },
        "transmission": {
            "gear_ratios": [3.242, 1.989, 1.289, 1.0],
            "final_drive": 3.9,
            "efficiency": 0.9,
            "shift_time": 1.0,
        },
        "road": {"resistance": 0.015},
        "adhesion": {"surface": "dry-asphalt", "driven_axle_load": 0.47},
        "drag": {"drag_coefficient": 0.48, "frontal_area": 1.85},
        "target": {"speed_kmh": 100.0},
    }
