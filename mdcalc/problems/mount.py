"""``mount``: an engine on elastic mounts shaken by its crank (seed 000 §7.5,
example 9.1, brief §4).

Model (7.60): M·x'' + c_d·x' + c·x = m·r·ω²·(cos ωt + λ·cos 2ωt), the mounts' stiffness
c given or from the static deflection, c = G/f (7.50), so β = √(c/M) = √(g/f); c_d =
2·ζ·√(c·M) when a damping ratio is given. Each harmonic has its steady amplitude
(first harmonic at ω, second at 2ω: resonances at ω = β and ω = β/2; the lecture's
(7.74) prints 2·β for the second). The peak displacement is the largest |x| of the
two-harmonic sum over a revolution, found exactly (its extrema are the roots of a
trigonometric polynomial); the lecture's estimate m·r/M is its high-speed limit
without the second harmonic. All closed forms: no numpy, no scipy.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from typing import Any, Literal

from pydantic import Field, model_validator

from mdcalc.core import sdof
from mdcalc.core.units import STANDARD_GRAVITY, rpm_to_rad_s
from mdcalc.methods import Method, compare
from mdcalc.model import CaseBase, CaseModel, exactly_one
from mdcalc.report import MethodQuantity, MethodsTable, Note, Quantities, Quantity, Report

RAD_S_TO_RPM = 30.0 / math.pi
#: The lecture's rule (after (7.78)): a load is quasi-static while μ ≤ 1.05.
QUASI_STATIC_FACTOR = 1.05

# ------------------------------------------------------------------------ the case


class Engine(CaseModel):
    mass: float | None = Field(default=None, gt=0, description="M, engine mass [kg]")
    weight: float | None = Field(default=None, gt=0, description="G, engine weight [N]")

    @model_validator(mode="after")
    def _one(self) -> Engine:
        exactly_one("engine", mass=self.mass, weight=self.weight)
        return self


class Mounts(CaseModel):
    stiffness: float | None = Field(default=None, gt=0, description="c, total stiffness [N/m]")
    static_deflection: float | None = Field(
        default=None, gt=0, description="f, static deflection under the engine, c = G/f [m]"
    )
    damping_ratio: float | None = Field(
        default=None, ge=0, le=10, description="ζ of the mounts (optional) [-]"
    )

    @model_validator(mode="after")
    def _one(self) -> Mounts:
        exactly_one("mounts", stiffness=self.stiffness, static_deflection=self.static_deflection)
        return self


class Crank(CaseModel):
    piston_mass: float | None = Field(default=None, gt=0, description="m, piston mass [kg]")
    piston_weight: float | None = Field(default=None, gt=0, description="piston weight [N]")
    radius: float = Field(gt=0, description="r, crank radius [m]")
    rod_ratio: float = Field(gt=0, lt=1, description="λ = r/l, crank radius over rod length [-]")
    speed: float | None = Field(default=None, gt=0, description="ω, crank speed [rad/s]")
    speed_rpm: float | None = Field(default=None, gt=0, description="n, crank speed [rpm]")

    @model_validator(mode="after")
    def _one(self) -> Crank:
        exactly_one("crank", piston_mass=self.piston_mass, piston_weight=self.piston_weight)
        exactly_one("crank", speed=self.speed, speed_rpm=self.speed_rpm)
        return self


class Isolation(CaseModel):
    transmissibility: float = Field(
        gt=0, lt=1, description="Target force transmissibility of the first harmonic [-]"
    )


class Case(CaseBase):
    problem: Literal["mount"] = Field(description="Problem name [-]")
    gravity: float = Field(default=STANDARD_GRAVITY, gt=0, description="Gravity g [m/s^2]")
    engine: Engine
    mounts: Mounts
    crank: Crank
    isolation: Isolation | None = None


# ------------------------------------------------------------------------ the scene


@dataclass(frozen=True)
class Scene:
    engine_mass: float  # M [kg]
    piston_mass: float  # m [kg]
    radius: float
    rod_ratio: float
    omega: float  # crank speed [rad/s]
    stiffness: float  # c [N/m]
    zeta: float  # 0 without damping
    g: float

    @property
    def beta(self) -> float:
        """Natural frequency √(c/M) [rad/s]."""
        return math.sqrt(self.stiffness / self.engine_mass)

    @property
    def damping(self) -> float:
        """c_d = 2·ζ·√(c·M) [N·s/m]."""
        return 2.0 * self.zeta * math.sqrt(self.stiffness * self.engine_mass)

    def force(self, order: int) -> float:
        """Amplitude of the harmonic of the given order: m·r·ω² and λ·m·r·ω² [N]."""
        base = self.piston_mass * self.radius * self.omega**2
        return base if order == 1 else base * self.rod_ratio

    def response(self, order: int) -> complex:
        """Complex steady amplitude X of the harmonic, x = Re(X·e^{i·order·ωt}) [m]."""
        w = order * self.omega
        return self.force(order) / complex(
            self.stiffness - self.engine_mass * w * w, self.damping * w
        )

    def transmitted(self, order: int) -> complex:
        """Complex amplitude of the force the mounts pass to the frame [N]."""
        return complex(self.stiffness, self.damping * order * self.omega) * self.response(order)


def scene_of(case: Case) -> Scene:
    g = case.gravity
    engine_mass = case.engine.mass or (case.engine.weight or 0.0) / g
    crank = case.crank
    if case.mounts.stiffness is not None:
        stiffness = case.mounts.stiffness
    else:  # (7.50): c = G/f
        assert case.mounts.static_deflection is not None
        stiffness = engine_mass * g / case.mounts.static_deflection
    return Scene(
        engine_mass=engine_mass,
        piston_mass=crank.piston_mass or (crank.piston_weight or 0.0) / g,
        radius=crank.radius,
        rod_ratio=crank.rod_ratio,
        omega=crank.speed or rpm_to_rad_s(crank.speed_rpm or 0.0),
        stiffness=stiffness,
        zeta=case.mounts.damping_ratio or 0.0,
        g=g,
    )


def peak_of_two_harmonics(first: complex, second: complex) -> tuple[float, float]:
    """max over θ of |Re(X1·e^{iθ} + X2·e^{2iθ})| and the crank angle θ [rad] where
    it occurs. The extrema are where the derivative, a trigonometric polynomial of
    degree 2, vanishes: bracketed on a grid, refined by bisection to round-off."""

    def value(theta: float) -> float:
        return (first * cmath.exp(1j * theta) + second * cmath.exp(2j * theta)).real

    def slope(theta: float) -> float:
        return (1j * first * cmath.exp(1j * theta) + 2j * second * cmath.exp(2j * theta)).real

    n = 64  # a degree-2 polynomial has at most 4 extrema per revolution
    grid = [2.0 * math.pi * k / n for k in range(n + 1)]
    best = (abs(value(0.0)), 0.0)
    for a, b in zip(grid, grid[1:], strict=False):
        sa, sb = slope(a), slope(b)
        if sa == 0.0 or sa * sb < 0.0:
            low, high = a, b
            for _ in range(100):
                middle = 0.5 * (low + high)
                if middle in (low, high):
                    break
                if slope(middle) * sa > 0.0:
                    low = middle
                else:
                    high = middle
            theta = 0.5 * (low + high)
            if abs(value(theta)) > best[0]:
                best = (abs(value(theta)), theta)
    return best


def stiffness_for(scene: Scene, target: float) -> float:
    """Mount stiffness whose first-harmonic transmissibility at ω is ``target``, with
    the same damping ratio: T² = (1 + 4ζ²u)/((1 - u)² + 4ζ²u), u = (ω/β)², a
    quadratic in u. For 0 < T < 1 it is (T² - 1)·(8ζ² + 1) < 0 at u = 2, so its
    larger root lies above 2, on the isolating side."""
    z2, t2 = scene.zeta**2, target**2
    a, b, c = t2, -2.0 * t2 + 4.0 * z2 * t2 - 4.0 * z2, t2 - 1.0
    u = (-b + math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a)
    return scene.engine_mass * scene.omega**2 / u


# ------------------------------------------------------------------------- result


@dataclass
class Result:
    case: Case
    scene: Scene
    methods: MethodsTable | None
    peak: tuple[float, float] = (0.0, 0.0)
    force_peak: tuple[float, float] = (0.0, 0.0)
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


QUANTITIES = [MethodQuantity("peak_displacement", "peak |x|", "m")]


def solve(case: Case) -> Result:
    scene = scene_of(case)
    ratio = scene.omega / scene.beta
    if scene.zeta == 0.0 and ratio in (1.0, 0.5):
        order = 1 if ratio == 1.0 else 2
        speed = scene.beta if order == 1 else scene.beta / 2.0
        return Result(
            case,
            scene,
            None,
            status="no-answer",
            message=(
                f"undamped resonance of the {'first' if order == 1 else 'second'} harmonic: "
                f"the crank speed {scene.omega:.6g} rad/s is exactly "
                f"{'β' if order == 1 else 'β/2'} = {speed:.6g} rad/s, the amplitude is "
                "unbounded; give the mounts a damping_ratio or move the speed"
            ),
        )
    first, second = scene.response(1), scene.response(2)
    mr_over_m = scene.piston_mass * scene.radius / scene.engine_mass
    methods = [
        Method(
            "lecture m·r/M",
            lambda: {"peak_displacement": mr_over_m},
            note="high-speed limit, first harmonic",
        ),
        Method(
            "lecture m·r/M + m·r·λ/(4M)",
            lambda: {"peak_displacement": mr_over_m * (1.0 + scene.rod_ratio / 4.0)},
            note="high-speed limit, both harmonics",
        ),
        Method("first harmonic |A₁|", lambda: {"peak_displacement": abs(first)}),
        Method(
            "|A₁| + |A₂|",
            lambda: {"peak_displacement": abs(first) + abs(second)},
            note="bound: both peaks in phase",
        ),
        Method(
            "exact peak of the two-harmonic sum",
            lambda: {"peak_displacement": peak_of_two_harmonics(first, second)[0]},
            reference=True,
        ),
    ]
    table = compare("Methods: peak displacement over a revolution", "peak", QUANTITIES, methods)
    return Result(
        case,
        scene,
        table,
        peak=peak_of_two_harmonics(first, second),
        force_peak=peak_of_two_harmonics(scene.transmitted(1), scene.transmitted(2)),
    )


# ------------------------------------------------------------------------- report


def report(result: Result) -> Report:
    case, s = result.case, result.scene
    title = case.title or "Engine on elastic mounts"
    beta = s.beta
    ratio = s.omega / beta
    sections: list[Any] = [
        Quantities(
            "Scene",
            [
                Quantity("engine_mass", "Engine mass M", s.engine_mass, "kg"),
                Quantity("piston_mass", "Piston mass m", s.piston_mass, "kg"),
                Quantity("crank_radius", "Crank radius r", s.radius, "m"),
                Quantity("rod_ratio", "λ = r/l", s.rod_ratio, ""),
                Quantity("crank_speed", "Crank speed ω", s.omega, "rad/s"),
                Quantity("crank_speed_rpm", "Crank speed", s.omega * RAD_S_TO_RPM, "rpm"),
                Quantity("stiffness", "Mount stiffness c", s.stiffness, "N/m"),
                Quantity(
                    "static_deflection",
                    "Static deflection f = M·g/c",
                    s.engine_mass * s.g / s.stiffness,
                    "m",
                ),
            ],
        ),
        Quantities(
            "Natural frequency and resonances",
            [
                Quantity("natural_frequency", "β = √(c/M) = √(g/f)", beta, "rad/s"),
                Quantity("natural_frequency_hz", "β/2π", beta / (2.0 * math.pi), "Hz"),
                Quantity(
                    "resonant_speed_1",
                    "Resonance of the 1st harmonic, ω = β",
                    beta,
                    "rad/s",
                    f"{beta * RAD_S_TO_RPM:.5g} rpm",
                ),
                Quantity(
                    "resonant_speed_2",
                    "Resonance of the 2nd harmonic, ω = β/2",
                    beta / 2.0,
                    "rad/s",
                    f"{beta / 2.0 * RAD_S_TO_RPM:.5g} rpm; (7.74) prints 2·β = {2 * beta:.4g}",
                ),
                Quantity("frequency_ratio", "ω/β", ratio, ""),
            ],
        ),
    ]
    notes: list[Note] = []
    if result.status != "ok":
        return Report("mount", title, sections, notes, result.status, result.message)

    first, second = s.response(1), s.response(2)
    harmonics = [
        Quantity("force_1", "1st harmonic force m·r·ω²", s.force(1), "N"),
        Quantity("force_2", "2nd harmonic force λ·m·r·ω²", s.force(2), "N"),
        Quantity("amplitude_1", "|A₁| = m·r·ω²/|c - M·ω²|", abs(first), "m", _phase_note(first)),
        Quantity(
            "amplitude_2", "|A₂| = λ·m·r·ω²/|c - 4·M·ω²|", abs(second), "m", _phase_note(second)
        ),
        Quantity(
            "peak_displacement",
            "Peak |x| over a revolution",
            result.peak[0],
            "m",
            f"{result.peak[0] * 1e3:.4g} mm at crank angle "
            f"{math.degrees(result.peak[1]) % 360:.1f}°",
        ),
    ]
    sections.append(Quantities("Forced vibration (steady state)", harmonics))

    if s.zeta == 0.0:
        mu, mu_label = 1.0 / (1.0 - ratio * ratio), "μ = 1/(1 - ω²·M/c)"
    else:
        mu, mu_label = sdof.magnification(ratio, s.zeta), "μ = |A₁|/f_st, damped"
    r_star = math.sqrt(1.0 - 1.0 / QUASI_STATIC_FACTOR)
    quasi = abs(mu) <= QUASI_STATIC_FACTOR and ratio < 1.0
    sections.append(
        Quantities(
            "Dynamic factor (7.78) and the quasi-static rule",
            [
                Quantity("dynamic_factor", mu_label, mu, ""),
                Quantity(
                    "quasi_static_ratio",
                    f"μ ≤ {QUASI_STATIC_FACTOR:g} while ω/β ≤ √(1 - 1/1.05)",
                    r_star,
                    "",
                    "the lecture rounds to 0.218",
                ),
                Quantity("quasi_static_speed", "that is ω ≤", r_star * beta, "rad/s"),
                Quantity(
                    "quasi_static_period_ratio",
                    "or forcing period over free period ≥",
                    1.0 / r_star,
                    "",
                    "the lecture prints 4.59",
                ),
                Quantity("quasi_static", "Load may be taken as static", quasi, ""),
            ],
        )
    )
    if case.mounts.damping_ratio is not None:
        sections.append(_transmission_section(result))
    if case.isolation is not None:
        sections.append(_isolation_section(s, case.isolation.transmissibility))
    assert result.methods is not None
    sections.append(result.methods)
    if 0.7 < ratio < 1.4 or 0.35 < ratio < 0.7:
        notes.append(
            Note("warning", f"ω/β = {ratio:.3g}: the crank runs near a resonance of the mounts")
        )
    return Report("mount", title, sections, notes)


def _phase_note(amplitude: complex) -> str:
    lag = -math.degrees(cmath.phase(amplitude))
    return f"{abs(amplitude) * 1e3:.4g} mm; lags the force by {lag:.4g}°"


def _transmission_section(result: Result) -> Quantities:
    s = result.scene
    items = [
        Quantity("damping_ratio", "Damping ratio ζ", s.zeta, ""),
        Quantity("damping_coefficient", "c_d = 2·ζ·√(c·M)", s.damping, "N·s/m"),
    ]
    for order in (1, 2):
        ratio = order * s.omega / s.beta
        items.append(
            Quantity(
                f"transmissibility_{order}",
                f"Transmissibility, harmonic {order}",
                sdof.transmissibility(ratio, s.zeta),
                "",
            )
        )
        items.append(
            Quantity(
                f"transmitted_force_{order}",
                f"Force on the frame, harmonic {order}",
                abs(s.transmitted(order)),
                "N",
            )
        )
    items.append(
        Quantity(
            "transmitted_force_peak",
            "Peak force on the frame over a revolution",
            result.force_peak[0],
            "N",
            "dynamic part, on top of the weight",
        )
    )
    return Quantities("Mount damping and force transmission", items)


def _isolation_section(s: Scene, target: float) -> Quantities:
    stiffness = stiffness_for(s, target)
    return Quantities(
        f"Isolation target (first harmonic, ζ = {s.zeta:g} kept)",
        [
            Quantity("target_transmissibility", "Target transmissibility", target, ""),
            Quantity("required_stiffness", "Mount stiffness needed c", stiffness, "N/m"),
            Quantity(
                "required_static_deflection",
                "Static deflection with it",
                s.engine_mass * s.g / stiffness,
                "m",
            ),
            Quantity(
                "required_natural_frequency",
                "Natural frequency with it",
                math.sqrt(stiffness / s.engine_mass),
                "rad/s",
            ),
        ],
    )


def template() -> dict[str, Any]:
    return {
        "problem": "mount",
        "title": "Compressor on rubber mounts",
        "engine": {"weight": 10000.0},
        "mounts": {"static_deflection": 0.01, "damping_ratio": 0.05},
        "crank": {"piston_weight": 100.0, "radius": 0.05, "rod_ratio": 0.2, "speed": 150.0},
        "isolation": {"transmissibility": 0.02},
    }
