"""``mdcalc sweep``: one case over a grid of parameter values.

``--vary KEY=START:STOP:N`` makes N evenly spaced values of a dotted key of the case
file (``vehicle.mass``, ``driver.reaction_time``); several ``--vary`` make the full
grid. A problem module with a ``sweep(case, grid)`` function evaluates the whole
grid at once with numpy (closed forms); otherwise every point is validated, solved
and reported like a case file of its own, in the process pool of ``mdcalc run``.

Pure logic: the CLI parses the options, shows progress and writes the file.
"""

from __future__ import annotations

import copy
import math
import re
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from itertools import product
from pathlib import Path
from typing import Any

from mdcalc.core.budget import DEFAULT_SECONDS
from mdcalc.errors import EXIT_BUG, EXIT_INPUT, EXIT_NO_ANSWER, EXIT_OK, InputError, Problem
from mdcalc.input.casefile import (  # get_key, set_key: the sweep's and the study's
    CaseText,
    get_key,
    is_integer_field,
    missing_name,
    read_case,
    set_key,
    unit_of,
    validate,
)
from mdcalc.input.model import DECLINED
from mdcalc.output.report import JSON_FORMAT, Report, ascii_unit
from mdcalc.runs.cluster import PoolMapper
from mdcalc.runs.kernel import BLOCK
from mdcalc.runs.runner import problem_of, solve_model

#: A grid larger than this is refused: 10⁷ points of a vectorized problem take
#: about 1 GB of columns; of a per-point problem, hours.
MAX_POINTS = 10_000_000

_VARY = re.compile(r"^\s*([A-Za-z0-9_.\-]+)\s*=\s*([^:]+):([^:]+):([^:]+)\s*$")


@dataclass(frozen=True)
class Vary:
    key: str  # dotted path in the case file
    start: float
    stop: float
    count: int
    #: The values themselves, where they were listed (from Python) and not spaced.
    listed: tuple[float, ...] | None = None

    @property
    def loc(self) -> tuple[str | int, ...]:
        return tuple(int(p) if p.isdigit() else p for p in self.key.split("."))

    def values(self) -> list[float]:
        if self.listed is not None:
            return list(self.listed)
        if self.count == 1:
            return [self.start]
        step = (self.stop - self.start) / (self.count - 1)
        return [self.start + i * step for i in range(self.count - 1)] + [self.stop]


def parse_vary(text: str) -> Vary:
    """``KEY=START:STOP:N`` -> :class:`Vary`; :class:`InputError` naming the option."""
    where = f"--vary {text}"
    match = _VARY.match(text)
    if match is None:
        raise InputError(
            where, [Problem("expected KEY=START:STOP:N, e.g. vehicle.mass=800:3000:12")]
        )
    key, start_text, stop_text, count_text = match.groups()
    try:
        start, stop = float(start_text), float(stop_text)
    except ValueError:
        raise InputError(where, [Problem("START and STOP must be numbers")]) from None
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise InputError(where, [Problem("START and STOP must be finite")])
    try:
        count = int(count_text)
    except ValueError:
        raise InputError(where, [Problem("N must be a whole number of points")]) from None
    if count < 1:
        raise InputError(where, [Problem(f"N = {count}; need at least one point")])
    if count > MAX_POINTS:
        raise InputError(where, [Problem(f"N = {count:,}; the limit is {MAX_POINTS:,} points")])
    return Vary(key, start, stop, count)


# ------------------------------------------------------------------------- the grid


@dataclass
class Plan:
    """A validated sweep: the base case, the varied keys and their values."""

    case: CaseText
    problem: str
    varies: list[Vary]
    axes: list[list[float | int]]  # the values of each varied key (ints where the key is)

    @property
    def points(self) -> int:
        return math.prod(len(a) for a in self.axes)

    def grid(self) -> Iterator[tuple[float | int, ...]]:
        """Every point of the grid; the last key varies fastest."""
        return product(*self.axes)

    def data_at(self, point: Sequence[float | int]) -> dict[str, Any]:
        data = copy.deepcopy(self.case.data)
        data.pop("expect", None)
        for vary, value in zip(self.varies, point, strict=True):
            set_key(data, vary.loc, value)
        return data


def plan(path: Path | CaseText, varies: Sequence[Vary]) -> Plan:
    """Read the case, check the keys, and validate the corners of the grid.

    Field bounds are checked at every corner (2^k of them), so a grid whose ends are
    valid is valid along its axes; a cross-field rule broken inside the grid shows up
    as an invalid point.
    """
    case = read_case(path) if isinstance(path, Path) else path  # (a text from Python)
    path = case.path
    spec = problem_of(case)
    module = spec.load()
    validate(module.Case, case)  # the base case itself
    if not varies:
        raise InputError(path, [Problem("nothing to vary: give --vary KEY=START:STOP:N")])
    keys = [v.key for v in varies]
    if len(set(keys)) != len(keys):
        raise InputError(path, [Problem(f"a key is varied twice: {', '.join(keys)}")])
    points = math.prod(v.count for v in varies)
    if points > MAX_POINTS:  # before any value list is built
        raise InputError(path, [Problem(f"{points:,} points; the limit is {MAX_POINTS:,}")])
    axes: list[list[float | int]] = []
    for vary in varies:
        base = get_key(case.data, vary.loc)
        quantity = any(c.loc == vary.loc for c in case.conversions)  # "52.5 N*m/deg"
        if (
            isinstance(base, bool)
            or isinstance(base, dict | list)
            or (isinstance(base, str) and not quantity)
        ):
            raise InputError(
                f"--vary {vary.key}", [Problem(f"{vary.key} is not a number in {path}")]
            )
        unknown = missing_name(module.Case, case.data, vary.loc)
        if unknown is not None:
            raise InputError(f"--vary {vary.key}", [Problem(unknown)])
        values: list[float | int] = list(vary.values())
        if is_integer_field(module.Case, vary.loc):
            rounded: list[float | int] = [round(v) for v in values]
            if any(
                abs(v - r) > 1e-9 * max(1.0, abs(v)) for v, r in zip(values, rounded, strict=True)
            ):
                raise InputError(
                    f"--vary {vary.key}",
                    [Problem("the key is an integer; choose START:STOP:N with whole steps")],
                )
            values = list(rounded)
        axes.append(values)
    result = Plan(case, spec.name, list(varies), axes)
    corners = product(*[(a[0], a[-1]) for a in axes]) if len(axes) <= 12 else iter(())
    for corner in corners:
        try:
            data = result.data_at(corner)
            set_text = CaseText(path, case.text, data)
            validate(module.Case, set_text)
        except KeyError as missing:
            at = ", ".join(v.key for v in varies)
            raise InputError(
                path, [Problem(f"no place for {missing} in this case (--vary {at})")]
            ) from None
        except InputError as exc:
            at = ", ".join(f"{v.key} = {c:g}" for v, c in zip(varies, corner, strict=True))
            for p in exc.problems:
                p.message += f" (at the grid corner {at})"
            raise
    return result


# ------------------------------------------------------------------------- evaluation


@dataclass
class Table:
    """The sweep's result: one row per grid point, in grid order."""

    keys: list[str]  # the varied keys, then the results
    units: dict[str, str]
    columns: dict[str, Any]  # key -> numpy array (float; NaN where a point has no value)
    status: Any  # numpy array of exit codes per point
    messages: list[str] = field(default_factory=list)
    vectorized: bool = False

    @property
    def exit_code(self) -> int:
        import numpy as np

        for code in (EXIT_BUG, EXIT_INPUT, EXIT_NO_ANSWER):
            if np.any(self.status == code):
                return code
        return EXIT_OK


def _numeric(report: Any) -> dict[str, tuple[float, str]]:
    return {
        key: (q.value, q.unit)
        for key, q in report.results().items()
        if isinstance(q.value, int | float) and not isinstance(q.value, bool)
    }


def point_results(
    args: tuple[str, str, dict[str, Any], float | None] | tuple[str, str, dict, Any, bool],
) -> tuple[int, dict[str, Any], str]:
    """One grid point as a case of its own, under its time limit: (exit code,
    {key: value}, message). A fifth item True runs each Methods table's reference
    alone (:func:`reference_only_fits` said the wanted results do not need more)."""
    from mdcalc import methods
    from mdcalc.problems import PROBLEMS

    methods.MIN_TIMING_SECONDS = 2e-4  # as in batch runs: the timings are not kept
    path, problem, data, time_limit = args[:4]
    module = PROBLEMS[problem].load()
    try:
        model = validate(module.Case, CaseText(Path(path), "", data))
        _, report = _solved(problem, module, model, time_limit, len(args) > 4 and bool(args[4]))
    except InputError as exc:
        return EXIT_INPUT, {}, "; ".join(p.format(path) for p in exc.problems)
    except ArithmeticError as exc:  # validation computing with a value like 5e-324
        return EXIT_NO_ANSWER, {}, f"no answer: {type(exc).__name__}: {exc}"
    except Exception as exc:
        return EXIT_BUG, {}, f"internal error: {type(exc).__name__}: {exc}"
    values = {key: value for key, (value, _) in _numeric(report).items()}
    if report.status != "ok":
        return EXIT_NO_ANSWER, values, report.message or "no answer"
    return EXIT_OK, values, ""


def _solved(problem: str, module: Any, model: Any, time_limit: Any, alone: bool) -> Any:
    from mdcalc import methods

    before, methods.REFERENCE_ONLY = methods.REFERENCE_ONLY, alone
    try:
        return solve_model(problem, module, model, time_limit)
    finally:
        methods.REFERENCE_ONLY = before


def reference_only_fits(
    problem: str, module: Any, model: Any, wanted: Sequence[str], time_limit: float | None
) -> bool:
    """Do the ``wanted`` results come out the same when every Methods table runs its
    reference alone? Tried on the base scene, both ways: a result taken from another
    method's run (mechanism's Kovylin path) is missing then, and the samples run
    every method."""
    try:
        _, full = _solved(problem, module, model, time_limit, False)
        _, alone = _solved(problem, module, model, time_limit, True)
    except Exception:
        return False
    a, b = _numeric(full), _numeric(alone)
    return all(k in a and k in b and a[k][0] == b[k][0] for k in wanted)


def choose_results(
    sweep: Plan, results: Sequence[str], time_limit: float | None = DEFAULT_SECONDS
) -> tuple[list[str], dict[str, str]]:
    """The result columns and their units, from a run of the base case
    (:func:`key_results`)."""
    module = _module(sweep.problem)
    model = validate(module.Case, sweep.case)
    return key_results(sweep.problem, module, model, results, "--result", time_limit)


def key_results(
    problem: str,
    module: Any,
    model: Any,
    results: Sequence[str],
    where: str,
    time_limit: float | None = DEFAULT_SECONDS,
    report: Report | None = None,
) -> tuple[list[str], dict[str, str]]:
    """The result keys and the units of every numeric result, from a run of the base
    scene (or its ``report``, where it has run). By default the key results: the
    quantities of the report's Methods tables (all numeric results where it has
    none). Asked-for ``results`` must be numeric results (else :class:`InputError` at
    ``where``)."""
    from mdcalc.output.report import MethodsTable

    if report is None:
        _, report = solve_model(problem, module, model, time_limit)
    numeric = _numeric(report)
    units = {key: unit for key, (_, unit) in numeric.items()}
    unknown = [k for k in results if k not in numeric]
    if unknown:
        raise InputError(
            where,
            [
                Problem(f"no numeric result {k!r}; this case has: {', '.join(numeric)}")
                for k in unknown
            ],
        )
    if results:
        return list(results), units
    keys: list[str] = []
    for section in report.sections:
        if isinstance(section, MethodsTable):
            keys += [q.key for q in section.quantities if q.key in numeric and q.key not in keys]
    return keys or list(numeric), units


def evaluate(
    sweep: Plan,
    results: Sequence[str],
    jobs: int,
    on_done: Callable[[int], None] | None = None,
    time_limit: float | None = DEFAULT_SECONDS,
    mapper: Any = None,
) -> Table:
    """Every grid point: vectorized where the problem offers it (in this process),
    else point by point, each point under ``time_limit`` seconds, on ``jobs``
    processes or on ``mapper`` (:mod:`mdcalc.runs.cluster`: a dask cluster).

    ``on_done(n)`` is told of every ``n`` points finished (for a progress bar).
    """
    import numpy as np

    module = _module(sweep.problem)
    wanted, units = choose_results(sweep, results, time_limit)
    keys = [v.key for v in sweep.varies]
    key_units = {v.key: unit_of(module.Case, v.loc) for v in sweep.varies}
    units = {**key_units, **{k: units.get(k, "") for k in wanted}}
    mesh = np.meshgrid(*[np.asarray(a, dtype=float) for a in sweep.axes], indexing="ij")
    grid = {key: m.ravel() for key, m in zip(keys, mesh, strict=True)}
    columns: dict[str, Any] = dict(grid)
    kernel = getattr(module, "sweep", None)
    model = validate(module.Case, sweep.case)
    status = np.zeros(sweep.points, dtype=int)
    messages: list[str] = []
    if kernel is None:
        vectorized = None
    else:  # in blocks: here, on the pool when a block is heavy, or on the cluster
        where = mapper if mapper is not None else PoolMapper(jobs)
        vectorized = _kernel_in_blocks(sweep, grid, keys, wanted, where, status, messages)
    todo = np.arange(sweep.points)
    if vectorized is not None and all(k in vectorized for k in wanted):
        for key in wanted:
            column = np.asarray(vectorized[key], dtype=float)
            columns[key] = np.array(np.broadcast_to(column, (sweep.points,)))
        declined = vectorized.get(DECLINED)
        if declined is None or not np.any(declined):
            if on_done is not None:
                on_done(sweep.points)
            return Table(keys + wanted, units, columns, status, messages, vectorized=True)
        todo = np.flatnonzero(np.broadcast_to(declined, (sweep.points,)))
        if on_done is not None:
            on_done(sweep.points - len(todo))
    else:
        for key in wanted:
            columns[key] = np.full(sweep.points, np.nan)

    # Point by point: every point, or the points the kernel declined.
    run = mapper if mapper is not None else PoolMapper(jobs)
    path = str(sweep.case.path)
    alone = reference_only_fits(sweep.problem, module, model, wanted, time_limit)
    points = list(sweep.grid())
    tasks = [(path, sweep.problem, sweep.data_at(points[i]), time_limit, alone) for i in todo]
    done = (lambda: on_done(1)) if on_done is not None else None
    outcomes = run(point_results, tasks, done, _lost_point)
    for index, (code, values, message) in zip(todo.tolist(), outcomes, strict=True):
        status[index] = code
        if message:
            at = ", ".join(f"{k} = {grid[k][index]:g}" for k in keys)
            messages.append(f"{path}: error: {at}: {message}")
        for key in wanted:
            columns[key][index] = values.get(key, np.nan)
    by_kernel = len(todo) < sweep.points
    return Table(keys + wanted, units, columns, status, messages, vectorized=by_kernel)


def _kernel_in_blocks(
    sweep: Plan,
    grid: dict[str, Any],
    keys: list[str],
    wanted: list[str],
    mapper: Any,
    status: Any,
    messages: list[str],
) -> dict[str, Any] | None:
    """The kernel in blocks of points (:func:`~mdcalc.runs.kernel.kernel_parts`: here,
    on the pool when a block is heavy, or on a cluster's workers, retried where one
    dies); a block lost past the retries gives its points exit 70 and a message. None
    where the kernel declines the grid (point by point then)."""
    import numpy as np

    from mdcalc.runs.kernel import LOST, LOST_REASON, KernelChunk, LostBlock, kernel_parts

    data = copy.deepcopy(sweep.case.data)
    data.pop("expect", None)
    run = KernelChunk(sweep.problem, sweep.case.path, data, keys, wanted)
    points = np.column_stack([grid[key] for key in keys])
    blocks = [points[i : i + BLOCK] for i in range(0, len(points), BLOCK)]
    columns = {key: np.full(len(points), np.nan) for key in wanted}
    declined = np.zeros(len(points), dtype=bool)
    start = 0
    parts, _ = kernel_parts(run, blocks, mapper)
    for block, part in zip(blocks, parts, strict=True):
        end = start + len(block)
        if part is None:
            return None
        if isinstance(part, LostBlock):
            status[start:end] = EXIT_BUG
            at = f"points {start} to {end - 1}"
            messages.append(f"{sweep.case.path}: error: {at}: {part.reason}")
        else:
            for key in wanted:
                columns[key][start:end] = part[key]
            declined[start:end] = part[DECLINED]
            if LOST in part:  # a piece of the block lost on the pool: its points failed
                where = start + np.flatnonzero(part[LOST])
                status[where] = EXIT_BUG
                at = f"points {where[0]} to {where[-1]} (in part)"
                messages.append(f"{sweep.case.path}: error: {at}: {part[LOST_REASON]}")
        start = end
    return columns | {DECLINED: declined}


def _lost_point(task: Any, error: BaseException) -> tuple[int, dict[str, Any], str]:
    return EXIT_BUG, {}, f"internal error: its worker process died ({type(error).__name__})"


def _module(problem: str) -> Any:
    from mdcalc.problems import PROBLEMS

    return PROBLEMS[problem].load()


# ------------------------------------------------------------------------- output


#: Rows formatted at a time by :func:`to_csv`: pieces of a few MB stay in the caches
#: and the allocator reuses them (one 75 MB text for 10⁶ rows took twice as long).
CSV_BLOCK_ROWS = 65_536


def to_csv(table: Table) -> Iterator[bytes | memoryview]:
    """CSV (UTF-8) with a header of ``key [unit]`` and a ``status`` column (0, 2, 3, 70),
    as pieces to write one after another, made block by block as they are written.

    Each number is the shortest text that reads back as the same float, a whole
    number without ".0" (orjson's formatting, in C: a million rows in a fraction of a
    second where Python's took seconds); a missing value (NaN) is an empty field."""
    import numpy as np
    import orjson

    header = [f"{k} [{table.units[k]}]" if table.units.get(k) else k for k in table.keys]
    yield (",".join([*header, "status"]) + "\n").encode()
    columns = [np.asarray(table.columns[k], dtype=float) for k in table.keys]
    whole = any(_whole(column) for column in columns)
    missing = any(np.isnan(column).any() for column in columns)
    status = np.asarray(table.status)
    for start in range(0, len(status), CSV_BLOCK_ROWS):
        rows = slice(start, start + CSV_BLOCK_ROWS)
        block = np.column_stack([column[rows] for column in columns])
        text = orjson.dumps(block, option=orjson.OPT_SERIALIZE_NUMPY)
        if whole:
            # A count (pairs.driven = 2) without ".0"; each pass reads the whole text.
            text = text.replace(b".0,", b",").replace(b".0]", b"]")
        if missing:
            text = text.replace(b"null", b"")  # orjson writes NaN as null: an empty field
        codes = status[rows]
        if codes.any():
            lines = zip(text[2:-2].split(b"],["), codes.tolist(), strict=True)
            yield b"".join(b"%s,%d\n" % pair for pair in lines)  # [[a,b],[c,d]] -> a,b
        else:
            # Every status 0: each row's end "],[" becomes ",0\n" (the same length;
            # "]" is nowhere else), one pass in C over the text.
            yield memoryview(text.replace(b"],[", b",0\n"))[2:-2]
            yield b",0\n"


def _whole(column: Any) -> bool:
    """Every value a whole number (the first one looked at before the whole column)."""
    import numpy as np

    return bool(
        column.size and column[0] == np.rint(column[0]) and np.array_equal(np.rint(column), column)
    )


def to_json(table: Table, sweep: Plan) -> bytes:
    """The sweep as one JSON document, UTF-8 bytes (``values``: a list per key, null
    where a point has no value), written by orjson straight from the numpy columns."""
    import numpy as np
    import orjson

    from mdcalc._version import __version__

    document = {
        "mdcalc": __version__,
        "format": JSON_FORMAT,
        "problem": sweep.problem,
        "case": str(sweep.case.path),
        "vary": [
            {"key": v.key, "start": v.start, "stop": v.stop, "n": v.count} for v in sweep.varies
        ],
        "vectorized": table.vectorized,
        "columns": [{"key": k, "unit": ascii_unit(table.units.get(k, ""))} for k in table.keys],
        # orjson takes C-contiguous arrays only; a point-by-point column may be a view.
        "values": {k: np.ascontiguousarray(table.columns[k], dtype=float) for k in table.keys},
        "status": np.asarray(table.status, dtype=np.int64),
    }
    return orjson.dumps(document, option=orjson.OPT_SERIALIZE_NUMPY)


def summary_rows(table: Table) -> list[tuple[str, str, str, str]]:
    """(key, unit, min, max) of each result column over the points that have it."""
    import numpy as np

    from mdcalc.output.report import format_value

    rows = []
    for key in table.keys:
        column = table.columns[key]
        finite = column[np.isfinite(column)]
        low = format_value(float(finite.min())) if finite.size else "—"
        high = format_value(float(finite.max())) if finite.size else "—"
        rows.append((key, table.units.get(key, ""), low, high))
    return rows
