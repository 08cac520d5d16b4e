"""A study file: a case file with a ``[study]`` table of uncertain inputs.

The scene is written inline, exactly as in a case file of its problem; the
``[study]`` table names the uncertain keys, the sampler, the limits and whether to
run a Sobol sensitivity analysis. ``plan`` validates both, converts quantity
strings in the distributions to the field's unit, and refuses a distribution that
can draw a value outside the field's validated bounds (unless it is truncated).

Pure logic: no sampling here (:mod:`mdcalc.runs.study.sample`), no solving.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any, Literal

from pydantic import Field, model_validator

from mdcalc.errors import InputError, Problem
from mdcalc.input.casefile import (
    CaseText,
    field_info,
    is_integer_field,
    missing_name,
    unit_of,
    validate,
)
from mdcalc.input.model import MAGNITUDE_LIMIT, CaseBase, CaseModel

#: Samples of one study (its Monte Carlo draws, or its Saltelli design): 10⁷ samples
#: of a vectorized problem take about 10 s and a few GB; of a per-sample problem, days.
MAX_SAMPLES = 10_000_000
#: The uniform draws stay inside [U_MIN, U_MAX]: an inverse CDF at 0 or 1 is infinite.
#: 2⁻⁵³ is the smallest positive draw of a double in [0, 1); a normal reaches ±8.2σ.
U_MIN = 2.0**-53
U_MAX = 1.0 - 2.0**-53

Number = float | str  # a number, or a quantity string ("50 kg")


class InputSpec(CaseModel):
    """One uncertain key: a distribution, or a tolerance read as uniform."""

    dist: Literal["normal", "uniform", "triangular", "lognormal"] | None = Field(
        default=None, description="Distribution; omit it for the tolerance form [-]"
    )
    mean: Number | None = Field(default=None, description="Mean (normal, lognormal) [field unit]")
    sd: Number | None = Field(
        default=None, description="Standard deviation (normal, lognormal) [field unit]"
    )
    low: Number | None = Field(
        default=None,
        description="Lower end (uniform, triangular); truncation (normal, lognormal) [field unit]",
    )
    high: Number | None = Field(
        default=None,
        description="Upper end (uniform, triangular); truncation (normal, lognormal) [field unit]",
    )
    mode: Number | None = Field(default=None, description="Most likely value (triangular)")
    nominal: Number | None = Field(default=None, description="Nominal value (tolerance form)")
    tol: Number | None = Field(
        default=None,
        description='Tolerance: "±10 %", "±0.05", "±2 mm", or a number (tolerance form)',
    )

    @model_validator(mode="after")
    def _one_form(self) -> InputSpec:
        given = {k for k, v in self.__dict__.items() if v is not None and k != "dist"}
        need: dict[str | None, tuple[set[str], set[str]]] = {
            None: ({"nominal", "tol"}, set()),
            "normal": ({"mean", "sd"}, {"low", "high"}),
            "lognormal": ({"mean", "sd"}, {"low", "high"}),
            "uniform": ({"low", "high"}, set()),
            "triangular": ({"low", "mode", "high"}, set()),
        }
        required, optional = need[self.dist]
        form = f'dist = "{self.dist}"' if self.dist else "the tolerance form (no dist)"
        if missing := sorted(required - given):
            raise ValueError(f"{form} needs {', '.join(missing)}")
        if extra := sorted(given - required - optional):
            raise ValueError(f"{form} takes {', '.join(sorted(required | optional))}, "
                             f"not {', '.join(extra)}")  # fmt: skip
        return self


class LimitSpec(CaseModel):
    """A threshold on a result: exceeded when the result is above ``above`` or below
    ``below``."""

    above: float | None = Field(default=None, description="Exceeded above this [result unit]")
    below: float | None = Field(default=None, description="Exceeded below this [result unit]")

    @model_validator(mode="after")
    def _some(self) -> LimitSpec:
        if self.above is None and self.below is None:
            raise ValueError("give above = ... or below = ... (or both)")
        if self.above is not None and self.below is not None and self.below >= self.above:
            raise ValueError("below must be less than above (the allowed band is between)")
        return self


class StudySpec(CaseModel):
    """The ``[study]`` table."""

    samples: int = Field(gt=0, le=MAX_SAMPLES, description="Monte Carlo samples [-]")
    sampler: Literal["random", "lhs", "sobol"] = Field(
        default="random", description="random, lhs (Latin hypercube) or sobol (scrambled) [-]"
    )
    seed: int = Field(default=0, ge=0, le=2**63 - 1, description="Seed of the draws [-]")
    inputs: dict[str, InputSpec] = Field(min_length=1, description="Uncertain keys [-]")
    results: list[str] | None = Field(
        default=None, min_length=1, description="Results to summarize (default: key results)"
    )
    limits: dict[str, LimitSpec] = Field(default_factory=dict, description="Limits on results")
    sensitivity: bool = Field(default=False, description="Sobol indices (SALib) [-]")
    sensitivity_samples: int = Field(
        default=1024, ge=16, le=MAX_SAMPLES, description="Saltelli base samples N, a power of 2"
    )

    @model_validator(mode="after")
    def _power_of_two(self) -> StudySpec:
        if self.results is not None and len(set(self.results)) != len(self.results):
            twice = sorted({r for r in self.results if self.results.count(r) > 1})
            raise ValueError(f"results names {', '.join(twice)} more than once")
        n = self.sensitivity_samples
        if n & (n - 1):
            raise ValueError(
                f"sensitivity_samples = {n}; the Saltelli design needs a power of 2 "
                f"(e.g. {1 << (n.bit_length() - 1)} or {1 << n.bit_length()})"
            )
        return self


class StudyDoc(CaseBase):
    """The study file's own keys (the scene's are its problem's)."""

    problem: str = Field(description="The problem of the scene")
    study: StudySpec = Field(description="The study table")


# ------------------------------------------------------------------- distributions


@dataclass(frozen=True)
class Distribution:
    """A continuous distribution by its inverse CDF, optionally truncated to
    [lower, upper]. ``kind`` normal/lognormal: a, b are the mean and sd of the value
    itself; uniform: a, b the ends; triangular: a, c, b low, mode, high."""

    kind: str
    a: float
    b: float
    c: float = math.nan
    lower: float | None = None  # truncation (normal, lognormal)
    upper: float | None = None

    # The log-space parameters of a lognormal with mean a and sd b.
    @property
    def _log(self) -> tuple[float, float]:
        sigma2 = math.log1p((self.b / self.a) ** 2)
        return math.log(self.a) - 0.5 * sigma2, math.sqrt(sigma2)

    def _base_cdf(self, x: float) -> float:
        from scipy.special import ndtr

        if self.kind == "normal":
            return float(ndtr((x - self.a) / self.b))
        if self.kind == "lognormal":
            if x <= 0.0:
                return 0.0
            mu, sigma = self._log
            return float(ndtr((math.log(x) - mu) / sigma))
        if self.kind == "uniform":
            return min(1.0, max(0.0, (x - self.a) / (self.b - self.a)))
        low, mode, high = self.a, self.c, self.b  # triangular
        if x <= low:
            return 0.0
        if x >= high:
            return 1.0
        if x <= mode:
            return (x - low) ** 2 / ((high - low) * (mode - low))
        return 1.0 - (high - x) ** 2 / ((high - low) * (high - mode))

    def _window(self) -> tuple[float, float]:
        lo = 0.0 if self.lower is None else self._base_cdf(self.lower)
        hi = 1.0 if self.upper is None else self._base_cdf(self.upper)
        return lo, hi

    def cdf(self, x: float) -> float:
        lo, hi = self._window()
        return min(1.0, max(0.0, (self._base_cdf(x) - lo) / (hi - lo)))

    def _z_window(self) -> tuple[float, float]:
        """The truncation in standard-normal units (normal; lognormal in log space)."""
        if self.kind == "normal":
            mu, sigma = self.a, self.b
            to = lambda x: (x - mu) / sigma  # noqa: E731
        else:
            mu, sigma = self._log
            to = lambda x: (math.log(x) - mu) / sigma if x > 0 else -math.inf  # noqa: E731
        z_lo = -math.inf if self.lower is None else to(self.lower)
        z_hi = math.inf if self.upper is None else to(self.upper)
        return z_lo, z_hi

    def mass(self) -> float:
        """The probability the truncation keeps (1 without one), from the nearer tail."""
        if self.kind not in ("normal", "lognormal"):
            return 1.0
        from scipy.special import ndtr

        z_lo, z_hi = self._z_window()
        if z_lo > 0.0:
            return float(ndtr(-z_lo) - ndtr(-z_hi))
        return float(ndtr(z_hi) - ndtr(z_lo))

    def _z(self, u: Any) -> Any:
        """Standard-normal quantiles of probabilities ``u`` inside the truncation,
        taken in the upper tail where the window lies there (1 - q would round)."""
        import numpy as np
        from scipy.special import ndtr, ndtri

        u = np.asarray(u, dtype=float)
        if self.lower is None and self.upper is None:
            return ndtri(u)
        z_lo, z_hi = self._z_window()
        if z_lo > 0.0:
            s_lo, s_hi = ndtr(-z_lo), ndtr(-z_hi)
            z = -ndtri(s_lo - u * (s_lo - s_hi))
        else:
            f_lo, f_hi = ndtr(z_lo), ndtr(z_hi)
            z = ndtri(f_lo + u * (f_hi - f_lo))
        return np.clip(z, z_lo, z_hi)

    def ppf(self, u: Any) -> Any:
        """Values at probabilities ``u`` (a numpy array in (0, 1))."""
        import numpy as np

        if self.kind in ("normal", "lognormal"):
            z = self._z(u)
            if self.kind == "normal":
                x = self.a + self.b * z
            else:
                mu, sigma = self._log
                x = np.exp(mu + sigma * z)
            if self.lower is not None or self.upper is not None:  # rounding at the cut
                x = np.clip(x, self.lower, self.upper)
            return x
        q = np.asarray(u, dtype=float)
        if self.kind == "uniform":
            x = self.a + q * (self.b - self.a)
        else:
            low, mode, high = self.a, self.c, self.b
            split = (mode - low) / (high - low)
            with np.errstate(invalid="ignore"):
                x = np.where(
                    q < split,
                    low + np.sqrt(q * (high - low) * (mode - low)),
                    high - np.sqrt((1.0 - q) * (high - low) * (high - mode)),
                )
        if self.lower is not None or self.upper is not None:  # rounding at the cut
            x = np.clip(x, self.lower, self.upper)
        return x

    def describe(self, unit: str) -> str:
        """The distribution in the key's unit, every number with the digits to check
        it by eye against what the file wrote (12 significant)."""
        u = f" {unit}" if unit else ""
        if self.kind in ("normal", "lognormal"):
            text = f"{self.kind}(mean {self.a:.12g}, sd {self.b:.12g}){u}"
            if self.lower is not None or self.upper is not None:
                lo = "-∞" if self.lower is None else f"{self.lower:.12g}"
                hi = "∞" if self.upper is None else f"{self.upper:.12g}"
                text += f" truncated to [{lo}, {hi}]"
            return text
        if self.kind == "uniform":
            return f"uniform({self.a:.12g} … {self.b:.12g}){u}"
        return f"triangular({self.a:.12g}, mode {self.c:.12g}, {self.b:.12g}){u}"

    def moments(self) -> tuple[float, float]:
        """Mean and standard deviation of the untruncated distribution."""
        if self.kind in ("normal", "lognormal"):
            return self.a, self.b
        if self.kind == "uniform":
            return 0.5 * (self.a + self.b), (self.b - self.a) / math.sqrt(12.0)
        a, c, b = self.a, self.c, self.b
        return (a + b + c) / 3.0, math.sqrt((a * a + b * b + c * c - a * b - a * c - b * c) / 18)


@dataclass(frozen=True)
class Input:
    key: str
    loc: tuple[str | int, ...]
    unit: str
    dist: Distribution


@dataclass
class Plan:
    """A validated study: the scene, its problem, the inputs and the table."""

    case: CaseText  # the study file; ``scene_data`` is its scene without [study]
    problem: str
    scene_data: dict[str, Any]
    spec: StudySpec
    inputs: list[Input]
    nominal: Any  # the scene validated, as written
    expect: dict[str, Any] = field(default_factory=dict)
    #: The scene as validated (its quantity strings' conversions); None: not kept.
    scene_case: CaseText | None = None

    @property
    def keys(self) -> list[str]:
        return [i.key for i in self.inputs]


def is_study(data: dict[str, Any]) -> bool:
    return "study" in data


def plan(case: CaseText) -> Plan:
    """Validate a study file already read: its scene, its ``[study]`` table and every
    distribution against the bounds of the key it draws."""
    from mdcalc.runs.runner import problem_of

    spec_problem = problem_of(case)
    module = spec_problem.load()
    scene_data = {k: v for k, v in case.data.items() if k not in ("study", "expect")}
    scene = CaseText(case.path, case.text, scene_data)
    nominal = validate(module.Case, scene)
    own: dict[str, Any] = {
        k: case.data[k] for k in ("problem", "title", "study", "expect") if k in case.data
    }
    doc = validate(StudyDoc, CaseText(case.path, case.text, own))
    spec = doc.study
    problems: list[Problem] = []
    inputs = []
    for key, given in spec.inputs.items():
        made = _input(module.Case, case, scene_data, key, given, problems)
        if made is not None:
            inputs.append(made)
    if problems:
        raise InputError(case.path, problems)
    _median_scene_is_valid(module.Case, case, scene_data, inputs)
    expect = dict(doc.expect or {})
    return Plan(case, spec_problem.name, scene_data, spec, inputs, nominal, expect, scene)


def _median_scene_is_valid(
    model: Any, case: CaseText, scene: dict[str, Any], inputs: list[Input]
) -> None:
    """The scene with every input at its median must validate: a key the scene does
    not write may need others beside it (a section of its own)."""
    import copy

    import numpy as np

    from mdcalc.input.casefile import set_key

    data = copy.deepcopy(scene)
    for item in inputs:
        try:
            set_key(data, item.loc, float(item.dist.ppf(np.array([0.5]))[0]))
        except KeyError:
            raise InputError(
                case.path,
                [Problem(f"no place for {item.key} in this scene", f"study.inputs.{item.key}")],
            ) from None
    try:
        validate(model, CaseText(case.path, case.text, data))
    except InputError as exc:
        for p in exc.problems:
            p.message += " (the scene with every study input at its median)"
        raise


def _input(
    model: Any,
    case: CaseText,
    scene: dict[str, Any],
    key: str,
    given: InputSpec,
    problems: list[Problem],
) -> Input | None:
    path = f'study.inputs."{key}"'
    loc: tuple[str | int, ...] = tuple(int(p) if p.isdigit() else p for p in key.split("."))
    line = case.line_of(("study", "inputs", key)) or case.line_of(("study", "inputs"))

    def fail(message: str) -> None:
        problems.append(Problem(message, path, line))

    info = field_info(model, loc)
    from mdcalc.input.casefile import get_key

    base = get_key(scene, loc)
    from mdcalc.input.casefile import takes_numbers

    if info is None or not takes_numbers(info.annotation) or isinstance(base, bool | dict | list):
        fail(f"{key} is not a number of this problem's scene; a study draws numeric keys")
        return None
    unknown = missing_name(model, scene, loc)
    if unknown is not None:
        fail(unknown)
        return None
    if is_integer_field(model, loc):
        fail(f"{key} takes whole numbers; a study draws continuous values only")
        return None
    unit = unit_of(model, loc)

    def number(name: str, value: Any) -> float | None:
        if value is None:
            return None
        if isinstance(value, str):
            from mdcalc.input.quantities import QuantityError, convert

            try:
                value = convert(value, unit if unit else "-")
            except QuantityError as exc:
                problems.append(Problem(f"{name}: {exc}", path, line))
                return None
        if not math.isfinite(value) or abs(value) > MAGNITUDE_LIMIT:
            fail(f"{name} = {value!r}; must be a finite number within ±{MAGNITUDE_LIMIT:g}")
            return None
        return float(value)

    values = {
        name: number(name, getattr(given, name))
        for name in ("mean", "sd", "low", "high", "mode", "nominal")
    }
    if problems and any(p.path == path for p in problems):
        return None
    kind = given.dist
    if kind is None:
        nominal = values["nominal"]
        half = _tolerance(given.tol, nominal, unit, fail)
        if nominal is None or half is None:
            return None
        if half <= 0.0:
            fail(f"tol = {given.tol!r}; a tolerance must be more than 0")
            return None
        dist = Distribution("uniform", nominal - half, nominal + half)
    elif kind in ("normal", "lognormal"):
        mean, sd = values["mean"], values["sd"]
        assert mean is not None and sd is not None
        if sd <= 0.0:
            fail(f"sd = {sd:g}; must be > 0")
            return None
        if kind == "lognormal" and mean <= 0.0:
            fail(f"mean = {mean:g}; a lognormal value is positive: the mean must be > 0")
            return None
        lower, upper = values["low"], values["high"]
        if lower is not None and upper is not None and lower >= upper:
            fail(f"low = {lower:g} is not below high = {upper:g}")
            return None
        dist = Distribution(kind, mean, sd, lower=lower, upper=upper)
        if not dist.mass() > 1e-300:
            fail("the truncation leaves no probability (low and high are far in one tail)")
            return None
    elif kind == "uniform":
        low, high = values["low"], values["high"]
        assert low is not None and high is not None
        if low >= high:
            fail(f"low = {low:g} is not below high = {high:g}")
            return None
        dist = Distribution("uniform", low, high)
    else:
        low, mode, high = values["low"], values["mode"], values["high"]
        assert low is not None and mode is not None and high is not None
        if not (low <= mode <= high and low < high):
            fail(f"need low <= mode <= high and low < high (got {low:g}, {mode:g}, {high:g})")
            return None
        dist = Distribution("triangular", low, high, mode)
    bounds_problem = _outside_bounds(info, loc, dist, unit)
    if bounds_problem is not None:
        fail(bounds_problem)
        return None
    return Input(key, loc, unit, dist)


_PERCENT = re.compile(r"^\s*(?:±|\+/-|\+-)?\s*([0-9.]+(?:[eE][-+]?\d+)?)\s*%\s*$")


def _tolerance(tol: Any, nominal: float | None, unit: str, fail: Any) -> float | None:
    """The half-width of a tolerance: "±10 %" of the nominal, or "±0.05" / "±2 mm" /
    0.05 in the field's unit; None (and ``fail`` told why) for anything else."""
    if nominal is None:
        return None
    half = _half_width(tol, nominal, unit, fail)
    if half is None:
        return None
    if not math.isfinite(half) or half > MAGNITUDE_LIMIT:
        fail(f"tol = {tol!r}; a tolerance must be a finite size within ±{MAGNITUDE_LIMIT:g}")
        return None
    return half


def _half_width(tol: Any, nominal: float, unit: str, fail: Any) -> float | None:
    if not isinstance(tol, str):
        return abs(float(tol))
    match = _PERCENT.match(tol)
    if match:
        return abs(nominal) * float(match.group(1)) / 100.0
    text = tol.strip().removeprefix("±").removeprefix("+/-").removeprefix("+-").strip()
    if text.startswith("-"):
        fail(f'tol = {tol!r}; a tolerance is a size: write "±5 %" or "±0.05"')
        return None
    try:
        return abs(float(text))
    except ValueError:
        pass
    from mdcalc.input.quantities import QuantityError, convert

    try:
        return abs(convert(text, unit if unit else "-"))
    except QuantityError as exc:
        fail(f'tol: {exc} (write "±10 %", "±0.05" or "±2 mm")')
        return None


def bound_marks(info: Any, loc: tuple[str | int, ...]) -> list[Any]:
    """The gt/ge/lt/le marks of the field at ``loc``: its own, or for a list item
    (``drive.stage_efficiencies.0``) those of the item type
    (``list[Annotated[float, Field(gt=0, le=1)]]``)."""
    from typing import get_args, get_origin

    if not loc or not isinstance(loc[-1], int):
        return list(getattr(info, "metadata", []))
    marks: list[Any] = []
    stack = [getattr(info, "annotation", None)]
    while stack:
        kind = stack.pop()
        if get_origin(kind) is list:
            for item in get_args(kind)[:1]:
                for extra in getattr(item, "__metadata__", ()):
                    marks += list(getattr(extra, "metadata", [extra]))
        else:
            stack.extend(get_args(kind))
    return marks


def _outside_bounds(info: Any, loc: Any, dist: Distribution, unit: str) -> str | None:
    """Why ``dist`` can draw a value the field refuses (its gt/ge/lt/le and the
    magnitude limit), with the probability outside; None if it cannot. A truncation
    at the bound itself leaves no probability outside and passes."""
    import numpy as np

    lowest, highest = (float(v) for v in dist.ppf(np.array([U_MIN, U_MAX])))
    u = f" {unit}" if unit else ""
    for item in bound_marks(info, loc):
        for name, op in (("gt", ">"), ("ge", ">="), ("lt", "<"), ("le", "<=")):
            bound = getattr(item, name, None)
            if bound is None:
                continue
            bad = {
                "gt": lowest <= bound,
                "ge": lowest < bound,
                "lt": highest >= bound,
                "le": highest > bound,
            }[name]
            if not bad:
                continue
            outside = dist.cdf(bound) if name in ("gt", "ge") else 1.0 - dist.cdf(bound)
            if outside == 0.0:
                continue
            edge = lowest if name in ("gt", "ge") else highest
            return (
                f"{dist.describe(unit)} draws values down to {edge:.6g}{u}"
                if name in ("gt", "ge")
                else f"{dist.describe(unit)} draws values up to {edge:.6g}{u}"
            ) + (
                f", but the key must be {op} {bound:g}{u}: a probability of {outside:.3g} lies "
                "outside; truncate it (low = / high =) or narrow it"
            )
    if max(abs(lowest), abs(highest)) > MAGNITUDE_LIMIT:
        return f"{dist.describe(unit)} draws beyond ±{MAGNITUDE_LIMIT:g}; narrow it"
    return None
