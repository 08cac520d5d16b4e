"""The command-line contract: exit codes, messages on stderr, JSON on stdout."""

from __future__ import annotations

import json
import os
import re

import pytest

from tests.conftest import CASES, assert_no_traceback, run_script

LECTURE = CASES / "braking" / "lecture.toml"

BRAKING = """\
problem = "braking"

[vehicle]
mass = {mass}
initial_speed = 27.8

[road]
surface = "dry-asphalt"
"""


def test_help_lists_every_problem(cli):
    from mdcalc.problems import PROBLEMS

    result = cli("--help")
    assert result.exit_code == 0
    for name in [*PROBLEMS, "check", "new"]:
        assert name in result.stdout


def test_help_shows_each_summary_whole_and_true(cli):
    """Issue 32.5: no summary cut off with '...'; each command's options are its own."""
    from mdcalc.cli.app import app

    result = cli("--help")
    assert "..." not in result.stdout.split("Commands:")[1]
    text = " ".join(result.stdout.split()).replace("- ", "-")  # click wraps at hyphens
    for command in app.registered_commands:
        summary = " ".join((command.short_help or "").split())
        assert summary and summary in text, command.name
    study = " ".join(cli("study", "--help").stdout.split())
    assert "--save" not in study and "per file" not in study
    assert "Let --plot, --out and --report overwrite a file." in study
    assert "the nominal scene's calculation report" in study
    sweep = " ".join(cli("sweep", "--help").stdout.split())
    assert "per file" not in sweep
    assert "mdcalc CASE.toml" in text
    braking = " ".join(cli("braking", "--help").stdout.split())
    assert "mdcalc schema braking --keys" in braking  # where its keys are listed


def test_lecture_braking_prints_the_lecture_numbers_and_the_lock_warning():
    # Real console script: what the issue promises a user sees.
    done = run_script("braking", LECTURE)
    assert done.returncode == 0, done.stderr
    out = " ".join(done.stdout.split())
    assert "35.257" in out and "2.5365" in out  # (7.48): 27.8²·1500/(2·16440), 27.8·1500/16440
    assert "35.3 m in 2.54 s of (7.48)" in out
    assert "wheels lock" in out


def test_json_is_valid_and_not_wrapped_when_piped():
    done = run_script("braking", LECTURE, "--json")
    assert done.returncode == 0
    document = json.loads(done.stdout)
    assert document["problem"] == "braking" and document["status"] == "ok"
    assert document["format"] == 2
    # (7.48) by hand: t = V0·m/(k·P_D), S = V0·t/2
    t = 27.8 * 1500 / (10 * 1644)
    assert document["results"]["lecture_time"]["value"] == pytest.approx(t, rel=1e-12)
    assert document["results"]["lecture_distance"]["value"] == pytest.approx(27.8 * t / 2, 1e-12)
    assert document["results"]["lecture_distance"]["unit"] == "m"
    methods = [s for s in document["sections"] if s["kind"] == "methods"]
    assert methods and all(r["seconds"] >= 0 for r in methods[0]["rows"])
    assert done.stderr == ""


def test_json_and_text_carry_the_same_results(cli):
    text = cli("braking", LECTURE)
    document = json.loads(cli("braking", LECTURE, "--json").stdout)
    for result in document["results"].values():
        assert result["label"] in text.stdout


def test_no_colour_when_piped_or_no_color(tmp_path):
    env = {**os.environ, "NO_COLOR": "1", "FORCE_COLOR": ""}
    done = run_script("hoist", CASES / "hoist" / "crane.toml", env=env)
    assert done.returncode == 0
    assert "\x1b[" not in done.stdout


def test_misspelt_key_names_the_place_and_suggests(cli, write_case):
    path = write_case(BRAKING.format(mass=1500.0).replace("mass =", "mas ="))
    result = cli("braking", path)
    assert result.exit_code == 2
    assert f"{path}:4: error: vehicle.mas: unknown key; did you mean 'mass'?" in result.stderr
    assert "Traceback" not in result.stderr and result.stdout == ""


def test_negative_mass_gives_path_value_and_bound(cli, write_case):
    path = write_case(BRAKING.format(mass=-5.0))
    result = cli("braking", path)
    assert result.exit_code == 2
    assert f"{path}:4: error: vehicle.mass: got -5.0; must be > 0 kg" in result.stderr


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        ("true", "got true; expected a number kg"),
        ("nan", "got nan; must be a finite number kg"),
        ("inf", "got inf; must be a finite number kg"),
        # A string is a quantity (issue 9); one without its unit is not taken as kg.
        ('"1500"', "got '1500'; a number in quotes without a unit: write 1500 or '1500 kg'"),
    ],
)
def test_strict_numbers(cli, write_case, value, expected):
    path = write_case(BRAKING.format(mass=value))
    result = cli("braking", path)
    assert result.exit_code == 2
    assert expected in result.stderr


def test_broken_toml_gives_line_and_column(cli, write_case):
    path = write_case('problem = "braking"\n\n[vehicle]\nmass = 1500.0\nspeed = [1,\n')
    result = cli("braking", path)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{path}:")
    assert ": error: TOML syntax:" in result.stderr
    # tomllib reports the position of the error; it must reach the message.
    place = result.stderr.split(": error:")[0]
    assert place.count(":") >= 1


def test_broken_toml_line_and_column_are_exact(cli, write_case):
    path = write_case('problem = "braking"\nx = = 3\n')
    result = cli("braking", path)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{path}:2:5: error: TOML syntax:")


def test_broken_toml_at_the_end_points_just_past_the_last_character(cli, write_case):
    # The text ends inside the array: line 3, column 4 (just after "  2").
    path = write_case('problem = "braking"\na = [1,\n  2')
    result = cli("braking", path)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{path}:3:4: error: TOML syntax:")


def test_missing_file(cli, tmp_path):
    result = cli("hoist", tmp_path / "nope.toml")
    assert result.exit_code == 2
    assert "nope.toml: error: no such file" in result.stderr


def test_binary_garbage_and_empty_file(cli, write_case, tmp_path):
    garbage = tmp_path / "garbage.toml"
    garbage.write_bytes(b"\xff\xfe\x00\x01problem")
    assert cli("hoist", garbage).exit_code == 2
    empty = write_case("")
    result = cli("hoist", empty)
    assert result.exit_code == 2
    assert "problem: missing" in result.stderr


def test_case_for_another_problem(cli):
    result = cli("hoist", LECTURE)
    assert result.exit_code == 2
    assert "this case is for 'braking', not 'hoist'" in result.stderr


def test_missing_section_and_exactly_one_of(cli, write_case):
    path = write_case('problem = "braking"\n[vehicle]\nmass = 1.0\ninitial_speed = 3.0\n')
    result = cli("braking", path)
    assert result.exit_code == 2
    assert "road: required key is missing" in result.stderr
    path = write_case(BRAKING.format(mass=1.0) + "adhesion = 0.5\n")
    result = cli("braking", path)
    assert result.exit_code == 2
    assert "give exactly one of surface or adhesion in [road]" in result.stderr


def test_no_answer_exits_3_with_reason():
    done = run_script("hoist", CASES / "hoist" / "cannot_start.toml")
    assert done.returncode == 3
    assert "error: no answer: the motor cannot start the load" in done.stderr
    assert "79.15 N·m" in done.stderr  # M_c = 1000·9.80665·1/(151.84·0.816)
    assert "Traceback" not in done.stderr


def test_internal_error_exits_70_with_one_line(cli, monkeypatch):
    from mdcalc.problems import braking

    def broken(case):  # not arithmetic: that is a scene out of float range (exit 3)
        raise RuntimeError("boom")

    monkeypatch.setattr(braking, "solve", broken)
    result = cli("braking", LECTURE)
    assert result.exit_code == 70
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "internal error: RuntimeError: boom" in lines[0]
    result = cli("braking", LECTURE, "--debug")
    assert result.exit_code == 70
    assert "Traceback" in result.stderr


def test_check_passes_on_shipped_cases(cli):
    # Every case file runs in test_cases.py and in `make test`'s `mdcalc check cases`;
    # here the command itself, on two folders.
    result = cli("check", CASES / "braking", CASES / "clutch")
    assert result.exit_code == 0, result.stdout + result.stderr
    assert " 0 failed" in result.stdout


def test_check_fails_on_a_wrong_value_and_goes_on_after_a_bad_file(cli, tmp_path):
    text = LECTURE.read_text(encoding="utf-8")
    wrong = text.replace("value = 2.54,", "value = 2.64,")
    assert wrong != text
    (tmp_path / "a_wrong.toml").write_text(wrong, encoding="utf-8")
    result = cli("check", tmp_path)
    assert result.exit_code == 1
    assert "FAIL" in result.stdout and "lecture_time" in result.stdout
    (tmp_path / "b_broken.toml").write_text("problem = \n", encoding="utf-8")
    (tmp_path / "c_good.toml").write_text(text, encoding="utf-8")
    result = cli("check", tmp_path)
    assert result.exit_code == 2  # unreadable file
    assert "b_broken.toml:1" in result.stderr
    assert "2 case files checked" in result.stdout  # checking went on past the bad file


def test_check_unknown_result_key_fails(cli, tmp_path):
    text = LECTURE.read_text(encoding="utf-8")
    extra = text + 'no_such = { value = 1.0, rel = 0.1, source = "test" }\n'
    (tmp_path / "x.toml").write_text(extra, encoding="utf-8")
    result = cli("check", tmp_path)
    assert result.exit_code == 1
    assert "no such result" in result.stdout


@pytest.mark.parametrize("problem", ["hoist", "braking"])
def test_new_writes_a_case_that_runs(cli, tmp_path, problem):
    path = tmp_path / f"{problem}.toml"
    assert cli("new", problem, "-o", path).exit_code == 0
    assert cli(problem, path).exit_code == 0
    again = cli("new", problem, "-o", path)
    assert again.exit_code == 2 and "use --force" in again.stderr
    assert cli("new", problem, "-o", path, "--force").exit_code == 0


def test_new_to_stdout_and_unknown_problem(cli):
    result = cli("new", "braking")
    assert result.exit_code == 0 and 'problem = "braking"' in result.stdout
    result = cli("new", "nosuch")
    assert result.exit_code == 2 and "unknown problem 'nosuch'" in result.stderr


def test_closed_pipe_is_not_an_internal_error():
    """`mdcalc ... --json | head` closes stdout early: no 'internal error' (exit 141)."""
    import subprocess
    import sys
    from pathlib import Path

    mdcalc = Path(sys.executable).parent / "mdcalc"
    proc = subprocess.run(
        f"'{mdcalc}' resonance cases/resonance/inline_six.toml --json | head -c 10",
        shell=True,
        capture_output=True,
        text=True,
        cwd=Path(__file__).resolve().parent.parent,
        timeout=60,
    )
    assert "internal error" not in proc.stderr
    assert proc.stdout == '{\n  "mdcal'


# Valid scenes whose numbers leave double precision (issue 20's probe of shipped cases
# pushed into exp overflow): exit 3 in one plain line, never exit 70, and no NaN or
# inf in the output. (Inputs of 1e-300 or 5e-324, which did the same, are now below
# the models' floor: exit 2, test_a_number_closer_to_0_than_the_floor_is_exit_2.)
OUT_OF_RANGE = [
    ("mechanism", "mechanism/crank_press.toml", "w0", "1e-12"),
]

BELOW_FLOOR = [
    ("coupling", "extreme/coupling_heavily_damped_pulse.toml", "driven_inertia", "5e-324"),
    ("hoist", "hoist/crane.toml", "lifting_speed", "1e-300"),
    ("hoist", "hoist/crane.toml", "motor_speed_rpm", "2.2e-308"),
]


@pytest.mark.parametrize(("problem", "case", "key", "value"), BELOW_FLOOR)
def test_a_number_closer_to_0_than_the_floor_is_exit_2(cli, write_case, problem, case, key, value):
    text = (CASES / case).read_text(encoding="utf-8")
    edited = re.sub(rf"(?m)^{key} = .*$", f"{key} = {value}", text, count=1)
    assert edited != text
    result = cli(problem, write_case(edited))
    assert result.exit_code == 2
    assert f"{key}: got {float(value)!r}; closer to 0 than mdcalc computes with" in result.stderr
    assert_no_traceback(result)


@pytest.mark.parametrize(("problem", "case", "key", "value"), OUT_OF_RANGE)
def test_a_scene_beyond_float_range_is_no_answer(cli, write_case, problem, case, key, value):
    text = (CASES / case).read_text(encoding="utf-8")
    edited = re.sub(rf"(?m)^{key} = .*$", f"{key} = {value}", text, count=1)
    assert edited != text
    for json_flag in ([], ["--json"]):
        result = cli(problem, write_case(edited), *json_flag)
        assert result.exit_code == 3, (result.stdout, result.stderr)
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and "range of floating-point arithmetic" in lines[0], lines
        assert not re.search(r"\b(nan|inf|NaN|Infinity)\b", result.stdout)


@pytest.mark.parametrize("damping", [5e5, 1e8, 1e12])
def test_a_heavily_over_damped_pulse_answers_as_a_first_order_lag(cli, write_case, damping):
    # J1 = J2 = 2, c = 900: β = √(c·(1/J1 + 1/J2)) = 30 rad/s, ζ = α·(1/J1 + 1/J2)/(2β).
    # Far over critical the coupling is a first-order lag of rate r = β/(ζ + √(ζ² - 1)):
    # a pulse of T = 0.3 s peaks at its end at 1 - exp(-r·T) of the static twist. The
    # exact propagator overflowed here (exit 70) and the ODE rows took minutes.
    import math
    import time

    text = (CASES / "extreme/coupling_heavily_damped_pulse.toml").read_text(encoding="utf-8")
    edited = re.sub(r"(?m)^damping = .*$", f"damping = {damping!r}", text, count=1)
    edited = edited[: edited.index("[expect]")]
    beta, zeta = 30.0, damping * 1.0 / (2 * 30.0)
    expected = -math.expm1(-0.3 * beta / (zeta + math.sqrt(zeta * zeta - 1.0)))
    start = time.perf_counter()
    result = cli("coupling", write_case(edited), "--json")
    assert time.perf_counter() - start < 5.0
    assert result.exit_code == 0, result.stderr
    document = json.loads(result.stdout)
    assert document["results"]["pulse_dynamic_factor"]["value"] == pytest.approx(expected, rel=1e-6)
    assert document["budget"]["cut"] == []


def _pulse_case(key: str, value: float) -> str:
    text = (CASES / "extreme/coupling_heavily_damped_pulse.toml").read_text(encoding="utf-8")
    edited = re.sub(rf"(?m)^{key} = .*$", f"{key} = {value!r}", text, count=1)
    assert edited != text
    return edited[: edited.index("[expect]")]


def test_extreme_couplings_answer_the_physics_in_seconds(cli, write_case):
    # J1 = 2, J2 = 2, c = 900, α = 3000, a 0.3 s pulse (the shipped extreme case).
    import math
    import time

    # J2 = 1e-18 (the models' floor): β and ζ near 1e10, yet the slow rate
    # β/(ζ + √(ζ² - 1)) → c/α = 0.3 1/s: a first-order lag, 1 - exp(-0.09). (At 1e-300,
    # before the floor, ζβ squared overflowed: a silent 1.)
    # c = 1e12: β = 1e6 rad/s, ζ = 3000/(2·1e6); the rise's overshoot has died long
    # before the pulse ends: the step peak 1 + exp(-πζ/√(1 - ζ²)).
    zeta = 3000.0 / 2e6
    expected = {
        ("driven_inertia", 1e-18): -math.expm1(-0.3 * 900.0 / 3000.0),
        ("stiffness", 1e12): 1.0 + math.exp(-math.pi * zeta / math.sqrt(1.0 - zeta * zeta)),
    }
    for (key, value), factor in expected.items():
        start = time.perf_counter()
        result = cli("coupling", write_case(_pulse_case(key, value)), "--json")
        assert time.perf_counter() - start < 10.0
        assert result.exit_code == 0, result.stderr
        got = json.loads(result.stdout)["results"]["pulse_dynamic_factor"]["value"]
        assert got == pytest.approx(factor, rel=1e-6), key
