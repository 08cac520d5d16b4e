"""The scene: the reduced inertia and the torque M(φ, ω) from the case (formulas
or tables, repeated over a period), with the torque's slope in ω."""

from __future__ import annotations

import bisect
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from mdcalc.core.xp import of
from mdcalc.input.expr import parse
from mdcalc.problems.mechanism.case import TWO_PI, VARIABLES, Case, _flat, _start_speed


class Periodic:
    """Linear interpolation of a table over one revolution, repeated every 2π."""

    def __init__(self, angles: list[float], values: list[float]) -> None:
        if angles[-1] - angles[0] >= TWO_PI * (1.0 - 1e-12):  # a closing point: drop it
            angles, values = angles[:-1], values[:-1]
        self.start = angles[0]
        self.angles = [*angles, angles[0] + TWO_PI]
        self.values = [*values, values[0]]

    def __call__(self, phi: float) -> float:
        x = self.start + (phi - self.start) % TWO_PI
        k = min(max(bisect.bisect_right(self.angles, x) - 1, 0), len(self.angles) - 2)
        a0, a1 = self.angles[k], self.angles[k + 1]
        w = (x - a0) / (a1 - a0)
        return self.values[k] + w * (self.values[k + 1] - self.values[k])


@dataclass(frozen=True)
class Scene:
    """One scene (floats), or a block of them (the kernel's: the functions take and
    give arrays, NaN where a formula cannot be evaluated)."""

    torque: Callable[[Any, Any], Any]  # M(φ, ω) [N·m]
    slope: Callable[[Any, Any], Any]  # ∂M/∂ω [N·m·s/rad]
    inertia: Callable[[Any], Any]  # I(φ) [kg·m²]
    depends_on_speed: bool
    start_angle: float
    start_speed: float
    revolutions: float
    steps: int  # per revolution
    speed_range: tuple[float, float] | None  # of a two-way table
    breaks: tuple[float, ...] = ()  # table knots in [0, 2π): kinks of M or I

    @property
    def span(self) -> float:
        return self.revolutions * TWO_PI

    @property
    def end_angle(self) -> float:
        return self.start_angle + self.span


def _central_slope(torque: Callable[[Any, Any], Any]) -> Callable[[Any, Any], Any]:
    """∂M/∂ω by a central difference (forward at rest: ω < 0 may be outside M's
    domain); floats or arrays."""

    def slope(phi: Any, omega: Any) -> Any:
        xp = of(phi, omega)
        h = 1e-6 * xp.maximum(xp.abs(omega), 1e-3)
        return xp.where(
            omega - h < 0.0,
            lambda: (torque(phi, omega + h) - torque(phi, omega)) / h,
            lambda: (torque(phi, omega + h) - torque(phi, omega - h)) / (2.0 * h),
        )

    return slope


def scene_of(case: Case) -> Scene:
    t, i = case.torque, case.inertia
    speed_range: tuple[float, float] | None = None
    torque: Callable[[float, float], float]
    slope: Callable[[float, float], float]
    if t.formula is not None:
        m = parse(t.formula, VARIABLES, case.parameters)
        depends = m.uses("omega")

        def torque(phi: float, omega: float) -> float:
            return m(phi=phi, omega=omega)

        slope = _central_slope(torque) if depends else (lambda phi, omega: 0.0)
    else:
        angles = t.table_angles()
        assert angles is not None and t.values is not None
        if t.speeds is None:
            table = Periodic(angles, [float(v) for v in _flat(t.values)])
            depends = False

            def torque(phi: float, omega: float) -> float:
                return table(phi)

            slope = lambda phi, omega: 0.0  # noqa: E731
        else:
            torque, slope = _two_way(angles, list(t.speeds), t.values)  # type: ignore[arg-type]
            depends = True
            speed_range = (t.speeds[0], t.speeds[-1])
    inertia: Callable[[float], float]
    if i.value is not None:
        constant = i.value
        inertia = lambda phi: constant  # noqa: E731
    elif i.formula is not None:
        expression = parse(i.formula, ("phi",), case.parameters)

        def inertia(phi: float) -> float:
            value = expression(phi=phi)
            if not value > 0.0:
                raise ArithmeticError(f"I(φ) = {value:.6g} kg·m² at φ = {phi:.6g} rad")
            return value

    else:
        angles = i.table_angles()
        assert angles is not None and i.values is not None
        inertia = Periodic(angles, list(i.values))
    motion = case.motion
    return Scene(
        torque,
        slope,
        inertia,
        depends,
        motion.start_angle,
        _start_speed(motion),
        motion.revolutions,
        motion.steps_per_revolution,
        speed_range,
        table_knots(case),
    )


def table_knots(case: Case) -> tuple[float, ...]:
    """The tables' knots in [0, 2π), in order: kinks of M or I."""
    knots: set[float] = set()
    for section in (case.torque, case.inertia):
        angles = section.table_angles()
        if angles is not None:
            knots.update(a % TWO_PI for a in angles)
    return tuple(sorted(knots))


def _two_way(
    angles: list[float], speeds: list[float], rows: list[list[float]]
) -> tuple[Callable[[float, float], float], Callable[[float, float], float]]:
    """M(φ, ω) bilinear in the table, periodic in φ, linear beyond the speed range."""
    columns = [Periodic(angles, [row[j] for row in rows]) for j in range(len(speeds))]

    def cell(omega: float) -> int:
        return min(max(bisect.bisect_right(speeds, omega) - 1, 0), len(speeds) - 2)

    def torque(phi: float, omega: float) -> float:
        j = cell(omega)
        m0, m1 = columns[j](phi), columns[j + 1](phi)
        return m0 + (omega - speeds[j]) / (speeds[j + 1] - speeds[j]) * (m1 - m0)

    def slope(phi: float, omega: float) -> float:
        j = cell(omega)
        return (columns[j + 1](phi) - columns[j](phi)) / (speeds[j + 1] - speeds[j])

    return torque, slope


class PeriodicRows:
    """:class:`Periodic` over a block: the angles shared, the values the case's (one
    per angle, or a list per angle: a two-way table's speeds), an entry a study
    draws an array over the block's rows; called with the rows (m,) and angles (m,)
    or (k, m). The table is kept once and the drawn entries beside it, so a block
    costs the table plus its drawn columns. The same cell and the same interpolation
    as one table's: a row's value is its single table's, bit for bit."""

    def __init__(self, angles: list[float], values: list[Any]) -> None:
        import numpy as np

        if angles[-1] - angles[0] >= TWO_PI * (1.0 - 1e-12):  # a closing point: drop it
            angles, values = angles[:-1], values[:-1]
        values = [*values, values[0]]  # the wrap to the first angle, a turn on
        self.start = angles[0]
        self.angles = np.array([*angles, angles[0] + TWO_PI])
        self.drawn: dict[tuple[int, ...], Any] = {}
        entries = [row if isinstance(row, list) else [row] for row in values]
        base = np.zeros((len(entries), len(entries[0])))
        for k, row in enumerate(entries):
            for s, value in enumerate(row):
                if np.ndim(value):
                    self.drawn[(k, s)] = np.asarray(value, dtype=float)
                else:
                    base[k, s] = value
        self.base = base if isinstance(values[0], list) else base[:, 0]
        #: The two arrays of angles last located (the arrays themselves) and their
        #: cells and weights, the latest first.
        self._last: list[Any] = [None, None, None, None]

    def locate(self, phi: Any) -> tuple[Any, Any]:
        """The cell k of each angle and the weight w of its right end. The last two
        arrays of angles asked and their cells are kept: M and I of one right-hand
        side are read at the same angles, Kovylin's step at two, from tables that may
        share theirs (:meth:`share`)."""
        import numpy as np

        last = self._last
        if phi is last[0]:
            return last[1]
        if phi is last[2]:
            return last[3]
        x = self.start + (phi - self.start) % TWO_PI
        top = len(self.angles) - 2
        k = np.minimum(np.maximum(np.searchsorted(self.angles, x, side="right") - 1, 0), top)
        a0, a1 = self.angles[k], self.angles[k + 1]
        found = k, (x - a0) / (a1 - a0)
        last[2], last[3] = last[0], last[1]
        last[0], last[1] = phi, found
        return found

    def share(self, other: PeriodicRows) -> None:
        """Locate angles with ``other``'s memory of the last ones, where the two
        tables have the same angles (a cell and weight are the angles' alone)."""
        if self.start == other.start and list(self.angles) == list(other.angles):
            self._last = other._last

    def value(self, rows: Any, k: Any, column: Any = None) -> Any:
        """The table's entry at angle k (and speed ``column``) of each row."""
        import numpy as np

        out = self.base[k] if column is None else self.base[k, column]
        for (at, speed), drawn in self.drawn.items():
            hit = k == at if column is None else (k == at) & (column == speed)
            if np.any(hit):
                out = np.where(hit, drawn[rows], out)
        return out

    def __call__(self, rows: Any, phi: Any) -> Any:
        k, w = self.locate(phi)
        v0, v1 = self.value(rows, k), self.value(rows, k + 1)
        return v0 + w * (v1 - v0)


def two_way_rows(
    angles: list[float],
    speeds: list[float],
    values: list[list[Any]],
    share: PeriodicRows | None = None,
) -> tuple[Callable[[Any, Any, Any], Any], Callable[[Any, Any, Any], Any]]:
    """:func:`_two_way` over a block (the values a list of rows, one per angle, an
    entry a study draws an array over the block): M and ∂M/∂ω of the rows (m,) at φ
    and ω ((m,) or (k, m)); its angles located with ``share``'s where they are the
    same (:meth:`PeriodicRows.share`)."""
    import numpy as np

    table = PeriodicRows(angles, values)
    if share is not None:
        table.share(share)
    grid = np.array(speeds)

    def columns(rows: Any, phi: Any, omega: Any) -> tuple[Any, Any, Any]:
        """The cell j of ω, and M of the columns j and j + 1 at φ."""
        j = speed_cell(grid, omega)
        k, w = table.locate(phi)
        ends = []
        for column in (j, j + 1):
            v0, v1 = table.value(rows, k, column), table.value(rows, k + 1, column)
            ends.append(v0 + w * (v1 - v0))
        return j, ends[0], ends[1]

    def torque(rows: Any, phi: Any, omega: Any) -> Any:
        return across_speeds(grid, omega, *columns(rows, phi, omega))

    def slope(rows: Any, phi: Any, omega: Any) -> Any:
        j, m0, m1 = columns(rows, phi, omega)
        return (m1 - m0) / (grid[j + 1] - grid[j])

    return torque, slope


def speed_cell(grid: Any, omega: Any) -> Any:
    """The cell j of ω among a two-way table's speeds ``grid`` (arrays): the
    first or last beyond them (0 for two speeds: one cell, extrapolated)."""
    import numpy as np

    last = len(grid) - 2
    if last == 0:
        return 0
    return np.minimum(np.maximum(np.searchsorted(grid, omega, side="right") - 1, 0), last)


def across_speeds(grid: Any, omega: Any, j: Any, m0: Any, m1: Any) -> Any:
    """M at ω from the columns j and j + 1 of the cell, M there m0 and m1."""
    return m0 + (omega - grid[j]) / (grid[j + 1] - grid[j]) * (m1 - m0)
