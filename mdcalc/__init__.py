"""mdcalc: a calculator for machine dynamics, on the command line and from Python.

From Python (docs/python.md)::

    import mdcalc
    calc = mdcalc.solve(Path("cases/braking/lecture.toml"))
    calc.results["stopping_distance"]   # a pint Quantity

``import mdcalc`` loads nothing heavy (numpy, scipy, pint, rich, pydantic wait for the
first call): the names below are resolved on first use, from :mod:`mdcalc.api`.

The package's layers (tests/test_architecture.py holds the rule): ``cli`` (the
console entry and the typer app) -> ``api`` (the calculations from Python; the
commands call it) -> ``runs`` (one case under its budget, batches, check, sweep,
study, the pool and the cluster) -> ``problems`` (one package or module per
subcommand) -> ``domain`` (data and case sections several problems share) ->
``methods``, ``input`` (case files) and ``output`` (the Report and its renderers) ->
``core`` (shared maths); below them all the leaves ``errors`` and ``_version``. No
module of the package imports this one.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from mdcalc._version import __version__
from mdcalc.errors import InputError, NoAnswer

if TYPE_CHECKING:
    from mdcalc.api import (
        Calculation,
        MethodsView,
        ProblemInfo,
        StudyResult,
        SweepResult,
        registry,
        solve,
        study,
        sweep,
    )

__all__ = [
    "Calculation",
    "InputError",
    "MethodsView",
    "NoAnswer",
    "ProblemInfo",
    "StudyResult",
    "SweepResult",
    "__version__",
    "registry",
    "solve",
    "study",
    "sweep",
]

#: What :mod:`mdcalc.api` gives, loaded on first use.
_LAZY = frozenset(__all__) - {"InputError", "NoAnswer", "__version__"}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        from mdcalc import api

        return getattr(api, name)
    raise AttributeError(f"module 'mdcalc' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
