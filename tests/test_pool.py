"""The process pool when a worker dies (killed by the system, out of memory): with
``on_error`` only the item that kills its process is an error, every other item's
result is the one it would have had, in input order; without it the error goes up."""

from __future__ import annotations

import os

import pytest

from mdcalc.runs.pool import pool_map

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


def test_folders_are_searched_in_the_order_of_sorted_paths(tmp_path):
    """collect() walks with scandir and sorts strings: the same files, in the same
    order, as sorted(Path.rglob("*.toml")) with is_file() (what it did before)."""
    from pathlib import Path

    from mdcalc.runs.pool import collect

    names = ["a/x.toml", "a-b/x.toml", "a.b/y.toml", "A/z.toml", "a/b/c.toml", ".h.toml",
             "z.toml", "a/.toml", "dir.toml/q.toml", "b/c.TOML", "a b/x.toml", "é/x.toml",
             "a0/x.toml", "b/notes.txt"]  # fmt: skip
    for name in names:
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text("x = 1\n", encoding="utf-8")
    os.symlink(tmp_path / "a", tmp_path / "link_to_folder")  # not followed
    os.symlink(tmp_path / "z.toml", tmp_path / "link.toml")  # a file: counted
    os.symlink(tmp_path / "nowhere", tmp_path / "broken.toml")
    (tmp_path / "empty.toml").mkdir()
    before = sorted(p for p in Path(tmp_path).rglob("*.toml") if p.is_file())
    found = collect([tmp_path])
    assert [case.path for case in found] == before
    assert [case.out_name for case in found] == [
        p.relative_to(tmp_path).with_suffix(".json") for p in before
    ]
    assert str(found[0].path) == str(tmp_path / ".h.toml")
    assert collect([tmp_path / "z.toml"])[0].out_name == Path("z.json")


def test_never_more_processes_than_items():
    """A fork pool starts every worker at once: --jobs 10**9 over 3 files is 3."""
    from mdcalc.runs.pool import default_jobs, jobs_for

    assert jobs_for(10**9, 3) == 3
    assert jobs_for(2, 1000) == 2
    assert jobs_for(0, 1000) == default_jobs(1000) == min(os.cpu_count() or 1, 1000)
    assert jobs_for(5, 0) == 1


#: A reader of a pool's stream that stops after its first result: the stream is
#: closed while the workers send results of a few MB (a kernel piece's columns).
STOPS_EARLY = """
import numpy as np
from mdcalc.runs.pool import pool_map

def big(i):
    return np.full(400_000, float(i))

for out in pool_map(big, list(range(12)), 2):
    break
del out
print("end", flush=True)
"""


def test_a_stream_closed_early_ends_the_command(tmp_path):
    # Closing the stream kills the workers; one killed while it sent a result left
    # half of it in the pipe, and the pool's manager thread waited for the rest for
    # ever: the interpreter's exit joins that thread, and the command hung after its
    # output (2 to 3 runs in 6 before the fix). Each run must end within 30 s.
    import subprocess
    import sys

    script = tmp_path / "stops_early.py"
    script.write_text(STOPS_EARLY, encoding="utf-8")
    for _ in range(3):
        done = subprocess.run(
            [sys.executable, str(script)], capture_output=True, text=True, timeout=30
        )
        assert done.returncode == 0 and done.stdout == "end\n", done.stderr[-2000:]
        assert "Exception ignored" not in done.stderr, done.stderr[-2000:]


def test_killing_a_pool_closes_this_process_end_of_its_result_pipe():
    # the mechanism of the fix above, without its race: after _kill the manager
    # thread's read of a half-sent result meets the end of the pipe
    from mdcalc.runs.pool import _kill, _new_pool

    pool = _new_pool(2)
    writer = pool._result_queue._writer
    assert pool.submit(abs, -3).result(timeout=30) == 3
    _kill(pool)
    assert writer.closed
