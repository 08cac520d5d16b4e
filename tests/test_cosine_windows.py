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
* Edge cases a review found: a negative frequency, a peak within the first sample
  step after a zero slope at t = 0, two peaks within two samples (an "M").
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


def test_a_row_its_windows_cannot_hold_falls_back_to_the_whole_grid(monkeypatch) -> None:
    # every windowed row reported lost (a sample within the slack at a window's
    # edge): each is sampled whole, with the same results
    block = hoist_like(np.random.default_rng(11), 120, 2, 3)
    windowed = cosine_sums.maxima(*block)
    original = candidates.in_windows

    def all_lost(sums, group, *args):
        found, _ = original(sums, group, *args)
        return tuple(part[:0] for part in found), group

    monkeypatch.setattr(candidates, "in_windows", all_lost)
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


def test_a_negative_frequency_is_its_absolute_value() -> None:
    # cos is even; a long row with a negative largest term's frequency crashed
    found = cosine_sums.cosine_sum_maximum(0.0, [1.0, 0.1], [-1.0, 10.0], 0.0, 200 * math.pi)
    same_sum = cosine_sums.cosine_sum_maximum(0.0, [1.0, 0.1], [1.0, 10.0], 0.0, 200 * math.pi)
    assert (found.value, found.time) == (same_sum.value, same_sum.time)
    assert found.value == pytest.approx(1.1, abs=1e-15)


@pytest.mark.parametrize(
    ("b", "w", "end"),
    [  # the peak inside the first sample step; inside the second
        ([-0.208067277, -1177.27692, -0.0957848474, 2097.25763],
         [20.22943001, 26.16186871, 1.54664533, 19.53867533], 0.22090181696668532),
        ([17.04054339, 1062.46380788, 1665.15402929, -589.01131453],
         [9.73009366, 8.01424954, 10.00836568, 20.27660224], 0.260356008392412),
    ],
)  # fmt: skip
def test_a_peak_right_after_a_flat_start_is_found(b, w, end) -> None:
    # f'(0) = 0 exactly (sin 0) at a local minimum, the peak within two sample
    # steps: the bracket's zero slope takes the sign just inside it, and a bracket
    # whose slope keeps its sign (from a hair before 0) is scanned for a root (both
    # were taken for a peak at t = 0: 2.7e-4 and 1.8e-4 below the maximum)
    for start in (0.0, -1e-12):  # (a hair off the zero slope: no zero at the end)
        found = cosine_sums.cosine_sum_maximum(0.0, b, w, start, end)
        expected, _ = brute_max(0.0, np.array(b), np.array(w), start, end)
        assert found.value == pytest.approx(expected, rel=1e-13)
        assert found.time > 0.0


def test_two_peaks_within_two_samples_are_never_below_the_best_sample() -> None:
    # an "M" top: the higher hump falls between two samples neither of which is a
    # sampled local maximum. The answer is at least the best sample (it was below
    # it), so within the sampling error of the truth.
    h = 2 * math.pi / 320
    start = -9.3 * h
    b, w = np.array([1.0, -0.0025231250]), np.array([1.0, 20.0])
    found = cosine_sums.cosine_sum_maximum(0.0, b.tolist(), w.tolist(), start, start + 40 * h)
    grid = start + h * np.arange(41)  # the samples the search takes (16 per 2π/20)
    best_sample = float(np.max(np.cos(np.outer(grid, w)) @ b))
    truth, _ = brute_max(0.0, b, w, start, start + 40 * h)
    slack = float(np.sum(np.abs(b) * w * w)) * h * h / 8
    assert best_sample <= found.value <= truth + 1e-15
    assert truth - found.value <= slack


@pytest.mark.parametrize(("ratio", "offset"), [(1.0196215996670155, -0.41455850197502575),
                                               (1.018279890786035, 0.64015150034107)])  # fmt: skip
def test_an_m_top_whose_higher_hump_is_inside_the_bracket(ratio: float, offset: float) -> None:
    # the bracket's slope keeps its sign, the higher hump lies between the sample and
    # an end: split at the sample, that half is refined (it was missed, by 4e-7)
    h = 2 * math.pi / 320
    start = (offset - 10.0) * h
    b, w = np.array([1.0, -ratio / 400.0]), np.array([1.0, 20.0])
    found = cosine_sums.cosine_sum_maximum(0.0, b.tolist(), w.tolist(), start, start + 40 * h)
    truth, _ = brute_max(0.0, b, w, start, start + 40 * h)
    assert found.value == pytest.approx(truth, rel=1e-13)
