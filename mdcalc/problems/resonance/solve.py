"""The solver: the Methods, and the result."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.methods import Method, compare
from mdcalc.output.report import MethodQuantity, MethodsTable, Note
from mdcalc.problems.resonance.case import Case
from mdcalc.problems.resonance.chain import (
    Amplitudes,
    Modal,
    energy_method,
    forced_response,
    modal,
    modal_dissipation,
    peak_response,
    undamped_mode,
)
from mdcalc.problems.resonance.mathieu import (
    liouville,
    monodromy_ode,
    monodromy_rk4,
    spectral_radius,
)


@dataclass
class Result:
    case: Case
    modal: Modal | None = None
    methods: list[MethodsTable] = field(default_factory=list)
    notes: list[Note] = field(default_factory=list)
    floquet: list[tuple[float, float, float, float]] = field(default_factory=list)
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


def solve(case: Case) -> Result:
    result = Result(case)
    if case.chain is not None:
        import numpy as np

        try:
            with np.errstate(all="ignore"):
                result.modal = modal(case.chain)
        except (ArithmeticError, ValueError) as exc:
            result.status, result.message = (
                "no-answer",
                f"the natural modes cannot be computed to working precision ({exc}): the "
                "chain's inertias and stiffnesses span too many decades over its length",
            )
            return result
    r = case.resonance
    if r is not None and r.harmonic_torque is not None:
        assert case.chain is not None and result.modal is not None
        md, j = result.modal, r.mode - 1
        section, torque = case.chain, r.harmonic_torque
        assert section.damping is not None
        import numpy as np

        damping = np.array([section.damping], dtype=float)
        dissipation = modal_dissipation(section, md, j)
        if undamped_mode(damping, np.array([dissipation]))[0]:
            result.status, result.message = (
                "no-answer",
                f"undamped resonance: no damping moves in mode {r.mode} (Σ ξᵢ·aᵢ² = 0), "
                "the resonant amplitude is unbounded; give the masses damping",
            )
            return result
        omega = md.frequencies[j]
        try:
            forced_response(section, md, j, r.order, torque, omega)
        except ArithmeticError:
            result.status, result.message = (
                "no-answer",
                f"the damped response at the resonance of mode {r.mode} cannot be resolved: "
                "(K - ω²J + iωΞ) is singular to working precision at ω = β: the damping "
                f"(Σ ξᵢ·aᵢ² = {dissipation:.3g} N·m·s/rad) is too small against the "
                "stiffness, so the amplitude is practically unbounded, or the stiffnesses "
                "span too many decades for the shaft torques to keep any digits",
            )
            return result

        def as_values(amp: Amplitudes) -> dict[str, float]:
            return {"amplitude": amp.reference_amplitude, "max_shaft_torque": amp.max_shaft_torque}

        methods = [
            Method(
                "energy balance, seed (5)",
                lambda: as_values(energy_method(section, md, j, r.order, torque)),
                note="free mode shape, phase diagram",
            ),
            Method(
                "exact forced response at ω = β",
                lambda: as_values(forced_response(section, md, j, r.order, torque, omega)),
                reference=True,
                note="(K - ω²J + iωΞ)·X = M",
            ),
            Method(
                "exact, peak over speed",
                lambda: as_values(peak_response(section, md, j, r.order, torque)[1]),
                note="golden section near β",
            ),
        ]
        result.methods.append(
            compare(
                f"Methods: resonance of order {r.order:g} with mode {r.mode}",
                "resonance",
                [
                    MethodQuantity("amplitude", "A at the reference mass", "rad"),
                    MethodQuantity("max_shaft_torque", "largest shaft torque", "N·m"),
                ],
                methods,
            )
        )
    m = case.mathieu
    if m is not None and m.points:
        c = m.damping
        for a, q in m.points:
            trace, det = monodromy_ode(a, q, c, 1e-12)
            result.floquet.append((a, q, trace, liouville(det, c)))
        quantities = [
            MethodQuantity(f"floquet_radius_{k + 1}", f"ρ at (a, q) = ({a:g}, {q:g})", "")
            for k, (a, q) in enumerate(m.points)
        ]

        def radii(
            run: Callable[[float, float], tuple[float, float]],
        ) -> Callable[[], dict[str, float]]:
            def go() -> dict[str, float]:
                out = {}
                for k, (a, q) in enumerate(m.points):
                    trace, det = run(a, q)
                    out[f"floquet_radius_{k + 1}"] = spectral_radius(trace, liouville(det, c))
                return out

            return go

        def ladder(rtol: float) -> dict[str, float]:  # --work-precision's rungs
            return radii(lambda a, q: monodromy_ode(a, q, c, rtol))()

        result.methods.append(
            compare(
                "Methods: Floquet multipliers of one period",
                "floquet",
                quantities,
                [
                    Method("RK4, 32 steps", radii(lambda a, q: monodromy_rk4(a, q, c, 32))),
                    Method(
                        "RK4, 256 steps",
                        radii(lambda a, q: monodromy_rk4(a, q, c, 256)),
                        accuracy=1,
                    ),
                    Method(
                        "DOP853 rtol 1e-7",
                        radii(lambda a, q: monodromy_ode(a, q, c, 1e-7)),
                        imports=ODE_IMPORTS,
                        accuracy=2,
                        ladder=ladder,
                    ),
                    Method(
                        "DOP853 rtol 1e-12",
                        radii(lambda a, q: monodromy_ode(a, q, c, 1e-12)),
                        reference=True,
                        imports=ODE_IMPORTS,
                        ladder=ladder,
                        rtol=1e-12,
                    ),
                ],
            )
        )
    return result
