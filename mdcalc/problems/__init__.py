"""Registry of problems: one module or package per subcommand.

A problem supplies, for its subcommand to exist:

1. ``Case`` -- a pydantic model of the case file, derived from
   :class:`mdcalc.input.model.CaseBase`, with ``problem: Literal["<name>"]``;
   sections are :class:`mdcalc.input.model.CaseModel` (strict, no unknown keys); SI
   units, the unit in brackets at the end of every field description; optional
   sections for optional parts of the scene.
2. ``solve(case) -> Result`` -- pure: no printing, no I/O. A valid scene without an
   answer comes back as a result whose ``status`` is ``"no-answer"`` with a
   ``message`` saying why (the CLI exits 3), never as an exception.
3. ``report(result) -> Report`` -- a :class:`mdcalc.output.report.Report` of the
   sections the scene needs (quantities with stable keys, tables, a Methods table
   built by :func:`mdcalc.methods.compare`).
4. ``template() -> dict`` -- a starter case that runs as it is (``mdcalc new``), and
   optionally ``starter_extras() -> dict``: example values the starter shows commented
   out beside it (other keys of its sections, and optional sections with their own
   optional keys under ``_or``; :mod:`mdcalc.input.starter`).
5. Optionally ``charts(result) -> list[Chart]`` (``--plot``; data only, no
   matplotlib) and ``sweep(case, grid, wanted=None) -> dict | None``, the
   vectorized kernel of ``mdcalc sweep`` and ``mdcalc study`` (``wanted``: the result
   keys asked for, so that a costly one is left out when not asked). A kernel runs
   the same formulas as ``solve``: closed forms are written once for floats and
   numpy arrays (:mod:`mdcalc.core.xp`), modal and other numerical work runs on a
   block of scenes, the single scene being a block of one (:mod:`mdcalc.core.chain`),
   and :func:`mdcalc.input.model.with_values` puts the grid's arrays into the case so
   that the problem's own scene code runs on them. Never restate a formula in numpy.
   A sample the kernel cannot take (no answer there) is marked in the answer's
   :data:`mdcalc.input.model.DECLINED` mask; the caller solves it alone. Where the
   single scene's reference is an ODE run and the kernel's value an exact closed
   form, ``ODE_REFERENCED`` (result key -> relative tolerance) says how closely the
   two agree.
6. Reference, stiff and extreme cases in ``cases/<name>/`` with ``[expect]`` tables,
   and tests whose expected values are computed independently of the module.

Layout: a small problem is one module, ``problems/<name>.py``. One that outgrows
~700 lines (tests/test_architecture.py holds the limit) is a package whose files
show its parts: ``problems/<name>/__init__.py`` is its face (the names above and
nothing else, in ``__all__``), ``case.py`` the pydantic sections, ``solve.py`` (or
one file per sub-scene) the scene and solver, ``report.py``, ``charts.py`` and
``kernel.py``. Imports inside a package run one way, case <- solve <- report <-
charts, with no circle (tests/test_architecture.py checks the whole import graph).

What a problem may import: :mod:`mdcalc.methods`, :mod:`mdcalc.input` (the case
models), :mod:`mdcalc.output` (the Report value, chart data), :mod:`mdcalc.core`
(shared maths) and :mod:`mdcalc.domain` (data and case sections several
problems share: road adhesion, allowable accelerations, drag); never another
problem, never :mod:`mdcalc.runs` or :mod:`mdcalc.cli` (the layers of
tests/test_architecture.py). Maths a second problem needs goes to ``core``; data or
a case section it needs, to ``domain`` (a layer of its own below the problems: it
is no problem and has no ``cases/`` folder).

Then add one :class:`ProblemSpec` to ``PROBLEMS`` below: the CLI command, ``check``
and ``new`` pick it up. The module is imported only when its command runs, so
``mdcalc --help`` pays for none of them.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol, cast

if TYPE_CHECKING:  # the CLI imports this registry; --help must not pay for report
    from mdcalc.output.report import Report


class ProblemModule(Protocol):
    Case: Any

    def solve(self, case: Any) -> Any: ...

    def report(self, result: Any) -> Report: ...

    def template(self) -> dict[str, Any]: ...


@dataclass(frozen=True)
class ProblemSpec:
    name: str
    module: str
    summary: str
    #: Does its scene draw curves (``charts``)? Without, its command has no --plot.
    draws: bool = True
    #: Has it ODE methods (``Method.ladder``)? Then its command has --work-precision.
    ladders: bool = True

    def load(self) -> ProblemModule:
        return cast(ProblemModule, importlib.import_module(f"mdcalc.problems.{self.module}"))


PROBLEMS: dict[str, ProblemSpec] = {
    spec.name: spec
    for spec in (
        ProblemSpec(
            "hoist",
            "hoist",
            "Hoist motor and brake: static and start torques, reduced inertia, rope loads.",
        ),
        ProblemSpec(
            "acceleration",
            "acceleration",
            "Car acceleration through the gears: time and distance to a target speed.",
        ),
        ProblemSpec(
            "braking",
            "braking",
            "Car braking: time and distance, adhesion limit, road resistance, drag, reaction.",
            draws=False,
        ),
        ProblemSpec(
            "coupling",
            "coupling",
            "Elastic coupling: dynamic factor under step, harmonic, pulse, ramp, tabulated torque.",
        ),
        ProblemSpec(
            "mine-hoist",
            "mine_hoist",
            "Mine hoist with head sheave: rope dynamic factors of a three-mass chain.",
        ),
        ProblemSpec(
            "variator",
            "variator",
            "Impulse variator: anti-resonance absorber, clutch load χ, pendulum absorber.",
        ),
        ProblemSpec(
            "mechanism",
            "mechanism",
            "One-degree-of-freedom mechanism under M(φ, ω): Kovylin's step against the ODE.",
        ),
        ProblemSpec(
            "resonance",
            "resonance",
            "Torsional resonance: modes, Campbell table, resonant amplitudes, Mathieu stability.",
        ),
        ProblemSpec(
            "clutch",
            "clutch",
            "Adaptive friction clutch: slip torques, stability bound of the gain C_max.",
            ladders=False,
        ),
        ProblemSpec(
            "mount",
            "mount",
            "Engine on elastic mounts: resonances, harmonic amplitudes, transmission.",
            ladders=False,
        ),
    )
}
