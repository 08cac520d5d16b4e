"""The JSON Schema of every problem's case file (issue 32.1): it takes every shipped
case, and it and pydantic refuse the same generated bad inputs: a value below each
bound, a value of the wrong type, an unknown key in each section."""

from __future__ import annotations

import copy
import json
import tomllib
from functools import cache
from pathlib import Path
from typing import Any

import pytest

from mdcalc.cli.schema import problem_schema
from mdcalc.errors import InputError
from mdcalc.input.casefile import CaseText, validate
from mdcalc.problems import PROBLEMS
from mdcalc.runs.study.spec import StudySpec
from tests.conftest import CASES, assert_no_traceback

jsonschema = pytest.importorskip("jsonschema")


@cache
def validator(problem: str) -> Any:
    schema = problem_schema(problem)
    jsonschema.Draft202012Validator.check_schema(schema)  # a schema by the meta-schema
    return jsonschema.Draft202012Validator(schema)


def shipped(problem: str) -> list[tuple[Path, dict[str, Any]]]:
    found = []
    for path in sorted(CASES.rglob("*.toml")):
        data = tomllib.loads(path.read_text("utf-8"))
        if data.get("problem") == problem:
            found.append((path, data))
    return found


@pytest.mark.parametrize("problem", list(PROBLEMS))
def test_every_shipped_case_is_valid_by_the_schema(problem):
    cases = shipped(problem)
    assert cases, f"no shipped case of {problem}"
    for path, data in cases:
        errors = [e.message for e in validator(problem).iter_errors(data)]
        assert errors == [], f"{path.relative_to(CASES)}: {errors[:3]}"


def test_the_shipped_cases_cover_quantity_strings_and_studies():
    """The claims above hold for the files that use what the schema adds to the models."""
    texts = [p.read_text("utf-8") for p in CASES.rglob("*.toml")]
    assert any('kN*m/rad"' in t or 'N*m/deg"' in t for t in texts)  # quantity strings
    assert any("[study]" in t for t in texts)
    assert any("[expect." in t or "[expect]" in t for t in texts)


# ------------------------------------------------------------------ generated bad inputs


def node_at(schema: dict[str, Any], loc: tuple[str | int, ...]) -> dict[str, Any]:
    """The schema of the value at ``loc``, $refs resolved."""
    definitions = schema["$defs"]

    def resolve(node: dict[str, Any]) -> dict[str, Any]:
        while "$ref" in node:
            node = definitions[node["$ref"].rsplit("/", 1)[1]]
        return node

    node = resolve(schema)
    for part in loc:
        if isinstance(part, int):
            arrays = [n for n in [node, *node.get("anyOf", [])] if "items" in n]
            node = resolve(arrays[0]["items"])
        elif part in node.get("properties", {}):
            node = resolve(node["properties"][part])
        else:
            node = resolve(node["additionalProperties"])
    return node


def leaves(data: Any, loc: tuple[str | int, ...] = ()) -> list[tuple[tuple[str | int, ...], Any]]:
    """Every key that holds a value (a number, a string, a list of numbers)."""
    if isinstance(data, dict):
        return [leaf for key, value in data.items() for leaf in leaves(value, (*loc, key))]
    if isinstance(data, list) and data and all(isinstance(v, dict) for v in data):
        return [leaf for i, value in enumerate(data) for leaf in leaves(value, (*loc, i))]
    return [(loc, data)]


def sections(data: Any, loc: tuple[str | int, ...] = ()) -> list[tuple[str | int, ...]]:
    """Every table of the file (the top level included)."""
    if isinstance(data, dict):
        return [loc] + [s for key, value in data.items() for s in sections(value, (*loc, key))]
    if isinstance(data, list):
        return [s for i, value in enumerate(data) for s in sections(value, (*loc, i))]
    return []


def below(node: dict[str, Any]) -> Any:
    """A value just outside the lower bound of ``node``; None if it has none."""
    integer = "integer" in node.get("type", [])
    if "exclusiveMinimum" in node:
        return int(node["exclusiveMinimum"]) if integer else float(node["exclusiveMinimum"])
    if "minimum" in node:
        low = node["minimum"]
        return int(low) - 1 if integer else low - max(abs(low), 1.0) * 0.5
    return None


def wrong_type(node: dict[str, Any]) -> Any:
    """A value of a type the key does not take."""
    types: set[str] = set()
    for option in [node, *node.get("anyOf", [])]:
        kind = option.get("type", [])
        types |= {kind} if isinstance(kind, str) else set(kind)
    if "integer" in types:
        types.add("number")  # 1.5 is no integer, but that is a bound of sorts: not a type
    for value, kind in ((True, "boolean"), (1.5, "number"), ("text", "string"), ([1.0], "array")):
        if kind not in types:
            return value
    return {"a": 1.0}


def mutations(data: dict[str, Any], schema: dict[str, Any]) -> list[tuple[str, dict[str, Any]]]:
    """(what, the file with it) for each generated bad input of ``data``."""
    out = []
    for loc, value in leaves(data):
        if loc[0] in ("saved", "problem") or loc[0] == "study" and len(loc) > 2:
            continue  # results of an earlier run (not read); the problem picks the schema
        node = node_at(schema, loc)
        if isinstance(value, list) and value and not isinstance(value[0], dict):
            item = node_at(schema, (*loc, 0))
            low = below(item)
            if low is not None:
                out.append((f"{loc}[0] = {low!r}", _set(data, (*loc, 0), low)))
        elif isinstance(value, int | float) and not isinstance(value, bool):
            low = below(node)
            if low is not None:
                out.append((f"{loc} = {low!r}", _set(data, loc, low)))
        out.append((f"{loc} of the wrong type", _set(data, loc, wrong_type(node))))
    for loc in sections(data):
        free = node_at(schema, loc).get("additionalProperties") is not False
        if loc and loc[0] == "saved" or free:
            continue  # a table of names the engineer chooses (mechanism's [parameters])
        out.append((f"unknown key in {loc}", _set(data, (*loc, "no_such_key"), 1.0)))
    return out


def _set(data: dict[str, Any], loc: tuple[str | int, ...], value: Any) -> dict[str, Any]:
    changed = copy.deepcopy(data)
    node: Any = changed
    for part in loc[:-1]:
        node = node[part]
    node[loc[-1]] = value
    return changed


def pydantic_refuses(problem: str, data: dict[str, Any]) -> bool:
    module = PROBLEMS[problem].load()
    scene = {k: v for k, v in data.items() if k != "study"}
    try:
        validate(module.Case, CaseText(Path("case.toml"), "", scene))
        if "study" in data:
            StudySpec.model_validate(data["study"])
    except (InputError, ValueError):
        return True
    return False


@pytest.mark.parametrize("problem", list(PROBLEMS))
def test_schema_and_pydantic_refuse_the_same_bad_inputs(problem):
    schema = problem_schema(problem)
    checked = 0
    for path, data in shipped(problem):
        assert not pydantic_refuses(problem, data), path
        for what, bad in mutations(data, schema):
            errors = list(validator(problem).iter_errors(bad))
            assert errors, f"{path.name}: the schema takes {what}"
            assert pydantic_refuses(problem, bad), f"{path.name}: pydantic takes {what}"
            checked += 1
    assert checked > 50


def test_the_generated_inputs_include_each_kind():
    schema = problem_schema("mine-hoist")
    data = tomllib.loads((CASES / "mine-hoist" / "seed_1025.toml").read_text("utf-8"))
    kinds = [what for what, _ in mutations(data, schema)]
    assert "('hoist', 'drum_inertia') = 0.0" in kinds  # exclusiveMinimum 0
    assert "('hoist', 'drum_inertia') of the wrong type" in kinds
    assert "unknown key in ('hoist',)" in kinds
    assert "unknown key in ()" in kinds


# ------------------------------------------------------------------ the schema's content


def test_quantity_strings_are_taken_where_mdcalc_converts_them():
    check = validator("mine-hoist")
    data = tomllib.loads((CASES / "mine-hoist" / "seed_1025.toml").read_text("utf-8"))
    data["hoist"]["rope_stiffness"] = "893.45 kN*m/rad"
    assert not list(check.iter_errors(data))
    for bad in ("kN*m/rad", "18 609.2 N*m/rad", "18609,2 N*m/rad", ""):
        data["hoist"]["rope_stiffness"] = bad
        assert list(check.iter_errors(data)), bad
    # a key whose unit depends on another (N·m/radⁿ) takes a plain number only
    clutch = problem_schema("variator")
    text = json.dumps(clutch, ensure_ascii=False)
    assert "radⁿ" in text


def test_each_key_says_its_unit_bounds_and_default():
    from mdcalc.input.schema import key_rows

    rows = {row.key: row for row in key_rows(problem_schema("acceleration"))}
    assert rows["gravity"].unit == "m/s²"
    assert rows["gravity"].default == "9.80665"
    assert rows["gravity"].allowed == "> 0"
    assert rows["transmission.efficiency"].allowed == "(0, 1]"
    assert rows["vehicle.mass"].default == "required"
    assert rows["drag"].default == "optional"
    assert rows["study.inputs.<key>.tol"].description.startswith("Tolerance")
    assert rows["expect.<result>.rel"].allowed == "≥ 0"
    units = {row.unit for p in PROBLEMS for row in key_rows(problem_schema(p))}
    assert not {u for u in units if "^" in u or "*" in u}, units  # as a person reads them
    assert {"kg·m²", "N·m/rad", "m/s²", "rpm"} <= units


def test_schema_command(cli, tmp_path):
    out = tmp_path / "s.json"
    result = cli("schema", "braking", "-o", out)
    assert result.exit_code == 0, result.stderr
    assert json.loads(out.read_text("utf-8")) == problem_schema("braking")
    again = cli("schema", "braking", "-o", out)
    assert again.exit_code == 2 and "--force" in again.stderr
    printed = cli("schema", "braking")
    assert json.loads(printed.stdout) == problem_schema("braking")
    keys = cli("schema", "braking", "--keys")
    assert keys.exit_code == 0
    assert "vehicle.mass" in keys.stdout and "kg" in keys.stdout
    unknown = cli("schema", "nope")
    assert unknown.exit_code == 2 and "unknown problem 'nope'" in unknown.stderr
    assert_no_traceback(unknown)
