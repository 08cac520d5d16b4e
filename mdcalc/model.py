"""Base pydantic models of case files.

Every case model is strict: ``true`` is not a number, ``nan`` and ``inf`` are
rejected, and a misspelt key is an error (lax mode would take ``true`` as 1.0 and
TOML's ``nan`` silently). Field descriptions end with the unit in brackets,
``"Load mass [kg]"``; error messages quote it.
"""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field, model_validator


class FieldError(ValueError):
    """A model validator's complaint about one key: ``loc`` is the key path relative
    to the model that raises it, so the message names that key and its line."""

    def __init__(self, loc: tuple[str | int, ...], message: str) -> None:
        super().__init__(message)
        self.loc = loc


class CaseModel(BaseModel):
    """A section of a case file."""

    model_config = ConfigDict(strict=True, allow_inf_nan=False, extra="forbid", frozen=True)


class Expectation(CaseModel):
    """One ``[expect]`` entry: ``key = { value = 35.3, rel = 1e-3, source = "..." }``."""

    value: float | bool | str = Field(description="Expected value of the result")
    rel: float | None = Field(default=None, ge=0, description="Relative tolerance [-]")
    abs: float | None = Field(default=None, ge=0, description="Absolute tolerance [unit of value]")
    source: str = Field(
        min_length=1,
        description="Where the expected value comes from: seed and equation, hand calculation",
    )

    @model_validator(mode="after")
    def _tolerance_for_numbers(self) -> Expectation:
        numeric = isinstance(self.value, float) and not isinstance(self.value, bool)
        if numeric and self.rel is None and self.abs is None:
            raise ValueError("a numeric expectation needs a tolerance: rel = ... or abs = ...")
        return self


class CaseBase(CaseModel):
    """Keys every case file may have besides its problem's own sections."""

    title: str | None = Field(default=None, description="Title printed on the report")
    expect: dict[str, Expectation] | None = Field(
        default=None, description="Expected results, checked by `mdcalc check`"
    )


def exactly_one(owner: str, **given: object) -> None:
    """Model-validator helper: exactly one of the named alternatives is given."""
    named = [k for k, v in given.items() if v is not None]
    if len(named) != 1:
        keys = " or ".join(given)
        raise ValueError(f"give exactly one of {keys} in [{owner}] (got {len(named)})")
