"""``hoist``: hoist motor and brake (seed 000 §7.2) and rope loads at start (§7.6).

Steady lifting: η = Π η_i, N_p = G·V, N_d = N_p/η (7.24), static torque on the motor
shaft M_c = G·V/(ω1·η) (7.26), brake torque K_t·M_c (7.27); lowering, the load
drives the train and M_c,low = G·V·η/ω1.

Start: reduced inertia by kinetic energy J = J1 + Σ J_k(ω_k/ω1)² + m(V/ω1)² (7.30) or
the estimate (1.1…1.2)·J1 (7.31); uniform acceleration ω1/t_p (7.32); starting
torque M_c + J·ω1/t_p (7.28), or t_p = J·ω1/(M_start - M_c) from a catalogue torque.

Rope (two-mass model on the rope line): drive mass m1 (drive inertia reduced to the
load's motion), rope stiffness c, load m2 = G/g. The drive force is G + (m1+m2)·V/t_p
during the start and G after it. The load either hangs on the rope (closed form
(7.92)-(7.96), exact for this model) or lies on the ground with the rope slack
(7.97)-(7.98); for the latter a tight ODE run with lift-off and touch-down events is
the reference.

``--plot``: the rope dynamic factor against time from the exact piecewise solution
of the same model (:func:`rope_history`), load hanging and load on the ground.

Its files:

- ``case.py``: The case file of ``mdcalc hoist``: pydantic sections in SI units, and the
  starter case.
- ``drive.py``: The drive: steady lifting and lowering (7.24)-(7.27), the reduced inertia
  (7.30)-(7.31) and the start (7.28)-(7.32); floats, or numpy arrays over a sweep grid.
- ``rope.py``: The rope at start: the two-mass model, its closed forms (7.92)-(7.98), the ODE
  reference with lift-off and touch-down.
- ``solve.py``: The solver: the Methods, and the result.
- ``report.py``: The report: the sections a hoist scene needs.
- ``kernel.py``: The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study``: the drive
  formulas and the rope's closed forms over a grid at once.
- ``history.py``: the exact piecewise solution of the rope model (the rope history
  and its peak), drawn by the charts.
- ``charts.py``: The charts of ``--plot``: the rope dynamic factor against time from the exact
  piecewise solution of the rope model (data only).
"""

from __future__ import annotations

from mdcalc.problems.hoist.case import Case, starter_extras, template
from mdcalc.problems.hoist.charts import charts
from mdcalc.problems.hoist.kernel import ODE_REFERENCED, SWEEP_KEYS, sweep
from mdcalc.problems.hoist.report import report
from mdcalc.problems.hoist.solve import solve

__all__ = ["Case", "solve", "report", "template", "starter_extras"]
__all__ += ["charts", "sweep", "SWEEP_KEYS", "ODE_REFERENCED"]  # what a study, sweep, --plot use
