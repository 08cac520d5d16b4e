"""The scene: the car, its gears and resistances; traction, adhesion limit and
acceleration in a gear. Its numbers are floats for one scene, or numpy arrays over a
block of scenes (the study kernel's): each method is written once for both."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from mdcalc.core.motion import constant_force_phase
from mdcalc.core.xp import of
from mdcalc.problems.acceleration.case import Case, engine_curve, engine_speeds
from mdcalc.problems.acceleration.engine import EngineCurve


@dataclass(frozen=True)
class Scene:
    """The case reduced to SI numbers the methods share."""

    mass: float
    g: float
    radius: float
    ratios: tuple[float, ...]
    final_drive: float
    efficiency: float
    deltas: tuple[float, ...]  # δ_i, clutch engaged
    delta_free: float  # δ_0: clutch slipping or disengaged, engine not accelerated
    psi: float
    drag: float  # k [kg/m]
    phi: float | None  # adhesion coefficient; None: traction unlimited
    axle_load: float  # static normal force on the driven wheels [N]
    transfer: float  # ±h/L: +1 rear drive, -1 front, 0 all-wheel or not given
    curve: EngineCurve
    launch: float  # ω held while the clutch slips [rad/s]
    shift: float  # upshift ω [rad/s]
    limit: float  # rev limit ω [rad/s]
    shift_time: float
    target: float  # [m/s]

    @property
    def gears(self) -> int:
        return len(self.ratios)

    def overall(self, gear: int) -> float:
        return self.ratios[gear] * self.final_drive

    def engine_speed(self, gear: int, v: float) -> float:
        return v * self.overall(gear) / self.radius

    def road_speed(self, gear: int, omega: float) -> float:
        return omega * self.radius / self.overall(gear)

    def resistance(self, v: float) -> float:
        """ψ·m·g + k·v² [N]."""
        return self.psi * self.mass * self.g + self.drag * v * v

    def engine_omega(self, gear: int, v: Any, slipping: Any) -> Any:
        """The engine speed that drives: held at the launch speed while the clutch
        slips, else the one the road speed gives in the gear [rad/s]."""
        return of(v, slipping).where(
            slipping, lambda: self.launch, lambda: self.engine_speed(gear, v)
        )

    def engine_force(self, gear: int, v: float, slipping: bool) -> float:
        """(7.35) with the engine curve: M_e·U_i·U_K·η/r [N]."""
        omega = self.engine_omega(gear, v, slipping)
        return self.curve.torque(omega) * self.overall(gear) * self.efficiency / self.radius

    def traction_coefficient(self, torque: float) -> float:
        """(7.35): A/m = M·U_K·η/r/m, the traction per unit gear ratio and unit mass
        that engine torque ``torque`` gives [m/s²]."""
        return torque * self.final_drive * self.efficiency / self.radius / self.mass

    def adhesion_force(self, v: float) -> float:
        """φ·N on the driven axle; N shifts by m·a·h/L, a = (F - R)/(δ_0·m)."""
        assert self.phi is not None
        resistance = self.resistance(v)
        s = self.transfer / self.delta_free
        return self.phi * (self.axle_load - s * resistance) / (1.0 - s * self.phi)

    def delta(self, gear: int, slipping: Any) -> Any:
        return of(slipping, self.deltas[gear]).where(
            slipping, lambda: self.delta_free, lambda: self.deltas[gear]
        )

    def engine_acceleration(self, gear: int, v: float, slipping: bool) -> float:
        """(F_t - R)/(δ·m): what the engine gives if the tyres pass it."""
        force = self.engine_force(gear, v, slipping)
        return (force - self.resistance(v)) / (self.delta(gear, slipping) * self.mass)

    def adhesion_acceleration(self, v: float) -> float:
        """(φ·N - R)/(δ_0·m): the most the tyres allow. When they limit the car, the
        engine's surplus turns the engine and driveline, so their inertia (δ_e·U_i²)
        is not charged to the tyre force; δ_0 keeps the wheels'. With rear drive, no
        more than the acceleration at which the front wheels lift:
        m·a·h/L = m·g - N_0."""
        a = (self.adhesion_force(v) - self.resistance(v)) / (self.delta_free * self.mass)
        xp = of(a, self.transfer)
        return xp.where(
            self.transfer > 0.0,
            lambda: xp.minimum(
                a, (self.mass * self.g - self.axle_load) / (self.mass * self.transfer)
            ),
            lambda: a,
        )

    def adhesion_limited(self, gear: int, v: Any, slipping: Any) -> Any:
        if self.phi is None:
            return False
        return self.adhesion_acceleration(v) < self.engine_acceleration(gear, v, slipping)

    def acceleration(self, gear: int, v: Any, slipping: Any) -> Any:
        a = self.engine_acceleration(gear, v, slipping)
        if self.phi is None:
            return a
        grip = self.adhesion_acceleration(v)
        return of(a, grip).minimum(a, grip)

    def engine_speed_at(self, gear: int, v: Any) -> Any:
        """The engine's actual speed: held at the launch speed while the clutch slips."""
        speed = self.engine_speed(gear, v)
        return of(speed, self.launch).maximum(speed, self.launch)

    def slipping_at(self, gear: int, v: Any) -> Any:
        """The clutch slips while the road speed gives less than the launch engine speed."""
        return self.engine_speed(gear, v) < self.launch

    def coast_deceleration(self, v: float) -> float:
        """R/(δ_0·m): the deceleration with no traction, the clutch open [m/s²]."""
        return self.resistance(v) / (self.delta_free * self.mass)

    def coast(self, v: Any, duration: Any) -> tuple[Any, Any]:
        """Speed after a shift of ``duration`` and the distance covered (closed form)."""
        phase = constant_force_phase(
            v, self.psi * self.mass * self.g, self.drag, self.delta_free * self.mass, duration
        )
        return phase.speed, phase.distance


def scene_of(case: Case) -> Scene:
    curve = engine_curve(case.engine)
    launch, shift, limit = engine_speeds(case, curve)
    vehicle, gearbox = case.vehicle, case.transmission
    ratios = tuple(gearbox.gear_ratios)
    if vehicle.rotating_mass_factors is not None:
        deltas = tuple(vehicle.rotating_mass_factors)
    else:
        deltas = tuple(
            vehicle.rotating_mass_base + vehicle.rotating_mass_engine * u * u for u in ratios
        )
    weight = vehicle.mass * case.gravity
    adhesion = case.adhesion
    transfer = 0.0
    if adhesion is not None and adhesion.cg_height is not None and adhesion.wheelbase is not None:
        sign = {"rear": 1.0, "front": -1.0, "all": 0.0}[adhesion.drive]
        transfer = sign * adhesion.cg_height / adhesion.wheelbase
    return Scene(
        mass=vehicle.mass,
        g=case.gravity,
        radius=vehicle.wheel_radius,
        ratios=ratios,
        final_drive=gearbox.final_drive,
        efficiency=gearbox.efficiency,
        deltas=deltas,
        delta_free=vehicle.rotating_mass_base,
        psi=case.road.resistance,
        drag=case.drag.factor if case.drag is not None else 0.0,
        phi=adhesion.phi if adhesion is not None else None,
        axle_load=(adhesion.driven_axle_load if adhesion is not None else 1.0) * weight,
        transfer=transfer,
        curve=curve,
        launch=launch,
        shift=shift,
        limit=limit,
        shift_time=gearbox.shift_time,
        target=case.target.value,
    )
