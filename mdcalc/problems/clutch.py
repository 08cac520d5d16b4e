"""``clutch``: stability of an adaptive friction clutch with differentiated friction
pairs (seed 004, Fokin, Gavrilenko, Shishkarev; brief §10).

A spring presses the disc pack with F_n; the driven group's torque drives rolling
bodies up ramps and spreads the pack with F_p, the feedback gain being
C = (R_cp/r)·tan α. With b = C·z₂·f₂, S₀ = z₁f₁ + z₂f₂ and S₁ = z₁η₁f₁ + z₂η₂f₂:

* spreading force (18) F_p = F_n·b/(1 + b); limit torque before slip (19)
  T_n = F_n·R_cp·S₀/(1 + b);
* sliding torque at the slip (20) T_c = F_n·R_cp·S₁/(1 + b) (the pack force is kept,
  the friction drops to η·f);
* first amplitude (25) T_a = F_n·R_cp·S₁·(1 + b(1 - η₂))/(1 + b) (the ramp force
  relaxes to η₂ of its value, (21)-(24));
* the self-oscillation decays when 4(T_a - T_c) < π·T_n (16), that is (26)
  C < C_max = π·S₀/[4·z₂f₂·S₁·(1 - η₂)]; with η₁ = η₂ = η (27)
  C_max = π/(4·z₂·f₂·η(1 - η)). η₂ = 1: stable for every gain.

The (1 + b) factors cancel, so the gain margin C_max/C equals π·T_n/(4(T_a - T_c))
exactly. All closed forms: no numpy, no scipy.
"""

from __future__ import annotations

import math
from collections.abc import Collection
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from pydantic import Field, model_validator

from mdcalc.core.xp import of
from mdcalc.input.model import CaseBase, CaseModel, FieldError, with_values
from mdcalc.methods import Method, NotApplicable, compare
from mdcalc.output.report import (
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
    from mdcalc.output.plot import Chart, Role

UNBOUNDED = "unbounded"

# ------------------------------------------------------------------------ the case


class Pairs(CaseModel):
    driving: int = Field(ge=0, le=100, description="z₁, friction pairs of the driving group [-]")
    driven: int = Field(ge=1, le=100, description="z₂, friction pairs of the driven group [-]")
    driving_friction: float = Field(
        ge=1e-6, le=2, description="f₁, static friction coefficient of the driving pairs [-]"
    )
    driven_friction: float = Field(
        ge=1e-6, le=2, description="f₂, static friction coefficient of the driven pairs [-]"
    )
    driving_ratio: float = Field(
        ge=1e-9, le=1, description="η₁ = sliding/static friction of the driving pairs [-]"
    )
    driven_ratio: float = Field(
        ge=1e-9, le=1, description="η₂ = sliding/static friction of the driven pairs [-]"
    )


class Clutch(CaseModel):
    gain: float | None = Field(
        default=None, ge=0, le=1e6, description="C = (R_cp/r)·tan α, feedback gain [-]"
    )
    rolling_radius: float | None = Field(
        default=None, gt=0, le=1e3, description="r, radius of the rolling bodies [m]"
    )
    ramp_angle_deg: float | None = Field(
        default=None, gt=0, lt=90, description="α, angle of the ramp of the sockets [deg]"
    )
    mean_radius: float | None = Field(
        default=None, gt=0, le=1e3, description="R_cp, mean friction radius [m]"
    )
    spring_force: float | None = Field(
        default=None, gt=0, le=1e9, description="F_n, force of the pressure spring [N]"
    )

    @model_validator(mode="after")
    def _gain(self) -> Clutch:
        ramp = self.rolling_radius is not None or self.ramp_angle_deg is not None
        if self.gain is not None and ramp:
            key = "rolling_radius" if self.rolling_radius is not None else "ramp_angle_deg"
            raise FieldError((key,), "give gain, or rolling_radius and ramp_angle_deg, not both")
        if self.gain is None:
            if not ramp:
                raise ValueError(
                    "give the feedback: gain = C, or rolling_radius, ramp_angle_deg and mean_radius"
                )
            for key in ("rolling_radius", "ramp_angle_deg", "mean_radius"):
                if getattr(self, key) is None:
                    raise FieldError((key,), "missing: the gain C = (R_cp/r)·tan α needs it")
        gain = self.feedback
        key = "gain" if self.gain is not None else "ramp_angle_deg"
        if gain > 1e6:
            raise FieldError(
                (key,), f"the gain (R_cp/r)·tan α = {gain:.4g} is beyond 1e6; check r and α"
            )
        if 0.0 < gain < 1e-12:
            raise FieldError((key,), f"a gain of {gain:.3g} is 0 for any clutch; give 0")
        if self.spring_force is not None and self.mean_radius is None:
            raise FieldError(("mean_radius",), "missing: the torques need R_cp with F_n")
        return self

    @property
    def feedback(self) -> Any:
        """C [-]: given, or (R_cp/r)·tan α (floats, or arrays over a sweep's grid)."""
        if self.gain is not None:
            return self.gain
        assert self.mean_radius is not None and self.rolling_radius is not None
        assert self.ramp_angle_deg is not None
        xp = of(self.mean_radius, self.rolling_radius, self.ramp_angle_deg)
        # α·(π/180) is math.radians' very product.
        alpha = self.ramp_angle_deg * (math.pi / 180.0)
        return self.mean_radius / self.rolling_radius * xp.tan(alpha)


class Curves(CaseModel):
    eta_from: float = Field(default=0.65, gt=0, le=1, description="First η of the table [-]")
    eta_to: float = Field(default=0.8, gt=0, le=1, description="Last η of the table [-]")
    points: int = Field(default=7, ge=2, le=1001, description="Rows of the table [-]")
    driven_ratios: list[float] | None = Field(
        default=None, description="η₂ of the curves where η₁ varies (default: the case's) [-]"
    )
    driving_ratios: list[float] | None = Field(
        default=None, description="η₁ of the curves where η₂ varies (default: the case's) [-]"
    )

    @model_validator(mode="after")
    def _range(self) -> Curves:
        if not self.eta_to > self.eta_from:
            raise FieldError(("eta_to",), f"must exceed eta_from = {self.eta_from:g}")
        for key in ("driven_ratios", "driving_ratios"):
            ratios = getattr(self, key)
            if ratios is not None:
                if len(ratios) > 8:
                    raise FieldError((key,), "at most 8 curves")
                for k, r in enumerate(ratios):
                    if not 0.0 < r <= 1.0:
                        raise FieldError((key, k), f"{r:g} is not in (0, 1]")
        return self


class Case(CaseBase):
    problem: Literal["clutch"] = Field(description="Problem name [-]")
    pairs: Pairs
    clutch: Clutch | None = None
    curves: Curves | None = None


# ------------------------------------------------------------------------ physics


@dataclass(frozen=True)
class Friction:
    z1: int
    z2: int
    f1: float
    f2: float
    eta1: float
    eta2: float

    @property
    def static_sum(self) -> float:
        """S₀ = z₁f₁ + z₂f₂."""
        return self.z1 * self.f1 + self.z2 * self.f2

    @property
    def sliding_sum(self) -> float:
        """S₁ = z₁η₁f₁ + z₂η₂f₂."""
        return self.z1 * self.eta1 * self.f1 + self.z2 * self.eta2 * self.f2

    def with_ratios(self, eta1: float, eta2: float) -> Friction:
        return Friction(self.z1, self.z2, self.f1, self.f2, eta1, eta2)


def gain_bound(fr: Friction) -> Any:
    """(26): C_max = π·S₀/[4·z₂f₂·S₁·(1 - η₂)]; inf for η₂ = 1. Floats, or arrays of
    pair data over a sweep's grid."""
    return of(*vars(fr).values()).where(
        fr.eta2 >= 1.0,
        lambda: math.inf,
        lambda: math.pi * fr.static_sum / (4.0 * fr.z2 * fr.f2 * fr.sliding_sum * (1.0 - fr.eta2)),
    )


def gain_bound_one_material(z2: Any, f: Any, eta: Any) -> Any:
    """(27): C_max = π/(4·z₂·f·η(1 - η)); inf for η = 1."""
    return of(z2, f, eta).where(
        eta >= 1.0, lambda: math.inf, lambda: math.pi / (4.0 * z2 * f * eta * (1.0 - eta))
    )


@dataclass(frozen=True)
class Torques:
    """(18)-(25) for spring force F_n, mean radius R_cp and gain C."""

    spreading: float  # F_p (18) [N]
    pack: float  # N₀ = F_n - F_p [N]
    limit: float  # T_n (19) [N·m]
    sliding: float  # T_c (20) [N·m]
    relaxed_spreading: float  # F₁p (23) [N]
    amplitude: float  # T_a (25) [N·m]


def torques(fr: Friction, force: Any, radius: Any, gain: Any) -> Torques:
    b = gain * fr.z2 * fr.f2
    scale = force * radius / (1.0 + b)
    return Torques(
        spreading=force * b / (1.0 + b),
        pack=force / (1.0 + b),
        limit=scale * fr.static_sum,
        sliding=scale * fr.sliding_sum,
        relaxed_spreading=force * b * fr.eta2 / (1.0 + b),
        amplitude=scale * fr.sliding_sum * (1.0 + b * (1.0 - fr.eta2)),
    )


def criterion(fr: Friction, gain: float) -> float:
    """π·T_n - 4(T_a - T_c) per unit F_n·R_cp: positive while the clutch is stable."""
    t = torques(fr, 1.0, 1.0, gain)
    return math.pi * t.limit - 4.0 * (t.amplitude - t.sliding)


def bound_by_bisection(fr: Friction) -> float:
    """C where the criterion (16) on the torques (19), (20), (25) changes sign."""
    if criterion(fr, 1e6) > 0.0:
        raise NotApplicable("the criterion holds for every gain up to 10⁶")
    low, high = 0.0, 1.0
    while criterion(fr, high) > 0.0:
        low, high = high, 2.0 * high
    for _ in range(200):
        middle = 0.5 * (low + high)
        if middle in (low, high):
            break
        if criterion(fr, middle) > 0.0:
            low = middle
        else:
            high = middle
    return 0.5 * (low + high)


def pair_numbers(fr: Friction) -> dict[str, Any]:
    """The numbers of the friction pairs: S₀, S₁, C_max (26) (inf for η₂ = 1) and,
    where η₁ = η₂, C_max by (27) (missing elsewhere). Floats, or arrays."""
    xp = of(*vars(fr).values())
    return {
        "static_sum": fr.static_sum,
        "sliding_sum": fr.sliding_sum,
        "c_max": gain_bound(fr),
        "c_max_one_material": xp.where(
            fr.eta1 == fr.eta2,
            lambda: gain_bound_one_material(fr.z2, fr.f2, fr.eta2),
            lambda: xp.missing,
        ),
    }


def gain_numbers(clutch: Clutch, fr: Friction, bound: Any) -> dict[str, Any]:
    """The numbers of the gain section: C, b, the gain margin C_max/C (inf for an
    unbounded C_max, missing for C = 0) and, with a spring force, the torques (18)-(25)
    and the margin π·T_n - 4(T_a - T_c). Floats, or arrays over a sweep's grid."""
    gain = clutch.feedback
    xp = of(gain, bound)
    out: dict[str, Any] = {
        "gain": gain,
        "feedback": gain * fr.z2 * fr.f2,
        "gain_margin": xp.where(
            bound == math.inf,
            lambda: math.inf,
            lambda: xp.where(gain > 0.0, lambda: bound / gain, lambda: xp.missing),
        ),
    }
    if clutch.spring_force is not None:
        assert clutch.mean_radius is not None
        t = torques(fr, clutch.spring_force, clutch.mean_radius, gain)
        out |= {
            "spreading_force": t.spreading,
            "pack_force": t.pack,
            "limit_torque": t.limit,
            "sliding_torque": t.sliding,
            "relaxed_spreading_force": t.relaxed_spreading,
            "first_amplitude": t.amplitude,
            "overshoot": t.amplitude / t.limit,
            "torque_margin": math.pi * t.limit - 4.0 * (t.amplitude - t.sliding),
        }
    return out


# ------------------------------------------------------------------------- result


@dataclass
class Result:
    case: Case
    friction: Friction
    bound: float
    methods: MethodsTable | None
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


QUANTITIES = [MethodQuantity("c_max", "C_max", "")]


def friction_of(case: Case) -> Friction:
    p = case.pairs
    return Friction(
        p.driving,
        p.driven,
        p.driving_friction,
        p.driven_friction,
        p.driving_ratio,
        p.driven_ratio,
    )


def solve(case: Case) -> Result:
    fr = friction_of(case)
    bound = gain_bound(fr)
    if math.isinf(bound):
        return Result(case, fr, bound, None)
    same = fr.eta1 == fr.eta2

    def one_material() -> dict[str, float]:
        if not same:
            raise NotApplicable(f"needs η₁ = η₂ (here {fr.eta1:g} and {fr.eta2:g})")
        return {"c_max": gain_bound_one_material(fr.z2, fr.f2, fr.eta2)}

    def without_pi() -> dict[str, float]:
        return {"c_max": bound / math.pi}

    methods = [
        Method("(26) closed form", lambda: {"c_max": gain_bound(fr)}, reference=True),
        Method("(27) η₁ = η₂", one_material, note="any f₁, z₁: S₁ = η·S₀"),
        Method(
            "criterion (16) by bisection",
            lambda: {"c_max": bound_by_bisection(fr)},
            note="4(T_a - T_c) = π·T_n with (19), (20), (25)",
        ),
        Method(
            "(26) without π",
            without_pi,
            note="the scan's garbled numerator; the brief restores π",
        ),
    ]
    table = compare("Methods: the gain bound C_max", "c_max", QUANTITIES, methods)
    return Result(case, fr, bound, table)


# ------------------------------------------------------------------------- report


def _bound_value(value: float) -> Value:
    return UNBOUNDED if math.isinf(value) else value


def report(result: Result) -> Report:
    case, fr = result.case, result.friction
    title = case.title or "Adaptive friction clutch: stability of the self-oscillation"
    notes: list[Note] = []
    numbers = pair_numbers(fr)
    pairs = [
        Quantity("static_sum", "S₀ = z₁f₁ + z₂f₂", numbers["static_sum"], ""),
        Quantity("sliding_sum", "S₁ = z₁η₁f₁ + z₂η₂f₂", numbers["sliding_sum"], ""),
        Quantity(
            "c_max",
            "Gain bound (26) C_max = π·S₀/[4·z₂f₂·S₁·(1 - η₂)]",
            _bound_value(result.bound),
            "",
            "η₂ = 1: no drop of friction in the driven pairs" if math.isinf(result.bound) else "",
        ),
    ]
    if numbers["c_max_one_material"] is not None:
        pairs.append(
            Quantity(
                "c_max_one_material",
                "(27) η₁ = η₂ = η: π/(4·z₂·f₂·η(1 - η))",
                _bound_value(numbers["c_max_one_material"]),
                "",
            )
        )
    pairs.append(
        Quantity(
            "unconditionally_stable",
            "Stable at every gain (η₂ = 1)",
            math.isinf(result.bound),
            "",
        )
    )
    sections: list[Any] = [Quantities("Friction pairs and the gain bound", pairs)]
    if case.clutch is not None:
        sections.append(_gain_section(case.clutch, fr, result.bound, notes))
    if result.methods is not None:
        sections.append(result.methods)
    if case.curves is not None:
        sections.append(_curves_table(case.curves, fr))
    return Report("clutch", title, sections, notes)


def _gain_section(clutch: Clutch, fr: Friction, bound: float, notes: list[Note]) -> Quantities:
    n = gain_numbers(clutch, fr, bound)
    gain = n["gain"]
    items = [
        Quantity("gain", "Feedback gain C = (R_cp/r)·tan α", gain, ""),
        Quantity("feedback", "b = C·z₂·f₂", n["feedback"], ""),
    ]
    stable = gain < bound
    if math.isinf(bound):
        items.append(Quantity("gain_margin", "Gain margin C_max/C", UNBOUNDED, ""))
    elif n["gain_margin"] is not None:
        items.append(
            Quantity(
                "gain_margin",
                "Gain margin C_max/C",
                n["gain_margin"],
                "",
                "= π·T_n/(4(T_a - T_c)) exactly",
            )
        )
    items.append(Quantity("stable", "Self-oscillation decays, 4(T_a - T_c) < π·T_n", stable, ""))
    if clutch.spring_force is not None:
        items += [
            Quantity("spreading_force", "Spreading force (18) F_p", n["spreading_force"], "N"),
            Quantity("pack_force", "Pack force F_n - F_p", n["pack_force"], "N"),
            Quantity("limit_torque", "Limit torque before slip (19) T_n", n["limit_torque"], "N·m"),
            Quantity(
                "sliding_torque", "Sliding torque at the slip (20) T_c", n["sliding_torque"], "N·m"
            ),
            Quantity(
                "relaxed_spreading_force",
                "Spreading force while sliding (23) F₁p",
                n["relaxed_spreading_force"],
                "N",
            ),
            Quantity("first_amplitude", "First amplitude (25) T_a", n["first_amplitude"], "N·m"),
            Quantity("overshoot", "T_a/T_n", n["overshoot"], ""),
            Quantity(
                "torque_margin",
                "π·T_n - 4(T_a - T_c)",
                n["torque_margin"],
                "N·m",
                "the torque amplitude falls by this much a cycle"
                if stable
                else "the torque amplitude grows by minus this much a cycle",
            ),
        ]
    if not stable:
        notes.append(
            Note(
                "warning",
                f"C = {gain:.4g} is above C_max = {bound:.4g}: the self-oscillation after a "
                "slip grows (4(T_a - T_c) > π·T_n); lower the ramp angle or raise r",
            )
        )
    return Quantities("Gain, torques and margin", items)


def _curves_table(curves: Curves, fr: Friction) -> Table:
    n = curves.points
    etas = [curves.eta_from + (curves.eta_to - curves.eta_from) * k / (n - 1) for k in range(n)]
    driven = curves.driven_ratios if curves.driven_ratios is not None else [fr.eta2]
    driving = curves.driving_ratios if curves.driving_ratios is not None else [fr.eta1]
    columns = [Column("η")]
    columns += [Column(f"C_max, η₁ = η, η₂ = {e:g}") for e in driven]
    columns += [Column(f"C_max, η₂ = η, η₁ = {e:g}") for e in driving]
    columns.append(Column("C_max, η₁ = η₂ = η"))
    rows: list[list[Value]] = []
    for eta in etas:
        row: list[Value] = [eta]
        row += [_bound_value(gain_bound(fr.with_ratios(eta, e))) for e in driven]
        row += [_bound_value(gain_bound(fr.with_ratios(e, eta))) for e in driving]
        row.append(_bound_value(gain_bound(fr.with_ratios(eta, eta))))
        rows.append(row)
    return Table(
        f"C_max(η) (Fig. 2 of the seed: z₁ = {fr.z1}, z₂ = {fr.z2}, f₁ = {fr.f1:g}, "
        f"f₂ = {fr.f2:g})",
        "curves",
        columns,
        rows,
    )


# ------------------------------------------------------------------------- charts

#: Points of each C_max(η) curve of the chart (the report's table has ``curves.points``).
CHART_POINTS = 200


def charts(result: Result) -> list[Chart]:
    """``--plot``: the curves C_max(η) of the report's table at ``CHART_POINTS``
    points, over its η range (without ``[curves]``, the default range widened to
    take in the case's η₁ and η₂). The case's own η₁, η₂ are marked when in range,
    with its bound C_max where it lies on a curve, and its gain C unless that would
    flatten the curves. η₂ = 1 has no finite bound: those points are left out.
    Closed forms only, no numpy."""
    from mdcalc.output.plot import Chart, Mark, Series

    case, fr = result.case, result.friction
    curves = case.curves or Curves()
    low, high = curves.eta_from, curves.eta_to
    if case.curves is None:  # show the case's own point on the curves
        low = min(low, fr.eta1, fr.eta2)
        high = max([high] + [e for e in (fr.eta1, fr.eta2) if e < 1.0])
    etas = [low + (high - low) * k / (CHART_POINTS - 1) for k in range(CHART_POINTS)]
    driven = curves.driven_ratios if curves.driven_ratios is not None else [fr.eta2]
    driving = curves.driving_ratios if curves.driving_ratios is not None else [fr.eta1]
    # (label, style, η₁, η₂); None: the η of the axis.
    wanted: list[tuple[str, Role, float | None, float | None]] = [
        *((f"η₁ = η, η₂ = {_eta_text(e)}", "result", None, e) for e in driven),
        *((f"η₂ = η, η₁ = {_eta_text(e)}", "secondary", e, None) for e in driving),
        ("η₁ = η₂ = η (27)", "comparison", None, None),
    ]
    series: list[Series] = []
    for label, role, eta1, eta2 in wanted:
        points = [
            (
                eta,
                gain_bound(
                    fr.with_ratios(eta if eta1 is None else eta1, eta if eta2 is None else eta2)
                ),
            )
            for eta in etas
        ]
        points = [(eta, c) for eta, c in points if math.isfinite(c)]  # η₂ = 1: unbounded
        if points:
            series.append(Series(label, [p[0] for p in points], [p[1] for p in points], role))
    if not series:
        return []
    inside = [e for e in dict.fromkeys((fr.eta2, fr.eta1)) if low <= e <= high]
    # The case's bound lies on the curve η₂ = η, η₁ = the case's at η₂, and on the
    # curve η₁ = η, η₂ = the case's at η₁.
    on_curves = [e for e in inside if (e == fr.eta2 and fr.eta1 in driving)]
    on_curves += [e for e in inside if (e == fr.eta1 and fr.eta2 in driven)]
    on_curves = list(dict.fromkeys(on_curves))
    if math.isfinite(result.bound) and on_curves:
        series.append(
            Series(
                f"this case: C_max = {result.bound:.4g}",
                on_curves,
                [result.bound] * len(on_curves),
                "this-case",
            )
        )
    names = [
        f"{'η₁ = η₂' if fr.eta1 == fr.eta2 else ('η₂' if e == fr.eta2 else 'η₁')} = {_eta_text(e)}"
        for e in inside
    ]
    # one legend entry for the case's ratios (one look, one meaning)
    label = f"this case: {', '.join(names)}" if names else ""
    marks = [Mark("x", e, label if k == 0 else "", "this-case") for k, e in enumerate(inside)]
    values = [c for s in series for c in s.y]
    top, bottom = max(values), min(values)
    y_log = bottom > 0.0 and top / bottom > 50.0
    if case.clutch is not None:
        gain = case.clutch.feedback
        if (gain > 0.0 or not y_log) and gain <= 1.5 * top:  # else it would flatten the curves
            marks.append(
                Mark(
                    "y",
                    gain,
                    f"gain C = {gain:.4g} of this clutch: stable where C_max is above",
                    "limit",
                )
            )
    unbounded = "; this case: η₂ = 1, stable at every gain" if math.isinf(result.bound) else ""
    return [
        Chart(
            f"Gain bound (26) C_max(η), stable below: z₁ = {fr.z1}, z₂ = {fr.z2}, "
            f"f₁ = {fr.f1:g}, f₂ = {fr.f2:g}{unbounded}",
            "η = sliding/static friction [-]",
            "C_max [-]",
            series,
            marks,
            y_log=y_log,
        )
    ]


def _eta_text(eta: float) -> str:
    """η with the digits that tell it from 1 (and from its neighbours): 0.8, or
    0.9999999991 where :g would print 1."""
    for digits in range(4, 18):
        text = f"{eta:.{digits}g}"
        if abs(float(text) - eta) <= 1e-3 * min(eta, 1.0 - eta) or float(text) == eta:
            return text
    return repr(eta)


# ------------------------------------------------------------------------- sweep

#: Keys ``mdcalc sweep`` and ``mdcalc study`` may vary in the vectorized form.
SWEEP_KEYS = {
    "pairs.driving": "z₁",
    "pairs.driven": "z₂",
    "pairs.driving_friction": "f₁",
    "pairs.driven_friction": "f₂",
    "pairs.driving_ratio": "η₁",
    "pairs.driven_ratio": "η₂",
    "clutch.gain": "C",
    "clutch.rolling_radius": "r",
    "clutch.ramp_angle_deg": "α",
    "clutch.mean_radius": "R_cp",
    "clutch.spring_force": "F_n",
}


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result of the report over a grid at once (numpy), by the same
    functions the report calls (:func:`pair_numbers`, :func:`gain_numbers`) on the
    case with the grid's arrays in it. Missing (NaN) where the report shows
    "unbounded" (η₂ = 1) or leaves a number out (no C_max/C for C = 0, no (27) where
    η₁ ≠ η₂). None for keys it does not vary."""
    import numpy as np

    if any(key not in SWEEP_KEYS for key in grid):
        return None
    arrays = with_values(case, {key: np.asarray(v, dtype=float) for key, v in grid.items()})
    fr = friction_of(arrays)
    numbers = pair_numbers(fr)
    if arrays.clutch is not None:
        numbers |= gain_numbers(arrays.clutch, fr, numbers["c_max"])
    size = max(np.size(v) for v in grid.values())
    out = {}
    with np.errstate(all="ignore"):
        for key, value in numbers.items():
            column = np.broadcast_to(np.asarray(np.nan if value is None else value, float), size)
            out[key] = np.where(np.isinf(column), np.nan, column)  # "unbounded": no number
    return out


def template() -> dict[str, Any]:
    return {
        "problem": "clutch",
        "title": "Adaptive friction clutch, Fig. 2 data",
        "pairs": {
            "driving": 1,
            "driven": 3,
            "driving_friction": 0.3,
            "driven_friction": 0.4,
            "driving_ratio": 0.65,
            "driven_ratio": 0.8,
        },
        "clutch": {
            "spring_force": 1000.0,
            "mean_radius": 0.1,
            "rolling_radius": 0.05,
            "ramp_angle_deg": 45.0,
        },
        "curves": {"eta_from": 0.65, "eta_to": 0.8, "points": 7},
    }


def starter_extras() -> dict[str, Any]:
    """Example values ``mdcalc new`` shows commented out beside :func:`template`."""
    return {
        "_source": "Fig. 2 of seed 004",
        "clutch": {"gain": 10000.0},
        "curves": {"driven_ratios": [0.8, 0.735], "driving_ratios": [0.65, 0.7]},
    }
