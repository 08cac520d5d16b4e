"""The shortcuts of :mod:`mdcalc.core.cosine_sums` against the plain search they
replace, and the plain search against an independent one.

* Long rows are sampled only in windows around the peaks of each sum's largest term
  (:func:`~mdcalc.core.cosine_sums.candidates.windows`): with the windows switched off
  (every row sampled whole) every maximum and its time must come out the same, bit
  for bit, and the windows must have been used.
* Candidates whose parabola bound cannot reach another's sample are not refined
  (:func:`~mdcalc.core.cosine_sums.candidates.worth_refining`): with every candidate
  refined the results must be the same, and some must have been dropped.
* A row's result does not depend on the rows beside it in a block.
* The maxima over a 20-period horizon against ``brute_max`` of ``test_chain``: a dense
  grid (200 points per fastest period) and scipy's bounded scalar search.
* The powers that replace cosines round like exact exponentials.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mdcalc.core import cosine_sums
from mdcalc.core.cosine_sums import candidates, samples
from mdcalc.core.powers import powers
from tests.test_chain import brute_max


def hoist_like(rng: np.random.Generator, rows: int, series: int, modes: int) -> tuple:
    """Sums like the mine hoist's: a slow term that dominates, faster ones 1.5 to 100
    times its frequency and up to 0.4 of its amplitude, some zero, over 1 to 60 of
    its periods (``maxima``'s arguments)."""
    slow = rng.uniform(1.0, 5.0, (rows, 1))
    ratios = np.concatenate([np.ones((rows, 1)), rng.uniform(1.5, 100.0, (rows, modes - 1))], 1)
    w = np.sort(slow * ratios, axis=1)
    b = rng.choice([-1.0, 1.0], (rows, series, modes)) * rng.uniform(0.5, 2.0, (rows, series, 1))
    b[:, :, 1:] *= rng.uniform(0.001, 0.4, (rows, series, modes - 1))
    b[rng.random(b.shape) < 0.05] = 0.0
    constant = rng.normal(0.0, 2.0, (rows, series))
    start = np.where(rng.random(rows) < 0.5, 0.0, rng.uniform(0.0, 5.0, rows))
    periods = rng.choice([1.0, 5.0, 20.0, 60.0], rows) * rng.uniform(0.9, 1.1, rows)
    return constant, b, w, start, start + 2.0 * math.pi / w[:, 0] * periods


def spy(monkeypatch: pytest.MonkeyPatch, module: object, name: str) -> list:
    """Record what ``module.name`` returns."""
    calls: list = []
    original = getattr(module, name)

    def recorded(*args, **kwargs):
        out = original(*args, **kwargs)
        calls.append(out)
        return out

    monkeypatch.setattr(module, name, recorded)
    return calls


def same(a: cosine_sums.Maxima, b: cosine_sums.Maxima) -> None:
    for field in ("value", "time", "bound", "error"):
        np.testing.assert_array_equal(getattr(a, field), getattr(b, field), err_msg=field)


@pytest.mark.parametrize("seed", range(6))
def test_windows_find_what_the_whole_grid_finds(seed: int, monkeypatch) -> None:
    rng = np.random.default_rng(seed)
    block = hoist_like(rng, 200, int(rng.integers(1, 4)), int(rng.integers(2, 5)))
    calls = spy(monkeypatch, candidates, "in_windows")
    windowed = cosine_sums.maxima(*block)
    assert sum(len(np.unique(found[0])) for found, _ in calls) > 50  # rows in windows
    assert all(len(lost) == 0 for _, lost in calls)  # none fell back to the grid
    monkeypatch.setattr(candidates, "WINDOW_SAMPLES", 1 << 40)
    same(windowed, cosine_sums.maxima(*block))


@pytest.mark.parametrize("seed", range(4))
def test_candidates_left_unrefined_could_not_win(seed: int, monkeypatch) -> None:
    rng = np.random.default_rng(20 + seed)
    block = hoist_like(rng, 200, 2, 3)
    calls = spy(monkeypatch, candidates, "worth_refining")
    pruned = cosine_sums.maxima(*block)
    assert not calls[0].all()  # some were dropped
    monkeypatch.setattr(
        candidates, "worth_refining", lambda sums, found: np.ones(len(found[0]), bool)
    )
    same(pruned, cosine_sums.maxima(*block))


def test_a_row_is_the_same_alone_and_in_a_block() -> None:
    rng = np.random.default_rng(7)
    block = hoist_like(rng, 60, 2, 3)
    together = cosine_sums.maxima(*block)
    for i in range(60):
        alone = cosine_sums.maxima(*(part[i : i + 1] for part in block))
        same(alone, cosine_sums.Maxima(*(getattr(together, f)[i : i + 1] for f in
                                          ("value", "time", "bound", "error"))))  # fmt: skip


@pytest.mark.parametrize("seed", range(8))
def test_horizon_maximum_matches_brute_force(seed: int) -> None:
    rng = np.random.default_rng(40 + seed)
    constant, b, w, start, _ = hoist_like(rng, 1, 1, int(rng.integers(2, 4)))
    end = start + 20 * 2 * math.pi / w[:, 0]  # the mine hoist's horizon
    found = cosine_sums.maxima(constant, b, w, start, end)
    assert candidates.windows(
        samples.Sums(constant, b, w, start, (end - start) / 4096), np.array([0]),
        np.array([4097]), np.zeros((1, 1)),
    )[0][0]  # fmt: skip  # (a row these sums would window)
    expected, _ = brute_max(constant[0, 0], b[0, 0], w[0], start[0], end[0])
    scale = abs(constant[0, 0]) + np.sum(np.abs(b))
    assert found.value[0, 0] == pytest.approx(expected, abs=1e-12 * scale)


def test_powers_round_like_exact_exponentials() -> None:
    # angles whose multiples are exact in binary: the reference rounds once
    theta = np.array([2.0**-10, 0.375, 2.875, 1234.5])
    eps = np.finfo(float).eps
    for count in (16, 64, 4096):
        table = powers(np.exp(1j * theta), count)
        k = np.arange(count)
        exact = np.exp(1j * np.multiply.outer(k, theta))
        assert np.all(
            np.abs(table - exact) <= (2.0 * k + 2.0 * math.log2(count) + 2.0)[:, None] * eps
        )
    assert powers(np.exp(1j * theta), 0).shape == (0, 4)
