"""Base pydantic models of case files.

Every case model is strict: ``true`` is not a number, ``nan`` and ``inf`` are
rejected, and a misspelt key is an error (lax mode would take ``true`` as 1.0 and
TOML's ``nan`` silently). Every number, in any section, lies within
±:data:`MAGNITUDE_LIMIT`: a finite 1e308 is as wrong as ``inf`` in a machine, and
squaring it would overflow inside a solver. Field descriptions end with the unit in brackets,
``"Load mass [kg]"``; error messages quote it.
"""

from __future__ import annotations

import itertools
from typing import Any, ClassVar, get_args

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    ValidationInfo,
    field_validator,
    model_validator,
)

#: The largest magnitude of any number in a case file (SI units). The stiffest
#: scenes in ``cases/`` use 6e12 N/m; 1e18 leaves room and keeps products of a
#: few inputs far from float overflow (about 1.8e308).
MAGNITUDE_LIMIT = 1e18
#: The smallest magnitude of any number but 0 in a case's scene (SI units), the
#: ceiling's mirror: a subnormal float (5e-324, 2.2e-308) or one a few products from
#: underflow (1e-300) is no machine's quantity, and LAPACK and the solvers' own
#: checks fail on it instead of answering. Expected results ([expect]) may be smaller.
MAGNITUDE_FLOOR = 1e-18


class FieldError(ValueError):
    """A model validator's complaint about one key: ``loc`` is the key path relative
    to the model that raises it, so the message names that key and its line."""

    def __init__(self, loc: tuple[str | int, ...], message: str) -> None:
        super().__init__(message)
        self.loc = loc


class CaseModel(BaseModel):
    """A section of a case file."""

    model_config = ConfigDict(
        strict=True, allow_inf_nan=False, extra="forbid", frozen=True, defer_build=True
    )

    #: Does the floor (MAGNITUDE_FLOOR) hold in this section? Not for expected results.
    _magnitude_floor: ClassVar[bool] = True

    @field_validator("*", mode="after")
    @classmethod
    def _within_magnitude_limit(cls, value: Any, info: ValidationInfo) -> Any:
        if info.field_name != "saved":  # results of an earlier run: not read
            _check_magnitude(value, (), cls._magnitude_floor)
        return value


def _check_magnitude(value: Any, loc: tuple[str | int, ...], floor: bool = True) -> None:
    """Raise :class:`FieldError` at the first number beyond ±MAGNITUDE_LIMIT, or (with
    ``floor``) closer to 0 than MAGNITUDE_FLOOR but for 0 itself."""
    if isinstance(value, bool) or isinstance(value, BaseModel):
        return  # sections check their own fields
    if isinstance(value, int | float):
        if abs(value) > MAGNITUDE_LIMIT:
            raise FieldError(
                loc,
                f"got {value!r}; beyond the range mdcalc computes in "
                f"(|value| <= {MAGNITUDE_LIMIT:g} in SI units)",
            )
        if floor and 0 < abs(value) < MAGNITUDE_FLOOR:
            raise FieldError(
                loc,
                f"got {value!r}; closer to 0 than mdcalc computes with (|value| >= "
                f"{MAGNITUDE_FLOOR:g} in SI units, or 0)",
            )
    elif isinstance(value, list | tuple):
        for index, item in enumerate(value):
            _check_magnitude(item, (*loc, index), floor)
    elif isinstance(value, dict):
        for key, item in value.items():
            _check_magnitude(item, (*loc, key), floor)


class Expectation(CaseModel):
    """One ``[expect]`` entry: ``key = { value = 35.3, rel = 1e-3, source = "..." }``."""

    _magnitude_floor: ClassVar[bool] = False  # a result may be 5e-19 m

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
    saved: dict[str, Any] | None = Field(
        default=None,
        description="Results an earlier run wrote with --save; kept for the reader, not read",
    )


def exactly_one(owner: str, **given: object) -> None:
    """Model-validator helper: exactly one of the named alternatives is given."""
    named = [k for k, v in given.items() if v is not None]
    if len(named) != 1:
        keys = " or ".join(given)
        raise ValueError(f"give exactly one of {keys} in [{owner}] (got {len(named)})")


#: The key of a vectorized kernel's answer (a bool array over the block) that marks
#: the samples it did not compute, such as scenes without an answer: the caller
#: solves each of them alone, as a single scene, and keeps the kernel's other values.
DECLINED = "__declined__"


def kernel_answer(values: dict[str, Any], declined: Any, size: int) -> dict[str, Any]:
    """A kernel's answer over a block of ``size`` samples: each value spread over the
    block as floats, NaN where ``declined`` (the samples to be solved alone), and the
    ``DECLINED`` mask itself."""
    import numpy as np

    mask = np.broadcast_to(np.asarray(declined, dtype=bool), (size,))
    out: dict[str, Any] = {
        key: np.where(mask, np.nan, np.broadcast_to(np.asarray(value, dtype=float), (size,)))
        for key, value in values.items()
    }
    out[DECLINED] = mask
    return out


def in_tiles(
    sweep: Any, case: Any, grid: dict[str, Any], wanted: Any, rows: int
) -> dict[str, Any] | None:
    """A kernel's answer over a block computed ``rows`` samples at a time (None where
    the block holds no more than one tile, a tile's answer is None or the tiles' keys
    differ: the caller then decides): a kernel of many small arrays a row (a modal
    solution's tables, an ODE reference's stages) runs faster where they stay in the
    processor's cache, and one with a large array a row fits in memory. The tiles are
    of equal size, a row apart at most (a block of 21 845 rows in tiles of 10 922 and
    10 923, not 16 384 and 5461), none above ``rows``. Each row's numbers are its
    own, so the answer is the same."""
    import numpy as np

    size = max([np.size(v) for v in grid.values()] + [1])
    if size <= rows:
        return None
    parts: list[dict[str, Any]] = []
    for first, last in itertools.pairwise(equal_ends(size, -(-size // rows))):
        tile = {k: v if np.size(v) == 1 else v[first:last] for k, v in grid.items()}
        part = sweep(case, tile, wanted)
        if part is None or (parts and set(part) != set(parts[0])):
            return None  # (tiles that give different keys: the block whole, as asked)
        parts.append(part)
    return {key: np.concatenate([p[key] for p in parts]) for key in parts[0]}


def equal_ends(size: int, count: int) -> list[int]:
    """The ends of ``count`` consecutive parts of ``size`` rows, their sizes a row
    apart at most: 0, …, size."""
    return [size * k // count for k in range(count + 1)]


def value_at(case: Any, key: str) -> Any:
    """The case's value at a key path (``"drive.load_torque"``,
    ``"torque.values.3.0"``): None where a section, field, table entry or list index
    is not there. What a kernel asks before it varies a key."""
    node = case
    for part in key.split("."):
        if isinstance(node, list):
            if not part.isdigit() or int(part) >= len(node):
                return None
            node = node[int(part)]
        elif isinstance(node, dict):
            node = node.get(part)
        else:
            node = getattr(node, part, None)
        if node is None:
            return None
    return node


def with_values(case: CaseBase, values: dict[str, Any]) -> Any:
    """The case with each key path of ``values`` (``"vehicle.mass"``,
    ``"drive.stage_efficiencies.1"``) set to its value, copied on the way and not
    validated, so that a value may be a numpy array over a sweep's grid and the
    problem's own scene formulas run on it (the sweep has validated the grid's
    corners). A section the case does not have is built from its defaults."""
    for key, value in values.items():
        case = _with_value(case, type(case), key.split("."), value)
    return case


def _with_value(node: Any, kind: Any, parts: list[str], value: Any) -> Any:
    if not parts:
        return value
    head, rest = parts[0], parts[1:]
    if isinstance(node, dict):  # a table of named numbers (``parameters.a``)
        return {**node, head: _with_value(node.get(head), None, rest, value)}
    if isinstance(node, list):
        i = int(head)
        return [*node[:i], _with_value(node[i], None, rest, value), *node[i + 1 :]]
    if node is None:  # an optional section the grid adds: its defaults, then the value
        node = next(t for t in (kind, *get_args(kind)) if _is_model(t)).model_construct()
    annotation = type(node).model_fields[head].annotation
    child = _with_value(getattr(node, head), annotation, rest, value)
    return node.model_copy(update={head: child})


def _is_model(kind: Any) -> bool:
    return isinstance(kind, type) and issubclass(kind, BaseModel)
