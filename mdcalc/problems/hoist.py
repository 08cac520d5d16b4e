"""``hoist``: hoist motor and brake (seed 000 §7.2) and rope loads at start (§7.6).

Steady lifting: η = Π η_i, N_p = G·V, N_d = N_p/η (7.24), static torque on the motor
shaft M_c = G·V/(ω1·η) (7.26), brake torque K_t·M_c (7.27); lowering, the load
drives the train and M_c,low = G·V·η/ω1.

Start: reduced inertia by kinetic energy J = J1 + Σ J_k(ω_k/ω1)² + m(V/ω1)² (7.30) or
the estimate (1.1…1.2)·J1 (7.31); uniform acceleration ω1/t_p (7.32); starting
torque M_c + J·ω1/t_p (7.28), or t_p = J·ω1/(M_start - M_c) from a catalogue torque.

Rope (two-mass model on the rope line): drive mass m1 (drive inertia reduced to the
load's motion), rope stiffness c, load m2 = G/g. The drive force is G + (m1+m2)·V/t_p
during the start and G after it. The load either hangs on the rope (closed form
(7.92)-(7.96), exact for this model) or lies on the ground with the rope slack
(7.97)-(7.98); for the latter a tight ODE run with lift-off and touch-down events is
the reference.

``--plot``: the rope dynamic factor against time from the exact piecewise solution
of the same model (:func:`rope_history`), load hanging and load on the ground.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated, Any, Literal

from pydantic import Field, model_validator

from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.sdof import rectangular_pulse_peak
from mdcalc.core.units import STANDARD_GRAVITY, rpm_to_rad_s
from mdcalc.methods import Method, NotApplicable, compare
from mdcalc.model import CaseBase, CaseModel
from mdcalc.report import MethodQuantity, MethodsTable, Note, Quantities, Quantity, Report
from mdcalc.tables import BRAKE_SAFETY_FACTOR, HOIST_ACCELERATION, Range

if TYPE_CHECKING:
    from mdcalc.plot import Chart

Efficiency = Annotated[float, Field(gt=0, le=1)]

#: The ODE methods are not run past this many rope oscillation periods.
MAX_ODE_PERIODS = 3000


# ------------------------------------------------------------------------ the case


class Load(CaseModel):
    mass: float = Field(gt=0, description="Mass of the load with its hook block [kg]")
    lifting_speed: float = Field(gt=0, description="Steady lifting speed V [m/s]")


class Shaft(CaseModel):
    name: str = Field(min_length=1, description="What turns on this shaft [-]")
    inertia: float = Field(gt=0, description="Moment of inertia on the shaft [kg*m^2]")
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
        gt=0, description="J1: rotor, coupling and brake pulley on the motor shaft [kg*m^2]"
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
        default=None, gt=0, description="Catalogue starting torque of the motor [N*m]"
    )
    machine: Literal["crane", "lift"] = Field(
        default="crane", description="Machine type, for the allowable acceleration [-]"
    )
    allowable_acceleration: float | None = Field(
        default=None, gt=0, description="Allowable load acceleration, overrides the table [m/s^2]"
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
    area: float | None = Field(default=None, gt=0, description="Metal area of one rope [m^2]")
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
        assert self.elastic_modulus and self.area and self.length
        return self.branches * self.elastic_modulus * self.area / self.length


class Case(CaseBase):
    problem: Literal["hoist"] = Field(description="Problem name [-]")
    gravity: float = Field(default=STANDARD_GRAVITY, gt=0, description="Gravity g [m/s^2]")
    load: Load
    drive: Drive
    start: Start
    rope: Rope | None = None


# -------------------------------------------------------------------- steady motion


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


# ---------------------------------------------------------------- reduced inertia


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
    def drive(self) -> float:
        """The rotating part of J, without the load [kg·m²]."""
        return max(self.total - self.load, self.motor)


def reduced_inertia(case: Case, motor_speed: float) -> Inertia:
    drive = case.drive
    shafts = sum(s.inertia * s.speed_ratio(motor_speed) ** 2 for s in drive.shafts)  # (7.30)
    load = case.load.mass * (case.load.lifting_speed / motor_speed) ** 2
    return Inertia(
        drive.motor_inertia, shafts, load, not drive.shafts, drive.inertia_estimate_factor
    )


# ------------------------------------------------------------------------- start


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


# --------------------------------------------------------------------- rope model


@dataclass(frozen=True)
class RopeScene:
    c: float  # rope stiffness [N/m]
    m1: float  # drive mass on the rope line [kg]
    m2: float  # load mass [kg]
    weight: float  # G [N]
    acceleration: float  # V/t_p [m/s²]
    start_time: float  # t_p [s]
    slack: float  # [m]

    @property
    def beta(self) -> float:
        """Two-mass natural frequency √(c·(1/m1 + 1/m2)) [rad/s]."""
        return math.sqrt(self.c * (1.0 / self.m1 + 1.0 / self.m2))

    @property
    def drive_force(self) -> float:
        """Drive force during the start: G + (m1 + m2)·a [N]."""
        return self.weight + (self.m1 + self.m2) * self.acceleration


def hanging_closed_form(r: RopeScene, beta: float) -> dict[str, float]:
    """(7.92)-(7.96) corrected: a rectangular force pulse m2·a of length t_p."""
    peak = r.weight + r.m2 * r.acceleration * rectangular_pulse_peak(beta, r.start_time)
    return {"peak_force": peak, "dynamic_factor": peak / r.weight}


def ground_closed_form(r: RopeScene, heavy_drive: bool) -> dict[str, float]:
    """Load lying on the ground: slack taken up, load lifts off, first peak.

    Exact for the two-mass model while the start lasts past the first peak. With
    ``heavy_drive`` the drive follows the uniform start exactly (m1 → ∞).
    """
    g_force, c, a = r.weight, r.c, r.acceleration
    if heavy_drive:
        # Drum end moves as a·t²/2: taut at s, lift-off at s + G/c.
        speed = math.sqrt(2.0 * a * (r.slack + g_force / c))
        t_lift = speed / a
        beta = math.sqrt(c / r.m2)
    else:
        force = r.drive_force
        t_slack = math.sqrt(2.0 * r.slack * r.m1 / force)
        v_slack = force / r.m1 * t_slack
        beta1 = math.sqrt(c / r.m1)
        # Drive on the rope with the load grounded: c·ξ = F - R·cos(β1·τ + θ).
        amplitude = math.hypot(force, c * v_slack / beta1)
        theta = math.atan2(c * v_slack / beta1, force)
        tau = (math.acos((force - g_force) / amplitude) - theta) / beta1
        speed = amplitude * beta1 / c * math.sin(beta1 * tau + theta)
        t_lift = t_slack + tau
        beta = r.beta
    if t_lift > r.start_time:
        raise NotApplicable("the load lifts off after the start has ended")
    # After lift-off the rope force oscillates about G + m2·a at β.
    w0 = -r.m2 * a / c
    phase = math.atan2(speed / beta, w0)
    if t_lift + phase / beta > r.start_time:
        raise NotApplicable("the first peak comes after the start has ended")
    swing = c * math.hypot(w0, speed / beta)
    if swing > g_force + r.m2 * a:
        # The rope goes slack after the peak and re-tightens with a jerk: later
        # peaks are not bounded by the first one.
        raise NotApplicable("the rope goes slack after the first peak")
    # After the start the force swings about G with at most swing + m2·a: never higher.
    peak = g_force + r.m2 * a + swing
    return {"peak_force": peak, "dynamic_factor": peak / g_force}


def rope_ode(
    r: RopeScene, hanging: bool, rtol: float, max_periods: float | None = MAX_ODE_PERIODS
) -> dict[str, float]:
    """Integrate the two-mass model with ground contact, slack rope and the drive switch.

    State [x1, v1, y, vy]: drive and load positions on the rope line; rope force
    c·max(x1 - y - s, 0). Hanging: the rope starts stretched by G/c and there is no
    ground. On the ground: the load rests until the rope force reaches G.
    """
    import numpy as np

    from mdcalc.core.ode import advance, pick_solver

    c, m1, m2, s, gw = r.c, r.m1, r.m2, r.slack, r.weight
    t_p, beta = r.start_time, r.beta
    period = 2.0 * math.pi / beta
    if max_periods is not None and periods_to_integrate(r) > max_periods:
        raise NotApplicable(f"more than {max_periods:g} rope periods to integrate")

    def drive(t: float) -> float:
        return r.drive_force if t < t_p else gw

    def tension(y: np.ndarray) -> float:
        return c * max(y[0] - y[2] - s, 0.0)

    def air(t: float, y: np.ndarray) -> np.ndarray:
        f = tension(y)
        return np.array([y[1], (drive(t) - f) / m1, y[3], (f - gw) / m2])

    def ground(t: float, y: np.ndarray) -> np.ndarray:
        return np.array([y[1], (drive(t) - tension(y)) / m1, 0.0, 0.0])

    def stretch_rate(t: float, y: np.ndarray) -> float:
        return float(y[1] - y[3])

    method = pick_solver(rtol)
    scale = max(r.drive_force / c + s, 1e-12)
    atol = np.array([scale, scale * beta, scale, scale * beta]) * rtol * 1e-2
    if hanging:
        t, y, on_ground = 0.0, np.array([s + gw / c, 0.0, 0.0, 0.0]), False
    else:
        t, y, on_ground = 0.0, np.zeros(4), True
    peak = tension(y)
    t_lift = 0.0 if hanging else math.inf
    for _ in range(10_000):
        t_end = t_p if t < t_p else max(t_p, t_lift) + 2.0 * period
        if on_ground and t >= t_p:
            t_end = t + 4.0 * math.pi * math.sqrt(m1 / c) + 2.0 * period
        if t >= t_end and not on_ground:
            return {"peak_force": peak, "dynamic_factor": peak / gw}
        if on_ground:
            segment = advance(
                ground,
                t,
                y,
                t_end,
                rtol=rtol,
                atol=atol,
                method=method,
                terminal=[(lambda t, y: tension(y) - gw, 1)],
                watch=[(stretch_rate, -1)],
            )
        else:
            segment = advance(
                air,
                t,
                y,
                t_end,
                rtol=rtol,
                atol=atol,
                method=method,
                terminal=[(lambda t, y: y[2], -1)] if not hanging else [],
                watch=[(stretch_rate, -1)],
            )
        for _, _, state in segment.hits:
            peak = max(peak, tension(state))
        t, y = segment.t, segment.y
        peak = max(peak, tension(y))
        if segment.event is not None:
            if on_ground:  # lift-off
                on_ground, t_lift = False, t
            else:  # touch-down: the load stops on the ground
                on_ground, y = True, np.array([y[0], y[1], 0.0, 0.0])
    raise ArithmeticError("the rope ODE run did not settle")


def periods_to_integrate(r: RopeScene) -> float:
    """Rope periods an ODE run covers: the start and two periods after it."""
    return r.start_time * r.beta / (2.0 * math.pi) + 2.0


ROPE_QUANTITIES = [
    MethodQuantity("peak_force", "F_max", "N"),
    MethodQuantity("dynamic_factor", "ψ", ""),
]


def rope_methods(r: RopeScene, hanging: bool) -> MethodsTable:
    heavy_beta = math.sqrt(r.c / r.m2)
    if hanging:
        methods = [
            Method(
                "lecture (7.95): G + 2·m2·V/t_p",
                lambda: _factor(r, r.weight + 2.0 * r.m2 * r.acceleration),
            ),
            Method(
                "closed form, heavy drive β = √(c/m2)", lambda: hanging_closed_form(r, heavy_beta)
            ),
            Method(
                "closed form, two-mass β (exact)",
                lambda: hanging_closed_form(r, r.beta),
                reference=True,
            ),
            Method("ODE RK45, rtol 1e-3", lambda: rope_ode(r, True, 1e-3), imports=ODE_IMPORTS),
            Method("ODE RK45, rtol 1e-6", lambda: rope_ode(r, True, 1e-6), imports=ODE_IMPORTS),
        ]
        title, key = "Methods: rope, load hanging at start", "rope_hanging"
    else:
        # The reference is the tight ODE run; when it would cover too many rope
        # periods and the two-mass closed form is valid, the closed form is exact
        # and takes its place (and the long run is not made).
        closed_form_valid = True
        try:
            ground_closed_form(r, False)
        except NotApplicable:
            closed_form_valid = False
        ode_reference = not closed_form_valid or periods_to_integrate(r) <= MAX_ODE_PERIODS
        methods = [
            Method(
                "lecture (7.98): 2·(G + m2·V/t_p)",
                lambda: _factor(r, 2.0 * (r.weight + r.m2 * r.acceleration)),
            ),
            Method("closed form, heavy drive", lambda: ground_closed_form(r, True)),
            Method(
                "closed form, two-mass",
                lambda: ground_closed_form(r, False),
                reference=not ode_reference,
            ),
            Method("ODE RK45, rtol 1e-3", lambda: rope_ode(r, False, 1e-3), imports=ODE_IMPORTS),
            Method("ODE RK45, rtol 1e-6", lambda: rope_ode(r, False, 1e-6), imports=ODE_IMPORTS),
            Method(
                "ODE DOP853, rtol 1e-10",
                lambda: rope_ode(r, False, 1e-10, None if ode_reference else MAX_ODE_PERIODS),
                imports=ODE_IMPORTS,
                reference=ode_reference,
            ),
        ]
        title, key = "Methods: rope, load lying on the ground", "rope_ground"
    return compare(title, key, ROPE_QUANTITIES, methods)


def _factor(r: RopeScene, peak: float) -> dict[str, float]:
    return {"peak_force": peak, "dynamic_factor": peak / r.weight}


# ------------------------------------------------------------------------- result


@dataclass
class Result:
    case: Case
    steady: Steady
    inertia: Inertia
    start: StartMotion | None
    allowable: Range | None
    inertia_table: MethodsTable | None
    rope: RopeScene | None
    rope_hanging: MethodsTable | None
    rope_ground: MethodsTable | None
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


def solve(case: Case) -> Result:
    st = steady(case)
    inertia = reduced_inertia(case, st.motor_speed)
    motion = start_motion(case, st, inertia.total)
    allowable = None
    if case.start.allowable_acceleration is None:
        allowable = HOIST_ACCELERATION[case.start.machine]
    result = Result(case, st, inertia, motion, allowable, None, None, None, None)
    if not inertia.estimated:
        result.inertia_table = inertia_methods(case, st, inertia)
    if motion is None:
        result.status = "no-answer"
        result.message = (
            f"the motor cannot start the load: starting torque {case.start.starting_torque:g} N·m "
            f"does not exceed the static torque M_c = {st.static_torque:.4g} N·m"
        )
        return result
    if case.rope is not None:
        m1 = case.rope.drive_mass
        if m1 is None:
            m1 = inertia.drive * (st.motor_speed / case.load.lifting_speed) ** 2
        rope = RopeScene(
            c=case.rope.c,
            m1=m1,
            m2=case.load.mass,
            weight=st.weight,
            acceleration=motion.load_acceleration,
            start_time=motion.time,
            slack=case.rope.slack_length,
        )
        result.rope = rope
        result.rope_hanging = rope_methods(rope, hanging=True)
        result.rope_ground = rope_methods(rope, hanging=False)
    return result


def _reference(table: MethodsTable, key: str) -> float:
    value = next(row for row in table.rows if row.reference).values[key]
    assert value is not None
    return value


# ------------------------------------------------------------------------- report


def report(result: Result) -> Report:
    case, st, inertia, motion = result.case, result.steady, result.inertia, result.start
    notes: list[Note] = []
    sections: list[Any] = [
        Quantities(
            "Steady lifting",
            [
                Quantity("weight", "Load weight G", st.weight, "N"),
                Quantity("total_efficiency", "Total efficiency η", st.efficiency, ""),
                Quantity(
                    "useful_power", "Useful power N_p = G·V (7.25)", st.useful_power / 1e3, "kW"
                ),
                Quantity(
                    "motor_power", "Motor power N_d = N_p/η (7.24)", st.motor_power / 1e3, "kW"
                ),
                Quantity("motor_speed", "Motor angular speed ω1", st.motor_speed, "rad/s"),
                Quantity(
                    "static_torque",
                    "Static torque M_c = G·V/(ω1·η) (7.26)",
                    st.static_torque,
                    "N·m",
                ),
            ],
        ),
        Quantities(
            "Brake on the motor shaft",
            [
                Quantity(
                    "brake_torque",
                    f"Brake torque K_t·M_c (7.27), K_t = {case.drive.brake_safety_factor:g}",
                    st.brake_torque,
                    "N·m",
                ),
                Quantity(
                    "lowering_torque",
                    "Load torque when lowering G·V·η/ω1",
                    st.lowering_torque,
                    "N·m",
                ),
                Quantity(
                    "brake_margin",
                    "Brake margin over the lowering torque",
                    st.brake_torque / st.lowering_torque,
                    "",
                ),
            ],
        ),
    ]
    k_t = BRAKE_SAFETY_FACTOR
    if not k_t.low <= case.drive.brake_safety_factor <= k_t.high:
        notes.append(
            Note(
                "warning",
                f"K_t = {case.drive.brake_safety_factor:g} is outside the "
                f"usual {k_t.low:g}…{k_t.high:g} of the duty classes",
            )
        )
    j_items = [Quantity("motor_inertia", "Motor shaft J1", inertia.motor, "kg·m²")]
    if inertia.estimated:
        j_items.append(
            Quantity(
                "reduced_inertia",
                f"J ≈ {inertia.factor:g}·J1 (7.31)",
                inertia.total,
                "kg·m²",
                "no other shafts given",
            )
        )
    else:
        j_items += [
            Quantity("shaft_inertia", "Other shafts Σ J_k·(ω_k/ω1)²", inertia.shafts, "kg·m²"),
            Quantity("load_inertia", "Load m·(V/ω1)²", inertia.load, "kg·m²"),
            Quantity("reduced_inertia", "Reduced inertia J (7.30)", inertia.total, "kg·m²"),
            Quantity(
                "inertia_ratio",
                "J/J1 (the lecture says 1.1…1.2)",
                inertia.total / inertia.motor,
                "",
            ),
        ]
    sections.append(Quantities("Reduced moment of inertia on the motor shaft", j_items))
    if motion is not None:
        given_time = case.start.time is not None
        items = [
            Quantity(
                "start_time",
                "Start time t_p" + ("" if given_time else " = J·ω1/(M_start − M_c)"),
                motion.time,
                "s",
            ),
            Quantity(
                "angular_acceleration",
                "Motor acceleration ω1/t_p (7.32)",
                motion.angular_acceleration,
                "rad/s²",
            ),
            Quantity("inertia_torque", "Inertia torque J·ω1/t_p", motion.inertia_torque, "N·m"),
            Quantity(
                "starting_torque",
                "Starting torque M_c + J·ω1/t_p (7.28)",
                motion.starting_torque,
                "N·m",
            ),
            Quantity(
                "load_acceleration", "Load acceleration V/t_p", motion.load_acceleration, "m/s²"
            ),
        ]
        a = motion.load_acceleration
        if result.allowable is not None:
            low, high = result.allowable.low, result.allowable.high
            label = f"allowable for a {case.start.machine}: {low:g}…{high:g} m/s²"
        else:
            assert case.start.allowable_acceleration is not None
            low, high = 0.0, case.start.allowable_acceleration
            label = f"allowable: ≤ {high:g} m/s²"
        ok = a <= high
        items.append(
            Quantity("acceleration_ok", "Within the allowable acceleration", ok, "", label)
        )
        if not ok:
            notes.append(
                Note(
                    "warning",
                    f"the load accelerates at {a:.3g} m/s², above the {label}: lengthen the start",
                )
            )
        elif a < low:
            notes.append(
                Note(
                    "info",
                    f"the load accelerates at {a:.3g} m/s², below the usual "
                    f"{low:g} m/s² for a {case.start.machine}: a slow start",
                )
            )
        sections.append(Quantities("Start", items))
    if result.inertia_table is not None:
        sections.append(result.inertia_table)
    if result.rope is not None and result.rope_hanging and result.rope_ground:
        r = result.rope
        beta = r.beta
        sections.append(
            Quantities(
                "Rope at start (two-mass model)",
                [
                    Quantity("rope_stiffness", "Rope stiffness c", r.c, "N/m"),
                    Quantity("drive_mass", "Drive mass on the rope line m1", r.m1, "kg"),
                    Quantity(
                        "rope_frequency", "Natural frequency β = √(c·(1/m1 + 1/m2))", beta, "rad/s"
                    ),
                    Quantity(
                        "half_period", "Half period π/β (compare with t_p)", math.pi / beta, "s"
                    ),
                    Quantity(
                        "hanging_peak_force",
                        "Peak rope force, load hanging",
                        _reference(result.rope_hanging, "peak_force"),
                        "N",
                    ),
                    Quantity(
                        "hanging_dynamic_factor",
                        "Dynamic factor ψ, load hanging",
                        _reference(result.rope_hanging, "dynamic_factor"),
                        "",
                    ),
                    Quantity(
                        "ground_peak_force",
                        "Peak rope force, load lifted off the ground",
                        _reference(result.rope_ground, "peak_force"),
                        "N",
                    ),
                    Quantity(
                        "ground_dynamic_factor",
                        "Dynamic factor ψ, load lifted off the ground",
                        _reference(result.rope_ground, "dynamic_factor"),
                        "",
                    ),
                ],
            )
        )
        sections += [result.rope_hanging, result.rope_ground]
    title = case.title or "Hoist motor and brake"
    return Report("hoist", title, sections, notes, result.status, result.message)


# ------------------------------------------------------------------------- charts

#: Points per rope period on the charts' curves.
CHART_SAMPLES_PER_PERIOD = 48
#: A horizon longer than this many rope periods is drawn only over its opening
#: (the lift-off and the first peak, and :data:`CHART_WINDOW_PERIODS` periods after).
CHART_PERIODS = 60
CHART_WINDOW_PERIODS = 6
#: Smooth pieces of the exact rope solution before it gives up (a chattering rope).
MAX_ROPE_PIECES = 10_000


@dataclass(frozen=True)
class RopePiece:
    """One smooth piece of the exact two-mass solution from ``t0`` to ``t1``: the rope
    taut or slack, the load on the ground or in the air, the drive force ``drive``
    constant. The state at ``t0``: rope stretch u = x1 - y - s and its rate, load
    height y and speed."""

    t0: float
    t1: float
    taut: bool
    grounded: bool
    drive: float  # D [N]
    u: float  # [m]
    du: float  # [m/s]
    y: float  # [m]
    vy: float  # [m/s]


@dataclass(frozen=True)
class RopeHistory:
    """The exact solution of :func:`rope_ode`'s model over the same horizon, piece by
    piece, with its events: (time, what) for "taut", "slack", "lift-off",
    "touch-down" and "start ends"."""

    pieces: list[RopePiece]
    events: list[tuple[float, str]]
    horizon: float
    complete: bool  # False: stopped at MAX_ROPE_PIECES


def _frequency(r: RopeScene, p: RopePiece) -> float:
    """Of a taut piece: β1 = √(c/m1) with the load on the ground, β in the air."""
    return math.sqrt(r.c / r.m1) if p.grounded else r.beta


def _centre(r: RopeScene, p: RopePiece) -> float:
    """Stretch about which a taut piece swings: c·u = D on the ground, and in the
    air c·u = (D·m2 + G·m1)/(m1 + m2) (G + m2·a during the start, G after it)."""
    if p.grounded:
        return p.drive / r.c
    return (p.drive * r.m2 + r.weight * r.m1) / ((r.m1 + r.m2) * r.c)


def _stretch_acceleration(r: RopeScene, p: RopePiece) -> float:
    """u'' of a slack piece: the drive accelerates at D/m1, a flying load falls at g."""
    return p.drive / r.m1 + (0.0 if p.grounded else r.weight / r.m2)


def _stretch(r: RopeScene, p: RopePiece, tau: Any) -> tuple[Any, Any]:
    """u and u' at ``tau`` after the piece's start (float or numpy array)."""
    import numpy as np

    if not p.taut:
        acc = _stretch_acceleration(r, p)
        return p.u + p.du * tau + 0.5 * acc * tau * tau, p.du + acc * tau
    w, centre = _frequency(r, p), _centre(r, p)
    x = w * tau
    a, b = p.u - centre, p.du / w
    return centre + a * np.cos(x) + b * np.sin(x), w * (b * np.cos(x) - a * np.sin(x))


def _load(r: RopeScene, p: RopePiece, tau: Any) -> tuple[Any, Any]:
    """Load height y and speed at ``tau`` after the piece's start. In a taut piece
    y'' = (c·u - G)/m2, integrated with P(x) = x²/2 - (1 - cos x) and
    Q(x) = x - sin x, which keep their accuracy at small x (no cancellation at
    lift-off, where c·u = G)."""
    import numpy as np

    if p.grounded:
        return 0.0 * tau, 0.0 * tau
    g = r.weight / r.m2
    if not p.taut:
        return p.y + p.vy * tau - 0.5 * g * tau * tau, p.vy - g * tau
    w, centre = _frequency(r, p), _centre(r, p)
    x = np.asarray(w * tau, dtype=float)
    small = np.abs(x) < 1e-2
    x2 = x * x
    p_x = np.where(small, x2 * x2 * (1 / 24 - x2 / 720), 0.5 * x2 - (1.0 - np.cos(x)))
    q_x = np.where(small, x * x2 * (1 / 6 - x2 / 120), x - np.sin(x))
    k = r.c / r.m2
    excess = (r.c * p.u - r.weight) / r.m2  # y'' at the piece's start
    a, b = p.u - centre, p.du / w
    y = p.y + p.vy * tau + 0.5 * excess * tau * tau + k * (b * q_x - a * p_x) / (w * w)
    vy = p.vy + excess * tau + k * (b * (1.0 - np.cos(x)) - a * q_x) / w
    return y, vy


def _sine_crossing(r: RopeScene, p: RopePiece, level: float, rising: bool) -> float:
    """First time after a taut piece's start at which u crosses ``level``."""
    w, centre = _frequency(r, p), _centre(r, p)
    a, b = p.u - centre, p.du / w
    amplitude = math.hypot(a, b)
    if amplitude == 0.0:
        return math.inf
    q = (level - centre) / amplitude
    if not -1.0 < q < 1.0:
        return math.inf  # never reached, or only touched
    # u = centre + amplitude·cos(x - φ); rising where sin(x - φ) < 0
    phi = math.atan2(b, a)
    angle = (phi + (-1.0 if rising else 1.0) * math.acos(q)) % (2.0 * math.pi)
    if angle < 1e-9:
        angle += 2.0 * math.pi  # the crossing the piece starts at
    return angle / w


def _quadratic_crossing(p0: float, p1: float, p2: float, rising: bool) -> float:
    """First τ > 0 at which p0 + p1·τ + p2·τ²/2 crosses 0 going up (or down)."""
    roots: list[float] = []
    if p2 == 0.0:
        if p1 != 0.0:
            roots = [-p0 / p1]
    else:
        disc = p1 * p1 - 2.0 * p2 * p0
        if disc < 0.0:
            return math.inf
        q = -0.5 * (p1 + math.copysign(math.sqrt(disc), p1))
        roots = [q / (0.5 * p2), p0 / q] if q != 0.0 else [0.0]
    for root in sorted(roots):
        slope = p1 + p2 * root
        if root > 0.0 and slope != 0.0 and (slope > 0.0) == rising:
            return root
    return math.inf


def _touch_down(r: RopeScene, p: RopePiece, span: float) -> float:
    """First time in (0, span] at which a taut piece's load comes down to the ground.
    y is a trend y0 + v·τ + y''·τ²/2 plus a swing of at most ``reach``: only where the
    trend is below ``reach`` can y reach 0; there it is sampled at 32 points a period,
    and the first sign change bisected."""
    import numpy as np

    w, centre = _frequency(r, p), _centre(r, p)
    k = r.c / (r.m2 * w * w)
    a, b = p.u - centre, p.du / w
    # y = trend(τ) + k·[a·(1 - cos x) - b·sin x] >= trend(τ) - k·(hypot(a, b) - a)
    reach = k * (math.hypot(a, b) - a)
    slope = p.vy + k * w * b
    curvature = (r.c * centre - r.weight) / r.m2
    start, stop = 0.0, span
    if curvature > 0.0:  # the trend is below reach between two roots at most
        disc = slope * slope - 2.0 * curvature * (p.y - reach)
        if disc < 0.0:
            return math.inf
        root = math.sqrt(disc)
        start = max(0.0, (-slope - root) / curvature)
        stop = min(span, (-slope + root) / curvature)
    step = 2.0 * math.pi / w / 32.0
    while start < stop:
        count = min(4096, math.ceil((stop - start) / step))
        tau = np.minimum(start + step * np.arange(1, count + 1), stop)
        heights, _ = _load(r, p, tau)
        below = np.nonzero(heights < 0.0)[0]
        if below.size:
            j = int(below[0])
            lo, hi = (start if j == 0 else float(tau[j - 1])), float(tau[j])
            for _ in range(80):
                mid = 0.5 * (lo + hi)
                if float(_load(r, p, mid)[0]) < 0.0:
                    hi = mid
                else:
                    lo = mid
            return hi
        start = float(tau[-1])
    return math.inf


def rope_history(r: RopeScene, hanging: bool) -> RopeHistory:
    """The exact piecewise solution of :func:`rope_ode`'s two-mass model: in each
    smooth piece the stretch is a sine about its centre (taut rope) or a parabola
    (slack), and the events (rope taut or slack, lift-off, touch-down, the end of
    the start) have closed forms -- a touch-down of a load on a taut rope is
    bisected. The horizon is :func:`rope_ode`'s: the start, then two periods after
    the start or after the last lift-off, whichever is later."""
    t_p, period = r.start_time, 2.0 * math.pi / r.beta
    drive = r.drive_force if t_p > 0.0 else r.weight
    if hanging:
        p = RopePiece(0.0, 0.0, True, False, drive, r.weight / r.c, 0.0, 0.0, 0.0)
        t_lift = 0.0
    else:
        p = RopePiece(0.0, 0.0, r.slack == 0.0, True, drive, -r.slack, 0.0, 0.0, 0.0)
        t_lift = math.inf
    pieces: list[RopePiece] = []
    events: list[tuple[float, str]] = []
    t = 0.0
    while len(pieces) < MAX_ROPE_PIECES:
        if t < t_p:
            limit = t_p
        elif p.grounded:
            limit = math.inf
        else:
            limit = max(t_p, t_lift) + 2.0 * period
            if t >= limit:
                return RopeHistory(pieces, events, t, True)
        found: list[tuple[float, str]] = []
        if p.taut:
            found.append((_sine_crossing(r, p, 0.0, rising=False), "slack"))
            if p.grounded:
                found.append((_sine_crossing(r, p, r.weight / r.c, rising=True), "lift-off"))
        else:
            acc = _stretch_acceleration(r, p)
            found.append((_quadratic_crossing(p.u, p.du, acc, rising=True), "taut"))
        if not hanging and not p.grounded:
            span = min(limit, *(f[0] + t for f in found)) - t
            if p.taut:
                found.append((_touch_down(r, p, span), "touch-down"))
            else:
                g = r.weight / r.m2
                found.append((_quadratic_crossing(p.y, p.vy, -g, rising=False), "touch-down"))
        tau, what = min(found)
        if t + tau >= limit:
            tau, what = limit - t, "start ends" if limit == t_p else "horizon"
        if not math.isfinite(tau):
            break  # nothing more happens (not reached: D >= G keeps it moving)
        u, du = (float(v) for v in _stretch(r, p, tau))
        y, vy = (float(v) for v in _load(r, p, tau))
        pieces.append(RopePiece(t, t + tau, p.taut, p.grounded, p.drive, p.u, p.du, p.y, p.vy))
        t = t_p if what == "start ends" else t + tau
        taut, grounded, drive = p.taut, p.grounded, p.drive
        if what == "start ends":
            drive = r.weight
        elif what == "slack":
            taut, u = False, 0.0
        elif what == "taut":
            taut, u = True, 0.0
        elif what == "lift-off":
            grounded, u, t_lift = False, r.weight / r.c, t
        elif what == "touch-down":  # the load stops on the ground; the drive goes on
            grounded, du, y, vy = True, du + vy, 0.0, 0.0
        if what != "horizon":
            events.append((t, what))
        p = RopePiece(t, t, taut, grounded, drive, u, du, y, vy)
    return RopeHistory(pieces, events, t, False)


def _piece_peak(r: RopeScene, p: RopePiece) -> tuple[float, float]:
    """(time, rope force) of the first maximum of the force over a piece."""
    if not p.taut:
        return p.t0, 0.0
    span = p.t1 - p.t0
    w, centre = _frequency(r, p), _centre(r, p)
    a, b = p.u - centre, p.du / w
    crest = (math.atan2(b, a) % (2.0 * math.pi)) / w  # first τ where u = centre + amplitude
    candidates = [0.0, span] + ([crest] if crest <= span else [])
    forces = [r.c * float(_stretch(r, p, tau)[0]) for tau in candidates]
    best = max(range(len(candidates)), key=lambda j: (forces[j], -candidates[j]))
    return p.t0 + candidates[best], forces[best]


def rope_peak(history: RopeHistory, r: RopeScene) -> tuple[float, float]:
    """(time, force) of the largest rope force over the horizon, its first occurrence
    (during a long start the same crest comes back every period)."""
    peaks = [_piece_peak(r, p) for p in history.pieces]
    top = max(f for _, f in peaks)
    return next((t, f) for t, f in peaks if f >= top * (1.0 - 1e-12))


def charts(result: Result) -> list[Chart]:
    """``--plot``: with a [rope] section, the rope dynamic factor ψ = F/G against time
    at the start, load hanging and load lying on the ground, from the exact piecewise
    solution of the two-mass model (:func:`rope_history`) -- the closed forms
    (7.92)-(7.98) phase by phase, including the slack rope and lift-off; with the
    reported ψ, the static ψ = 1 and the time of the peak. [] for a scene without a
    rope (the uniform start has no curve worth a chart) or without an answer."""
    if result.status != "ok" or result.rope is None:
        return []
    if result.rope_hanging is None or result.rope_ground is None:
        return []
    r = result.rope
    return [
        _rope_chart(r, result.rope_hanging, hanging=True),
        _rope_chart(r, result.rope_ground, hanging=False),
    ]


def _rope_chart(r: RopeScene, table: MethodsTable, hanging: bool) -> Chart:
    import numpy as np

    from mdcalc.plot import Chart, Mark, Series

    history = rope_history(r, hanging)
    t_peak, f_peak = rope_peak(history, r)
    period = 2.0 * math.pi / r.beta
    lifts = [t for t, what in history.events if what == "lift-off"]
    first = 0.0 if hanging or not lifts else lifts[0]
    shown = history.horizon
    if shown > CHART_PERIODS * period:
        shown = min(shown, max(first, t_peak) + CHART_WINDOW_PERIODS * period)
    times: list[float] = []
    forces: list[float] = []
    for p in history.pieces:
        if p.t0 > shown:
            break
        span = min(p.t1, shown) - p.t0
        if p.taut:
            count = math.ceil(span / (2.0 * math.pi / _frequency(r, p)) * CHART_SAMPLES_PER_PERIOD)
            tau = np.linspace(0.0, span, max(count, 1) + 1)
            if p.t0 <= t_peak <= p.t0 + span:
                tau = np.union1d(tau, [t_peak - p.t0])
            force = r.c * np.asarray(_stretch(r, p, tau)[0])
        else:
            tau, force = np.array([0.0, span]), np.zeros(2)
        start = 1 if times else 0  # a piece starts where the last one ended
        times += (p.t0 + tau[start:]).tolist()
        forces += force[start:].tolist()
    psi = [f / r.weight for f in forces]
    series = [Series("ψ(t), exact two-mass solution", times, psi)]
    events = [(t, what) for t, what in history.events if t <= shown]
    if r.slack > 0.0 and not hanging and events and events[0][1] == "taut":
        t_taut = events.pop(0)[0]
        series.append(Series(f"slack taken up, t = {t_taut:.4g} s", [t_taut], [0.0], "points"))
    lifts_shown = [t for t, what in events if what == "lift-off"]
    if not hanging and lifts_shown:
        many = f" ({len(lifts_shown)}×)" if len(lifts_shown) > 1 else ""
        label = f"load lifts off, t = {lifts_shown[0]:.4g} s{many}"
        series.append(Series(label, lifts_shown, [1.0] * len(lifts_shown), "points"))
    slack = [t for t, what in events if what in ("slack", "taut")]
    if slack:
        episodes = sum(1 for _, what in events if what == "slack")
        if len(slack) == 2:
            label = f"rope slack from {slack[0]:.4g} to {slack[1]:.4g} s"
        else:
            label = f"rope goes slack {episodes}× (first at {slack[0]:.4g} s)"
        series.append(Series(label, slack, [0.0] * len(slack), "points"))
    downs = [t for t, what in events if what == "touch-down"]
    if downs:
        label = f"load touches down, t = {downs[0]:.4g} s" + (
            f" ({len(downs)}×)" if len(downs) > 1 else ""
        )
        series.append(Series(label, downs, [_psi_at(r, history, t) for t in downs], "points"))
    if r.start_time <= shown:
        t_p = r.start_time
        series.append(
            Series(f"start ends, t_p = {t_p:.4g} s", [t_p], [_psi_at(r, history, t_p)], "points")
        )
    scene = "load hanging" if hanging else "load lifting off the ground"
    if r.slack > 0.0 and not hanging:
        scene += f", {r.slack:g} m of slack"
    title = f"Rope dynamic factor ψ = F/G at the start, {scene} (t_p = {r.start_time:.4g} s)"
    if shown < history.horizon:
        title += f"\nfirst {shown:.3g} s of {history.horizon:.4g} s "
        title += f"({history.horizon / period:.3g} rope periods) shown"
    if not history.complete:
        title += f"\nstopped after {MAX_ROPE_PIECES} pieces (a chattering rope)"
    reference = next(row for row in table.rows if row.reference)
    reported = reference.values["dynamic_factor"]
    assert reported is not None
    peak = f_peak / r.weight
    return Chart(
        title,
        "t [s]",
        "ψ = F/G [-]",
        series,
        [
            Mark("y", reported, f"reported ψ = {_psi_text(reported)} ({reference.method})"),
            Mark("y", 1.0, "static, ψ = 1"),
            Mark("x", t_peak, f"peak of the curve ψ = {_psi_text(peak)} at t = {t_peak:.4g} s"),
        ],
    )


def _psi_text(psi: float) -> str:
    """ψ to 5 digits, or as 1 + δ when it is within 1e-3 of 1 (a slow start)."""
    if 0.0 < abs(psi - 1.0) < 1e-3:
        return f"1 {'+' if psi > 1.0 else '−'} {abs(psi - 1.0):.4g}"
    return f"{psi:.5g}"


def _psi_at(r: RopeScene, history: RopeHistory, t: float) -> float:
    for p in history.pieces:
        if p.t0 <= t <= p.t1:
            return r.c * max(float(_stretch(r, p, t - p.t0)[0]), 0.0) / r.weight
    return 0.0


# ------------------------------------------------------------------------- sweep

#: Keys ``mdcalc sweep`` may vary in the vectorized form (N: any list index), and what
#: each sets. The rope's keys are not here: its peaks need the ODE runs.
SWEEP_KEYS = {
    "gravity": "g",
    "load.mass": "m",
    "load.lifting_speed": "V",
    "drive.motor_speed_rpm": "ω1",
    "drive.motor_inertia": "J1",
    "drive.stage_efficiencies.N": "η_i",
    "drive.pulley_efficiency": "η of the reeving",
    "drive.brake_safety_factor": "K_t",
    "drive.inertia_estimate_factor": "factor of (7.31)",
    "drive.shafts.N.inertia": "J_k",
    "drive.shafts.N.speed_rpm": "ω_k",
    "drive.shafts.N.ratio": "ω1/ω_k",
    "start.time": "t_p",
    "start.starting_torque": "M_start",
}


def sweep(case: Case, grid: dict[str, Any]) -> dict[str, Any] | None:
    """Every numeric result of a rope-less scene over a grid at once (numpy), by the
    formulas of :func:`solve` run on a copy of the case that holds the grid's arrays.

    None with a rope (its peaks need the ODE runs), for a key this form does not know
    or one that switches an alternative (t_p or M_start, speed_rpm or ratio), and when
    the motor cannot start the load at some point (that point has no answer, exit 3).
    """
    import numpy as np

    if case.rope is not None:
        return None
    for key, column in grid.items():
        parts = key.split(".")
        pattern = ".".join("N" if p.isdigit() else p for p in parts)
        if pattern not in SWEEP_KEYS or _value_at(case, parts) is None:
            return None
        case = _with_value(case, parts, np.asarray(column, dtype=float))
    st = steady(case)
    if not np.all(can_start(case, st)):
        return None
    inertia = reduced_inertia(case, st.motor_speed)
    motion = uniform_start(case, st, inertia.total)
    values: dict[str, Any] = {
        "weight": st.weight,
        "total_efficiency": st.efficiency,
        "useful_power": st.useful_power / 1e3,
        "motor_power": st.motor_power / 1e3,
        "motor_speed": st.motor_speed,
        "static_torque": st.static_torque,
        "brake_torque": st.brake_torque,
        "lowering_torque": st.lowering_torque,
        "brake_margin": st.brake_torque / st.lowering_torque,
        "motor_inertia": inertia.motor,
        "reduced_inertia": inertia.total,
        "start_time": motion.time,
        "angular_acceleration": motion.angular_acceleration,
        "inertia_torque": motion.inertia_torque,
        "starting_torque": motion.starting_torque,
        "load_acceleration": motion.load_acceleration,
    }
    if not inertia.estimated:  # the report shows these with the shafts only
        values["shaft_inertia"] = inertia.shafts
        values["load_inertia"] = inertia.load
        values["inertia_ratio"] = inertia.total / inertia.motor
    return values


def _value_at(node: Any, parts: list[str]) -> Any:
    for part in parts:
        node = node[int(part)] if isinstance(node, list) else getattr(node, part)
    return node


def _with_value(node: Any, parts: list[str], value: Any) -> Any:
    """``node`` (the case, a section or a list) with ``value`` at ``parts``, copied on
    the way and not validated, so that ``value`` may be a numpy array."""
    if not parts:
        return value
    head, rest = parts[0], parts[1:]
    if isinstance(node, list):
        i = int(head)
        return [*node[:i], _with_value(node[i], rest, value), *node[i + 1 :]]
    return node.model_copy(update={head: _with_value(getattr(node, head), rest, value)})


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
