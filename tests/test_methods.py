"""The Methods machinery: relative errors, the single reference, timing, n/a rows."""

from __future__ import annotations

import pytest

from mdcalc.methods import Method, NotApplicable, compare, relative_error, timed
from mdcalc.output.report import MethodQuantity

Q = [MethodQuantity("x", "x", "m")]


def test_relative_error():
    assert relative_error(1.1, 1.0) == pytest.approx(0.1)
    assert relative_error(0.9, -1.0) == pytest.approx(1.9)
    assert relative_error(0.25, 0.0) == 0.25  # absolute where the reference is zero


def test_compare_measures_errors_against_the_reference():
    table = compare(
        "t",
        "k",
        Q,
        [
            Method("rough", lambda: {"x": 2.2}),
            Method("exact", lambda: {"x": 2.0}, reference=True),
        ],
    )
    rough, exact = table.rows
    assert rough.rel_errors["x"] == pytest.approx(0.1)
    assert exact.reference and exact.rel_errors == {}
    assert rough.seconds > 0


def test_exactly_one_reference():
    with pytest.raises(ValueError):
        compare("t", "k", Q, [Method("a", lambda: {"x": 1.0})])


def test_not_applicable_row_and_non_finite_value():
    def never():
        raise NotApplicable("outside its validity")

    table = compare(
        "t",
        "k",
        Q,
        [
            Method("closed form", never),
            Method("ref", lambda: {"x": 1.0}, reference=True),
        ],
    )
    assert table.rows[0].note == "not applicable: outside its validity"
    with pytest.raises(ArithmeticError):
        compare("t", "k", Q, [Method("ref", lambda: {"x": float("nan")}, reference=True)])


def test_timed_repeats_cheap_calls():
    calls = []
    result, seconds = timed(lambda: calls.append(1) or {"x": 1.0})
    assert result == {"x": 1.0}
    assert len(calls) > 1 and 0 < seconds < 1e-3
