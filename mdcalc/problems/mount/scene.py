"""The scene: the case reduced to SI numbers, the harmonic responses and the peak
of their sum; floats, or numpy arrays over a sweep grid."""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from typing import Any

from mdcalc.core import sdof
from mdcalc.core.units import rpm_to_rad_s
from mdcalc.core.xp import of
from mdcalc.problems.mount.case import Case

RAD_S_TO_RPM = 30.0 / math.pi

#: The lecture's rule (after (7.78)): a load is quasi-static while μ ≤ 1.05.
QUASI_STATIC_FACTOR = 1.05

#: ... that is while ω/β ≤ √(1 - 1/1.05).
QUASI_STATIC_RATIO = math.sqrt(1.0 - 1.0 / QUASI_STATIC_FACTOR)


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
        return of(self.stiffness, self.engine_mass).sqrt(self.stiffness / self.engine_mass)

    @property
    def damping(self) -> float:
        """c_d = 2·ζ·√(c·M) [N·s/m]."""
        cm = self.stiffness * self.engine_mass
        return 2.0 * self.zeta * of(cm).sqrt(cm)

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


def dynamic_factor(ratio: Any, zeta: Any) -> Any:
    """(7.78): μ = A₁/f_st of the first harmonic at r = ω/β; undamped the lecture's
    signed 1/(1 - r²), damped the magnification |A₁|/f_st."""
    return of(ratio, zeta).where(
        zeta == 0.0,
        lambda: 1.0 / (1.0 - ratio * ratio),
        lambda: sdof.magnification(ratio, zeta),
    )


def stiffness_for(scene: Scene, target: float) -> float:
    """Mount stiffness whose first-harmonic transmissibility at ω is ``target``, with
    the same damping ratio: T² = (1 + 4ζ²u)/((1 - u)² + 4ζ²u), u = (ω/β)², a
    quadratic in u. For 0 < T < 1 it is (T² - 1)·(8ζ² + 1) < 0 at u = 2, so its
    larger root lies above 2, on the isolating side."""
    z2, t2 = scene.zeta**2, target**2
    a, b, c = t2, -2.0 * t2 + 4.0 * z2 * t2 - 4.0 * z2, t2 - 1.0
    discriminant = b * b - 4.0 * a * c
    u = (-b + of(discriminant).sqrt(discriminant)) / (2.0 * a)
    return scene.engine_mass * scene.omega**2 / u


# ---------------------------------------------------- the report's numbers, by key
# One formula each, for the report of one scene and the sweep kernel's grid alike.


def scene_numbers(s: Scene) -> dict[str, Any]:
    """The scene, its natural frequency and resonances."""
    beta = s.beta
    return {
        "engine_mass": s.engine_mass,
        "piston_mass": s.piston_mass,
        "crank_radius": s.radius,
        "rod_ratio": s.rod_ratio,
        "crank_speed": s.omega,
        "crank_speed_rpm": s.omega * RAD_S_TO_RPM,
        "stiffness": s.stiffness,
        "static_deflection": s.engine_mass * s.g / s.stiffness,  # f = M·g/c
        "natural_frequency": beta,
        "natural_frequency_hz": beta / (2.0 * math.pi),
        "resonant_speed_1": beta,
        "resonant_speed_2": beta / 2.0,
        "frequency_ratio": s.omega / beta,
    }


def response_numbers(s: Scene) -> dict[str, Any]:
    """The harmonics' forces and steady amplitudes, the dynamic factor (7.78) and the
    quasi-static rule (no answer at an undamped resonance: not called there)."""
    first, second = s.response(1), s.response(2)
    xp = of(first, second)
    return {
        "force_1": s.force(1),
        "force_2": s.force(2),
        "amplitude_1": xp.abs(first),
        "amplitude_2": xp.abs(second),
        "dynamic_factor": dynamic_factor(s.omega / s.beta, s.zeta),
        "quasi_static_ratio": QUASI_STATIC_RATIO,
        "quasi_static_speed": QUASI_STATIC_RATIO * s.beta,
        "quasi_static_period_ratio": 1.0 / QUASI_STATIC_RATIO,
    }


def transmission_numbers(s: Scene) -> dict[str, Any]:
    """With the mounts' damping: the force each harmonic passes to the frame."""
    numbers = {"damping_ratio": s.zeta, "damping_coefficient": s.damping}
    for order in (1, 2):
        transmitted = s.transmitted(order)
        ratio = order * s.omega / s.beta
        numbers[f"transmissibility_{order}"] = sdof.transmissibility(ratio, s.zeta)
        numbers[f"transmitted_force_{order}"] = of(transmitted).abs(transmitted)
    return numbers


def isolation_numbers(s: Scene, target: Any) -> dict[str, Any]:
    """The mount stiffness that gives the target transmissibility, and what follows."""
    stiffness = stiffness_for(s, target)
    return {
        "target_transmissibility": target,
        "required_stiffness": stiffness,
        "required_static_deflection": s.engine_mass * s.g / stiffness,
        "required_natural_frequency": of(stiffness, s.engine_mass).sqrt(stiffness / s.engine_mass),
    }


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


def _inputs(case: Case) -> dict[str, Any]:
    """The case's value of every key of :data:`SWEEP_KEYS` by its name; None if not given."""
    given: dict[str, Any] = {}
    for key, name in SWEEP_KEYS.items():
        node: Any = case
        for part in key.split("."):
            node = getattr(node, part, None)
        given[name] = node
    return given


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
