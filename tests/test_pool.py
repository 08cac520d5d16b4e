"""The process pool when a worker dies (killed by the system, out of memory): with
``on_error`` only the item that kills its process is an error, every other item's
result is the one it would have had, in input order; without it the error goes up."""

from __future__ import annotations

import os

import pytest

from mdcalc.pool import pool_map

DEADLY = 13


def square_or_die(x: int) -> int:
    if x == DEADLY:
        os._exit(1)  # as the kernel's OOM killer would end it
    return x * x


def lost(item: int, error: BaseException) -> tuple[str, int]:
    return ("lost", item)


def test_a_dead_worker_costs_only_the_item_that_killed_it():
    done: list[int] = []
    out = list(pool_map(square_or_die, list(range(60)), 2, lambda: done.append(1), lost))
    assert out == [("lost", x) if x == DEADLY else x * x for x in range(60)]
    assert len(done) == 60


def test_without_on_error_a_dead_worker_is_an_error():
    from concurrent.futures.process import BrokenProcessPool

    with pytest.raises(BrokenProcessPool):
        list(pool_map(square_or_die, list(range(30)), 2))
