"""7b: the induction motor as a spring-damper (8.40)-(8.41), Kloss and the seed's
correction of the critical slip. Written once for a scene's floats and a block's
arrays."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from mdcalc.core.units import rpm_to_rad_s
from mdcalc.core.xp import of
from mdcalc.problems.variator.case import Motor


@dataclass(frozen=True)
class MotorModel:
    name: str
    slip: Any  # S_H
    a: Any
    critical_slip: Any  # S_K
    nu: Any
    time_constant: Any  # T_D [s]
    stiffness: Any  # c_D [N·m/rad]
    damping: Any  # b_D [N·m·s/rad]


def nominal_torque(m: Motor) -> Any:
    """M_H, given or from P_H at n_H [N·m]."""
    if m.nominal_torque is not None:
        return m.nominal_torque
    assert m.nominal_power is not None  # exactly one of the two is given
    return m.nominal_power / rpm_to_rad_s(m.nominal_speed_rpm)


def motor_models(m: Motor) -> tuple[Any, Any, list[MotorModel]]:
    """(8.40)–(8.41): ω_c, ω₀ and the motor as a spring-damper three ways."""
    xp = of(m.mains_frequency, m.pole_pairs, m.nominal_speed_rpm, m.overload_ratio)
    omega_c = 2.0 * xp.pi * m.mains_frequency
    omega_0 = omega_c / m.pole_pairs
    n, n_h, lam = m.synchronous, m.nominal_speed_rpm, m.overload_ratio
    m_k = lam * nominal_torque(m)
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
        s_k = s_h * (a + xp.sqrt(a * a - 1.0))
        nu = s_k / (2.0 * m_k)
        t_d = 1.0 / (omega_c * s_k)
        models.append(
            MotorModel(name, s_h, a, s_k, nu, t_d, 1.0 / (t_d * nu * omega_0), 1.0 / (nu * omega_0))
        )
    return omega_c, omega_0, models


def motor_values(m: Motor) -> dict[str, Any]:
    """Every number of the motor's section, by result key."""
    omega_c, omega_0, (kloss, seed, _) = motor_models(m)
    torque = nominal_torque(m)
    return {
        "motor_mains": omega_c,
        "motor_field_speed": omega_0,
        "motor_synchronous_rpm": m.synchronous,
        "motor_nominal_torque": torque,
        "motor_critical_torque": m.overload_ratio * torque,
        "motor_slip": kloss.slip,
        "motor_critical_slip": seed.critical_slip,
        "motor_critical_slip_kloss": kloss.critical_slip,
        "motor_time_constant": seed.time_constant,
        "motor_stiffness": seed.stiffness,
        "motor_damping": seed.damping,
        "motor_damping_kloss": kloss.damping,
    }
