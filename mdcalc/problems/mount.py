"""``mount``: an engine on elastic mounts shaken by its crank (seed 000 §7.5,
example 9.1, brief §4).

Model (7.60): M·x'' + c_d·x' + c·x = m·r·ω²·(cos ωt + λ·cos 2ωt), the mounts' stiffness
c given or from the static deflection, c = G/f (7.50), so β = √(c/M) = √(g/f); c_d =
2·ζ·√(c·M) when a damping ratio is given. Each harmonic has its steady amplitude
(first harmonic at ω, second at 2ω: resonances at ω = β and ω = β/2; the lecture's
(7.74) prints 2·β for the second). The peak displacement is the largest |x| of the
two-harmonic sum over a revolution, found exactly (its extrema are the roots of a
trigonometric polynomial); the lecture's estimate m·r/M is its high-speed limit
without the second harmonic. All closed forms: no numpy, no scipy (but for the
vectorized sweep kernel and ``charts`` at the end, which import numpy when they run).
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, Literal

from pydantic import Field, model_validator

from mdcalc.core import sdof
from mdcalc.core.units import STANDARD_GRAVITY, rpm_to_rad_s
from mdcalc.methods import Method, compare
from mdcalc.model import CaseBase, CaseModel, exactly_one
from mdcalc.report import MethodQuantity, MethodsTable, Note, Quantities, Quantity, Report

if TYPE_CHECKING:
    from mdcalc.plot import Chart, Series, Style

RAD_S_TO_RPM = 30.0 / math.pi
#: The lecture's rule (after (7.78)): a load is quasi-static while μ ≤ 1.05.
QUASI_STATIC_FACTOR = 1.05
#: ... that is while ω/β ≤ √(1 - 1/1.05).
QUASI_STATIC_RATIO = math.sqrt(1.0 - 1.0 / QUASI_STATIC_FACTOR)

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


def _sqrt(x: Any) -> Any:
    """√x of a float (math), or of a numpy array (the scenes of a sweep)."""
    if isinstance(x, int | float):
        return math.sqrt(x)
    import numpy as np

    return np.sqrt(x)


@dataclass(frozen=True)
class Scene:
    """Floats; or numpy arrays over a grid in :func:`sweep` (the formulas serve both)."""

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
        return _sqrt(self.stiffness / self.engine_mass)

    @property
    def damping(self) -> float:
        """c_d = 2·ζ·√(c·M) [N·s/m]."""
        return 2.0 * self.zeta * _sqrt(self.stiffness * self.engine_mass)

    def force(self, order: int) -> float:
        """Amplitude of the harmonic of the given order: m·r·ω² and λ·m·r·ω² [N]."""
        base = self.piston_mass * self.radius * self.omega**2
        return base if order == 1 else base * self.rod_ratio

    def response(self, order: int) -> complex:
        """Complex steady amplitude X of the harmonic, x = Re(X·e^{i·order·ωt}) [m]."""
        w = order * self.omega
        return self.force(order) / (
            self.stiffness - self.engine_mass * w * w + 1j * (self.damping * w)
        )

    def transmitted(self, order: int) -> complex:
        """Complex amplitude of the force the mounts pass to the frame [N]."""
        return (self.stiffness + 1j * (self.damping * order * self.omega)) * self.response(order)


def scene_of(case: Case) -> Scene:
    return scene_from(_inputs(case))


def scene_from(given: dict[str, Any]) -> Scene:
    """The scene of the case's inputs by the names :data:`SWEEP_KEYS` gives them (None
    where not given); floats, or numpy arrays over a sweep's grid."""
    g = given["g"]

    def either(name: str, other: str, of_other: Any) -> Any:
        return given[name] if given[name] is not None else of_other(given[other])

    engine_mass = either("engine_mass", "engine_weight", lambda weight: weight / g)
    return Scene(
        engine_mass=engine_mass,
        piston_mass=either("piston_mass", "piston_weight", lambda weight: weight / g),
        radius=given["radius"],
        rod_ratio=given["rod_ratio"],
        omega=either("speed", "speed_rpm", rpm_to_rad_s),
        # (7.50): c = G/f
        stiffness=either("stiffness", "static_deflection", lambda f: engine_mass * g / f),
        zeta=given["zeta"] if given["zeta"] is not None else 0.0,
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
    u = (-b + _sqrt(b * b - 4.0 * a * c)) / (2.0 * a)
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
    r_star = QUASI_STATIC_RATIO
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


# ------------------------------------------------------------------------- sweep

#: Keys ``mdcalc sweep`` may vary in the vectorized form, and the scene input each sets.
SWEEP_KEYS = {
    "crank.speed": "speed",
    "crank.speed_rpm": "speed_rpm",
    "mounts.damping_ratio": "zeta",
    "mounts.stiffness": "stiffness",
    "mounts.static_deflection": "static_deflection",
    "engine.mass": "engine_mass",
    "engine.weight": "engine_weight",
    "crank.piston_mass": "piston_mass",
    "crank.piston_weight": "piston_weight",
    "crank.radius": "radius",
    "crank.rod_ratio": "rod_ratio",
    "gravity": "g",
    "isolation.transmissibility": "target",
}
#: Inputs of which a case gives exactly one.
ALTERNATIVES = [
    ("engine_mass", "engine_weight"),
    ("piston_mass", "piston_weight"),
    ("speed", "speed_rpm"),
    ("stiffness", "static_deflection"),
]


def _inputs(case: Case) -> dict[str, Any]:
    """The case's value of every key of :data:`SWEEP_KEYS` by its name; None if not given."""
    given: dict[str, Any] = {}
    for key, name in SWEEP_KEYS.items():
        node: Any = case
        for part in key.split("."):
            node = getattr(node, part, None)
        given[name] = node
    return given


def sweep(case: Case, grid: dict[str, Any]) -> dict[str, Any] | None:
    """Every numeric result over a grid of scenes at once (numpy), by the formulas of
    :func:`solve` and :func:`report`; None for a key it does not know, or where a point
    has no answer (an undamped resonance: point by point says so)."""
    import numpy as np

    if any(key not in SWEEP_KEYS for key in grid):
        return None
    varied = {SWEEP_KEYS[key]: np.asarray(values, dtype=float) for key, values in grid.items()}
    shape = np.broadcast_shapes(*(values.shape for values in varied.values()))
    given: dict[str, Any] = {
        name: None if value is None else np.broadcast_to(value, shape)
        for name, value in (_inputs(case) | varied).items()
    }
    if any(given[a] is not None and given[b] is not None for a, b in ALTERNATIVES):
        return None  # not a valid case (the sweep's plan refuses it)
    s = scene_from(given)
    beta, zeta = s.beta, s.zeta
    ratio = s.omega / beta
    if np.any((zeta == 0.0) & ((ratio == 1.0) | (ratio == 0.5))):
        return None
    with np.errstate(divide="ignore", invalid="ignore"):
        first, second = s.response(1), s.response(2)
        if not (np.all(np.isfinite(first)) and np.all(np.isfinite(second))):
            return None  # c = M·ω² to round-off: point by point says what happens

        def magnification(r: Any) -> Any:  # sdof.magnification
            return 1.0 / np.hypot(1.0 - r * r, 2.0 * zeta * r)

        results = {
            "engine_mass": s.engine_mass,
            "piston_mass": s.piston_mass,
            "crank_radius": s.radius,
            "rod_ratio": s.rod_ratio,
            "crank_speed": s.omega,
            "crank_speed_rpm": s.omega * RAD_S_TO_RPM,
            "stiffness": s.stiffness,
            "static_deflection": s.engine_mass * s.g / s.stiffness,
            "natural_frequency": beta,
            "natural_frequency_hz": beta / (2.0 * math.pi),
            "resonant_speed_1": beta,
            "resonant_speed_2": beta / 2.0,
            "frequency_ratio": ratio,
            "force_1": s.force(1),
            "force_2": s.force(2),
            "amplitude_1": np.abs(first),
            "amplitude_2": np.abs(second),
            "peak_displacement": peak_of_two_harmonics_array(first, second),
            "dynamic_factor": np.where(
                zeta == 0.0, 1.0 / (1.0 - ratio * ratio), magnification(ratio)
            ),
            "quasi_static_ratio": QUASI_STATIC_RATIO,
            "quasi_static_speed": QUASI_STATIC_RATIO * beta,
            "quasi_static_period_ratio": 1.0 / QUASI_STATIC_RATIO,
        }
        if given["zeta"] is not None:  # as in _transmission_section
            forces = s.transmitted(1), s.transmitted(2)
            results |= {
                "damping_ratio": zeta,
                "damping_coefficient": s.damping,
                "transmitted_force_peak": peak_of_two_harmonics_array(*forces),
            }
            for order, force in zip((1, 2), forces, strict=True):
                r = order * s.omega / beta
                transmissibility = np.hypot(1.0, 2.0 * zeta * r) * magnification(r)  # sdof's
                results[f"transmissibility_{order}"] = transmissibility
                results[f"transmitted_force_{order}"] = np.abs(force)
        if given["target"] is not None:  # as in _isolation_section
            stiffness = stiffness_for(s, given["target"])
            results |= {
                "target_transmissibility": given["target"],
                "required_stiffness": stiffness,
                "required_static_deflection": s.engine_mass * s.g / stiffness,
                "required_natural_frequency": np.sqrt(stiffness / s.engine_mass),
            }
    return results


def peak_of_two_harmonics_array(first: Any, second: Any) -> Any:
    """The peak of :func:`peak_of_two_harmonics` over arrays (numpy), without a search.

    With X₁ = A·e^{iα}, X₂ = B·e^{iγ} and ψ = θ + α, the sum is A·cos ψ + B·cos(2ψ + δ),
    δ = γ - 2α: on the unit circle (cos ψ, sin ψ) a quadratic form with eigenvalues ±B
    plus a linear term, f = B·(p² - q²) + P·p + R·q in the form's eigenvectors, where
    P + iR = A·e^{iδ/2}. Its maximum on p² + q² = 1 (a trust-region problem) is at
    p = P/(2ν), q = R/(2(ν + 2B)), ν ≥ 0 the root of P²/ν² + R²/(ν + 2B)² = 4 (ν = 0
    if there is none: the "hard case"); Newton's method on the concave 1/√(...) - 1/2
    climbs to it from below. The maximum of -f is the same with P² and R² swapped.
    f is evaluated at a point of the circle, so it is never above the peak; the search
    finds the same extremum (it is π/2 or more from any other), equal to round-off."""
    import numpy as np

    first, second = np.broadcast_arrays(np.atleast_1d(first), second)
    b = np.abs(second)
    half = np.sqrt(second) * np.conj(first) / np.sqrt(b)  # ±(P + iR)
    p2, r2 = half.real**2, half.imag**2

    def highest(p2: Any, r2: Any) -> Any:  # max of f with these P², R²
        nu = np.fmax(np.sqrt(p2) / 2.0, np.sqrt(r2) / 2.0 - 2.0 * b)  # ν ≤ the root
        todo = np.flatnonzero((p2 > 0.0) & (r2 > 0.0))  # else ν is the root already
        for _ in range(100):
            if todo.size == 0:
                break
            n, m = nu[todo], nu[todo] + 2.0 * b[todo]
            x, y = p2[todo] / n**2, r2[todo] / m**2
            step = np.fmax((x + y) * (np.sqrt(x + y) - 2.0) / (2.0 * (x / n + y / m)), 0.0)
            nu[todo] = n + step
            todo = todo[step > 1e-12 * nu[todo]]
        q = np.sqrt(r2) / (2.0 * (nu + 2.0 * b))
        p = np.sqrt(np.fmax(1.0 - q * q, 0.0))
        return b * (p * p - q * q) + np.sqrt(p2) * p + np.sqrt(r2) * q

    return np.maximum(highest(p2, r2), highest(r2, p2))


# ------------------------------------------------------------------------ charts

#: Points of each curve of ``--plot`` (and the case's ratio, 1/2 and 1 added).
CHART_POINTS = 600
#: An undamped curve is unbounded at its resonance: drawn clipped at this many times
#: its level (amplitude m·r/M, transmissibility 1), or at the case's value if higher.
CHART_CLIP = 100.0
#: A chart's y axis is logarithmic when its values span more than this factor.
CHART_DECADE = 20.0


def charts(result: Result) -> list[Chart]:
    """``--plot``: against the frequency ratio ω/β (β kept, the crank speed varied, so
    the forces m·r·ω² grow with it), the amplitudes |A₁|, |A₂| of :meth:`Scene.response`
    and the peak |x| of their sum (:func:`peak_of_two_harmonics_array`); with a
    damping ratio or an [isolation] target, the transmissibility of both harmonics
    (:meth:`Scene.transmitted`) with the √2 line and the target, met at the ratio of
    :func:`stiffness_for`. The case's point lies on the curves (undamped ones clipped);
    the resonances ω = β and β/2 are marked. Linear in ω/β from 0.05 to 3 (or 1.25
    times the case's ratio), logarithmic when the case lies below 0.1 or above 8."""
    import numpy as np

    from mdcalc.plot import Chart, Mark, Series

    case, s = result.case, result.scene
    ratio = s.omega / s.beta
    target = case.isolation.transmissibility if case.isolation is not None else None
    needed = (
        None if target is None else math.sqrt(s.engine_mass / stiffness_for(s, target)) * s.omega
    )
    ratios, x_log = _chart_ratios([ratio] if needed is None else [ratio, needed])
    omega: Any = ratios * s.beta
    omega[ratios == ratio] = s.omega  # the case's own point, to the last digit
    swept = replace(s, omega=omega)
    ok = result.status == "ok"
    # an undamped resonance is unbounded: the curves are clipped there
    clip = CHART_CLIP if s.zeta == 0.0 else max(CHART_CLIP, 1.0 / s.zeta)

    level = s.piston_mass * s.radius / s.engine_mass  # m·r/M, the high-speed limit
    own = [result.peak[0], abs(s.response(1)), abs(s.response(2))] if ok else []
    ceiling = max([clip * level, *own])
    with np.errstate(all="ignore"):
        first, second = swept.response(1), swept.response(2)
        curves: list[tuple[str, Any, Style]] = [
            ("peak |x|", peak_of_two_harmonics_array(first, second), "line"),
            ("|A₁| (ω)", np.abs(first), "dashed"),
            ("|A₂| (2ω)", np.abs(second), "dotted"),
        ]
    x = ratios.tolist()
    series = [
        Series(label, x, (1e3 * _clipped(values, ceiling)).tolist(), style)
        for label, values, style in curves
    ]
    speed = f"this case: ω = {s.omega:.4g} rad/s = {s.omega * RAD_S_TO_RPM:.4g} rpm"
    marks = [
        Mark("x", 1.0, "resonances ω = β, β/2"),
        Mark("x", 0.5),
        Mark("y", 1e3 * level, "m·r/M (lecture, high speed)"),
    ]
    if ok:
        series.append(Series(speed, [ratio] * 3, [1e3 * a for a in own], "points"))
    else:
        marks.append(Mark("x", ratio, f"{speed}: unbounded"))
    damping = "undamped, clipped at resonance" if s.zeta == 0.0 else f"ζ = {s.zeta:g}"
    out = [
        Chart(
            f"Engine amplitude against ω/β (β = {s.beta:.4g} rad/s; {damping})",
            "frequency ratio ω/β [-]",
            "amplitude [mm]",
            series,
            marks,
            x_log=x_log,
            y_log=_spread(series),
        )
    ]
    if case.mounts.damping_ratio is None and target is None:
        return out

    clip_t = max([clip, *(sdof.transmissibility(k * ratio, s.zeta) for k in (1, 2) if ok)])
    with np.errstate(all="ignore"):
        passed = [np.abs(swept.transmitted(k)) / swept.force(k) for k in (1, 2)]
    series = [
        Series("1st harmonic, T(ω/β)", x, _clipped(passed[0], clip_t).tolist()),
        Series("2nd harmonic, T(2ω/β)", x, _clipped(passed[1], clip_t).tolist(), "dashed"),
    ]
    if ok:
        own_t = [sdof.transmissibility(k * ratio, s.zeta) for k in (1, 2)]
        series.append(Series(f"this case: ω/β = {ratio:.4g}", [ratio] * 2, own_t, "points"))
    marks = [
        Mark("x", math.sqrt(2.0), "T = 1 at any ζ: ω/β = √2, √2/2"),
        Mark("x", math.sqrt(0.5)),
    ]
    if target is not None and needed is not None:
        stiffness = stiffness_for(s, target)
        series.append(
            Series(
                f"target met with c = {stiffness:.4g} N/m (ω/β = {needed:.4g})",
                [needed],
                [target],
                "points",
            )
        )
        marks.append(Mark("y", target, f"target T = {target:g} (1st harmonic)"))
    out.append(
        Chart(
            f"Force transmissibility of the mounts against ω/β "
            f"({'undamped, clipped at resonance' if s.zeta == 0.0 else f'ζ = {s.zeta:g}'})",
            "frequency ratio ω/β [-]",
            "transmissibility T = |F_frame|/|F| [-]",
            series,
            marks,
            x_log=x_log,
            y_log=_spread(series),
        )
    )
    return out


def _chart_ratios(points: list[float]) -> tuple[Any, bool]:
    """The ω/β grid of :func:`charts` (numpy) holding ``points``, 1/2 and 1, and
    whether it is logarithmic."""
    import numpy as np

    low, high = min(points), max(points)
    if low >= 0.1 and high <= 8.0:
        grid, log = np.linspace(0.05, max(3.0, 1.25 * high), CHART_POINTS), False
    else:
        grid, log = np.geomspace(min(0.05, low / 3.0), max(3.0, 3.0 * high), CHART_POINTS), True
    return np.unique(np.concatenate([grid, [0.5, 1.0, *points]])), log


def _spread(series: list[Series]) -> bool:
    """Whether the series' values, all positive, span more than :data:`CHART_DECADE`."""
    values = [y for s in series for y in s.y]
    return min(values) > 0.0 and max(values) > CHART_DECADE * min(values)


def _clipped(values: Any, ceiling: float) -> Any:
    """``values`` (numpy) at most ``ceiling``; an unbounded one (inf, nan) at it."""
    import numpy as np

    return np.where(np.isfinite(values), np.minimum(values, ceiling), ceiling)


def template() -> dict[str, Any]:
    return {
        "problem": "mount",
        "title": "Compressor on rubber mounts",
        "engine": {"weight": 10000.0},
        "mounts": {"static_deflection": 0.01, "damping_ratio": 0.05},
        "crank": {"piston_weight": 100.0, "radius": 0.05, "rod_ratio": 0.2, "speed": 150.0},
        "isolation": {"transmissibility": 0.02},
    }
