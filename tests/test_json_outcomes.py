"""JSON for every outcome (issue 33, item 4): with ``--json`` a problem command writes
one JSON object on stdout whatever happens: the report (computed or no answer), or
the record ``run --json`` writes for an input error, field for field; exit codes and
the stderr line are those without ``--json``. A list result is a JSON array."""

from __future__ import annotations

import json

import pytest

from mdcalc.problems import PROBLEMS
from tests.conftest import CASES, strict_json

#: A shipped case of each problem that runs, and the shipped no-answer cases.
RUNS = {
    "hoist": "hoist/crane.toml",
    "acceleration": "acceleration/lecture.toml",
    "braking": "braking/dry.toml",
    "coupling": "coupling/example_8_1.toml",
    "mine-hoist": "mine-hoist/seed_1025.toml",
    "variator": "variator/two_disk_absorber.toml",
    "mechanism": "mechanism/linear_torque.toml",
    "resonance": "resonance/two_mass_crank.toml",
    "clutch": "clutch/fig2_differentiated.toml",
    "mount": "mount/example_9_1.toml",
}
NO_ANSWER = {
    "hoist": "hoist/cannot_start.toml",
    "acceleration": "acceleration/steep_hill.toml",
    "coupling": "coupling/resonance_undamped.toml",
    "mine-hoist": "mine-hoist/cannot_lift.toml",
    "variator": "variator/absorber_resonance.toml",
    "mechanism": "mechanism/stall.toml",
    "resonance": "resonance/undamped.toml",
    "mount": "mount/resonance_undamped.toml",
}


def test_every_problem_is_covered():
    assert set(RUNS) == set(PROBLEMS)


@pytest.mark.parametrize("problem", list(PROBLEMS))
def test_an_input_error_writes_the_run_record(cli, write_case, problem):
    text = (CASES / RUNS[problem]).read_text("utf-8")
    bad = write_case("no_such_key = 1.0\n" + text)  # a key in the root
    alone = cli(problem, bad)
    result = cli(problem, bad, "--json")
    assert result.exit_code == alone.exit_code == 2
    assert result.stderr == alone.stderr and alone.stdout == ""
    record = strict_json(result.stdout)
    batch = cli("run", bad, "--json", "--jobs", "1")
    assert record == json.loads(batch.stdout.splitlines()[0])  # field for field
    assert record["status"] == "input-error" and record["case"] == str(bad)
    assert record["errors"][0]["path"] == "no_such_key"


@pytest.mark.parametrize("problem", list(PROBLEMS))
def test_a_computed_case_and_a_no_answer_write_their_reports(cli, problem):
    done = cli(problem, CASES / RUNS[problem], "--json")
    assert done.exit_code == 0 and strict_json(done.stdout)["status"] == "ok"
    if problem in NO_ANSWER:
        path = CASES / NO_ANSWER[problem]
        none = cli(problem, path, "--json")
        assert none.exit_code == 3
        assert strict_json(none.stdout)["status"] == "no-answer"
        assert none.stderr.count("no answer") == 1


def test_a_file_that_names_no_problem_writes_a_record_too(cli, write_case):
    path = write_case('title = "no problem"\n')
    result = cli(path, "--json")
    assert result.exit_code == 2
    record = strict_json(result.stdout)
    assert record["status"] == "input-error" and record["errors"][0]["path"] == "problem"


def test_a_list_result_is_a_json_array(cli):
    done = cli("acceleration", CASES / "acceleration" / "lecture.toml", "--json")
    results = json.loads(done.stdout)["results"]
    assert results["gear_ratios"]["value"] == [3.8, 2.3, 1.5, 1.0]  # the case's U_i
    assert all(isinstance(d, float) for d in results["rotating_mass_factors"]["value"])
    text = cli("acceleration", CASES / "acceleration" / "lecture.toml").stdout
    assert "3.8 / 2.3 / 1.5 / 1" in text  # the reader's form is unchanged
