"""Independent physics tests of ``mdcalc mechanism`` (brief PROBLEMS.md §8, seed 001,
Yu. Ya. Kovylin, "the method of linearization").

Model: reduced torque M(φ, ω), reduced inertia I(φ), ω = ω₀ at φ₀. Energy (1):
I_k·ω_k²/2 - I_i·ω_i²/2 = ∫M dφ. Kovylin's step (5):
Δω = [2·M′·Δφ + (I_i - I_k)·ω_i²] / [2·I_k·ω_i - C·Δφ], M′ = ½[M(φ_i, ω_i) + M(φ_k, ω_i)],
C = ∂M/∂ω at (φ_k, ω_i); time per step Δt = 2Δφ/(ω_i + ω_k).

Every expected value is computed in this file, never copied from the program:

* closed forms by hand: constant I with M = a - b·ω,
  φ(ω) = (I/b)·[(ω₀ - ω) + (a/b)·ln((a - b·ω₀)/(a - b·ω))], t(ω) = (I/b)·ln(...);
  a fan load from rest M = M₀ - k·ω², ω² = (M₀/k)(1 - e^(-2kφ/I)),
  t = I/√(M₀k)·atanh(ω√(k/M₀)); a torque of φ alone, E(φ) = E₀ + ∫M dφ written out;
  the stall angle I₀·ω₀²/(2|M|) and time I·ω₀/|M| of a constant braking torque;
* Kovylin's (5) and the "(1) solved for ω_k" step by a plain loop written here from
  the seed's formulas, with an analytic ∂M/∂ω;
* the equation of motion in the TIME domain, I(φ)·ω' = M - ½·I′(φ)·ω², φ' = ω, with I′
  analytic (or the slope of the table's segment), integrated by scipy's DOP853 at
  rtol 1e-12 segment by segment between table nodes; its dense output gives ω_max,
  ω_min over the last revolution (refined by a bounded scalar search) -- a different
  formulation from the program's energy-in-angle ODE dE/dφ = M;
* scipy's ``quad`` of φ(ω) = ∫I·w/M(w) dw and t(ω) = ∫I/M(w) dw from rest;
* tables: a periodic linear interpolation written here (linear search, no bisect).
"""

from __future__ import annotations

import copy
import json
import math
import re
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq, minimize_scalar
from tomli_w import dumps as toml_dumps

from tests.conftest import assert_no_traceback, strict_json, walk_finite

TWO_PI = 2.0 * math.pi
DEG = math.pi / 180.0
HAND = 1e-9  # against closed forms
ODE = 1e-8  # against the own time-domain integration
PEAK = 1e-7  # ω_max, ω_min, δ (extrema of a dense solution)
LOOP = 1e-12  # against the own loop of (5)
ERROR_LINE = re.compile(r"^(\S+\.toml):(\d+): error: (\S+): (.+)$", re.M)
NON_FINITE = re.compile(r"\b(nan|inf|infinity)\b", re.I)

Torque = Callable[[float, float], float]
Inertia = Callable[[float], float]

# ----------------------------------------------------------------------------- helpers


def case(
    torque: dict[str, Any],
    inertia: dict[str, Any],
    motion: dict[str, Any],
    parameters: dict[str, float] | None = None,
) -> dict[str, Any]:
    data: dict[str, Any] = {"problem": "mechanism"}
    if parameters:
        data["parameters"] = dict(parameters)
    data["torque"] = copy.deepcopy(torque)
    data["inertia"] = copy.deepcopy(inertia)
    data["motion"] = dict(motion)
    return data


def run(cli, write_case, data: dict[str, Any], code: int = 0, text: bool = False) -> dict[str, Any]:
    """Run in-process with --json (and, with ``text``, also as text); check the exit
    code, no traceback, no NaN/inf anywhere; return the JSON document."""
    path = write_case(toml_dumps(data))
    result = cli("mechanism", path, "--json")
    assert result.exit_code == code, (result.stdout, result.stderr)
    assert_no_traceback(result)
    document = strict_json(result.stdout)
    walk_finite(document)
    if text:
        shown = cli("mechanism", path)
        assert shown.exit_code == code
        assert_no_traceback(shown)
        assert not NON_FINITE.search(shown.stdout + shown.stderr), shown.stdout
    return document


def values(document: dict[str, Any]) -> dict[str, float]:
    return {key: item["value"] for key, item in document["results"].items()}


def method_rows(document: dict[str, Any]) -> dict[str, dict[str, Any]]:
    (table,) = [s for s in document["sections"] if s["kind"] == "methods"]
    return {row["method"]: row for row in table["rows"]}


def row_value(document: dict[str, Any], prefix: str, key: str = "final_speed") -> float:
    rows = method_rows(document)
    (name,) = [n for n in rows if n.startswith(prefix)]
    return float(rows[name]["values"][key])


def row_error(document: dict[str, Any], prefix: str, key: str = "final_speed") -> float:
    rows = method_rows(document)
    (name,) = [n for n in rows if n.startswith(prefix)]
    return float(rows[name]["rel_errors"][key])


def rel(expected: float, tol: float) -> Any:
    return pytest.approx(expected, rel=tol, abs=0.0)


def stall_numbers(message: str) -> tuple[float, float]:
    """φ [rad] and t [s] named in the stall message."""
    angle = re.search(r"φ = ([-+0-9.eE]+) rad", message)
    time = re.search(r"t = ([-+0-9.eE]+) s", message)
    assert angle is not None and time is not None, message
    return float(angle.group(1)), float(time.group(1))


# ----------------------------------------------------------------------------- own numerics


class OwnPeriodic:
    """Linear interpolation of a table over one revolution, repeated every 2π; a node at
    the start angle + 360° closes the table and is dropped. Linear search."""

    def __init__(self, angles_deg: list[float], table: list[float]) -> None:
        angles = [a * DEG for a in angles_deg]
        table = list(table)
        if abs(angles[-1] - angles[0] - TWO_PI) < 1e-9:
            angles, table = angles[:-1], table[:-1]
        self.nodes = [*angles, angles[0] + TWO_PI]
        self.table = [*table, table[0]]
        self.origin = angles[0]

    def _segment(self, phi: float) -> tuple[int, float]:
        x = self.origin + math.fmod(phi - self.origin, TWO_PI)
        if x < self.origin:
            x += TWO_PI
        for k in range(len(self.nodes) - 1):
            if x < self.nodes[k + 1]:
                return k, x
        return len(self.nodes) - 2, x

    def __call__(self, phi: float) -> float:
        k, x = self._segment(phi)
        a0, a1 = self.nodes[k], self.nodes[k + 1]
        return self.table[k] + (self.table[k + 1] - self.table[k]) * (x - a0) / (a1 - a0)

    def slope(self, phi: float) -> float:
        k, _ = self._segment(phi)
        return (self.table[k + 1] - self.table[k]) / (self.nodes[k + 1] - self.nodes[k])

    def breaks(self, start: float, end: float) -> list[float]:
        """Every node angle strictly inside (start, end)."""
        out = []
        for node in self.nodes[:-1]:
            k = math.floor((start - node) / TWO_PI)
            while node + k * TWO_PI < end:
                angle = node + k * TWO_PI
                if start < angle < end:
                    out.append(angle)
                k += 1
        return sorted(out)


def two_way(angles_deg: list[float], speeds: list[float], rows: list[list[float]]):
    """M(φ, ω) bilinear in a table, periodic in φ, linear (extrapolated) in ω; and its
    exact ∂M/∂ω."""
    columns = [OwnPeriodic(angles_deg, [row[j] for row in rows]) for j in range(len(speeds))]

    def cell(omega: float) -> int:
        j = 0
        while j < len(speeds) - 2 and omega >= speeds[j + 1]:
            j += 1
        return j

    def torque(phi: float, omega: float) -> float:
        j = cell(omega)
        m0, m1 = columns[j](phi), columns[j + 1](phi)
        return m0 + (m1 - m0) * (omega - speeds[j]) / (speeds[j + 1] - speeds[j])

    def slope(phi: float, omega: float) -> float:
        j = cell(omega)
        return (columns[j + 1](phi) - columns[j](phi)) / (speeds[j + 1] - speeds[j])

    return torque, slope, columns


def own_kovylin(
    torque: Torque,
    slope: Torque,
    inertia: Inertia,
    phi0: float,
    omega0: float,
    revolutions: float,
    n: int,
    quadratic: bool = False,
) -> tuple[float, float]:
    """ω and t at the end by (5) (or the root of (1) with the linearized torque),
    ``ceil(revolutions·n)`` equal steps; asserts that every step is one the seed's
    formula takes whole (|Δω| < ω/2, positive denominator)."""
    count = math.ceil(revolutions * n - 1e-9)
    dphi = revolutions * TWO_PI / count
    phi, omega, t = phi0, omega0, 0.0
    for k in range(1, count + 1):
        phi_k = phi0 + k * dphi
        i_i, i_k = inertia(phi), inertia(phi_k)
        m_mean = 0.5 * (torque(phi, omega) + torque(phi_k, omega))
        c = slope(phi_k, omega)
        if quadratic:
            # I_k·x² - C·Δφ·x - (I_i·ω_i² + 2·M′·Δφ - C·Δφ·ω_i) = 0, the positive root
            qa, qb = i_k, -c * dphi
            qc = -(i_i * omega * omega + 2.0 * m_mean * dphi - c * dphi * omega)
            nxt = (-qb + math.sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa)
        else:
            denominator = 2.0 * i_k * omega - c * dphi
            assert denominator > 0.0
            delta = (2.0 * m_mean * dphi + (i_i - i_k) * omega**2) / denominator
            assert abs(delta) < 0.5 * omega, "the plain loop needs whole steps"
            nxt = omega + delta
        assert nxt > 0.0
        t += 2.0 * dphi / (omega + nxt)
        phi, omega = phi_k, nxt
    return omega, t


def time_domain(
    torque: Torque,
    inertia: Inertia,
    inertia_slope: Inertia,
    phi0: float,
    omega0: float,
    phi_end: float,
    breaks: list[float] | None = None,
    segment_slope: bool = False,
) -> dict[str, float]:
    """I(φ)·ω' = M(φ, ω) - ½·I′(φ)·ω², φ' = ω in time, DOP853 rtol 1e-12, stopped at
    every break (table node) and at φ_end - 2π; with ``segment_slope`` I′ is taken at
    the middle of each segment (a piecewise linear table). Returns ω and t at the end and
    ω_max, ω_min, the time of the last revolution."""
    mark = phi_end - TWO_PI
    cuts = sorted({b for b in (breaks or []) if phi0 < b < phi_end} | {mark} - {phi0})
    cuts = [c for c in cuts if phi0 < c < phi_end] + [phi_end]
    t, omega, low = 0.0, omega0, phi0
    t_mark = 0.0 if mark <= phi0 else math.nan
    top, bottom = (omega0, omega0) if mark <= phi0 else (-math.inf, math.inf)
    for high in cuts:
        middle = 0.5 * (low + high)

        def rhs(_t: float, y: np.ndarray, low=low, high=high, middle=middle) -> list[float]:
            phi = min(max(y[0], low), high)
            d_inertia = inertia_slope(middle) if segment_slope else inertia_slope(phi)
            accel = (torque(phi, y[1]) - 0.5 * d_inertia * y[1] ** 2) / inertia(phi)
            return [y[1], accel]

        def reach(_t: float, y: np.ndarray, high=high) -> float:
            return y[0] - high

        reach.terminal = True  # type: ignore[attr-defined]
        reach.direction = 1  # type: ignore[attr-defined]
        horizon = 10.0 * (high - low) / max(omega, 1e-12) + 1.0
        sol = solve_ivp(
            rhs,
            (t, t + horizon),
            [low, omega],
            method="DOP853",
            rtol=1e-12,
            atol=[1e-14 * max(1.0, abs(high)), 1e-14 * max(omega, 1.0)],
            events=reach,
            dense_output=True,
        )
        assert sol.status == 1 and len(sol.t_events[0]) == 1, sol.message
        t_high = float(sol.t_events[0][0])
        omega_high = float(sol.y_events[0][0][1])
        if low >= mark - 1e-12:
            top, bottom = _extrema(sol.sol, t, t_high, top, bottom)
        t, omega, low = t_high, omega_high, high
        if abs(high - mark) < 1e-12:
            t_mark = t
    return {"speed": omega, "time": t, "max": top, "min": bottom, "revolution": t - t_mark}


def _extrema(dense: Any, t0: float, t1: float, top: float, bottom: float) -> tuple[float, float]:
    grid = np.linspace(t0, t1, 129)
    speeds = dense(grid)[1]
    for sign in (1.0, -1.0):
        k = int(np.argmax(sign * speeds))
        best = float(speeds[k])
        lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
        if hi > lo:
            found = minimize_scalar(
                lambda s, sign=sign: -sign * float(dense(s)[1]),
                bounds=(lo, hi),
                method="bounded",
                options={"xatol": 1e-14 * max(1.0, abs(t1))},
            )
            candidate = -sign * float(found.fun)
            best = max(best, candidate) if sign > 0 else min(best, candidate)
        if sign > 0:
            top = max(top, best)
        else:
            bottom = min(bottom, best)
    return top, bottom


def assert_motion(document: dict[str, Any], own: dict[str, float], tol: float = ODE) -> None:
    got = values(document)
    assert got["final_speed"] == rel(own["speed"], tol)
    assert got["final_time"] == rel(own["time"], tol)
    assert got["max_speed"] == rel(own["max"], PEAK)
    assert got["min_speed"] == rel(own["min"], PEAK)
    mean = TWO_PI / own["revolution"]
    assert got["mean_speed_revolution"] == rel(mean, tol)
    assert got["fluctuation"] == rel((own["max"] - own["min"]) / mean, 10 * PEAK)


# ----------------------------------------------------------------------------- closed form


def linear_closed_form(a: float, b: float, inertia: float, omega0: float):
    """φ(ω) and t(ω) for I·ω·dω/dφ = a - b·ω, and ω(φ) by brentq."""
    u0 = a - b * omega0

    def angle(omega: float) -> float:
        return (inertia / b) * ((omega0 - omega) + (a / b) * math.log(u0 / (a - b * omega)))

    def time(omega: float) -> float:
        return (inertia / b) * math.log(u0 / (a - b * omega))

    def speed(phi: float) -> float:
        limit = a / b
        low, high = sorted((omega0, limit))
        span = high - low
        return brentq(
            lambda w: angle(w) - phi,
            low + (0.0 if omega0 == low else 1e-15 * span),
            high - (0.0 if omega0 == high else 1e-15 * span),
            xtol=1e-15,
            rtol=1e-15,
            maxiter=500,
        )

    return angle, time, speed


LINEAR = {"a": 60.0, "b": 1.5}  # a/b = 40 rad/s


@pytest.mark.parametrize("omega0", [5.0, 70.0], ids=["accelerating", "decelerating"])
def test_constant_inertia_linear_torque_closed_form(cli, write_case, omega0: float):
    inertia, phi0, revolutions = 0.8, 0.7, 2.5
    data = case(
        {"formula": "a - b*omega"},
        {"value": inertia},
        {"start_angle": phi0, "start_speed": omega0, "revolutions": revolutions},
        LINEAR,
    )
    got = values(run(cli, write_case, data))
    _, time, speed = linear_closed_form(LINEAR["a"], LINEAR["b"], inertia, omega0)
    span = revolutions * TWO_PI
    w_end, w_first = speed(span), speed(span - TWO_PI)
    t_end, t_first = time(w_end), time(w_first)
    assert got["final_speed"] == rel(w_end, HAND)
    assert got["final_time"] == rel(t_end, HAND)
    assert got["mean_speed"] == rel(span / t_end, HAND)
    assert got["end_angle"] == rel(phi0 + span, 1e-15)
    assert got["start_torque"] == rel(LINEAR["a"] - LINEAR["b"] * omega0, 1e-15)
    assert got["start_inertia"] == inertia
    # monotone: the extremes of the last revolution are its ends
    assert got["max_speed"] == rel(max(w_end, w_first), HAND)
    assert got["min_speed"] == rel(min(w_end, w_first), HAND)
    mean = TWO_PI / (t_end - t_first)
    assert got["mean_speed_revolution"] == rel(mean, HAND)
    assert got["fluctuation"] == rel(abs(w_end - w_first) / mean, 1e-8)


def test_start_speed_in_rpm(cli, write_case):
    rpm = 300.0
    data = case(
        {"formula": "a - b*omega"},
        {"value": 0.8},
        {"start_speed_rpm": rpm, "revolutions": 1.0},
        LINEAR,
    )
    got = values(run(cli, write_case, data))
    omega0 = rpm * math.pi / 30.0
    _, time, speed = linear_closed_form(LINEAR["a"], LINEAR["b"], 0.8, omega0)
    assert got["start_speed"] == rel(omega0, 1e-15)
    assert got["final_speed"] == rel(speed(TWO_PI), HAND)
    assert got["final_time"] == rel(time(speed(TWO_PI)), HAND)


def test_kovylin_first_order_on_linear_torque(cli, write_case):
    """(5) is first order: the error of the end speed halves when n doubles -- in the
    program's Methods table and in the own loop; the table's values are the own loop's."""
    inertia, omega0, revolutions, n = 0.8, 15.0, 2.5, 12
    data = case(
        {"formula": "a - b*omega"},
        {"value": inertia},
        {"start_speed": omega0, "revolutions": revolutions, "steps_per_revolution": n},
        LINEAR,
    )
    document = run(cli, write_case, data)
    _, _, speed = linear_closed_form(LINEAR["a"], LINEAR["b"], inertia, omega0)
    exact = speed(revolutions * TWO_PI)

    def torque(phi: float, omega: float) -> float:
        return LINEAR["a"] - LINEAR["b"] * omega

    def slope(phi: float, omega: float) -> float:
        return -LINEAR["b"]

    own = {
        k: own_kovylin(torque, slope, lambda p: inertia, 0.0, omega0, revolutions, k)
        for k in (n, 2 * n, 4 * n)
    }
    table = {k: row_error(document, f"Kovylin (5), n = {k}") for k in (n, 2 * n, 4 * n)}
    for k in (n, 2 * n, 4 * n):
        assert row_value(document, f"Kovylin (5), n = {k}") == rel(own[k][0], LOOP)
        assert row_value(document, f"Kovylin (5), n = {k}", "final_time") == rel(own[k][1], LOOP)
        assert table[k] == rel(abs(own[k][0] - exact) / exact, 1e-6)
    assert values(document)["kovylin_final_speed"] == rel(own[n][0], LOOP)
    for k in (n, 2 * n):
        assert 1.8 < table[k] / table[2 * k] < 2.2
        own_ratio = abs(own[k][0] - exact) / abs(own[2 * k][0] - exact)
        assert 1.8 < own_ratio < 2.2
    # the reference row has no error of its own; its value is the closed form
    rows = method_rows(document)
    (reference,) = [r for r in rows.values() if r["reference"]]
    assert reference["values"]["final_speed"] == rel(exact, HAND)


# ----------------------------------------------------------------------------- varying I(φ)

CRANK = {"M0": 250.0, "w0": 90.0, "Mr": 150.0}
CRANK_TORQUE = "M0*(1 - omega/w0) - Mr*sin(phi)**2"
CRANK_INERTIA = "1.5 + 0.3*cos(2*phi) + 0.1*sin(phi)"


def crank_torque(phi: float, omega: float) -> float:
    return CRANK["M0"] * (1.0 - omega / CRANK["w0"]) - CRANK["Mr"] * math.sin(phi) ** 2


def crank_slope(phi: float, omega: float) -> float:
    return -CRANK["M0"] / CRANK["w0"]


def crank_inertia(phi: float) -> float:
    return 1.5 + 0.3 * math.cos(2.0 * phi) + 0.1 * math.sin(phi)


def crank_inertia_slope(phi: float) -> float:
    return -0.6 * math.sin(2.0 * phi) + 0.1 * math.cos(phi)


@pytest.fixture(scope="module")
def crank_document(tmp_path_factory) -> dict[str, Any]:
    from typer.testing import CliRunner

    from mdcalc.cli.app import app

    data = case(
        {"formula": CRANK_TORQUE},
        {"formula": CRANK_INERTIA},
        {"start_angle": 0.25, "start_speed": 60.0, "revolutions": 4.0, "steps_per_revolution": 16},
        CRANK,
    )
    path = tmp_path_factory.mktemp("crank") / "crank.toml"
    path.write_text(toml_dumps(data), encoding="utf-8")
    result = CliRunner().invoke(app, ["mechanism", str(path), "--json"])
    assert result.exit_code == 0, result.stderr
    document = strict_json(result.stdout)
    walk_finite(document)
    return document


def test_varying_inertia_formula_against_time_domain(crank_document):
    own = time_domain(
        crank_torque, crank_inertia, crank_inertia_slope, 0.25, 60.0, 0.25 + 4 * TWO_PI
    )
    assert_motion(crank_document, own)
    got = values(crank_document)
    assert got["start_inertia"] == rel(crank_inertia(0.25), 1e-15)
    assert got["start_torque"] == rel(crank_torque(0.25, 60.0), 1e-14)


def test_varying_inertia_kovylin_matches_own_loop(crank_document):
    for n in (16, 32, 64):
        w, t = own_kovylin(crank_torque, crank_slope, crank_inertia, 0.25, 60.0, 4.0, n)
        # ∂M/∂ω by the program's difference quotient vs the exact slope: round-off only
        assert row_value(crank_document, f"Kovylin (5), n = {n}") == rel(w, LOOP)
        assert row_value(crank_document, f"Kovylin (5), n = {n}", "final_time") == rel(t, LOOP)
    w16, _ = own_kovylin(crank_torque, crank_slope, crank_inertia, 0.25, 60.0, 4.0, 16)
    assert values(crank_document)["kovylin_final_speed"] == rel(w16, LOOP)


def test_energy_root_row_matches_own_loop_and_beats_kovylin(crank_document):
    """The "(1) solved for ω_k" row keeps ω_k² whole: with I(φ) varying it is far more
    accurate than (5) at the same n."""
    w, t = own_kovylin(
        crank_torque, crank_slope, crank_inertia, 0.25, 60.0, 4.0, 16, quadratic=True
    )
    assert row_value(crank_document, "(1) solved for ω_k, n = 16") == rel(w, LOOP)
    assert row_value(crank_document, "(1) solved for ω_k, n = 16", "final_time") == rel(t, LOOP)
    own = time_domain(
        crank_torque, crank_inertia, crank_inertia_slope, 0.25, 60.0, 0.25 + 4 * TWO_PI
    )
    kovylin, _ = own_kovylin(crank_torque, crank_slope, crank_inertia, 0.25, 60.0, 4.0, 16)
    assert abs(w - own["speed"]) < 0.2 * abs(kovylin - own["speed"])
    assert row_error(crank_document, "(1) solved for ω_k") < 0.2 * row_error(
        crank_document, "Kovylin (5), n = 16"
    )
    assert row_error(crank_document, "(1) solved for ω_k") == rel(
        abs(w - own["speed"]) / own["speed"], 1e-5
    )


def test_kovylin_worst_error_is_at_least_the_end_error(crank_document):
    got = values(crank_document)
    own = time_domain(
        crank_torque, crank_inertia, crank_inertia_slope, 0.25, 60.0, 0.25 + 4 * TWO_PI
    )
    end_error = abs(got["kovylin_final_speed"] - own["speed"]) / own["speed"]
    assert got["kovylin_worst_error"] >= end_error * (1.0 - 1e-6)
    assert got["kovylin_worst_error"] < 1.0


# ----------------------------------------------------------------------------- tables

I_ANGLES = [10.0, 60.0, 100.0, 170.0, 200.0, 250.0, 300.0, 340.0]  # not from 0, not closed
I_VALUES = [2.0, 2.3, 2.6, 2.2, 1.9, 1.7, 1.8, 1.95]
M_ANGLES = [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0]
M_SPEEDS = [0.0, 40.0, 80.0, 120.0]
M_ROWS = [[300.0 - 15 * k, 160.0 - 10 * k, 20.0 - 5 * k, -90.0 - 3 * k] for k in range(8)]


@pytest.mark.parametrize(("phi0", "revolutions", "n"), [(0.4, 3.0, 12), (-2.0, 2.25, 16)])
def test_tabulated_inertia_and_two_way_torque(
    cli, write_case, phi0: float, revolutions: float, n: int
):
    data = case(
        {"angles_deg": M_ANGLES, "speeds": M_SPEEDS, "values": M_ROWS},
        {"angles_deg": I_ANGLES, "values": I_VALUES},
        {
            "start_angle": phi0,
            "start_speed": 50.0,
            "revolutions": revolutions,
            "steps_per_revolution": n,
        },
    )
    document = run(cli, write_case, data)
    inertia = OwnPeriodic(I_ANGLES, I_VALUES)
    torque, slope, columns = two_way(M_ANGLES, M_SPEEDS, M_ROWS)
    end = phi0 + revolutions * TWO_PI
    breaks = inertia.breaks(phi0, end) + columns[0].breaks(phi0, end)
    own = time_domain(torque, inertia, inertia.slope, phi0, 50.0, end, breaks, segment_slope=True)
    assert_motion(document, own)
    w, t = own_kovylin(torque, slope, inertia, phi0, 50.0, revolutions, n)
    assert values(document)["kovylin_final_speed"] == rel(w, LOOP)
    assert row_value(document, f"Kovylin (5), n = {n}", "final_time") == rel(t, LOOP)
    w2, _ = own_kovylin(torque, slope, inertia, phi0, 50.0, revolutions, 2 * n, quadratic=True)
    w1, _ = own_kovylin(torque, slope, inertia, phi0, 50.0, revolutions, n, quadratic=True)
    assert row_value(document, f"(1) solved for ω_k, n = {n}") == rel(w1, LOOP)
    assert w2 != w1
    got = values(document)
    assert got["start_inertia"] == rel(inertia(phi0), 1e-13)
    assert got["start_torque"] == rel(torque(phi0, 50.0), 1e-13)


def test_one_way_torque_table_in_radians_with_closing_node(cli, write_case):
    """M(φ) from a table in radians closed at 2π (same value as at 0), I(φ) a formula."""
    angles = [k * TWO_PI / 6 for k in range(7)]
    table = [120.0, 40.0, -60.0, -20.0, 80.0, 150.0, 120.0]
    data = case(
        {"angles": angles, "values": table},
        {"formula": "1.2 + 0.2*cos(phi)"},
        {"start_speed": 30.0, "revolutions": 3.0, "steps_per_revolution": 12},
    )
    document = run(cli, write_case, data)
    own_table = OwnPeriodic([a / DEG for a in angles], table)

    def torque(phi: float, omega: float) -> float:
        return own_table(phi)

    def inertia(phi: float) -> float:
        return 1.2 + 0.2 * math.cos(phi)

    own = time_domain(
        torque,
        inertia,
        lambda p: -0.2 * math.sin(p),
        0.0,
        30.0,
        3 * TWO_PI,
        own_table.breaks(0.0, 3 * TWO_PI),
    )
    assert_motion(document, own)
    # M of φ alone: the energy at the end is E₀ + ∫M dφ, the trapezoids of the table
    work = 3 * sum(0.5 * (table[k] + table[k + 1]) * TWO_PI / 6 for k in range(6))
    energy = 0.5 * inertia(0.0) * 30.0**2 + work
    assert values(document)["final_speed"] == rel(math.sqrt(2 * energy / inertia(3 * TWO_PI)), HAND)
    w, t = own_kovylin(torque, lambda p, w: 0.0, inertia, 0.0, 30.0, 3.0, 12)
    assert values(document)["kovylin_final_speed"] == rel(w, LOOP)


def test_closed_table_equals_open_table(cli, write_case):
    base = {"start_speed": 30.0, "revolutions": 2.0}
    open_ = case(
        {"formula": "100 - 2*omega"},
        {"angles_deg": [0, 90, 180, 270], "values": [1.0, 2.0, 3.0, 4.0]},
        base,
    )
    closed = case(
        {"formula": "100 - 2*omega"},
        {"angles_deg": [0, 90, 180, 270, 360], "values": [1.0, 2.0, 3.0, 4.0, 1.0]},
        base,
    )
    a = values(run(cli, write_case, open_))
    b = values(run(cli, write_case, closed))
    assert a["final_speed"] == b["final_speed"] and a["final_time"] == b["final_time"]


def test_contradictory_closing_value_is_not_dropped_silently(cli, write_case):
    data = case(
        {"formula": "100 - 2*omega"},
        {"angles_deg": [0, 90, 180, 270, 360], "values": [1.0, 2.0, 3.0, 4.0, 9.0]},
        {"start_speed": 30.0, "revolutions": 2.0},
    )
    result = cli("mechanism", write_case(toml_dumps(data)), "--json")
    assert_no_traceback(result)
    if result.exit_code == 2:
        assert "inertia.values" in result.stderr or "inertia.angles_deg" in result.stderr
    else:
        notes = " ".join(n["text"] for n in strict_json(result.stdout)["notes"])
        assert re.search(r"360|clos|last value|repeat", notes), notes


# ----------------------------------------------------------------------------- from rest


def test_fan_load_from_rest_closed_form(cli, write_case):
    m0, k, inertia, revolutions = 80.0, 0.02, 0.6, 3.0
    data = case(
        {"formula": "M0 - k*omega**2"},
        {"value": inertia},
        {"start_speed": 0.0, "revolutions": revolutions},
        {"M0": m0, "k": k},
    )
    document = run(cli, write_case, data)
    got = values(document)

    def speed(phi: float) -> float:
        return math.sqrt(m0 / k * -math.expm1(-2.0 * k * phi / inertia))

    def time(omega: float) -> float:
        return inertia / math.sqrt(m0 * k) * math.atanh(omega * math.sqrt(k / m0))

    span = revolutions * TWO_PI
    assert got["start_speed"] == 0.0
    assert got["final_speed"] == rel(speed(span), HAND)
    assert got["final_time"] == rel(time(speed(span)), HAND)
    assert got["min_speed"] == rel(speed(span - TWO_PI), 1e-8)
    assert got["max_speed"] == rel(speed(span), 1e-8)
    # Kovylin from rest (first step by the quadratic) converges to it
    errors = [row_error(document, f"Kovylin (5), n = {n}") for n in (16, 32, 64)]
    assert errors[2] < errors[1] < errors[0] < 0.05


KLOSS = {"Mk": 150.0, "sk": 0.25, "ws": 100.0, "Ml": 30.0}


def kloss(omega: float) -> float:
    s = 1.0 - omega / KLOSS["ws"]
    return 2.0 * KLOSS["Mk"] / (s / KLOSS["sk"] + KLOSS["sk"] / s) - KLOSS["Ml"]


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
def test_motor_start_from_rest_against_quadrature(cli, write_case):
    """φ(ω) = ∫₀^ω I·w/M(w) dw, t(ω) = ∫₀^ω I/M(w) dw; ω at the end solves φ(ω) = span."""
    inertia, revolutions = 0.3, 4.0
    data = case(
        {"formula": "2*Mk/((1 - omega/ws)/sk + sk/(1 - omega/ws)) - Ml"},
        {"value": inertia},
        {"start_speed": 0.0, "revolutions": revolutions, "steps_per_revolution": 16},
        KLOSS,
    )
    got = values(run(cli, write_case, data))

    def angle(omega: float) -> float:
        return quad(
            lambda w: inertia * w / kloss(w), 0.0, omega, epsabs=0.0, epsrel=1e-12, limit=200
        )[0]

    def time(omega: float) -> float:
        return quad(lambda w: inertia / kloss(w), 0.0, omega, epsabs=0.0, epsrel=1e-12, limit=200)[
            0
        ]

    # the running speed: where the motor torque equals the load (above the breakdown slip)
    running = brentq(kloss, KLOSS["ws"] * (1 - KLOSS["sk"]), KLOSS["ws"] * (1 - 1e-9))
    span = revolutions * TWO_PI
    w_end = brentq(lambda w: angle(w) - span, 1e-6, running * (1 - 1e-9), xtol=1e-14, rtol=1e-15)
    assert got["final_speed"] == rel(w_end, ODE)
    assert got["final_time"] == rel(time(w_end), ODE)


def test_start_from_rest_with_varying_inertia_against_time_domain(cli, write_case):
    data = case(
        {"formula": CRANK_TORQUE},
        {"formula": CRANK_INERTIA},
        {"start_speed": 0.0, "revolutions": 2.0, "steps_per_revolution": 16},
        CRANK,
    )
    document = run(cli, write_case, data)
    own = time_domain(crank_torque, crank_inertia, crank_inertia_slope, 0.0, 0.0, 2 * TWO_PI)
    assert_motion(document, own)


# ----------------------------------------------------------------------------- stall


def test_constant_braking_torque_stalls_by_hand(cli, write_case):
    """E = I·ω₀²/2 = 16 J runs out after 16/5 = 3.2 rad, at t = I·ω₀/|M| = 1.6 s."""
    data = case({"formula": "-5"}, {"value": 2.0}, {"start_speed": 4.0, "revolutions": 1.0})
    document = run(cli, write_case, data, code=3)
    assert document["status"] == "no-answer"
    angle, time = stall_numbers(document["message"])
    assert angle == rel(3.2, 1e-5)
    assert time == rel(1.6, 1e-5)
    assert "final_speed" not in document["results"]


def test_braking_torque_stall_with_varying_inertia(cli, write_case):
    """The stall angle does not depend on I(φ) between: I₀·ω₀²/(2|M|) = 4·9/12 = 3 rad
    (I₀ = 3 + cos 0 = 4)."""
    data = case(
        {"formula": "-6"}, {"formula": "3 + cos(phi)"}, {"start_speed": 3.0, "revolutions": 2.0}
    )
    document = run(cli, write_case, data, code=3)
    angle, _ = stall_numbers(document["message"])
    assert angle == rel(3.0, 1e-5)


def test_stall_in_the_second_revolution(cli, write_case):
    """M = -c + d·sin φ: E(φ) = E₀ - c·φ + d·(1 - cos φ); the first zero past 2π."""
    c, d, inertia, omega0, phi0 = 5.0, 3.0, 1.0, 10.0, 0.5
    data = case(
        {"formula": "-c + d*sin(phi)"},
        {"value": inertia},
        {"start_angle": phi0, "start_speed": omega0, "revolutions": 3.0},
        {"c": c, "d": d},
    )
    document = run(cli, write_case, data, code=3)

    def energy(phi: float) -> float:
        return 0.5 * inertia * omega0**2 - c * (phi - phi0) - d * (math.cos(phi) - math.cos(phi0))

    grid = np.linspace(phi0, phi0 + 3 * TWO_PI, 20001)
    first = next(k for k, p in enumerate(grid) if energy(p) <= 0.0)
    stall = brentq(energy, grid[first - 1], grid[first], xtol=1e-14)
    assert TWO_PI < stall - phi0 < 2 * TWO_PI
    time = quad(lambda p: 1.0 / math.sqrt(2.0 * energy(p) / inertia), phi0, stall, limit=400)[0]
    angle, t = stall_numbers(document["message"])
    assert angle == rel(stall, 1e-5)
    assert t == rel(time, 1e-5)
    assert "revolutions" in document["message"]


@pytest.mark.parametrize(
    ("torque", "phi0", "parameters"),
    [
        ({"formula": "-5"}, 0.0, None),
        ({"formula": "0*phi"}, 0.0, None),
        ({"formula": "sin(phi)"}, 0.0, None),  # exactly zero at φ₀
        ({"formula": "omega - 1"}, 0.0, None),
        ({"formula": "phi - 1"}, 0.5, None),
        ({"formula": "a*(1 - omega)"}, 1.0, {"a": -3.0}),
        ({"angles_deg": [0, 90, 180, 270], "values": [-1.0, 5.0, 5.0, 5.0]}, 0.0, None),
    ],
)
def test_no_drive_torque_from_rest_is_exit_3(cli, write_case, torque, phi0: float, parameters):
    data = case(
        torque,
        {"value": 1.0},
        {"start_angle": phi0, "start_speed": 0.0, "revolutions": 1.0},
        parameters,
    )
    document = run(cli, write_case, data, code=3)
    angle, time = stall_numbers(document["message"])
    assert angle == pytest.approx(phi0, abs=1e-9)
    assert time == 0.0


def test_stall_as_text_names_the_angle(cli, write_case):
    data = case({"formula": "-5"}, {"value": 2.0}, {"start_speed": 4.0, "revolutions": 1.0})
    result = cli("mechanism", write_case(toml_dumps(data)))
    assert result.exit_code == 3
    assert_no_traceback(result)
    assert "3.2 rad" in result.stdout + result.stderr


# ----------------------------------------------------------------------------- bad input

GOOD = case(
    {"formula": "a - b*omega"},
    {"value": 2.0},
    {"start_speed": 10.0, "revolutions": 1.0},
    {"a": 100.0, "b": 2.0},
)


def _mutate(change: Callable[[dict[str, Any]], None]) -> dict[str, Any]:
    data = copy.deepcopy(GOOD)
    change(data)
    return data


def _set(section: str, **items: Any) -> Callable[[dict[str, Any]], None]:
    def change(data: dict[str, Any]) -> None:
        data[section].update(items)

    return change


def _replace(section: str, value: dict[str, Any]) -> Callable[[dict[str, Any]], None]:
    def change(data: dict[str, Any]) -> None:
        data[section] = value

    return change


def _rename(section: str, old: str, new: str) -> Callable[[dict[str, Any]], None]:
    def change(data: dict[str, Any]) -> None:
        data[section][new] = data[section].pop(old)

    return change


BAD = {
    "misspelt revolutions": (_rename("motion", "revolutions", "revolutons"), "motion.revolutons"),
    "misspelt formula": (_rename("torque", "formula", "formule"), "torque.formule"),
    "unknown section key": (_set("inertia", valu=3.0), "inertia.valu"),
    "negative inertia": (_set("inertia", value=-2.0), "inertia.value"),
    "zero inertia": (_set("inertia", value=0.0), "inertia.value"),
    "nan inertia": (_set("inertia", value=math.nan), "inertia.value"),
    "negative table inertia": (
        _replace("inertia", {"angles_deg": [0, 120, 240], "values": [1.0, -1.0, 2.0]}),
        "inertia.values",
    ),
    "inertia length mismatch": (
        _replace("inertia", {"angles_deg": [0, 90, 180, 270], "values": [1.0, 2.0, 3.0]}),
        "inertia.values",
    ),
    "torque length mismatch": (
        _replace("torque", {"angles_deg": [0, 90, 180], "values": [1.0, 2.0, 3.0, 4.0]}),
        "torque.values",
    ),
    "angles not increasing": (
        _replace("inertia", {"angles_deg": [0, 90, 90, 270], "values": [1.0, 2.0, 3.0, 4.0]}),
        "inertia.angles_deg",
    ),
    "angles decreasing": (
        _replace("torque", {"angles_deg": [0, 200, 100], "values": [1.0, 2.0, 3.0]}),
        "torque.angles_deg",
    ),
    "table beyond 360 deg": (
        _replace("inertia", {"angles_deg": [0, 120, 240, 361], "values": [1.0, 2.0, 3.0, 1.0]}),
        "inertia.angles_deg",
    ),
    "table beyond 2 pi": (
        _replace("torque", {"angles": [0.0, 3.0, 6.3], "values": [1.0, 2.0, 3.0]}),
        "torque.angles",
    ),
    "angles and angles_deg": (
        _replace("inertia", {"angles": [0.0, 1.0], "angles_deg": [0, 57], "values": [1.0, 2.0]}),
        "inertia.angles_deg",
    ),
    "value and formula": (_set("inertia", formula="2 + cos(phi)"), "inertia"),
    "formula negative at start": (
        _replace("inertia", {"formula": "cos(phi) - 2"}),
        "inertia.formula",
    ),
    "formula zero at start": (_replace("inertia", {"formula": "sin(phi)"}), "inertia.formula"),
    "parameter sin": (lambda d: d["parameters"].update(sin=1.0), "parameters.sin"),
    "parameter _x": (lambda d: d["parameters"].update(_x=1.0), "parameters._x"),
    "parameter phi": (lambda d: d["parameters"].update(phi=1.0), "parameters.phi"),
    "parameter nan": (lambda d: d["parameters"].update(a=math.nan), "parameters.a"),
    "nan start speed": (_set("motion", start_speed=math.nan), "motion.start_speed"),
    "inf revolutions": (_set("motion", revolutions=math.inf), "motion.revolutions"),
    "negative start speed": (_set("motion", start_speed=-1.0), "motion.start_speed"),
    "text start speed": (_set("motion", start_speed="fast"), "motion.start_speed"),
    "both start speeds": (_set("motion", start_speed_rpm=100.0), "motion"),
    "zero revolutions": (_set("motion", revolutions=0.0), "motion.revolutions"),
    "three steps": (_set("motion", steps_per_revolution=3), "motion.steps_per_revolution"),
    "unknown name in formula": (_set("torque", formula="a - c*omega"), "torque.formula"),
    "no torque": (_replace("torque", {}), "torque"),
    "speeds not increasing": (
        _replace(
            "torque",
            {"angles_deg": [0, 180], "speeds": [10.0, 5.0], "values": [[1.0, 2.0], [3.0, 4.0]]},
        ),
        "torque.speeds",
    ),
    "formula with speeds": (_set("torque", speeds=[1.0, 2.0]), "torque.speeds"),
    "nan in torque table": (
        _replace("torque", {"angles_deg": [0, 180], "values": [1.0, math.nan]}),
        "torque.values",
    ),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_exit_2_names_the_field(cli, write_case, name: str):
    change, field = BAD[name]
    path = write_case(toml_dumps(_mutate(change)))
    result = cli("mechanism", path, "--json")
    assert result.exit_code == 2, (result.stdout, result.stderr)
    assert_no_traceback(result)
    assert json.loads(result.stdout)["status"] == "input-error"  # the record of run --json
    lines = ERROR_LINE.findall(result.stderr)
    assert lines, result.stderr
    assert all(file.endswith(path.name) for file, *_ in lines), result.stderr
    matching = [
        (int(line), f)
        for _, line, f, _ in lines
        if f == field or f.startswith(field + ".") or f.startswith(field + "[")
    ]
    assert matching, (field, result.stderr)
    # the line number points at the key (or its section) in the file
    text = path.read_text(encoding="utf-8").splitlines()
    line, found = matching[0]
    assert 1 <= line <= len(text), result.stderr
    keys = re.split(r"[.\[]", found)
    assert any(k and k in text[line - 1] for k in keys), (found, line, text[line - 1])


# ----------------------------------------------------------------------------- extremes


def test_stiff_steep_characteristic(cli, write_case):
    """b/I = 10⁴ s⁻¹: ω locks onto a/b = 100 within degrees. At the end a - b·ω is
    e^-2500 of its start: ω = a/b, t = (I/b)·L with L = (φ·b/I - (ω₀ - a/b))·b/a."""
    a, b, inertia, omega0, revolutions = 5000.0, 50.0, 0.005, 20.0, 2.0
    data = case(
        {"formula": "a - b*omega"},
        {"value": inertia},
        {"start_speed": omega0, "revolutions": revolutions},
        {"a": a, "b": b},
    )
    got = values(run(cli, write_case, data, text=True))
    span = revolutions * TWO_PI
    big_l = (span * b / inertia - (omega0 - a / b)) * b / a
    assert got["final_speed"] == rel(a / b, HAND)
    assert got["final_time"] == rel(inertia / b * big_l, 1e-8)
    assert got["fluctuation"] == pytest.approx(0.0, abs=1e-9)


def test_thousand_steps_per_revolution(cli, write_case):
    inertia, omega0 = 0.8, 5.0
    data = case(
        {"formula": "a - b*omega"},
        {"value": inertia},
        {"start_speed": omega0, "revolutions": 2.0, "steps_per_revolution": 1000},
        LINEAR,
    )
    document = run(cli, write_case, data, text=True)
    _, _, speed = linear_closed_form(LINEAR["a"], LINEAR["b"], inertia, omega0)
    exact = speed(2 * TWO_PI)
    got = values(document)
    assert got["final_speed"] == rel(exact, HAND)
    assert got["kovylin_final_speed"] == rel(exact, 1e-3)
    assert (
        1.8
        < row_error(document, "Kovylin (5), n = 1000")
        / row_error(document, "Kovylin (5), n = 2000")
        < 2.2
    )
    path = [s for s in document["sections"] if s.get("key") == "path"]
    assert path and len(path[0]["rows"]) <= 40  # the table is thinned, not 2001 rows


def _energy_case(
    inertia: float, m_text: str, work: Callable[[float], float], omega0: float, revs: float
):
    """A torque of φ alone on a constant inertia: ω_end = √(2(E₀ + W)/I)."""
    data = case(
        {"formula": m_text}, {"value": inertia}, {"start_speed": omega0, "revolutions": revs}
    )
    energy = 0.5 * inertia * omega0**2 + work(revs * TWO_PI)
    return data, math.sqrt(2.0 * energy / inertia)


@pytest.mark.parametrize(
    ("inertia", "m_text", "scale", "omega0"),
    [
        (1e-9, "1e-6*(1 + 0.5*sin(phi))", 1e-6, 3.0),  # tiny inertia, tiny torque
        (1e12, "3e11*(1 + 0.5*sin(phi))", 3e11, 2.0),  # huge inertia, huge torque
        (1e-6, "1e12*(1 + 0.5*sin(phi))", 1e12, 0.0),  # 3.5·10⁹ rad/s from rest
    ],
    ids=["tiny", "huge", "violent"],
)
def test_extreme_inertia_by_energy(
    cli, write_case, inertia: float, m_text: str, scale: float, omega0: float
):
    def work(phi: float) -> float:
        return scale * (phi + 0.5 * (1.0 - math.cos(phi)))

    data, expected = _energy_case(inertia, m_text, work, omega0, 2.0)
    got = values(run(cli, write_case, data, text=True))
    assert got["final_speed"] == rel(expected, HAND)

    def speed(phi: float) -> float:
        return math.sqrt((inertia * omega0**2 + 2.0 * work(phi)) / inertia)

    time = quad(lambda p: 1.0 / speed(p), 0.0, 2 * TWO_PI, epsabs=0.0, epsrel=1e-12, limit=200)[0]
    assert got["final_time"] == rel(time, 1e-8)


def test_near_stall_that_barely_passes(cli, write_case):
    """M = -A·sin φ, E(φ) = E₀ - A·(1 - cos φ): at φ = π only 10⁻⁶ of E₀ is left
    (ω_min = 10⁻³·ω₀·√(I(0)/I(π))); after two revolutions ω is back at ω₀·√(I(0)/I(4π))."""
    inertia0, omega0 = 2.0, 10.0
    e0 = 0.5 * inertia0 * omega0**2
    amplitude = 0.5 * e0 * (1.0 - 1e-6)
    data = case(
        {"formula": "-A*sin(phi)"},
        {"formula": "1.5 + 0.5*cos(phi)"},
        {"start_speed": omega0, "revolutions": 2.0},
        {"A": amplitude},
    )
    got = values(run(cli, write_case, data, text=True))

    def inertia(phi: float) -> float:
        return 1.5 + 0.5 * math.cos(phi)

    def energy(phi: float) -> float:
        return e0 - amplitude * (1.0 - math.cos(phi))

    assert got["final_speed"] == rel(
        math.sqrt(2.0 * energy(2 * TWO_PI) / inertia(2 * TWO_PI)), HAND
    )
    assert got["min_speed"] == rel(
        math.sqrt(2.0 * energy(3 * math.pi) / inertia(3 * math.pi)), 1e-6
    )
    time = sum(
        quad(
            lambda p: 1.0 / math.sqrt(2.0 * energy(p) / inertia(p)),
            lo,
            hi,
            points=[k * math.pi for k in range(5) if lo < k * math.pi < hi],
            epsabs=0.0,
            epsrel=1e-12,
            limit=400,
        )[0]
        for lo, hi in [(0.0, TWO_PI), (TWO_PI, 2 * TWO_PI)]
    )
    assert got["final_time"] == rel(time, 1e-7)


def test_near_stall_at_the_end_angle(cli, write_case):
    """A constant braking torque that leaves 10⁻⁹ of E₀ at the end: ω_end = √(2·10⁻⁹E₀/I)."""
    inertia, omega0 = 2.0, 10.0
    e0 = 0.5 * inertia * omega0**2
    brake = e0 * (1.0 - 1e-9) / TWO_PI
    data = case(
        {"formula": "-Mf"},
        {"value": inertia},
        {"start_speed": omega0, "revolutions": 1.0},
        {"Mf": brake},
    )
    got = values(run(cli, write_case, data, text=True))
    left = e0 - brake * TWO_PI
    assert got["final_speed"] == rel(math.sqrt(2.0 * left / inertia), 1e-5)
    # t = ∫dφ/ω = (I·ω₀ - I·ω_end)/|M| exactly for a constant torque
    assert got["final_time"] == rel(
        inertia * (omega0 - math.sqrt(2 * left / inertia)) / brake, 1e-8
    )


def test_free_run_at_top_speed(cli, write_case):
    data = case({"formula": "0*phi"}, {"value": 1.0}, {"start_speed": 1e6, "revolutions": 50.0})
    got = values(run(cli, write_case, data, text=True))
    assert got["final_speed"] == rel(1e6, 1e-12)
    assert got["final_time"] == rel(50 * TWO_PI / 1e6, 1e-12)
    assert got["fluctuation"] == pytest.approx(0.0, abs=1e-12)


# ----------------------------------------------------------------------------- known bugs


def test_inertia_formula_negative_later_is_no_crash(cli, write_case):
    data = case(
        {"formula": "100 - 2*omega"},
        {"formula": "1 + 2*sin(phi)"},
        {"start_speed": 10.0, "revolutions": 1.0},
    )
    result = cli("mechanism", write_case(toml_dumps(data)))
    assert_no_traceback(result)
    assert result.exit_code in (2, 3), (result.exit_code, result.stderr)
    assert "inertia" in (result.stdout + result.stderr)


def test_very_stiff_characteristic_is_solved(cli, write_case):
    a, b, inertia, omega0 = 1e6, 1e4, 1e-3, 10.0
    data = case(
        {"formula": "a - b*omega"},
        {"value": inertia},
        {"start_speed": omega0, "revolutions": 1.0},
        {"a": a, "b": b},
    )
    result = cli("mechanism", write_case(toml_dumps(data)), "--json")
    assert_no_traceback(result)
    assert result.exit_code == 0, result.stdout[-400:]
    got = values(strict_json(result.stdout))
    assert got["final_speed"] == rel(a / b, HAND)


def test_loose_ode_row_stalling_is_no_crash(cli, write_case):
    """I = 1, ω₀ = 10 (E₀ = 50 J), M = -A·sin φ with 2A = E₀·(1 - 10⁻¹⁰)."""
    amplitude = 25.0 * (1.0 - 1e-10)
    data = case(
        {"formula": "-A*sin(phi)"},
        {"value": 1.0},
        {"start_speed": 10.0, "revolutions": 1.0},
        {"A": amplitude},
    )
    result = cli("mechanism", write_case(toml_dumps(data)), "--json")
    assert_no_traceback(result)
    assert result.exit_code == 0, result.stderr
    got = values(strict_json(result.stdout))
    assert got["final_speed"] == rel(10.0, HAND)  # E(2π) = E₀
