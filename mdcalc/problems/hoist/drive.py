"""The drive: steady lifting and lowering (7.24)-(7.27), the reduced inertia
(7.30)-(7.31) and the start (7.28)-(7.32); floats, or numpy arrays over a sweep grid."""

from __future__ import annotations

import math
from dataclasses import dataclass

from mdcalc.core.units import rpm_to_rad_s
from mdcalc.core.xp import of
from mdcalc.methods import Method, compare
from mdcalc.output.report import MethodQuantity, MethodsTable
from mdcalc.problems.hoist.case import Case


@dataclass(frozen=True)
class Steady:
    weight: float  # G [N]
    efficiency: float  # η [-]
    useful_power: float  # N_p [W]
    motor_power: float  # N_d [W]
    motor_speed: float  # ω1 [rad/s]
    static_torque: float  # M_c [N·m]
    brake_torque: float  # [N·m]
    lowering_torque: float  # [N·m]

    @property
    def brake_margin(self) -> float:
        """The brake torque over the torque of the load when lowering [-]."""
        return self.brake_torque / self.lowering_torque


def steady(case: Case) -> Steady:
    weight = case.load.mass * case.gravity
    efficiency = math.prod(case.drive.stage_efficiencies) * case.drive.pulley_efficiency
    omega = rpm_to_rad_s(case.drive.motor_speed_rpm)
    useful = weight * case.load.lifting_speed  # (7.25)
    static = useful / (omega * efficiency)  # (7.26)
    return Steady(
        weight=weight,
        efficiency=efficiency,
        useful_power=useful,
        motor_power=useful / efficiency,  # (7.24)
        motor_speed=omega,
        static_torque=static,
        brake_torque=case.drive.brake_safety_factor * static,  # (7.27)
        lowering_torque=useful * efficiency / omega,  # the load drives: η multiplies
    )


@dataclass(frozen=True)
class Inertia:
    motor: float  # J1
    shafts: float  # Σ J_k (ω_k/ω1)²
    load: float  # m (V/ω1)²
    estimated: bool  # True: J = factor·J1 (7.31), no shafts given

    factor: float

    @property
    def total(self) -> float:
        if self.estimated:
            return self.factor * self.motor
        return self.motor + self.shafts + self.load

    @property
    def ratio(self) -> float:
        """J/J1, which the lecture puts at 1.1…1.2 [-]."""
        return self.total / self.motor

    @property
    def drive(self) -> float:
        """The rotating part of J, without the load [kg·m²]."""
        return of(self.total, self.motor).maximum(self.total - self.load, self.motor)


def reduced_inertia(case: Case, motor_speed: float) -> Inertia:
    drive = case.drive
    shafts = sum(s.inertia * s.speed_ratio(motor_speed) ** 2 for s in drive.shafts)  # (7.30)
    load = case.load.mass * (case.load.lifting_speed / motor_speed) ** 2
    return Inertia(
        drive.motor_inertia, shafts, load, not drive.shafts, drive.inertia_estimate_factor
    )


@dataclass(frozen=True)
class StartMotion:
    time: float  # t_p [s]
    angular_acceleration: float  # ω1/t_p [rad/s²]
    inertia_torque: float  # J·ω1/t_p [N·m]
    starting_torque: float  # [N·m]
    load_acceleration: float  # V/t_p [m/s²]


def start_motion(case: Case, st: Steady, inertia: float) -> StartMotion | None:
    """Uniform start (7.28), (7.32); None when the catalogue torque cannot start the load."""
    return uniform_start(case, st, inertia) if can_start(case, st) else None


def can_start(case: Case, st: Steady) -> bool:
    """Always with t_p given; with a catalogue torque, when M_start > M_c."""
    if case.start.time is not None:
        return True
    assert case.start.starting_torque is not None
    return case.start.starting_torque > st.static_torque


def uniform_start(case: Case, st: Steady, inertia: float) -> StartMotion:
    """(7.28), (7.32) for a load the motor starts (also over numpy arrays, see :func:`sweep`)."""
    omega = st.motor_speed
    if case.start.time is not None:
        t_p = case.start.time
        torque = st.static_torque + inertia * omega / t_p
    else:
        assert case.start.starting_torque is not None
        torque = case.start.starting_torque
        t_p = inertia * omega / (torque - st.static_torque)
    return StartMotion(
        t_p, omega / t_p, torque - st.static_torque, torque, case.load.lifting_speed / t_p
    )


def inertia_methods(case: Case, st: Steady, inertia: Inertia) -> MethodsTable:
    """(7.30) against the estimate (7.31) at both ends of its range.

    With the start time given, the methods also compare the starting torque; with a
    catalogue torque, the start time -- unless the motor cannot start the load at
    all, when only J is compared.
    """
    from_time = case.start.time is not None
    starts = start_motion(case, st, inertia.total) is not None
    key = "starting_torque" if from_time else "start_time"
    quantities = [MethodQuantity("reduced_inertia", "J", "kg·m²")]
    if starts:
        unit = "N·m" if from_time else "s"
        quantities.append(MethodQuantity(key, "M_start" if from_time else "t_p", unit))

    def method(j: float) -> dict[str, float]:
        values = {"reduced_inertia": j}
        motion = start_motion(case, st, j)
        if starts and motion is not None:
            values[key] = motion.starting_torque if from_time else motion.time
        return values

    return compare(
        "Methods: reduced inertia",
        "inertia",
        quantities,
        [
            Method("kinetic energy (7.30)", lambda: method(inertia.total), reference=True),
            Method("estimate 1.1·J1 (7.31)", lambda: method(1.1 * inertia.motor)),
            Method("estimate 1.2·J1 (7.31)", lambda: method(1.2 * inertia.motor)),
        ],
    )
