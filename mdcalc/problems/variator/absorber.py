"""7a: the two-disk anti-resonance absorber (8.36)-(8.39): amplitudes by the seed's
formulas and by the chain, the tuning, the depth of the minimum with damping."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mdcalc.core.chain import Chain, harmonic_response
from mdcalc.methods import NotApplicable
from mdcalc.problems.variator.case import Absorber


@dataclass(frozen=True)
class AbsorberScene:
    j1: float
    c: float
    j2: float
    cg: float
    bg: float
    m0: float
    omega: float
    tuned: bool  # c_g = J₂·ω² (A₁ is exactly 0 without damping)

    def amplitudes(self, omega: float) -> tuple[complex, complex]:
        """Complex A₁, A₂ [rad] at ω: (8.38) with k_g = c_g + iω·b_g."""
        w2 = omega * omega
        kg = complex(self.cg, omega * self.bg)
        numerator = kg - self.j2 * w2
        # (c + k_g - J₁ω²)(k_g - J₂ω²) - k_g², written without the k_g² - k_g² cancellation
        det = (self.c - self.j1 * w2) * (kg - self.j2 * w2) - kg * self.j2 * w2
        if det == 0:
            raise ZeroDivisionError
        return self.m0 * numerator / det, self.m0 * kg / det

    def determinant_is_zero(self, omega: float) -> bool:
        """Δ = 0 to round-off (undamped resonance of the two-disk system)."""
        if self.bg != 0.0:
            return False
        w2 = omega * omega
        first = (self.c - self.j1 * w2) * (self.cg - self.j2 * w2)
        second = self.cg * self.j2 * w2
        return abs(first - second) <= 1e-12 * max(abs(first), second)

    def untuned(self, omega: float) -> float | None:
        """|A| of J₁ without the absorber, M₀/|c - J₁ω²| (None: resonance)."""
        gap = self.c - self.j1 * omega * omega
        if abs(gap) <= 1e-12 * self.c:
            return None
        return self.m0 / abs(gap)

    def resonances(self) -> tuple[float, float]:
        """Roots of Δ = 0: ω⁴ - (a + b + d)·ω² + a·d = 0, a = c/J₁, b = c_g/J₁,
        d = c_g/J₂ [rad/s] (discriminant (a + b - d)² + 4bd > 0)."""
        a, b, d = self.c / self.j1, self.cg / self.j1, self.cg / self.j2
        high = 0.5 * ((a + b + d) + math.sqrt((a + b - d) ** 2 + 4.0 * b * d))
        return math.sqrt(a * d / high), math.sqrt(high)

    def band(self) -> tuple[float, float]:
        """Where the undamped absorber lowers |A₁| below M₀/|c - J₁ω²|:
        (d - ω²)(a - ω²) < ω²·b/2, between the roots of ω⁴ - (a + d + b/2)ω² + ad."""
        a, b, d = self.c / self.j1, self.cg / self.j1, self.cg / self.j2
        s = a + d + 0.5 * b
        high = 0.5 * (s + math.sqrt((a - d) ** 2 + b * (a + d) + 0.25 * b * b))
        return math.sqrt(a * d / high), math.sqrt(high)


def absorber_scene(a: Absorber) -> AbsorberScene:
    w2 = a.frequency * a.frequency
    if a.absorber_stiffness is not None:
        cg, tuned = (
            a.absorber_stiffness,
            abs(a.absorber_stiffness - a.absorber_inertia * w2) <= (4e-16 * a.absorber_stiffness),
        )
    else:
        tune = a.tuning_frequency if a.tuning_frequency is not None else a.frequency
        # J₂·(ω·ω): the same product amplitudes() forms, so tuned means A₁ = 0 exactly
        cg, tuned = a.absorber_inertia * (tune * tune), tune == a.frequency
    return AbsorberScene(
        a.inertia,
        a.stiffness,
        a.absorber_inertia,
        cg,
        a.absorber_damping,
        a.torque_amplitude,
        a.frequency,
        tuned,
    )


def seed_amplitudes(s: AbsorberScene) -> dict[str, float]:
    """(8.38) as printed: A₁ = M₀(c_g/J₂ - ω²)/(J₁Δ), A₂ = M₀(c_g/J₂)/(J₁Δ)."""
    if s.bg != 0.0:
        raise NotApplicable("(8.38) has no damping")
    w2 = s.omega * s.omega
    d = s.cg / s.j2
    delta = d * (s.c / s.j1 - w2) - w2 * ((s.c + s.cg) / s.j1 - w2)
    top = d - w2
    terms = (abs(d * (s.c / s.j1 - w2)), abs(w2 * ((s.c + s.cg) / s.j1 - w2)))
    if abs(delta) <= 1e-8 * max(terms):
        raise NotApplicable("Δ as printed loses its digits to cancellation at these scales")
    return {"a1": abs(s.m0 * top / (s.j1 * delta)), "a2": abs(s.m0 * d / (s.j1 * delta))}


def chain_amplitudes(s: AbsorberScene) -> dict[str, float]:
    """The shared chain core: J₁ - c_g - J₂ with c from J₁ to the ground."""
    try:
        angles, _ = harmonic_response(
            Chain((s.j1, s.j2), (s.cg,)),
            s.omega,
            [s.m0, 0.0],
            spring_damping=[s.bg],
            ground_stiffness=[s.c, 0.0],
        )
    except ArithmeticError as reason:
        raise NotApplicable(f"the 2×2 system is too ill-conditioned ({reason})") from None
    return {"a1": float(abs(angles[0])), "a2": float(abs(angles[1]))}


def absorber_minimum(s: AbsorberScene) -> tuple[float, float] | None:
    """Smallest |A₁| between the two resonances and where [rad, rad/s]: a log grid,
    then golden section; None when there is no minimum inside (heavy damping)."""
    low, high = s.resonances()

    def value(omega: float) -> float:
        return abs(s.amplitudes(omega)[0])

    grid = np.geomspace(low, high, 2001)[1:-1]
    values = [value(float(w)) for w in grid]
    k = int(np.argmin(values))
    if k in (0, len(grid) - 1):  # |A₁| falls all the way to a resonance: no notch
        return None
    a, b = float(grid[k - 1]), float(grid[k + 1])
    ratio = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(200):
        x1, x2 = b - ratio * (b - a), a + ratio * (b - a)
        if value(x1) < value(x2):
            b = x2
        else:
            a = x1
        if b - a <= 1e-15 * b:
            break
    where = 0.5 * (a + b)
    return value(where), where
