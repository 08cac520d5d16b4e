"""``variator``: anti-resonance in an impulse-variator drive and the centrifugal
pendulum absorber (seed 000 §8.2–8.5, brief §7a–7g).

Each part is a section of the case file and appears in the report only when its
section is there:

* ``[absorber]`` (7a) -- disk J₁ on a shaft c to the ground, torque M₀·cos ωt,
  absorber disk J₂ on a shaft c_g (8.36): amplitudes (8.38), the tuning c_g = J₂ω²
  (8.39) that makes A₁ = 0, the two resonances of the tuned system (Δ = 0), the band
  where the absorber helps, A₁(ω) and A₂(ω); with damping b_g across the absorber
  shaft, the depth of the minimum.
* ``[motor]`` (7b) -- the induction motor as a spring-damper (8.40)–(8.41), slip
  relative to the synchronous speed, the seed's correction of the critical slip
  beside plain Kloss. Note c_D = 1/(T_D·ν·ω₀) = 2·P·M_K whatever the critical slip.
* ``[clutch]`` (7c) -- the loading curve M = c₀·ξⁿ (8.42), its lines over the
  working range (secant, least squares through the origin, chord) with their errors.
* ``[mechanism]`` (7d) -- the transfer functions (8.46) of one working stroke
  Δα = 2π/z and the check that the mean of Π′ is 1/i_c.
* ``[drive]`` (7e) -- the clutch deformation q of the two-mass model,
  J·q'' + b·q' + c·q = M_c + J·ω²·Π″(ωt), in its periodic state; χ = q_max/q_c (8.47).
* ``[antiresonance]`` (7f) -- an elastic coupling c₂ (b₂) and the machine J₃ behind
  a ratio i = ω₃/ω₂. Reduced to the variator's output shaft (J₃' = i²J₃, c₂' = i²c₂,
  b₂' = i²b₂) with q₂ the coupling's twist:
  J₂q₁'' + b₁q₁' + c₁q₁ - (c₂'q₂ + b₂'q₂') = J₂u,
  J₃'(q₁'' + q₂'') + c₂'q₂ + b₂'q₂' = M_c + J₃'u, u = ω²Π″.
  The clutch has no load at the frequency where J₂ and J₃' swing against each other
  on c₂ with the clutch at rest: c₂' = (zω)²·J₂J₃'/(J₂ + J₃'). The report compares
  χ before (J₃ rigid on the output shaft) and after.
* ``[pendulum]`` (7g) -- L = R/n², the mass (8.56), whether the bob fits on so
  short a pendulum, the detuning at the design swing, the bifilar alternative.

The periodic states come from :mod:`mdcalc.core.periodic` (closed form, Fourier
series and time integration, compared in the Methods tables).

Its files:

- ``case.py``: The case file of ``mdcalc variator``: pydantic sections in SI units, and the
  starter case.
- ``absorber.py``: 7a: the two-disk anti-resonance absorber (8.36)-(8.39): amplitudes by the seed's
  formulas and by the chain, the tuning, the depth of the minimum with damping.
- ``motor.py``: 7b: the induction motor as a spring-damper (8.40)-(8.41), Kloss and the seed's
  correction of the critical slip.
- ``clutch.py``: 7c: the clutch loading curve M = c₀·ξⁿ (8.42) and its lines over the working
  range.
- ``transfer.py``: 7d: the transfer functions (8.46) of one working stroke of the mechanism.
- ``drive.py``: 7e, 7f: the clutch deformation in the periodic state of the two-mass drive, χ
  (8.47), and the three-mass anti-resonance design.
- ``pendulum.py``: 7g: the centrifugal pendulum absorber: the arithmetic-geometric mean of its
  large-swing period.
- ``solve.py``: The solver: the parts the case has, their Methods, and the result.
- ``report.py``: The report: a section for each part the case has.
- ``kernel.py``: The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study``: every numeric
  result of every section over a block of scenes, by the functions the single scene
  runs.
- ``charts.py``: The charts of ``--plot``: absorber amplitudes, the clutch's loading
  curve and its lines, the transfer functions, the clutch load over a stroke, the
  anti-resonance design and the pendulum (data only).
"""

from __future__ import annotations

from mdcalc.problems.variator.case import Case, starter_extras, template
from mdcalc.problems.variator.charts import charts
from mdcalc.problems.variator.kernel import SWEEP_KEYS, sweep
from mdcalc.problems.variator.report import report
from mdcalc.problems.variator.solve import solve

__all__ = ["Case", "solve", "report", "template", "starter_extras"]
__all__ += ["charts", "sweep", "SWEEP_KEYS"]  # what a study, sweep, --plot use
