"""``resonance``: torsional resonance of an engine-transmission chain (seed 003,
Tverskov; brief §9).

A free-free chain J₁ - c₁ - J₂ - … - Jₙ (:mod:`mdcalc.core.chain`), some masses
being cranks with firing angles δᵢ.

* Natural frequencies fⱼ and mode shapes, relative amplitudes aᵢ with a = 1 at the
  reference mass (the first mass, or the first crank when the first mass is a node).
* Critical speeds n = 60·f/k for each harmonic order k (half orders for a
  four-stroke engine): a Campbell table over the speed range.
* Resonant amplitude by the energy balance (the seed's (5)): the work of the k-th
  order torque M_k over a cycle, π·M_k·A·|Σ aᵢ·e^(i·k·δᵢ)|, equals the damping work
  π·ω_c·A²·Σ ξᵢ·aᵢ², so A = M_k·|Σ aᵢ·e^(i·k·δᵢ)|/(ω_c·Σ ξᵢ·aᵢ²); shaft torques
  cᵢ(Aᵢ - Aᵢ₊₁). The Methods table sets it against the exact damped steady state
  (K - ω²J + iωΞ)·X = M at the resonant speed and at the peak over speed.
* Parametric resonance (Hooke's joints): x″ + c·x′ + (a - 2q·cos 2t)·x = 0 is
  stable when both Floquet multipliers of one period π lie inside the unit circle;
  det = e^(-cπ) (Liouville), so it is |trace| < 1 + e^(-cπ).

Its files:

- ``case.py``: The case file of ``mdcalc resonance``: pydantic sections in SI units, and the
  starter case.
- ``chain.py``: The torsional chain: natural modes with their reference masses, the
  geometric sums of the orders, resonant amplitudes (energy method, forced response and
  its peak).
- ``mathieu.py``: Parametric excitation: the Mathieu equation, its stability by Floquet theory.
- ``solve.py``: The solver: the Methods, and the result.
- ``report.py``: The report: the sections a resonance scene needs.
- ``kernel.py``: The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study``: every
  numeric result over a block of chains (the Mathieu points aside), by the functions
  the single scene runs on a block of one.
- ``charts.py``: The charts of ``--plot``: the Campbell diagram and the Ince-Strutt chart of
  the Mathieu equation (data only).
"""

from __future__ import annotations

from mdcalc.problems.resonance.case import Case, starter_extras, template
from mdcalc.problems.resonance.charts import charts
from mdcalc.problems.resonance.kernel import ODE_REFERENCED, SWEEP_KEYS, sweep
from mdcalc.problems.resonance.report import report
from mdcalc.problems.resonance.solve import solve

__all__ = ["Case", "solve", "report", "template", "starter_extras"]
__all__ += ["charts", "sweep", "SWEEP_KEYS", "ODE_REFERENCED"]  # what a study, sweep, --plot use
