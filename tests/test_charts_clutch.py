"""``clutch`` chart (``--plot``): the curves C_max(η) of (26), checked against the
formula written out here (brief PROBLEMS.md §10, seed 004):

    C_max = π·(z₁f₁ + z₂f₂) / [4·z₂f₂·(z₁η₁f₁ + z₂η₂f₂)·(1 - η₂)]        (26)
    C_max = π / (4·z₂·f·η·(1 - η))                       η₁ = η₂ = η, one f  (27)
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import pytest

from mdcalc.input.casefile import read_case
from mdcalc.output.plot import Chart, Series
from mdcalc.runs.runner import solve_text
from tests.conftest import CASES


def c_max(z1: int, z2: int, f1: float, f2: float, eta1: float, eta2: float) -> float:
    """(26), by hand."""
    return (
        math.pi
        * (z1 * f1 + z2 * f2)
        / (4.0 * z2 * f2 * (z1 * eta1 * f1 + z2 * eta2 * f2) * (1.0 - eta2))
    )


def chart_of(name: str, folder: str = "clutch") -> Chart:
    run = solve_text(read_case(CASES / folder / f"{name}.toml"))
    charts = run.module.charts(run.result)
    assert len(charts) == 1
    return charts[0]


def series(chart: Chart, label: str) -> Series:
    found = [s for s in chart.series if s.label == label]
    assert len(found) == 1, [s.label for s in chart.series]
    return found[0]


def test_fig2_curves_follow_26_at_200_points():
    """fig2_differentiated: z₁ = 1, z₂ = 3, f₁ = 0.3, f₂ = 0.4, η₁ = 0.65, η₂ = 0.8;
    [curves] η from 0.65 to 0.8, driven_ratios 0.8 and 0.735 (η₁ varies), η₁ = 0.65
    where η₂ varies (the case's, by default), and η₁ = η₂."""
    chart = chart_of("fig2_differentiated")
    pairs = (1, 3, 0.3, 0.4)
    curves = {
        "η₁ = η, η₂ = 0.8": lambda eta: c_max(*pairs, eta, 0.8),
        "η₁ = η, η₂ = 0.735": lambda eta: c_max(*pairs, eta, 0.735),
        "η₂ = η, η₁ = 0.65": lambda eta: c_max(*pairs, 0.65, eta),
        "η₁ = η₂ = η (27)": lambda eta: c_max(*pairs, eta, eta),
    }
    for label, formula in curves.items():
        s = series(chart, label)
        assert len(s.x) == 200
        assert s.x[0] == pytest.approx(0.65, rel=1e-15)
        assert s.x[-1] == pytest.approx(0.8, rel=1e-15)
        assert all(b > a for a, b in zip(s.x, s.x[1:], strict=False))
        for eta, value in zip(s.x, s.y, strict=True):
            assert value == pytest.approx(formula(eta), rel=1e-12), (label, eta)
    # The case's own bound, at its η₂ on the curve where η₂ varies and at its η₁ on
    # the curve η₂ = 0.8: 4.24999 (the case file's hand value).
    own = c_max(*pairs, 0.65, 0.8)
    assert own == pytest.approx(4.249990061674503, rel=1e-12)
    point = series(chart, f"this case: C_max = {own:.4g}")
    assert point.role == "this-case"
    assert sorted(point.x) == [0.65, 0.8]
    assert list(point.y) == pytest.approx([own, own], rel=1e-12)
    assert series(chart, "η₂ = η, η₁ = 0.65").y[-1] == pytest.approx(own, rel=1e-12)
    assert series(chart, "η₁ = η, η₂ = 0.8").y[0] == pytest.approx(own, rel=1e-12)
    marks = [(m.label, m.axis, m.value, m.role) for m in chart.marks]
    assert marks == [
        ("this case: η₂ = 0.8, η₁ = 0.65", "x", 0.8, "this-case"),  # one legend entry
        ("", "x", 0.65, "this-case"),
        ("gain C = 2 of this clutch: stable where C_max is above", "y", 2.0, "limit"),
    ]
    assert not chart.y_log
    assert "[-]" in chart.x_label and "[-]" in chart.y_label


@pytest.mark.parametrize(
    ("name", "eta", "reference"),
    [("one_material_065", 0.65, 2.877), ("one_material_080", 0.8, 4.091)],
)
def test_one_material_curve_27_passes_the_brief_references(name: str, eta: float, reference: float):
    """Brief §10: one material, z₂ = 3, f = 0.4: C_max = π/(4.8·η(1 - η)) = 2.877 at
    0.65 and 4.091 at 0.8. No [curves]: the default range 0.65-0.8."""
    chart = chart_of(name)
    one = series(chart, "η₁ = η₂ = η (27)")
    for x, value in zip(one.x, one.y, strict=True):
        assert value == pytest.approx(
            math.pi / (4.0 * 3 * 0.4 * x * (1.0 - x)), rel=1e-2
        )  # f₁ ≠ f₂
        assert value == pytest.approx(c_max(1, 3, 0.3, 0.4, x, x), rel=1e-12)
    (point,) = [s for s in chart.series if s.role == "this-case"]
    assert point.x == [eta]
    assert point.y[0] == pytest.approx(reference, rel=2e-4)
    end = one.y[0] if eta == 0.65 else one.y[-1]
    assert end == pytest.approx(math.pi / (4.8 * eta * (1.0 - eta)), rel=1e-12)
    assert [m.label for m in chart.marks] == [f"this case: η₁ = η₂ = {eta:g}"]  # no [clutch]


def test_range_widens_to_the_case_and_gain_above_the_bound_is_marked():
    """unstable_ramp: η₁ = 0.7, η₂ = 0.6 (below the default 0.65): the range starts
    at 0.6. C = (0.12/0.02)·tan 30° = 3.464 > C_max = 2.569."""
    chart = chart_of("unstable_ramp")
    pairs = (2, 4, 0.35, 0.3)
    driven = series(chart, "η₂ = η, η₁ = 0.7")
    assert driven.x[0] == pytest.approx(0.6) and driven.x[-1] == pytest.approx(0.8)
    assert driven.y[0] == pytest.approx(c_max(*pairs, 0.7, 0.6), rel=1e-12)
    assert driven.y[0] == pytest.approx(2.5693121736486773, rel=1e-12)
    gain = 0.12 / 0.02 * math.tan(math.radians(30.0))
    (mark,) = [m for m in chart.marks if m.axis == "y"]
    assert mark.value == pytest.approx(gain, rel=1e-12)
    assert mark.value > driven.y[0]  # unstable: the gain is above the case's bound


def test_eta2_equal_to_one_leaves_out_the_unbounded_points():
    """driven_no_drop: η₂ = 1, (26) divides by 1 - η₂ = 0: the curve η₂ = 1 is all
    unbounded and not drawn; the curves where η₂ varies stop short of 1. The gain
    10⁴ would flatten the curves (C_max about 5-8 here) and is not marked."""
    chart = chart_of("driven_no_drop")
    labels = [s.label for s in chart.series]
    assert labels == ["η₂ = η, η₁ = 0.7", "η₁ = η₂ = η (27)"]
    assert "η₂ = 1" in chart.title
    for s in chart.series:
        assert all(math.isfinite(v) for v in s.y)
        assert max(s.x) < 1.0
    varying = series(chart, "η₂ = η, η₁ = 0.7")
    for eta, value in zip(varying.x, varying.y, strict=True):
        assert value == pytest.approx(c_max(2, 2, 0.3, 0.35, 0.7, eta), rel=1e-12)
    assert [m.label for m in chart.marks] == ["this case: η₁ = 0.7"]


def test_eta_next_to_one_is_finite_on_a_log_axis():
    """clutch_eta_near_one: η = 1 - 2^-30; (27) gives π/(4·3·0.4·η·2^-30) = 7.03e8."""
    chart = chart_of("clutch_eta_near_one", "extreme")
    eta = 1.0 - 2.0**-30
    assert chart.y_log
    own = math.pi / (4.0 * 3 * 0.4 * eta * (1.0 - eta))
    (point,) = [s for s in chart.series if s.role == "this-case"]
    assert point.x == [eta] and point.y[0] == pytest.approx(own, rel=1e-9)
    one = series(chart, "η₁ = η₂ = η (27)")
    assert one.x[-1] == pytest.approx(eta, abs=1e-15)
    assert one.y[-1] == pytest.approx(own, rel=1e-6)
    # The labels tell η from 1.
    assert "η₁ = η, η₂ = 0.999999999069" in [s.label for s in chart.series]


@pytest.mark.parametrize(
    "path",
    sorted((CASES / "clutch").glob("*.toml")) + sorted((CASES / "extreme").glob("clutch_*.toml")),
    ids=lambda p: p.stem,
)
def test_every_case_has_a_finite_labelled_chart(path: Path):
    run = solve_text(read_case(path))
    (chart,) = run.module.charts(run.result)
    assert chart.title and chart.x_label and chart.y_label
    for s in chart.series:
        assert len(s.x) == len(s.y) > 0
        assert all(math.isfinite(v) for v in [*s.x, *s.y])
        if chart.y_log:
            assert min(s.y) > 0.0
    for m in chart.marks:
        assert math.isfinite(m.value)
        assert not (chart.y_log and m.axis == "y" and m.value <= 0.0)


def test_charts_import_no_numpy():
    """The clutch is all closed forms: drawing its data needs no numpy."""
    case = str(CASES / "clutch" / "fig2_differentiated.toml")
    probe = (
        "import sys\n"
        "from pathlib import Path\n"
        "from mdcalc.input.casefile import read_case\n"
        "from mdcalc.runs.runner import solve_text\n"
        f"run = solve_text(read_case(Path({case!r})))\n"
        "assert run.module.charts(run.result)\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('numpy', 'scipy')))\n"
    )
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"
