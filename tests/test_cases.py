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
def test_case_meets_its_expectations_with_finite_json(path, cli):
    # Through the Python API (mdcalc.solve): the [expect] table as `mdcalc check`
    # reads it, the JSON strict (no NaN, no Infinity) with every number finite, and
    # that JSON the command line's (issue 34: every shipped case, in-process).
    import tomllib

    import mdcalc
    from mdcalc.input.model import CaseBase
    from mdcalc.runs.check import within
    from tests.conftest import comparable_json, strict_json, walk_finite

    calc = mdcalc.solve(path)
    document = strict_json(calc.to_json())
    walk_finite(document)
    command = cli(document["problem"], path, "--json")
    assert command.exit_code == (0 if calc.status == "ok" else 3), command.stderr
    told = strict_json(command.stdout)
    assert told["case"] == document["case"] == str(path)
    assert comparable_json(told) == comparable_json(document)
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    assert "expect" in data, "a shipped case must have an [expect] table"
    expectations = CaseBase.model_validate({"expect": data["expect"]}).expect or {}
    results = calc.run.report.results()
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
