"""The case file of ``mdcalc variator``: pydantic sections in SI units, and the
starter case."""

from __future__ import annotations

import math
from typing import Any, Literal

from pydantic import Field, model_validator

from mdcalc.core.units import rpm_to_rad_s
from mdcalc.input.model import CaseBase, CaseModel, FieldError, exactly_one

KGF_M = 9.80665  # N·m per kgf·m

STEEL_DENSITY = 7850.0  # kg/m³

RAD_S_TO_RPM = 30.0 / math.pi


class Absorber(CaseModel):
    inertia: float = Field(ge=1e-9, le=1e9, description="J₁, the disk that is shaken [kg·m²]")
    stiffness: float = Field(ge=1e-6, le=1e15, description="c, its shaft to the ground [N·m/rad]")
    absorber_inertia: float = Field(ge=1e-9, le=1e9, description="J₂, the absorber disk [kg·m²]")
    absorber_stiffness: float | None = Field(
        default=None,
        ge=1e-6,
        le=1e15,
        description="c_g, the absorber's shaft (default: tuned) [N·m/rad]",
    )
    tuning_frequency: float | None = Field(
        default=None, ge=1e-6, le=1e9, description="ω_t, tune c_g = J₂·ω_t² (default: ω) [rad/s]"
    )
    absorber_damping: float = Field(
        default=0.0, ge=0, le=1e12, description="b_g, across the absorber's shaft [N·m·s/rad]"
    )
    torque_amplitude: float = Field(ge=1e-9, le=1e12, description="M₀ [N·m]")
    frequency: float = Field(ge=1e-6, le=1e9, description="ω, of the torque [rad/s]")
    curve_points: int = Field(default=25, ge=3, le=2001, description="rows of the A(ω) table [-]")

    @model_validator(mode="after")
    def _tuning(self) -> Absorber:
        if self.absorber_stiffness is not None and self.tuning_frequency is not None:
            raise ValueError(
                "give absorber_stiffness or tuning_frequency in [absorber], not both "
                "(neither: tuned to the frequency)"
            )
        return self


class Motor(CaseModel):
    mains_frequency: float = Field(default=50.0, gt=0, le=1000, description="f_c [Hz]")
    pole_pairs: int = Field(ge=1, le=64, description="P [-]")
    synchronous_speed_rpm: float | None = Field(
        default=None, gt=0, description="n (default 60·f_c/P) [rpm]"
    )
    nominal_speed_rpm: float = Field(gt=0, description="n_H, catalogue [rpm]")
    nominal_torque: float | None = Field(default=None, gt=0, le=1e9, description="M_H [N·m]")
    nominal_power: float | None = Field(default=None, gt=0, le=1e10, description="P_H [W]")
    overload_ratio: float = Field(gt=1, le=10, description="λ_m = M_K/M_H [-]")

    @model_validator(mode="after")
    def _check(self) -> Motor:
        exactly_one("motor", nominal_torque=self.nominal_torque, nominal_power=self.nominal_power)
        if self.nominal_speed_rpm >= self.synchronous:
            raise FieldError(
                ("nominal_speed_rpm",),
                f"got {self.nominal_speed_rpm:g}; must be below the synchronous speed "
                f"{self.synchronous:g} rpm (an induction motor runs with slip)",
            )
        return self

    @property
    def synchronous(self) -> float:
        if self.synchronous_speed_rpm is not None:  # (a float, or a study's array)
            return self.synchronous_speed_rpm
        return 60.0 * self.mains_frequency / self.pole_pairs


class Clutch(CaseModel):
    loading_coefficient: float | None = Field(
        default=None, ge=1e-6, le=1e15, description="c₀ of M = c₀·ξⁿ [N·m/radⁿ]"
    )
    loading_coefficient_kgfm: float | None = Field(
        default=None, ge=1e-6, le=1e15, description="c₀ as the seed gives it [kgf·m/radⁿ]"
    )
    loading_exponent: float = Field(ge=0.5, le=10, description="n of M = c₀·ξⁿ [-]")
    load_min: float = Field(default=0.0, ge=0, le=1e12, description="working range from [N·m]")
    load_max: float = Field(ge=1e-6, le=1e12, description="working range to [N·m]")
    unloading_stiffness: float | None = Field(
        default=None, gt=0, le=1e15, description="c of the linearized unloading [N·m/rad]"
    )
    unloading_stiffness_kgfm: float | None = Field(
        default=None, gt=0, le=1e15, description="the same in the seed's unit [kgf·m/rad]"
    )
    loop_area_ratio: float | None = Field(
        default=None, ge=0, le=1, description="ψ = S₁/S of the loading loop (8.43) [-]"
    )

    @model_validator(mode="after")
    def _check(self) -> Clutch:
        exactly_one(
            "clutch",
            loading_coefficient=self.loading_coefficient,
            loading_coefficient_kgfm=self.loading_coefficient_kgfm,
        )
        if self.unloading_stiffness is not None and self.unloading_stiffness_kgfm is not None:
            raise ValueError("give unloading_stiffness or unloading_stiffness_kgfm, not both")
        if self.load_min >= self.load_max:
            raise FieldError(
                ("load_min",),
                f"got {self.load_min:g}; must be below load_max {self.load_max:g} N·m",
            )
        return self

    @property
    def c0(self) -> float:
        if self.loading_coefficient is not None:
            return self.loading_coefficient
        assert self.loading_coefficient_kgfm is not None  # exactly one is given
        return self.loading_coefficient_kgfm * KGF_M

    @property
    def unloading(self) -> float | None:
        if self.unloading_stiffness_kgfm is not None:
            return self.unloading_stiffness_kgfm * KGF_M
        return self.unloading_stiffness


class Mechanism(CaseModel):
    mechanisms: int = Field(ge=2, le=64, description="z, elementary mechanisms [-]")
    input_speed_rpm: float = Field(ge=1e-3, le=1e6, description="n₁, input shaft [rpm]")
    mean_ratio: float | None = Field(default=None, ge=1e-6, le=1e6, description="i_c [-]")
    output_speed_rpm: float | None = Field(
        default=None, ge=1e-6, le=1e6, description="n₂, mean output speed: i_c = n₁/n₂ [rpm]"
    )

    @model_validator(mode="after")
    def _one(self) -> Mechanism:
        exactly_one("mechanism", mean_ratio=self.mean_ratio, output_speed_rpm=self.output_speed_rpm)
        return self

    @property
    def ratio(self) -> float:
        if self.mean_ratio is not None:  # (a float, or a study's array)
            return self.mean_ratio
        assert self.output_speed_rpm is not None  # exactly one of the two is given
        return self.input_speed_rpm / self.output_speed_rpm


class Drive(CaseModel):
    driven_inertia: float = Field(ge=1e-9, le=1e9, description="J₂, on the output shaft [kg·m²]")
    load_torque: float = Field(ge=1e-6, le=1e12, description="M_c, on the output shaft [N·m]")
    clutch_stiffness: float | None = Field(
        default=None, ge=1e-6, le=1e15, description="c, linearized clutch [N·m/rad]"
    )
    clutch_stiffness_kgfm: float | None = Field(
        default=None, ge=1e-6, le=1e15, description="c in the seed's unit [kgf·m/rad]"
    )
    clutch_damping: float | None = Field(
        default=None, ge=0, le=1e12, description="b of the clutch [N·m·s/rad]"
    )
    clutch_loop_area_ratio: float | None = Field(
        default=None,
        ge=0,
        le=1,
        description="ψ = S₁/S, b = ψ/(2π)·√(J·c) (8.44) (default: [clutch] loop_area_ratio) [-]",
    )
    harmonics: list[int] = Field(
        default=[1, 10, 100, 1000], description="Fourier rows of the Methods table [-]"
    )
    ode: bool = Field(default=True, description="time-integration rows in the Methods table")
    points: int = Field(default=13, ge=3, le=1001, description="rows of the q(τ) table [-]")

    @model_validator(mode="after")
    def _check(self) -> Drive:
        exactly_one(
            "drive",
            clutch_stiffness=self.clutch_stiffness,
            clutch_stiffness_kgfm=self.clutch_stiffness_kgfm,
        )
        if self.clutch_damping is not None and self.clutch_loop_area_ratio is not None:
            raise ValueError("give clutch_damping or clutch_loop_area_ratio in [drive], not both")
        for index, k in enumerate(self.harmonics):
            if not 1 <= k <= 100_000:
                raise FieldError(("harmonics", index), f"got {k}; must be 1 to 100000 harmonics")
        return self

    @property
    def stiffness(self) -> float:
        if self.clutch_stiffness is not None:
            return self.clutch_stiffness
        assert self.clutch_stiffness_kgfm is not None  # exactly one is given
        return self.clutch_stiffness_kgfm * KGF_M


class Antiresonance(CaseModel):
    machine_inertia: float = Field(ge=1e-9, le=1e9, description="J₃, the machine [kg·m²]")
    ratio: float = Field(
        default=1.0, gt=0, le=1e4, description="i = ω₃/ω₂, machine over output speed [-]"
    )
    coupling_stiffness: float | None = Field(
        default=None, ge=1e-6, le=1e15, description="c₂ (default: tuned) [N·m/rad]"
    )
    coupling_damping: float = Field(default=0.0, ge=0, le=1e12, description="b₂ [N·m·s/rad]")


class Pendulum(CaseModel):
    pivot_radius: float = Field(ge=1e-4, le=100, description="R, disk centre to pivot [m]")
    order: float = Field(ge=1e-3, le=1000, description="n, oscillations per revolution [-]")
    speed: float | None = Field(default=None, ge=1e-3, le=1e6, description="ω, disk [rad/s]")
    speed_rpm: float | None = Field(default=None, ge=1e-3, le=1e7, description="disk [rpm]")
    inertia_torque: float | None = Field(
        default=None, ge=1e-9, le=1e12, description="M_ин, torque amplitude to absorb [N·m]"
    )
    max_swing: float | None = Field(
        default=None, ge=1e-6, lt=math.pi, description="θ_max, allowed swing [rad]"
    )
    bob_density: float = Field(
        default=STEEL_DENSITY, ge=1.0, le=1e5, description="bob material [kg/m³]"
    )
    bifilar_pin_diameter: float | None = Field(
        default=None, gt=0, le=10, description="d, pin of a bifilar design [m]"
    )

    @model_validator(mode="after")
    def _check(self) -> Pendulum:
        if self.speed is not None and self.speed_rpm is not None:
            raise ValueError("give speed or speed_rpm in [pendulum], not both")
        given = {
            "speed": self.speed or self.speed_rpm,
            "inertia_torque": self.inertia_torque,
            "max_swing": self.max_swing,
        }
        if self.inertia_torque is not None and None in given.values():
            missing = [k for k, v in given.items() if v is None]
            raise FieldError(
                (missing[0],), "the mass (8.56) needs speed, inertia_torque and max_swing"
            )
        return self

    @property
    def omega(self) -> float | None:
        if self.speed is not None:
            return self.speed
        return rpm_to_rad_s(self.speed_rpm) if self.speed_rpm is not None else None


class Case(CaseBase):
    problem: Literal["variator"] = Field(description="Problem name [-]")
    absorber: Absorber | None = None
    motor: Motor | None = None
    clutch: Clutch | None = None
    mechanism: Mechanism | None = None
    drive: Drive | None = None
    antiresonance: Antiresonance | None = None
    pendulum: Pendulum | None = None

    @model_validator(mode="after")
    def _sections(self) -> Case:
        parts = ("absorber", "motor", "clutch", "mechanism", "drive", "antiresonance", "pendulum")
        if all(getattr(self, p) is None for p in parts):
            raise ValueError(f"give at least one section: {', '.join(f'[{p}]' for p in parts)}")
        if self.drive is not None and self.mechanism is None:
            raise FieldError(("drive",), "[drive] needs [mechanism] (the stroke and its speed)")
        if self.antiresonance is not None and self.drive is None:
            raise FieldError(("antiresonance",), "[antiresonance] needs [drive]")
        return self


def template() -> dict[str, Any]:
    return {
        "problem": "variator",
        "title": "Two-disk anti-resonance absorber",
        "absorber": {
            "inertia": 2.0,
            "stiffness": 800.0,
            "absorber_inertia": 0.2,
            "torque_amplitude": 100.0,
            "frequency": 20.0,
        },
        "pendulum": {"pivot_radius": 0.1, "order": 4.0},
    }


def starter_extras() -> dict[str, Any]:
    """Example values ``mdcalc new`` shows commented out beside :func:`template` (keys
    of its sections, optional sections; ``_or``: keys shown but not uncommented): the VK
    impulse variator of seed 000 §8.3-8.5 (``cases/variator/vk_variator.toml``)."""
    return {
        "_source": "illustrative; the optional sections: the VK variator of seed 000 §8.3-8.5",
        "absorber": {"absorber_stiffness": 80.0, "tuning_frequency": 20.0},
        "pendulum": {"speed_rpm": 2000.0, "speed": 209.4, "inertia_torque": 1200.0,
                     "max_swing": 0.3, "bifilar_pin_diameter": 0.02},
        "motor": {"pole_pairs": 3, "nominal_speed_rpm": 949.0, "nominal_power": 3000.0,
                  "overload_ratio": 2.5,
                  "_or": {"synchronous_speed_rpm": 1000.0, "nominal_torque": 30.19}},
        "clutch": {"loading_coefficient_kgfm": 2.785e5, "loading_exponent": 2.15,
                   "load_min": 50.0, "load_max": 300.0, "unloading_stiffness_kgfm": 8.9e5,
                   "loop_area_ratio": 0.6,
                   "_or": {"loading_coefficient": 2.731e6, "unloading_stiffness": 8.728e6}},
        "mechanism": {"mechanisms": 4, "input_speed_rpm": 1000.0, "output_speed_rpm": 185.0,
                      "_or": {"mean_ratio": 5.405}},
        "drive": {"driven_inertia": 0.05, "load_torque": 300.0, "clutch_stiffness_kgfm": 8.9e5,
                  "_or": {"clutch_stiffness": 8.728e6, "clutch_damping": 350.0,
                          "clutch_loop_area_ratio": 0.6}},
        "antiresonance": {"machine_inertia": 1.5, "coupling_damping": 20.0,
                          "_or": {"coupling_stiffness": 8490.0}},
    }  # fmt: skip
