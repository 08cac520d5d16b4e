"""The system of :mod:`mdcalc.core.periodic`: M·x'' + C·x' + K·x = F + s·u(τ) under the
sawtooth u = u₀ + u₁·τ over [0, T), and why a state may have no answer."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np


class Unbounded(ArithmeticError):
    """No periodic state: an undamped mode in resonance with a harmonic of the load."""


class Unresolved(ArithmeticError):
    """A scene outside what the closed form resolves to 8 digits (modes spread too
    wide, or one mode far slower than the load); the message says which."""


@dataclass(frozen=True)
class RampSystem:
    mass: np.ndarray  # M, n×n [kg·m²]
    damping: np.ndarray  # C, n×n [N·m·s/rad]
    stiffness: np.ndarray  # K, n×n [N·m/rad]
    constant: np.ndarray  # F, n [N·m]
    shape: np.ndarray  # s, n: load per unit of u [N·m per unit of u]
    start: Any  # u₀ = u(0⁺) (a float; in a block, one per row)
    slope: Any  # u₁ = du/dτ [unit of u per s]
    period: Any  # T [s]

    @property
    def size(self) -> int:
        return int(np.shape(self.constant)[-1])

    @property
    def mean_excitation(self) -> float:
        """ū = u₀ + u₁·T/2."""
        return self.start + 0.5 * self.slope * self.period

    def static(self) -> np.ndarray:
        """Mean position x̄ = K⁻¹·(F + s·ū)."""
        return np.linalg.solve(self.stiffness, self.constant + self.shape * self.mean_excitation)

    def first_order(self) -> np.ndarray:
        """A of y' = A·y + g for y = (x, x') (one per row of a block: leading axes)."""
        n = self.size
        inverse = np.linalg.inv(self.mass)
        a = np.zeros((*np.shape(self.mass)[:-2], 2 * n, 2 * n))
        a[..., :n, n:] = np.eye(n)
        a[..., n:, :n] = -inverse @ self.stiffness
        a[..., n:, n:] = -inverse @ self.damping
        return a

    def load(self, tau: float) -> np.ndarray:
        """g(τ) of y' = A·y + g(τ), τ in [0, T)."""
        n = self.size
        g = np.zeros(2 * n)
        force = self.constant + self.shape * (self.start + self.slope * tau)
        g[n:] = np.linalg.solve(self.mass, force)
        return g


Observable = np.ndarray  # w, 2n: the quantity w·(x, x')
