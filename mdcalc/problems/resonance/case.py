"""The case file of ``mdcalc resonance``: pydantic sections in SI units, and the
starter case."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import Field, model_validator

from mdcalc.input.model import CaseBase, CaseModel, FieldError

#: The modal core polishes each mode against the whole chain (O(n³) in all):
#: 60 masses take about 2 s. Engine-transmission models have a few tens.
MAX_MASSES = 60


class ChainSection(CaseModel):
    inertias: list[float] = Field(description="J₁ … Jₙ [kg·m²]")
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
                raise FieldError(("inertias", k), f"{j:g} kg·m² is not in (0, 1e9]")
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


def starter_extras() -> dict[str, Any]:
    """Example values ``mdcalc new`` shows commented out beside :func:`template`."""
    return {
        "_source": "illustrative, for the methods of seed 003",
        "campbell": {"orders": [3.0, 4.5, 6.0]},
        "measured": [{"order": 4.5, "speed_rpm": 1500.0, "_or": {"frequency_hz": 112.5}}],
    }
