"""The samples of a block's cosine sums on their grids, t = t₀ + j·Δt: all of a
row's samples in turn, or windows of them. No cosine a sample: products of complex
exponentials (a cosine costs about 17 ns here, a complex product 0.5)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mdcalc.core.powers import powers

#: Samples of a run of the whole grid: each run of a sum is one small matrix product.
RUN = 32
#: Anchors between two exact exponentials (the rest are their powers).
ANCHOR_POWERS = 16
#: Samples a window's anchor table counts in its fine part (a = 64q + r).
FINE = 64


@dataclass(frozen=True)
class Sums:
    """S cosine sums R + Σ Bₖ·cos(wₖt) of each row of a block, sampled at t₀ + j·Δt:
    ``constant`` R (B, S), ``amplitudes`` B of the modes sampled (B, S, m, zero
    for the others), ``frequencies`` w (B, m), ``start`` t₀ and ``step`` Δt (B,).

    A sample's angle splits at an anchor a, w·(t₀ + aΔt) + w·rΔt, so that
    B·cos(A + R) = (B·cos A)·cos R - (B·sin A)·sin R: the factors of the anchors and
    of the run are taken apart, and a run of samples of a sum is one small matrix
    product over the modes (and the constant). The factors are powers: e^{iw·rΔt} of
    e^{iwΔt}, e^{iwA} an exact exponential every ANCHOR_POWERS anchors times powers
    between (:func:`~mdcalc.core.powers.powers`). A sample so carries a rounding of some 100ε of
    R + Σ|B| (a window longer than FINE samples: its length times ε), far inside
    the sampling error the search allows for (the slack)."""

    constant: np.ndarray
    amplitudes: np.ndarray
    frequencies: np.ndarray
    start: np.ndarray
    step: np.ndarray

    @property
    def series(self) -> int:
        return int(self.amplitudes.shape[1])

    @property
    def modes(self) -> int:
        return int(self.amplitudes.shape[2])

    def runs(self, at: np.ndarray, anchors: np.ndarray) -> np.ndarray:
        """The sums of rows ``at`` over the runs of RUN samples from the samples
        RUN·``anchors`` ((G, K) or (1, K) anchor numbers): (G, S, K, RUN)."""
        size, count = len(at), anchors.shape[1]
        t0, dt = self.start[at][:, None], self.step[at][:, None]
        low = int(np.min(anchors))
        exact = low + ANCHOR_POWERS * np.arange(
            -(-(int(np.max(anchors)) - low + 1) // ANCHOR_POWERS)
        )
        chosen = np.broadcast_to(anchors - low, (size, count))
        factors = np.empty((size, self.series, count, 2 * self.modes + 1))
        runs = np.empty((size, 2 * self.modes + 1, RUN))
        for k in range(self.modes):
            wk = self.frequencies[at, k]
            run = powers(np.exp(1j * wk * dt[:, 0]), RUN).T  # (G, RUN): e^{iw·rΔt}
            between = powers(np.exp(1j * wk * (RUN * dt[:, 0])), ANCHOR_POWERS).T
            angle = np.exp(1j * wk[:, None] * (t0 + dt * (RUN * exact)))
            angle = (angle[:, :, None] * between[:, None, :]).reshape(size, -1)
            angle = np.take_along_axis(angle, chosen, axis=1)  # (G, K): e^{iwA}
            self._factors(factors, at, k, angle[:, None, :])
            runs[:, 2 * k], runs[:, 2 * k + 1] = run.real, run.imag
        return self._product(factors, runs, at)

    def grid(self, at: np.ndarray, index: np.ndarray) -> np.ndarray:
        """The sums of rows ``at`` at their samples ``index`` (consecutive sample
        numbers, shared by the rows): (G, S, K), by :meth:`runs`."""
        first = int(index[0]) - int(index[0]) % RUN  # a multiple of RUN at or below
        anchors = -(-(int(index[-1]) - first + 1) // RUN)
        total = self.runs(at, (first // RUN + np.arange(anchors))[None, :])
        skip = int(index[0]) - first
        flat = total.reshape(len(at), self.series, anchors * RUN)
        return flat[:, :, skip : skip + len(index)]

    def windows(self, at: np.ndarray, starts: np.ndarray, width: int) -> np.ndarray:
        """The sums of rows ``at`` at ``width`` samples from each of ``starts``
        (G, S, P), each sum its own windows: (G, S, P, width). A window's anchor is
        its first sample a, a - a₀ = FINE·q + r from the tile's lowest start a₀:
        e^{iw(t₀ + aΔt)} = e^{iw(t₀ + (a₀ + FINE·q)Δt)}·e^{iw·rΔt}."""
        size, count = len(at), starts.shape[2]
        t0, dt = self.start[at], self.step[at]
        low = int(np.min(starts))
        coarse = (int(np.max(starts)) - low) // FINE + 1
        exact = low + FINE * ANCHOR_POWERS * np.arange(-(-coarse // ANCHOR_POWERS))
        near, far = (starts - low) % FINE, (starts - low) // FINE
        line = np.arange(size)[:, None, None]
        factors = np.empty((size, self.series, count, 2 * self.modes + 1))
        runs = np.empty((size, 2 * self.modes + 1, width))
        for k in range(self.modes):
            wk = self.frequencies[at, k]
            fine = powers(np.exp(1j * wk * dt), max(FINE, width)).T  # (G, ·): e^{iw·rΔt}
            between = powers(np.exp(1j * FINE * wk * dt), ANCHOR_POWERS).T
            angle = np.exp(1j * wk[:, None] * (t0[:, None] + dt[:, None] * exact))
            angle = (angle[:, :, None] * between[:, None, :]).reshape(size, -1)
            self._factors(factors, at, k, angle[line, far] * fine[line, near])
            runs[:, 2 * k], runs[:, 2 * k + 1] = fine.real[:, :width], fine.imag[:, :width]
        return self._product(factors, runs, at)

    def _factors(self, factors: np.ndarray, at: np.ndarray, k: int, angle: np.ndarray) -> None:
        """Mode k's anchor factors B·cos A and -B·sin A from e^{iA} (broadcast to
        (G, S, K))."""
        bk = self.amplitudes[at, :, k][:, :, None]
        factors[:, :, :, 2 * k] = bk * angle.real
        factors[:, :, :, 2 * k + 1] = bk * -angle.imag

    def _product(self, factors: np.ndarray, runs: np.ndarray, at: np.ndarray) -> np.ndarray:
        """Each anchor's factors (and the constant) times its run's: (G, S, K, run)."""
        size, series, count = factors.shape[:3]
        factors[:, :, :, -1] = self.constant[at][:, :, None]
        runs[:, -1] = 1.0
        total = factors.reshape(size, series * count, -1) @ runs
        return total.reshape(size, series, count, runs.shape[2])
