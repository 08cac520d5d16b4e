"""mdcalc: a command-line calculator for machine dynamics.

The package's layers (tests/test_architecture.py holds the rule): ``cli`` (the
console entry and the typer app) -> ``runs`` (one case under its budget, batches,
check, sweep, study, the pool and the cluster) -> ``problems`` (one package or
module per subcommand) -> ``domain`` (data and case sections several problems
share) -> ``methods``, ``input`` (case files) and ``output`` (the Report and its
renderers) -> ``core`` (shared maths);
below them all the leaves ``errors`` and ``_version``. No module of the package
imports this one: it is the face for users of mdcalc from Python.
"""

from mdcalc._version import __version__

__all__ = ["__version__"]
