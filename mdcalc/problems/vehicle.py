"""Case-file sections shared by the road-vehicle problems (braking, acceleration)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from mdcalc.model import CaseModel

#: Road surfaces of :data:`mdcalc.tables.ROAD_SURFACES`.
SurfaceName = Literal[
    "dry-asphalt", "wet-asphalt", "gravel", "dry-dirt", "wet-dirt", "packed-snow", "icy-road", "ice"
]


class Drag(CaseModel):
    drag_coefficient: float = Field(gt=0, le=3, description="Drag coefficient C_x [-]")
    frontal_area: float = Field(gt=0, le=100, description="Frontal area A [m^2]")
    air_density: float = Field(default=1.225, gt=0, le=5, description="Air density rho [kg/m^3]")

    @property
    def factor(self) -> float:
        """k in F = k·v² [kg/m]."""
        return 0.5 * self.air_density * self.drag_coefficient * self.frontal_area
