"""Unit conversions and physical constants (SI inside the code)."""

from __future__ import annotations

import math

#: Standard gravity [m/s^2] (CGPM 1901). The lecture notes round it to 9.81.
STANDARD_GRAVITY = 9.80665


def rpm_to_rad_s(speed_rpm: float) -> float:
    """Rotational speed [rpm] -> angular speed [rad/s]."""
    return speed_rpm * 2.0 * math.pi / 60.0


def kmh_to_m_s(speed_kmh: float) -> float:
    """Speed [km/h] -> [m/s]."""
    return speed_kmh / 3.6
