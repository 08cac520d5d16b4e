"""The case file of ``mdcalc mount``: pydantic sections in SI units, and the
starter case."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import Field, model_validator

from mdcalc.core.units import STANDARD_GRAVITY
from mdcalc.input.model import CaseBase, CaseModel, exactly_one


class Engine(CaseModel):
    mass: float | None = Field(default=None, gt=0, description="M, engine mass [kg]")
    weight: float | None = Field(default=None, gt=0, description="G, engine weight [N]")

    @model_validator(mode="after")
    def _one(self) -> Engine:
        exactly_one("engine", mass=self.mass, weight=self.weight)
        return self


class Mounts(CaseModel):
    stiffness: float | None = Field(default=None, gt=0, description="c, total stiffness [N/m]")
    static_deflection: float | None = Field(
        default=None, gt=0, description="f, static deflection under the engine, c = G/f [m]"
    )
    damping_ratio: float | None = Field(
        default=None, ge=0, le=10, description="ζ of the mounts (optional) [-]"
    )

    @model_validator(mode="after")
    def _one(self) -> Mounts:
        exactly_one("mounts", stiffness=self.stiffness, static_deflection=self.static_deflection)
        return self


class Crank(CaseModel):
    piston_mass: float | None = Field(default=None, gt=0, description="m, piston mass [kg]")
    piston_weight: float | None = Field(default=None, gt=0, description="piston weight [N]")
    radius: float = Field(gt=0, description="r, crank radius [m]")
    rod_ratio: float = Field(gt=0, lt=1, description="λ = r/l, crank radius over rod length [-]")
    speed: float | None = Field(default=None, gt=0, description="ω, crank speed [rad/s]")
    speed_rpm: float | None = Field(default=None, gt=0, description="n, crank speed [rpm]")

    @model_validator(mode="after")
    def _one(self) -> Crank:
        exactly_one("crank", piston_mass=self.piston_mass, piston_weight=self.piston_weight)
        exactly_one("crank", speed=self.speed, speed_rpm=self.speed_rpm)
        return self


class Isolation(CaseModel):
    transmissibility: float = Field(
        gt=0, lt=1, description="Target force transmissibility of the first harmonic [-]"
    )


class Case(CaseBase):
    problem: Literal["mount"] = Field(description="Problem name [-]")
    gravity: float = Field(default=STANDARD_GRAVITY, gt=0, description="Gravity g [m/s²]")
    engine: Engine
    mounts: Mounts
    crank: Crank
    isolation: Isolation | None = None


def template() -> dict[str, Any]:
    return {
        "problem": "mount",
        "title": "Compressor on rubber mounts",
        "engine": {"weight": 10000.0},
        "mounts": {"static_deflection": 0.01, "damping_ratio": 0.05},
        "crank": {"piston_weight": 100.0, "radius": 0.05, "rod_ratio": 0.2, "speed": 150.0},
        "isolation": {"transmissibility": 0.02},
    }


def starter_extras() -> dict[str, Any]:
    """Example values ``mdcalc new`` shows commented out beside :func:`template`."""
    return {
        "_source": "illustrative, for seed 000 §7.5",
        "engine": {"mass": 1019.7},
        "mounts": {"stiffness": 1.0e6},
        "crank": {"piston_mass": 10.197, "speed_rpm": 1432.4},
    }
