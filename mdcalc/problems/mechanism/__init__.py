"""``mechanism``: motion of a one-degree-of-freedom mechanism under a torque that
depends on position and speed, by Kovylin's linearization (seed 001, brief §8).

Given the reduced torque M(φ, ω) and the reduced inertia I(φ), and ω = ω₀ at φ₀,
find ω(φ). Over a step from φ_i to φ_k the energy balance (1)
I_k·ω_k²/2 - I_i·ω_i²/2 = ∫M dφ, with ω_k² ≈ ω_i² + 2ω_iΔω (3) and M linearized
in ω (4), gives Kovylin's step (5):

    Δω = [2·M′·Δφ + (I_i - I_k)·ω_i²] / [2·I_k·ω_i - C·Δφ],
    M′ = ½[M(φ_i, ω_i) + M(φ_k, ω_i)],  C = ∂M/∂ω at (φ_k, ω_i).

From rest (ω_i = 0) (5) is undefined; the step then solves (1) with the same
linearized torque without (3): I_k·ω_k² - C·Δφ·ω_k - 2·M′·Δφ = 0. A step whose
denominator is not positive, whose ω_k is not positive or whose increment is more
than half of ω_i is halved (the seed: "refine the step"), down to 2⁻³⁰ of it.

The reference integrates the energy E = I·ω²/2 over the angle, dE/dφ = M(φ, ω),
ω = √(2E/I(φ)), and the time dt/dφ = 1/ω: no derivative of I is needed, and the
mechanism stalls where E reaches zero (exit 3 with the angle and the time).
M and I come as formulas (:mod:`mdcalc.input.expr`, never ``eval``) or as tables over
one revolution, interpolated linearly and periodically; M may be tabulated over
angle and speed.

Its files:

- ``case.py``: The case file of ``mdcalc mechanism``: pydantic sections in SI units, and the
  starter case.
- ``scene.py``: The scene: the reduced inertia and the torque M(φ, ω) from the case (formulas
  or tables, repeated over a period), with the torque's slope in ω.
- ``kovylin.py``: Kovylin's linearized step (seed 001) and the energy step: the path over the angle.
- ``reference.py``: The ODE reference: the energy equation integrated over the angle, with a
  budget and a dense solution.
- ``fluctuation.py``: The speed fluctuation over a period: coefficient of unevenness, extremes.
- ``kernel.py``: The vectorized kernel of sweeps and studies: the reference, the
  fluctuation and Kovylin's (5) over a block of scenes.
- ``pieces.py``: The right-hand side of a mechanism's block on one piece between the tables'
  knots: there I and every speed column of M are straight lines.
- ``extremes.py``: The extremes of ω over a mechanism block's last revolution, from the
  reference's steps, kept as they are taken and sampled where they can hold one.
- ``solve.py``: The solver: the Methods, and the result.
- ``report.py``: The report: the sections a mechanism scene needs.
- ``charts.py``: The charts of ``--plot``: speed and torque against the angle (data only).
"""

from __future__ import annotations

from mdcalc.problems.mechanism.case import Case, starter_extras, template
from mdcalc.problems.mechanism.charts import charts
from mdcalc.problems.mechanism.kernel import ODE_REFERENCED, SWEEP_KEYS, sweep
from mdcalc.problems.mechanism.report import report
from mdcalc.problems.mechanism.solve import solve

__all__ = ["Case", "solve", "report", "template", "starter_extras"]
__all__ += ["charts", "sweep", "SWEEP_KEYS", "ODE_REFERENCED"]  # what a study, sweep, --plot use
