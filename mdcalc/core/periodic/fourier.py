"""The periodic state as the static part plus K harmonics of the sawtooth, each
through the frequency response (K - k²Ω²M + ikΩC)⁻¹."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mdcalc.core.periodic.system import Observable, RampSystem


@dataclass(frozen=True)
class FourierSeries:
    """x̄ plus K harmonics: w·y(τ) = w·ȳ + Σ Im(zₖ(w)·e^{ikΩτ})."""

    period: float
    mean: np.ndarray  # ȳ = (x̄, 0)
    responses: np.ndarray  # K × 2n complex: per unit of sin(kΩτ) forcing, (X, ikΩX)·cₖ

    @property
    def harmonics(self) -> int:
        return len(self.responses)

    def _z(self, w: Observable) -> np.ndarray:
        return self.responses @ w

    def observe(self, w: Observable, tau: np.ndarray) -> np.ndarray:
        omega = 2.0 * math.pi / self.period
        k = np.arange(1, self.harmonics + 1)
        phases = np.exp(1j * omega * np.outer(tau, k))
        return float(w @ self.mean) + (phases @ self._z(w)).imag

    def rate(self, w: Observable, tau: np.ndarray) -> np.ndarray:
        omega = 2.0 * math.pi / self.period
        k = np.arange(1, self.harmonics + 1)
        phases = np.exp(1j * omega * np.outer(tau, k))
        return (phases @ (self._z(w) * 1j * omega * k)).imag

    def sampled(self, w: Observable, samples: int) -> np.ndarray:
        """w·y at τ = jT/N by one inverse FFT (N > 2K)."""
        spectrum = np.zeros(samples, dtype=complex)
        spectrum[1 : self.harmonics + 1] = self._z(w)
        return float(w @ self.mean) + (samples * np.fft.ifft(spectrum)).imag


def fourier_periodic(system: RampSystem, harmonics: int) -> FourierSeries:
    n, t = system.size, system.period
    omega = 2.0 * math.pi / t
    k = np.arange(1, harmonics + 1)
    w = omega * k
    matrices = (
        system.stiffness[None, :, :]
        - (w * w)[:, None, None] * system.mass[None, :, :]
        + 1j * w[:, None, None] * system.damping[None, :, :]
    )
    # u - ū = -u₁·(T/π)·Σ sin(kΩτ)/k
    amplitudes = -system.slope * t / (math.pi * k)
    loads = np.broadcast_to(system.shape.astype(complex), (harmonics, n))
    x = np.linalg.solve(matrices, loads[:, :, None])[:, :, 0] * amplitudes[:, None]
    responses = np.concatenate([x, 1j * w[:, None] * x], axis=1)
    mean = np.concatenate([system.static(), np.zeros(n)])
    return FourierSeries(t, mean, responses)
