"""Case files and the process pool that ``mdcalc run``, ``check --jobs`` and
``sweep`` share.

Workers are forked from a parent that has already imported the shared machinery
(pydantic, the case reader, the report, and the module of the function it maps);
each worker imports a problem's module the first time one of its files comes up,
so imports are paid once per worker, not per file. Results come back in input
order, so a run's output does not depend on the number of jobs.
"""

from __future__ import annotations

import multiprocessing
import os
from collections.abc import Callable, Iterable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import TypeVar

from mdcalc.errors import InputError, Problem

T = TypeVar("T")
R = TypeVar("R")


# ------------------------------------------------------------------------- files


@dataclass(frozen=True)
class CaseFile:
    path: Path
    #: Where its result goes under ``--out DIR``: the file's path inside the folder it
    #: was found in (so cases/a/x.toml and cases/b/x.toml do not collide), .json.
    out_name: Path


def collect(paths: Iterable[Path], outputs: bool = False) -> list[CaseFile]:
    """Files as given, folders searched recursively for ``*.toml`` (sorted).

    With ``outputs``, two files that would write the same result file are an error.
    """
    files: list[CaseFile] = []
    for path in paths:
        if path.is_dir():
            for found in sorted(p for p in path.rglob("*.toml") if p.is_file()):
                files.append(CaseFile(found, found.relative_to(path).with_suffix(".json")))
        else:
            files.append(CaseFile(path, Path(path.name).with_suffix(".json")))
    names: dict[Path, Path] = {}
    clashes = []
    for case in files:
        other = names.setdefault(case.out_name, case.path)
        if other != case.path:
            clashes.append(Problem(f"{other} and {case.path} would both write {case.out_name}"))
    if clashes and outputs:
        raise InputError("mdcalc run --out", clashes)
    return files


# ------------------------------------------------------------------------- the pool


def default_jobs(count: int) -> int:
    """One process per core, never more than the files; in-process for one file."""
    return max(1, min(os.cpu_count() or 1, count))


def warm() -> None:
    """Import what every worker needs, once, before the workers are forked."""
    import mdcalc.casefile  # noqa: F401
    import mdcalc.model  # noqa: F401
    import mdcalc.report  # noqa: F401
    import mdcalc.runner  # noqa: F401


def pool_map(
    func: Callable[[T], R], items: Sequence[T], jobs: int, on_done: Callable[[], None] | None = None
) -> Iterator[R]:
    """``map(func, items)`` in input order, over ``jobs`` processes (in-process for 1)."""
    if jobs <= 1 or len(items) <= 1:
        for item in items:
            yield func(item)
            if on_done is not None:
                on_done()
        return
    warm()
    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("fork" if "fork" in methods else None)
    # Chunks amortise the round trips of small, fast cases; four per worker keep the
    # load balanced when a few cases are slow.
    chunksize = max(1, min(64, len(items) // (jobs * 4)))
    with ProcessPoolExecutor(max_workers=jobs, mp_context=context) as pool:
        try:
            for result in pool.map(func, items, chunksize=chunksize):
                yield result
                if on_done is not None:
                    on_done()
        except BaseException:
            pool.shutdown(wait=False, cancel_futures=True)
            raise
