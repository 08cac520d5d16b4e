"""``mdcalc check``: run the ``[expect]`` tables of case files.

Pure logic: collects files, runs them, compares; the CLI prints the outcome.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path

from mdcalc.core.budget import DEFAULT_SECONDS
from mdcalc.errors import InputError
from mdcalc.input.casefile import CaseText, read_case
from mdcalc.input.model import CaseBase, Expectation
from mdcalc.output.report import Quantity, Value, format_value
from mdcalc.runs.pool import collect as collect_cases
from mdcalc.runs.pool import pool_map
from mdcalc.runs.runner import run_text


@dataclass
class CheckRow:
    file: str
    key: str
    expected: str
    got: str
    tolerance: str
    passed: bool
    source: str


@dataclass
class CheckOutcome:
    rows: list[CheckRow] = field(default_factory=list)
    input_errors: list[str] = field(default_factory=list)  # formatted, one per line
    internal_errors: list[str] = field(default_factory=list)
    files_checked: int = 0
    files_skipped: int = 0  # case files without an [expect] table

    @property
    def passed(self) -> int:
        return sum(r.passed for r in self.rows)

    @property
    def failed(self) -> int:
        return sum(not r.passed for r in self.rows) + len(self.internal_errors)


def collect(paths: Iterable[Path]) -> list[Path]:
    """Files as given; folders searched recursively for ``*.toml``, in sorted order
    (the file list of ``mdcalc run``)."""
    return [case.path for case in collect_cases(paths)]


def within(expectation: Expectation, got: Value | None) -> bool:
    """Does ``got`` meet the expectation (tolerance: rel or abs, whichever is wider)?"""
    want = expectation.value
    if got is None:
        return False
    if isinstance(want, bool) or isinstance(got, bool) or isinstance(want, str):
        return type(want) is type(got) and want == got
    if isinstance(got, str | tuple):
        return False
    allowed = max(expectation.abs or 0.0, (expectation.rel or 0.0) * abs(want))
    return abs(float(got) - want) <= allowed


def tolerance_text(expectation: Expectation) -> str:
    parts = []
    if expectation.rel is not None:
        parts.append(f"rel {expectation.rel:g}")
    if expectation.abs is not None:
        parts.append(f"abs {expectation.abs:g}")
    return ", ".join(parts) or "exact"


def check_file(
    path: Path, outcome: CheckOutcome, time_limit: float | None = DEFAULT_SECONDS
) -> None:
    try:
        case = read_case(path)
        if "expect" not in case.data:
            outcome.files_skipped += 1
            return
        if "study" in case.data:
            results = study_values(case, time_limit)
        else:
            results = run_text(case, time_limit=time_limit).results()
        # The run validated the whole file, so the [expect] table is valid here.
        expectations = CaseBase.model_validate({"expect": case.data["expect"]}).expect or {}
    except InputError as exc:
        outcome.input_errors.append(str(exc))
        return
    except Exception as exc:  # a bug: reported, and checking goes on
        outcome.internal_errors.append(f"{path}: internal error: {type(exc).__name__}: {exc}")
        return
    outcome.files_checked += 1
    for key, expectation in expectations.items():
        quantity = results.get(key)
        got = quantity.value if quantity is not None else None
        outcome.rows.append(
            CheckRow(
                file=str(path),
                key=key,
                expected=format_value(expectation.value, 7),
                got=format_value(got, 7) if quantity is not None else "no such result",
                tolerance=tolerance_text(expectation),
                passed=within(expectation, got),
                source=expectation.source,
            )
        )


def study_values(case: CaseText, time_limit: float | None) -> dict[str, Quantity]:
    """A study file's summary numbers by their flat keys (``stopping_distance.p95``),
    the study run in this process (a check runs its files in the pool)."""
    from mdcalc.runs.cluster import PoolMapper
    from mdcalc.runs.study import run

    values = run(case, PoolMapper(1), time_limit).values()
    return {key: Quantity(key, key, value) for key, value in values.items()}


def check_one(path: Path, time_limit: float | None = DEFAULT_SECONDS) -> CheckOutcome:
    outcome = CheckOutcome()
    check_file(path, outcome, time_limit)
    return outcome


def merge(outcomes: Iterable[CheckOutcome]) -> CheckOutcome:
    total = CheckOutcome()
    for part in outcomes:
        total.rows += part.rows
        total.input_errors += part.input_errors
        total.internal_errors += part.internal_errors
        total.files_checked += part.files_checked
        total.files_skipped += part.files_skipped
    return total


def check_paths(
    paths: Iterable[Path], jobs: int = 1, time_limit: float | None = DEFAULT_SECONDS
) -> CheckOutcome:
    """Check every case file under ``paths``; ``jobs`` processes (results in file order),
    each file under ``time_limit`` seconds."""
    return merge(pool_map(partial(check_one, time_limit=time_limit), collect(paths), jobs))
