"""The case file of ``mdcalc mechanism``: pydantic sections in SI units, and the
starter case."""

from __future__ import annotations

import math
from typing import Any, Literal

from pydantic import Field, field_validator, model_validator

from mdcalc.core.units import rpm_to_rad_s
from mdcalc.input.expr import ExpressionError, check_name, parse
from mdcalc.input.model import CaseBase, CaseModel, FieldError, exactly_one

TWO_PI = 2.0 * math.pi

DEG = math.pi / 180.0

#: The least step between two angles of a table [rad]: closer ones are a jump the
#: angles' rounding (an ulp of a few turns is 10⁻¹⁵) reads a part of.
MIN_ANGLE_STEP = 1e-9

#: Kovylin nodes over the run at the user's n (the Methods table runs 7 times as many).
MAX_NODES = 20_000


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
            if b - a < MIN_ANGLE_STEP:
                raise FieldError(
                    (key,),
                    f"two angles {b - a:.3g} rad apart: a table cannot tell them apart"
                    f" (at least {MIN_ANGLE_STEP:g} rad; a jump needs a step of its own,"
                    " say 0.01°)",
                )
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
    value: float | None = Field(default=None, gt=0, le=1e12, description="Constant I [kg·m²]")
    formula: str | None = Field(default=None, description="I(phi), phi in [rad] [kg·m²]")
    values: list[float] | None = Field(default=None, description="I at the angles [kg·m²]")

    @model_validator(mode="after")
    def _one(self) -> Inertia:
        if self.angles is not None and self.angles_deg is not None:
            raise FieldError(("angles_deg",), "give angles or angles_deg, not both")
        exactly_one("inertia", value=self.value, formula=self.formula, table=self.table_angles())
        if self.table_angles() is not None:
            if self.values is None:
                raise FieldError(("values",), "missing: the inertia at each angle [kg·m²]")
            self._check_angles(len(self.values))
            for v in self.values:
                if not 0.0 < v <= 1e12:
                    raise FieldError(("values",), f"inertia {v:g} kg·m² is not in (0, 1e12]")
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
                    f"I(φ) = {value:.6g} kg·m² at φ = {phi:.6g} rad; an inertia must be "
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


def template() -> dict[str, Any]:
    return {
        "problem": "mechanism",
        "title": "Crank press on a motor with a falling characteristic",
        "parameters": {"M0": 400.0, "w0": 105.0, "Mr": 300.0},
        "torque": {"formula": "M0*(1 - omega/w0) - Mr*max(sin(phi), 0)"},
        "inertia": {"formula": "2.0 + 0.4*cos(2*phi)"},
        "motion": {"start_speed": 80.0, "revolutions": 5.0, "steps_per_revolution": 16},
    }


def starter_extras() -> dict[str, Any]:
    """Example values ``mdcalc new`` shows commented out beside :func:`template`: the
    crank press as tables (``cases/mechanism/tabulated_press.toml``)."""
    angles = [0, 30, 60, 90, 120, 150, 180, 210, 240, 270, 300, 330, 360]
    radians = [round(math.radians(a), 15) for a in angles]
    press = [400.0, 250.0, 140.0, 100.0, 140.0, 250.0] + [400.0] * 7
    return {
        "_source": "illustrative, for Kovylin's method of seed 001",
        "torque": {"angles": radians, "angles_deg": angles, "speeds": [0.0, 200.0],
                   "values": [[m, round(m - 761.905, 3)] for m in press]},
        "inertia": {"value": 2.0, "angles": radians, "angles_deg": angles,
                    "values": [2.4, 2.3, 2.0, 1.6, 1.4, 1.5, 1.9, 2.2, 2.3, 2.0, 1.7, 2.0, 2.4]},
        "motion": {"start_speed_rpm": 763.9},
    }  # fmt: skip
