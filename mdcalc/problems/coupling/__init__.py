"""``coupling``: dynamic factor of an elastic coupling between two inertias (seed 000
§8.1, §8.2 first part, example 8.1; brief §5).

Model (8.3): for the twist φ = φ₁ - φ₂, φ'' + p·φ' + q·φ = M₁/J₁ + M₂/J₂ with
q = c·(1/J₁ + 1/J₂) = β², p = α·(1/J₁ + 1/J₂). A torque M passed through the
coupling enters as M/J, J = J₁J₂/(J₁ + J₂), so its static twist is M/c. Damping from
the absorption coefficient ψ (p = ψ/τ, (8.7) and (8.14) with the lecture's
τ = 2π/β), the logarithmic decrement δ (p = 2δ/τ) or α itself. In the terms of
:mod:`mdcalc.core.sdof`, ζ = p/(2β).

* Suddenly applied torque (8.15)-(8.16): dynamic factor 1 + exp(-π·ζ/√(1 - ζ²)),
  envelope 1 + e^(-p·t/2), exactly 2 undamped, 1 over-damped.
* Harmonic torques on both halves (8.19)-(8.32): the combined amplitude (8.21), the
  steady twist (8.27), the response curve over λ = ω/β, the resonance peak at
  λ = √(1 - γ²/2) of height M/(β²·γ·√(1 - γ²/4)), γ = p/β (the printed (8.32) has
  √(1 - γ²/2)).
* Rectangular pulse, ramp and tabulated torque through the Duhamel integral, exact
  for piecewise-linear loads, checked against ODE runs in the Methods table.

Its files:

- ``case.py``: The case file of ``mdcalc coupling``: pydantic sections in SI units, and the
  starter case.
- ``scene.py``: The scene: the case reduced to the twist oscillator (β, p, ζ), and the closed
  forms of the suddenly applied and the harmonic torques; floats, or numpy arrays
  over a sweep grid.
- ``transients.py``: Transient torques (pulse, ramp, table) as piecewise-linear knots, their exact
  Duhamel response and the ODE runs that check it.
- ``solve.py``: The solver: the Methods of each load, and the result.
- ``report.py``: The report: the sections a coupling scene needs.
- ``kernel.py``: The vectorized kernel of ``mdcalc sweep``: the closed forms over a grid at once.
- ``charts.py``: The charts of ``--plot``: step response with its envelope, response curve over
  λ = ω/β, transient histories (data only).
"""

from __future__ import annotations

from mdcalc.problems.coupling.case import Case, starter_extras, template
from mdcalc.problems.coupling.charts import charts
from mdcalc.problems.coupling.kernel import SWEEP_KEYS, sweep
from mdcalc.problems.coupling.report import report
from mdcalc.problems.coupling.solve import solve

__all__ = ["Case", "solve", "report", "template", "starter_extras"]
__all__ += ["charts", "sweep", "SWEEP_KEYS"]  # what a study, sweep, --plot use
