"""``mine-hoist``: dynamic factors in the ropes of a mine hoist with a head sheave,
a three-mass torsional chain (seed 002; brief §6).

Model: J₁ (motor, reducer, drum), J₂ (head sheave), J₃ (cage with load and its share
of the rope), all reduced to the drum axis; c₁₂ the rope chord from drum to sheave,
c₂₃ the vertical rope from sheave to cage. The drive torque M₁ and the load torque
W (resisting) are applied suddenly to the chain at rest with unloaded ropes. The
rope moments M₁₂ = c₁₂(φ₁ - φ₂), M₂₃ = c₂₃(φ₂ - φ₃) obey seed (6); their static
parts R₁₂, R₂₃ are (11)-(12) with M₃ = -W; μ = M/R are the dynamic factors.

* Exact modal solution (:mod:`mdcalc.core.chain`): μ(t) = 1 + Σ bⱼ·cos(βⱼt), the
  maximum in the first swing (t ≤ 2π/β₁), over a horizon, and the undamped supremum
  1 + Σ|bⱼ|.
* The seed's simplified formulas (19)-(20), read by meaning: the seed's labels of the
  two modes are swapped between (17) and (18). (19) is 2 + b₁₂(fast), i.e. the slow
  swing alone; (20) is 1 + (R₁₂/R₂₃)(J₂/c₁₂)(β₁₂² - β_slow²), i.e. B₁₂(slow) ≈ -R₁₂.
* ODE runs of (6), explicit (DOP853) and implicit (Radau) at three tolerances.
* Optional rope-mass reduction (2)-(5) and a height sweep (the seed's Table 1).

Its files:

- ``case.py``: The case file of ``mdcalc mine-hoist``: pydantic sections in SI units, and the
  starter case.
- ``scene.py``: The scene: the rope reduced to two springs, the three-mass chain at a height.
- ``modal.py``: The modal solution of the chain (the reference): modes, the first-swing
  dynamic factors, the seed formula and the simplified factors.
- ``ode_rows.py``: The ODE rows of the Methods table: their evaluation budget and the runs.
- ``solve.py``: The solver: the Methods, the height sweep, and the result.
- ``report.py``: The report: the sections a mine-hoist scene needs.
- ``kernel.py``: The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study``: every
  numeric result over a block of scenes, by the functions the single scene runs on a
  block of one.
- ``charts.py``: The charts of ``--plot``: the dynamic factors against time, and over the
  height sweep (data only).
"""

from __future__ import annotations

from mdcalc.problems.mine_hoist.case import Case, starter_extras, template
from mdcalc.problems.mine_hoist.charts import charts
from mdcalc.problems.mine_hoist.kernel import SWEEP_KEYS, sweep
from mdcalc.problems.mine_hoist.report import report
from mdcalc.problems.mine_hoist.solve import solve

__all__ = ["Case", "solve", "report", "template", "starter_extras"]
__all__ += ["charts", "sweep", "SWEEP_KEYS"]  # what a study, sweep, --plot use
