"""``--save FILE.toml`` (issue 9.3): the case as read, with its results, written
atomically; never over an existing file without ``--force``."""

from __future__ import annotations

import math
import tomllib

import pytest

from mdcalc.problems import PROBLEMS
from tests.conftest import CASES, assert_no_traceback, strict_json

LECTURE = CASES / "braking" / "lecture.toml"


def test_saved_file_holds_inputs_and_the_json_results(cli, tmp_path):
    out = tmp_path / "saved.toml"
    result = cli("braking", LECTURE, "--save", out)
    assert result.exit_code == 0, result.stderr
    saved = tomllib.loads(out.read_text(encoding="utf-8"))
    source = tomllib.loads(LECTURE.read_text(encoding="utf-8"))
    assert {k: v for k, v in saved.items() if k != "saved"} == source
    results = strict_json(cli("braking", LECTURE, "--json").stdout)["results"]
    assert set(saved["saved"]["results"]) == set(results)
    for key, entry in results.items():
        value = saved["saved"]["results"][key]
        if isinstance(entry["value"], float):
            assert math.isclose(value, entry["value"], rel_tol=1e-15), key
        else:
            assert value == entry["value"], key
        if entry["unit"]:
            assert saved["saved"]["units"][key] == entry["unit"]
    assert saved["saved"]["status"] == "ok"
    assert saved["saved"]["case"] == str(LECTURE)


def test_saved_methods_rows_carry_values_errors_and_times(cli, tmp_path):
    out = tmp_path / "saved.toml"
    assert cli("braking", LECTURE, "--save", out).exit_code == 0
    rows = tomllib.loads(out.read_text(encoding="utf-8"))["saved"]["methods"]["stop"]
    reference = [row for row in rows if row.get("reference")]
    assert len(reference) == 1
    others = [row for row in rows if not row.get("reference") and "stopping_distance" in row]
    assert others and all("stopping_distance_rel_error" in row for row in others)
    assert all(row["seconds"] > 0 for row in others)
    ref = reference[0]["stopping_distance"]
    for row in others:  # the saved error is the error of the saved value
        expected = abs(row["stopping_distance"] - ref) / abs(ref)
        assert row["stopping_distance_rel_error"] == pytest.approx(expected, rel=1e-9)


def test_a_saved_file_runs_again_with_the_same_results(cli, tmp_path):
    out = tmp_path / "saved.toml"
    assert (
        cli("coupling", CASES / "coupling" / "example_8_1_units.toml", "--save", out).exit_code == 0
    )
    again = cli("coupling", out, "--json")
    assert again.exit_code == 0, again.stderr
    first = tomllib.loads(out.read_text(encoding="utf-8"))
    assert first["coupling"]["stiffness"] == "52.5 N*m/deg"  # as written, not converted
    values = strict_json(again.stdout)["results"]
    for key, value in first["saved"]["results"].items():
        assert values[key]["value"] == value, key
    # Saving the saved file replaces its [saved] table, not nests another.
    twice = tmp_path / "twice.toml"
    assert cli("coupling", out, "--save", twice).exit_code == 0
    assert "saved" not in tomllib.loads(twice.read_text(encoding="utf-8"))["saved"]


def test_no_overwrite_without_force(cli, tmp_path):
    out = tmp_path / "saved.toml"
    out.write_text("keep", encoding="utf-8")
    result = cli("braking", LECTURE, "--save", out)
    assert result.exit_code == 2
    assert f"{out}: error: --save: the file exists; use --force to overwrite it" in result.stderr
    assert result.stdout == ""  # refused before anything was computed
    assert out.read_text(encoding="utf-8") == "keep"
    assert cli("braking", LECTURE, "--save", out, "--force").exit_code == 0
    assert "saved" in tomllib.loads(out.read_text(encoding="utf-8"))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["saved.toml"]  # no temp file left


def test_save_refuses_another_suffix_and_the_case_itself(cli, tmp_path):
    result = cli("braking", LECTURE, "--save", tmp_path / "saved.json")
    assert result.exit_code == 2 and "--save: use a file ending .toml" in result.stderr
    copy = tmp_path / "case.toml"
    copy.write_text(LECTURE.read_text(encoding="utf-8"), encoding="utf-8")
    result = cli("braking", copy, "--save", copy, "--force")
    assert result.exit_code == 2 and "would overwrite the case file itself" in result.stderr
    assert_no_traceback(result)


def test_save_of_a_scene_without_answer_records_why(cli, tmp_path):
    out = tmp_path / "saved.toml"
    result = cli("hoist", CASES / "hoist" / "cannot_start.toml", "--save", out)
    assert result.exit_code == 3
    saved = tomllib.loads(out.read_text(encoding="utf-8"))["saved"]
    assert saved["status"] == "no-answer" and saved["message"]


@pytest.mark.parametrize("name", sorted(PROBLEMS))
def test_every_template_runs_and_saves(name, cli, tmp_path):
    case = tmp_path / "new.toml"
    assert cli("new", name, "-o", case).exit_code == 0
    out = tmp_path / "saved.toml"
    result = cli(name, case, "--save", out)
    assert result.exit_code == 0, result.stderr
    assert cli(name, out).exit_code == 0
