"""The case file of ``mdcalc mine-hoist``: pydantic sections in SI units, and the
starter case."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import Field, model_validator

from mdcalc.input.model import CaseBase, CaseModel, FieldError


class Hoist(CaseModel):
    drum_inertia: float = Field(
        gt=0, description="J₁, motor rotor, reducer and drum, at the drum axis [kg·m²]"
    )
    sheave_inertia: float = Field(
        gt=0,
        description=(
            "J₂, head sheave reduced to the drum axis; its own inertia when "
            "rope.sheave_radius is given [kg·m²]"
        ),
    )
    cage_inertia: float = Field(
        gt=0,
        description=(
            "J₃, cage with load reduced to the drum axis (m·R²), with the rope's share "
            "unless a [rope] section adds it [kg·m²]"
        ),
    )
    chord_stiffness: float | None = Field(
        default=None,
        gt=0,
        description="c₁₂, rope chord drum-sheave; or rope.axial_stiffness [N·m/rad]",
    )
    rope_stiffness: float | None = Field(
        default=None,
        gt=0,
        description="c₂₃, vertical rope sheave-cage; or rope.axial_stiffness [N·m/rad]",
    )


class Loads(CaseModel):
    drive_torque: float = Field(
        ge=0, le=1e12, description="M₁, starting torque of the drive on the drum [N·m]"
    )
    load_torque: float = Field(
        ge=0, le=1e12, description="W, load torque resisting the lift, at the drum axis [N·m]"
    )

    @model_validator(mode="after")
    def _something(self) -> Loads:
        if self.drive_torque == 0.0 and self.load_torque == 0.0:
            raise FieldError(("drive_torque",), "both torques are 0: nothing loads the ropes")
        return self


class Rope(CaseModel):
    mass_per_metre: float = Field(gt=0, description="ρ, mass of one metre of rope [kg/m]")
    drum_radius: float = Field(gt=0, description="R, drum radius [m]")
    chord_length: float = Field(gt=0, description="L₁, rope chord from drum to sheave [m]")
    length: float = Field(gt=0, description="H, vertical rope from sheave to cage [m]")
    axial_stiffness: float | None = Field(
        default=None,
        gt=0,
        description="E·A of the rope; then c₁₂ = EA·R²/L₁ and c₂₃ = EA·R²/H [N]",
    )
    sheave_radius: float | None = Field(
        default=None,
        gt=0,
        description="R_ns; then hoist.sheave_inertia is the sheave's own, reduced by (R/R_ns)² [m]",
    )


class Analysis(CaseModel):
    horizon: float | None = Field(
        default=None, gt=0, description="Window for the maxima; default 20 periods 2π/β₁ [s]"
    )
    time_points: int = Field(
        default=21, ge=2, le=2001, description="Rows of the μ(t) table over the first swing [-]"
    )
    ode: bool = Field(default=True, description="Run the ODE rows of the Methods table [-]")


class Sweep(CaseModel):
    heights: list[float] = Field(
        min_length=1, max_length=200, description="Heights H for the seed's Table 1 [m]"
    )

    @model_validator(mode="after")
    def _positive(self) -> Sweep:
        for index, height in enumerate(self.heights):
            if not height > 0.0:
                raise FieldError(("heights", index), f"got {height}; every height must be > 0 m")
        return self


class Case(CaseBase):
    problem: Literal["mine-hoist"] = Field(description="Problem name [-]")
    hoist: Hoist
    loads: Loads
    rope: Rope | None = None
    analysis: Analysis = Analysis()
    sweep: Sweep | None = None

    @model_validator(mode="after")
    def _stiffness_sources(self) -> Case:
        from_rope = self.rope is not None and self.rope.axial_stiffness is not None
        for key in ("chord_stiffness", "rope_stiffness"):
            given = getattr(self.hoist, key) is not None
            if given and from_rope:
                raise FieldError(
                    ("hoist", key),
                    "given twice: rope.axial_stiffness already sets it (c = EA·R²/L)",
                )
            if not given and not from_rope:
                raise FieldError(("hoist", key), "missing: give it, or rope.axial_stiffness")
        if self.sweep is not None and not from_rope:
            raise FieldError(
                ("sweep", "heights"),
                "a height sweep needs [rope] with axial_stiffness (c₂₃ = EA·R²/H changes with H)",
            )
        return self


def template() -> dict[str, Any]:
    return {
        "problem": "mine-hoist",
        "title": "Mine hoist, seed 002 data at H = 1025 m, M₁ = 2·W",
        "hoist": {
            "drum_inertia": 479.15e3,
            "sheave_inertia": 27.97e3,
            "cage_inertia": 156.86e3,
            "chord_stiffness": 18609.2e3,
            "rope_stiffness": 893.45e3,
        },
        "loads": {"drive_torque": 1.0e6, "load_torque": 5.0e5},
    }


def starter_extras() -> dict[str, Any]:
    """Example values ``mdcalc new`` shows commented out beside :func:`template` (keys
    of its sections, optional sections; ``_or``: keys shown but not uncommented)."""
    return {
        "_source": "seed 002 as printed",
        "rope": {"mass_per_metre": 7.0, "drum_radius": 3.0, "chord_length": 49.2,
                 "length": 1025.0, "_or": {"axial_stiffness": 1.0176e8, "sheave_radius": 2.5}},
        "analysis": {"horizon": 47.0},
        "sweep": {
            "heights": [410.0, 615.0, 820.0, 1025.0],
            "_needs": "needs [rope] with axial_stiffness, in place of [hoist]'s two stiffnesses",
        },
    }  # fmt: skip
