"""Starter case files that teach: ``mdcalc new PROBLEM -o case.toml``.

The starter is the problem's template (a scene that runs as it is) written with every
key of its schema beside it: each value with its unit and one-line meaning, the keys
left to their defaults and the other forms of a section commented out (``# ``), and
every optional section commented out with example values (its own optional keys
twice, ``# # ``, so that uncommenting the section leaves them as they are). Which
commented key is an alternative of which, and which optional section needs which, is
not written down anywhere twice: the starter tries each against the problem's own
validation and says what it found (``instead of speed_kmh``, ``needs [drive]``).

Pure: text in, text out; the caller writes the file.
"""

from __future__ import annotations

import itertools
import json
from pathlib import Path
from typing import Any

from pydantic import BaseModel

from mdcalc.errors import InputError
from mdcalc.input.casefile import CaseText, get_key, unit_in, validate, without_unit
from mdcalc.input.schema import strict_definition

#: The column where a value's comment starts (longer lines put it two spaces after).
COMMENT_COLUMN = 34
#: In a commented optional block, the keys shown but not uncommented with it.
OTHER = "_or"
#: An optional block's own words on what it needs, where uncommenting sections is not
#: enough (the mine hoist's height sweep: [rope] with EA in place of two stiffnesses).
NOTE = "_needs"
#: Where a starter's numbers come from (a key of ``starter_extras``, not a section).
SOURCE = "_source"
#: Root keys that are no part of a scene.
NOT_SCENE = ("expect", "saved", "study")


def starter_text(
    problem: str,
    summary: str,
    model: type[BaseModel],
    schema: dict[str, Any],
    template: dict[str, Any],
    extras: dict[str, Any],
    schema_file: str,
) -> str:
    """The starter case of ``problem``: ``template`` active, ``extras`` commented out
    (keys of a section the template has, or optional sections and their keys)."""
    writer = _Writer(model, schema, template, extras)
    head = [
        f"#:schema ./{schema_file}",
        f"# mdcalc {problem}: {summary}",
        f"# {template.get('title', problem)}. The numbers: {extras.get(SOURCE, 'illustrative')};",
        "# the commented ones are examples.",
        "# A line '# key = ...' is optional: its default, or another form of its section",
        "# (the comment says which); remove '# ' to use it. Every key, its unit and range:",
        f"# mdcalc schema {problem} --keys. Run: mdcalc {problem} case.toml",
        "",
    ]
    return "\n".join(head + writer.lines()) + "\n"


class _Writer:
    def __init__(
        self,
        model: type[BaseModel],
        schema: dict[str, Any],
        template: dict[str, Any],
        extras: dict[str, Any],
    ) -> None:
        self.model = model
        self.schema = schema
        self.template = template
        self.extras = extras

    # ------------------------------------------------------------------ validation
    def problems(self, data: dict[str, Any]) -> list[str]:
        """What the problem's validation says of ``data`` ([] when it is valid)."""
        try:
            validate(self.model, CaseText(Path("starter.toml"), "", data))
        except InputError as exc:
            return [p.message for p in exc.problems] or ["invalid"]
        return []

    def valid(self, data: dict[str, Any]) -> bool:
        return not self.problems(data)

    def needs(self, name: str) -> list[str]:
        """The other optional sections ``name`` needs to validate (fewest first)."""
        optional = [k for k, v in self.extras.items() if k not in self.template and _table(v)]
        others = [k for k in optional if k != name]
        for size in range(min(len(others), 3) + 1):
            for group in itertools.combinations(others, size):
                data = dict(self.template)
                for section in (name, *group):
                    data[section] = _active(self.extras[section])
                if self.valid(data):
                    return list(group)
        return []

    def lone(
        self, context: dict[str, Any], where: tuple[str | int, ...], key: str, value: Any
    ) -> bool:
        """Is ``key`` neither valid alone nor in place of one key beside it?"""
        section = get_key(context, where)
        if self.valid(_with(context, where, {**section, key: value})):
            return False
        return not any(
            self.valid(
                _with(
                    context, where, {**{k: v for k, v in section.items() if k != other}, key: value}
                )
            )  # fmt: skip
            for other in section
        )

    def label(
        self,
        context: dict[str, Any],
        where: tuple[str | int, ...],
        key: str,
        value: Any,
        shown: dict[str, Any],
        node: dict[str, Any],
    ) -> str:
        """What a commented key is, tried against the validation in ``context`` (the
        case with its section uncommented): optional; instead of a key beside it (or of
        the section's keys that have no default); with the other commented keys of a
        form (``shown``), instead of some; else what the validation says of it alone."""
        section = get_key(context, where)
        shown = {k: v for k, v in shown.items() if not _table(v)}  # keys, not sub-tables
        alone = self.problems(_with(context, where, {**section, key: value}))
        if not alone:
            clash = [
                other
                for other, its in shown.items()
                if other != key
                and other not in section
                and self.valid(_with(context, where, {**section, other: its}))
                and not self.valid(_with(context, where, {**section, key: value, other: its}))
            ]
            return f"optional; not with {', '.join(clash)}" if clash else "optional"
        for other in section:
            rest = {k: v for k, v in section.items() if k != other}
            if self.valid(_with(context, where, {**rest, key: value})):
                return f"instead of {other}"
        properties = node.get("properties", {})
        kept = {k: v for k, v in section.items() if "default" in properties.get(k, {})}
        kept |= {k: v for k, v in section.items() if k in node.get("required", [])}
        dropped = [k for k in section if k not in kept]
        if dropped and self.valid(_with(context, where, {**kept, key: value})):
            return "instead of " + ", ".join(dropped)
        group = {k: v for k, v in shown.items() if k != key and self.lone(context, where, k, v)}
        # the group, or the group less one of its keys (another spelling of the same)
        groups = [group] + [{k: v for k, v in group.items() if k != out} for out in group]
        for members in (g for g in groups if g):
            for base, instead in ((section, []), (kept, dropped)):
                if self.valid(_with(context, where, {**base, key: value, **members})):
                    with_ = "with " + ", ".join(members)
                    return f"{with_}, instead of {', '.join(instead)}" if instead else with_
        others = [k for k in shown if k != key and k not in section]
        for size in (1, 2):
            for combo in itertools.combinations(others, size):
                given = {k: shown[k] for k in combo}
                if self.valid(_with(context, where, {**section, key: value, **given})):
                    return "optional, with " + ", ".join(combo)
        return f"another form; alone, mdcalc says: {alone[0]}"

    # ------------------------------------------------------------------ text
    def lines(self) -> list[str]:
        out: list[str] = []
        root = self.schema
        scalars, tables = self._split(root)
        shown = {"base": "other_case.toml", **self.extras}  # a case to take keys from
        for key in scalars:
            if key in NOT_SCENE:
                continue
            out += self._key_line(
                root["properties"][key], key, self.template, shown, (), False,
                self.template, root,
            )  # fmt: skip
        for key in tables:
            if key in NOT_SCENE:
                continue
            out += self._table(key, (key,), root["properties"][key], self.template, self.extras)
        return out

    def _table(
        self,
        key: str,
        where: tuple[str, ...],
        node: dict[str, Any],
        active: dict[str, Any],
        extras: dict[str, Any],
    ) -> list[str]:
        target = self._resolve(node)
        array = target.get("type") == "array"
        body = self._resolve(target["items"]) if array else target
        header = f"[[{'.'.join(where)}]]" if array else f"[{'.'.join(where)}]"
        about = _first_sentence(node.get("description") or body.get("description"))
        if key in active:
            items = active[key] if array else [active[key]]
            more = extras.get(key, [{}] if array else {})
            more = more if isinstance(more, list) else [more]
            out = []
            for index, item in enumerate(items):
                spot: tuple[str | int, ...] = (*where, index) if array else where
                out += ["", header + (f"  # {about}" if about and index == 0 else "")]
                out += self._body(body, spot, item, more[min(index, len(more) - 1)], False)
            return out
        if key not in extras:
            return []  # a section with no example: `mdcalc schema --keys` lists it
        items = extras[key] if array else [extras[key]]
        context = dict(self.template)
        note = items[0].get(NOTE)
        needs = self.needs(key) if len(where) == 1 and note is None else []
        for section in needs:
            context[section] = _active(self.extras[section])
        spot = (*where, 0) if array else where
        context = _with(context, spot, _active(items[0]))
        need = "; needs " + ", ".join(f"[{n}]" for n in needs) if needs else ""
        need = f"; {note}" if note else need
        lines = ["", f"# {header}  # optional{need}" + (f": {about}" if about else "")]
        lines += self._body(body, spot, _active(items[0]), items[0].get(OTHER, {}), True, context)
        return lines

    def _body(
        self,
        node: dict[str, Any],
        where: tuple[str | int, ...],
        active: dict[str, Any],
        extras: dict[str, Any],
        commented: bool,
        context: dict[str, Any] | None = None,
    ) -> list[str]:
        context = context if context is not None else self.template
        scalars, tables = self._split(node)
        out: list[str] = []
        if not node.get("properties"):  # a table of names the engineer chooses
            for key, value in active.items():
                out.append(("# " if commented else "") + f"{key} = {toml_value(value)}")
            return out
        for key in scalars:
            out += self._key_line(
                node["properties"][key], key, active, extras, where, commented, context, node
            )
        for key in tables:
            sub = extras.get(key, {})
            path = (*(str(w) for w in where if isinstance(w, str)), key)
            out += self._table(
                key, path, node["properties"][key], active, {key: sub} if sub else {}
            )
        return out

    def _key_line(
        self,
        node: dict[str, Any],
        key: str,
        active: dict[str, Any],
        extras: dict[str, Any],
        where: tuple[str | int, ...],
        commented: bool,
        context: dict[str, Any],
        parent: dict[str, Any],
    ) -> list[str]:
        node = self._resolve(node)
        description = " ".join(str(node.get("description") or "").split())
        unit = unit_in(description)
        meaning = without_unit(description) if unit is not None else description
        note = f"{unit} · {meaning}" if unit not in (None, "", "-") else meaning
        lead = "# " if commented else ""
        if key in active:
            return [_line(lead + f"{key} = {toml_value(active[key])}", note)]
        if key in extras:
            label = (
                self.label(context, where, key, extras[key], extras, parent)
                if where
                else "optional"
            )
            return [_line(lead + f"# {key} = {toml_value(extras[key])}", f"{note} ({label})")]
        if "default" in node and node["default"] is not None:
            return [_line(lead + f"# {key} = {toml_value(node['default'])}", f"{note} (default)")]
        return []

    def _split(self, node: dict[str, Any]) -> tuple[list[str], list[str]]:
        scalars, tables = [], []
        for key, value in node.get("properties", {}).items():
            target = self._resolve(value)
            items = self._resolve(target.get("items", {})) if "items" in target else {}
            named = isinstance(target.get("additionalProperties"), dict)  # [parameters]
            is_table = target.get("type") == "object" and ("properties" in target or named)
            if (is_table and key not in ("expect", "saved")) or items.get("type") == "object":
                tables.append(key)
            else:
                scalars.append(key)
        return scalars, tables

    def _resolve(self, node: dict[str, Any]) -> dict[str, Any]:
        ref = node.get("$ref")
        if isinstance(ref, str):
            return {**strict_definition(self.schema, ref), **node, "$ref": None}
        return node


def _first_sentence(text: str | None) -> str:
    """A section's description in a line: its first sentence, without a unit."""
    text = without_unit(" ".join((text or "").split()))
    return text.split(". ")[0].rstrip(".") if text else ""


def _line(code: str, comment: str) -> str:
    """``key = value  # comment``; an array of arrays too long for a line gets a line a
    row (each under the line's comment marks, if any)."""
    key, _, value = code.partition(" = ")
    if len(code) > 80 and value.startswith("[") and "=" not in value:
        lead = key[: len(key) - len(key.lstrip("# "))]
        items = json.loads(value)
        head = f"{key} = [" + (f"  # {comment}" if comment else "")
        if value.startswith("[["):
            body = [f"{lead}    {toml_value(row)}," for row in items]
        else:  # a flat list: as many a line as fit in 80 columns
            body, row = [], ""
            for item in items:
                piece = toml_value(item) + ","
                if row and len(lead) + 4 + len(row) + 1 + len(piece) > 80:
                    body.append(f"{lead}    {row}")
                    row = ""
                row = f"{row} {piece}" if row else piece
            body.append(f"{lead}    {row}")
        return "\n".join([head, *body, f"{lead}]"])
    if not comment:
        return code
    return f"{code.ljust(COMMENT_COLUMN - 2)}  # {comment}"


def _table(value: Any) -> bool:
    return isinstance(value, dict) or (
        isinstance(value, list) and bool(value) and all(isinstance(v, dict) for v in value)
    )


def _active(value: Any) -> Any:
    """An example section without the keys it only shows (``_or``)."""
    if isinstance(value, list):
        return [_active(v) for v in value]
    if isinstance(value, dict):
        return {k: _active(v) for k, v in value.items() if k not in (OTHER, NOTE)}
    return value


def _with(data: Any, where: tuple[str | int, ...], value: Any) -> Any:
    """``data`` with ``value`` at ``where``, copied along the path (a missing table or
    array of tables on the way is made)."""
    if not where:
        return value
    head, rest = where[0], where[1:]
    if isinstance(head, int):
        items = list(data) if isinstance(data, list) else []
        items += [{}] * (head + 1 - len(items))
        items[head] = _with(items[head], rest, value)
        return items
    table = dict(data) if isinstance(data, dict) else {}
    table[head] = _with(table.get(head), rest, value)
    return table


def toml_value(value: Any) -> str:
    """A value as TOML writes it on one line."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(v)}" for k, v in value.items()) + " }"
    raise TypeError(f"no TOML for {value!r}")
