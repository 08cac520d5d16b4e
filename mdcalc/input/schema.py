"""A JSON Schema of a problem's case file, made from its pydantic model.

The schema is what an editor reads (Taplo, Even Better TOML: ``#:schema`` on a case's
first line) to complete keys and flag errors as the engineer types, and what
``mdcalc schema PROBLEM --keys`` prints as a table. It covers the file as engineers
write it:

* every section and key of the problem, with its description (the unit in brackets
  at its end, as a person reads it: ``kg·m²``, ``N·m/rad``), bounds and default;
  no unknown key (``additionalProperties: false``, as ``extra="forbid"``);
* a quantity string wherever mdcalc converts one (``"893.45 kN*m/rad"``): a number
  key takes ``{"type": ["number", "string"]}``, its bounds apply to the number and
  a pattern (a number, then a unit) to the string;
* ``problem``, ``title``, ``[expect]``, ``[saved]`` and the sections a caller adds
  (``[study]``).

What it cannot say, the program still checks: the rules between keys (exactly one
of two alternatives, gears in falling order), the unit of a quantity string, and the
range of every number (0, or 1e-18 to 1e18 in magnitude).

Pure: no I/O; pint is asked only whether a description's unit is one it converts to.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import Any

from pydantic import BaseModel

from mdcalc.input.casefile import unit_in, without_unit

DIALECT = "https://json-schema.org/draft/2020-12/schema"
#: A quantity string: a number (no spaces, no comma), then a unit.
QUANTITY_PATTERN = r"^\s*[-+]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?\s*[^\s\d.,;].*$"
#: For a pure number a quoted number alone is taken too ("0.8", "5 %").
NUMBER_PATTERN = r"^\s*[-+]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?\s*([^\s\d.,;].*)?$"
_REF = "#/$defs/"


def case_schema(
    model: type[BaseModel], problem: str, sections: dict[str, type[BaseModel]] | None = None
) -> dict[str, Any]:
    """The JSON Schema of a case file of ``problem`` (its pydantic ``model``), with
    ``sections`` added as optional tables (``{"study": StudySpec}``)."""
    schema = model.model_json_schema(ref_template=_REF + "{model}")
    definitions = schema.setdefault("$defs", {})
    for name, section in (sections or {}).items():
        extra = section.model_json_schema(ref_template=_REF + "{model}")
        for key, value in extra.pop("$defs", {}).items():
            if key in definitions and definitions[key] != value:
                raise ValueError(f"two models named {key} in the schema of {problem}")
            definitions[key] = value
        title = extra.get("title", name)
        if title in definitions and definitions[title] != extra:
            raise ValueError(f"two models named {title} in the schema of {problem}")
        definitions[title] = extra
        schema["properties"][name] = {"$ref": _REF + title, "description": extra.get("description")}
    _tidy(schema)
    schema["properties"]["base"] = {
        "type": "string",
        "description": "A case file whose keys this one takes where it gives none (tables "
        "merged key by key; not its [expect], [saved] or [study]): a path relative to this "
        "file [-]",
    }
    # as a case file reads: its problem, title and base, the scene, then what checks it
    properties = schema["properties"]
    first = [k for k in ("problem", "title", "base") if k in properties]
    last = [k for k in ("expect", "saved", *(sections or {})) if k in properties]
    middle = [k for k in properties if k not in first and k not in last]
    schema["properties"] = {k: properties[k] for k in first + middle + last}
    _partial_with_base(schema, own=("expect", "saved", *(sections or {})))
    head = {
        "$schema": DIALECT,
        "title": f"mdcalc {problem} case file",
        "description": (
            f"A case file of `mdcalc {problem}`: SI units (or a quantity string, "
            '"893.45 kN*m/rad"), the unit of each key in brackets at the end of its '
            "description. Made by `mdcalc schema " + problem + "`."
        ),
    }
    schema.pop("title", None)
    schema.pop("description", None)
    return {**head, **schema}


#: The name of a section's schema without its required keys (for a file with a base).
PARTIAL = "Partial"


def _partial_with_base(schema: dict[str, Any], own: tuple[str, ...]) -> None:
    """A file with ``base =`` may leave out any key its base gives: its sections are
    checked against copies of their schemas without ``required`` (keys, types, bounds
    and no unknown key still hold), and the required keys apply only to a file without
    a base (``if``/``else``). Its own tables (``own``: [expect], [study]) stay whole."""
    definitions = schema["$defs"]
    for name, definition in list(definitions.items()):
        partial = _renamed_refs(copy.deepcopy(definition))
        partial.pop("required", None)
        definitions[name + PARTIAL] = partial
    properties = schema["properties"]
    strict = {k: v for k, v in properties.items() if k not in own and _refers(v)}
    for key in strict:
        properties[key] = _renamed_refs(copy.deepcopy(properties[key]))
    schema["if"] = {"required": ["base"]}
    schema["else"] = {"required": schema.pop("required", []), "properties": strict}


def _refers(node: Any) -> bool:
    """Does ``node`` name a section's schema anywhere inside?"""
    if isinstance(node, dict):
        return "$ref" in node or any(_refers(v) for v in node.values())
    return isinstance(node, list) and any(_refers(v) for v in node)


def _renamed_refs(node: Any) -> Any:
    """``node`` with every ``$ref`` to a section's schema turned to its partial copy,
    but in an array's items: an array from the base is replaced whole, never merged."""
    if isinstance(node, dict):
        return {
            k: (
                v + PARTIAL
                if k == "$ref" and isinstance(v, str)
                else v
                if k == "items"
                else _renamed_refs(v)
            )
            for k, v in node.items()
        }
    if isinstance(node, list):
        return [_renamed_refs(v) for v in node]
    return node


def strict_definition(schema: dict[str, Any], ref: str) -> dict[str, Any]:
    """The schema a ``$ref`` names, its required keys included (a partial copy's
    original)."""
    name = ref.rsplit("/", 1)[1]
    definitions = schema.get("$defs", {})
    if name.endswith(PARTIAL) and name[: -len(PARTIAL)] in definitions:
        name = name[: -len(PARTIAL)]
    return definitions[name]


def _tidy(node: Any) -> None:
    """Shape pydantic's schema as a TOML file is written: no null (a key left out is
    its default), no titles made from key names, quantity strings beside numbers."""
    if isinstance(node, list):
        for item in node:
            _tidy(item)
        return
    if not isinstance(node, dict):
        return
    for key in ("properties", "$defs"):
        for value in node.get(key, {}).values():
            _tidy(value)
            value.pop("title", None)
    options = node.get("anyOf")
    if options is not None:
        kept = [option for option in options if option.get("type") != "null"]
        if node.get("default", 0) is None:
            del node["default"]
        if len(kept) == 1:
            del node["anyOf"]
            node.update({k: v for k, v in kept[0].items() if k not in node})
        else:
            node["anyOf"] = kept
    for key in ("items", "additionalProperties", "anyOf", "oneOf", "allOf", "prefixItems"):
        if isinstance(node.get(key), dict | list):
            _tidy(node[key])
    if "description" in node and _converts(node["description"]):
        plain = unit_in(node["description"]) in ("", "-")
        _take_quantities(node, NUMBER_PATTERN if plain else QUANTITY_PATTERN)


def _take_quantities(node: dict[str, Any], pattern: str) -> None:
    """A key's numbers, alone, in lists, in a table of named numbers or in the
    alternatives of its type, may be quantity strings (what mdcalc converts to the
    key's unit)."""
    if node.get("type") in ("number", "integer"):
        node["type"] = [node["type"], "string"]
        node["pattern"] = pattern
    for option in node.get("anyOf", []):
        _take_quantities(option, pattern)
    for key in ("items", "additionalProperties"):
        if isinstance(node.get(key), dict):
            _take_quantities(node[key], pattern)


def _converts(description: str | None) -> bool:
    """Does mdcalc convert a quantity string to this description's unit?"""
    unit = unit_in(description)
    if unit is None:
        return False
    if unit in ("", "-"):
        return True
    from mdcalc.input.quantities import field_unit, registry

    try:
        registry().Unit(field_unit(unit))
    except Exception:  # "N·m/radⁿ", "field unit": a plain number only
        return False
    return True


#: How a table of named entries shows its names: ``expect.<result>.rel``.
PLACEHOLDERS = {"expect": "<result>", "inputs": "<key>", "limits": "<result>"}


@dataclass(frozen=True)
class KeyRow:
    """One key of a case file, as ``mdcalc schema PROBLEM --keys`` shows it."""

    key: str
    unit: str
    default: str
    allowed: str
    description: str


def key_rows(schema: dict[str, Any]) -> list[KeyRow]:
    """Every key of the schema, section by section, in the models' order: a table of
    tables (``[[transmission.gears]]``) as ``section[].key``."""
    definitions = schema.get("$defs", {})
    rows: list[KeyRow] = []

    def walk(node: dict[str, Any], prefix: str, required: set[str]) -> None:
        for name, value in node.get("properties", {}).items():
            key = f"{prefix}{name}"
            target = _resolve(value, definitions)
            if target.get("type") == "object" and "properties" in target:
                rows.append(_row(key, value | target, name in required, section=True))
                walk(target, key + ".", set(target.get("required", [])))
                continue
            items = _resolve(target.get("items", {}), definitions) if "items" in target else {}
            if target.get("type") == "array" and items.get("type") == "object":
                rows.append(_row(key + "[]", value | target, name in required, section=True))
                walk(items, key + "[].", set(items.get("required", [])))
                continue
            entry = target.get("additionalProperties")
            entry = _resolve(entry, definitions) if isinstance(entry, dict) else {}
            if entry.get("type") == "object" and "properties" in entry:
                rows.append(_row(key, value | target, name in required, section=True))
                inner = f"{key}.{PLACEHOLDERS.get(name, '<name>')}."
                walk(entry, inner, set(entry.get("required", [])))
                continue
            rows.append(_row(key, value | target, name in required))

    walk(schema, "", set(schema.get("else", {}).get("required", schema.get("required", []))))
    return rows


def _resolve(node: dict[str, Any], definitions: dict[str, Any]) -> dict[str, Any]:
    ref = node.get("$ref")
    if isinstance(ref, str) and ref.startswith(_REF):
        target = strict_definition({"$defs": definitions}, ref)
        return {**target, **{k: v for k, v in node.items() if k != "$ref"}}
    return node


def _row(key: str, node: dict[str, Any], required: bool, section: bool = False) -> KeyRow:
    description = " ".join(str(node.get("description") or "").split())
    unit = unit_in(description)
    text = without_unit(description) if unit is not None else description
    if section:
        text = text.split(". ")[0].rstrip(".")
    if section:
        default = "required" if required else "optional"
    elif "default" in node:
        default = _show(node["default"])
    else:
        default = "required" if required else ""
    return KeyRow(key, "" if unit in (None, "-") else unit, default, _allowed(node), text)


def _allowed(node: dict[str, Any]) -> str:
    """The range or choices of a key, as a reader writes them: (0, 1], ≥ 2, one of …"""
    if "const" in node:
        return _show(node["const"])
    if "enum" in node:
        return "one of " + ", ".join(_show(v) for v in node["enum"])
    low = ("(", node["exclusiveMinimum"]) if "exclusiveMinimum" in node else None
    low = low or ("[", node.get("minimum"))
    high = (")", node["exclusiveMaximum"]) if "exclusiveMaximum" in node else None
    high = high or ("]", node.get("maximum"))
    if low[1] is None and high[1] is None:
        return ""
    if high[1] is None:
        return f"{'>' if low[0] == '(' else '≥'} {_show(low[1])}"
    if low[1] is None:
        return f"{'<' if high[0] == ')' else '≤'} {_show(high[1])}"
    return f"{low[0]}{_show(low[1])}, {_show(high[1])}{high[0]}"


def _show(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e6:
        return repr(value)
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, list | dict):
        return str(copy.deepcopy(value)).replace("'", '"').replace("True", "true")
    return f"{value:g}" if isinstance(value, float) else str(value)
