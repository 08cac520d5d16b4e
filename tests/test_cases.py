"""Every shipped case file meets its [expect] table (the same check `mdcalc check` runs)."""

from __future__ import annotations

import pytest

from mdcalc.runs.check import collect
from tests.conftest import CASES

#: Case files; the study files of cases/studies are checked by `mdcalc check` and
#: tests/test_study.py.
FILES = [p for p in collect([CASES]) if p.parent.name != "studies"]
STUDIES = sorted((CASES / "studies").glob("*.toml"))


def test_every_problem_has_cases_and_extreme_cases():
    from mdcalc.problems import PROBLEMS

    for name in PROBLEMS:
        assert list((CASES / name).glob("*.toml")), f"no cases for {name}"
        assert list((CASES / "extreme").glob(f"{name}_*.toml")), f"no extreme case for {name}"


@pytest.mark.parametrize("path", FILES, ids=[str(p.relative_to(CASES)) for p in FILES])
def test_case_meets_its_expectations_with_finite_json(path):
    # One run per file: the [expect] table as `mdcalc check` reads it, and the JSON
    # strict (no NaN, no Infinity) with every number finite.
    from mdcalc.input.casefile import read_case
    from mdcalc.input.model import CaseBase
    from mdcalc.output.jsondoc import to_json
    from mdcalc.runs.check import within
    from mdcalc.runs.runner import run_text
    from tests.conftest import strict_json, walk_finite

    case = read_case(path)
    report = run_text(case)
    walk_finite(strict_json(to_json(report)))
    assert "expect" in case.data, "a shipped case must have an [expect] table"
    expectations = CaseBase.model_validate({"expect": case.data["expect"]}).expect or {}
    results = report.results()
    failed = [
        (key, e.value, results[key].value if key in results else "no such result")
        for key, e in expectations.items()
        if not within(e, results[key].value if key in results else None)
    ]
    assert not failed, failed


def test_every_study_case_is_a_study_with_expectations():
    import tomllib

    assert len(STUDIES) >= 3
    for path in STUDIES:
        data = tomllib.loads(path.read_text("utf-8"))
        assert "study" in data and "expect" in data, path
