"""``acceleration``: time for a car to reach a target speed through its gears
(seed 000 §7.3, brief §2).

Lecture method (7.40)-(7.42): constant acceleration A·U_i/m - ψ in each gear, each
gear ending where the engine reaches ω_D: v_end = ω_D·r/(U_i·U_K), capped at the
target; t_i = Δv/(A·U_i/m - ψ); total = Σ t_i + shifts·t_shift. Its conventions (ψ
subtracted as an acceleration in m/s², weight taken as mass, A/m = 1.1 given) are
kept so that it reproduces the lecture's 17.49 s; the report says so.

Physical model: δ·m·dv/dt = F_t - ψ·m·g - k·v², k = ½·ρ·C_x·A, with
F_t = M_e(n)·U_i·U_K·η/r and n the engine speed the road speed gives in gear i,
the engine torque M_e from Leiderman's curve (the brief's reading of (7.37)) or a
table, δ_i = δ_0 + δ_e·U_i² unless given. Adhesion limits the tyre force on the
driven axle to φ·N (N with load transfer when the centre-of-gravity height is
given); then δ_0·m·dv/dt = φ·N - R, the engine's surplus spinning the engine and
driveline, and the acceleration is the lesser of the two. The launch
and any gear whose road speed is below the launch engine speed start with the
clutch slipping: the engine held at the launch speed passes its torque there, the
engine's inertia is not accelerated (δ_0). Upshift at the shift engine speed: for
t_shift no traction, resistances acting (closed form, :mod:`mdcalc.core.motion`).

Its files:

- ``engine.py``: The engine curve: torque against speed from a catalogue table or the external
  characteristic.
- ``case.py``: The case file of ``mdcalc acceleration``: pydantic sections in SI units, the
  engine speeds a case implies (launch, shift, rev limit, with their defaults), and the
  starter case.
- ``scene.py``: The scene: the car, its gears and resistances; traction, adhesion limit and
  acceleration in a gear.
- ``plan.py``: The plan: in which gears the car runs, and where it shifts up (the crossover
  of the accelerations).
- ``runs.py``: The runs through the gears and shifts: the lecture's method, piecewise closed
  forms, the ODE reference.
- ``kernel.py``: The vectorized kernel of sweeps and studies: the plan, the lecture and the
  ODE reference over a block of cars.
- ``solve.py``: The solver: the Methods, and the result.
- ``report.py``: The report: the sections an acceleration scene needs.
- ``charts.py``: The charts of ``--plot``: speed against time and the traction diagram (data
  only).
"""

from __future__ import annotations

from mdcalc.problems.acceleration.case import Case, starter_extras, template
from mdcalc.problems.acceleration.charts import charts
from mdcalc.problems.acceleration.kernel import ODE_REFERENCED, SWEEP_KEYS, sweep
from mdcalc.problems.acceleration.report import report
from mdcalc.problems.acceleration.solve import solve

__all__ = ["Case", "solve", "report", "template", "starter_extras"]
__all__ += ["charts", "sweep", "SWEEP_KEYS", "ODE_REFERENCED"]  # what a study, sweep, --plot use
