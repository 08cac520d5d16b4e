"""core/search.py: the golden-section search shared by the mechanism's extremes and
the resonance's peak amplitudes."""

from __future__ import annotations

import math

import numpy as np

from mdcalc.core.search import GOLDEN, golden_maximum


def test_golden_section_finds_the_peak_within_its_last_bracket():
    # -(x - c)² + a cosine's hump: the peak is c for the parabola, π/2·k for the sine
    for iterations in (10, 40):
        found = golden_maximum(lambda x: -((x - 0.3) ** 2), 0.0, 1.0, iterations)
        assert abs(found - 0.3) <= GOLDEN**iterations
    found = golden_maximum(math.sin, 0.0, 3.0, 60)
    assert abs(found - math.pi / 2) < 1e-7  # sin is flat to 1e-14 within 1.5e-7 of it


def test_golden_section_evaluates_once_an_iteration():
    calls = []

    def f(x: float) -> float:
        calls.append(x)
        return -abs(x - 0.7)

    golden_maximum(f, 0.0, 2.0, 30)
    assert len(calls) == 31  # two inner points, then the one new point an iteration


def test_golden_section_on_arrays_is_each_row_s_float_search():
    rng = np.random.default_rng(3)
    centre = rng.uniform(-1.0, 1.0, 40)
    low, high = centre - rng.uniform(0.1, 2.0, 40), centre + rng.uniform(0.1, 2.0, 40)
    found = golden_maximum(lambda x: -((x - centre) ** 2) * (1.0 + x * x), low, high, 40)
    for k in range(40):
        c = float(centre[k])
        alone = golden_maximum(lambda x, c=c: -((x - c) ** 2) * (1.0 + x * x), low[k], high[k], 40)
        assert found[k] == alone
        assert abs(alone - c) <= (high[k] - low[k]) * GOLDEN**40
