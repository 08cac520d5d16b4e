"""The case file of ``mdcalc coupling``: pydantic sections in SI units, and the
starter case."""

from __future__ import annotations

import math
from typing import Any, Literal

from pydantic import Field, model_validator

from mdcalc.core.units import rpm_to_rad_s
from mdcalc.input.model import CaseBase, CaseModel, FieldError, exactly_one

DEG = math.pi / 180.0


class Coupling(CaseModel):
    driving_inertia: float = Field(gt=0, description="J₁, driving half with the motor [kg·m²]")
    driven_inertia: float = Field(gt=0, description="J₂, driven half with the machine [kg·m²]")
    stiffness: float | None = Field(default=None, gt=0, description="c [N·m/rad]")
    stiffness_nm_per_deg: float | None = Field(
        default=None, gt=0, description="c, as catalogues give it [N·m/deg]"
    )
    absorption: float | None = Field(
        default=None, ge=0, le=20, description="ψ = ΔU/U, absorption coefficient (8.13) [-]"
    )
    log_decrement: float | None = Field(
        default=None, ge=0, le=10, description="δ = ln(A₁/A₂), logarithmic decrement (8.7) [-]"
    )
    damping: float | None = Field(
        default=None, ge=0, description="α, viscous damping of the coupling [N·m·s/rad]"
    )

    @model_validator(mode="after")
    def _one(self) -> Coupling:
        exactly_one(
            "coupling", stiffness=self.stiffness, stiffness_nm_per_deg=self.stiffness_nm_per_deg
        )
        given = [
            k for k in ("absorption", "log_decrement", "damping") if getattr(self, k) is not None
        ]
        if len(given) > 1:
            raise FieldError(
                (given[1],),
                f"give one of absorption, log_decrement, damping (got {', '.join(given)})",
            )
        return self


class Step(CaseModel):
    torque: float | None = Field(
        default=None, gt=0, description="M₀, the suddenly applied torque (optional) [N·m]"
    )


class Harmonic(CaseModel):
    driving_torque: float = Field(ge=0, description="M₁, amplitude on the driving half [N·m]")
    driving_phase_deg: float = Field(default=0.0, description="α, its phase [deg]")
    driven_torque: float = Field(
        default=0.0, ge=0, description="M₂, amplitude on the driven half [N·m]"
    )
    driven_phase_deg: float = Field(default=0.0, description="γ, its phase [deg]")
    speed: float | None = Field(default=None, gt=0, description="ω [rad/s]")
    speed_rpm: float | None = Field(default=None, gt=0, description="ω [rpm]")

    @model_validator(mode="after")
    def _one(self) -> Harmonic:
        exactly_one("harmonic", speed=self.speed, speed_rpm=self.speed_rpm)
        if self.driving_torque == 0.0 and self.driven_torque == 0.0:
            raise FieldError(
                ("driving_torque",), "both torque amplitudes are 0: nothing excites the coupling"
            )
        return self

    @property
    def omega(self) -> float:
        if self.speed is not None:
            return self.speed
        assert self.speed_rpm is not None  # validated: exactly one (no `or`: arrays in sweep)
        return rpm_to_rad_s(self.speed_rpm)


class Pulse(CaseModel):
    torque: float = Field(gt=0, description="Torque of the rectangular pulse [N·m]")
    duration: float = Field(gt=0, description="Its duration [s]")
    horizon: float | None = Field(
        default=None, gt=0, description="End of the run; default duration + 2τ [s]"
    )


class Ramp(CaseModel):
    torque: float = Field(gt=0, description="Torque reached and then held [N·m]")
    rise_time: float = Field(gt=0, description="Time to reach it, rising linearly [s]")
    horizon: float | None = Field(
        default=None, gt=0, description="End of the run; default rise + 2τ [s]"
    )


class TorqueTable(CaseModel):
    time: list[float] = Field(
        min_length=2, description="Times, not decreasing; a repeat is a jump [s]"
    )
    torque: list[float] = Field(
        min_length=2, description="Torque, linear between points, held after [N·m]"
    )
    horizon: float | None = Field(
        default=None, gt=0, description="End of the run; default last time + 2τ [s]"
    )

    @model_validator(mode="after")
    def _table(self) -> TorqueTable:
        if len(self.time) != len(self.torque):
            raise FieldError(("torque",), f"{len(self.torque)} values for {len(self.time)} times")
        if self.time[0] < 0 or any(b < a for a, b in zip(self.time, self.time[1:], strict=False)):
            raise FieldError(("time",), f"got {self.time}; must start at >= 0 s and not decrease")
        if all(t == 0.0 for t in self.torque):
            raise FieldError(("torque",), "all zero: nothing loads the coupling")
        return self


class Case(CaseBase):
    problem: Literal["coupling"] = Field(description="Problem name [-]")
    coupling: Coupling
    step: Step | None = None
    harmonic: Harmonic | None = None
    pulse: Pulse | None = None
    ramp: Ramp | None = None
    torque_table: TorqueTable | None = None


def template() -> dict[str, Any]:
    return {
        "problem": "coupling",
        "title": "Elastic coupling, example 8.1",
        "coupling": {
            "driving_inertia": 10.0,
            "driven_inertia": 4.0,
            "stiffness_nm_per_deg": 52.5,
            "absorption": 0.63,
        },
        "step": {"torque": 500.0},
        "harmonic": {"driving_torque": 200.0, "driven_torque": 0.0, "speed": 60.0},
        "pulse": {"torque": 500.0, "duration": 0.05},
    }


def starter_extras() -> dict[str, Any]:
    """Example values ``mdcalc new`` shows commented out beside :func:`template` (keys
    of its sections, optional sections; ``_or``: keys shown but not uncommented)."""
    return {
        "_source": "example 8.1 of seed 000",
        "coupling": {"stiffness": 3008.03, "log_decrement": 0.315, "damping": 50.0},
        "harmonic": {"speed_rpm": 573.0},
        "pulse": {"horizon": 1.0},
        "ramp": {"torque": 500.0, "rise_time": 0.3, "_or": {"horizon": 2.0}},
        "torque_table": {"time": [0.0, 0.1, 0.2, 0.5], "torque": [0.0, 500.0, 500.0, 0.0],
                         "_or": {"horizon": 1.0}},
    }  # fmt: skip
