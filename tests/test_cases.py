"""Every shipped case file meets its [expect] table (the same check `mdcalc check` runs)."""

from __future__ import annotations

import pytest

from mdcalc.check import CheckOutcome, check_file, collect
from tests.conftest import CASES

FILES = collect([CASES])


def test_every_problem_has_cases():
    from mdcalc.problems import PROBLEMS

    for name in PROBLEMS:
        assert list((CASES / name).glob("*.toml")), f"no cases for {name}"


@pytest.mark.parametrize("path", FILES, ids=[str(p.relative_to(CASES)) for p in FILES])
def test_case_meets_its_expectations(path):
    outcome = CheckOutcome()
    check_file(path, outcome)
    assert not outcome.input_errors and not outcome.internal_errors
    assert outcome.rows, "a shipped case must have an [expect] table"
    failed = [r for r in outcome.rows if not r.passed]
    assert not failed, [(r.key, r.expected, r.got) for r in failed]


@pytest.mark.parametrize("path", FILES, ids=[str(p.relative_to(CASES)) for p in FILES])
def test_no_nan_or_inf_in_json(path):
    import json

    from mdcalc.report import to_json
    from mdcalc.runner import run_case

    text = to_json(run_case(path))
    assert "NaN" not in text and "Infinity" not in text
    json.loads(text)
