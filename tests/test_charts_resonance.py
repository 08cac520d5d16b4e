"""``resonance.charts`` (``--plot``): the chart data against values worked out here.

Every expected number is computed in this file, never copied from the program:

* natural frequencies of two-mass chains by hand, ω = √(c·(1/J₁ + 1/J₂)), and the
  critical speeds where the order k·n/60 meets them, n = 60·ω/(2π·k);
* measured resonances f = n·k/60 (the brief's reference numbers, §9);
* the Ince–Strutt chart of x″ + c·x′ + (a - 2q·cos 2t)·x = 0 against textbook
  values: at q = 0 stable for a > 0 and unstable for a < 0; the first tongue between
  the transition curves b₁ = 1 - q - q²/8 + q³/64 and a₁ = 1 + q - q²/8 - q³/64
  (McLachlan); with damping c, the first approximation q² > (a - 1)² + c².
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.conftest import CASES, chart


def solved(path: Path) -> list[Any]:
    from mdcalc.input.casefile import read_case
    from mdcalc.runs.runner import solve_text

    run = solve_text(read_case(path))
    return run.module.charts(run.result)


def written(tmp_path: Path, text: str) -> list[Any]:
    path = tmp_path / "case.toml"
    path.write_text('problem = "resonance"\n' + text, encoding="utf-8")
    return solved(path)


def series(c: Any, start: str) -> tuple[list[float], list[float]]:
    found = [s for s in c.series if s.label.startswith(start)]
    assert len(found) == 1, [s.label for s in c.series]
    return list(found[0].x), list(found[0].y)


# ------------------------------------------------------------------------ Campbell


def test_campbell_of_the_130_hz_mode():
    c = chart(solved(CASES / "resonance" / "mode_130hz.toml"), "Campbell")
    omega = math.sqrt(333592.6287568203 * (1.0 / 1.0 + 1.0 / 1.0))  # J₁ = J₂ = 1
    f = omega / (2.0 * math.pi)  # 130 Hz
    x, y = series(c, "mode 1")
    assert y == pytest.approx([f, f], rel=1e-10)
    n, fs = series(c, "critical speeds")
    want = sorted(60.0 * omega / (2.0 * math.pi * k) for k in (3.0, 4.5, 6.0))
    assert sorted(n) == pytest.approx(want, rel=1e-10)  # 1300, 1733.3, 2600 rpm
    assert fs == pytest.approx([f] * 3, rel=1e-10)
    for k in (3.0, 4.5, 6.0):
        xr, yr = series(c, f"order k = {k:g}")
        assert (xr[0], yr[0]) == (0.0, 0.0)
        assert yr[-1] == pytest.approx(k * xr[-1] / 60.0, rel=1e-12)
    assert sorted(m.value for m in c.marks) == [1000.0, 3000.0]
    assert "[rpm]" in c.x_label and "[Hz]" in c.y_label


CHAIN = """
[chain]
inertias = [0.5, 2.0]
stiffnesses = [1.0e5]
"""


def test_default_four_stroke_orders_are_one_fan(tmp_path):
    c = chart(written(tmp_path, CHAIN + "[campbell]\nfrom_rpm = 600.0\nto_rpm = 3000.0\n"), "")
    omega = math.sqrt(1.0e5 * (1.0 / 0.5 + 1.0 / 2.0))  # 500 rad/s
    rays = [s for s in c.series if s.group == "orders"]
    assert rays[0].label.startswith("orders k·n/60") and not any(s.label for s in rays[1:])
    orders = [0.5 * j for j in range(1, 25)]  # 0.5 … 12, four-stroke: a ray each
    assert [list(s.x) for s in rays] == [[0.0, 3000.0]] * 24
    assert [s.y[0] for s in rays] == [0.0] * 24
    assert [s.y[1] for s in rays] == pytest.approx([k * 3000.0 / 60.0 for k in orders], rel=1e-12)
    n, _ = series(c, "critical speeds")
    want = [60.0 * omega / (2.0 * math.pi * k) for k in orders]
    assert sorted(n) == pytest.approx(sorted(s for s in want if 600.0 <= s <= 3000.0), rel=1e-10)
    assert len(n) == 12  # k = 2 … 7.5


def test_without_campbell_the_resonance_order_is_drawn(tmp_path):
    c = chart(written(tmp_path, CHAIN + "[resonance]\norder = 2.0\n"), "Campbell")
    omega = 500.0
    (n,), (f,) = series(c, "critical speeds")
    assert n == pytest.approx(60.0 * omega / (2.0 * math.pi * 2.0), rel=1e-10)  # 2387.3 rpm
    assert f == pytest.approx(omega / (2.0 * math.pi), rel=1e-10)
    x, _ = series(c, "order k = 2")
    assert x[-1] == pytest.approx(1.25 * n, rel=1e-10)
    assert c.marks == []


def test_a_chain_without_speeds_has_no_chart(tmp_path):
    assert written(tmp_path, CHAIN) == []


def test_measured_resonances_without_a_chain():
    c = chart(solved(CASES / "resonance" / "seed_measurements.toml"), "Campbell")
    n, f = series(c, "measured: f")
    # brief §9: 1500 and 1800 rpm at order 4.5 → 112.5 and 135 Hz; 2100 rpm, order 3 → 105
    assert n == [1500.0, 1800.0, 1733.3333333333333, 2100.0]
    assert f == pytest.approx([112.5, 135.0, 130.0, 105.0], rel=1e-12)
    assert series(c, "measured: the f stated") == ([1733.3333333333333, 2100.0], [130.0, 110.0])
    assert {s.label for s in c.series} >= {"order k = 3", "order k = 4.5"}
    assert not any(s.label.startswith("mode") for s in c.series)


# -------------------------------------------------------------------- Ince–Strutt


def stability(c: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    s = c.shade
    assert s is not None and list(s.levels) == [0.0, 1.0, 2.0]
    z = np.asarray(s.z, dtype=float)
    assert z.shape == (len(s.y), len(s.x)) and np.all(np.isfinite(z))
    return np.asarray(s.x), np.asarray(s.y), z


def unstable_at(c: Any, q: float, a: float) -> bool:
    qs, as_, z = stability(c)
    j, i = int(np.argmin(np.abs(qs - q))), int(np.argmin(np.abs(as_ - a)))
    assert qs[j] == pytest.approx(q, abs=1e-12) and as_[i] == pytest.approx(a, abs=1e-12)
    return bool(z[i, j] > 1.0)


UNDAMPED = """
[mathieu]
points = [[1.0, 0.1]]
a_from = -1.0
a_to = 3.0
q_to = 0.6
"""


@pytest.fixture(scope="module")
def undamped(tmp_path_factory) -> Any:
    return chart(written(tmp_path_factory.mktemp("mathieu"), UNDAMPED), "Ince–Strutt")


@pytest.mark.parametrize(
    ("q", "a", "unstable"),
    [
        (0.1, 1.0, True),  # inside the first tongue, 1 - q < a < 1 + q
        (0.5, 1.0, True),
        (0.1, 0.25, False),  # between the a₀ boundary (≈ -q²/2) and the first tongue
        (0.1, 2.0, False),  # between the first and second tongues
        (0.1, -0.5, True),  # below a₀ = -q²/2 + …
        (0.0, 0.5, False),  # q = 0: x″ + a·x = 0 oscillates for a > 0 …
        (0.0, -0.5, True),  # … and grows for a < 0
    ],
)
def test_ince_strutt_undamped_textbook_points(undamped, q, a, unstable):
    assert unstable_at(undamped, q, a) is unstable


def test_the_first_tongue_between_its_transition_curves(undamped):
    c = undamped
    qs, as_, z = stability(c)
    step = as_[1] - as_[0]
    for j in (12, 20, 30):  # q = 0.12, 0.2, 0.3 on a 61-column grid to 0.6
        q = qs[j]
        low = 1.0 - q - q * q / 8.0 + q**3 / 64.0  # b₁(q)
        high = 1.0 + q - q * q / 8.0 - q**3 / 64.0  # a₁(q)
        inside = as_[(z[:, j] > 1.0) & (as_ > 0.2)]
        assert inside.min() == pytest.approx(low, abs=step)
        assert inside.max() == pytest.approx(high, abs=step)
    assert series(c, "the case's (q, a)") == ([0.1], [1.0])


def test_damping_closes_the_tip_of_the_first_tongue(tmp_path):
    text = "[mathieu]\ndamping = 0.1\npoints = [[1.0, 0.5]]\nq_to = 1.0\n"
    c = chart(written(tmp_path, text), "Ince–Strutt")
    # first approximation: unstable when q² > (a - 1)² + c²
    assert not unstable_at(c, 0.05, 1.0)
    assert unstable_at(c, 0.5, 1.0)
    assert not unstable_at(c, 0.5, 2.0)
    x, y = series(c, "first approximation")
    for q, a in zip(x, y, strict=True):
        assert (a - 1.0) ** 2 == pytest.approx(q * q - 0.01, abs=1e-12)
    assert min(x) == pytest.approx(0.1)  # the tip at q = c
    assert "c = 0.1" in c.title


def test_the_map_widens_to_the_case_points(tmp_path):
    c = chart(written(tmp_path, "[mathieu]\npoints = [[6.0, 3.0], [-2.0, 0.5]]\n"), "Ince–Strutt")
    qs, as_, _ = stability(c)
    assert qs[0] == 0.0 and qs[-1] > 3.0
    assert as_[0] < -2.0 and as_[-1] > 6.0


def test_no_mathieu_no_ince_strutt():
    charts = solved(CASES / "resonance" / "inline_six.toml")
    assert [c.title.split(":")[0] for c in charts] == ["Campbell diagram"]
