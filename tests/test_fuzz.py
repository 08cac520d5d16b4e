"""Property-based tests (hypothesis) over every registered problem's case model.

Every test is parametrized over ``PROBLEMS``, and everything a test needs -- seed cases,
numeric leaves, their bounds, required keys, sections -- is read from the problem's
``Case`` model and its cases, so a problem added later is covered without new code.

* Valid draws: a seed case (the problem's ``template()`` and every ``cases/<problem>/``
  file without its ``[expect]``) with each number scaled by 10**u, |u| <= 0.5, kept
  within the bounds its pydantic field declares, run with ``--time-limit``. Exit 0 or 3
  with no traceback and no NaN or infinity in the text or JSON output, each run back
  within its budget + 1 s; exit 2 only with every message in the
  ``file:line: error: path: message`` form (cross-field rules may reject a draw).
* Invalid draws, each always exit 2 with the place named: a number replaced by a string,
  bool, table or array; pushed beyond its bound; nan, inf, -inf, ±1e308; an unknown key;
  a required key or section removed; TOML truncated inside a ``key = value`` line; binary
  garbage; an empty file.

Run with ``-s`` to see how many draws each problem got (the last test prints them).
"""

from __future__ import annotations

import copy
import importlib
import math
import re
import signal
import time
import tomllib
import types
from collections import Counter, defaultdict
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Annotated, Any, Literal, Union, get_args, get_origin

import annotated_types
import pytest
import tomli_w
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from pydantic import BaseModel
from pydantic.fields import FieldInfo

import mdcalc.input.model
from mdcalc.problems import PROBLEMS
from tests.conftest import CASES, assert_no_traceback, strict_json, walk_finite

NAMES = list(PROBLEMS)
#: |x| <= this for every number of a case file (mdcalc.input.model); 1e18 if not declared there.
LIMIT = float(getattr(mdcalc.input.model, "MAGNITUDE_LIMIT", 1e18))
#: A seed whose unmodified run (text) takes longer is left out of the valid draws.
SEED_SECONDS = 1.0
#: Valid draws run with --time-limit BUDGET: each run must end within BUDGET + 1 s
#: (a perturbed stiff scene is cut by its budget, never left running).
BUDGET = 1.5
#: A watchdog over a draw's two runs: reaching it means a run ignored its budget.
RUN_SECONDS = 2 * (BUDGET + 1.0)
#: Valid draws per problem, each running the CLI twice (text and --json): at most
#: VALID_EXAMPLES, and no more than VALID_MIN once VALID_SECONDS have gone by.
VALID_EXAMPLES, VALID_MIN, VALID_SECONDS = 25, 6, 3.0
INVALID_EXAMPLES = 20  # per problem and kind of damage; validation only, milliseconds each
#: Draws per problem and kind, printed by the last test (run with -s).
TRIED: defaultdict[str, Counter[str]] = defaultdict(Counter)

NON_FINITE = re.compile(r"\b(nan|inf|infinity)\b", re.IGNORECASE)
FUZZ = settings(
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)

Path_ = tuple[str | int, ...]


# ---------------------------------------------------------------- the model, read generically


@dataclass(frozen=True)
class Node:
    """What the model says about one value of a case file."""

    models: tuple[type[BaseModel], ...] = ()
    items: tuple[Any, ...] = ()  # annotations of list items
    values: tuple[Any, ...] = ()  # annotations of dict values (dict[str, X])
    lo: float = -LIMIT
    lo_open: bool = False
    hi: float = LIMIT
    hi_open: bool = False
    integer: bool = False
    literal: bool = False


def node(annotation: Any, metadata: list[Any] | tuple[Any, ...] = ()) -> Node:
    """Flatten ``Annotated``, ``X | None`` and unions into a :class:`Node`."""
    todo, plain, meta = [annotation], [], list(metadata)
    while todo:
        a = todo.pop()
        origin = get_origin(a)
        if origin is Annotated:
            base, *extra = get_args(a)
            todo.append(base)
            meta.extend(extra)
        elif origin in (Union, types.UnionType):
            todo.extend(get_args(a))
        elif a is not type(None):
            plain.append(a)
    while any(isinstance(m, FieldInfo) for m in meta):
        meta = [x for m in meta for x in (m.metadata if isinstance(m, FieldInfo) else [m])]
    lo, lo_open, hi, hi_open = -LIMIT, False, LIMIT, False
    for m in meta:
        if isinstance(m, annotated_types.Gt) and m.gt >= lo:
            lo, lo_open = float(m.gt), True
        elif isinstance(m, annotated_types.Ge) and m.ge > lo:
            lo, lo_open = float(m.ge), False
        elif isinstance(m, annotated_types.Lt) and m.lt <= hi:
            hi, hi_open = float(m.lt), True
        elif isinstance(m, annotated_types.Le) and m.le < hi:
            hi, hi_open = float(m.le), False
    scalars = [a for a in plain if a in (int, float)]
    return Node(
        models=tuple(a for a in plain if isinstance(a, type) and issubclass(a, BaseModel)),
        items=tuple(get_args(a)[0] for a in plain if get_origin(a) is list),
        values=tuple(get_args(a)[1] for a in plain if get_origin(a) is dict),
        lo=lo,
        lo_open=lo_open,
        hi=hi,
        hi_open=hi_open,
        integer=bool(scalars) and float not in scalars,
        literal=any(get_origin(a) is Literal for a in plain),
    )


def child(parent: Node, key: str | int) -> Node | None:
    """The node of ``parent[key]``; None for a key the model does not know."""
    if isinstance(key, int):
        return node(Union[parent.items]) if parent.items else None  # noqa: UP007
    for model in parent.models:
        info = model.model_fields.get(key)
        if info is not None:
            return node(info.annotation, info.metadata)
    return node(Union[parent.values]) if parent.values else None  # noqa: UP007


def is_number(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def numbers(data: Any, here: Node, path: Path_ = ()) -> Iterator[tuple[Path_, Node]]:
    """Every number of ``data`` (in tables and arrays) with its node."""
    if is_number(data):
        yield path, here
    elif isinstance(data, dict | list):
        pairs = data.items() if isinstance(data, dict) else enumerate(data)
        for key, value in pairs:
            sub = child(here, key)
            if sub is not None:
                yield from numbers(value, sub, (*path, key))


def tables(data: Any, here: Node, path: Path_ = ()) -> Iterator[tuple[Path_, Node]]:
    """Every table of ``data`` that is a model (not a free ``dict[str, X]``)."""
    if isinstance(data, dict) and here.models:
        yield path, here
    if isinstance(data, dict | list):
        pairs = data.items() if isinstance(data, dict) else enumerate(data)
        for key, value in pairs:
            sub = child(here, key)
            if sub is not None:
                yield from tables(value, sub, (*path, key))


def required(data: Any, here: Node, path: Path_ = ()) -> Iterator[Path_]:
    """Every key written in ``data`` that its model requires."""
    for table, info in tables(data, here, path):
        for key in get(data, table[len(path) :]):
            fields = [m.model_fields[key] for m in info.models if key in m.model_fields]
            if fields and fields[0].is_required():
                yield (*table, key)


def get(data: Any, path: Path_) -> Any:
    for key in path:
        data = data[key]
    return data


def replaced(data: Any, path: Path_, value: Any) -> Any:
    out = copy.deepcopy(data)
    get(out, path[:-1])[path[-1]] = value
    return out


def dotted(path: Path_) -> str:
    out = ""
    for key in path:
        out += f"[{key}]" if isinstance(key, int) else (f".{key}" if out else key)
    return out


# ------------------------------------------------------------------------------- seeds


@cache
def seeds(name: str) -> list[tuple[str, dict[str, Any]]]:
    """The template and the shipped cases of ``name``, without their [expect] (shared:
    never modified in place)."""
    out = [("template", PROBLEMS[name].load().template())]
    for path in sorted(CASES.rglob("*.toml")):
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        if data.get("problem") == name and "study" not in data:
            data.pop("expect", None)
            out.append((str(path.relative_to(CASES)), data))
    return out


class Overtime(BaseException):
    """Raised by the alarm inside a run that takes too long (not an Exception: the CLI
    maps those to exit 70)."""


@contextmanager
def time_limit(seconds: float) -> Iterator[None]:
    if not hasattr(signal, "setitimer"):
        yield
        return

    def alarm(signum: int, frame: Any) -> None:
        raise Overtime

    previous = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


_FAST: dict[str, list[tuple[str, dict[str, Any]]]] = {}
#: Seeds left out of the valid draws, and draws abandoned: (problem, seed, why).
LEFT_OUT: list[tuple[str, str, str]] = []


def fast_seeds(name: str, run: Any) -> list[tuple[str, dict[str, Any]]]:
    """Seeds whose unmodified run takes at most SEED_SECONDS and exits 0 or 3 (an exit 70
    or 2 is left out and listed by the last test: the shipped cases have their own tests)."""
    if not _FAST:  # the first solve of a session would pay these imports, not its seed
        for spec in PROBLEMS.values():
            spec.load()
        with suppress(ImportError):
            importlib.import_module("scipy.integrate")
    if name not in _FAST:
        kept = []
        for label, data in seeds(name):
            try:
                with time_limit(SEED_SECONDS):
                    result = run(name, tomli_w.dumps(data))
            except Overtime:
                LEFT_OUT.append((name, label, f"> {SEED_SECONDS:g} s"))
                continue
            if result.exit_code in (0, 3):
                kept.append((label, data))
            else:
                LEFT_OUT.append((name, label, f"exit {result.exit_code}"))
        _FAST[name] = kept
    return _FAST[name]


@pytest.fixture
def run(cli, write_case):
    """run(problem, text_or_bytes, *args) -> (result); the file is ``case.toml``."""

    def invoke(name: str, content: str | bytes, *args: str):
        path = write_case("")
        if isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(content, encoding="utf-8")
        result = cli(name, path, *args)
        result.path = str(path)
        return result

    return invoke


# ------------------------------------------------------------------------------ checks

PLACE = re.compile(r"^(?P<file>.+?)(?::(?P<line>\d+))?(?::(?P<col>\d+))?: error: (?P<rest>.*)$")
KEY_PATH = re.compile(r"^[\w-]+(?:\.[\w-]+|\[\d+\])*: ")


def error_lines(result) -> list[re.Match[str]]:
    """stderr of an exit 2, each line parsed; every line must be a message."""
    assert result.exit_code == 2, (result.exit_code, result.stdout[-2000:], result.stderr)
    assert_no_traceback(result)
    lines = result.stderr.strip().splitlines()
    assert lines, "exit 2 without a message"
    parsed = [PLACE.match(line) for line in lines]
    assert all(m and m["file"] == result.path for m in parsed), result.stderr
    return [m for m in parsed if m]


def written_line(text: str, path: Path_) -> int | None:
    """The line of tomli_w's ``text`` where the longest written prefix of ``path`` is: a
    key at the start of a line or a table header (a key inside an inline table has no line
    of its own, the array holding it has)."""
    lines: dict[Path_, int] = {}
    arrays: Counter[Path_] = Counter()  # [[name]] headers seen so far

    def resolve(name: Path_) -> Path_:  # a.b.c under [[a.b]]: a.b[last].c
        out: Path_ = ()
        for n, key in enumerate(name, start=1):
            out = (*out, key) + ((arrays[name[:n]] - 1,) if arrays[name[:n]] else ())
        return out

    table: Path_ = ()
    for number, line in enumerate(text.splitlines(), start=1):
        if header := re.fullmatch(r"\[(\[?)([\w.-]+)\]?\]", line):
            name = tuple(header[2].split("."))
            if header[1]:
                arrays[name] += 1
            table = resolve(name)
            lines.setdefault(table[:-1] if header[1] else table, number)
            lines.setdefault(table, number)
        elif key := re.match(r"([\w-]+) = ", line):
            lines.setdefault((*table, key[1]), number)
    for n in range(len(path), 0, -1):
        if path[:n] in lines:
            return lines[path[:n]]
    return None


def assert_names(result, path: Path_, line_of: Path_ | None) -> None:
    """Exit 2 and a message at ``path`` on the line where ``line_of`` is written
    (``line_of`` None: a place without a line, such as a section that is not there)."""
    want = dotted(path)
    hits = [m for m in error_lines(result) if m["rest"].startswith(f"{want}: ")]
    assert hits, f"no message at {want}:\n{result.stderr}"
    text = Path(result.path).read_text(encoding="utf-8")
    line = None if line_of is None else written_line(text, line_of)
    assert line_of is None or line is not None, (line_of, text)
    for m in hits:
        assert m["col"] is None, m.string
        assert (None if m["line"] is None else int(m["line"])) == line, (m.string, line)


def assert_field_messages(result) -> None:
    """Exit 2 where every message is ``file:line: error: key.path: message``."""
    for m in error_lines(result):
        assert m["line"] is not None and m["col"] is None, m.string
        assert KEY_PATH.match(m["rest"]), m.string


def assert_clean_output(result, as_json: bool) -> None:
    """Exit 0 or 3, no traceback, no NaN or infinity in stdout or stderr, strict JSON."""
    assert_no_traceback(result)
    assert result.exit_code in (0, 3), (result.exit_code, result.stderr)
    for stream in (result.stdout, result.stderr):
        found = NON_FINITE.search(stream)
        assert not found, f"{found.group()!r} in the output:\n{stream}"
    if as_json:
        walk_finite(strict_json(result.stdout))


# --------------------------------------------------------------------- valid draws


def scaled(value: float, factor: float, here: Node) -> float | int:
    """``value * factor`` kept inside the node's bounds, an integer for an int field."""
    new = value * factor
    if here.integer:
        lo = math.floor(here.lo) + 1 if here.lo_open else math.ceil(here.lo)
        hi = math.ceil(here.hi) - 1 if here.hi_open else math.floor(here.hi)
        return min(max(round(new), lo), hi)
    if new < here.lo or (here.lo_open and new <= here.lo):
        new = (value + here.lo) / 2 if here.lo_open else here.lo
    if new > here.hi or (here.hi_open and new >= here.hi):
        new = (value + here.hi) / 2 if here.hi_open else here.hi
    return float(new)


EXPONENT = st.one_of(st.just(0.0), st.floats(-0.5, 0.5))


def perturb(draw: Any, data: Any, here: Node) -> Any:
    """Scale every number by 10**u: one u per number, one per array of numbers (its
    order and ratios kept); bools, strings and literals untouched."""
    if isinstance(data, dict):
        subs = {key: child(here, key) for key in data}
        return {k: v if subs[k] is None else perturb(draw, v, subs[k]) for k, v in data.items()}
    if isinstance(data, list) and any(isinstance(v, dict) for v in data):
        return [perturb(draw, v, child(here, i) or here) for i, v in enumerate(data)]
    leaves = [(path, leaf) for path, leaf in numbers(data, here) if not leaf.literal]
    if not leaves:
        return data
    factor = 10.0 ** draw(EXPONENT)
    if not isinstance(data, list):
        return scaled(data, factor, here)
    out = copy.deepcopy(data)
    for path, leaf in leaves:
        holder = get(out, path[:-1])
        holder[path[-1]] = scaled(holder[path[-1]], factor, leaf)
    return out


def top(name: str) -> Node:
    return node(PROBLEMS[name].load().Case)


@pytest.mark.parametrize("name", NAMES)
def test_valid_draws_compute_or_explain(name, run):
    """Perturbed seeds: exit 0/3 with finite output, or exit 2 with placed messages."""
    pool = fast_seeds(name, run)
    assert pool, f"no seed of {name} runs within {SEED_SECONDS} s"
    here, counts = top(name), TRIED[name]
    before, start = counts.copy(), time.perf_counter()

    @settings(FUZZ, max_examples=VALID_EXAMPLES)
    @given(st.data())
    def check(data: st.DataObject) -> None:
        label, seed = data.draw(st.sampled_from(pool), label="seed")
        text = tomli_w.dumps(perturb(data.draw, seed, here))
        ran = counts["valid draws"] - before["valid draws"]
        late = time.perf_counter() - start > VALID_SECONDS
        if late and ran >= VALID_MIN and counts["failures"] == before["failures"]:
            return  # out of time; a failure being shrunk runs every draw
        counts["valid draws"] += 1
        limit = ("--time-limit", str(BUDGET))
        try:
            with time_limit(RUN_SECONDS):
                began = time.perf_counter()
                as_text = run(name, text, *limit)
                middle = time.perf_counter()
                as_json = None if as_text.exit_code == 2 else run(name, text, "--json", *limit)
                ended = time.perf_counter()
        except Overtime:
            counts["failures"] += 1
            raise AssertionError(f"{name}: a run of {label} ignored its time budget") from None
        try:
            assert middle - began < BUDGET + 1.0 and ended - middle < BUDGET + 1.0
            if as_json is None:
                assert_field_messages(as_text)  # a cross-field rule refused the draw
            else:
                assert_clean_output(as_text, as_json=False)
                assert_clean_output(as_json, as_json=True)
                if as_json.exit_code != as_text.exit_code:
                    # Wall time: near its budget a scene may be cut in one run and not
                    # in the other (CI once cut the text run, exit 3, not the JSON one).
                    said = as_text.stdout + as_text.stderr + as_json.stdout + as_json.stderr
                    assert "time budget" in said, (as_text.exit_code, as_json.exit_code)
        except AssertionError:
            counts["failures"] += 1
            raise
        counts[f"valid exit {as_text.exit_code}"] += 1

    check()
    tried = counts["valid draws"] - before["valid draws"]
    computed = sum(counts[f"valid exit {c}"] - before[f"valid exit {c}"] for c in (0, 3))
    # Not vacuous: cross-field rules refuse some draws, but most must be computed.
    assert computed >= 0.25 * tried, f"{name}: only {computed} of {tried} draws were valid"


# ------------------------------------------------------------------- invalid draws


def invalid(kind: str):
    """Make an invalid-draw property ``body(data, name, run)`` a test per problem."""

    def wrap(body):
        @pytest.mark.parametrize("name", NAMES)
        def test(name, run):
            @settings(FUZZ, max_examples=INVALID_EXAMPLES)
            @given(st.data())
            def check(data: st.DataObject) -> None:
                counts = TRIED[name]
                try:
                    body(data, name, run)  # a draw refused by assume() is not counted
                except AssertionError:
                    counts.update(["failures", "invalid draws", f"invalid: {kind}"])
                    raise
                counts.update(["invalid draws", f"invalid: {kind}"])

            check()

        test.__name__ = body.__name__
        test.__doc__ = body.__doc__
        return test

    return wrap


def pick(data: st.DataObject, name: str) -> dict[str, Any]:
    """A seed of ``name``: every seed, slow ones too (an invalid case is never solved)."""
    return data.draw(st.sampled_from(seeds(name)), label="seed")[1]


def some_number(data: st.DataObject, seed: dict[str, Any], here: Node) -> tuple[Path_, Node]:
    leaves = list(numbers(seed, here))
    assume(leaves)
    return data.draw(st.sampled_from(leaves), label="number")


def _not_a_quantity(text: str) -> bool:
    """A string pint cannot read: "3", "m" or "pi" are quantities now (issue 9)."""
    from mdcalc.input.quantities import QuantityError, convert

    for unit in ("-", "m", "N·m/rad", "rpm"):
        try:
            convert(text, unit)
            return False
        except QuantityError as exc:
            if "does not convert" in str(exc) or "without a unit" in str(exc):
                return False  # read, but of another dimension: could fit some key
    return True


WRONG_TYPES = st.one_of(
    st.text(max_size=8).filter(_not_a_quantity),
    st.booleans(),
    st.dictionaries(st.from_regex(r"[a-z]{1,6}", fullmatch=True), st.integers(), max_size=2),
    st.lists(st.floats(-10, 10), max_size=3),
)


@invalid("wrong type")
def test_a_number_of_the_wrong_type_is_named(data, name, run):
    """A number replaced by a string, bool, table or array."""
    seed = pick(data, name)
    path, _ = some_number(data, seed, top(name))
    value = data.draw(WRONG_TYPES, label="value")
    result = run(name, tomli_w.dumps(replaced(seed, path, value)))
    assert_names(result, path, path)


@invalid("beyond a bound")
def test_a_number_beyond_its_bound_is_named(data, name, run):
    """A number pushed past its field's bound (or past ±MAGNITUDE_LIMIT if it has none)."""
    seed = pick(data, name)
    path, leaf = some_number(data, seed, top(name))
    assume(not leaf.literal)
    side = data.draw(st.sampled_from(["lo", "hi"]), label="side")
    bound, is_open = (leaf.lo, leaf.lo_open) if side == "lo" else (leaf.hi, leaf.hi_open)
    sign = -1.0 if side == "lo" else 1.0
    step = data.draw(st.sampled_from([1e-6, 1e-3, 1.0, 1e3]), label="step")
    value: float | int = bound + sign * step * max(abs(bound), 1.0)
    if is_open:
        value = data.draw(st.sampled_from([bound, value]), label="value")
    if leaf.integer:
        value = int(math.floor(value) if side == "lo" else math.ceil(value))
        if value == bound and not is_open:
            value += int(sign)
    result = run(name, tomli_w.dumps(replaced(seed, path, value)))
    assert_names(result, path, path)


@invalid("nan, inf, 1e308")
def test_nan_inf_and_1e308_are_named(data, name, run):
    """nan, inf, -inf, 1e308 or -1e308 written in place of a number."""
    seed = pick(data, name)
    path, _ = some_number(data, seed, top(name))
    value = data.draw(st.sampled_from([math.nan, math.inf, -math.inf, 1e308, -1e308]))
    text = tomli_w.dumps(replaced(seed, path, value))
    assert re.search(r"(?<![\w.])-?(nan|inf|1e\+308)\b", text)
    result = run(name, text)
    assert_names(result, path, path)


@invalid("unknown key")
def test_an_unknown_key_is_named(data, name, run):
    """A key the model does not know, at top level or in any section."""
    seed = pick(data, name)
    where, info = data.draw(st.sampled_from(list(tables(seed, top(name)))), label="table")
    known = {k for m in info.models for k in m.model_fields}
    key = data.draw(st.from_regex(r"[a-z][a-z0-9_]{0,15}", fullmatch=True), label="key")
    assume(key not in known)
    value = data.draw(st.one_of(st.integers(), st.floats(-1, 1), st.text(max_size=5)))
    case = copy.deepcopy(seed)
    get(case, where)[key] = value
    result = run(name, tomli_w.dumps(case))
    assert_names(result, (*where, key), (*where, key))
    assert "unknown key" in result.stderr


@invalid("required key removed")
def test_a_missing_required_key_is_named(data, name, run):
    """A required key or section removed (``problem`` too)."""
    seed = pick(data, name)
    path = data.draw(st.sampled_from(list(required(seed, top(name)))), label="key")
    case = copy.deepcopy(seed)
    del get(case, path[:-1])[path[-1]]
    result = run(name, tomli_w.dumps(case))
    # A missing key has no line of its own: the message names its table's line.
    assert_names(result, path, path[:-1] or None)


@invalid("truncated")
def test_toml_cut_inside_a_key_value_line_gives_line_and_column(data, name, run):
    """The file ends in the middle of a ``key = value`` line: a TOML syntax error."""
    lines = tomli_w.dumps(pick(data, name)).splitlines(keepends=True)
    pairs = [n for n, line in enumerate(lines) if re.match(r"[\w-]+ = .", line)]
    n = data.draw(st.sampled_from(pairs), label="line")
    cut = data.draw(st.integers(1, len(lines[n].rstrip("\n")) - 1), label="cut")
    text = "".join(lines[:n]) + lines[n][:cut]
    try:
        tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        pass
    else:
        assume(False)  # a number cut short ("1500" -> "15") is still TOML
    result = run(name, text)
    (m,) = error_lines(result)
    assert m["rest"].startswith("TOML syntax: "), m.string
    assert m["line"] is not None and int(m["line"]) == n + 1, m.string
    assert m["col"] is not None and 1 <= int(m["col"]) <= cut + 1, m.string


@invalid("binary garbage")
def test_binary_garbage_is_refused_with_a_place(data, name, run):
    """Random bytes, alone or inside a seed's text."""
    seed = tomli_w.dumps(pick(data, name)).encode()
    if data.draw(st.booleans(), label="alone"):
        blob = data.draw(st.binary(max_size=300), label="bytes")
        result = run(name, blob)
        for m in error_lines(result):
            # Not UTF-8 or not TOML: the line; TOML without `problem`: that key.
            assert m["line"] is not None or m["rest"].startswith("problem: "), m.string
        return
    garbage = b"\xff" + data.draw(st.binary(max_size=40), label="bytes").replace(b"\n", b"")
    at = data.draw(st.integers(0, len(seed)), label="at")
    result = run(name, seed[:at] + garbage + seed[at:])
    (m,) = error_lines(result)
    assert int(m["line"] or 0) == seed[:at].count(b"\n") + 1, m.string
    assert "UTF-8" in m["rest"], m.string


@pytest.mark.parametrize("name", NAMES)
def test_an_empty_file_asks_for_the_problem(name, run):
    for text in ("", "\n", "# only a comment\n", " \t\n\n"):
        TRIED[name]["invalid draws"] += 1
        TRIED[name]["invalid: empty"] += 1
        assert_names(run(name, text), ("problem",), None)


# ------------------------------------------- bugs the properties found (fixed since)


def test_a_union_field_names_its_key_path_without_pydantic_tags(cli, write_case):
    """torque.values is list[float] | list[list[float]]: the message named
    "torque.values.list[float][1]" and added one "expected an array" per element."""
    path = write_case(
        'problem = "mechanism"\n\n[torque]\nangles_deg = [0, 180, 360]\n'
        "values = [100.0, nan, 100.0]\n\n[inertia]\nvalue = 2.0\n\n"
        "[motion]\nstart_speed = 10.0\nrevolutions = 2.0\n"
    )
    result = cli("mechanism", path)
    assert result.exit_code == 2
    assert (
        result.stderr
        == f"{path}:5: error: torque.values[1]: got nan; must be a finite number N·m\n"
    )


def test_one_bad_cell_of_a_two_way_table_is_one_message(cli, write_case):
    """A table replaced a number of a two-way table: one message per row was given."""
    path = write_case(
        'problem = "mechanism"\n\n[torque]\nangles_deg = [0, 180, 360]\nspeeds = [0.0, 10.0]\n'
        "values = [[100.0, 90.0], [100.0, []], [100.0, 90.0]]\n\n[inertia]\nvalue = 2.0\n\n"
        "[motion]\nstart_speed = 10.0\nrevolutions = 2.0\n"
    )
    result = cli("mechanism", path)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{path}:6: error: torque.values[1][1]: got an array")
    assert len(result.stderr.splitlines()) == 1, result.stderr


def test_toml_cut_at_the_end_of_the_file_gives_a_column(cli, write_case):
    """tomllib has no position for an error at the end of the document: no column was given."""
    path = write_case('problem = "braking"\n\n[vehicle]\nmass =')
    result = cli("braking", path)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{path}:4:7: error: TOML syntax: ")


# ----------------------------------------------------------------------------- summary


def test_zz_summary_of_draws():
    """Draws per problem of the tests above (see them with ``pytest -s``); runs last."""
    if not TRIED:
        pytest.skip("no property test ran")
    columns = ["valid draws", "valid exit 0", "valid exit 3", "valid exit 2"]
    columns += ["invalid draws", "failures"]
    print("\n" + " | ".join(["problem", *columns]))
    for name in NAMES:
        print(" | ".join([name, *(str(TRIED[name][c]) for c in columns)]))
    kinds = Counter(k for c in TRIED.values() for k in c.elements() if k.startswith("invalid:"))
    print("invalid draws by kind: " + ", ".join(f"{k[9:]} {n}" for k, n in kinds.items()))
    for name, label, why in LEFT_OUT:
        print(f"left out: {name} {label} ({why})")
