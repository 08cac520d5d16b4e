"""The vectorized kernel of ``mdcalc sweep`` and ``mdcalc study`` for a mechanism:
every numeric result of the scene over a block of scenes, its torque and inertia
formulas or tables (each row with its own parameters or table values).

The reference is the single scene's: the energy equation dE/dφ = M, dt/dφ = 1/ω
integrated by DOP853 at rtol 10⁻¹¹ with the same tolerances, start from rest and
floor (:func:`~.reference.reference`), here stepped for every row at once by
:func:`mdcalc.core.block_ode.dop853_block`. The speed fluctuation takes the extremes of
ω over the last revolution from DOP853's continuous extension (:mod:`~.extremes`),
sampled as closely as a bound on its curvature needs (no closer than the single
scene's grid) and refined by golden section. Kovylin's (5) runs as
:func:`~.kovylin.kovylin` does, node by node with each row's own halving, on the
same step formula.

A row the single scene would run otherwise is marked ``DECLINED``, to be solved
alone: a stiff scene (Radau), a stall, a formula that cannot be evaluated along the
run, more than the explicit budget of evaluations. With tables the reference runs
from knot to knot, as the single one does: every row's knots in one sorted array,
each row stepping through its own. Each piece goes on with the step the last one
proposed (the single scene starts each afresh), and with tables of both M and I (or
a constant I) its right-hand side is the piece's lines (:mod:`~.pieces`): the two
runs then take different steps and agree within their tolerance.
"""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass
from typing import Any

from mdcalc.core.units import rpm_to_rad_s
from mdcalc.input.expr import parse
from mdcalc.input.model import in_tiles, kernel_answer, value_at, with_values
from mdcalc.problems.mechanism.case import TWO_PI, VARIABLES, Case
from mdcalc.problems.mechanism.extremes import FLUCTUATION_KEYS, Extremes, speed
from mdcalc.problems.mechanism.kovylin import MAX_REFINEMENT, kovylin_step
from mdcalc.problems.mechanism.pieces import Lines, at_knots
from mdcalc.problems.mechanism.scene import (
    PeriodicRows,
    Scene,
    _central_slope,
    table_knots,
    two_way_rows,
)

#: Keys ``mdcalc sweep`` and ``mdcalc study`` may vary in the vectorized form; and
#: ``parameters.NAME`` for every parameter the case names.
SWEEP_KEYS = {
    "inertia.value": "I",
    "motion.start_angle": "φ₀",
    "motion.start_speed": "ω₀",
    "motion.start_speed_rpm": "ω₀",
    "motion.revolutions": "revolutions",
    "motion.steps_per_revolution": "n (Kovylin's)",
    "parameters.*": "a parameter of the formulas",
    "torque.values.N": "M at an angle of the table",
    "torque.values.N.N": "M at an angle and speed of the two-way table",
    "inertia.values.N": "I at an angle of the table",
}

#: The reference is an ODE run at rtol 10⁻¹¹ (DOP853, as the single scene's).
#: Without tables the kernel takes the single run's steps up to rounding (with them
#: each piece goes on with the proposed step), but where the error estimate
#: is itself at rounding level (a kink of M each revolution, as crank_press.toml's
#: max(sin φ, 0); E near zero before a stall) the two runs step differently and
#: differ by the reference's own error: measured 5.6·10⁻⁷ of ω against the exact
#: √(2(E₀ - c·2π)/I) in cases/extreme/mechanism_near_stall.toml, 2·10⁻⁷ on the
#: crank press. Kovylin's worst error is measured against that reference.
ODE_REFERENCED: dict[str, float | tuple[float, float]] = {
    key: 1e-6
    for key in (
        "final_speed",
        "final_time",
        "mean_speed",
        "max_speed",
        "min_speed",
        "mean_speed_revolution",
        "fluctuation",
    )
}
#: A relative error of ω measured against the reference: uncertain by the
#: reference's own error, 10⁻⁶ absolute (with 10⁻⁶ relative).
ODE_REFERENCED["kovylin_worst_error"] = (1e-6, 1e-6)

#: Kovylin's nodes × rows of a block at most (a node array of 32 MB), and rows at
#: most (the reference's arrays stay in the cache: 16 384 rows of
#: mechanism_inertia.toml run at 1.3x the rate of 65 536): a block of more rows runs
#: in parts.
NODE_CELLS = 4_000_000
TILE_ROWS = 16_384

KOVYLIN_KEYS = ("kovylin_final_speed", "kovylin_worst_error")


class _Formulas:
    """M(φ, ω) and I(φ) of a block: the case's formulas over arrays, each row with
    its own parameters (NaN where the single scene's formula would raise), or its
    tables, each row with its own values."""

    def __init__(self, case: Case, parameters: dict[str, Any], size: int) -> None:
        import numpy as np

        t, i = case.torque, case.inertia
        self.parameters, self.size = parameters, size
        self.inertia_value: Any = i.value
        self.torque = None if t.formula is None else parse(t.formula, VARIABLES, case.parameters)
        self.torque_arrays = None if self.torque is None else self.torque.on_arrays()
        self.inertia_formula = (
            None if i.formula is None else parse(i.formula, ("phi",), case.parameters).on_arrays()
        )
        self.depends = t.speeds is not None if self.torque is None else self.torque.uses("omega")
        self.case_speeds = None if t.speeds is None else list(t.speeds)
        self.torque_table: Any = None
        self.slope_table: Any = None
        self.inertia_table: Any = None
        if i.values is not None:
            angles = i.table_angles()
            assert angles is not None
            self.inertia_table = PeriodicRows(angles, list(i.values))
        if t.values is not None:
            angles = t.table_angles()
            assert angles is not None
            if t.speeds is None:
                table = PeriodicRows(angles, list(t.values))
                if self.inertia_table is not None:
                    table.share(self.inertia_table)
                self.torque_table = lambda rows, phi, omega: table(rows, phi)
            else:
                self.torque_table, self.slope_table = two_way_rows(
                    angles,
                    list(t.speeds),
                    [list(row) for row in t.values],  # type: ignore[arg-type]
                    self.inertia_table,
                )
        self.everyone = np.arange(size)

    def scene(self, rows: Any, base: Any) -> Scene:
        """The block's scene over the rows ``rows`` (None: all of them)."""
        import numpy as np

        own = {k: v if rows is None else v[rows] for k, v in self.parameters.items()}
        index = self.everyone if rows is None else rows

        def evaluate(run: Any, values: dict[str, Any]) -> Any:
            shape = np.broadcast_shapes(*(np.shape(v) for v in [*values.values(), *own.values()]))
            env = {**own, **values, "_bad": np.zeros(shape, dtype=bool)}
            out = np.broadcast_to(run(env), shape)
            return np.where(env["_bad"], np.nan, out)

        table, slope_table = self.torque_table, self.slope_table
        if table is None:

            def torque(phi: Any, omega: Any) -> Any:
                return evaluate(self.torque_arrays, {"phi": phi, "omega": omega})

        else:

            def torque(phi: Any, omega: Any) -> Any:
                return table(index, phi, omega)

        inertia_formula, inertia_table = self.inertia_formula, self.inertia_table
        if inertia_table is not None:

            def inertia(phi: Any) -> Any:
                return inertia_table(index, phi)

        elif inertia_formula is None:
            value = self.inertia_value
            constant = value if rows is None or np.ndim(value) == 0 else value[rows]

            def inertia(phi: Any) -> Any:
                return constant

        else:

            def inertia(phi: Any) -> Any:
                i = evaluate(inertia_formula, {"phi": phi})
                return np.where(i > 0.0, i, np.nan)

        if slope_table is not None:
            slope = lambda phi, omega: slope_table(index, phi, omega)  # noqa: E731
        else:
            slope = _central_slope(torque) if self.depends else (lambda phi, omega: 0.0)
        return Scene(
            torque,
            slope,
            inertia,
            self.depends,
            base.start_angle,
            base.start_speed,
            base.revolutions,
            base.steps,
            None,
            base.breaks,
        )


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result of the block's scenes (numpy), as the single scene's
    reference and Kovylin give them. None for a key this form does not know, or one
    that switches an alternative."""
    import numpy as np

    knots = table_knots(case)
    parameters: dict[str, Any] = {}
    others: dict[str, Any] = {}
    for key, column in grid.items():
        head, _, name = key.partition(".")
        pattern = ".".join("N" if p.isdigit() else p for p in key.split("."))
        if head == "parameters" and name in case.parameters:
            parameters[name] = np.asarray(column, dtype=float)
        elif pattern in SWEEP_KEYS and _number_at(case, key):
            others[key] = np.asarray(column, dtype=float)
        else:
            return None
    size = max([np.size(v) for v in grid.values()] + [1])
    c = with_values(case, others)
    motion = c.motion
    kovylin = wanted is None or bool(set(wanted) & set(KOVYLIN_KEYS))
    nodes = np.max(np.ceil(np.asarray(motion.revolutions * motion.steps_per_revolution))) + 1
    rows = min(max(1, int(NODE_CELLS // nodes)) if kovylin else size, TILE_ROWS)
    if size > rows:  # in parts that fit in memory and the cache; rows are independent
        return in_tiles(sweep, case, grid, wanted, rows)

    def spread(value: Any) -> Any:
        return np.array(np.broadcast_to(np.asarray(value, dtype=float), (size,)))

    parameters = {k: spread(v) for k, v in parameters.items()}
    start = spread(motion.start_angle)
    steps: Any = np.broadcast_to(np.asarray(motion.steps_per_revolution), (size,))
    # the block's numbers (arrays) in the single scene's fields; its functions come
    # from _Formulas.scene
    base = Scene(
        lambda phi, omega: 0.0,
        lambda phi, omega: 0.0,
        lambda phi: 1.0,
        False,
        start,
        spread(
            motion.start_speed
            if motion.start_speed is not None
            else rpm_to_rad_s(motion.start_speed_rpm)
        ),
        spread(motion.revolutions),
        steps,
        None,
        knots,
    )
    formulas = _Formulas(c, parameters, size)
    want = set(wanted) if wanted is not None else None
    with np.errstate(all="ignore"):
        fluctuation = want is None or bool(want & set(FLUCTUATION_KEYS))
        run = _reference(formulas, base, fluctuation, kovylin)
        values = run.values
        declined = run.declined
        if kovylin:
            speeds, failed = _kovylin(formulas, base)
            count, _ = _node_grid(base)
            final = speeds[count, np.arange(size)]
            values["kovylin_final_speed"] = np.where(failed, np.nan, final)
            ref = run.node_speeds
            error = np.where(
                ref > 0.0, np.abs(speeds - ref) / ref, np.where(np.isnan(ref), np.nan, 0.0)
            )
            worst = np.fmax.reduce(error, axis=0)
            values["kovylin_worst_error"] = np.where(failed, np.nan, worst)
    return kernel_answer(values, declined, size)


def _number_at(case: Case, key: str) -> bool:
    """The case holds a number at ``key``: a field it gives, or an entry of a table
    it has (not a whole row of a two-way table)."""
    value = value_at(case, key)
    return value is not None and not isinstance(value, list)


@dataclass
class _Run:
    values: dict[str, Any]
    declined: Any
    node_speeds: Any  # ω of the reference at Kovylin's nodes (nodes, rows), if asked


def _reference(formulas: _Formulas, base: Any, fluctuation: bool, nodes: bool) -> _Run:
    """The single scene's reference (:func:`~.reference.reference` with DOP853 at
    its rtol, and :func:`~.reference.stiffness_of`) over the block."""
    import numpy as np

    from mdcalc.core.block_ode import dop853_block
    from mdcalc.problems.mechanism.solve import EXPLICIT_BUDGET, REFERENCE_RTOL, STIFFNESS_LIMIT

    scene = formulas.scene(None, base)
    n = np.size(base.start_angle)
    phi0, omega0 = base.start_angle, base.start_speed
    span = base.revolutions * TWO_PI
    end = phi0 + span
    i0 = np.broadcast_to(scene.inertia(phi0), (n,))
    m0 = scene.torque(phi0, omega0)
    declined = ~np.isfinite(m0) | ~np.isfinite(i0)
    if scene.depends_on_speed:
        declined |= _stiffness(scene, base, i0, m0, span) > STIFFNESS_LIMIT
    e0 = 0.5 * i0 * omega0**2
    e_scale = np.maximum(np.maximum(e0, np.abs(m0) * span), 1e-300)
    # From rest E ≈ M₀·ε, t ≈ √(2·I₀·ε/M₀): start a hair after φ₀.
    rest = e0 == 0.0
    declined |= rest & ~(m0 > 0.0)
    eps = 1e-12 * span
    start = np.where(rest, phi0 + eps, phi0)
    e_start = np.where(rest, m0 * eps, e0)
    t_offset = np.where(rest, np.sqrt(2.0 * i0 * eps / m0), 0.0)
    floor = 1e-13 * e_scale
    bad = np.zeros(n, dtype=bool)

    def rhs(rows: Any, phi: Any, y: Any) -> Any:
        part = formulas.scene(rows, base)
        energy = np.maximum(y[:, 0], floor[rows])
        omega = np.sqrt(2.0 * energy / part.inertia(phi))
        torque = part.torque(phi, omega)
        bad[rows] |= ~np.isfinite(torque) | ~np.isfinite(omega)
        return np.stack([torque, 1.0 / omega], axis=1)

    def stop(step: Any) -> Any:  # E reaches the floor: a stall
        g_old = step.y_old[:, 0] - floor[step.rows]
        g_new = step.y_new[:, 0] - floor[step.rows]
        return (g_old >= 0.0) & (g_new <= 0.0)

    t_scale = span / np.maximum(omega0, np.sqrt(2.0 * e_scale / i0))
    atol = np.stack([e_scale, t_scale], axis=1) * REFERENCE_RTOL * 1e-3
    extremes = Extremes(formulas, base, end - TWO_PI, end, start) if fluctuation else None
    at_nodes = _Nodes(base, start, formulas) if nodes else None
    y0 = np.stack([e_start, t_offset], axis=1)
    live = ~declined
    y0 = np.where(live[:, None], y0, np.array([1.0, 0.0]))  # a harmless start, ignored

    def on_step(step: Any) -> None:
        if at_nodes is not None:
            at_nodes.see(step)
        if extremes is not None:
            extremes.see(step)

    # From knot to knot of the tables, as the single reference (one piece without)
    t, y = np.where(live, start, end), y0
    used = np.zeros(n, dtype=np.int64)
    moving = live.copy()
    knots, first, count = _knots(base.breaks, start, end)
    across = count < 0  # rows that run across their knots, in one piece
    count = np.maximum(count, 0)
    tables = formulas.torque_table is not None and formulas.inertia_formula is None
    lines = Lines(formulas, base, base.breaks) if tables and base.breaks else None
    moving &= ~_unfit_inertia(formulas, base, lines)
    proposal = np.ones(n)  # each piece goes on with the step the last one proposed
    for piece in range(int(np.max(count, initial=0)) + 1):
        inside = piece < count
        index = np.minimum(first + piece, len(knots) - 1)
        stage = np.where(inside, knots[index], end)
        groups: list[tuple[Any, Any]] = [(rhs, np.ones(n, dtype=bool))]
        if lines is not None:  # a row across its knots has no lines: rhs, alone
            groups = [(lines.piece(knots, index, t, floor), ~across), (rhs, across)]
        for f, members in groups:
            active = moving & members
            if not active.any():
                continue
            every = bool(active.all())  # no blends to make (the common case)
            out = dop853_block(
                f,
                t if every else np.where(active, t, stage),
                y if every else np.where(active[:, None], y, np.array([1.0, 0.0])),
                stage,
                rtol=REFERENCE_RTOL,
                atol=atol,
                stop=stop,
                on_step=on_step,
                budget=EXPLICIT_BUDGET - used,
                dense_counted=True,  # the single reference keeps its dense solution
                first_step=None if piece == 0 else proposal,
                quadratures=1,  # t is an integral: dE/dφ does not read it
            )
            if every:
                proposal, t, y, moving = out.step, out.t, out.y, out.done
                used += out.evaluations
                continue
            proposal = np.where(active, out.step, proposal)
            used += np.where(active, out.evaluations, 0)
            t, y = np.where(active, out.t, t), np.where(active[:, None], out.y, y)
            moving = np.where(active, out.done, moving)
    declined |= ~moving | bad
    e_end, t_end = y[:, 0], y[:, 1]
    final_speed = np.sqrt(2.0 * e_end / np.broadcast_to(scene.inertia(end), (n,)))
    values: dict[str, Any] = {
        "start_angle": phi0,
        "start_speed": omega0,
        "start_inertia": i0,
        "start_torque": m0,
        "end_angle": end,
        "steps_per_revolution": base.steps,
        "final_speed": final_speed,
        "final_time": t_end,
        "mean_speed": span / t_end,
    }
    if extremes is not None:
        values |= extremes.values(t_end)
        # a last turn's extreme that is not a number leaves the row to the single scene
        for key in ("max_speed", "min_speed"):
            declined |= extremes.has & ~np.isfinite(values[key])
    declined |= ~np.isfinite(final_speed) | ~np.isfinite(t_end)
    return _Run(values, declined, None if at_nodes is None else at_nodes.speeds)


#: A table of I whose least value is below this fraction of its largest is left to
#: the single scene: lines of I across a dip to nearly nothing lose its digits (a
#: drawn 10⁻¹⁴ kg·m² beside 2 gave ω_max 4·10⁻⁴ high; 10⁻¹⁶, NaN extremes).
INERTIA_SPAN = 1e-10


def _unfit_inertia(formulas: _Formulas, base: Any, lines: Lines | None) -> Any:
    """The rows whose table of I has a value at a knot below MAGNITUDE_FLOOR (the
    single scene's validation refuses it; drawn, ω is infinite there and 1/ω = 0, no
    NaN to stop the run) or below INERTIA_SPAN of its largest (the values at the
    knots are ``lines``', where there are lines)."""
    import numpy as np

    from mdcalc.input.model import MAGNITUDE_FLOOR

    n = np.size(base.start_angle)
    table = formulas.inertia_table
    if table is None:
        return np.zeros(n, dtype=bool)
    values = (
        at_knots(lambda phi: table(np.arange(n), phi), base.breaks, n)
        if lines is None
        else lines.inertia
    )
    low, high = values.min(axis=0), values.max(axis=0)
    return ~(low >= MAGNITUDE_FLOOR) | ~(low >= INERTIA_SPAN * high)


def _knots(breaks: tuple[float, ...], start: Any, end: Any) -> tuple[Any, Any, Any]:
    """:func:`~.reference.knots_between` of every row: the knots of all rows in
    order, and each row's first among them and its count (0 past MAX_SEGMENTS)."""
    import numpy as np

    from mdcalc.problems.mechanism.reference import MAX_SEGMENTS

    if not breaks:
        return np.zeros(1), np.zeros(np.shape(start), dtype=np.int64), np.zeros(np.shape(start))
    # from a turn before the first start: every piece has a knot below it
    turns = range(int(np.floor(np.min(start) / TWO_PI)) - 1, int(np.ceil(np.max(end) / TWO_PI)) + 2)
    knots = np.array([turn * TWO_PI + b for turn in turns for b in breaks])
    first = np.searchsorted(knots, start + 1e-12 * TWO_PI, side="right")
    count = np.searchsorted(knots, end - 1e-12 * TWO_PI, side="left") - first
    # past MAX_SEGMENTS a row runs across its knots, as the single reference
    return knots, first, np.where(count > MAX_SEGMENTS, -1, count)


def _stiffness(scene: Scene, base: Any, i0: Any, m0: Any, span: Any) -> Any:
    """:func:`~.reference.stiffness_of` over the block (NaN candidates skipped)."""
    import numpy as np

    gained = np.sqrt(2.0 * np.abs(m0) * span / i0)
    worst = np.zeros(np.shape(i0))
    for omega in (base.start_speed, 0.1 * gained, gained):
        c = scene.slope(base.start_angle, omega)
        ratio = np.abs(c) / (i0 * omega) * span
        worst = np.where((omega > 0.0) & np.isfinite(ratio), np.maximum(worst, ratio), worst)
    return worst


class _Nodes:
    """ω of the reference at Kovylin's nodes φ₀ + k·Δφ, from each step's extension."""

    def __init__(self, base: Any, start: Any, formulas: _Formulas) -> None:
        import numpy as np

        self.base, self.formulas, self.start = base, formulas, start
        self.count, self.dphi = _node_grid(base)
        self.speeds = np.full((int(self.count.max()) + 1, np.size(start)), np.nan)
        self.speeds[0] = base.start_speed
        self.next = np.ones(np.size(start), dtype=np.int64)

    def see(self, step: Any) -> None:
        import numpy as np

        rows, base = step.rows, self.base
        while True:
            k = self.next[rows]
            last = k == self.count[rows]
            angle = np.where(
                last,
                base.start_angle[rows] + base.revolutions[rows] * TWO_PI,
                base.start_angle[rows] + k * self.dphi[rows],
            )
            due = (k <= self.count[rows]) & (angle <= step.t_new)
            if not due.any():
                return
            # a node at the step's end (a table's knot, within rounding) is its end
            # point; one inside the step is read from the step's extension
            end = due & (np.abs(angle - step.t_new) <= 1e-12 * TWO_PI)
            at = np.flatnonzero(end)
            if at.size:
                r = rows[at]
                energy = np.maximum(step.y_new[at, 0], 0.0)
                inertia = self.formulas.scene(r, base).inertia(step.t_new[at])
                self.speeds[k[at], r] = np.sqrt(2.0 * energy / inertia)
            at = np.flatnonzero(due & ~end)
            if at.size:
                r = rows[at]
                self.speeds[k[at], r] = speed(
                    self.formulas, base, self.start, r, step.dense().take(at), angle[at]
                )
            self.next[rows[due]] += 1


def _node_grid(base: Any) -> tuple[Any, Any]:
    """Kovylin's node count over the run and its step, as :func:`~.kovylin.kovylin`."""
    import numpy as np

    count = np.maximum(1, np.ceil(base.revolutions * base.steps - 1e-9)).astype(np.int64)
    return count, base.revolutions * TWO_PI / count


def _kovylin(formulas: _Formulas, base: Any) -> tuple[Any, Any]:
    """ω at Kovylin's nodes by (5), each row stepping as :func:`~.kovylin._advance`
    does (a step halved where (5) cannot take it, grown back after); and the rows
    that stall (no step down to 2⁻³⁰ of Δφ)."""
    import numpy as np

    count, dphi = _node_grid(base)
    n = np.size(dphi)
    phi, omega = base.start_angle.copy(), base.start_speed.copy()
    speeds = np.full((int(count.max()) + 1, n), np.nan)
    speeds[0] = omega
    failed = np.zeros(n, dtype=bool)
    for k in range(int(count.max())):
        moving = (k < count) & ~failed
        end = phi + dphi
        h = dphi.copy()
        inner = moving.copy()
        while inner.any():
            rows = np.flatnonzero(inner)
            hh = np.minimum(h[rows], end[rows] - phi[rows])
            nxt = kovylin_step(formulas.scene(rows, base), phi[rows], omega[rows], hh)
            ok = np.isfinite(nxt)
            stall = ~ok & (hh < dphi[rows] * 2.0**-MAX_REFINEMENT)
            failed[rows[stall]] = True
            g, hg = rows[ok], hh[ok]
            phi[g] = np.where(end[g] - phi[g] > hg * (1 + 1e-12), phi[g] + hg, end[g])
            omega[g] = nxt[ok]
            h[g] = np.minimum(2.0 * hg, dphi[g])
            halve = ~ok & ~stall
            h[rows[halve]] = 0.5 * hh[halve]
            inner = moving & ~failed & (phi < end)
        phi = np.where(moving, end, phi)
        speeds[k + 1] = np.where(moving & ~failed, omega, np.nan)
    return speeds, failed
