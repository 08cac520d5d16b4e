"""7a: the two-disk anti-resonance absorber (8.36)-(8.39): amplitudes by the seed's
formulas and by the chain, the tuning, the depth of the minimum with damping."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from mdcalc.core.chain import Chain, harmonic_response
from mdcalc.core.xp import FLOATS, of
from mdcalc.methods import NotApplicable
from mdcalc.problems.variator.case import Absorber


@dataclass(frozen=True)
class AbsorberScene:
    """The two-disk absorber. Its numbers are floats for one scene, or numpy arrays
    over a block of scenes (a study's samples): every method runs on either."""

    j1: Any
    c: Any
    j2: Any
    cg: Any
    bg: Any
    m0: Any
    omega: Any
    tuned: Any  # c_g = J₂·ω² (A₁ is exactly 0 without damping)

    def amplitudes(self, omega: Any) -> tuple[Any, Any]:
        """Complex A₁, A₂ [rad] at ω: (8.38) with k_g = c_g + iω·b_g."""
        w2 = omega * omega
        kg = self.cg + 1j * (omega * self.bg)
        numerator = kg - self.j2 * w2
        # (c + k_g - J₁ω²)(k_g - J₂ω²) - k_g², written without the k_g² - k_g² cancellation
        det = (self.c - self.j1 * w2) * (kg - self.j2 * w2) - kg * self.j2 * w2
        if np.ndim(det) == 0 and det == 0:
            raise ZeroDivisionError
        with np.errstate(all="ignore"):
            return self.m0 * numerator / det, self.m0 * kg / det

    def determinant_is_zero(self, omega: Any) -> Any:
        """Δ = 0 to round-off (undamped resonance of the two-disk system)."""
        w2 = omega * omega
        first = (self.c - self.j1 * w2) * (self.cg - self.j2 * w2)
        second = self.cg * self.j2 * w2
        xp = of(first, second, self.bg)
        flat = abs(first - second) <= 1e-12 * xp.maximum(abs(first), second)
        return (self.bg == 0.0) & flat if xp is not FLOATS else self.bg == 0.0 and flat

    def untuned(self, omega: Any) -> Any:
        """|A| of J₁ without the absorber, M₀/|c - J₁ω²| (None, or NaN over arrays:
        resonance)."""
        gap = self.c - self.j1 * omega * omega
        xp = of(gap, self.c)
        return xp.where(abs(gap) <= 1e-12 * self.c, lambda: xp.missing, lambda: self.m0 / abs(gap))

    def resonances(self) -> tuple[Any, Any]:
        """Roots of Δ = 0: ω⁴ - (a + b + d)·ω² + a·d = 0, a = c/J₁, b = c_g/J₁,
        d = c_g/J₂ [rad/s] (discriminant (a + b - d)² + 4bd > 0)."""
        a, b, d = self.c / self.j1, self.cg / self.j1, self.cg / self.j2
        xp = of(a, b, d)
        high = 0.5 * ((a + b + d) + xp.sqrt((a + b - d) ** 2 + 4.0 * b * d))
        return xp.sqrt(a * d / high), xp.sqrt(high)

    def band(self) -> tuple[Any, Any]:
        """Where the undamped absorber lowers |A₁| below M₀/|c - J₁ω²|:
        (d - ω²)(a - ω²) < ω²·b/2, between the roots of ω⁴ - (a + d + b/2)ω² + ad."""
        a, b, d = self.c / self.j1, self.cg / self.j1, self.cg / self.j2
        xp = of(a, b, d)
        s = a + d + 0.5 * b
        high = 0.5 * (s + xp.sqrt((a - d) ** 2 + b * (a + d) + 0.25 * b * b))
        return xp.sqrt(a * d / high), xp.sqrt(high)


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
    then golden section; None when there is no minimum inside (heavy damping). One
    scene as a block of one (:func:`absorber_minima`)."""
    depth, where = absorber_minima(s, 1)
    return None if math.isnan(depth[0]) else (float(depth[0]), float(where[0]))


#: Scenes whose grids of |A₁| are evaluated at once (2001 complex values each).
MINIMUM_CHUNK = 512


def absorber_minima(s: AbsorberScene, size: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`absorber_minimum` of a block of ``size`` scenes: the depths and their
    frequencies, NaN where there is no minimum inside."""

    def whole(value: Any) -> np.ndarray:
        return np.broadcast_to(np.asarray(value, dtype=float), (size,))

    j1, c, j2, cg, bg, m0 = (whole(v) for v in (s.j1, s.c, s.j2, s.cg, s.bg, s.m0))
    depth, where = np.full(size, np.nan), np.full(size, np.nan)
    for first in range(0, size, MINIMUM_CHUNK):
        part = slice(first, first + MINIMUM_CHUNK)
        scene = AbsorberScene(j1[part], c[part], j2[part], cg[part], bg[part], m0[part], 0.0, False)
        depth[part], where[part] = _minima(scene)
    return depth, where


def _minima(s: AbsorberScene) -> tuple[np.ndarray, np.ndarray]:
    low, high = s.resonances()

    def value(omega: np.ndarray) -> np.ndarray:
        return np.abs(s.amplitudes(omega)[0])

    grid = np.geomspace(low, high, 2001)[1:-1]  # (1999, B)
    k = np.argmin(value(grid), axis=0)
    inside = (k > 0) & (k < len(grid) - 1)  # else |A₁| falls all the way to a resonance
    column = np.arange(len(k))
    a = grid[np.clip(k - 1, 0, len(grid) - 1), column]
    b = grid[np.clip(k + 1, 0, len(grid) - 1), column]
    ratio = (math.sqrt(5.0) - 1.0) / 2.0
    running = inside.copy()
    for _ in range(200):
        x1, x2 = b - ratio * (b - a), a + ratio * (b - a)
        left = value(x1) < value(x2)
        b = np.where(running & left, x2, b)
        a = np.where(running & ~left, x1, a)
        running &= ~(b - a <= 1e-15 * b)
        if not running.any():
            break
    at = 0.5 * (a + b)
    return np.where(inside, value(at), np.nan), np.where(inside, at, np.nan)


def absorber_values(a: Absorber, size: int) -> tuple[dict[str, Any], Any] | None:
    """Every number of the absorber's sections over a block of ``size`` scenes, by
    result key, and the samples at an undamped resonance of the two-disk system (no
    answer). None when some samples are damped and some not (their sections
    differ: solved point by point)."""
    s = absorber_scene(a)
    declined = np.broadcast_to(s.determinant_is_zero(s.omega), (size,))
    low, high = s.resonances()
    try:
        a1, a2 = s.amplitudes(s.omega)
    except ZeroDivisionError:  # Δ shared by the rows, and 0: every row declined
        a1 = a2 = np.full(size, np.nan)
    static = s.m0 / s.c
    values: dict[str, Any] = {
        "absorber_stiffness": s.cg,
        "absorber_tuning": np.sqrt(s.cg / s.j2),
        "absorber_partial": np.sqrt(s.c / s.j1),
        "absorber_resonance_low": low,
        "absorber_resonance_high": high,
        "absorber_a1": np.abs(a1),
        "absorber_a2": np.abs(a2),
        "absorber_moment": np.abs((s.cg + 1j * (s.omega * s.bg)) * (a2 - a1)),
        "absorber_static": static,
        "absorber_untuned": s.untuned(s.omega),
    }
    undamped = np.broadcast_to(np.asarray(s.bg) == 0.0, (size,))
    if undamped.all():
        values["absorber_band_low"], values["absorber_band_high"] = s.band()
    elif not undamped.any():
        depth, where = absorber_minima(s, size)
        values |= {
            "absorber_minimum": depth,
            "absorber_minimum_frequency": where,
            "absorber_minimum_depth": depth / static,
        }
    else:
        return None
    return values, declined
