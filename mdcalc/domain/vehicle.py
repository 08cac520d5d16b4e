"""Case-file sections shared by the road-vehicle problems (braking, acceleration)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from mdcalc.core.units import kmh_to_m_s
from mdcalc.domain.tables import ROAD_SURFACES
from mdcalc.input.model import CaseModel

#: Road surfaces of :data:`mdcalc.domain.tables.ROAD_SURFACES`.
SurfaceName = Literal[
    "dry-asphalt", "wet-asphalt", "gravel", "dry-dirt", "wet-dirt", "packed-snow", "icy-road", "ice"
]


class Drag(CaseModel):
    drag_coefficient: float = Field(gt=0, le=3, description="Drag coefficient C_x [-]")
    frontal_area: float = Field(gt=0, le=100, description="Frontal area A [m²]")
    air_density: float = Field(default=1.225, gt=0, le=5, description="Air density rho [kg/m³]")

    @property
    def factor(self) -> float:
        """k in F = k·v² [kg/m]."""
        return 0.5 * self.air_density * self.drag_coefficient * self.frontal_area


def adhesion_of(surface: str | None, coefficient: float | None) -> float:
    """φ given directly, or the low (conservative) end of a named surface's range."""
    if coefficient is not None:
        return coefficient
    assert surface is not None, "validation ensures one of the two"
    return ROAD_SURFACES[surface].low


def speed_of(speed: float | None, speed_kmh: float | None) -> float:
    """A speed given in m/s or in km/h, in m/s."""
    if speed is not None:
        return speed
    assert speed_kmh is not None, "validation ensures one of the two"
    return kmh_to_m_s(speed_kmh)
