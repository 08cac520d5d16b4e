"""``base = "other.toml"``: a case or study file that takes the keys of another case
where it gives none (issue 32: the schema covers it)."""

from __future__ import annotations

import json
import tomllib

import pytest

from mdcalc.cli.schema import problem_schema
from tests.conftest import CASES, assert_no_traceback

LECTURE = CASES / "braking" / "lecture.toml"


def results(cli, *args) -> dict:
    done = cli(*args, "--json")
    assert done.exit_code == 0, done.stderr
    return {k: v["value"] for k, v in json.loads(done.stdout)["results"].items()}


def test_a_file_takes_its_base_and_gives_its_own_keys(cli, write_case, tmp_path):
    heavier = write_case(f'base = "{LECTURE}"\n[vehicle]\nmass = 1600.0\n', "heavier.toml")
    # the same scene written out whole: the lecture's keys, the mass replaced
    data = tomllib.loads(LECTURE.read_text("utf-8"))
    whole = LECTURE.read_text("utf-8").replace("mass = 1500.0", "mass = 1600.0")
    assert data["vehicle"]["mass"] == 1500.0 and "mass = 1600.0" in whole
    (tmp_path / "whole.toml").write_text(whole.split("[expect]")[0], "utf-8")
    assert results(cli, heavier) == results(cli, "braking", tmp_path / "whole.toml")


def test_tables_merge_key_by_key_and_the_rest_is_replaced(tmp_path):
    from mdcalc.input.casefile import read_case

    base = tmp_path / "base.toml"
    base.write_text(
        'problem = "resonance"\ntitle = "base"\n[chain]\ninertias = [1.0, 2.0, 3.0]\n'
        "stiffnesses = [10.0, 20.0]\n[expect]\nx = { value = 1.0, rel = 0.1, source = 's' }\n"
        "[study]\nsamples = 10\n",
        "utf-8",
    )
    top = tmp_path / "top.toml"
    top.write_text('base = "base.toml"\n[chain]\ninertias = [5.0]\n', "utf-8")
    data = read_case(top).data
    assert data["chain"] == {"inertias": [5.0], "stiffnesses": [10.0, 20.0]}  # an array whole
    assert data["title"] == "base" and data["problem"] == "resonance"
    assert "expect" not in data and "study" not in data and "base" not in data


def test_a_chain_of_bases_and_a_study_on_a_base(cli, tmp_path):
    (tmp_path / "heavier.toml").write_text(
        f'base = "{LECTURE}"\n[vehicle]\nmass = 1600.0\n', "utf-8"
    )
    study = tmp_path / "study.toml"
    study.write_text(
        'base = "heavier.toml"\ntitle = "two deep"\n[study]\nsamples = 200\nseed = 1\n'
        '[study.inputs."vehicle.mass"]\nnominal = 1600.0\ntol = "±5 %"\n',
        "utf-8",
    )
    done = cli(study, "--json")  # mdcalc CASE.toml: the problem from the base, then study
    assert done.exit_code == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["kind"] == "study" and out["problem"] == "braking"


@pytest.mark.parametrize(
    ("files", "says"),
    [
        ({"a.toml": 'base = "b.toml"\n', "b.toml": 'base = "a.toml"\n'}, "a cycle of bases"),
        ({"a.toml": 'base = "missing.toml"\n'}, "no such case file"),
        ({"a.toml": "base = 3\n[vehicle]\nmass = 1.0\n"}, "a path to a case file, as a string"),
        ({"a.toml": f'problem = "hoist"\nbase = "{LECTURE}"\n'}, "its base"),
    ],
)
def test_a_base_that_cannot_be_is_exit_2(cli, tmp_path, files, says):
    for name, text in files.items():
        (tmp_path / name).write_text(text, "utf-8")
    result = cli("braking", tmp_path / "a.toml")
    assert result.exit_code == 2
    assert says in result.stderr, result.stderr
    assert_no_traceback(result)


def test_a_saved_case_is_whole(cli, write_case, tmp_path):
    heavier = write_case(f'base = "{LECTURE}"\n[vehicle]\nmass = 1600.0\n', "heavier.toml")
    saved = tmp_path / "saved.toml"
    assert cli("braking", heavier, "--save", saved).exit_code == 0
    data = tomllib.loads(saved.read_text("utf-8"))
    assert "base" not in data and data["vehicle"]["mass"] == 1600.0
    assert data["brakes"]["force_multiple"] == 10.0  # from the base
    assert cli("braking", saved).exit_code == 0


def test_the_schema_lets_a_file_with_a_base_leave_out_keys():
    jsonschema = pytest.importorskip("jsonschema")
    check = jsonschema.Draft202012Validator(problem_schema("braking"))
    partial = {"base": "lecture.toml", "vehicle": {"initial_speed": 20.0}}
    assert list(check.iter_errors(partial)) == []
    alone = {"problem": "braking", "vehicle": {"initial_speed": 20.0}, "road": {}}
    messages = " ".join(e.message for e in check.iter_errors(alone))
    assert "'mass' is a required property" in messages
    bad = {"base": "lecture.toml", "vehicle": {"mass": -1.0, "mas": 1.0}}
    assert len(list(check.iter_errors(bad))) >= 2  # bounds and unknown keys still hold


def test_a_base_path_that_cannot_be_read_is_exit_2(cli, tmp_path):
    (tmp_path / "long.toml").write_text(f'base = "{"a" * 5000}"\n', "utf-8")
    (tmp_path / "loop1").symlink_to(tmp_path / "loop2")
    (tmp_path / "loop2").symlink_to(tmp_path / "loop1")
    (tmp_path / "loop.toml").write_text('base = "loop1"\n', "utf-8")
    for name in ("long.toml", "loop.toml"):
        result = cli("braking", tmp_path / name)
        assert result.exit_code == 2, result.stderr
        assert ":1: error: base: cannot read" in result.stderr
        assert_no_traceback(result)


def test_a_bad_value_from_the_base_is_named_in_the_base(cli, tmp_path):
    base = tmp_path / "base.toml"
    base.write_text(
        'problem = "braking"\n[vehicle]\nmass = -1500.0\ninitial_speed_kmh = 100.0\n'
        '[road]\nsurface = "dry-asphalt"\n',
        "utf-8",
    )
    child = tmp_path / "child.toml"
    child.write_text('base = "base.toml"\n[vehicle]\ninitial_speed = 20.0\n', "utf-8")
    result = cli("braking", child)
    assert result.exit_code == 2
    assert f"vehicle.mass: got -1500.0; must be > 0 kg (set in its base {base}:3)" in (
        result.stderr
    )
    mismatch = tmp_path / "mm.toml"
    mismatch.write_text('# a hoist?\nproblem = "hoist"\nbase = "base.toml"\n', "utf-8")
    result = cli("hoist", mismatch)
    assert result.exit_code == 2 and f"{mismatch}:2: error: problem:" in result.stderr


def test_the_schema_keeps_arrays_of_tables_whole_and_quoted_plain_numbers():
    jsonschema = pytest.importorskip("jsonschema")
    hoist = jsonschema.Draft202012Validator(problem_schema("hoist"))
    partial_item = {"base": "crane.toml", "drive": {"shafts": [{"name": "gear"}]}}
    assert list(hoist.iter_errors(partial_item))  # an array from a base is replaced whole
    braking = jsonschema.Draft202012Validator(problem_schema("braking"))
    data = tomllib.loads(LECTURE.read_text("utf-8"))
    data["road"] = {"adhesion": "0.8", "resistance": "1.5 %"}  # pure numbers, quoted
    assert list(braking.iter_errors(data)) == []
    mechanism = jsonschema.Draft202012Validator(problem_schema("mechanism"))
    press = tomllib.loads((CASES / "mechanism" / "crank_press.toml").read_text("utf-8"))
    press["parameters"] = {name: "400" for name in press["parameters"]}
    assert list(mechanism.iter_errors(press)) == []
