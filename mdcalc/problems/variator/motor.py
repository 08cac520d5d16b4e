"""7b: the induction motor as a spring-damper (8.40)-(8.41), Kloss and the seed's
correction of the critical slip."""

from __future__ import annotations

import math
from dataclasses import dataclass

from mdcalc.core.units import rpm_to_rad_s
from mdcalc.problems.variator.case import Motor


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
