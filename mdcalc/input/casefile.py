"""Read case files (tomli), validate them (pydantic), turn errors into messages.

All file I/O of case files lives here. Messages follow the
``file:line: error: path: message`` form that editors and CI annotators read.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar, get_args, get_origin

import tomli
from pydantic import BaseModel, ValidationError
from pydantic.fields import FieldInfo

from mdcalc.errors import InputError, Problem
from mdcalc.input.files import read_regular, write_atomic
from mdcalc.input.model import FieldError

M = TypeVar("M", bound=BaseModel)

_HEADER = re.compile(r"^\s*(\[\[?)\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")
_KEY = re.compile(r"^\s*([A-Za-z0-9_\-\".' ]+?)\s*=")
_UNIT = re.compile(r"\[([^\]]+)\]\s*$")


@dataclass(frozen=True)
class Conversion:
    """A number written as a quantity string, and the value it became."""

    loc: tuple[str | int, ...]
    written: str
    value: float
    unit: str  # the field's unit, "" for a plain number


class CaseText:
    """A case file's text and parsed data, with the line of each key."""

    def __init__(self, path: Path, text: str, data: dict[str, Any]) -> None:
        self.path = path
        self.text = text
        self.data = data
        self._lines: dict[tuple[str | int, ...], int] | None = None  # made when asked for
        #: Quantity strings converted by the last :func:`validate` of this case.
        self.conversions: list[Conversion] = []
        #: The cases of its ``base =`` chain, nearest first (:func:`read_case`).
        self.bases: list[CaseText] = []

    def written(self) -> dict[str, int]:
        """The line of each key path the file itself writes, by its dotted name."""
        if self._lines is None:
            self._lines = _key_lines(self.text)
        return {dotted(loc): line for loc, line in self._lines.items()}

    def line_of(self, loc: tuple[str | int, ...]) -> int | None:
        """Line of the key at ``loc``, or of its nearest enclosing table."""
        if self._lines is None:  # only a message needs lines: most cases never ask
            self._lines = _key_lines(self.text)
        for n in range(len(loc), 0, -1):
            line = self._lines.get(tuple(loc[:n]))
            if line is not None:
                return line
        return None


def read_case(path: Path) -> CaseText:
    """Read and parse a TOML case file; raise :class:`InputError` when it cannot.

    A file with ``base = "other.toml"`` (a path relative to the file) takes every key
    of that case it does not give itself (tables merged key by key; other values, arrays
    among them, replaced whole), but not its ``[expect]``, ``[saved]`` or ``[study]``; a
    base may have a base of its own (at most :data:`MAX_BASES` files, no cycle). The
    data is the merged scene, without ``base``; the text stays the file's own (a key
    the file does not write has no line in a message)."""
    return with_base(_read_one(path))


def with_base(case: CaseText) -> CaseText:
    """``case`` with the keys of its ``base`` (a path from the file's folder; from the
    current directory for a text given from Python) it does not give itself."""
    if "base" in case.data:
        case.data = _with_base(case, [case.path], case.bases)
    return case


#: Files a chain of ``base =`` may go through.
MAX_BASES = 8
#: What a file does not take from its base: its checks, results and study are its own.
NOT_INHERITED = ("expect", "saved", "study", "base")


def _with_base(case: CaseText, chain: list[Path], bases: list[CaseText]) -> dict[str, Any]:
    """``case.data`` over the case its ``base`` names (see :func:`read_case`); each case
    of the chain is added to ``bases``."""
    base = case.data["base"]
    line = case.line_of(("base",))
    if not isinstance(base, str) or not base.strip():
        raise InputError(case.path, [Problem("a path to a case file, as a string", "base", line)])
    target = Path(base) if Path(base).is_absolute() else case.path.parent / base
    try:
        seen = [p.resolve() for p in chain]
        cycle = target.resolve() in seen
        there = target.is_file()
    except (OSError, RuntimeError) as exc:  # a name too long, a loop of symbolic links
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        shown = base if len(base) <= 80 else f"{base[:60]}…({len(base)} characters)"
        problem = Problem(f"cannot read {shown!r}: {why}", "base", line)
        raise InputError(case.path, [problem]) from None
    if cycle:
        names = " -> ".join(str(p) for p in [*chain, target])
        raise InputError(case.path, [Problem(f"a cycle of bases: {names}", "base", line)])
    if len(chain) >= MAX_BASES:
        problem = Problem(f"more than {MAX_BASES} files in a chain of bases", "base", line)
        raise InputError(case.path, [problem])
    if not there:
        problem = Problem(f"no such case file: {target}", "base", line)
        raise InputError(case.path, [problem])
    parent = _read_one(target)
    bases.append(parent)
    inherited = (
        _with_base(parent, [*chain, target], bases) if "base" in parent.data else parent.data
    )
    own = {k: v for k, v in case.data.items() if k != "base"}
    mine, theirs = own.get("problem"), inherited.get("problem")
    if mine is not None and theirs is not None and mine != theirs:
        problem = Problem(
            f"{mine!r}, but its base {target} is a {theirs!r} case",
            "problem",
            case.line_of(("problem",)),
        )
        raise InputError(case.path, [problem])
    return _merged({k: v for k, v in inherited.items() if k not in NOT_INHERITED}, own)


def _merged(under: dict[str, Any], over: dict[str, Any]) -> dict[str, Any]:
    """``over`` on ``under``: tables merged key by key, anything else replaced."""
    out = dict(under)
    for key, value in over.items():
        below = out.get(key)
        out[key] = (
            _merged(below, value) if isinstance(value, dict) and isinstance(below, dict) else value
        )
    return out


def _read_one(path: Path) -> CaseText:
    """One TOML file, parsed (no ``base`` followed)."""
    raw = read_regular(path)  # a regular file of bounded size, or InputError
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        bad_line = raw[: exc.start].count(b"\n") + 1
        problem = Problem("not a UTF-8 text file (TOML must be UTF-8)", line=bad_line)
        raise InputError(path, [problem]) from None
    return case_from_text(path, text)


def case_from_text(path: Path, text: str) -> CaseText:
    """TOML text, parsed as a case file named ``path`` (``<string>`` from Python)."""
    try:
        data = tomli.loads(text)
    except RecursionError:  # tomli's own limits: 400 levels of brackets, 1000 key parts
        raise InputError(path, [Problem(_TOO_DEEP)]) from None
    except tomli.TOMLDecodeError as exc:
        # At the end of the document too: just past the last character.
        problem = Problem(f"TOML syntax: {exc.msg}", line=exc.lineno, column=exc.colno)
        raise InputError(path, [problem]) from None
    except ValueError as exc:  # an integer of more than 4300 digits, say
        raise InputError(
            path, [Problem(f"TOML value out of range: {str(exc).split(':')[0]}")]
        ) from None
    # Each level of nesting takes a "[", "{" or "." of the text: a small case has too
    # few of them to need the walk.
    nesting = text.count("[") + text.count("{") + text.count(".")
    if nesting >= MAX_DEPTH and _depth(data) > MAX_DEPTH:
        raise InputError(path, [Problem(_TOO_DEEP)])
    return CaseText(path, text, data)


#: How deep tables and lists may nest in a case file (the deepest shipped case: 3).
MAX_DEPTH = 16
_TOO_DEEP = f"tables and lists nested more than {MAX_DEPTH} deep; a case file needs a few"


def _depth(data: Any) -> int:
    """How deep ``data`` nests, counted without recursion (stops past MAX_DEPTH)."""
    deepest, stack = 0, [(data, 1)]
    while stack:
        node, depth = stack.pop()
        deepest = max(deepest, depth)
        if depth > MAX_DEPTH:
            break
        children = node.values() if isinstance(node, dict) else node
        if isinstance(node, dict | list):
            stack.extend((child, depth + 1) for child in children if isinstance(child, dict | list))
    return deepest


def validate(model: type[M], case: CaseText) -> M:
    """Validate parsed data against ``model``; every problem is reported at once.

    Numbers written as quantity strings (``"52.5 N*m/deg"``) are converted to the
    field's unit first (:mod:`mdcalc.input.quantities`); ``case.conversions`` lists them.
    """
    problems: list[Problem] = []
    conversions: list[Conversion] = []
    data = case.data
    if _has_strings(data):  # most batch cases have none but the problem's name
        data = _with_quantities(model, case, data, (), conversions, problems)
    case.conversions = conversions
    try:
        validated = model.model_validate(data)
    except ValidationError as exc:
        failed = {p.path for p in problems}  # already told: not a number it could read
        errors = _one_union_member(model, exc.errors())
        found = [_problem_from_error(model, case, err) for err in errors]
        problems += [p for p in found if p.path not in failed]
    if problems and case.bases:
        problems = [_blamed_on_base(case, p) for p in problems]
    if problems:
        raise InputError(case.path, problems) from None
    return validated


def _blamed_on_base(case: CaseText, problem: Problem) -> Problem:
    """A problem with a key the file does not write but a base does: named there."""
    if not problem.path or problem.path in case.written():
        return problem
    for base in case.bases:
        line = base.written().get(problem.path)
        if line is not None:
            where = f"{problem.message} (set in its base {base.path}:{line})"
            return Problem(where, problem.path, None)
    return problem


def _has_strings(data: dict[str, Any]) -> bool:
    """Is there a string in ``data`` besides the top-level ``problem`` and ``title``
    (which are never numbers)?"""
    stack: list[Any] = [v for k, v in data.items() if k not in ("problem", "title")]
    while stack:
        node = stack.pop()
        if isinstance(node, str):
            return True
        if isinstance(node, dict):
            stack.extend(node.values())
        elif isinstance(node, list):
            stack.extend(node)
    return False


def _with_quantities(
    model: type[BaseModel],
    case: CaseText,
    value: Any,
    loc: tuple[str | int, ...],
    conversions: list[Conversion],
    problems: list[Problem],
) -> Any:
    """``value`` with every quantity string under a numeric field replaced by its
    number in the field's unit; strings elsewhere are left for pydantic to judge."""
    if isinstance(value, dict):
        return {
            key: _with_quantities(model, case, item, (*loc, key), conversions, problems)
            for key, item in value.items()
        }
    if isinstance(value, list):
        return [
            _with_quantities(model, case, item, (*loc, index), conversions, problems)
            for index, item in enumerate(value)
        ]
    if not isinstance(value, str) or not loc:
        return value
    info = _walk(model, loc)[1]
    if info is None or not takes_numbers(info.annotation):
        return value
    from mdcalc.input.quantities import QuantityError, convert

    unit = _unit(info)
    try:
        number = convert(value, unit if unit else "-")
    except QuantityError as exc:
        problems.append(Problem(str(exc), dotted(loc), case.line_of(loc)))
        return value
    if _leaves(info.annotation) - {type(None)} == {int}:  # int, int | None, list[int]
        if number != round(number):
            problems.append(
                Problem(f"got {value!r} = {number:g}; expected a whole number", dotted(loc),
                        case.line_of(loc))
            )  # fmt: skip
            return value
        number = int(round(number))
    conversions.append(Conversion(loc, value, number, unit))
    return number


def _leaves(annotation: Any) -> set[Any]:
    """The plain types inside an annotation (``list[int] | None`` -> {int, None})."""
    args = getattr(annotation, "__args__", None)
    if not args:
        return {annotation}
    return set().union(*(_leaves(arg) for arg in args))


def takes_numbers(annotation: Any) -> bool:
    """Does the field take numbers (``float``, ``int | None``, ``list[float]`` ...) and
    no strings?"""
    leaves = _leaves(annotation)
    return bool(leaves & {float, int}) and str not in leaves


def write_toml_atomic(path: Path, data: dict[str, Any], force: bool = False) -> None:
    """Write ``data`` as TOML to ``path`` atomically; never overwrite without ``force``
    (:func:`mdcalc.input.files.write_atomic`: exclusive creation, regular files only)."""
    import tomli_w

    write_atomic(path, tomli_w.dumps(data), replace=force)


def write_text_atomic(
    path: Path, text: str | bytes | bytearray | Iterable[bytes | memoryview]
) -> None:
    """Write ``text`` (str, or bytes already UTF-8) to ``path`` atomically, replacing
    a regular file that is there (the results of ``run --out`` and ``sweep --out``,
    written again on each run)."""
    write_atomic(path, text, replace=True)


# ------------------------------------------------------------------ error messages


def dotted(loc: tuple[str | int, ...]) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += f".{part}" if out else str(part)
    return out


def _walk(model: type[BaseModel], loc: tuple[str | int, ...]) -> tuple[Any, Any]:
    """Follow ``loc`` through nested models: (model class holding the last key, FieldInfo)."""
    current: Any = model
    holder: Any = None
    info: Any = None
    for part in loc:
        if isinstance(part, int):
            continue
        fields = getattr(current, "model_fields", None)
        if fields is None and info is not None and get_origin(info.annotation) is dict:
            # a key of a table of named numbers (``parameters.a``): the value's type,
            # the table's description
            value, description = get_args(info.annotation)[1], info.description
            info = FieldInfo.from_annotation(value)
            info.description = description
            current = _inner_model(value)
            continue
        if fields is None or part not in fields:
            return current, None  # an unknown key: ``current`` is where it was written
        holder, info = current, fields[part]
        current = _inner_model(info.annotation)
    return holder, info


def _inner_model(annotation: Any) -> Any:
    """The BaseModel inside ``X``, ``X | None``, ``list[X]``, ``dict[str, X]``."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in getattr(annotation, "__args__", ()) or ():
        found = _inner_model(arg)
        if found is not None:
            return found
    return None


def field_info(model: type[BaseModel], loc: tuple[str | int, ...]) -> Any:
    """The pydantic FieldInfo of the key at ``loc`` (its bounds, its description);
    None for a key the model does not have."""
    return _walk(model, loc)[1]


def missing_name(
    model: type[BaseModel], data: dict[str, Any], loc: tuple[str | int, ...]
) -> str | None:
    """Why ``loc`` cannot be drawn or varied when it names an entry the case's table of
    named numbers (``parameters.a``) does not hold: a new name would change nothing.
    None otherwise."""
    if len(loc) < 2:
        return None
    table = _walk(model, loc[:-1])[1]
    if table is None or get_origin(table.annotation) is not dict:
        return None
    node: Any = data
    for part in loc[:-1]:
        node = node.get(part, {}) if isinstance(node, dict) else {}
    if loc[-1] in node:
        return None
    held = ", ".join(str(k) for k in node) or "none"
    where = ".".join(str(p) for p in loc[:-1])
    return f"the case has no {where} {loc[-1]!r} (it has: {held}); a new name changes nothing"


def unit_of(model: type[BaseModel], loc: tuple[str | int, ...]) -> str:
    """The unit of the field at ``loc`` (from its description), "" if it has none."""
    return _unit(_walk(model, loc)[1])


def is_integer_field(model: type[BaseModel], loc: tuple[str | int, ...]) -> bool:
    """Does the field at ``loc`` take integers only (``int``, ``int | None``)?"""
    info = _walk(model, loc)[1]
    annotation = getattr(info, "annotation", None)
    kinds = set(getattr(annotation, "__args__", None) or (annotation,)) - {type(None)}
    return kinds == {int}


def _unit(info: Any) -> str:
    unit = unit_in(getattr(info, "description", None))
    return unit if unit not in (None, "-") else ""


def unit_in(description: str | None) -> str | None:
    """The unit in brackets at the end of a field's description ("-" for a pure
    number), None where it names none."""
    match = _UNIT.search(description or "")
    return match.group(1) if match else None


def without_unit(description: str) -> str:
    """A field's description without the unit at its end."""
    return _UNIT.sub("", description).strip()


def _show(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return "an array"
    return repr(value)


#: Error kinds that say "this value is of another type": a union member that gives
#: only these is not the member the user meant.
_TYPE_KINDS = {
    "float_type", "int_type", "bool_type", "string_type", "list_type", "dict_type",
    "model_type", "model_attributes_type", "literal_error", "int_from_float", "float_parsing",
}  # fmt: skip


def _split_loc(
    model: type[BaseModel], loc: tuple[str | int, ...], kind: str
) -> tuple[tuple[str | int, ...], tuple[int, tuple[str, ...]]]:
    """The key path of an error without pydantic's tags (union members such as
    ``list[float]``, validator names), and where in it the tags stood."""
    clean: list[str | int] = []
    tags: list[str] = []
    where = -1
    current: Any = model
    free_key = False  # the next part is a key of a dict[str, X] field
    for index, part in enumerate(loc):
        if isinstance(part, int):
            clean.append(part)
            continue
        if free_key:
            clean.append(part)
            free_key = False
            continue
        fields = getattr(current, "model_fields", None)
        last = index == len(loc) - 1
        if fields is not None and part in fields:
            clean.append(part)
            current = _inner_model(fields[part].annotation)
            free_key = _is_dict(fields[part].annotation)
        elif fields is not None and last and kind == "extra_forbidden":
            clean.append(part)  # the unknown key itself
        elif fields is None and current is None and not _looks_like_tag(part):
            clean.append(part)  # a key of a table of free keys ([parameters], [expect])
        else:
            if where < 0:
                where = len(clean)
            tags.append(part)
            if _inner_model_named(current, part) is not None:
                current = _inner_model_named(current, part)
    return tuple(clean), (where, tuple(tags))


def _is_dict(annotation: Any) -> bool:
    """Is the annotation ``dict[...]`` or ``dict[...] | None``?"""
    if getattr(annotation, "__origin__", None) is dict:
        return True
    return any(_is_dict(a) for a in getattr(annotation, "__args__", ()) or () if a is not str)


def _looks_like_tag(part: str) -> bool:
    return "[" in part or part.startswith(("function-", "union")) or part in _SCALAR_TAGS


_SCALAR_TAGS = {"float", "int", "str", "bool", "none"}


def _inner_model_named(current: Any, name: str) -> Any:
    """A union member model named by a pydantic tag (a model class name)."""
    if isinstance(current, type) and current.__name__ == name:
        return current
    for arg in getattr(current, "__args__", ()) or ():
        if isinstance(arg, type) and arg.__name__ == name:
            return arg
    return None


def _one_union_member(model: type[BaseModel], errors: list[Any]) -> list[Any]:
    """Where a value fits no member of a union, pydantic reports every member's
    errors; keep the member the user most likely meant: the fewest type errors
    (``[1, nan]`` for ``list[float] | list[list[float]]`` is a list of floats with a
    bad value, not a table with three wrong rows), then the fewest errors."""
    members: dict[tuple[str | int, ...], dict[tuple[str, ...], list[tuple[int, Any]]]] = {}
    kept: list[tuple[int, Any]] = []
    for index, err in enumerate(errors):
        clean, (where, tags) = _split_loc(model, tuple(err["loc"]), err["type"])
        entry = (index, {**err, "loc": clean})
        members_tags = tuple(t for t in tags if not t.startswith(("function-", "union")))
        if not members_tags:
            kept.append(entry)
            continue
        members.setdefault(clean[:where], {}).setdefault(members_tags, []).append(entry)
    for groups in members.values():
        ranked = sorted(
            groups.values(),
            key=lambda g: (sum(e["type"] in _TYPE_KINDS for _, e in g), len(g)),
        )
        kept.extend(ranked[0])
    return [err for _, err in sorted(kept, key=lambda entry: entry[0])]


def _problem_from_error(model: type[BaseModel], case: CaseText, err: Any) -> Problem:
    loc: tuple[str | int, ...] = tuple(err["loc"])
    kind = err["type"]
    value = err.get("input")
    ctx = err.get("ctx") or {}
    if isinstance(ctx.get("error"), FieldError):
        loc = (*loc, *ctx["error"].loc)
    holder, info = _walk(model, loc)
    unit = _unit(info)
    unit_text = f" {unit}" if unit else ""
    path = dotted(loc)
    line = case.line_of(loc)

    if kind == "extra_forbidden":
        names = list(getattr(holder, "model_fields", {}) or {})
        key = str(loc[-1]) if loc else ""
        close = difflib.get_close_matches(key, names, n=1, cutoff=0.6)
        hint = f"did you mean '{close[0]}'?" if close else f"allowed keys: {', '.join(names)}"
        return Problem(f"unknown key; {hint}", path, line)
    if kind == "missing":
        what = (getattr(info, "description", None) or "").strip()
        return Problem(f"required key is missing{f' ({what})' if what else ''}", path, line)
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        op = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<"}.get(kind, "<=")
        bound = next(iter(ctx.values()))
        bound = f"{bound:g}" if isinstance(bound, float) else bound
        return Problem(f"got {_show(value)}; must be {op} {bound}{unit_text}", path, line)
    if kind == "finite_number":
        return Problem(f"got {_show(value)}; must be a finite number{unit_text}", path, line)
    if kind in ("float_type", "int_type", "float_parsing", "int_from_float"):
        want = "an integer" if kind.startswith("int") else "a number"
        return Problem(f"got {_show(value)}; expected {want}{unit_text}", path, line)
    if kind == "literal_error":
        return Problem(f"got {_show(value)}; allowed: {ctx.get('expected', '')}", path, line)
    if kind == "string_type":
        return Problem(f"got {_show(value)}; expected a string", path, line)
    if kind in ("model_type", "model_attributes_type", "dict_type"):
        return Problem(f"got {_show(value)}; expected a table", path, line)
    if kind == "list_type":
        return Problem(f"got {_show(value)}; expected an array", path, line)
    if kind in ("too_short", "too_long"):
        return Problem(err["msg"].lower(), path, line)
    if kind == "value_error":
        message = str(ctx.get("error", err["msg"]))
        return Problem(message, path, line)
    return Problem(f"got {_show(value)}; {err['msg'].lower()}", path, line)


# --------------------------------------------------------------------- line finder


def _split_key(key: str) -> tuple[str, ...]:
    parts = []
    for piece in re.findall(r'"[^"]*"|\'[^\']*\'|[^.]+', key):
        parts.append(piece.strip().strip("\"'"))
    return tuple(p for p in parts if p)


def _key_lines(text: str) -> dict[tuple[str | int, ...], int]:
    """Map each table and key path to its first line (arrays of tables indexed)."""
    lines: dict[tuple[str | int, ...], int] = {}
    counts: dict[tuple[str | int, ...], int] = {}  # arrays of tables: their items so far
    current: tuple[str | int, ...] = ()

    def resolve(name: tuple[str, ...]) -> tuple[str | int, ...]:
        """A header's path, each array of tables on the way at its last item
        ([a.b] after [[a]] is a table of a's last item)."""
        out: tuple[str | int, ...] = ()
        for part in name:
            out = (*out, part)
            if out in counts:
                out = (*out, counts[out] - 1)
        return out

    depth = 0  # brackets a multi-line array value leaves open: its lines are no keys
    quote: str | None = None  # the multi-line string a value leaves open
    for number, line in enumerate(text.splitlines(), start=1):
        if quote is not None:
            if line.count(quote) % 2:
                quote = None
            continue
        if depth > 0:
            depth = max(0, depth + _depth_change(line))
            continue
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        header = _HEADER.match(line)
        if header and "=" not in header.group(2):
            name = _split_key(header.group(2))
            if header.group(1) == "[[":
                array = (*resolve(name[:-1]), name[-1])
                index = counts.get(array, 0)
                counts[array] = index + 1
                current = (*array, index)
                lines.setdefault(array, number)
            else:
                current = resolve(name)
            lines.setdefault(current, number)
            continue
        key = _KEY.match(line)
        if key:
            lines.setdefault((*current, *_split_key(key.group(1))), number)
            value = line[key.end() :]
            for mark in ('"""', "'''"):
                if value.count(mark) % 2:
                    quote = mark
            if quote is None:
                depth = max(0, _depth_change(value))
    return lines


_STRING = re.compile(r"\"(?:[^\"\\]|\\.)*\"|'[^']*'")


def _depth_change(code: str) -> int:
    """Brackets a line of a value opens minus those it closes (strings and a
    comment left out)."""
    code = _STRING.sub('""', code).split("#", 1)[0]
    return code.count("[") + code.count("{") - code.count("]") - code.count("}")


# ------------------------------------------------------------ keys of case data


def set_key(data: dict[str, Any], loc: tuple[str | int, ...], value: Any) -> None:
    """Set ``data[loc] = value``, making missing tables on the way."""
    node: Any = data
    for part in loc[:-1]:
        if isinstance(part, int):
            if not isinstance(node, list) or part >= len(node):
                raise KeyError(part)
            node = node[part]
        else:
            if not isinstance(node, dict):
                raise KeyError(part)
            node = node.setdefault(part, {})
    last = loc[-1]
    if isinstance(last, int):
        if not isinstance(node, list) or last >= len(node):
            raise KeyError(last)
        node[last] = value
    elif isinstance(node, dict):
        node[last] = value
    else:
        raise KeyError(last)


def get_key(data: Any, loc: tuple[str | int, ...]) -> Any:
    """``data[loc]``, or None where the path is not there."""
    node = data
    for part in loc:
        try:
            node = node[part]
        except (KeyError, IndexError, TypeError):
            return None
    return node
