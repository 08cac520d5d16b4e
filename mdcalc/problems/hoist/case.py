"""The case file of ``mdcalc hoist``: pydantic sections in SI units, and the
starter case."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import Field, model_validator

from mdcalc.core.units import STANDARD_GRAVITY, rpm_to_rad_s
from mdcalc.input.model import CaseBase, CaseModel

Efficiency = Annotated[float, Field(gt=0, le=1)]


class Load(CaseModel):
    mass: float = Field(gt=0, description="Mass of the load with its hook block [kg]")
    lifting_speed: float = Field(gt=0, description="Steady lifting speed V [m/s]")


class Shaft(CaseModel):
    name: str = Field(min_length=1, description="What turns on this shaft [-]")
    inertia: float = Field(gt=0, description="Moment of inertia on the shaft [kg·m²]")
    speed_rpm: float | None = Field(default=None, gt=0, description="Shaft speed [rpm]")
    ratio: float | None = Field(
        default=None, gt=0, description="Gear ratio from the motor, omega_1/omega_k [-]"
    )

    @model_validator(mode="after")
    def _one_speed(self) -> Shaft:
        if (self.speed_rpm is None) == (self.ratio is None):
            raise ValueError("give exactly one of speed_rpm or ratio")
        return self

    def speed_ratio(self, motor_speed: float) -> float:
        """omega_k/omega_1 [-]."""
        if self.ratio is not None:
            return 1.0 / self.ratio
        assert self.speed_rpm is not None
        return rpm_to_rad_s(self.speed_rpm) / motor_speed


class Drive(CaseModel):
    motor_speed_rpm: float = Field(gt=0, description="Motor speed, steady lifting [rpm]")
    motor_inertia: float = Field(
        gt=0, description="J1: rotor, coupling and brake pulley on the motor shaft [kg·m²]"
    )
    stage_efficiencies: list[Efficiency] = Field(
        min_length=1, description="Efficiencies of the gear stages and the drum [-]"
    )
    pulley_efficiency: Efficiency = Field(
        default=1.0, description="Efficiency of the reeving (polyspast) [-]"
    )
    brake_safety_factor: float = Field(ge=1, le=10, description="K_t of (7.27) [-]")
    shafts: list[Shaft] = Field(
        default_factory=list, description="Other inertias (gears, drum) for (7.30) [-]"
    )
    inertia_estimate_factor: float = Field(
        default=1.2, ge=1, le=2, description="Factor of (7.31) when no shafts are given [-]"
    )


class Start(CaseModel):
    time: float | None = Field(default=None, gt=0, description="Start time t_p [s]")
    starting_torque: float | None = Field(
        default=None, gt=0, description="Catalogue starting torque of the motor [N·m]"
    )
    machine: Literal["crane", "lift"] = Field(
        default="crane", description="Machine type, for the allowable acceleration [-]"
    )
    allowable_acceleration: float | None = Field(
        default=None, gt=0, description="Allowable load acceleration, overrides the table [m/s²]"
    )

    @model_validator(mode="after")
    def _one_way(self) -> Start:
        if (self.time is None) == (self.starting_torque is None):
            raise ValueError("give exactly one of time or starting_torque")
        return self


class Rope(CaseModel):
    stiffness: float | None = Field(
        default=None, gt=0, description="Stiffness of the reeving at the load c [N/m]"
    )
    elastic_modulus: float | None = Field(
        default=None, gt=0, description="Rope modulus E, with area and length [Pa]"
    )
    area: float | None = Field(default=None, gt=0, description="Metal area of one rope [m²]")
    length: float | None = Field(default=None, gt=0, description="Length of one branch [m]")
    branches: int = Field(default=1, ge=1, le=64, description="Branches carrying the load [-]")
    drive_mass: float | None = Field(
        default=None, gt=0, description="m1, drive inertia reduced to the rope line [kg]"
    )
    slack_length: float = Field(
        default=0.0, ge=0, description="Slack to take up before the rope tightens [m]"
    )

    @model_validator(mode="after")
    def _one_stiffness(self) -> Rope:
        parts = (self.elastic_modulus, self.area, self.length)
        if self.stiffness is not None and any(p is not None for p in parts):
            raise ValueError("give stiffness, or elastic_modulus with area and length, not both")
        if self.stiffness is None and any(p is None for p in parts):
            raise ValueError("give stiffness, or elastic_modulus with area and length")
        return self

    @property
    def c(self) -> float:
        if self.stiffness is not None:
            return self.stiffness
        assert self.elastic_modulus is not None and self.area is not None
        assert self.length is not None
        return self.branches * self.elastic_modulus * self.area / self.length


class Case(CaseBase):
    problem: Literal["hoist"] = Field(description="Problem name [-]")
    gravity: float = Field(default=STANDARD_GRAVITY, gt=0, description="Gravity g [m/s²]")
    load: Load
    drive: Drive
    start: Start
    rope: Rope | None = None


def template() -> dict[str, Any]:
    return {
        "problem": "hoist",
        "title": "Overhead crane main hoist, 10 t",
        "load": {"mass": 10000.0, "lifting_speed": 0.2},
        "drive": {
            "motor_speed_rpm": 960.0,
            "motor_inertia": 0.35,
            "stage_efficiencies": [0.97, 0.97, 0.98],
            "pulley_efficiency": 0.97,
            "brake_safety_factor": 1.75,
        },
        "start": {"time": 1.5, "machine": "crane"},
    }


def starter_extras() -> dict[str, Any]:
    """Example values ``mdcalc new`` shows commented out beside :func:`template` (keys
    of its sections, optional sections; ``_or``: keys shown but not uncommented)."""
    return {
        "_source": "illustrative, for the formulas of seed 000 §7.2 and §7.6",
        "drive": {
            "inertia_estimate_factor": 1.2,
            "shafts": [
                {"name": "intermediate gear", "inertia": 0.5, "ratio": 5.0,
                 "_or": {"speed_rpm": 192.0}},
            ],
        },
        "start": {"starting_torque": 450.0, "allowable_acceleration": 0.3},
        "rope": {
            "elastic_modulus": 1.0e11, "area": 1.5e-4, "length": 10.0, "branches": 4,
            "_or": {"stiffness": 6.0e6, "drive_mass": 4000.0, "slack_length": 0.05},
        },
    }  # fmt: skip
