"""``mechanism``: motion of a one-degree-of-freedom mechanism under a torque that
depends on position and speed, by Kovylin's linearization (seed 001, brief §8).

Given the reduced torque M(φ, ω) and the reduced inertia I(φ), and ω = ω₀ at φ₀,
find ω(φ). Over a step from φ_i to φ_k the energy balance (1)
I_k·ω_k²/2 - I_i·ω_i²/2 = ∫M dφ, with ω_k² ≈ ω_i² + 2ω_iΔω (3) and M linearized
in ω (4), gives Kovylin's step (5):

    Δω = [2·M′·Δφ + (I_i - I_k)·ω_i²] / [2·I_k·ω_i - C·Δφ],
    M′ = ½[M(φ_i, ω_i) + M(φ_k, ω_i)],  C = ∂M/∂ω at (φ_k, ω_i).

From rest (ω_i = 0) (5) is undefined; the step then solves (1) with the same
linearized torque without (3): I_k·ω_k² - C·Δφ·ω_k - 2·M′·Δφ = 0. A step whose
denominator is not positive, whose ω_k is not positive or whose increment is more
than half of ω_i is halved (the seed: "refine the step"), down to 2⁻³⁰ of it.

The reference integrates the energy E = I·ω²/2 over the angle, dE/dφ = M(φ, ω),
ω = √(2E/I(φ)), and the time dt/dφ = 1/ω: no derivative of I is needed, and the
mechanism stalls where E reaches zero (exit 3 with the angle and the time).
M and I come as formulas (:mod:`mdcalc.expr`, never ``eval``) or as tables over
one revolution, interpolated linearly and periodically; M may be tabulated over
angle and speed.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

from pydantic import Field, field_validator, model_validator

from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.search import golden_maximum
from mdcalc.core.units import rpm_to_rad_s
from mdcalc.expr import ExpressionError, check_name, parse
from mdcalc.methods import Method, NotApplicable, compare
from mdcalc.model import CaseBase, CaseModel, FieldError, exactly_one
from mdcalc.report import (
    Column,
    MethodQuantity,
    MethodsTable,
    Note,
    Quantities,
    Quantity,
    Report,
    Table,
)

if TYPE_CHECKING:
    from mdcalc.plot import Chart

TWO_PI = 2.0 * math.pi
DEG = math.pi / 180.0
RAD_S_TO_RPM = 30.0 / math.pi
#: Largest number of halvings of one Kovylin step (2⁻³⁰ of the user's step).
MAX_REFINEMENT = 30
#: Kovylin's assumption (3) needs a small increment: a step whose |Δω| exceeds this
#: fraction of ω_i is halved.
MAX_INCREMENT = 0.5
REFERENCE_RTOL = 1e-11
STIFF_REFERENCE_RTOL = 1e-10
LOOSE_RTOL = 1e-6
#: Above this product of |∂(dE/dφ)/∂E| and the angle span the reference uses Radau.
STIFFNESS_LIMIT = 1e3
#: Right-hand-side evaluations an ODE row may use before it is reported as too long.
EVALUATION_BUDGET = 400_000
#: An explicit reference that needs more than this is taken as stiff and rerun by Radau.
EXPLICIT_BUDGET = 100_000
TABLE_ROWS = 37
#: Kovylin nodes over the run at the user's n (the Methods table runs 7 times as many).
MAX_NODES = 20_000

# ------------------------------------------------------------------------ the case


class _Tabulated(CaseModel):
    angles: list[float] | None = Field(
        default=None, description="Angles of the table over one revolution [rad]"
    )
    angles_deg: list[float] | None = Field(
        default=None, description="Angles of the table over one revolution [deg]"
    )

    def table_angles(self) -> list[float] | None:
        if self.angles is not None:
            return list(self.angles)
        if self.angles_deg is not None:
            return [a * DEG for a in self.angles_deg]
        return None

    def _check_angles(self, values: int) -> None:
        angles = self.table_angles()
        assert angles is not None
        key = "angles" if self.angles is not None else "angles_deg"
        if len(angles) < 2:
            raise FieldError((key,), "a table needs at least 2 angles")
        if len(angles) != values:
            raise FieldError(
                ("values",), f"{values} values for {len(angles)} angles; give one per angle"
            )
        for a, b in zip(angles, angles[1:], strict=False):
            if not b > a:
                raise FieldError((key,), "angles must increase strictly")
        if angles[-1] - angles[0] > TWO_PI * (1.0 + 1e-12):
            raise FieldError(
                (key,), "a table covers one revolution (it repeats every 360°); the span is more"
            )
        if not all(math.isfinite(a) and abs(a) <= 1e3 for a in angles):
            raise FieldError((key,), "angles beyond ±1000 rad")

    def _check_closing(self, rows: list[Any]) -> None:
        """A table that spans the whole revolution repeats its first row last."""
        angles = self.table_angles()
        assert angles is not None
        if angles[-1] - angles[0] < TWO_PI * (1.0 - 1e-12):
            return
        first, last = rows[0], rows[-1]
        pairs = zip(first, last, strict=True) if isinstance(first, list) else [(first, last)]
        for a, b in pairs:
            if abs(a - b) > 1e-9 * max(abs(a), abs(b), 1e-300):
                raise FieldError(
                    ("values", len(rows) - 1),
                    f"the table spans 360°, so its last row repeats the first: {b!r} ≠ {a!r}",
                )


class Torque(_Tabulated):
    formula: str | None = Field(
        default=None,
        description="M(phi, omega) as a formula of phi [rad] and omega [rad/s] [N·m]",
    )
    speeds: list[float] | None = Field(
        default=None, description="Speeds of a two-way table M(φ, ω), increasing [rad/s]"
    )
    values: list[float] | list[list[float]] | None = Field(
        default=None,
        description="M at the angles, or one row per angle at the speeds [N·m]",
    )

    @model_validator(mode="after")
    def _one(self) -> Torque:
        table = self.table_angles()
        if self.angles is not None and self.angles_deg is not None:
            raise FieldError(("angles_deg",), "give angles or angles_deg, not both")
        exactly_one("torque", formula=self.formula, table=table)
        if self.formula is not None:
            for key in ("values", "speeds"):
                if getattr(self, key) is not None:
                    raise FieldError((key,), "a formula takes no table; remove this key")
            return self
        if self.values is None:
            raise FieldError(("values",), "missing: the torque at each angle [N·m]")
        self._check_angles(len(self.values))
        rows = self.values
        if self.speeds is None:
            if any(isinstance(v, list) for v in rows):
                raise FieldError(("values",), "rows of values need speeds = [...]")
        else:
            if len(self.speeds) < 2 or any(
                not b > a for a, b in zip(self.speeds, self.speeds[1:], strict=False)
            ):
                raise FieldError(("speeds",), "at least 2 speeds, strictly increasing")
            for i, row in enumerate(rows):
                if not isinstance(row, list) or len(row) != len(self.speeds):
                    raise FieldError(
                        ("values", i), f"a row of {len(self.speeds)} values, one per speed"
                    )
        for v in _flat(rows):
            if abs(v) > 1e12:
                raise FieldError(("values",), f"torque {v:g} N·m is beyond ±1e12")
        self._check_closing(list(rows))
        return self


class Inertia(_Tabulated):
    value: float | None = Field(default=None, gt=0, le=1e12, description="Constant I [kg·m^2]")
    formula: str | None = Field(default=None, description="I(phi), phi in [rad] [kg·m^2]")
    values: list[float] | None = Field(default=None, description="I at the angles [kg·m^2]")

    @model_validator(mode="after")
    def _one(self) -> Inertia:
        if self.angles is not None and self.angles_deg is not None:
            raise FieldError(("angles_deg",), "give angles or angles_deg, not both")
        exactly_one("inertia", value=self.value, formula=self.formula, table=self.table_angles())
        if self.table_angles() is not None:
            if self.values is None:
                raise FieldError(("values",), "missing: the inertia at each angle [kg·m^2]")
            self._check_angles(len(self.values))
            for v in self.values:
                if not 0.0 < v <= 1e12:
                    raise FieldError(("values",), f"inertia {v:g} kg·m^2 is not in (0, 1e12]")
            self._check_closing(list(self.values))
        elif self.values is not None:
            raise FieldError(("values",), "values need angles or angles_deg")
        return self


class Motion(CaseModel):
    start_angle: float = Field(default=0.0, ge=-1e3, le=1e3, description="φ₀ [rad]")
    start_speed: float | None = Field(
        default=None, ge=0, le=1e6, description="ω₀ at φ₀; 0 starts from rest [rad/s]"
    )
    start_speed_rpm: float | None = Field(default=None, ge=0, le=1e7, description="ω₀ at φ₀ [rpm]")
    revolutions: float = Field(
        ge=1e-3, le=100, description="Angle to follow, in revolutions of the link [-]"
    )
    steps_per_revolution: int = Field(
        default=16, ge=4, le=100_000, description="Kovylin's steps per revolution n [-]"
    )

    @model_validator(mode="after")
    def _one(self) -> Motion:
        exactly_one("motion", start_speed=self.start_speed, start_speed_rpm=self.start_speed_rpm)
        nodes = self.revolutions * self.steps_per_revolution
        if nodes > MAX_NODES:
            raise FieldError(
                ("steps_per_revolution",),
                f"revolutions × steps_per_revolution = {nodes:.6g}; at most {MAX_NODES} "
                "(the Methods table runs Kovylin at n, 2n and 4n)",
            )
        return self


class Case(CaseBase):
    problem: Literal["mechanism"] = Field(description="Problem name [-]")
    parameters: dict[str, float] = Field(
        default_factory=dict, description="Named numbers the formulas may use [-]"
    )
    torque: Torque
    inertia: Inertia
    motion: Motion

    @field_validator("parameters")
    @classmethod
    def _names(cls, value: dict[str, float]) -> dict[str, float]:
        for name, number in value.items():
            try:
                check_name(name, VARIABLES)
            except ExpressionError as exc:
                raise FieldError((name,), str(exc)) from None
            if not math.isfinite(number) or abs(number) > 1e15:
                raise FieldError((name,), f"{number:g} is beyond ±1e15")
        return value

    @model_validator(mode="after")
    def _formulas(self) -> Case:
        start = self.motion.start_angle
        omega = _start_speed(self.motion)
        for section, variables in (("torque", VARIABLES), ("inertia", ("phi",))):
            text = getattr(self, section).formula
            if text is None:
                continue
            try:
                expression = parse(text, variables, self.parameters)
                value = expression(phi=start, omega=omega)
            except ExpressionError as exc:
                raise FieldError((section, "formula"), str(exc)) from None
            except ArithmeticError as exc:
                raise FieldError(
                    (section, "formula"), f"cannot be evaluated at the start φ₀, ω₀: {exc}"
                ) from None
            if section == "inertia":
                self._inertia_positive(expression, value)
        return self

    def _inertia_positive(self, expression: Any, value: float) -> None:
        """I(φ) > 0 over the run, checked every half degree (at most 20 000 points)."""
        start, span = self.motion.start_angle, self.motion.revolutions * TWO_PI
        count = min(20_000, max(2, math.ceil(span / (0.5 * DEG))))
        phi = start
        for k in range(count + 1):
            phi = start + span * k / count
            try:
                value = expression(phi=phi)
            except ArithmeticError as exc:
                raise FieldError(
                    ("inertia", "formula"), f"cannot be evaluated at φ = {phi:.6g} rad: {exc}"
                ) from None
            if not 0.0 < value <= 1e12:
                raise FieldError(
                    ("inertia", "formula"),
                    f"I(φ) = {value:.6g} kg·m^2 at φ = {phi:.6g} rad; an inertia must be "
                    "in (0, 1e12]",
                )


VARIABLES = ("phi", "omega")


def _flat(rows: list[float] | list[list[float]]) -> list[float]:
    out: list[float] = []
    for row in rows:
        out.extend(row if isinstance(row, list) else [row])
    return out


def _start_speed(motion: Motion) -> float:
    if motion.start_speed is not None:
        return motion.start_speed
    return rpm_to_rad_s(motion.start_speed_rpm or 0.0)


# ------------------------------------------------------------------------ the scene


class Periodic:
    """Linear interpolation of a table over one revolution, repeated every 2π."""

    def __init__(self, angles: list[float], values: list[float]) -> None:
        if angles[-1] - angles[0] >= TWO_PI * (1.0 - 1e-12):  # a closing point: drop it
            angles, values = angles[:-1], values[:-1]
        self.start = angles[0]
        self.angles = [*angles, angles[0] + TWO_PI]
        self.values = [*values, values[0]]

    def __call__(self, phi: float) -> float:
        x = self.start + (phi - self.start) % TWO_PI
        k = min(max(bisect.bisect_right(self.angles, x) - 1, 0), len(self.angles) - 2)
        a0, a1 = self.angles[k], self.angles[k + 1]
        w = (x - a0) / (a1 - a0)
        return self.values[k] + w * (self.values[k + 1] - self.values[k])


@dataclass(frozen=True)
class Scene:
    torque: Callable[[float, float], float]  # M(φ, ω) [N·m]
    slope: Callable[[float, float], float]  # ∂M/∂ω [N·m·s/rad]
    inertia: Callable[[float], float]  # I(φ) [kg·m²]
    depends_on_speed: bool
    start_angle: float
    start_speed: float
    revolutions: float
    steps: int  # per revolution
    speed_range: tuple[float, float] | None  # of a two-way table
    breaks: tuple[float, ...] = ()  # table knots in [0, 2π): kinks of M or I

    @property
    def span(self) -> float:
        return self.revolutions * TWO_PI

    @property
    def end_angle(self) -> float:
        return self.start_angle + self.span


def _central_slope(torque: Callable[[float, float], float]) -> Callable[[float, float], float]:
    def slope(phi: float, omega: float) -> float:
        h = 1e-6 * max(abs(omega), 1e-3)
        if omega - h < 0.0:  # forward difference at rest: ω < 0 may be outside M's domain
            return (torque(phi, omega + h) - torque(phi, omega)) / h
        return (torque(phi, omega + h) - torque(phi, omega - h)) / (2.0 * h)

    return slope


def scene_of(case: Case) -> Scene:
    t, i = case.torque, case.inertia
    speed_range: tuple[float, float] | None = None
    torque: Callable[[float, float], float]
    slope: Callable[[float, float], float]
    if t.formula is not None:
        m = parse(t.formula, VARIABLES, case.parameters)
        depends = m.uses("omega")

        def torque(phi: float, omega: float) -> float:
            return m(phi=phi, omega=omega)

        slope = _central_slope(torque) if depends else (lambda phi, omega: 0.0)
    else:
        angles = t.table_angles()
        assert angles is not None and t.values is not None
        if t.speeds is None:
            table = Periodic(angles, [float(v) for v in _flat(t.values)])
            depends = False

            def torque(phi: float, omega: float) -> float:
                return table(phi)

            slope = lambda phi, omega: 0.0  # noqa: E731
        else:
            torque, slope = _two_way(angles, list(t.speeds), t.values)  # type: ignore[arg-type]
            depends = True
            speed_range = (t.speeds[0], t.speeds[-1])
    inertia: Callable[[float], float]
    if i.value is not None:
        constant = i.value
        inertia = lambda phi: constant  # noqa: E731
    elif i.formula is not None:
        expression = parse(i.formula, ("phi",), case.parameters)

        def inertia(phi: float) -> float:
            value = expression(phi=phi)
            if not value > 0.0:
                raise ArithmeticError(f"I(φ) = {value:.6g} kg·m² at φ = {phi:.6g} rad")
            return value

    else:
        angles = i.table_angles()
        assert angles is not None and i.values is not None
        inertia = Periodic(angles, list(i.values))
    motion = case.motion
    knots: set[float] = set()
    for section in (t, i):
        angles = section.table_angles()
        if angles is not None:
            knots.update(a % TWO_PI for a in angles)
    return Scene(
        torque,
        slope,
        inertia,
        depends,
        motion.start_angle,
        _start_speed(motion),
        motion.revolutions,
        motion.steps_per_revolution,
        speed_range,
        tuple(sorted(knots)),
    )


def _two_way(
    angles: list[float], speeds: list[float], rows: list[list[float]]
) -> tuple[Callable[[float, float], float], Callable[[float, float], float]]:
    """M(φ, ω) bilinear in the table, periodic in φ, linear beyond the speed range."""
    columns = [Periodic(angles, [row[j] for row in rows]) for j in range(len(speeds))]

    def cell(omega: float) -> int:
        return min(max(bisect.bisect_right(speeds, omega) - 1, 0), len(speeds) - 2)

    def torque(phi: float, omega: float) -> float:
        j = cell(omega)
        m0, m1 = columns[j](phi), columns[j + 1](phi)
        return m0 + (omega - speeds[j]) / (speeds[j + 1] - speeds[j]) * (m1 - m0)

    def slope(phi: float, omega: float) -> float:
        j = cell(omega)
        return (columns[j + 1](phi) - columns[j](phi)) / (speeds[j + 1] - speeds[j])

    return torque, slope


# ------------------------------------------------------------- Kovylin's method


class Stall(ArithmeticError):
    """ω reaches zero: the torque cannot carry the mechanism on."""

    def __init__(self, angle: float, time: float) -> None:
        super().__init__(f"stalls at φ = {angle:.6g} rad")
        self.angle = angle
        self.time = time


@dataclass
class Path:
    """ω and t at the nodes φ₀ + k·Δφ."""

    angles: list[float]
    speeds: list[float]
    times: list[float]
    refined: int = 0  # steps that had to be halved


def kovylin_step(scene: Scene, phi: float, omega: float, dphi: float) -> float | None:
    """ω_k after one step by (5), or from rest by the quadratic; None when the step
    is not acceptable (denominator or ω_k not positive, increment too large)."""
    phi_k = phi + dphi
    i_i, i_k = scene.inertia(phi), scene.inertia(phi_k)
    m_mean = 0.5 * (scene.torque(phi, omega) + scene.torque(phi_k, omega))
    c = scene.slope(phi_k, omega) if scene.depends_on_speed else 0.0
    if omega == 0.0:
        # (1) with M′ + ½·C·ω_k over the step: I_k·ω_k² - C·Δφ·ω_k - 2·M′·Δφ = 0
        disc = (c * dphi) ** 2 + 8.0 * i_k * m_mean * dphi
        if m_mean <= 0.0 or disc <= 0.0:
            return None
        return (c * dphi + math.sqrt(disc)) / (2.0 * i_k)
    denominator = 2.0 * i_k * omega - c * dphi
    if not denominator > 0.0:
        return None
    delta = (2.0 * m_mean * dphi + (i_i - i_k) * omega * omega) / denominator
    if abs(delta) > MAX_INCREMENT * omega or omega + delta <= 0.0:
        return None
    return omega + delta


def energy_step(scene: Scene, phi: float, omega: float, dphi: float) -> float | None:
    """ω_k from (1) with the torque of (4) but without (3): the root of
    I_k·ω_k² - C·Δφ·ω_k - (I_i·ω_i² + 2·M′·Δφ - C·Δφ·ω_i) = 0; None without a
    positive root."""
    phi_k = phi + dphi
    i_i, i_k = scene.inertia(phi), scene.inertia(phi_k)
    m_mean = 0.5 * (scene.torque(phi, omega) + scene.torque(phi_k, omega))
    c = scene.slope(phi_k, omega) if scene.depends_on_speed else 0.0
    b = c * dphi
    free = i_i * omega * omega + 2.0 * m_mean * dphi - b * omega
    disc = b * b + 4.0 * i_k * free
    if disc < 0.0:
        return None
    root = math.sqrt(disc)
    # the larger root, without cancellation when b > 0
    value = (b + root) / (2.0 * i_k) if b >= 0.0 else 2.0 * free / (root - b)
    return value if value > 0.0 else None


def kovylin(scene: Scene, steps_per_revolution: int, quadratic: bool = False) -> Path:
    """ω(φ) and t(φ) by (5) at ``steps_per_revolution`` nodes a revolution (or by
    :func:`energy_step`, ``quadratic``)."""
    count = max(1, math.ceil(scene.revolutions * steps_per_revolution - 1e-9))
    dphi = scene.span / count
    phi, omega, t = scene.start_angle, scene.start_speed, 0.0
    path = Path([phi], [omega], [t])
    for _ in range(count):
        phi, omega, t, halved = _advance(scene, phi, omega, t, dphi, quadratic)
        path.refined += halved
        path.angles.append(phi)
        path.speeds.append(omega)
        path.times.append(t)
    return path


def _advance(
    scene: Scene, phi: float, omega: float, t: float, dphi: float, quadratic: bool
) -> tuple[float, float, float, int]:
    """One node step, halved where (5) cannot take it whole."""
    end = phi + dphi
    h, halved = dphi, 0
    while phi < end:
        h = min(h, end - phi)
        step = energy_step if quadratic else kovylin_step
        nxt = step(scene, phi, omega, h)
        if nxt is None:
            if h < dphi * 2.0**-MAX_REFINEMENT:
                raise Stall(phi, t)
            h *= 0.5
            halved = 1
            continue
        t += 2.0 * h / (omega + nxt)  # ω linear in t over the step
        phi = phi + h if end - phi > h * (1 + 1e-12) else end
        omega = nxt
        h = min(2.0 * h, dphi)  # grow back after a refined stretch
    return end, omega, t, halved


# ------------------------------------------------------------- the ODE reference


@dataclass
class Reference:
    final_speed: float
    final_time: float
    evaluations: int
    solver: str
    speed_at: Callable[[float], float]  # ω(φ)
    time_at: Callable[[float], float]  # t(φ)
    speeds_at: Callable[[list[float]], list[float]]  # ω at many angles, vectorized


def stiffness_of(scene: Scene) -> float:
    """|∂(dE/dφ)/∂E|·span = |C|/(I·ω)·span at the start (an estimate)."""
    if not scene.depends_on_speed:
        return 0.0
    i0 = scene.inertia(scene.start_angle)
    # speeds typical of the run: the start, and what the start torque gives over it
    gained = math.sqrt(
        2.0 * abs(scene.torque(scene.start_angle, scene.start_speed)) * scene.span / i0
    )
    candidates = [w for w in (scene.start_speed, 0.1 * gained, gained) if w > 0.0]
    worst = 0.0
    for omega in candidates:
        try:
            c = scene.slope(scene.start_angle, omega)
        except ArithmeticError:
            continue
        worst = max(worst, abs(c) / (i0 * omega) * scene.span)
    return worst


def reference(scene: Scene, rtol: float, method: str, budget: int = EVALUATION_BUDGET) -> Reference:
    """Integrate dE/dφ = M, dt/dφ = 1/ω from φ₀ to the end angle; raise :class:`Stall`
    where E reaches zero."""
    import numpy as np

    from mdcalc.core.ode import TooManySteps, advance

    count = [0]
    phi0 = scene.start_angle
    i0 = scene.inertia(phi0)
    e0 = 0.5 * i0 * scene.start_speed**2
    m0 = scene.torque(phi0, scene.start_speed)
    e_scale = max(e0, abs(m0) * scene.span, 1e-300)
    t_offset = 0.0
    if e0 == 0.0:
        # From rest E ≈ M₀·ε, t ≈ √(2·I₀·ε/M₀): start a hair after φ₀.
        if m0 <= 0.0:
            raise Stall(phi0, 0.0)
        eps = 1e-12 * scene.span
        phi0, e0 = phi0 + eps, m0 * eps
        t_offset = math.sqrt(2.0 * i0 * eps / m0)
    floor = 1e-13 * e_scale

    def rhs(phi: float, y: np.ndarray) -> Any:
        count[0] += 1
        if count[0] > budget:
            raise TooManySteps(f"{method} stopped after {budget} evaluations")
        energy = max(y[0], floor)
        omega = math.sqrt(2.0 * energy / scene.inertia(phi))
        return np.array([scene.torque(phi, omega), 1.0 / omega])

    t_scale = scene.span / max(scene.start_speed, math.sqrt(2 * e_scale / i0))
    atol = np.array([e_scale, t_scale]) * rtol * 1e-3
    # Integrate from kink to kink of the tables: a step across a kink of M or I is
    # rejected again and again and leaves an error no tolerance controls.
    ends = [*knots_between(scene, phi0, scene.end_angle), scene.end_angle]
    starts: list[float] = []
    pieces: list[Callable[[Any], Any]] = []
    y = np.array([e0, t_offset])
    at = phi0
    for end in ends:
        segment = advance(
            rhs,
            at,
            y,
            end,
            rtol=rtol,
            atol=atol,
            method=method,
            terminal=[(lambda phi, y: y[0] - floor, -1)],
            dense=True,
        )
        if segment.sol is not None:
            starts.append(at)
            pieces.append(segment.sol)
        at, y = segment.t, segment.y
        if segment.event is not None:
            break
    if segment.event is not None:
        # E falls linearly to zero with slope M, t as 2·Δφ/ω: extrapolate the last hair
        phi_s, (e_s, t_s) = segment.t, segment.y
        omega_s = math.sqrt(2.0 * max(e_s, 0.0) / scene.inertia(phi_s))
        m_s = scene.torque(phi_s, omega_s)
        rest = max(e_s, 0.0) / -m_s if m_s < 0.0 else 0.0
        raise Stall(phi_s + rest, t_s + (2.0 * rest / omega_s if omega_s > 0 else 0.0))
    start = phi0

    def sol(phi: Any) -> Any:
        """The dense solution, piece by piece; ``phi`` a number or an array."""
        if np.ndim(phi) == 0:
            k = max(bisect.bisect_right(starts, float(phi)) - 1, 0)
            return pieces[k](phi)
        angles = np.asarray(phi, dtype=float)
        index = np.clip(np.searchsorted(starts, angles, side="right") - 1, 0, len(pieces) - 1)
        out = np.empty((2, angles.size))
        for k in np.unique(index).tolist():
            chosen = index == k
            out[:, chosen] = pieces[k](angles[chosen])
        return out

    def speed_at(phi: float) -> float:
        if phi <= start:
            return scene.start_speed
        return math.sqrt(2.0 * max(float(sol(phi)[0]), 0.0) / scene.inertia(phi))

    def time_at(phi: float) -> float:
        return 0.0 if phi <= start else float(sol(phi)[1])

    def speeds_at(angles: list[float]) -> list[float]:
        energies = sol(np.clip(np.array(angles), start, scene.end_angle))[0]
        return [
            scene.start_speed if a <= start else math.sqrt(2.0 * max(e, 0.0) / scene.inertia(a))
            for a, e in zip(angles, energies.tolist(), strict=True)
        ]

    e_end, t_end = segment.y
    return Reference(
        math.sqrt(2.0 * e_end / scene.inertia(scene.end_angle)),
        float(t_end),
        count[0],
        method,
        speed_at,
        time_at,
        speeds_at,
    )


#: Beyond this many table kinks over the run the reference integrates across them.
MAX_SEGMENTS = 4000


def knots_between(scene: Scene, start: float, end: float) -> list[float]:
    """The tables' knots strictly between ``start`` and ``end``, in order."""
    if not scene.breaks:
        return []
    first = math.floor(start / TWO_PI)
    out: list[float] = []
    turn = first
    while turn * TWO_PI < end:
        for b in scene.breaks:
            angle = turn * TWO_PI + b
            if start + 1e-12 * TWO_PI < angle < end - 1e-12 * TWO_PI:
                out.append(angle)
                if len(out) > MAX_SEGMENTS:
                    return []
        turn += 1
    return out


# ------------------------------------------------------------- speed fluctuation


@dataclass(frozen=True)
class Fluctuation:
    """Over the last revolution of the run."""

    maximum: float
    maximum_angle: float
    minimum: float
    minimum_angle: float
    mean: float  # 2π / (time of the revolution)
    start: float  # ω at the start of the revolution
    end: float

    @property
    def coefficient(self) -> float:
        """δ = (ω_max - ω_min)/ω_mean."""
        return (self.maximum - self.minimum) / self.mean


def fluctuation_of_path(path: Path) -> Fluctuation | None:
    end = path.angles[-1]
    first = end - TWO_PI
    if first < path.angles[0] - 1e-9:
        return None
    nodes = [k for k, a in enumerate(path.angles) if a >= first - 1e-9 * TWO_PI]
    speeds = [path.speeds[k] for k in nodes]
    k_max = nodes[speeds.index(max(speeds))]
    k_min = nodes[speeds.index(min(speeds))]
    t_first = _interpolate(path.angles, path.times, first)
    omega_first = _interpolate(path.angles, path.speeds, first)
    return Fluctuation(
        path.speeds[k_max],
        path.angles[k_max],
        path.speeds[k_min],
        path.angles[k_min],
        TWO_PI / (path.times[-1] - t_first),
        omega_first,
        path.speeds[-1],
    )


def _interpolate(xs: list[float], ys: list[float], x: float) -> float:
    k = min(max(bisect.bisect_right(xs, x) - 1, 0), len(xs) - 2)
    w = (x - xs[k]) / (xs[k + 1] - xs[k])
    return ys[k] + w * (ys[k + 1] - ys[k])


def fluctuation_of_reference(scene: Scene, ref: Reference) -> Fluctuation | None:
    end = scene.end_angle
    first = end - TWO_PI
    if first < scene.start_angle - 1e-9:
        return None
    samples = 2048
    grid = [first + TWO_PI * k / samples for k in range(samples + 1)]
    speeds = ref.speeds_at(grid)

    def refine(k: int, sign: float) -> tuple[float, float]:
        low, high = grid[max(k - 1, 0)], grid[min(k + 1, samples)]
        f = lambda a: sign * ref.speed_at(a)  # noqa: E731
        best = golden_maximum(f, low, high, 60)  # on the dense solution
        candidates = [(f(best), best), (f(grid[k]), grid[k])]
        value, angle = max(candidates)
        return sign * value, angle

    top, top_angle = refine(speeds.index(max(speeds)), 1.0)
    low, low_angle = refine(speeds.index(min(speeds)), -1.0)
    return Fluctuation(
        top,
        top_angle,
        low,
        low_angle,
        TWO_PI / (ref.final_time - ref.time_at(first)),
        ref.speed_at(first),
        ref.final_speed,
    )


# ------------------------------------------------------------------------- result


@dataclass
class Result:
    case: Case
    scene: Scene
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None
    reference: Reference | None = None
    path: Path | None = None  # Kovylin at the user's step
    fluctuation: Fluctuation | None = None
    methods: MethodsTable | None = None
    stiffness: float = 0.0
    notes: list[Note] = field(default_factory=list)


def _values(final_speed: float, final_time: float, fl: Fluctuation | None) -> dict[str, float]:
    values = {"final_speed": final_speed, "final_time": final_time}
    if fl is not None:
        values["fluctuation"] = fl.coefficient
    return values


def solve(case: Case) -> Result:
    scene = scene_of(case)
    stiffness = stiffness_of(scene)
    stiff = stiffness > STIFFNESS_LIMIT
    method, rtol = ("Radau", STIFF_REFERENCE_RTOL) if stiff else ("DOP853", REFERENCE_RTOL)
    from mdcalc.core.ode import TooManySteps

    try:
        try:
            ref = reference(
                scene, rtol, method, EXPLICIT_BUDGET if not stiff else EVALUATION_BUDGET
            )
        except TooManySteps:
            if stiff:
                raise
            # stiffer than the start suggested: the implicit solver
            stiff, method, rtol = True, "Radau", STIFF_REFERENCE_RTOL
            ref = reference(scene, rtol, method)
    except Stall as stall:
        return Result(
            case,
            scene,
            "no-answer",
            f"the mechanism stalls: ω reaches zero at φ = {stall.angle:.6g} rad "
            f"({math.degrees(stall.angle):.4g}°, {(stall.angle - scene.start_angle) / TWO_PI:.4g} "
            f"revolutions from φ₀) after t = {stall.time:.6g} s; the torque cannot carry "
            "it on (the motion reverses, which this angle-stepping model does not follow)",
        )
    except ArithmeticError as exc:
        return Result(case, scene, "no-answer", f"the torque or inertia cannot be evaluated: {exc}")
    result = Result(case, scene, reference=ref, stiffness=stiffness)
    try:
        result.fluctuation = fluctuation_of_reference(scene, ref)
    except ArithmeticError as exc:
        return Result(case, scene, "no-answer", f"the torque or inertia cannot be evaluated: {exc}")
    paths: dict[int, Path] = {}

    def kovylin_row(n: int, quadratic: bool = False) -> Callable[[], dict[str, float]]:
        def run() -> dict[str, float]:
            try:
                path = kovylin(scene, n, quadratic)
            except Stall as stall:
                raise NotApplicable(
                    f"(5) cannot step past φ = {stall.angle:.6g} rad even at 2⁻³⁰ of a step"
                ) from None
            except ArithmeticError as exc:
                raise NotApplicable(f"torque or inertia not evaluable: {exc}") from None
            if not quadratic:
                paths[n] = path
            return _values(path.speeds[-1], path.times[-1], fluctuation_of_path(path))

        return run

    def ode_row(rtol_: float, method_: str) -> Callable[[], dict[str, float]]:
        def run() -> dict[str, float]:
            from mdcalc.core.ode import TooManySteps

            try:
                r = reference(scene, rtol_, method_)
            except TooManySteps as exc:
                raise NotApplicable(str(exc)) from None
            except Stall as stall:
                raise NotApplicable(
                    f"stalls at φ = {stall.angle:.6g} rad (the reference does not)"
                ) from None
            return _values(r.final_speed, r.final_time, fluctuation_of_reference(scene, r))

        return run

    n = scene.steps
    methods = [
        Method(f"Kovylin (5), n = {n}", kovylin_row(n), note="the user's step"),
        Method(f"Kovylin (5), n = {2 * n}", kovylin_row(2 * n)),
        Method(f"Kovylin (5), n = {4 * n}", kovylin_row(4 * n)),
        Method(
            f"(1) solved for ω_k, n = {n}",
            kovylin_row(n, quadratic=True),
            note="the same torque, without (3)",
        ),
        Method(
            f"{'Radau' if stiff else 'DOP853'} rtol {LOOSE_RTOL:g}",
            ode_row(LOOSE_RTOL, method),
            imports=ODE_IMPORTS,
        ),
        Method(
            f"{method} rtol {rtol:g}",
            ode_row(rtol, method),
            reference=True,
            note=f"{ref.evaluations} evaluations",
            imports=ODE_IMPORTS,
        ),
    ]
    quantities = [
        MethodQuantity("final_speed", "ω at the end", "rad/s"),
        MethodQuantity("final_time", "t at the end", "s"),
    ]
    if result.fluctuation is not None:
        quantities.append(MethodQuantity("fluctuation", "δ, last revolution", ""))
    result.methods = compare(
        "Methods: Kovylin's step against the energy ODE", "mechanism", quantities, methods
    )
    result.path = paths.get(n)
    if stiff:
        result.notes.append(
            Note(
                "info",
                f"stiff: |∂M/∂ω|/(I·ω) over the span is {stiffness:.3g}; the reference "
                "runs the implicit Radau solver",
            )
        )
    if result.path is not None and result.path.refined:
        result.notes.append(
            Note(
                "info",
                f"Kovylin at n = {n}: {result.path.refined} step(s) halved where (5) "
                "could not take them whole (ω near zero or a large increment)",
            )
        )
    if scene.speed_range is not None:
        speeds = ref.speeds_at([scene.start_angle + scene.span * k / 512 for k in range(513)])
        low, high = scene.speed_range
        if min(speeds) < low or max(speeds) > high:
            result.notes.append(
                Note(
                    "warning",
                    f"ω runs over {min(speeds):.4g}–{max(speeds):.4g} rad/s, beyond the "
                    f"table's {low:.4g}–{high:.4g} rad/s: M extrapolated linearly",
                )
            )
    fl = result.fluctuation
    if fl is not None and abs(fl.end - fl.start) > 1e-3 * fl.mean:
        result.notes.append(
            Note(
                "warning",
                f"not yet steady: ω changes by {(fl.end - fl.start) / fl.mean:+.3%} of its mean "
                "over the last revolution; δ describes a transient revolution (add revolutions)",
            )
        )
    return result


# ------------------------------------------------------------------------- report


def report(result: Result) -> Report:
    case, s = result.case, result.scene
    title = case.title or "Mechanism: motion under M(φ, ω)"
    scene_items = [
        Quantity("start_angle", "Start angle φ₀", s.start_angle, "rad"),
        Quantity("start_speed", "Start speed ω₀", s.start_speed, "rad/s"),
        Quantity("start_inertia", "I(φ₀)", s.inertia(s.start_angle), "kg·m²"),
        Quantity("start_torque", "M(φ₀, ω₀)", s.torque(s.start_angle, s.start_speed), "N·m"),
        Quantity("end_angle", "End angle φ₀ + 2π·revolutions", s.end_angle, "rad"),
        Quantity("steps_per_revolution", "Kovylin's steps per revolution n", s.steps, ""),
    ]
    sections: list[Any] = [Quantities("Scene", scene_items)]
    if result.status != "ok":
        return Report("mechanism", title, sections, [], result.status, result.message)
    ref = result.reference
    assert ref is not None and result.methods is not None
    motion = [
        Quantity(
            "final_speed",
            "ω at the end angle",
            ref.final_speed,
            "rad/s",
            f"{ref.final_speed * RAD_S_TO_RPM:.6g} rpm",
        ),
        Quantity("final_time", "Time to the end angle t", ref.final_time, "s"),
        Quantity("mean_speed", "Mean speed over the run", s.span / ref.final_time, "rad/s"),
    ]
    sections.append(Quantities(f"Motion ({ref.solver} reference)", motion))
    fl = result.fluctuation
    if fl is not None:
        sections.append(
            Quantities(
                "Speed fluctuation over the last revolution",
                [
                    Quantity(
                        "max_speed",
                        "ω_max",
                        fl.maximum,
                        "rad/s",
                        f"at φ = {math.degrees(fl.maximum_angle):.5g}°",
                    ),
                    Quantity(
                        "min_speed",
                        "ω_min",
                        fl.minimum,
                        "rad/s",
                        f"at φ = {math.degrees(fl.minimum_angle):.5g}°",
                    ),
                    Quantity(
                        "mean_speed_revolution",
                        "ω_mean = 2π / time of the revolution",
                        fl.mean,
                        "rad/s",
                    ),
                    Quantity("fluctuation", "δ = (ω_max - ω_min)/ω_mean", fl.coefficient, ""),
                ],
            )
        )
    if result.path is not None:
        sections.append(_path_table(result.path, ref))
        worst = max(
            abs(w - ref.speed_at(a)) / ref.speed_at(a) if ref.speed_at(a) > 0 else 0.0
            for a, w in zip(result.path.angles, result.path.speeds, strict=True)
        )
        sections.append(
            Quantities(
                f"Kovylin at n = {s.steps}",
                [
                    Quantity(
                        "kovylin_final_speed", "ω at the end angle", result.path.speeds[-1], "rad/s"
                    ),
                    Quantity(
                        "kovylin_worst_error", "Largest relative error of ω at a node", worst, ""
                    ),
                ],
            )
        )
    sections.append(result.methods)
    return Report("mechanism", title, sections, list(result.notes))


def _path_table(path: Path, ref: Reference) -> Table:
    rows: list[list[Any]] = []
    indices = list(range(len(path.angles)))
    title = "ω(φ) and t(φ) at Kovylin's nodes"
    if len(indices) > TABLE_ROWS:
        last = path.angles[-1] - TWO_PI
        indices = [k for k in indices if path.angles[k] >= last - 1e-9]
        if len(indices) > TABLE_ROWS:
            stride = math.ceil(len(indices) / TABLE_ROWS)
            indices = indices[::stride] + ([] if indices[-1] % stride == 0 else [indices[-1]])
        title += " (last revolution)"
    for k in indices:
        phi, omega = path.angles[k], path.speeds[k]
        exact = ref.speed_at(phi)
        rows.append(
            [
                math.degrees(phi),
                omega,
                exact,
                (omega - exact) / exact if exact > 0 else 0.0,
                path.times[k],
                ref.time_at(phi),
            ]
        )
    return Table(
        title,
        "path",
        [
            Column("φ", "deg"),
            Column("ω Kovylin", "rad/s"),
            Column("ω reference", "rad/s"),
            Column("rel. error"),
            Column("t Kovylin", "s"),
            Column("t reference", "s"),
        ],
        rows,
    )


# -------------------------------------------------------------------------- charts

#: Points of the ω(φ) curve per revolution, and at least and at most over the run.
CHART_POINTS_PER_REVOLUTION = 720
CHART_POINTS = (1441, 6001)


def charts(result: Result) -> list[Chart]:
    """ω(φ) of the reference over the run (its dense solution on a fine grid, no new
    ODE run) with Kovylin's nodes at the user's n and the last revolution's ω_mean,
    ω_max and ω_min; and M(φ, ω(φ)) along it. [] when the mechanism stalls."""
    ref = result.reference
    if result.status != "ok" or ref is None:
        return []
    scene, fl = result.scene, result.fluctuation
    angles = _chart_grid(scene, fl)
    speeds = ref.speeds_at(angles)
    out = [_speed_chart(result, angles, speeds)]
    try:
        torques = [scene.torque(phi, omega) for phi, omega in zip(angles, speeds, strict=True)]
    except ArithmeticError:
        return out
    if all(math.isfinite(m) for m in torques):
        out.append(_torque_chart(angles, torques))
    return out


def _chart_grid(scene: Scene, fl: Fluctuation | None) -> list[float]:
    """Equal steps over the run, with the last revolution's extremes added so that
    the curve reaches the report's ω_max and ω_min [rad]."""
    low, high = CHART_POINTS
    count = min(max(math.ceil(scene.revolutions * CHART_POINTS_PER_REVOLUTION) + 1, low), high)
    grid = [scene.start_angle + scene.span * k / (count - 1) for k in range(count)]
    grid[-1] = scene.end_angle
    if fl is not None:
        step = scene.span / (count - 1)
        for angle in (fl.maximum_angle, fl.minimum_angle):
            nearest = round((angle - scene.start_angle) / step)
            if abs(angle - scene.start_angle - nearest * step) > 1e-6 * step:
                grid.append(angle)
        grid = sorted(set(grid))
    return grid


def _speed_chart(result: Result, angles: list[float], speeds: list[float]) -> Chart:
    from mdcalc.plot import Chart, Mark, Series

    ref, scene, fl = result.reference, result.scene, result.fluctuation
    assert ref is not None
    degrees = [math.degrees(a) for a in angles]
    series = [Series(f"ω(φ), {ref.solver} reference", degrees, speeds)]
    marks: list[Mark] = []
    if fl is not None:
        marks += [
            Mark("y", fl.maximum, f"ω_max = {fl.maximum:.5g} rad/s"),
            Mark("y", fl.mean, f"ω_mean = {fl.mean:.5g} rad/s (last revolution)"),
            Mark("y", fl.minimum, f"ω_min = {fl.minimum:.5g} rad/s"),
        ]
        first = scene.end_angle - TWO_PI
        if first > scene.start_angle + 1e-9 * TWO_PI:
            marks.append(Mark("x", math.degrees(first), "last revolution"))
    else:
        mean = scene.span / ref.final_time
        marks.append(Mark("y", mean, f"mean over the run {mean:.5g} rad/s"))
    path = result.path
    if path is not None:
        # Nodes far off the reference's range would squash its curve: left out, and said
        low, high = min(speeds), max(speeds)
        margin = max(high - low, 1e-3 * high)
        kept = [
            (math.degrees(a), w)
            for a, w in zip(path.angles, path.speeds, strict=True)
            if low - margin <= w <= high + margin
        ]
        label = f"Kovylin (5), n = {scene.steps}"
        if len(kept) < len(path.angles):
            label += f" ({len(path.angles) - len(kept)} of {len(path.angles)} nodes off the scale)"
        if kept:
            series.append(Series(label, [a for a, _ in kept], [w for _, w in kept], "points"))
    return Chart(
        "Angular speed ω(φ) over the run",
        "φ [deg]",
        "ω [rad/s]",
        series,
        marks,
    )


def _torque_chart(angles: list[float], torques: list[float]) -> Chart:
    from mdcalc.plot import Chart, Mark, Series

    return Chart(
        "Reduced torque along the run: driving above 0, resisting below",
        "φ [deg]",
        "M [N·m]",
        [Series("M(φ, ω(φ))", [math.degrees(a) for a in angles], torques)],
        [Mark("y", 0.0)],
    )


def template() -> dict[str, Any]:
    return {
        "problem": "mechanism",
        "title": "Crank press on a motor with a falling characteristic",
        "parameters": {"M0": 400.0, "w0": 105.0, "Mr": 300.0},
        "torque": {"formula": "M0*(1 - omega/w0) - Mr*max(sin(phi), 0)"},
        "inertia": {"formula": "2.0 + 0.4*cos(2*phi)"},
        "motion": {"start_speed": 80.0, "revolutions": 5.0, "steps_per_revolution": 16},
    }
