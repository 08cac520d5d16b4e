"""``resonance``: torsional resonance of an engine-transmission chain (seed 003,
Tverskov; brief §9).

A free-free chain J₁ - c₁ - J₂ - … - Jₙ (:mod:`mdcalc.core.chain`), some masses
being cranks with firing angles δᵢ.

* Natural frequencies fⱼ and mode shapes, relative amplitudes aᵢ with a = 1 at the
  reference mass (the first mass, or the first crank when the first mass is a node).
* Critical speeds n = 60·f/k for each harmonic order k (half orders for a
  four-stroke engine): a Campbell table over the speed range.
* Resonant amplitude by the energy balance (the seed's (5)): the work of the k-th
  order torque M_k over a cycle, π·M_k·A·|Σ aᵢ·e^(i·k·δᵢ)|, equals the damping work
  π·ω_c·A²·Σ ξᵢ·aᵢ², so A = M_k·|Σ aᵢ·e^(i·k·δᵢ)|/(ω_c·Σ ξᵢ·aᵢ²); shaft torques
  cᵢ(Aᵢ - Aᵢ₊₁). The Methods table sets it against the exact damped steady state
  (K - ω²J + iωΞ)·X = M at the resonant speed and at the peak over speed.
* Parametric resonance (Hooke's joints): x″ + c·x′ + (a - 2q·cos 2t)·x = 0 is
  stable when both Floquet multipliers of one period π lie inside the unit circle;
  det = e^(-cπ) (Liouville), so it is |trace| < 1 + e^(-cπ).
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

from pydantic import Field, model_validator

from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.search import golden_maximum
from mdcalc.methods import Method, compare
from mdcalc.model import CaseBase, CaseModel, FieldError
from mdcalc.report import (
    Column,
    MethodQuantity,
    MethodsTable,
    Note,
    Quantities,
    Quantity,
    Report,
    Table,
    Value,
)

if TYPE_CHECKING:
    from mdcalc.plot import Chart, Series

TWO_PI = 2.0 * math.pi
HZ_TO_RPM = 60.0
MAX_MODES_SHOWN = 5
#: The modal core polishes each mode against the whole chain (O(n³) in all):
#: 60 masses take about 2 s. Engine-transmission models have a few tens.
MAX_MASSES = 60
#: A Floquet verdict within this of the boundary |trace| = 1 + det is "boundary".
BOUNDARY = 1e-9

# ------------------------------------------------------------------------ the case


class ChainSection(CaseModel):
    inertias: list[float] = Field(description="J₁ … Jₙ [kg·m^2]")
    stiffnesses: list[float] = Field(description="c₁ … cₙ₋₁, shaft k joins masses k, k+1 [N·m/rad]")
    damping: list[float] | None = Field(
        default=None, description="ξ₁ … ξₙ, viscous damping of each mass [N·m·s/rad]"
    )
    cranks: list[int] | None = Field(
        default=None, description="Masses that are engine cranks, numbered from 1 [-]"
    )
    firing_angles_deg: list[float] | None = Field(
        default=None, description="δ of each crank: crank angle after the first fires [deg]"
    )
    strokes: Literal[2, 4] = Field(default=4, description="Engine cycle: 2 or 4 strokes [-]")

    @model_validator(mode="after")
    def _shape(self) -> ChainSection:
        n = len(self.inertias)
        if not 2 <= n <= MAX_MASSES:
            raise FieldError(("inertias",), f"{n} masses; a chain has 2 to {MAX_MASSES}")
        for k, j in enumerate(self.inertias):
            if not 0.0 < j <= 1e9:
                raise FieldError(("inertias", k), f"{j:g} kg·m^2 is not in (0, 1e9]")
        if len(self.stiffnesses) != n - 1:
            raise FieldError(
                ("stiffnesses",), f"{len(self.stiffnesses)} shafts for {n} masses; give {n - 1}"
            )
        for k, c in enumerate(self.stiffnesses):
            if not 0.0 < c <= 1e13:
                raise FieldError(("stiffnesses", k), f"{c:g} N·m/rad is not in (0, 1e13]")
        if self.damping is not None:
            if len(self.damping) != n:
                raise FieldError(
                    ("damping",), f"{len(self.damping)} values for {n} masses; give one per mass"
                )
            for k, x in enumerate(self.damping):
                if not 0.0 <= x <= 1e9:
                    raise FieldError(("damping", k), f"{x:g} N·m·s/rad is not in [0, 1e9]")
        if (self.cranks is None) != (self.firing_angles_deg is None):
            missing = "firing_angles_deg" if self.cranks is not None else "cranks"
            raise FieldError((missing,), "cranks and firing_angles_deg go together")
        if self.cranks is not None and self.firing_angles_deg is not None:
            if not self.cranks:
                raise FieldError(("cranks",), "at least one crank")
            if len(set(self.cranks)) != len(self.cranks):
                raise FieldError(("cranks",), "a mass is listed twice")
            for k, m in enumerate(self.cranks):
                if not 1 <= m <= n:
                    raise FieldError(("cranks", k), f"mass {m} does not exist (1 … {n})")
            if len(self.firing_angles_deg) != len(self.cranks):
                raise FieldError(
                    ("firing_angles_deg",),
                    f"{len(self.firing_angles_deg)} angles for {len(self.cranks)} cranks",
                )
            for k, d in enumerate(self.firing_angles_deg):
                if not -1440.0 <= d <= 1440.0:
                    raise FieldError(("firing_angles_deg", k), f"{d:g}° is beyond ±1440°")
        return self


class Campbell(CaseModel):
    from_rpm: float = Field(gt=0, le=1e6, description="Lowest engine speed [rpm]")
    to_rpm: float = Field(gt=0, le=1e6, description="Highest engine speed [rpm]")
    orders: list[float] | None = Field(
        default=None,
        description="Harmonic orders (default: 0.5 … 12 by 0.5, four-stroke; 1 … 12) [-]",
    )

    @model_validator(mode="after")
    def _range(self) -> Campbell:
        if not self.to_rpm > self.from_rpm:
            raise FieldError(("to_rpm",), f"must exceed from_rpm = {self.from_rpm:g}")
        if self.orders is not None:
            if not 1 <= len(self.orders) <= 100:
                raise FieldError(("orders",), "1 to 100 orders")
            for k, o in enumerate(self.orders):
                if not 0.0 < o <= 100.0 or abs(2.0 * o - round(2.0 * o)) > 1e-9:
                    raise FieldError(("orders", k), f"{o:g}: orders are 0.5, 1, 1.5, … ≤ 100")
        return self


class Resonance(CaseModel):
    order: float = Field(gt=0, le=100, description="Harmonic order k (0.5, 1, 1.5, …) [-]")
    mode: int = Field(default=1, ge=1, description="Elastic mode, 1 the slowest [-]")
    harmonic_torque: float | None = Field(
        default=None,
        gt=0,
        le=1e9,
        description="M_k, amplitude of the order's torque per crank [N·m]",
    )

    @model_validator(mode="after")
    def _half(self) -> Resonance:
        if abs(2.0 * self.order - round(2.0 * self.order)) > 1e-9:
            raise FieldError(("order",), f"{self.order:g}: orders are 0.5, 1, 1.5, …")
        return self


class Measured(CaseModel):
    order: float = Field(gt=0, le=100, description="Harmonic order observed [-]")
    speed_rpm: float = Field(gt=0, le=1e6, description="Engine speed of the resonance [rpm]")
    frequency_hz: float | None = Field(
        default=None, gt=0, le=1e6, description="Frequency the measurement states [Hz]"
    )


class Mathieu(CaseModel):
    damping: float = Field(
        default=0.0, ge=0, le=100, description="c in x″ + c·x′ + (a - 2q·cos 2t)·x = 0 [-]"
    )
    points: list[list[float]] = Field(
        default_factory=list, description="(a, q) points to decide, [[a, q], …] [-]"
    )
    chart: bool = Field(default=False, description="Tabulate the Ince–Strutt chart [-]")
    a_from: float = Field(default=0.0, ge=-100, le=100, description="Chart: lowest a [-]")
    a_to: float = Field(default=2.0, ge=-100, le=100, description="Chart: highest a [-]")
    q_to: float = Field(default=1.0, gt=0, le=100, description="Chart: highest q [-]")
    columns: int = Field(default=21, ge=2, le=81, description="Chart: a values [-]")
    rows: int = Field(default=11, ge=2, le=81, description="Chart: q values [-]")

    @model_validator(mode="after")
    def _points(self) -> Mathieu:
        if not self.points and not self.chart:
            raise FieldError(("points",), "give points = [[a, q], …] or chart = true")
        if len(self.points) > 8:
            raise FieldError(("points",), "at most 8 points")
        for k, p in enumerate(self.points):
            if len(p) != 2:
                raise FieldError(("points", k), "a point is [a, q]")
            if not all(abs(v) <= 100.0 for v in p):
                raise FieldError(("points", k), "a and q beyond ±100")
        if not self.a_to > self.a_from:
            raise FieldError(("a_to",), f"must exceed a_from = {self.a_from:g}")
        return self


class Case(CaseBase):
    problem: Literal["resonance"] = Field(description="Problem name [-]")
    chain: ChainSection | None = None
    campbell: Campbell | None = None
    resonance: Resonance | None = None
    measured: list[Measured] | None = Field(default=None, description="Observed resonances")
    mathieu: Mathieu | None = None

    @model_validator(mode="after")
    def _needs(self) -> Case:
        if not any((self.chain, self.measured, self.mathieu)):
            raise ValueError("give [chain], [[measured]] or [mathieu]")
        for key in ("campbell", "resonance"):
            if getattr(self, key) is not None and self.chain is None:
                raise FieldError((key,), "needs [chain]")
        if self.resonance is not None and self.chain is not None:
            r, c = self.resonance, self.chain
            if r.mode > len(c.inertias) - 1:
                raise FieldError(
                    ("resonance", "mode"),
                    f"the chain has {len(c.inertias) - 1} elastic modes",
                )
            if r.harmonic_torque is not None:
                if c.cranks is None:
                    raise FieldError(
                        ("chain", "cranks"), "missing: the harmonic torque acts on the cranks"
                    )
                if c.damping is None:
                    raise FieldError(
                        ("chain", "damping"), "missing: the energy balance needs the damping"
                    )
        if self.measured is not None and len(self.measured) > 50:
            raise FieldError(("measured",), "at most 50 measurements")
        return self


# ------------------------------------------------------------------------ the chain


@dataclass
class Modal:
    frequencies: list[float]  # βⱼ [rad/s]
    shapes: list[list[float]]  # shapes[j][i]: a of mass i in mode j, a = 1 at reference
    moments: list[list[float]]  # moments[j][k]: shaft k's torque per unit reference angle
    references: list[int]  # per mode: index of the mass with a = 1 (the first if it moves)


def modal(section: ChainSection) -> Modal:
    from mdcalc.core.chain import Chain, natural_modes

    chain = Chain(tuple(section.inertias), tuple(section.stiffnesses))
    modes = natural_modes(chain)
    first_crank = (section.cranks[0] - 1) if section.cranks else 0
    shapes, moments, references = [], [], []
    for j in range(chain.size - 1):
        theta = modes.shapes[:, j].tolist()
        spring = modes.moments[:, j].tolist()
        ref = 0 if abs(theta[0]) > 1e-6 else first_crank
        if abs(theta[ref]) <= 1e-6:
            ref = max(range(len(theta)), key=lambda i: abs(theta[i]))
        references.append(ref)
        shapes.append([t / theta[ref] for t in theta])
        moments.append([m / theta[ref] for m in spring])
    return Modal(list(modes.frequencies), shapes, moments, references)


def geometric_sum(section: ChainSection, shape: list[float], order: float) -> complex:
    """Σ aᵢ·e^(i·k·δᵢ) over the cranks."""
    assert section.cranks is not None and section.firing_angles_deg is not None
    return sum(
        (
            shape[m - 1] * cmath.exp(1j * order * math.radians(d))
            for m, d in zip(section.cranks, section.firing_angles_deg, strict=True)
        ),
        0j,
    )


def is_main_order(section: ChainSection, order: float) -> bool:
    """All the cranks' phases k·δᵢ agree modulo 360°: the geometric sum is algebraic."""
    if section.firing_angles_deg is None:
        return False
    phases = [(order * d) % 360.0 for d in section.firing_angles_deg]
    return all(min(abs(p - phases[0]), 360.0 - abs(p - phases[0])) < 1e-6 for p in phases)


@dataclass(frozen=True)
class Amplitudes:
    reference_amplitude: float  # A at the reference mass [rad]
    shaft_torques: list[float]  # amplitude of each shaft's torque [N·m]

    @property
    def max_shaft_torque(self) -> float:
        return max(abs(t) for t in self.shaft_torques)


def energy_method(
    section: ChainSection, md: Modal, mode: int, order: float, torque: float
) -> Amplitudes:
    """The seed's (5): A = M_k·|Σ aᵢe^(ikδᵢ)|/(ω_c·Σ ξᵢaᵢ²)."""
    assert section.damping is not None
    shape = md.shapes[mode]
    omega = md.frequencies[mode]
    dissipation = math.fsum(x * a * a for x, a in zip(section.damping, shape, strict=True))
    if dissipation <= 0.0:
        raise ArithmeticError("no damping moves in this mode")
    amplitude = torque * abs(geometric_sum(section, shape, order)) / (omega * dissipation)
    return Amplitudes(amplitude, [amplitude * m for m in md.moments[mode]])


def forced_response(
    section: ChainSection, md: Modal, mode: int, order: float, torque: float, omega: float
) -> Amplitudes:
    """Exact steady state at vibration frequency ω (crank speed ω/k): torques
    M_k·e^(-i·k·δᵢ) on the cranks, (K - ω²J + iωΞ)·X = M."""
    from mdcalc.core.chain import Chain, harmonic_response

    assert section.cranks is not None and section.firing_angles_deg is not None
    chain = Chain(tuple(section.inertias), tuple(section.stiffnesses))
    load = [0j] * chain.size
    for m, d in zip(section.cranks, section.firing_angles_deg, strict=True):
        load[m - 1] = torque * cmath.exp(-1j * order * math.radians(d))
    angles, springs = harmonic_response(chain, omega, load, absolute_damping=section.damping)
    reference = md.references[mode]
    return Amplitudes(float(abs(angles[reference])), [float(abs(s)) for s in springs])


def peak_response(
    section: ChainSection, md: Modal, mode: int, order: float, torque: float
) -> tuple[float, Amplitudes]:
    """The largest reference amplitude over the vibration frequency near mode j:
    sampled between the neighbouring modes' midpoints, refined by golden section."""
    beta = md.frequencies
    low = 0.5 * (beta[mode - 1] + beta[mode]) if mode > 0 else 0.5 * beta[mode]
    high = 0.5 * (beta[mode] + beta[mode + 1]) if mode + 1 < len(beta) else 1.5 * beta[mode]
    low, high = max(low, 0.8 * beta[mode]), min(high, 1.2 * beta[mode])

    def amplitude(omega: float) -> float:
        return forced_response(section, md, mode, order, torque, omega).reference_amplitude

    samples = 401
    grid = [low + (high - low) * k / (samples - 1) for k in range(samples)]
    values = [amplitude(w) for w in grid]
    k = values.index(max(values))
    low, high = grid[max(k - 1, 0)], grid[min(k + 1, samples - 1)]
    omega = golden_maximum(amplitude, low, high, 80)
    return omega, forced_response(section, md, mode, order, torque, omega)


# ------------------------------------------------------------------ Mathieu / Floquet


def monodromy_rk4(a: Any, q: Any, c: float, steps: int) -> tuple[Any, Any]:
    """Trace and determinant of the period-π map by classical RK4 with ``steps``
    steps; ``a``, ``q`` may be numpy arrays (the chart) or floats."""
    h = math.pi / steps

    def f(t: float, x: Any, v: Any) -> tuple[Any, Any]:
        return v, -c * v - (a - 2.0 * q * math.cos(2.0 * t)) * x

    columns = []
    for x, v in ((1.0 + 0.0 * a, 0.0 * a), (0.0 * a, 1.0 + 0.0 * a)):
        t = 0.0
        for _ in range(steps):
            k1 = f(t, x, v)
            k2 = f(t + h / 2, x + h / 2 * k1[0], v + h / 2 * k1[1])
            k3 = f(t + h / 2, x + h / 2 * k2[0], v + h / 2 * k2[1])
            k4 = f(t + h, x + h * k3[0], v + h * k3[1])
            x = x + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            v = v + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            t += h
        columns.append((x, v))
    (x1, v1), (x2, v2) = columns
    return x1 + v2, x1 * v2 - x2 * v1


def monodromy_ode(a: float, q: float, c: float, rtol: float) -> tuple[float, float]:
    """Trace and determinant of the period-π map by DOP853."""
    import numpy as np

    from mdcalc.core.ode import advance

    def rhs(t: float, y: np.ndarray) -> Any:
        return np.array([y[1], -c * y[1] - (a - 2.0 * q * math.cos(2.0 * t)) * y[0]])

    ends = []
    for start in ((1.0, 0.0), (0.0, 1.0)):
        segment = advance(
            rhs, 0.0, np.array(start), math.pi, rtol=rtol, atol=rtol * 1e-3, method="DOP853"
        )
        ends.append(segment.y)
    (x1, v1), (x2, v2) = ends
    return float(x1 + v2), float(x1 * v2 - x2 * v1)


def liouville(det: float, c: float) -> float:
    """The determinant to use: the computed one (its error goes with the trace's,
    which matters where the multipliers nearly coincide), unless cancellation has
    spoiled it (multipliers far apart); then e^(-cπ), exact by Liouville."""
    exact = math.exp(-c * math.pi)
    return det if abs(det - exact) <= 1e-6 * exact else exact


def spectral_radius(trace: float, det: float) -> float:
    """Largest |μ| of μ² - trace·μ + det = 0."""
    disc = trace * trace - 4.0 * det
    if disc < 0.0:
        return math.sqrt(max(det, 0.0))
    return (abs(trace) + math.sqrt(disc)) / 2.0


def verdict(trace: float, c: float) -> str:
    """stable / unstable / boundary by |trace| against 1 + e^(-cπ)."""
    edge = 1.0 + math.exp(-c * math.pi)
    if abs(abs(trace) - edge) <= BOUNDARY * edge:
        return "boundary"
    return "stable" if abs(trace) < edge else "unstable"


def first_approximation(a: float, q: float, c: float) -> str:
    """Harmonic balance in the principal region: unstable when q² > (a - 1)² + c²."""
    return "unstable" if q * q > (a - 1.0) ** 2 + c * c else "stable"


# ------------------------------------------------------------------------- result


@dataclass
class Result:
    case: Case
    modal: Modal | None = None
    methods: list[MethodsTable] = field(default_factory=list)
    notes: list[Note] = field(default_factory=list)
    floquet: list[tuple[float, float, float, float]] = field(default_factory=list)
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


def solve(case: Case) -> Result:
    result = Result(case)
    if case.chain is not None:
        import numpy as np

        try:
            with np.errstate(all="ignore"):
                result.modal = modal(case.chain)
        except (ArithmeticError, ValueError) as exc:
            result.status, result.message = (
                "no-answer",
                f"the natural modes cannot be computed to working precision ({exc}): the "
                "chain's inertias and stiffnesses span too many decades over its length",
            )
            return result
    r = case.resonance
    if r is not None and r.harmonic_torque is not None:
        assert case.chain is not None and result.modal is not None
        md, j = result.modal, r.mode - 1
        section, torque = case.chain, r.harmonic_torque
        assert section.damping is not None
        dissipation = math.fsum(
            x * a * a for x, a in zip(section.damping, md.shapes[j], strict=True)
        )
        if dissipation <= 1e-12 * math.fsum(section.damping) or not any(section.damping):
            result.status, result.message = (
                "no-answer",
                f"undamped resonance: no damping moves in mode {r.mode} (Σ ξᵢ·aᵢ² = 0), "
                "the resonant amplitude is unbounded; give the masses damping",
            )
            return result
        omega = md.frequencies[j]
        try:
            forced_response(section, md, j, r.order, torque, omega)
        except ArithmeticError:
            result.status, result.message = (
                "no-answer",
                f"the damped response at the resonance of mode {r.mode} cannot be resolved: "
                "(K - ω²J + iωΞ) is singular to working precision at ω = β: the damping "
                f"(Σ ξᵢ·aᵢ² = {dissipation:.3g} N·m·s/rad) is too small against the "
                "stiffness, so the amplitude is practically unbounded, or the stiffnesses "
                "span too many decades for the shaft torques to keep any digits",
            )
            return result

        def as_values(amp: Amplitudes) -> dict[str, float]:
            return {"amplitude": amp.reference_amplitude, "max_shaft_torque": amp.max_shaft_torque}

        methods = [
            Method(
                "energy balance, seed (5)",
                lambda: as_values(energy_method(section, md, j, r.order, torque)),
                note="free mode shape, phase diagram",
            ),
            Method(
                "exact forced response at ω = β",
                lambda: as_values(forced_response(section, md, j, r.order, torque, omega)),
                reference=True,
                note="(K - ω²J + iωΞ)·X = M",
            ),
            Method(
                "exact, peak over speed",
                lambda: as_values(peak_response(section, md, j, r.order, torque)[1]),
                note="golden section near β",
            ),
        ]
        result.methods.append(
            compare(
                f"Methods: resonance of order {r.order:g} with mode {r.mode}",
                "resonance",
                [
                    MethodQuantity("amplitude", "A at the reference mass", "rad"),
                    MethodQuantity("max_shaft_torque", "largest shaft torque", "N·m"),
                ],
                methods,
            )
        )
    m = case.mathieu
    if m is not None and m.points:
        c = m.damping
        for a, q in m.points:
            trace, det = monodromy_ode(a, q, c, 1e-12)
            result.floquet.append((a, q, trace, liouville(det, c)))
        quantities = [
            MethodQuantity(f"floquet_radius_{k + 1}", f"ρ at (a, q) = ({a:g}, {q:g})", "")
            for k, (a, q) in enumerate(m.points)
        ]

        def radii(
            run: Callable[[float, float], tuple[float, float]],
        ) -> Callable[[], dict[str, float]]:
            def go() -> dict[str, float]:
                out = {}
                for k, (a, q) in enumerate(m.points):
                    trace, det = run(a, q)
                    out[f"floquet_radius_{k + 1}"] = spectral_radius(trace, liouville(det, c))
                return out

            return go

        result.methods.append(
            compare(
                "Methods: Floquet multipliers of one period",
                "floquet",
                quantities,
                [
                    Method("RK4, 32 steps", radii(lambda a, q: monodromy_rk4(a, q, c, 32))),
                    Method("RK4, 256 steps", radii(lambda a, q: monodromy_rk4(a, q, c, 256))),
                    Method(
                        "DOP853 rtol 1e-7",
                        radii(lambda a, q: monodromy_ode(a, q, c, 1e-7)),
                        imports=ODE_IMPORTS,
                    ),
                    Method(
                        "DOP853 rtol 1e-12",
                        radii(lambda a, q: monodromy_ode(a, q, c, 1e-12)),
                        reference=True,
                        imports=ODE_IMPORTS,
                    ),
                ],
            )
        )
    return result


# ------------------------------------------------------------------------- report


def report(result: Result) -> Report:
    case = result.case
    title = case.title or "Torsional resonance"
    sections: list[Any] = []
    notes = list(result.notes)
    c = case.chain
    md = result.modal
    if md is None and c is not None:
        return Report("resonance", title, sections, notes, result.status, result.message)
    if c is not None and md is not None:
        sections += _modes_sections(c, md)
        if case.campbell is not None:
            sections.append(_campbell_table(c, md, case.campbell))
        if case.resonance is not None:
            sections.append(_resonance_section(c, md, case.resonance, result.status == "ok"))
            if case.resonance.harmonic_torque is not None and result.status == "ok":
                sections.append(_shaft_table(c, md, case.resonance))
    if case.measured is not None:
        sections += _measured_sections(case.measured, md)
    if result.status != "ok":
        return Report("resonance", title, sections, notes, result.status, result.message)
    sections += [t for t in result.methods if t.key == "resonance"]
    if case.mathieu is not None:
        sections += _mathieu_sections(case.mathieu, result)
        sections += [t for t in result.methods if t.key == "floquet"]
    return Report("resonance", title, sections, notes)


def _modes_sections(c: ChainSection, md: Modal) -> list[Any]:
    shown = min(len(md.frequencies), MAX_MODES_SHOWN)
    items = []
    for j in range(shown):
        beta = md.frequencies[j]
        items.append(
            Quantity(
                f"frequency_{j + 1}",
                f"Mode {j + 1}: natural frequency f",
                beta / TWO_PI,
                "Hz",
                f"β = {beta:.6g} rad/s",
            )
        )
    columns = [Column("mass"), Column("J", "kg·m²")]
    columns += [Column(f"a, mode {j + 1}") for j in range(shown)]
    rows: list[list[Value]] = []
    cranks = set(c.cranks or [])
    for i, inertia in enumerate(c.inertias):
        label = f"{i + 1}" + (" (crank)" if i + 1 in cranks else "")
        rows.append([label, inertia, *(md.shapes[j][i] for j in range(shown))])
    ref = ", ".join(sorted({str(r + 1) for r in md.references[:shown]}))
    return [
        Quantities("Natural frequencies", items),
        Table(f"Mode shapes, relative amplitudes (a = 1 at mass {ref})", "modes", columns, rows),
    ]


def default_orders(strokes: int) -> list[float]:
    step = 0.5 if strokes == 4 else 1.0
    return [step * k for k in range(1, int(12 / step) + 1)]


def _campbell_table(c: ChainSection, md: Modal, cb: Campbell) -> Table:
    orders = cb.orders or default_orders(c.strokes)
    rows: list[list[Value]] = []
    for j, beta in enumerate(md.frequencies):
        f = beta / TWO_PI
        for k in orders:
            speed = HZ_TO_RPM * f / k
            if not cb.from_rpm <= speed <= cb.to_rpm:
                continue
            row: list[Value] = [speed, k, j + 1, f]
            if c.cranks is not None:
                row += [
                    abs(geometric_sum(c, md.shapes[j], k)),
                    "main" if is_main_order(c, k) else "",
                ]
            rows.append(row)
    rows.sort(key=lambda r: float(r[0]))
    columns = [
        Column("critical speed", "rpm"),
        Column("order k"),
        Column("mode"),
        Column("f", "Hz"),
    ]
    if c.cranks is not None:
        columns += [Column("|Σ a·e^(ikδ)|"), Column("order")]
    return Table(
        f"Campbell table: n = 60·f/k within {cb.from_rpm:g} … {cb.to_rpm:g} rpm",
        "campbell",
        columns,
        rows,
    )


def _resonance_section(c: ChainSection, md: Modal, r: Resonance, solved: bool) -> Quantities:
    j = r.mode - 1
    beta = md.frequencies[j]
    f = beta / TWO_PI
    items = [
        Quantity("resonance_frequency", f"Mode {r.mode} frequency f", f, "Hz"),
        Quantity(
            "critical_speed_rpm",
            f"Critical speed of order {r.order:g}, n = 60·f/k",
            HZ_TO_RPM * f / r.order,
            "rpm",
        ),
    ]
    if c.cranks is not None:
        s = geometric_sum(c, md.shapes[j], r.order)
        items += [
            Quantity("geometric_sum", "|Σ aᵢ·e^(i·k·δᵢ)| over the cranks", abs(s), ""),
            Quantity(
                "algebraic_sum",
                "Σ aᵢ over the cranks",
                math.fsum(md.shapes[j][m - 1] for m in c.cranks),
                "",
            ),
            Quantity("main_order", "Main order (all phases equal)", is_main_order(c, r.order), ""),
        ]
    if r.harmonic_torque is not None and c.damping is not None:
        dissipation = math.fsum(x * a * a for x, a in zip(c.damping, md.shapes[j], strict=True))
        items.append(Quantity("modal_damping", "Σ ξᵢ·aᵢ²", dissipation, "N·m·s/rad"))
        if solved:
            amp = energy_method(c, md, j, r.order, r.harmonic_torque)
            exact = forced_response(c, md, j, r.order, r.harmonic_torque, beta)
            items += [
                Quantity(
                    "amplitude",
                    f"A at mass {md.references[j] + 1}, energy balance (5)",
                    amp.reference_amplitude,
                    "rad",
                    f"{math.degrees(amp.reference_amplitude):.4g}°",
                ),
                Quantity(
                    "amplitude_exact",
                    "A, exact damped response at ω = β",
                    exact.reference_amplitude,
                    "rad",
                ),
                Quantity(
                    "max_shaft_torque",
                    "Largest shaft torque, energy balance",
                    amp.max_shaft_torque,
                    "N·m",
                ),
                Quantity(
                    "max_shaft_torque_exact",
                    "Largest shaft torque, exact",
                    exact.max_shaft_torque,
                    "N·m",
                ),
            ]
    return Quantities(f"Resonance: order {r.order:g}, mode {r.mode}", items)


def _shaft_table(c: ChainSection, md: Modal, r: Resonance) -> Table:
    assert r.harmonic_torque is not None
    j = r.mode - 1
    amp = energy_method(c, md, j, r.order, r.harmonic_torque)
    exact = forced_response(c, md, j, r.order, r.harmonic_torque, md.frequencies[j])
    rows: list[list[Value]] = []
    for k, stiffness in enumerate(c.stiffnesses):
        rows.append(
            [f"{k + 1}–{k + 2}", stiffness, abs(amp.shaft_torques[k]), exact.shaft_torques[k]]
        )
    return Table(
        "Shaft torques at the resonance, cₖ·(Aₖ - Aₖ₊₁)",
        "shafts",
        [
            Column("shaft"),
            Column("c", "N·m/rad"),
            Column("energy balance", "N·m"),
            Column("exact", "N·m"),
        ],
        rows,
    )


def _measured_sections(measured: list[Measured], md: Modal | None) -> list[Any]:
    items = []
    columns = [Column("order k"), Column("speed", "rpm"), Column("f = n·k/60", "Hz")]
    columns.append(Column("stated f", "Hz"))
    columns.append(Column("stated/implied - 1"))
    if md is not None:
        columns += [
            Column("nearest mode"),
            Column("its f", "Hz"),
            Column("its critical speed", "rpm"),
        ]
    rows: list[list[Value]] = []
    for k, m in enumerate(measured):
        f = m.speed_rpm * m.order / HZ_TO_RPM
        items.append(
            Quantity(
                f"measured_frequency_{k + 1}",
                f"Order {m.order:g} at {m.speed_rpm:g} rpm: f = n·k/60",
                f,
                "Hz",
            )
        )
        row: list[Value] = [m.order, m.speed_rpm, f]
        row += [m.frequency_hz, m.frequency_hz / f - 1.0] if m.frequency_hz else ["", ""]
        if m.frequency_hz is not None:
            items.append(
                Quantity(
                    f"stated_speed_{k + 1}",
                    f"Speed at which order {m.order:g} meets the stated {m.frequency_hz:g} Hz",
                    HZ_TO_RPM * m.frequency_hz / m.order,
                    "rpm",
                )
            )
        if md is not None:
            fs = [b / TWO_PI for b in md.frequencies]
            j = min(range(len(fs)), key=lambda i: abs(fs[i] - f))
            row += [j + 1, fs[j], HZ_TO_RPM * fs[j] / m.order]
        rows.append(row)
    return [
        Quantities("Measured resonances", items),
        Table("Measured resonances against n = 60·f/k", "measured", columns, rows),
    ]


def _mathieu_sections(m: Mathieu, result: Result) -> list[Any]:
    out: list[Any] = []
    c = m.damping
    if result.floquet:
        items = []
        rows: list[list[Value]] = []
        for k, (a, q, trace, det) in enumerate(result.floquet):
            rho = spectral_radius(trace, det)
            state = verdict(trace, c)
            items.append(
                Quantity(
                    f"stability_{k + 1}",
                    f"(a, q) = ({a:g}, {q:g})",
                    state,
                    "",
                    f"|trace| = {abs(trace):.6g} against 1 + e^(-cπ) = "
                    f"{1 + math.exp(-c * math.pi):.6g}",
                )
            )
            items.append(
                Quantity(f"floquet_radius_{k + 1}", f"ρ = max |μ| at ({a:g}, {q:g})", rho, "")
            )
            rows.append(
                [a, q, trace, math.exp(-c * math.pi), rho, state, first_approximation(a, q, c)]
            )
        out.append(
            Quantities(f"Parametric resonance, c = {c:g}: x″ + c·x′ + (a - 2q·cos 2t)·x = 0", items)
        )
        out.append(
            Table(
                "Floquet multipliers of one period π (DOP853, rtol 1e-12)",
                "floquet_points",
                [
                    Column("a"),
                    Column("q"),
                    Column("trace"),
                    Column("det = e^(-cπ)"),
                    Column("ρ = max |μ|"),
                    Column("verdict"),
                    Column("first approximation"),
                ],
                rows,
            )
        )
    if m.chart:
        out.append(_chart(m))
    return out


def _chart(m: Mathieu) -> Table:
    import numpy as np

    a_values = np.linspace(m.a_from, m.a_to, m.columns)
    q_values = np.linspace(0.0, m.q_to, m.rows)
    a_grid, q_grid = np.meshgrid(a_values, q_values)
    trace, _ = monodromy_rk4(a_grid, q_grid, m.damping, 400)
    edge = 1.0 + math.exp(-m.damping * math.pi)
    rows: list[list[Value]] = []
    for i in range(m.rows - 1, -1, -1):
        marks = "".join("·" if abs(t) < edge else "█" for t in trace[i].tolist())
        rows.append([float(q_values[i]), marks])
    return Table(
        f"Ince–Strutt chart, c = {m.damping:g}: █ unstable, · stable; "
        f"a from {m.a_from:g} to {m.a_to:g} in {m.columns} columns (RK4, 400 steps)",
        "chart",
        [Column("q"), Column("a →")],
        rows,
    )


# ------------------------------------------------------------------------- charts

#: The Ince–Strutt map of ``--plot``: a coarse grid of RK4 monodromies, vectorized
#: (a few tenths of a second); the report's own chart (``chart = true``) is a table.
MAP_COLUMNS = 61  # q values
MAP_ROWS = 81  # a values
MAP_STEPS = 400
#: Orders drawn as rays each with its own legend entry; more share one entry.
LABELLED_ORDERS = 6


def charts(result: Result) -> list[Chart]:
    """``--plot``: the Campbell diagram (natural frequencies against engine speed, the
    orders k·n/60 as rays, the critical speeds where they meet, measured resonances),
    and with [mathieu] the Ince–Strutt chart with the case's points."""
    out: list[Chart] = []
    campbell = _campbell_chart(result.case, result.modal)
    if campbell is not None:
        out.append(campbell)
    if result.case.mathieu is not None:
        out.append(_ince_strutt_chart(result.case.mathieu))
    return out


def _campbell_chart(case: Case, md: Modal | None) -> Chart | None:
    """Over the [campbell] range and orders; without it, from 0 to 1.25 times the
    critical speed of [resonance] and the measured speeds, with their orders."""
    from mdcalc.plot import Chart, Mark, Series

    c, cb, r, measured = case.chain, case.campbell, case.resonance, case.measured or []
    orders = {m.order for m in measured}
    speeds = [m.speed_rpm for m in measured]
    marks: list[Mark] = []
    if md is not None and c is not None and cb is not None:
        orders |= set(cb.orders or default_orders(c.strokes))
        low, high = cb.from_rpm, cb.to_rpm
        marks = [Mark("x", low, "speed range of the Campbell table"), Mark("x", high)]
    else:
        if md is not None and r is not None:
            orders.add(r.order)
            speeds.append(HZ_TO_RPM * md.frequencies[r.mode - 1] / TWO_PI / r.order)
        if not speeds:
            return None
        low, high = 0.0, 1.25 * max(speeds)
    ks = sorted(orders)
    series: list[Series] = []
    if md is not None:
        top = ks[-1] * high / HZ_TO_RPM  # the highest ray's frequency at the top speed
        fs = [beta / TWO_PI for beta in md.frequencies]
        shown = [j for j, f in enumerate(fs) if f <= top][:MAX_MODES_SHOWN] or [0]
        for j in shown:
            series.append(Series(f"mode {j + 1}: f = {fs[j]:.4g} Hz", [0.0, high], [fs[j]] * 2))
    if len(ks) <= LABELLED_ORDERS:
        for k in ks:
            series.append(
                Series(f"order k = {k:g}", [0.0, high], [0.0, k * high / HZ_TO_RPM], "dashed")
            )
    else:  # one polyline out and back along each ray: one legend entry for the fan
        x, y = [0.0], [0.0]
        for k in ks:
            x += [high, 0.0]
            y += [k * high / HZ_TO_RPM, 0.0]
        series.append(Series(f"orders k·n/60, k = {ks[0]:g} … {ks[-1]:g}", x, y, "dashed"))
    if md is not None:
        critical = [
            (HZ_TO_RPM * fs[j] / k, fs[j])
            for j in shown
            for k in ks
            if low <= HZ_TO_RPM * fs[j] / k <= high
        ]
        if critical:
            series.append(
                Series(
                    "critical speeds n = 60·f/k",
                    [n for n, _ in critical],
                    [f for _, f in critical],
                    "points",
                )
            )
    if measured:
        series.append(
            Series(
                "measured: f = n·k/60",
                [m.speed_rpm for m in measured],
                [m.speed_rpm * m.order / HZ_TO_RPM for m in measured],
                "points",
            )
        )
        stated = [m for m in measured if m.frequency_hz is not None]
        if stated:
            series.append(
                Series(
                    "measured: the f stated",
                    [m.speed_rpm for m in stated],
                    [m.frequency_hz or 0.0 for m in stated],
                    "points",
                )
            )
    return Chart(
        "Campbell diagram: natural frequencies, engine orders f = k·n/60, "
        "critical speeds n = 60·f/k",
        "engine speed n [rpm]",
        "frequency f [Hz]",
        series,
        marks,
    )


def _widened(low: float, high: float, points: list[float]) -> tuple[float, float]:
    """[low, high] widened to hold the points, with a margin beyond those outside."""
    lowest, highest = min([low, *points]), max([high, *points])
    pad = 0.05 * (highest - lowest)
    return (low if lowest >= low else lowest - pad), (high if highest <= high else highest + pad)


def _ince_strutt_chart(m: Mathieu) -> Chart:
    """Stable and unstable regions of x″ + c·x′ + (a - 2q·cos 2t)·x = 0 over (q, a):
    |trace| of the period-π map against 1 + e^(-cπ) (RK4, vectorized over the grid),
    over the chart's range widened to the case's points, which are marked."""
    import numpy as np

    from mdcalc.plot import Chart, Series, Shade

    c = m.damping
    a_low, a_high = _widened(m.a_from, m.a_to, [p[0] for p in m.points])
    q_low, q_high = _widened(0.0, m.q_to, [p[1] for p in m.points])
    q_values = np.linspace(q_low, q_high, MAP_COLUMNS)
    a_values = np.linspace(a_low, a_high, MAP_ROWS)
    q_grid, a_grid = np.meshgrid(q_values, a_values)  # [i, j] at (q_j, a_i)
    with np.errstate(all="ignore"):
        trace, _ = monodromy_rk4(a_grid, q_grid, c, MAP_STEPS)
        ratio = np.abs(trace) / (1.0 + math.exp(-c * math.pi))
    # 0 … 1 stable, 1 … 2 unstable (a growth too fast for floats is unstable too)
    z = np.where(np.isfinite(ratio), np.minimum(ratio, 2.0), 2.0)
    series = []
    # first approximation (harmonic balance): the principal tongue a = 1 ± √(q² - c²)
    start = max(q_low, c)
    edge = np.linspace(start, q_high, 201).tolist() if start < q_high else []
    tongue = [(q, 1.0 - math.sqrt(q * q - c * c)) for q in reversed(edge)]
    tongue += [(q, 1.0 + math.sqrt(q * q - c * c)) for q in edge]
    tongue = [(q, a) for q, a in tongue if a_low <= a <= a_high]
    if tongue:
        series.append(
            Series(
                "first approximation, a = 1 ± √(q² - c²)",
                [q for q, _ in tongue],
                [a for _, a in tongue],
                "dashed",
            )
        )
    if m.points:
        series.append(
            Series(
                "the case's (q, a)",
                [p[1] for p in m.points],
                [p[0] for p in m.points],
                "points",
            )
        )
    return Chart(
        f"Ince–Strutt chart of x″ + c·x′ + (a - 2q·cos 2t)·x = 0, c = {c:g} "
        "(dark: unstable, Floquet)",
        "q [-]",
        "a [-]",
        series,
        shade=Shade(
            q_values.tolist(), a_values.tolist(), z.tolist(), "unstable", levels=[0.0, 1.0, 2.0]
        ),
    )


def template() -> dict[str, Any]:
    return {
        "problem": "resonance",
        "title": "Six-cylinder in-line engine, flywheel and gearbox",
        "chain": {
            "inertias": [0.02, 0.02, 0.02, 0.02, 0.02, 0.02, 0.6, 0.05],
            "stiffnesses": [3.0e5, 3.0e5, 3.0e5, 3.0e5, 3.0e5, 6.0e5, 2.0e4],
            "damping": [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0],
            "cranks": [1, 2, 3, 4, 5, 6],
            "firing_angles_deg": [0.0, 480.0, 240.0, 600.0, 120.0, 360.0],
            "strokes": 4,
        },
        "campbell": {"from_rpm": 600.0, "to_rpm": 3000.0},
        "resonance": {"order": 4.5, "mode": 2, "harmonic_torque": 50.0},
        "mathieu": {"damping": 0.05, "points": [[1.0, 0.1], [1.0, 0.02]]},
    }
