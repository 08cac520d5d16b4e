"""The case file of ``mdcalc acceleration``: pydantic sections in SI units, the engine
speeds a case implies (launch, shift, rev limit, with their defaults), and the
starter case."""

from __future__ import annotations

import math
from typing import Any, Literal

from pydantic import Field, model_validator

from mdcalc.core.units import STANDARD_GRAVITY, rpm_to_rad_s
from mdcalc.domain.vehicle import Drag, SurfaceName, adhesion_of, speed_of
from mdcalc.input.model import CaseBase, CaseModel, FieldError, exactly_one
from mdcalc.problems.acceleration.engine import EngineCurve

RAD_S_TO_RPM = 30.0 / math.pi


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
        description="A/m in (7.42), traction per unit gear ratio; lecture 1.1 [m/s²]",
    )
    shift_angular_speed: float | None = Field(
        default=None, gt=0, description="ω_D in (7.40), engine speed ending each gear [rad/s]"
    )


class Case(CaseBase):
    problem: Literal["acceleration"] = Field(description="Problem name [-]")
    gravity: float = Field(default=STANDARD_GRAVITY, gt=0, description="Gravity g [m/s²]")
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


# The engine speeds of a case, with their defaults (the case validates itself with
# them; the scene runs with them).


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


def starter_extras() -> dict[str, Any]:
    """Example values ``mdcalc new`` shows commented out beside :func:`template` (keys
    of its sections, optional sections; ``_or``: keys shown but not uncommented)."""
    return {
        "_source": "the VAZ-2106 of seed 000 §7.3 (its catalogue engine data)",
        "vehicle": {"rotating_mass_factors": [1.46, 1.2, 1.11, 1.08]},
        "engine": {
            "max_speed_rpm": 5600.0,
            "torque_curve": {"speed_rpm": [1000.0, 3000.0, 5400.0],
                             "torque": [96.0, 116.0, 100.8]},
        },
        "transmission": {"shift_speed_rpm": 5400.0, "launch_speed_rpm": 2000.0},
        "target": {"speed": 27.78, "measured_time": 17.0, "table_step": 0.5},
        "adhesion": {"coefficient": 0.8, "cg_height": 0.55, "wheelbase": 2.424},
        "lecture": {"traction_coefficient": 1.1, "shift_angular_speed": 300.0},
    }  # fmt: skip
