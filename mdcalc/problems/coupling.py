"""``coupling``: dynamic factor of an elastic coupling between two inertias (seed 000
§8.1, §8.2 first part, example 8.1; brief §5).

Model (8.3): for the twist φ = φ₁ - φ₂, φ'' + p·φ' + q·φ = M₁/J₁ + M₂/J₂ with
q = c·(1/J₁ + 1/J₂) = β², p = α·(1/J₁ + 1/J₂). A torque M passed through the
coupling enters as M/J, J = J₁J₂/(J₁ + J₂), so its static twist is M/c. Damping from
the absorption coefficient ψ (p = ψ/τ, (8.7) and (8.14) with the lecture's
τ = 2π/β), the logarithmic decrement δ (p = 2δ/τ) or α itself. In the terms of
:mod:`mdcalc.core.sdof`, ζ = p/(2β).

* Suddenly applied torque (8.15)-(8.16): dynamic factor 1 + exp(-π·ζ/√(1 - ζ²)),
  envelope 1 + e^(-p·t/2), exactly 2 undamped, 1 over-damped.
* Harmonic torques on both halves (8.19)-(8.32): the combined amplitude (8.21), the
  steady twist (8.27), the response curve over λ = ω/β, the resonance peak at
  λ = √(1 - γ²/2) of height M/(β²·γ·√(1 - γ²/4)), γ = p/β (the printed (8.32) has
  √(1 - γ²/2)).
* Rectangular pulse, ramp and tabulated torque through the Duhamel integral, exact
  for piecewise-linear loads, checked against ODE runs in the Methods table.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

from pydantic import Field, model_validator

from mdcalc.core import sdof
from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.units import rpm_to_rad_s
from mdcalc.methods import Method, compare
from mdcalc.model import CaseBase, CaseModel, FieldError, exactly_one
from mdcalc.report import (
    Column,
    MethodQuantity,
    MethodsTable,
    Note,
    Quantities,
    Quantity,
    Report,
    Table,
)

if TYPE_CHECKING:
    from mdcalc.plot import Chart

DEG = math.pi / 180.0

# ------------------------------------------------------------------------ the case


class Coupling(CaseModel):
    driving_inertia: float = Field(gt=0, description="J₁, driving half with the motor [kg·m^2]")
    driven_inertia: float = Field(gt=0, description="J₂, driven half with the machine [kg·m^2]")
    stiffness: float | None = Field(default=None, gt=0, description="c [N·m/rad]")
    stiffness_nm_per_deg: float | None = Field(
        default=None, gt=0, description="c, as catalogues give it [N·m/deg]"
    )
    absorption: float | None = Field(
        default=None, ge=0, le=20, description="ψ = ΔU/U, absorption coefficient (8.13) [-]"
    )
    log_decrement: float | None = Field(
        default=None, ge=0, le=10, description="δ = ln(A₁/A₂), logarithmic decrement (8.7) [-]"
    )
    damping: float | None = Field(
        default=None, ge=0, description="α, viscous damping of the coupling [N·m·s/rad]"
    )

    @model_validator(mode="after")
    def _one(self) -> Coupling:
        exactly_one(
            "coupling", stiffness=self.stiffness, stiffness_nm_per_deg=self.stiffness_nm_per_deg
        )
        given = [
            k for k in ("absorption", "log_decrement", "damping") if getattr(self, k) is not None
        ]
        if len(given) > 1:
            raise FieldError(
                (given[1],),
                f"give one of absorption, log_decrement, damping (got {', '.join(given)})",
            )
        return self


class Step(CaseModel):
    torque: float | None = Field(
        default=None, gt=0, description="M₀, the suddenly applied torque (optional) [N·m]"
    )


class Harmonic(CaseModel):
    driving_torque: float = Field(ge=0, description="M₁, amplitude on the driving half [N·m]")
    driving_phase_deg: float = Field(default=0.0, description="α, its phase [deg]")
    driven_torque: float = Field(
        default=0.0, ge=0, description="M₂, amplitude on the driven half [N·m]"
    )
    driven_phase_deg: float = Field(default=0.0, description="γ, its phase [deg]")
    speed: float | None = Field(default=None, gt=0, description="ω [rad/s]")
    speed_rpm: float | None = Field(default=None, gt=0, description="ω [rpm]")

    @model_validator(mode="after")
    def _one(self) -> Harmonic:
        exactly_one("harmonic", speed=self.speed, speed_rpm=self.speed_rpm)
        if self.driving_torque == 0.0 and self.driven_torque == 0.0:
            raise FieldError(
                ("driving_torque",), "both torque amplitudes are 0: nothing excites the coupling"
            )
        return self

    @property
    def omega(self) -> float:
        if self.speed is not None:
            return self.speed
        assert self.speed_rpm is not None  # validated: exactly one (no `or`: arrays in sweep)
        return rpm_to_rad_s(self.speed_rpm)


class Pulse(CaseModel):
    torque: float = Field(gt=0, description="Torque of the rectangular pulse [N·m]")
    duration: float = Field(gt=0, description="Its duration [s]")
    horizon: float | None = Field(
        default=None, gt=0, description="End of the run; default duration + 2τ [s]"
    )


class Ramp(CaseModel):
    torque: float = Field(gt=0, description="Torque reached and then held [N·m]")
    rise_time: float = Field(gt=0, description="Time to reach it, rising linearly [s]")
    horizon: float | None = Field(
        default=None, gt=0, description="End of the run; default rise + 2τ [s]"
    )


class TorqueTable(CaseModel):
    time: list[float] = Field(
        min_length=2, description="Times, not decreasing; a repeat is a jump [s]"
    )
    torque: list[float] = Field(
        min_length=2, description="Torque, linear between points, held after [N·m]"
    )
    horizon: float | None = Field(
        default=None, gt=0, description="End of the run; default last time + 2τ [s]"
    )

    @model_validator(mode="after")
    def _table(self) -> TorqueTable:
        if len(self.time) != len(self.torque):
            raise FieldError(("torque",), f"{len(self.torque)} values for {len(self.time)} times")
        if self.time[0] < 0 or any(b < a for a, b in zip(self.time, self.time[1:], strict=False)):
            raise FieldError(("time",), f"got {self.time}; must start at >= 0 s and not decrease")
        if all(t == 0.0 for t in self.torque):
            raise FieldError(("torque",), "all zero: nothing loads the coupling")
        return self


class Case(CaseBase):
    problem: Literal["coupling"] = Field(description="Problem name [-]")
    coupling: Coupling
    step: Step | None = None
    harmonic: Harmonic | None = None
    pulse: Pulse | None = None
    ramp: Ramp | None = None
    torque_table: TorqueTable | None = None


# ------------------------------------------------------------------------ the scene


@dataclass(frozen=True)
class Scene:
    """Floats; in :func:`sweep`, numpy arrays with ``xp`` numpy (same formulas)."""

    j1: float
    j2: float
    stiffness: float  # c [N·m/rad]
    p: float  # [1/s]
    xp: Any = field(default=math, repr=False, compare=False)  # math or numpy

    @property
    def reduced_inertia(self) -> float:
        return self.j1 * self.j2 / (self.j1 + self.j2)

    @property
    def beta(self) -> float:
        return self.xp.sqrt(self.stiffness / self.reduced_inertia)

    @property
    def period(self) -> float:
        """τ = 2π/β (8.5), the lecture's period (undamped)."""
        return 2.0 * math.pi / self.beta

    @property
    def zeta(self) -> float:
        return self.p / (2.0 * self.beta)

    @property
    def alpha(self) -> float:
        """α = p·J [N·m·s/rad]."""
        return self.p * self.reduced_inertia


def scene_of(case: Case, xp: Any = math) -> Scene:
    """The scene; with ``xp`` numpy, of a case whose fields are arrays (:func:`sweep`)."""
    k = case.coupling
    if k.stiffness is not None:
        stiffness = k.stiffness
    else:  # validated: exactly one (no `or`: arrays in sweep)
        assert k.stiffness_nm_per_deg is not None
        stiffness = k.stiffness_nm_per_deg / DEG
    j = k.driving_inertia * k.driven_inertia / (k.driving_inertia + k.driven_inertia)
    tau = 2.0 * math.pi / xp.sqrt(stiffness / j)
    if k.absorption is not None:
        p = k.absorption / tau  # (8.7), (8.14): δ = ψ/2 = p·τ/2
    elif k.log_decrement is not None:
        p = 2.0 * k.log_decrement / tau
    elif k.damping is not None:
        p = k.damping / j  # p = α·(1/J₁ + 1/J₂)
    else:
        p = 0.0
    return Scene(k.driving_inertia, k.driven_inertia, stiffness, p, xp)


# ---------------------------------------------------------------------- transients


@dataclass(frozen=True)
class Transient:
    """A torque history M(t) through the coupling, as piecewise-linear knots."""

    key: str
    title: str
    knots: list[tuple[float, float]]
    horizon: float
    closed_form: float | None = None  # an exact peak factor where one exists
    closed_form_name: str = ""

    @property
    def peak_torque(self) -> float:
        return max(abs(m) for _, m in self.knots)


def transients(case: Case, scene: Scene) -> list[Transient]:
    tau = scene.period
    out: list[Transient] = []
    if case.pulse is not None:
        p = case.pulse
        knots = [(0.0, 0.0), (0.0, p.torque), (p.duration, p.torque), (p.duration, 0.0)]
        exact = sdof.rectangular_pulse_peak(scene.beta, p.duration) if scene.p == 0.0 else None
        out.append(
            Transient(
                "pulse",
                f"Rectangular pulse, {p.torque:g} N·m for {p.duration:g} s",
                knots,
                p.horizon or p.duration + 2.0 * tau,
                exact,
                "closed form 2·sin(β·T/2) or 2 (7.96)",
            )
        )
    if case.ramp is not None:
        r = case.ramp
        exact = None
        if scene.p == 0.0:  # undamped ramp-and-hold: 1 + |sin(β·t_r/2)|/(β·t_r/2)
            half = 0.5 * scene.beta * r.rise_time
            exact = 1.0 + abs(math.sin(half)) / half
        out.append(
            Transient(
                "ramp",
                f"Ramp to {r.torque:g} N·m in {r.rise_time:g} s, then held",
                [(0.0, 0.0), (r.rise_time, r.torque)],
                r.horizon or r.rise_time + 2.0 * tau,
                exact,
                "closed form 1 + |sin(β·t_r/2)|/(β·t_r/2)",
            )
        )
    if case.torque_table is not None:
        t = case.torque_table
        knots = list(zip(t.time, t.torque, strict=True))
        if knots[0][0] > 0.0:
            knots.insert(0, (0.0, 0.0))
        out.append(
            Transient(
                "table",
                "Tabulated torque",
                knots,
                t.horizon or t.time[-1] + 2.0 * tau,
            )
        )
    return out


def duhamel_response(scene: Scene, transient: Transient) -> sdof.Response:
    """The exact response, twist over static-under-peak-torque, sampled to the horizon."""
    scale = transient.peak_torque
    return sdof.piecewise_linear_response(
        [t for t, _ in transient.knots],
        [m / scale for _, m in transient.knots],
        scene.beta,
        scene.zeta,
        transient.horizon,
    )


def duhamel_peak(scene: Scene, transient: Transient) -> tuple[float, float]:
    """Peak twist over static-under-peak-torque, and its time: the exact response."""
    response = duhamel_response(scene, transient)
    return response.peak, response.peak_time


def ode_peak(scene: Scene, transient: Transient, rtol: float) -> float:
    from mdcalc.core.ode import oscillator_peak

    scale = transient.peak_torque
    knots = [(t, m / scale) for t, m in transient.knots]
    return oscillator_peak(scene.beta, scene.zeta, knots, transient.horizon, rtol)[0]


# ------------------------------------------------------------------------- result


@dataclass
class Result:
    case: Case
    scene: Scene
    step_methods: MethodsTable | None = None
    harmonic_methods: MethodsTable | None = None
    transient_methods: list[tuple[Transient, MethodsTable, tuple[float, float]]] = field(
        default_factory=list
    )
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


FACTOR = [MethodQuantity("dynamic_factor", "dynamic factor", "")]
ODE_RTOLS = ((1e-3, "RK45"), (1e-6, "RK45"), (1e-10, "DOP853"))


def _ode_methods(run: Callable[[float], float]) -> list[Method]:
    def method(rtol: float, name: str) -> Method:
        return Method(
            f"ODE {name}, rtol {rtol:.0e}".replace("e-0", "e-"),
            lambda: {"dynamic_factor": run(rtol)},
            imports=ODE_IMPORTS,
        )

    return [method(rtol, name) for rtol, name in ODE_RTOLS]


def step_factor_lecture(scene: Scene) -> float:
    """Example 8.1's reading of (8.16): peak at t = τ/2 with β₁ ≈ β and (p/2)²
    neglected: 1 + e^(-p·τ/4)."""
    return 1.0 + math.exp(-scene.p * scene.period / 4.0)


def solve(case: Case) -> Result:
    scene = scene_of(case)
    result = Result(case, scene)
    if case.harmonic is not None and scene.p == 0.0:
        ratio = case.harmonic.omega / scene.beta
        if ratio == 1.0:
            result.status = "no-answer"
            result.message = (
                f"undamped resonance: ω = β = {scene.beta:.6g} rad/s and the coupling has no "
                "damping, so the steady twist (8.27) is unbounded; give absorption, "
                "log_decrement or damping"
            )
            return result
    if case.step is not None:
        zeta = scene.zeta
        horizon = (sdof.step_peak_time(scene.beta, zeta) or 10.0 / scene.beta) * 1.5
        step = Transient("step", "step", [(0.0, 1.0)], horizon)
        result.step_methods = compare(
            "Methods: dynamic factor of a suddenly applied torque",
            "step",
            FACTOR,
            [
                Method(
                    "lecture: t = τ/2, β₁ ≈ β",
                    lambda: {"dynamic_factor": step_factor_lecture(scene)},
                    note="example 8.1",
                ),
                Method(
                    "exact 1 + exp(-πζ/√(1-ζ²))",
                    lambda: {"dynamic_factor": sdof.step_peak(zeta)},
                    reference=True,
                ),
                *_ode_methods(lambda rtol: ode_peak(scene, step, rtol)),
            ],
        )
    if case.harmonic is not None and scene.p > 0.0:
        gamma = scene.p / scene.beta
        if gamma * gamma < 2.0:
            result.harmonic_methods = compare(
                "Methods: resonance peak of the twist, in units of M/β²",
                "resonance",
                [MethodQuantity("resonance_peak", "peak·β²/M", "")],
                [
                    Method(
                        "(8.32) as printed, √(1 - γ²/2)",
                        lambda: {"resonance_peak": 1.0 / (gamma * math.sqrt(1.0 - gamma**2 / 2.0))},
                    ),
                    Method(
                        "corrected (8.32), √(1 - γ²/4)",
                        lambda: {"resonance_peak": 1.0 / (gamma * math.sqrt(1.0 - gamma**2 / 4.0))},
                        reference=True,
                    ),
                    Method(
                        "max of (8.28) on a λ grid of 10⁴ points",
                        lambda: {"resonance_peak": _grid_peak(gamma)},
                    ),
                ],
            )
    for transient in transients(case, scene):
        table = compare(
            f"Methods: {transient.title}",
            transient.key,
            FACTOR,
            _transient_methods(scene, transient),
        )
        result.transient_methods.append((transient, table, duhamel_peak(scene, transient)))
    return result


def _transient_methods(scene: Scene, transient: Transient) -> list[Method]:
    methods: list[Method] = []
    exact = transient.closed_form
    if exact is not None:
        methods.append(
            Method(transient.closed_form_name, lambda: {"dynamic_factor": exact}, note="undamped")
        )
    methods.append(
        Method(
            "Duhamel, exact for piecewise-linear loads",
            lambda: {"dynamic_factor": duhamel_peak(scene, transient)[0]},
            reference=True,
        )
    )
    return methods + _ode_methods(lambda rtol: ode_peak(scene, transient, rtol))


def _grid_peak(gamma: float) -> float:
    return max(
        1.0 / math.hypot(1.0 - lam * lam, gamma * lam)
        for lam in (3.0 * k / 10000 for k in range(10001))
    )


# ------------------------------------------------------------------------- report


def report(result: Result) -> Report:
    case, s = result.case, result.scene
    title = case.title or "Elastic coupling"
    sections: list[Any] = [_scene_section(case, s)]
    notes: list[Note] = []
    if result.status != "ok":
        return Report("coupling", title, sections, notes, result.status, result.message)
    if case.step is not None:
        sections.append(_step_section(case.step, s))
        assert result.step_methods is not None
        sections.append(result.step_methods)
    if case.harmonic is not None:
        harmonic_sections, harmonic_notes = _harmonic_sections(case.harmonic, s)
        sections += harmonic_sections
        notes += harmonic_notes
        if result.harmonic_methods is not None:
            sections.append(result.harmonic_methods)
    for transient, table, (factor, when) in result.transient_methods:
        static = transient.peak_torque / s.stiffness
        sections.append(
            Quantities(
                transient.title,
                [
                    Quantity(
                        f"{transient.key}_dynamic_factor", "Dynamic factor φ_max/φ_st", factor, ""
                    ),
                    Quantity(f"{transient.key}_peak_time", "Time of the peak", when, "s"),
                    Quantity(
                        f"{transient.key}_peak_twist", "Peak twist φ_max", factor * static, "rad"
                    ),
                    Quantity(
                        f"{transient.key}_peak_torque",
                        "Peak elastic torque c·φ_max",
                        factor * transient.peak_torque,
                        "N·m",
                    ),
                ],
            )
        )
        sections.append(table)
    return Report("coupling", title, sections, notes)


def _scene_section(case: Case, s: Scene) -> Quantities:
    items = [
        Quantity("driving_inertia", "J₁", s.j1, "kg·m²"),
        Quantity("driven_inertia", "J₂", s.j2, "kg·m²"),
        Quantity(
            "stiffness", "Stiffness c", s.stiffness, "N·m/rad", f"{s.stiffness * DEG:.5g} N·m/deg"
        ),
        Quantity("reduced_inertia", "J = J₁·J₂/(J₁ + J₂)", s.reduced_inertia, "kg·m²"),
        Quantity("natural_frequency", "β = √(c/J)", s.beta, "rad/s"),
        Quantity("period", "τ = 2π/β (8.5)", s.period, "s"),
    ]
    if s.p > 0.0:
        items += [
            Quantity("damping_p", "p (8.3)", s.p, "1/s"),
            Quantity("damping_alpha", "α = p·J", s.alpha, "N·m·s/rad"),
            Quantity("log_decrement", "δ = p·τ/2 (8.7)", s.p * s.period / 2.0, ""),
            Quantity("absorption", "ψ = 2δ (8.14)", s.p * s.period, ""),
            Quantity("damping_ratio", "ζ = p/(2β)", s.zeta, ""),
        ]
    return Quantities("Coupling", items)


def _step_section(step: Step, s: Scene) -> Quantities:
    zeta = s.zeta
    factor = sdof.step_peak(zeta)
    peak_time = sdof.step_peak_time(s.beta, zeta)
    items = [
        Quantity(
            "step_dynamic_factor",
            "Dynamic factor, first peak",
            factor,
            "",
            "over-damped: no overshoot" if peak_time is None else "",
        ),
    ]
    if peak_time is not None:
        items.append(Quantity("step_peak_time", "Time of the first peak π/β₁", peak_time, "s"))
    items += [
        Quantity(
            "envelope_at_period",
            "Envelope 1 + e^(-pτ/2) at t = τ",
            sdof.step_envelope(s.period, s.beta, zeta),
            "",
        ),
        Quantity(
            "envelope_at_1_5_period",
            "Envelope at t = 1.5·τ",
            sdof.step_envelope(1.5 * s.period, s.beta, zeta),
            "",
        ),
        Quantity("undamped_dynamic_factor", "Without damping", 2.0, ""),
    ]
    if step.torque is not None:
        items += [
            Quantity("static_twist", "Static twist M₀/c", step.torque / s.stiffness, "rad"),
            Quantity("peak_twist", "Peak twist", factor * step.torque / s.stiffness, "rad"),
            Quantity("peak_torque", "Peak elastic torque", factor * step.torque, "N·m"),
        ]
    return Quantities("Suddenly applied torque (8.15)-(8.16)", items)


def harmonic_numbers(h: Harmonic, s: Scene) -> dict[str, Any]:
    """(8.21)-(8.27) by result key, floats or (in :func:`sweep`) arrays; the report
    shows steady_torque_total and gamma only with damping. Undamped resonance (no
    answer) divides by 0."""
    xp = s.xp
    a1, a2 = h.driving_torque / s.j1, h.driven_torque / s.j2
    alpha, gamma_phase = h.driving_phase_deg * DEG, h.driven_phase_deg * DEG
    real = a1 * xp.cos(alpha) + a2 * xp.cos(gamma_phase)
    imag = a1 * xp.sin(alpha) + a2 * xp.sin(gamma_phase)
    m = xp.hypot(real, imag)  # (8.21)
    twist = m / xp.hypot(s.beta**2 - h.omega**2, s.p * h.omega)  # (8.27)
    return {
        "combined_amplitude": m,
        "combined_phase": xp.degrees(xp.atan2(imag, real)),
        "frequency_ratio": h.omega / s.beta,
        "steady_twist": twist,
        "steady_torque": s.stiffness * twist,
        "steady_torque_total": xp.hypot(s.stiffness, s.alpha * h.omega) * twist,
        "gamma": s.p / s.beta,
    }


def resonance(m: Any, s: Scene) -> tuple[Any, Any]:
    """λ of the resonance peak (8.31) and its twist (corrected (8.32)) for the combined
    amplitude m; the report shows them for p > 0 and γ² < 2."""
    gamma = s.p / s.beta
    peak = m / (s.beta**2 * gamma * s.xp.sqrt(1.0 - gamma**2 / 4.0))
    return s.xp.sqrt(1 - gamma**2 / 2), peak


def _harmonic_sections(h: Harmonic, s: Scene) -> tuple[list[Any], list[Note]]:
    n = harmonic_numbers(h, s)
    omega, lam, gamma = h.omega, n["frequency_ratio"], n["gamma"]
    items = [
        Quantity(
            "combined_amplitude", "M (8.21), in units of M/J", n["combined_amplitude"], "rad/s²"
        ),
        Quantity("combined_phase", "ε", n["combined_phase"], "deg"),
        Quantity("frequency_ratio", "λ = ω/β", lam, ""),
        Quantity("steady_twist", "Steady twist amplitude φ_max (8.27)", n["steady_twist"], "rad"),
        Quantity("steady_torque", "Elastic torque amplitude c·φ_max", n["steady_torque"], "N·m"),
    ]
    if s.p > 0.0:
        items.append(
            Quantity(
                "steady_torque_total",
                "Torque amplitude with damping √(c² + (αω)²)·φ_max",
                n["steady_torque_total"],
                "N·m",
            )
        )
        items.append(Quantity("gamma", "γ = p/β", gamma, ""))
        if gamma * gamma < 2.0:
            ratio, peak = resonance(n["combined_amplitude"], s)
            items += [
                Quantity("resonance_ratio", "Peak at λ = √(1 - γ²/2) (8.31)", ratio, ""),
                Quantity(
                    "resonance_twist",
                    "Peak twist M/(β²·γ·√(1 - γ²/4))",
                    peak,
                    "rad",
                    "the printed (8.32) has √(1 - γ²/2)",
                ),
            ]
    rows: list[list[Any]] = []
    for k in range(31):
        x = 0.1 * k
        rows.append(
            [x, 1.0 / math.hypot(1 - x * x, gamma * x) if (x != 1.0 or gamma > 0) else None]
        )
    curve = Table(
        "Response curve (8.28): φ_max·β²/M against λ",
        "response_curve",
        [Column("λ"), Column("φ_max·β²/M")],
        rows,
    )
    notes = []
    if lam <= 1.5:
        notes.append(
            Note(
                "warning",
                f"λ = ω/β = {lam:.3g}: the lecture's advice is λ > 1.5 (a softer coupling, "
                f"c < {s.reduced_inertia * (omega / 1.5) ** 2:.4g} N·m/rad), passing "
                "the resonance quickly at start and stop",
            )
        )
    return [Quantities("Harmonic torques (8.19)-(8.27)", items), curve], notes


# ------------------------------------------------------------------------- sweep

#: Keys ``mdcalc sweep`` may vary in the vectorized form, and the scene input each sets.
SWEEP_KEYS = {
    "coupling.driving_inertia": "j1",
    "coupling.driven_inertia": "j2",
    "coupling.stiffness": "stiffness",
    "coupling.stiffness_nm_per_deg": "stiffness",
    "coupling.absorption": "p",
    "coupling.log_decrement": "p",
    "coupling.damping": "p",
    "step.torque": "step_torque",
    "harmonic.driving_torque": "combined_amplitude",
    "harmonic.driving_phase_deg": "combined_amplitude",
    "harmonic.driven_torque": "combined_amplitude",
    "harmonic.driven_phase_deg": "combined_amplitude",
    "harmonic.speed": "omega",
    "harmonic.speed_rpm": "omega",
}
SECTIONS: dict[str, type[CaseModel]] = {
    "coupling": Coupling,
    "step": Step,
    "harmonic": Harmonic,
}


def sweep(case: Case, grid: dict[str, Any]) -> dict[str, Any] | None:
    """The closed-form results over a grid of scenes at once (numpy): the coupling,
    the suddenly applied torque and the harmonic torques, by the formulas of the
    report; missing (NaN) where the report does not show a value. Without the pulse,
    ramp and table results (Duhamel: point by point). None for another key, or where
    a point is at undamped resonance (no answer)."""
    import numpy as np

    if any(key not in SWEEP_KEYS for key in grid):
        return None
    update: dict[str, dict[str, Any]] = {name: {} for name in SECTIONS}
    for key, values in grid.items():
        section, _, name = key.partition(".")
        update[section][name] = np.asarray(values, dtype=float)
    # The case with the grid's arrays in its sections (no validation: the sweep has
    # validated the grid's corners), so that scene_of picks the alternatives it does.
    sections: dict[str, Any] = {}
    for section, model in SECTIONS.items():
        base = getattr(case, section)
        if base is not None:
            sections[section] = base.model_copy(update=update[section])
        elif update[section]:  # a section the grid adds (step.torque)
            sections[section] = model.model_construct(**update[section])
    arrays = case.model_copy(update=sections)
    s = scene_of(arrays, np)
    damped = s.p > 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        out: dict[str, Any] = {
            "driving_inertia": s.j1,
            "driven_inertia": s.j2,
            "stiffness": s.stiffness,
            "reduced_inertia": s.reduced_inertia,
            "natural_frequency": s.beta,
            "period": s.period,
            "damping_p": np.where(damped, s.p, np.nan),
            "damping_alpha": np.where(damped, s.alpha, np.nan),
            "log_decrement": np.where(damped, s.p * s.period / 2.0, np.nan),
            "absorption": np.where(damped, s.p * s.period, np.nan),
            "damping_ratio": np.where(damped, s.zeta, np.nan),
        }
        if arrays.step is not None:
            out |= _step_arrays(arrays.step.torque, s)
        if arrays.harmonic is not None:
            numbers = harmonic_numbers(arrays.harmonic, s)
            if np.any((s.p == 0.0) & (numbers["frequency_ratio"] == 1.0)):
                return None  # no answer there, as the point-by-point status says
            resonant = damped & (numbers["gamma"] * numbers["gamma"] < 2.0)
            ratio, peak = resonance(numbers["combined_amplitude"], s)
            out |= numbers | {
                "steady_torque_total": np.where(damped, numbers["steady_torque_total"], np.nan),
                "gamma": np.where(damped, numbers["gamma"], np.nan),
                "resonance_ratio": np.where(resonant, ratio, np.nan),
                "resonance_twist": np.where(resonant, peak, np.nan),
            }
    return out


def _step_arrays(torque: Any, s: Scene) -> dict[str, Any]:
    """The suddenly applied torque's results, as in :func:`_step_section` with
    sdof.step_peak, step_peak_time and step_envelope on arrays (errors ignored)."""
    import numpy as np

    zeta, beta = s.zeta, s.beta
    root = np.sqrt(1.0 - zeta * zeta)  # 0 or NaN from ζ = 1 on: factor 1, no peak time
    factor = np.where(zeta < 1.0, 1.0 + np.exp(-math.pi * zeta / root), 1.0)
    out = {
        "step_dynamic_factor": factor,
        "step_peak_time": np.where(zeta < 1.0, math.pi / (beta * root), np.nan),
        "envelope_at_period": 1.0 + np.exp(-zeta * beta * s.period),
        "envelope_at_1_5_period": 1.0 + np.exp(-zeta * beta * (1.5 * s.period)),
        "undamped_dynamic_factor": 2.0,
    }
    if torque is not None:
        out |= {
            "static_twist": torque / s.stiffness,
            "peak_twist": factor * torque / s.stiffness,
            "peak_torque": factor * torque,
        }
    return out


# ------------------------------------------------------------------------- charts

#: Points of the response curve over λ (λ = 1, the resonance and the case's λ added).
CHART_POINTS = 300
#: An undamped resonance is clipped at this many times the static twist M/β².
CHART_CLIP = 100.0
#: A logarithmic y axis when the positive values span more than this factor.
CHART_DECADE = 100.0
#: Step response: samples per undamped period τ (at most STEP_MAX_POINTS of them),
#: and a fine grid over its first 8·τ whatever the horizon.
STEP_SAMPLES_PER_PERIOD = 64
STEP_MAX_POINTS = 4000
#: At most this many points of a Duhamel response are drawn; beyond, each of half as
#: many buckets keeps its lowest and highest sample (a fast oscillation stays a band).
CHART_MAX_POINTS = 8000


def charts(result: Result) -> list[Chart]:
    """``--plot``, in the report's order: with [step], the dynamic factor φ/φ_st of a
    suddenly applied torque against t from the closed form (:func:`sdof.step_response`,
    any damping) over :func:`step_chart_horizon`, the lecture's envelope 1 ± e^(-pt/2)
    when under-damped (through the peaks, not a bound), the first peak and the
    envelope at τ and 1.5·τ as the report gives them; with [harmonic], the steady twist
    amplitude (8.27)-(8.28) against λ = ω/β from :func:`harmonic_numbers` on a numpy
    grid, the case's point, the resonance (8.31)-(8.32) and the λ > 1.5 advice (an
    undamped resonance clipped at :data:`CHART_CLIP`·M/β²); per pulse, ramp and table,
    φ/φ_st against t from the exact Duhamel response over the peak search's horizon,
    the torque M(t)/M_max and the reported peak. At an undamped resonance (no answer)
    only the response curve, the case's λ marked unbounded."""
    case, s = result.case, result.scene
    if result.status != "ok":
        return [] if case.harmonic is None else [_harmonic_chart(case.harmonic, s, False)]
    out: list[Chart] = []
    if case.step is not None:
        out.append(_step_chart(s))
    if case.harmonic is not None:
        out.append(_harmonic_chart(case.harmonic, s, True))
    for transient, _, (factor, when) in result.transient_methods:
        out.append(_transient_chart(s, transient, factor, when))
    return out


def _damping_words(s: Scene) -> str:
    if s.p == 0.0:
        return "undamped"
    if s.zeta < 1.0:
        return f"ζ = {s.zeta:.4g}"
    return f"ζ = {s.zeta:.4g}, {'critically damped' if s.zeta == 1.0 else 'over-damped'}"


def step_chart_horizon(s: Scene) -> float:
    """The step chart's end: 4·τ, or 1.25 times the first peak's time when later;
    without overshoot, 6 time constants of the slow decay e^(-β·t/(ζ + √(ζ² - 1)))."""
    zeta = s.zeta
    peak_time = sdof.step_peak_time(s.beta, zeta)
    if peak_time is not None:
        return max(4.0 * s.period, 1.25 * peak_time)
    slow = s.beta / (zeta + math.sqrt(zeta * zeta - 1.0))
    return max(4.0 * s.period, 6.0 / slow)


def _step_chart(s: Scene) -> Chart:
    import numpy as np

    from mdcalc.plot import Chart, Mark, Series

    zeta, beta, tau = s.zeta, s.beta, s.period
    horizon = step_chart_horizon(s)
    count = min(STEP_MAX_POINTS, math.ceil(STEP_SAMPLES_PER_PERIOD * horizon / tau) + 1)
    peak_time = sdof.step_peak_time(beta, zeta)
    fine = np.linspace(0.0, min(horizon, 8.0 * tau), 8 * STEP_SAMPLES_PER_PERIOD + 1)
    extra = [] if peak_time is None else [peak_time]
    times = np.unique(np.concatenate([np.linspace(0.0, horizon, count), fine, extra]))
    x = times.tolist()
    series = [
        Series(
            "φ/φ_st = 1 - e^(-pt/2)·(cos β₁t + p/(2β₁)·sin β₁t)"
            if zeta < 1.0
            else "φ/φ_st, closed form (no overshoot)",
            x,
            [sdof.step_response(t, beta, zeta) for t in x],
        )
    ]
    if zeta < 1.0:
        decay = np.exp(-zeta * beta * times)
        # one outline, the upper edge out and the lower edge back: one colour, one entry
        outline = [*(1.0 + decay).tolist(), *(1.0 - decay)[::-1].tolist()]
        series.append(
            Series(
                "envelope 1 ± e^(-pt/2), through the peaks",
                [*x, *x[::-1]],
                outline,
                "dashed",
            )
        )
        at = [tau, 1.5 * tau]
        series.append(
            Series(
                "envelope at τ, 1.5·τ (report)",
                at,
                [sdof.step_envelope(t, beta, zeta) for t in at],
                "points",
            )
        )
    if peak_time is not None:
        factor = sdof.step_peak(zeta)
        series.append(
            Series(
                f"first peak {factor:.5g} at π/β₁ = {peak_time:.4g} s (report)",
                [peak_time],
                [factor],
                "points",
            )
        )
    words = _damping_words(s)
    if peak_time is None:
        words += ": factor 1"
    return Chart(
        f"Suddenly applied torque (8.15)-(8.16), φ/φ_st against t ({words})",
        "t [s]",
        "φ/φ_st, φ_st = M₀/c [-]",
        series,
        [Mark("y", 1.0, "static, φ/φ_st = 1")],
    )


def _harmonic_chart(h: Harmonic, s: Scene, ok: bool) -> Chart:
    import dataclasses

    import numpy as np

    from mdcalc.plot import Chart, Mark, Series

    lam = h.omega / s.beta
    gamma = s.p / s.beta
    resonant = s.p > 0.0 and gamma * gamma < 2.0
    x_log = not 0.1 <= lam <= 8.0
    if x_log:
        grid = np.geomspace(min(0.05, lam / 3.0), max(3.0, 3.0 * lam), CHART_POINTS)
    else:
        grid = np.linspace(0.0, max(3.0, 1.25 * lam), CHART_POINTS)
    with np.errstate(all="ignore"):  # (8.21), also at an undamped resonance
        m = float(harmonic_numbers(h, dataclasses.replace(s, xp=np))["combined_amplitude"])
    ratio, peak = resonance(m, s) if resonant else (1.0, math.inf)
    lams = np.unique(np.concatenate([grid, [1.0, lam, ratio]]))
    omega: Any = lams * s.beta
    omega[lams == lam] = h.omega  # the case's own point, to the last digit
    swept = h.model_copy(update={"speed": omega, "speed_rpm": None})
    with np.errstate(all="ignore"):
        twist = harmonic_numbers(swept, dataclasses.replace(s, xp=np))["steady_twist"]
    static = m / s.beta**2  # the twist at λ = 0, M/β²
    own = [float(harmonic_numbers(h, s)["steady_twist"])] if ok else []
    ceiling = max([CHART_CLIP * static, *own, *([float(peak)] if resonant else [])])
    curve = np.where(np.isfinite(twist), np.minimum(twist, ceiling), ceiling)
    x = lams.tolist()
    series = [Series("φ_max(λ) = M/√((β² - ω²)² + p²ω²) (8.27)", x, curve.tolist())]
    marks = [Mark("y", static, f"static twist M/β² = {static:.4g} rad")]
    if resonant:
        series.append(
            Series(
                f"resonance peak {float(peak):.4g} rad, M/(β²γ√(1 - γ²/4))",
                [float(ratio)],
                [float(peak)],
                "points",
            )
        )
        marks.append(Mark("x", float(ratio), f"resonance λ = √(1 - γ²/2) = {float(ratio):.4g}"))
    elif s.p == 0.0:
        marks.append(Mark("x", 1.0, "resonance λ = 1 (undamped: unbounded)"))
    if ok:
        series.append(
            Series(f"this case: λ = {lam:.4g}, φ_max = {own[0]:.4g} rad", [lam], own, "points")
        )
    else:
        marks.append(Mark("x", lam, f"this case: λ = {lam:.4g}, unbounded"))
    marks.append(Mark("x", 1.5, "advice: λ > 1.5"))
    words = f"undamped, clipped at {CHART_CLIP:g}·M/β²" if s.p == 0.0 else f"γ = p/β = {gamma:.4g}"
    y_log = float(curve.min()) > 0.0 and float(curve.max()) > CHART_DECADE * float(curve.min())
    return Chart(
        f"Steady twist (8.27) against λ = ω/β (β = {s.beta:.4g} rad/s; {words})",
        "frequency ratio λ = ω/β [-]",
        "twist amplitude φ_max [rad]",
        series,
        marks,
        x_log=x_log,
        y_log=y_log,
    )


def _transient_chart(s: Scene, transient: Transient, factor: float, when: float) -> Chart:
    import numpy as np

    from mdcalc.plot import Chart, Mark, Series

    response = duhamel_response(s, transient)
    times = np.asarray(response.times, dtype=float)
    factors = np.asarray(response.displacements, dtype=float)
    nearest = int(np.argmin(np.abs(times - when)))
    peak = factor if factors[nearest] >= 0.0 else -factor
    if times[nearest] != when:  # the peak refined between samples, on the curve
        k = int(np.searchsorted(times, when))
        times, factors = np.insert(times, k, when), np.insert(factors, k, peak)
    times, factors = _thinned(times, factors)
    load_t, load = _load_line(transient)
    static = transient.peak_torque / s.stiffness
    return Chart(
        f"{transient.title} (φ_st = {static:.4g} rad; {_damping_words(s)})",
        "t [s]",
        "φ/φ_st, φ_st = M_max/c [-]",
        [
            Series("φ/φ_st, exact Duhamel response", times.tolist(), factors.tolist()),
            Series("torque M(t)/M_max", load_t, load, "dotted"),
            Series(f"peak {factor:.5g} at t = {when:.4g} s (report)", [when], [peak], "points"),
        ],
        [Mark("y", 1.0, "static, φ/φ_st = 1")],
    )


def _load_line(transient: Transient) -> tuple[list[float], list[float]]:
    """The torque over M_max through its knots, held after the last, cut at the horizon."""
    scale, horizon = transient.peak_torque, transient.horizon
    knots = [(t, m / scale) for t, m in transient.knots]
    inside = [(t, f) for t, f in knots if t <= horizon]
    after = [(t, f) for t, f in knots if t > horizon]
    if after:  # linear up to the next knot, as the response reads it
        (t0, f0), (t1, f1) = inside[-1], after[0]
        inside.append((horizon, f0 + (f1 - f0) * (horizon - t0) / (t1 - t0)))
    elif inside[-1][0] < horizon:
        inside.append((horizon, inside[-1][1]))
    return [t for t, _ in inside], [f for _, f in inside]


def _thinned(times: Any, values: Any) -> tuple[Any, Any]:
    """At most about :data:`CHART_MAX_POINTS` samples (numpy): each bucket's lowest
    and highest, and the ends."""
    import numpy as np

    n = len(times)
    if n <= CHART_MAX_POINTS:
        return times, values
    edges = np.linspace(0, n, CHART_MAX_POINTS // 2 + 1).astype(int)
    keep = {0, n - 1}
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        if b > a:
            keep.add(a + int(np.argmin(values[a:b])))
            keep.add(a + int(np.argmax(values[a:b])))
    index = np.array(sorted(keep))
    return times[index], values[index]


def template() -> dict[str, Any]:
    return {
        "problem": "coupling",
        "title": "Elastic coupling, example 8.1",
        "coupling": {
            "driving_inertia": 10.0,
            "driven_inertia": 4.0,
            "stiffness_nm_per_deg": 52.5,
            "absorption": 0.63,
        },
        "step": {"torque": 500.0},
        "harmonic": {"driving_torque": 200.0, "driven_torque": 0.0, "speed": 60.0},
        "pulse": {"torque": 500.0, "duration": 0.05},
    }
