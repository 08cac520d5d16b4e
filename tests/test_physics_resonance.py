"""Independent physics tests of ``mdcalc resonance`` (brief PROBLEMS.md §9, seed 003,
Tverskov, "Амплитуды колебаний при резонансе").

Every expected value is computed in this file, never copied from the program:

* natural frequencies and mode shapes of the free-free chain J₁-c₁-…-Jₙ from
  ``scipy.linalg.eigh(K, J)`` (rigid mode dropped), from the closed form of a uniform
  chain (λⱼ = 4c/J·sin²(jπ/2n), aᵢ ∝ cos((i - ½)jπ/n)), or for three masses from the
  quadratic λ² - sλ + p = 0 (small root as p/λ_large, no cancellation);
* critical speeds n = 60·f/k and the Campbell rows by hand;
* the geometric sum |Σ aᵢ·e^(i·k·δᵢ)| over the cranks with numpy;
* the energy balance (seed "(5)") A = M_k·|Σ aᵢe^(ikδᵢ)|/(ω_c·Σ ξᵢaᵢ²), shaft torques
  cᵢ·|aᵢ - aᵢ₊₁|·A, and the exact damped steady state (K - ω²J + iωΞ)·X = M by
  ``numpy.linalg.solve`` with Mᵢ = M_k·e^(-ikδᵢ) on the cranks;
* Floquet: the monodromy of x″ + c·x′ + (a - 2q·cos 2t)·x = 0 over one period π by
  ``scipy.integrate.solve_ivp`` (all points of a chart at once), closed forms at q = 0,
  and the undamped first-tongue transition curves a = 1 ± q - q²/8 ∓ q³/64.

The program is run in-process through its CLI (``--json``) or, for the modal property
tests, through ``mdcalc.problems.resonance.chain.modal`` on a ``ChainSection``.
"""

from __future__ import annotations

import cmath
import io
import json
import math
import re
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import scipy.linalg
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from rich.console import Console
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar
from tomli_w import dumps as toml_dumps
from typer.testing import CliRunner

from mdcalc.cli.app import app
from mdcalc.output.jsondoc import to_json
from mdcalc.output.text import render_rich
from mdcalc.problems.resonance.case import ChainSection
from mdcalc.problems.resonance.chain import modal
from mdcalc.runs.runner import run_case
from tests.conftest import CASES, assert_no_traceback, strict_json, walk_finite

TWO_PI = 2.0 * math.pi
RUNNER = CliRunner()
NODE = 1e-6  # |a| below this (largest |a| = 1) makes a mass a node for normalisation

INLINE_SIX: dict[str, Any] = {
    k: v
    for k, v in tomllib.loads((CASES / "resonance" / "inline_six.toml").read_text("utf-8")).items()
    if k != "expect"
}

# ----------------------------------------------------------------------------- helpers


def invoke(path: Path, *options: str) -> Any:
    return RUNNER.invoke(app, ["resonance", str(path), *options])


def run_json(data: dict[str, Any] | str, folder: Path, code: int = 0) -> dict[str, Any]:
    """Write the case, run it with --json, check the exit code and finiteness."""
    path = folder / "case.toml"
    path.write_text(data if isinstance(data, str) else toml_dumps(data), encoding="utf-8")
    result = invoke(path, "--json")
    assert_no_traceback(result)
    assert result.exit_code == code, result.stdout + result.stderr
    report = strict_json(result.stdout)
    walk_finite(report)
    return report


def values(report: dict[str, Any]) -> dict[str, Any]:
    return {key: item["value"] for key, item in report["results"].items()}


def section(report: dict[str, Any], key: str) -> dict[str, Any]:
    found = [s for s in report["sections"] if s.get("key") == key]
    assert len(found) == 1, f"no single section {key!r}"
    return found[0]


def rows(report: dict[str, Any], key: str) -> list[list[Any]]:
    return section(report, key)["rows"]


def method_values(report: dict[str, Any], key: str) -> dict[str, dict[str, float]]:
    return {row["method"]: row["values"] for row in section(report, key)["rows"]}


def stiffness_matrix(stiffnesses: list[float]) -> np.ndarray:
    n = len(stiffnesses) + 1
    k = np.zeros((n, n))
    for i, c in enumerate(stiffnesses):
        k[i, i] += c
        k[i + 1, i + 1] += c
        k[i, i + 1] -= c
        k[i + 1, i] -= c
    return k


def own_modes(inertias: list[float], stiffnesses: list[float]) -> tuple[np.ndarray, np.ndarray]:
    """β [rad/s] of the elastic modes and their shapes (rows), by eigh(K, J)."""
    w, v = scipy.linalg.eigh(stiffness_matrix(stiffnesses), np.diag(inertias))
    return np.sqrt(w[1:]), v[:, 1:].T.copy()


def own_reference(shape: np.ndarray, cranks: list[int] | None) -> int:
    """Mass 1 unless it is a node; then the first crank, else the largest amplitude."""
    s = shape / np.max(np.abs(shape))
    if abs(s[0]) > NODE:
        return 0
    if cranks and abs(s[cranks[0] - 1]) > NODE:
        return cranks[0] - 1
    return int(np.argmax(np.abs(s)))


def own_sum(shape: np.ndarray, cranks: list[int], angles_deg: list[float], k: float) -> complex:
    return complex(
        sum(
            shape[m - 1] * cmath.exp(1j * k * math.radians(d))
            for m, d in zip(cranks, angles_deg, strict=True)
        )
    )


def own_main(angles_deg: list[float], k: float) -> bool:
    phases = [(k * d) % 360.0 for d in angles_deg]
    return all(min(abs(p - phases[0]), 360.0 - abs(p - phases[0])) < 1e-7 for p in phases)


def own_exact(chain: dict[str, Any], k: float, torque: float, omega: float) -> np.ndarray:
    """X of (K - ω²J + iωΞ)·X = M, Mᵢ = M_k·e^(-ikδᵢ) on the cranks."""
    j = np.array(chain["inertias"], dtype=float)
    xi = np.array(chain["damping"], dtype=float)
    load = np.zeros(len(j), dtype=complex)
    for m, d in zip(chain["cranks"], chain["firing_angles_deg"], strict=True):
        load[m - 1] = torque * cmath.exp(-1j * k * math.radians(d))
    matrix = (
        stiffness_matrix(chain["stiffnesses"]) - omega**2 * np.diag(j) + 1j * omega * np.diag(xi)
    )
    return np.linalg.solve(matrix, load)


def own_energy(chain: dict[str, Any], mode: int, k: float, torque: float) -> dict[str, Any]:
    """Seed (5) with eigh's mode shape normalised at the reference mass."""
    beta, shapes = own_modes(chain["inertias"], chain["stiffnesses"])
    shape = shapes[mode - 1]
    ref = own_reference(shape, chain.get("cranks"))
    a = shape / shape[ref]
    xi = np.array(chain["damping"], dtype=float)
    total = abs(own_sum(a, chain["cranks"], chain["firing_angles_deg"], k))
    amplitude = torque * total / (beta[mode - 1] * float(np.sum(xi * a * a)))
    shafts = [c * abs(a[i] - a[i + 1]) * amplitude for i, c in enumerate(chain["stiffnesses"])]
    x = own_exact(chain, k, torque, beta[mode - 1])
    exact_shafts = [c * abs(x[i] - x[i + 1]) for i, c in enumerate(chain["stiffnesses"])]
    return {
        "beta": beta[mode - 1],
        "ref": ref,
        "shape": a,
        "geometric_sum": total,
        "amplitude": amplitude,
        "shafts": shafts,
        "amplitude_exact": abs(x[ref]),
        "exact_shafts": exact_shafts,
    }


def monodromy(a: Any, q: Any, c: float, rtol: float = 1e-12) -> tuple[np.ndarray, np.ndarray]:
    """Trace and determinant of the period-π map of x″ + c·x′ + (a - 2q·cos 2t)·x = 0,
    every (a, q) pair integrated at once by DOP853."""
    a = np.atleast_1d(np.asarray(a, dtype=float)).ravel()
    q = np.atleast_1d(np.asarray(q, dtype=float)).ravel()
    m = a.size

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        x1, v1, x2, v2 = y.reshape(4, m)
        p = a - 2.0 * q * math.cos(2.0 * t)
        return np.concatenate([v1, -c * v1 - p * x1, v2, -c * v2 - p * x2])

    start = np.concatenate([np.ones(m), np.zeros(m), np.zeros(m), np.ones(m)])
    sol = solve_ivp(rhs, (0.0, math.pi), start, method="DOP853", rtol=rtol, atol=rtol * 1e-3)
    assert sol.success
    x1, v1, x2, v2 = sol.y[:, -1].reshape(4, m)
    return x1 + v2, x1 * v2 - x2 * v1


def radius(trace: float, det: float) -> float:
    roots = np.roots([1.0, -trace, det])
    return float(np.max(np.abs(roots)))


def mathieu_case(points: list[list[float]], damping: float = 0.0, **chart: Any) -> dict[str, Any]:
    body: dict[str, Any] = {"damping": damping}
    if points:
        body["points"] = [[float(a), float(q)] for a, q in points]
    body.update(chart)
    return {"problem": "resonance", "mathieu": body}


# ============================================================ natural modes (property)

exponent = st.floats(min_value=0.0, max_value=1.0, allow_nan=False)


@st.composite
def chains(draw: Any) -> tuple[list[float], list[float]]:
    n = draw(st.integers(min_value=2, max_value=8))
    inertias = [0.05 * 100.0 ** draw(exponent) for _ in range(n)]  # 0.05 … 5 kg·m²
    stiffnesses = [1e4 * 100.0 ** draw(exponent) for _ in range(n - 1)]  # 1e4 … 1e6
    return inertias, stiffnesses


@settings(max_examples=40, deadline=None, derandomize=True)
@given(chains())
def test_random_chain_modes_against_eigh(chain: tuple[list[float], list[float]]) -> None:
    inertias, stiffnesses = chain
    n = len(inertias)
    beta, shapes = own_modes(inertias, stiffnesses)
    for shape in shapes:
        s = np.abs(shape / np.max(np.abs(shape)))
        assume(s[0] > 1e-4 or s[0] < 1e-8)  # not at the node threshold
    md = modal(ChainSection(inertias=inertias, stiffnesses=stiffnesses))
    assert len(md.frequencies) == n - 1
    assert np.array(md.frequencies) == pytest.approx(beta, rel=1e-9)
    k, j = stiffness_matrix(stiffnesses), np.diag(inertias)
    for mode in range(n - 1):
        ref = own_reference(shapes[mode], None)
        assert md.references[mode] == ref
        a = np.array(md.shapes[mode])
        assert a[ref] == pytest.approx(1.0, abs=1e-14)
        expected = shapes[mode] / shapes[mode][ref]
        scale = float(np.max(np.abs(expected)))
        assert a == pytest.approx(expected, abs=1e-8 * scale)
        # (K - β²J)·a = 0 with the program's own β, independent of eigh's accuracy
        residual = (k - md.frequencies[mode] ** 2 * j) @ a
        assert np.max(np.abs(residual)) <= 1e-9 * np.max(np.abs(k)) * scale
        # spring moments per unit reference angle: c_k·(a_k - a_{k+1})
        moments = [c * (a[i] - a[i + 1]) for i, c in enumerate(stiffnesses)]
        assert md.moments[mode] == pytest.approx(moments, abs=1e-8 * max(map(abs, moments)))
        # J-orthogonal to the rigid mode (Σ J·a = 0) and to the other modes
        assert abs(float(np.sum(np.array(inertias) * a))) <= 1e-9 * sum(inertias) * scale
        for other in range(mode):
            b = np.array(md.shapes[other])
            assert abs(a @ j @ b) <= 1e-8 * math.sqrt((a @ j @ a) * (b @ j @ b))


@pytest.mark.parametrize("n", [2, 3, 7, 30])
def test_uniform_chain_closed_form(n: int) -> None:
    """J, c uniform: λⱼ = (4c/J)·sin²(jπ/2n), aᵢ = cos((i - ½)jπ/n)/cos(jπ/2n)."""
    inertia, stiffness = 0.7, 3.0e5
    md = modal(ChainSection(inertias=[inertia] * n, stiffnesses=[stiffness] * (n - 1)))
    for j in range(1, n):
        lam = 4.0 * stiffness / inertia * math.sin(j * math.pi / (2 * n)) ** 2
        assert md.frequencies[j - 1] == pytest.approx(math.sqrt(lam), rel=1e-11)
        shape = [
            math.cos((i + 0.5) * j * math.pi / n) / math.cos(j * math.pi / (2 * n))
            for i in range(n)
        ]
        assert md.shapes[j - 1] == pytest.approx(shape, abs=1e-9)


def test_inline_six_frequencies_and_mode_table(tmp_path: Path) -> None:
    report = run_json(INLINE_SIX, tmp_path)
    got = values(report)
    chain = INLINE_SIX["chain"]
    beta, shapes = own_modes(chain["inertias"], chain["stiffnesses"])
    for j in range(5):
        assert got[f"frequency_{j + 1}"] == pytest.approx(beta[j] / TWO_PI, rel=1e-10)
    assert "frequency_6" not in got  # at most five modes shown
    assert "a = 1 at mass 1)" in section(report, "modes")["title"]
    table = rows(report, "modes")
    assert len(table) == 8
    for i, row in enumerate(table):
        assert row[0].startswith(f"{i + 1}")
        assert ("crank" in row[0]) == (i < 6)
        assert row[1] == pytest.approx(chain["inertias"][i], rel=1e-15)
        for j in range(5):
            assert row[2 + j] == pytest.approx(shapes[j][i] / shapes[j][0], rel=1e-8, abs=1e-9)


# ============================================================ normalisation and nodes


@pytest.mark.parametrize("middle", [1.0, 0.25, 4.0])
def test_symmetric_three_mass_chain(tmp_path: Path, middle: float) -> None:
    """J - c - J₀ - c - J: the antisymmetric mode (1, 0, -1) at β² = c/J has its node on
    the middle mass; the symmetric one (1, -2J/J₀, 1) at β² = c(1/J + 2/J₀)."""
    inertia, stiffness = 1.5, 2.0e5
    data = {
        "problem": "resonance",
        "chain": {"inertias": [inertia, middle, inertia], "stiffnesses": [stiffness, stiffness]},
    }
    got = values(run_json(data, tmp_path))
    anti = math.sqrt(stiffness / inertia)
    sym = math.sqrt(stiffness * (1.0 / inertia + 2.0 / middle))
    first, second = sorted([(anti, [1.0, 0.0, -1.0]), (sym, [1.0, -2.0 * inertia / middle, 1.0])])
    assert got["frequency_1"] == pytest.approx(first[0] / TWO_PI, rel=1e-12)
    assert got["frequency_2"] == pytest.approx(second[0] / TWO_PI, rel=1e-12)
    md = modal(ChainSection(inertias=[inertia, middle, inertia], stiffnesses=[stiffness] * 2))
    assert md.references == [0, 0]
    assert md.shapes[0] == pytest.approx(first[1], abs=1e-12)
    assert md.shapes[1] == pytest.approx(second[1], abs=1e-12)


def test_node_crank_gets_no_excitation(tmp_path: Path) -> None:
    """A single crank on the node of the antisymmetric mode: the geometric sum is 0, so
    the energy balance gives A = 0 and the exact response at ω = β is 0 too (the load
    is orthogonal to the resonant mode; what is left is the finite off-resonant part)."""
    data = {
        "problem": "resonance",
        "chain": {
            "inertias": [1.0, 1.0, 1.0],
            "stiffnesses": [1.0e5, 1.0e5],
            "damping": [2.0, 2.0, 2.0],
            "cranks": [2],
            "firing_angles_deg": [0.0],
        },
        "resonance": {"order": 2.0, "mode": 1, "harmonic_torque": 100.0},
    }
    got = values(run_json(data, tmp_path))
    assert got["geometric_sum"] == pytest.approx(0.0, abs=1e-12)
    assert got["amplitude"] == pytest.approx(0.0, abs=1e-12)
    own = own_exact(data["chain"], 2.0, 100.0, math.sqrt(1.0e5))
    assert got["amplitude_exact"] == pytest.approx(abs(own[0]), rel=1e-9, abs=1e-15)


def test_first_mass_nearly_at_rest_normalises_at_first_crank(tmp_path: Path) -> None:
    """A free-free chain never has an exact node on its end mass (Holzer from that end
    starts at θ₁ = 1), so the brief's "mass 1 is a node" is a huge first inertia: with
    J₁ = 10⁹ the first mass moves ~10⁻⁹ of the others. The shape is then normalised at
    the first crank (mass 2), and without cranks at the largest amplitude."""
    inertias, stiffnesses = [1.0e9, 1.0, 1.0], [1.0e4, 1.0e4]
    beta, shapes = own_modes(inertias, stiffnesses)
    base = {"problem": "resonance", "chain": {"inertias": inertias, "stiffnesses": stiffnesses}}
    with_crank = {
        "problem": "resonance",
        "chain": {**base["chain"], "cranks": [2], "firing_angles_deg": [0.0]},
    }
    report = run_json(with_crank, tmp_path)
    assert "a = 1 at mass 2)" in section(report, "modes")["title"]
    table = rows(report, "modes")
    for j in range(2):
        expected = shapes[j] / shapes[j][1]
        column = [row[2 + j] for row in table]
        assert column[1] == pytest.approx(1.0, abs=1e-14)
        assert column == pytest.approx(list(expected), rel=1e-6, abs=1e-12)
        assert abs(column[0]) < 1e-8
    md = modal(ChainSection(**base["chain"]))
    for j in range(2):
        ref = own_reference(shapes[j], None)
        assert ref != 0
        assert md.references[j] == ref
        assert md.shapes[j] == pytest.approx(list(shapes[j] / shapes[j][ref]), rel=1e-6, abs=1e-12)
    # frequencies: the two light masses on a nearly fixed base, λ² - 3λc + c² = 0 (J = 1)
    c = 1.0e4
    assert np.array(md.frequencies) == pytest.approx(
        np.sqrt([c * (3 - math.sqrt(5)) / 2, c * (3 + math.sqrt(5)) / 2]), rel=1e-8
    )


def test_amplitude_reported_at_the_reference_crank(tmp_path: Path) -> None:
    """Same near-node chain with a harmonic torque on the crank (mass 2): the energy
    balance and the exact response are both the amplitude of mass 2."""
    chain = {
        "inertias": [1.0e9, 1.0, 1.0],
        "stiffnesses": [1.0e4, 1.0e4],
        "damping": [0.0, 0.5, 0.5],
        "cranks": [2],
        "firing_angles_deg": [0.0],
    }
    for mode in (1, 2):
        data = {
            "problem": "resonance",
            "chain": chain,
            "resonance": {"order": 1.0, "mode": mode, "harmonic_torque": 10.0},
        }
        report = run_json(data, tmp_path)
        got = values(report)
        own = own_energy(chain, mode, 1.0, 10.0)
        assert own["ref"] == 1
        assert "A at mass 2" in report["results"]["amplitude"]["label"]
        assert got["amplitude"] == pytest.approx(own["amplitude"], rel=1e-7)
        assert got["amplitude_exact"] == pytest.approx(own["amplitude_exact"], rel=1e-6)
        assert got["max_shaft_torque"] == pytest.approx(max(own["shafts"]), rel=1e-7)


# ============================================================ critical speeds, Campbell


def own_campbell(
    chain: dict[str, Any], orders: list[float], lo: float, hi: float
) -> list[list[Any]]:
    beta, shapes = own_modes(chain["inertias"], chain["stiffnesses"])
    out = []
    for j, b in enumerate(beta):
        f = b / TWO_PI
        a = shapes[j] / shapes[j][own_reference(shapes[j], chain.get("cranks"))]
        for k in orders:
            n = 60.0 * f / k
            if lo <= n <= hi:
                row: list[Any] = [n, k, j + 1, f]
                if chain.get("cranks"):
                    s = own_sum(a, chain["cranks"], chain["firing_angles_deg"], k)
                    row += [abs(s), "main" if own_main(chain["firing_angles_deg"], k) else ""]
                out.append(row)
    return sorted(out, key=lambda r: r[0])


def compare_campbell(table: list[list[Any]], expected: list[list[Any]]) -> None:
    assert len(table) == len(expected)
    for got, want in zip(table, expected, strict=True):
        assert got[0] == pytest.approx(want[0], rel=1e-10)
        assert got[1] == pytest.approx(want[1], rel=1e-15)
        assert got[2] == want[2]
        assert got[3] == pytest.approx(want[3], rel=1e-10)
        if len(want) > 4:
            assert got[4] == pytest.approx(want[4], rel=1e-8, abs=1e-9)
            assert got[5] == want[5]


@pytest.mark.parametrize(
    ("strokes", "lo", "hi"), [(4, 600.0, 3000.0), (4, 100.0, 2.0e5), (2, 100.0, 2.0e5)]
)
def test_inline_six_campbell_default_orders(
    tmp_path: Path, strokes: int, lo: float, hi: float
) -> None:
    """Default orders 0.5 … 12 by 0.5 (four-stroke) or 1 … 12 (two-stroke); firing
    order 1-5-3-6-2-4 makes k = 3, 6, 9, 12 the main orders."""
    data = {
        "problem": "resonance",
        "chain": {**INLINE_SIX["chain"], "strokes": strokes},
        "campbell": {"from_rpm": lo, "to_rpm": hi},
    }
    report = run_json(data, tmp_path)
    step = 0.5 if strokes == 4 else 1.0
    orders = [step * i for i in range(1, int(12 / step) + 1)]
    expected = own_campbell(data["chain"], orders, lo, hi)
    assert expected  # the range holds critical speeds
    table = rows(report, "campbell")
    compare_campbell(table, expected)
    assert {row[1] for row in table} <= set(orders)
    for row in table:
        assert (row[5] == "main") == (row[1] % 3 == 0)
        if row[5] == "main":  # algebraic: Σ aᵢ over the six cranks
            j = row[2] - 1
            beta, shapes = own_modes(data["chain"]["inertias"], data["chain"]["stiffnesses"])
            assert row[4] == pytest.approx(abs(np.sum(shapes[j][:6] / shapes[j][0])), rel=1e-8)


def test_campbell_without_cranks(tmp_path: Path) -> None:
    chain = {"inertias": [2.0, 0.3, 0.9, 0.1], "stiffnesses": [5.0e4, 2.0e5, 8.0e3]}
    data = {
        "problem": "resonance",
        "chain": chain,
        "campbell": {"from_rpm": 50.0, "to_rpm": 40000.0, "orders": [0.5, 1.0, 2.5, 7.0]},
    }
    report = run_json(data, tmp_path)
    assert len(section(report, "campbell")["columns"]) == 4
    compare_campbell(
        rows(report, "campbell"), own_campbell(chain, [0.5, 1.0, 2.5, 7.0], 50.0, 40000.0)
    )


def test_130_hz_reference(tmp_path: Path) -> None:
    """Brief §9: a 130 Hz mode has its order-4.5 critical speed at 60·130/4.5 = 1733.3 rpm.
    Two masses J₁, J₂ on c: β² = c·(1/J₁ + 1/J₂)."""
    j1, j2 = 0.8, 2.5
    c = (TWO_PI * 130.0) ** 2 / (1.0 / j1 + 1.0 / j2)
    data = {
        "problem": "resonance",
        "chain": {"inertias": [j1, j2], "stiffnesses": [c]},
        "campbell": {"from_rpm": 1000.0, "to_rpm": 3000.0, "orders": [3.0, 4.5, 6.0]},
        "resonance": {"order": 4.5},
        "measured": [{"order": 4.5, "speed_rpm": 1500.0}, {"order": 3.0, "speed_rpm": 2100.0}],
    }
    report = run_json(data, tmp_path)
    got = values(report)
    assert got["frequency_1"] == pytest.approx(130.0, rel=1e-12)
    assert got["resonance_frequency"] == pytest.approx(130.0, rel=1e-12)
    assert got["critical_speed_rpm"] == pytest.approx(1733.3333333333333, rel=1e-12)
    assert round(got["critical_speed_rpm"], 1) == 1733.3
    table = rows(report, "campbell")
    assert [r[1] for r in table] == [6.0, 4.5, 3.0]
    assert [r[0] for r in table] == pytest.approx([1300.0, 60 * 130 / 4.5, 2600.0], rel=1e-12)
    # the measured rows point at mode 1 and its critical speed for their order
    measured = rows(report, "measured")
    assert measured[0][5] == 1 and measured[1][5] == 1
    assert measured[0][6] == pytest.approx(130.0, rel=1e-12)
    assert measured[0][7] == pytest.approx(60 * 130 / 4.5, rel=1e-12)
    assert measured[1][7] == pytest.approx(2600.0, rel=1e-12)


def test_seed_measurements(tmp_path: Path) -> None:
    """Seed 003 run-up: order 4.5 at 1500 and 1800 rpm → 112.5 and 135 Hz (the seed's
    130 Hz lies between, at 1733.3 rpm); order 3 at 2100 rpm → 105 Hz (seed: 110 Hz,
    which would need 2200 rpm)."""
    data = {
        "problem": "resonance",
        "measured": [
            {"order": 4.5, "speed_rpm": 1500.0},
            {"order": 4.5, "speed_rpm": 1800.0, "frequency_hz": 130.0},
            {"order": 3.0, "speed_rpm": 2100.0, "frequency_hz": 110.0},
        ],
    }
    report = run_json(data, tmp_path)
    got = values(report)
    assert got["measured_frequency_1"] == pytest.approx(1500 * 4.5 / 60, rel=1e-14)
    assert got["measured_frequency_1"] == pytest.approx(112.5, rel=1e-14)
    assert got["measured_frequency_2"] == pytest.approx(135.0, rel=1e-14)
    assert got["measured_frequency_3"] == pytest.approx(105.0, rel=1e-14)
    assert got["stated_speed_2"] == pytest.approx(60 * 130 / 4.5, rel=1e-14)
    assert got["stated_speed_3"] == pytest.approx(2200.0, rel=1e-14)
    assert "stated_speed_1" not in got
    assert 112.5 < 130.0 < 135.0
    table = rows(report, "measured")
    assert table[1][4] == pytest.approx(130.0 / 135.0 - 1.0, rel=1e-12)
    assert table[2][4] == pytest.approx(110.0 / 105.0 - 1.0, rel=1e-12)
    assert table[0][3] == "" and table[0][4] == ""


# ============================================================ geometric sum, main orders

INLINE_FOUR: dict[str, Any] = {
    "inertias": [0.03, 0.03, 0.03, 0.03, 0.8],
    "stiffnesses": [4.0e5, 4.0e5, 4.0e5, 9.0e5],
    "damping": [0.8, 0.8, 0.8, 0.8, 0.0],
    "cranks": [1, 2, 3, 4],
    "firing_angles_deg": [0.0, 180.0, 540.0, 360.0],
}


@pytest.mark.parametrize("order", [0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 4.5, 6.0, 8.0])
@pytest.mark.parametrize("mode", [1, 2])
def test_inline_four_geometric_sum(tmp_path: Path, order: float, mode: int) -> None:
    """Firing 0, 180, 540, 360°: k·δ agree mod 360° exactly for k = 2, 4, 6, …, where
    the geometric sum becomes Σ aᵢ (main orders)."""
    data = {
        "problem": "resonance",
        "chain": INLINE_FOUR,
        "resonance": {"order": order, "mode": mode, "harmonic_torque": 40.0},
    }
    got = values(run_json(data, tmp_path))
    own = own_energy(INLINE_FOUR, mode, order, 40.0)
    a = own["shape"]
    main = order % 2 == 0
    assert got["main_order"] is main
    assert own_main(INLINE_FOUR["firing_angles_deg"], order) is main
    assert got["algebraic_sum"] == pytest.approx(float(np.sum(a[:4])), rel=1e-9, abs=1e-12)
    assert got["geometric_sum"] == pytest.approx(own["geometric_sum"], rel=1e-9, abs=1e-12)
    if main:
        assert got["geometric_sum"] == pytest.approx(abs(got["algebraic_sum"]), rel=1e-9)
    assert got["amplitude"] == pytest.approx(own["amplitude"], rel=1e-9, abs=1e-15)
    assert got["amplitude_exact"] == pytest.approx(own["amplitude_exact"], rel=1e-7)
    assert got["modal_damping"] == pytest.approx(0.8 * float(np.sum(a[:4] ** 2)), rel=1e-9)


def test_inline_four_campbell_main_orders(tmp_path: Path) -> None:
    orders = [0.5 * i for i in range(1, 25)]
    data = {
        "problem": "resonance",
        "chain": INLINE_FOUR,
        "campbell": {"from_rpm": 1.0, "to_rpm": 1.0e6, "orders": orders},
    }
    report = run_json(data, tmp_path)
    table = rows(report, "campbell")
    assert len(table) == 4 * len(orders)  # every mode and order is inside the range
    compare_campbell(table, own_campbell(INLINE_FOUR, orders, 1.0, 1.0e6))
    assert {r[1] for r in table if r[5] == "main"} == {2.0, 4.0, 6.0, 8.0, 10.0, 12.0}


def test_inline_six_firing_order_geometric_sums(tmp_path: Path) -> None:
    """1-5-3-6-2-4 → δ = 0, 480, 240, 600, 120, 360° for cylinders 1…6. Order 4.5 with
    mode 2 (the reference case) and the main order 3 with mode 1."""
    for order, mode in [(4.5, 2), (3.0, 1), (6.0, 2), (1.5, 1)]:
        data = dict(INLINE_SIX, resonance={"order": order, "mode": mode, "harmonic_torque": 50.0})
        got = values(run_json(data, tmp_path))
        own = own_energy(INLINE_SIX["chain"], mode, order, 50.0)
        assert got["geometric_sum"] == pytest.approx(own["geometric_sum"], rel=1e-9)
        assert got["main_order"] is (order % 3 == 0)
        if order % 3 == 0:
            assert got["geometric_sum"] == pytest.approx(float(np.sum(own["shape"][:6])), rel=1e-9)
        assert got["critical_speed_rpm"] == pytest.approx(
            60 * own["beta"] / TWO_PI / order, rel=1e-10
        )


# ============================================================ energy method against exact


def test_inline_six_energy_and_exact(tmp_path: Path) -> None:
    data = dict(INLINE_SIX)
    report = run_json(data, tmp_path)
    got = values(report)
    own = own_energy(data["chain"], 2, 4.5, 50.0)
    assert got["amplitude"] == pytest.approx(own["amplitude"], rel=1e-9)
    assert got["amplitude_exact"] == pytest.approx(own["amplitude_exact"], rel=1e-8)
    assert got["max_shaft_torque"] == pytest.approx(max(own["shafts"]), rel=1e-9)
    assert got["max_shaft_torque_exact"] == pytest.approx(max(own["exact_shafts"]), rel=1e-8)
    shafts = rows(report, "shafts")
    assert len(shafts) == 7
    for k, row in enumerate(shafts):
        assert row[0] == f"{k + 1}–{k + 2}"
        assert row[1] == data["chain"]["stiffnesses"][k]
        assert row[2] == pytest.approx(own["shafts"][k], rel=1e-8)
        assert row[3] == pytest.approx(own["exact_shafts"][k], rel=1e-8)
    methods = method_values(report, "resonance")
    energy = methods["energy balance, seed (5)"]
    exact = methods["exact forced response at ω = β"]
    assert energy["amplitude"] == pytest.approx(own["amplitude"], rel=1e-9)
    assert exact["amplitude"] == pytest.approx(own["amplitude_exact"], rel=1e-8)


def test_peak_over_speed_against_own_search(tmp_path: Path) -> None:
    """The largest |X_ref(ω)| near β₂ by a dense grid and a bounded scalar search."""
    report = run_json(INLINE_SIX, tmp_path)
    chain = INLINE_SIX["chain"]
    beta, _ = own_modes(chain["inertias"], chain["stiffnesses"])
    b = beta[1]

    def amplitude(w: float) -> float:
        return float(abs(own_exact(chain, 4.5, 50.0, w)[0]))

    grid = np.linspace(0.9 * b, 1.1 * b, 4001)
    best = grid[int(np.argmax([amplitude(w) for w in grid]))]
    step = grid[1] - grid[0]
    found = minimize_scalar(
        lambda w: -amplitude(w),
        bounds=(best - step, best + step),
        method="bounded",
        options={"xatol": 1e-10 * b},
    )
    peak = -found.fun
    got = method_values(report, "resonance")["exact, peak over speed"]
    assert got["amplitude"] == pytest.approx(peak, rel=1e-8)
    assert peak >= amplitude(b) * (1 - 1e-12)


def test_energy_and_exact_converge_linearly_in_damping(tmp_path: Path) -> None:
    """Generic chain (damping on every mass, cranks 90° apart): the free mode shape is
    only the zero-damping limit, so (A_energy - A_exact)/A_exact ∝ ξ."""
    base = {
        "inertias": [0.5, 0.3, 1.0],
        "stiffnesses": [1.0e5, 2.0e5],
        "cranks": [1, 2],
        "firing_angles_deg": [0.0, 90.0],
    }
    ratios = []
    for scale in [1.0, 0.1, 0.01, 0.001]:
        chain = {**base, "damping": [5.0 * scale, 3.0 * scale, 1.0 * scale]}
        data = {
            "problem": "resonance",
            "chain": chain,
            "resonance": {"order": 1.0, "mode": 1, "harmonic_torque": 100.0},
        }
        got = values(run_json(data, tmp_path))
        own = own_energy(chain, 1, 1.0, 100.0)
        assert got["amplitude"] == pytest.approx(own["amplitude"], rel=1e-9)
        assert got["amplitude_exact"] == pytest.approx(own["amplitude_exact"], rel=1e-8)
        difference = got["amplitude"] / got["amplitude_exact"] - 1.0
        ratios.append(difference / scale)
    assert abs(ratios[0]) > 1e-4  # a genuine first-order effect here
    for r in ratios[1:]:
        assert r == pytest.approx(ratios[0], rel=0.01)


def test_energy_and_exact_converge_inline_six(tmp_path: Path) -> None:
    """The reference engine: the difference shrinks at least in proportion to ξ."""
    differences = []
    scales = [1.0, 0.1, 0.01]
    for scale in scales:
        chain = {**INLINE_SIX["chain"], "damping": [scale] * 6 + [0.0, 0.0]}
        data = dict(INLINE_SIX, chain=chain)
        got = values(run_json(data, tmp_path))
        own = own_energy(chain, 2, 4.5, 50.0)
        assert got["amplitude"] == pytest.approx(own["amplitude"], rel=1e-9)
        assert got["amplitude_exact"] == pytest.approx(own["amplitude_exact"], rel=1e-7)
        assert got["amplitude"] * scale == pytest.approx(own["amplitude"] * scale, rel=1e-9)
        differences.append(abs(got["amplitude"] / got["amplitude_exact"] - 1.0))
    assert differences[0] < 1e-3
    for d, s in zip(differences[1:], scales[1:], strict=True):
        assert d <= 1.5 * differences[0] * s / scales[0] + 1e-12


def test_two_mass_crank_by_hand(tmp_path: Path) -> None:
    """β² = c(1/J₁ + 1/J₂); a = (1, -J₁/J₂); damping only on the crank: A = M/(β·ξ₁),
    equal to the exact response (the load and the damper sit on the same mass)."""
    j1, j2, c, xi, m = 0.4, 1.6, 2.5e5, 12.0, 80.0
    data = {
        "problem": "resonance",
        "chain": {
            "inertias": [j1, j2],
            "stiffnesses": [c],
            "damping": [xi, 0.0],
            "cranks": [1],
            "firing_angles_deg": [30.0],
        },
        "resonance": {"order": 2.5, "harmonic_torque": m},
    }
    got = values(run_json(data, tmp_path))
    beta = math.sqrt(c * (1 / j1 + 1 / j2))
    assert got["amplitude"] == pytest.approx(m / (beta * xi), rel=1e-12)
    assert got["amplitude_exact"] == pytest.approx(m / (beta * xi), rel=1e-10)
    assert got["max_shaft_torque"] == pytest.approx(c * (1 + j1 / j2) * m / (beta * xi), rel=1e-12)
    assert got["geometric_sum"] == pytest.approx(1.0, rel=1e-14)
    assert got["main_order"] is True  # one crank: always "all phases equal"


def test_tiny_damping_gives_large_finite_amplitude(tmp_path: Path) -> None:
    j1, j2, c, m = 0.5, 2.0, 1.0e5, 100.0
    data = {
        "problem": "resonance",
        "chain": {
            "inertias": [j1, j2],
            "stiffnesses": [c],
            "damping": [1e-9, 0.0],
            "cranks": [1],
            "firing_angles_deg": [0.0],
        },
        "resonance": {"order": 1.0, "harmonic_torque": m},
    }
    got = values(run_json(data, tmp_path))
    assert got["amplitude"] == pytest.approx(m / (500.0 * 1e-9), rel=1e-10)
    assert got["amplitude_exact"] == pytest.approx(m / (500.0 * 1e-9), rel=1e-5)


# ============================================================ undamped resonance: exit 3


@pytest.mark.parametrize(
    ("chain", "mode"),
    [
        (
            {
                "inertias": [0.5, 2.0],
                "stiffnesses": [1.0e5],
                "damping": [0.0, 0.0],
                "cranks": [1],
                "firing_angles_deg": [0.0],
            },
            1,
        ),
        # damping only on the middle mass, the node of the antisymmetric mode 1
        (
            {
                "inertias": [1.0, 1.0, 1.0],
                "stiffnesses": [1.0e5, 1.0e5],
                "damping": [0.0, 5.0, 0.0],
                "cranks": [1, 3],
                "firing_angles_deg": [0.0, 180.0],
            },
            1,
        ),
    ],
    ids=["no-damping", "damper-on-node"],
)
def test_undamped_resonance_exits_3(tmp_path: Path, chain: dict[str, Any], mode: int) -> None:
    data = {
        "problem": "resonance",
        "chain": chain,
        "resonance": {"order": 1.0, "mode": mode, "harmonic_torque": 100.0},
    }
    report = run_json(data, tmp_path, code=3)
    assert report["status"] == "no-answer"
    assert "undamped" in report["message"]
    got = values(report)
    assert got["modal_damping"] == pytest.approx(0.0, abs=1e-20)
    assert "amplitude" not in got
    path = tmp_path / "case.toml"
    text = invoke(path)
    assert text.exit_code == 3
    assert "no answer" in text.stderr
    assert_no_traceback(text)
    assert not re.search(r"\b(nan|inf)\b", text.stdout, re.IGNORECASE)


def test_damper_on_node_still_damps_symmetric_mode(tmp_path: Path) -> None:
    """Same chain, mode 2 = (1, -2, 1) at β² = 3c/J: Σξa² = 5·4, cranks in phase
    (δ = 0, 180° at order 2): A = M·|1 + 1|/(β·20)."""
    chain = {
        "inertias": [1.0, 1.0, 1.0],
        "stiffnesses": [1.0e5, 1.0e5],
        "damping": [0.0, 5.0, 0.0],
        "cranks": [1, 3],
        "firing_angles_deg": [0.0, 180.0],
    }
    data = {
        "problem": "resonance",
        "chain": chain,
        "resonance": {"order": 2.0, "mode": 2, "harmonic_torque": 100.0},
    }
    got = values(run_json(data, tmp_path))
    beta = math.sqrt(3.0e5)
    assert got["modal_damping"] == pytest.approx(20.0, rel=1e-12)
    assert got["amplitude"] == pytest.approx(100.0 * 2.0 / (beta * 20.0), rel=1e-12)
    own = own_exact(chain, 2.0, 100.0, beta)
    assert got["amplitude_exact"] == pytest.approx(abs(own[0]), rel=1e-9)


# ============================================================ Floquet / Mathieu


def overdamped_radius(a: float, c: float) -> float:
    """q = 0: multipliers e^(πr), r = -c/2 ± √(c²/4 - a)."""
    return math.exp(math.pi * (-c / 2 + math.sqrt(c * c / 4 - a)))


@pytest.mark.parametrize("c", [0.0, 0.1, 0.6, 2.0])
def test_floquet_q_zero_closed_form(tmp_path: Path, c: float) -> None:
    """q = 0 is the damped oscillator: ρ = e^(-cπ/2) and trace = 2e^(-cπ/2)cos(π√(a - c²/4))
    for a > c²/4; below, ρ = e^(π(-c/2 + √(c²/4 - a))), = e^(π√-a) undamped."""
    points = [[2.0, 0.0], [0.3 + c * c / 4, 0.0], [-0.5, 0.0], [-3.0, 0.0], [-100.0, 0.0]]
    if c >= 1.0:
        points.append([c * c / 8, 0.0])  # overdamped with a > 0
    report = run_json(mathieu_case(points, c), tmp_path)
    got = values(report)
    table = rows(report, "floquet_points")
    for k, (a, _) in enumerate(points):
        if a > c * c / 4:
            rho = math.exp(-c * math.pi / 2)
            trace = 2 * rho * math.cos(math.pi * math.sqrt(a - c * c / 4))
            assert table[k][2] == pytest.approx(trace, rel=1e-8, abs=1e-10)
            assert got[f"stability_{k + 1}"] == "stable"  # |trace| < 2e^(-cπ/2) ≤ 1 + e^(-cπ)
        else:
            rho = overdamped_radius(a, c)
            r1, r2 = -c / 2 + math.sqrt(c * c / 4 - a), -c / 2 - math.sqrt(c * c / 4 - a)
            trace = math.exp(math.pi * r1) + math.exp(math.pi * r2)
            assert table[k][2] == pytest.approx(trace, rel=1e-8)
            assert got[f"stability_{k + 1}"] == ("unstable" if rho > 1 else "stable")
        assert got[f"floquet_radius_{k + 1}"] == pytest.approx(rho, rel=1e-8)
        assert table[k][4] == pytest.approx(rho, rel=1e-8)
        if abs(a) < 10:
            assert table[k][3] == pytest.approx(math.exp(-c * math.pi), rel=1e-8)
    assert got["floquet_radius_5"] == pytest.approx(overdamped_radius(-100.0, c), rel=1e-8)
    if c == 0:
        assert got["floquet_radius_5"] == pytest.approx(math.exp(10 * math.pi), rel=1e-8)


def test_floquet_undamped_q_zero_boundary(tmp_path: Path) -> None:
    """c = 0, q = 0, a = m² (m = 1, 2): trace = 2cos(mπ) = ±2, the boundary."""
    got = values(run_json(mathieu_case([[1.0, 0.0], [4.0, 0.0], [2.0, 0.0]]), tmp_path))
    assert got["stability_1"] == "boundary"
    assert got["stability_2"] == "boundary"
    assert got["stability_3"] == "stable"
    for k in (1, 2, 3):
        assert got[f"floquet_radius_{k}"] == pytest.approx(1.0, rel=1e-8)


@pytest.mark.parametrize("q", [0.05, 0.1, 0.2])
def test_first_tongue_transition_curves(tmp_path: Path, q: float) -> None:
    """Undamped first tongue between a = 1 - q - q²/8 + q³/64 and 1 + q - q²/8 - q³/64:
    points 0.05·q² inside are unstable, 0.05·q² outside stable."""
    upper = 1 + q - q * q / 8 - q**3 / 64
    lower = 1 - q - q * q / 8 + q**3 / 64
    margin = 0.05 * q * q
    points = [
        [upper - margin, q],
        [lower + margin, q],
        [upper + margin, q],
        [lower - margin, q],
        [1.0, q],
    ]
    expected = ["unstable", "unstable", "stable", "stable", "unstable"]
    got = values(run_json(mathieu_case(points), tmp_path))
    trace, _ = monodromy([p[0] for p in points], [p[1] for p in points], 0.0)
    for k, want in enumerate(expected):
        assert (abs(trace[k]) > 2) == (want == "unstable")  # own check of the series
        assert got[f"stability_{k + 1}"] == want
        if want == "stable":
            assert got[f"floquet_radius_{k + 1}"] == pytest.approx(1.0, rel=1e-8)
        else:
            assert got[f"floquet_radius_{k + 1}"] > 1.0
    # the largest growth sits in the middle of the tongue: ρ ≈ e^(πq/2)
    assert got["floquet_radius_5"] == pytest.approx(math.exp(math.pi * q / 2), rel=0.02)


def test_damped_threshold_and_first_approximation(tmp_path: Path) -> None:
    """With damping the tongue lifts off the a axis: at a = 1 instability needs q > c
    (first approximation q² > (a - 1)² + c²)."""
    c = 0.02
    points = [[1.0, 0.01], [1.0, 0.04], [1.0, 0.1], [1.05, 0.02], [0.9, 0.3], [1.3, 0.05]]
    report = run_json(mathieu_case(points, c), tmp_path)
    got = values(report)
    table = rows(report, "floquet_points")
    trace, det = monodromy([p[0] for p in points], [p[1] for p in points], c)
    edge = 1 + math.exp(-c * math.pi)
    for k, (a, q) in enumerate(points):
        first = "unstable" if q * q > (a - 1) ** 2 + c * c else "stable"
        assert table[k][6] == first
        own = "unstable" if abs(trace[k]) > edge else "stable"
        assert own == first  # these points are far enough from the edge for both
        assert got[f"stability_{k + 1}"] == own
        assert table[k][2] == pytest.approx(trace[k], rel=1e-8, abs=1e-10)
        assert table[k][3] == pytest.approx(math.exp(-c * math.pi), rel=1e-8)  # Liouville
        assert got[f"floquet_radius_{k + 1}"] == pytest.approx(radius(trace[k], det[k]), rel=1e-8)


def _case_number(low: float, high: float) -> st.SearchStrategy[float]:
    """A float a case file may hold: 0, or at least 1e-18 in magnitude (the floor)."""
    floats = st.floats(min_value=low, max_value=high, allow_nan=False)
    return floats.map(lambda x: 0.0 if abs(x) < 1e-18 else x)


points_strategy = st.lists(
    st.tuples(_case_number(-5.0, 12.0), _case_number(-6.0, 6.0)),
    min_size=1,
    max_size=4,
)


@settings(max_examples=8, deadline=None, derandomize=True)
@given(points=points_strategy, c=_case_number(0.0, 1.5))
def test_random_floquet_points_against_own_monodromy(
    points: list[tuple[float, float]], c: float
) -> None:
    """Each point and its mirror (a, -q) in one run: the mirror is the same equation
    shifted by half a period, so it has the same multipliers."""
    everything = [[a, q] for a, q in points] + [[a, -q] for a, q in points]
    trace, det = monodromy([p[0] for p in everything], [p[1] for p in everything], c)
    edge = 1 + math.exp(-c * math.pi)
    with tempfile.TemporaryDirectory() as folder:
        report = run_json(mathieu_case(everything, c), Path(folder))
    got = values(report)
    table = rows(report, "floquet_points")
    for k, (a, q) in enumerate(everything):
        rho = radius(trace[k], det[k])
        assert got[f"floquet_radius_{k + 1}"] == pytest.approx(rho, rel=1e-7)
        liouville = math.exp(-c * math.pi)
        assert table[k][3] == pytest.approx(liouville, rel=1e-7, abs=1e-7 * rho * rho)
        assert table[k][6] == ("unstable" if q * q > (a - 1) ** 2 + c * c else "stable")
        if abs(abs(trace[k]) - edge) > 1e-6 * edge:
            assert got[f"stability_{k + 1}"] == ("unstable" if abs(trace[k]) > edge else "stable")
    n = len(points)
    for k in range(n):
        assert got[f"floquet_radius_{k + n + 1}"] == pytest.approx(
            got[f"floquet_radius_{k + 1}"], rel=1e-7
        )


@pytest.mark.parametrize(
    ("c", "a_from", "a_to", "q_to", "columns", "rows_"),
    [(0.1, 0.0, 5.0, 2.0, 51, 11), (0.0, -1.0, 10.0, 4.0, 23, 9), (0.5, -2.0, 6.0, 6.0, 17, 13)],
)
def test_chart_marks_against_own_monodromy_and_points(
    tmp_path: Path, c: float, a_from: float, a_to: float, q_to: float, columns: int, rows_: int
) -> None:
    a_values = np.linspace(a_from, a_to, columns)
    q_values = np.linspace(0.0, q_to, rows_)
    grid_a, grid_q = np.meshgrid(a_values, q_values)
    trace, _ = monodromy(grid_a, grid_q, c, rtol=1e-10)
    trace = trace.reshape(grid_a.shape)
    edge = 1 + math.exp(-c * math.pi)
    # eight grid cells as points too: the chart and the point verdicts must agree
    rng = np.random.default_rng(3)
    cells = [
        (int(i), int(j))
        for i, j in zip(rng.integers(0, rows_, 8), rng.integers(0, columns, 8), strict=True)
    ]
    points = [[float(a_values[j]), float(q_values[i])] for i, j in cells]
    report = run_json(
        mathieu_case(
            points, c, chart=True, a_from=a_from, a_to=a_to, q_to=q_to, columns=columns, rows=rows_
        ),
        tmp_path,
    )
    chart = rows(report, "chart")
    assert len(chart) == rows_
    assert [r[0] for r in chart] == pytest.approx(list(q_values[::-1]), abs=1e-12)
    checked = 0
    for line, row in enumerate(chart):
        i = rows_ - 1 - line
        marks = row[1]
        assert len(marks) == columns and set(marks) <= {"·", "█"}
        for j, mark in enumerate(marks):
            if abs(abs(trace[i, j]) - edge) < 1e-4 * edge:
                continue  # too near the edge for the chart's RK4
            checked += 1
            assert mark == ("█" if abs(trace[i, j]) > edge else "·"), (a_values[j], q_values[i])
    assert checked > 0.9 * rows_ * columns
    got = values(report)
    for k, (i, j) in enumerate(cells):
        verdict = got[f"stability_{k + 1}"]
        if verdict == "boundary" or abs(abs(trace[i, j]) - edge) < 1e-4 * edge:
            continue
        mark = chart[rows_ - 1 - i][1][j]
        assert mark == ("█" if verdict == "unstable" else "·")


def test_floquet_methods_table_reference(tmp_path: Path) -> None:
    points = [[1.0, 0.5], [4.0, 0.2], [-1.0, 1.0]]
    report = run_json(mathieu_case(points, 0.1), tmp_path)
    trace, det = monodromy([1.0, 4.0, -1.0], [0.5, 0.2, 1.0], 0.1)
    methods = method_values(report, "floquet")
    assert set(methods) >= {"RK4, 32 steps", "RK4, 256 steps", "DOP853 rtol 1e-12"}
    for k in range(3):
        rho = radius(trace[k], det[k])
        assert methods["DOP853 rtol 1e-12"][f"floquet_radius_{k + 1}"] == pytest.approx(
            rho, rel=1e-8
        )
        assert methods["RK4, 256 steps"][f"floquet_radius_{k + 1}"] == pytest.approx(rho, rel=1e-5)


def test_floquet_det_column_strongly_unstable_point(tmp_path: Path) -> None:
    report = run_json(mathieu_case([[-100.0, 0.0], [-100.0, 100.0]]), tmp_path)
    table = rows(report, "floquet_points")
    for row in table:
        assert row[3] == pytest.approx(1.0, rel=1e-6)  # Liouville: det = e^(-cπ) = 1


# ============================================================ bad input: exit 2


GOOD_CHAIN = {
    "inertias": [0.5, 0.3, 1.0],
    "stiffnesses": [1.0e5, 2.0e5],
    "damping": [1.0, 1.0, 0.0],
    "cranks": [1, 2],
    "firing_angles_deg": [0.0, 180.0],
}


def chain_with(**change: Any) -> dict[str, Any]:
    chain = {k: v for k, v in {**GOOD_CHAIN, **change}.items() if v is not None}
    return {"problem": "resonance", "chain": chain}


BAD: dict[str, tuple[Any, str]] = {
    "stiffness-count": (chain_with(stiffnesses=[1.0e5]), "chain.stiffnesses"),
    "stiffness-count-long": (chain_with(stiffnesses=[1.0e5] * 3), "chain.stiffnesses"),
    "negative-inertia": (chain_with(inertias=[0.5, -0.3, 1.0]), "chain.inertias[1]"),
    "zero-inertia": (chain_with(inertias=[0.0, 0.3, 1.0]), "chain.inertias[0]"),
    "zero-stiffness": (chain_with(stiffnesses=[1.0e5, 0.0]), "chain.stiffnesses[1]"),
    "one-mass": (chain_with(inertias=[1.0], stiffnesses=[]), "chain.inertias"),
    "201-masses": (
        chain_with(
            inertias=[1.0] * 201,
            stiffnesses=[1.0] * 200,
            damping=None,
            cranks=None,
            firing_angles_deg=None,
        ),
        "chain.inertias",
    ),
    "crank-0": (chain_with(cranks=[0, 2]), "chain.cranks[0]"),
    "crank-beyond-n": (chain_with(cranks=[1, 4]), "chain.cranks[1]"),
    "crank-twice": (chain_with(cranks=[2, 2]), "chain.cranks"),
    "angles-count": (chain_with(firing_angles_deg=[0.0, 180.0, 360.0]), "chain.firing_angles_deg"),
    "cranks-without-angles": (chain_with(firing_angles_deg=None), "firing_angles_deg"),
    "angles-without-cranks": (chain_with(cranks=None), "cranks"),
    "damping-count": (chain_with(damping=[1.0, 1.0]), "chain.damping"),
    "negative-damping": (chain_with(damping=[1.0, -1.0, 0.0]), "chain.damping[1]"),
    "strokes-3": (chain_with(strokes=3), "chain.strokes"),
    "order-1.3": ({**chain_with(), "resonance": {"order": 1.3}}, "resonance.order"),
    "order-0": ({**chain_with(), "resonance": {"order": 0.0}}, "resonance.order"),
    "mode-n": ({**chain_with(), "resonance": {"order": 1.0, "mode": 3}}, "resonance.mode"),
    "mode-0": ({**chain_with(), "resonance": {"order": 1.0, "mode": 0}}, "resonance.mode"),
    "torque-without-damping": (
        {**chain_with(damping=None), "resonance": {"order": 1.0, "harmonic_torque": 10.0}},
        "chain.damping",
    ),
    "torque-without-cranks": (
        {
            **chain_with(cranks=None, firing_angles_deg=None),
            "resonance": {"order": 1.0, "harmonic_torque": 10.0},
        },
        "chain.cranks",
    ),
    "campbell-without-chain": (
        {
            "problem": "resonance",
            "campbell": {"from_rpm": 100.0, "to_rpm": 200.0},
            "measured": [{"order": 1.0, "speed_rpm": 100.0}],
        },
        "campbell",
    ),
    "resonance-without-chain": (
        {"problem": "resonance", "resonance": {"order": 1.0}, "mathieu": {"points": [[1.0, 0.1]]}},
        "resonance",
    ),
    "to-rpm-equal": (
        {**chain_with(), "campbell": {"from_rpm": 100.0, "to_rpm": 100.0}},
        "campbell.to_rpm",
    ),
    "to-rpm-below": (
        {**chain_with(), "campbell": {"from_rpm": 100.0, "to_rpm": 50.0}},
        "campbell.to_rpm",
    ),
    "campbell-order-1.3": (
        {**chain_with(), "campbell": {"from_rpm": 100.0, "to_rpm": 500.0, "orders": [1.0, 1.3]}},
        "campbell.orders[1]",
    ),
    "mathieu-3-numbers": (
        mathieu_case([[1.0, 0.1]]) | {"mathieu": {"points": [[1.0, 0.1, 0.2]]}},
        "mathieu.points[0]",
    ),
    "mathieu-nothing": ({"problem": "resonance", "mathieu": {"damping": 0.1}}, "mathieu.points"),
    "mathieu-negative-damping": (mathieu_case([[1.0, 0.1]], -0.1), "mathieu.damping"),
    "mathieu-a-range": (mathieu_case([], chart=True, a_from=2.0, a_to=1.0), "mathieu.a_to"),
    "mathieu-beyond-100": (mathieu_case([[101.0, 0.1]]), "mathieu.points[0]"),
    "measured-zero-speed": (
        {"problem": "resonance", "measured": [{"order": 1.0, "speed_rpm": 0.0}]},
        "measured",
    ),
    "unknown-key": (chain_with(inertia=[1.0, 2.0]), "chain.inertia"),
    "nothing-to-do": ({"problem": "resonance"}, "chain"),
    "empty": ("", "problem"),
    "nan-inertia": (
        'problem = "resonance"\n[chain]\ninertias = [nan, 1.0]\nstiffnesses = [1.0e5]\n',
        "chain.inertias[0]",
    ),
    "inf-stiffness": (
        'problem = "resonance"\n[chain]\ninertias = [1.0, 1.0]\nstiffnesses = [inf]\n',
        "chain.stiffnesses[0]",
    ),
    # "4.5" is a dimensionless quantity string (issue 9); a word is refused.
    "string-order": ({**chain_with(), "resonance": {"order": "four"}}, "resonance.order"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_exits_2_naming_the_field(tmp_path: Path, name: str) -> None:
    data, where = BAD[name]
    path = tmp_path / "case.toml"
    path.write_text(data if isinstance(data, str) else toml_dumps(data), encoding="utf-8")
    result = invoke(path)
    assert_no_traceback(result)
    assert result.exit_code == 2, result.stdout + result.stderr
    assert where in result.stderr, result.stderr
    assert result.stdout.strip() == ""


def test_bad_input_console_script(tmp_path: Path) -> None:
    path = tmp_path / "case.toml"
    path.write_text(toml_dumps(chain_with(cranks=[0, 2])), encoding="utf-8")
    proc = subprocess.run(
        [str(Path(sys.executable).parent / "mdcalc"), "resonance", str(path), "--json"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 2
    assert "chain.cranks[0]" in proc.stderr
    assert "Traceback" not in proc.stderr
    assert json.loads(proc.stdout)["status"] == "input-error"  # the record of run --json


# ============================================================ extremes: finite output


def three_mass_closed_form(j: list[float], c: list[float]) -> tuple[float, float]:
    """β₁, β₂ of J₁-c₁-J₂-c₂-J₃: λ² - sλ + p = 0."""
    s = c[0] * (1 / j[0] + 1 / j[1]) + c[1] * (1 / j[1] + 1 / j[2])
    p = c[0] * c[1] * (j[0] + j[1] + j[2]) / (j[0] * j[1] * j[2])
    big = (s + math.sqrt(s * s - 4 * p)) / 2
    return math.sqrt(p / big), math.sqrt(big)


def run_both(data: dict[str, Any], folder: Path) -> dict[str, Any]:
    """Solve once in-process; check both the JSON and the text report for NaN/inf."""
    path = folder / "case.toml"
    path.write_text(toml_dumps(data), encoding="utf-8")
    report = run_case(path, expected_problem="resonance")
    assert report.status == "ok", report.message
    document = strict_json(to_json(report))
    walk_finite(document)
    buffer = io.StringIO()
    render_rich(report, Console(file=buffer, width=140, highlight=False))
    text = buffer.getvalue()
    assert not re.search(r"\b(nan|inf|infinity)\b", text, re.IGNORECASE), text
    return document


@pytest.mark.parametrize(
    ("inertias", "stiffnesses"),
    [
        ([1.0, 0.5, 2.0], [1.0e12, 1.0e3]),  # stiffness ratio 1e9
        ([1.0, 0.5, 2.0], [1.0e3, 1.0e12]),
        ([1.0, 1.0e-9, 1.0e6], [1.0e5, 1.0e5]),  # a tiny inertia next to 1e6
        ([1.0e6, 1.0e-9, 1.0], [1.0e5, 1.0e5]),
    ],
)
def test_extreme_chains_closed_form_and_finite(
    tmp_path: Path, inertias: list[float], stiffnesses: list[float]
) -> None:
    chain = {
        "inertias": inertias,
        "stiffnesses": stiffnesses,
        "damping": [1.0, 1.0, 1.0],
        "cranks": [1, 2, 3],
        "firing_angles_deg": [0.0, 240.0, 480.0],
    }
    data = {
        "problem": "resonance",
        "chain": chain,
        "campbell": {"from_rpm": 1.0, "to_rpm": 1.0e6},
        "resonance": {"order": 1.5, "mode": 1, "harmonic_torque": 100.0},
    }
    got = values(run_both(data, tmp_path))
    low, high = three_mass_closed_form(inertias, stiffnesses)
    assert got["frequency_1"] == pytest.approx(low / TWO_PI, rel=1e-9)
    assert got["frequency_2"] == pytest.approx(high / TWO_PI, rel=1e-9)
    assert got["critical_speed_rpm"] == pytest.approx(60 * low / TWO_PI / 1.5, rel=1e-9)
    assert got["amplitude"] > 0 and got["amplitude_exact"] > 0
    md = modal(ChainSection(**chain))
    a = np.array(md.shapes[0])
    k, j = stiffness_matrix(stiffnesses), np.array(inertias)
    # each row of (K - β²J)·a against the size of its own terms
    terms = np.abs(k) @ np.abs(a) + md.frequencies[0] ** 2 * j * np.abs(a)
    assert np.all(np.abs(k @ a - md.frequencies[0] ** 2 * j * a) <= 1e-8 * terms + 1e-300)


CRASHES: dict[str, dict[str, Any]] = {
    # stiffness contrast 1e16 (both inside the allowed (0, 1e13]), well damped
    "stiff-contrast": {
        "inertias": [1.0, 1.0, 1.0],
        "stiffnesses": [1.0e13, 1.0e-3],
        "damping": [1.0, 1.0, 1.0],
        "cranks": [1],
        "firing_angles_deg": [0.0],
    },
    # tiny but positive damping: A = M/(β·ξ) = 2e11 rad is finite
    "tiny-damping": {
        "inertias": [0.5, 2.0],
        "stiffnesses": [1.0e5],
        "damping": [1.0e-12, 0.0],
        "cranks": [1],
        "firing_angles_deg": [0.0],
    },
}


# Found by these tests: these crashed with exit 70; now exit 3 with the reason.
@pytest.mark.parametrize("name", sorted(CRASHES))
def test_ill_conditioned_damped_case_does_not_crash(tmp_path: Path, name: str) -> None:
    chain = CRASHES[name]
    data = {
        "problem": "resonance",
        "chain": chain,
        "resonance": {"order": 1.0, "harmonic_torque": 100.0},
    }
    path = tmp_path / "case.toml"
    path.write_text(toml_dumps(data), encoding="utf-8")
    result = invoke(path, "--json")
    assert "internal error" not in result.stderr
    assert result.exit_code in (0, 3), result.stderr
    if result.exit_code == 0:
        got = values(strict_json(result.stdout))
        own = own_energy(chain, 1, 1.0, 100.0)
        assert got["amplitude"] == pytest.approx(own["amplitude"], rel=1e-6)


EXTREME_POINTS = [
    [-100.0, 0.0],
    [-100.0, 100.0],
    [100.0, 100.0],
    [-100.0, -100.0],
    [0.0, 100.0],
    [100.0, -100.0],
    [100.0, 0.0],
]


@pytest.mark.parametrize(("c", "count"), [(0.0, 7), (100.0, 3)])
def test_extreme_mathieu_finite(tmp_path: Path, c: float, count: int) -> None:
    """a = ±100, q = ±100, damping 0 and 100 (the limits): finite multipliers that
    match the own monodromy, a finite chart over the whole allowed range."""
    points = EXTREME_POINTS[:count]
    data = mathieu_case(
        points, c, chart=True, a_from=-100.0, a_to=100.0, q_to=100.0, columns=41, rows=11
    )
    report = run_both(data, tmp_path)
    got = values(report)
    trace, det = monodromy([p[0] for p in points], [p[1] for p in points], c)
    for k in range(len(points)):
        rho = radius(trace[k], det[k])
        assert got[f"floquet_radius_{k + 1}"] == pytest.approx(rho, rel=1e-6)
    assert got["stability_1"] == "unstable"
    assert got["floquet_radius_1"] == pytest.approx(overdamped_radius(-100.0, c), rel=1e-8)
    chart = rows(report, "chart")
    assert len(chart) == 11 and all(len(r[1]) == 41 for r in chart)


def test_forty_mass_chain_closed_form_and_finite(tmp_path: Path) -> None:
    n = 40
    chain = {
        "inertias": [0.4] * n,
        "stiffnesses": [2.0e5] * (n - 1),
        "damping": [0.5] * n,
        "cranks": list(range(1, 7)),
        "firing_angles_deg": [0.0, 480.0, 240.0, 600.0, 120.0, 360.0],
    }
    data = {
        "problem": "resonance",
        "chain": chain,
        "campbell": {"from_rpm": 10.0, "to_rpm": 3000.0},
        "resonance": {"order": 3.0, "mode": 2, "harmonic_torque": 30.0},
    }
    got = values(run_both(data, tmp_path))
    for j in range(1, 6):
        f = math.sqrt(4 * 2.0e5 / 0.4) * math.sin(j * math.pi / (2 * n)) / TWO_PI
        assert got[f"frequency_{j}"] == pytest.approx(f, rel=1e-10)
    own = own_energy(chain, 2, 3.0, 30.0)
    assert got["amplitude"] == pytest.approx(own["amplitude"], rel=1e-8)
    assert got["amplitude_exact"] == pytest.approx(own["amplitude_exact"], rel=1e-6)


# Found by these tests: 200 masses took 30-55 s (O(n³) mode polishing); the
# model now allows 60 masses, which take about 2 s.
def test_largest_chain_in_reasonable_time(tmp_path: Path) -> None:
    n = 60
    data = {
        "problem": "resonance",
        "chain": {"inertias": [1.0] * n, "stiffnesses": [1.0e5] * (n - 1)},
    }
    path = tmp_path / "case.toml"
    path.write_text(toml_dumps(data), encoding="utf-8")
    proc = subprocess.run(
        [str(Path(sys.executable).parent / "mdcalc"), "resonance", str(path), "--json"],
        capture_output=True,
        text=True,
        timeout=8,
    )
    assert proc.returncode == 0, proc.stderr
    report = strict_json(proc.stdout)
    walk_finite(report)
    got = values(report)
    for j in range(1, 6):
        f = math.sqrt(4 * 1.0e5) * math.sin(j * math.pi / (2 * n)) / TWO_PI
        assert got[f"frequency_{j}"] == pytest.approx(f, rel=1e-9)
