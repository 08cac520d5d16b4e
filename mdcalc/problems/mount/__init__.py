"""``mount``: an engine on elastic mounts shaken by its crank (seed 000 §7.5,
example 9.1, brief §4).

Model (7.60): M·x'' + c_d·x' + c·x = m·r·ω²·(cos ωt + λ·cos 2ωt), the mounts' stiffness
c given or from the static deflection, c = G/f (7.50), so β = √(c/M) = √(g/f); c_d =
2·ζ·√(c·M) when a damping ratio is given. Each harmonic has its steady amplitude
(first harmonic at ω, second at 2ω: resonances at ω = β and ω = β/2; the lecture's
(7.74) prints 2·β for the second). The peak displacement is the largest |x| of the
two-harmonic sum over a revolution, found exactly (its extrema are the roots of a
trigonometric polynomial); the lecture's estimate m·r/M is its high-speed limit
without the second harmonic. All closed forms: no numpy, no scipy (but for the
vectorized sweep kernel and ``charts`` at the end, which import numpy when they run).

Its files:

- ``case.py``: The case file of ``mdcalc mount``: pydantic sections in SI units, and the
  starter case.
- ``scene.py``: The scene: the case reduced to SI numbers, the harmonic responses and the peak
  of their sum; floats, or numpy arrays over a sweep grid.
- ``solve.py``: The solver: the Methods for the peak displacement, and the result.
- ``report.py``: The report: the sections a mount scene needs.
- ``kernel.py``: The vectorized kernel of ``mdcalc sweep``: the scene formulas over a grid at once.
- ``charts.py``: The charts of ``--plot``: amplitudes and transmissibility against the crank
  speed (data only).
"""

from __future__ import annotations

from mdcalc.problems.mount.case import Case, starter_extras, template
from mdcalc.problems.mount.charts import charts
from mdcalc.problems.mount.kernel import sweep
from mdcalc.problems.mount.report import report
from mdcalc.problems.mount.scene import SWEEP_KEYS
from mdcalc.problems.mount.solve import solve

__all__ = ["Case", "solve", "report", "template", "starter_extras"]
__all__ += ["charts", "sweep", "SWEEP_KEYS"]  # what a study, sweep, --plot use
