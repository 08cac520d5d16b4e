"""Where batches run: this machine's process pool, or a dask.distributed cluster.

``mdcalc study``, ``sweep`` and ``run`` take ``--scheduler``: ``tcp://HOST:PORT`` (a
running ``dask scheduler``), ``local:N`` (a LocalCluster of N worker processes on
this machine, listening on 127.0.0.1 only), or the environment variable
``MDCALC_SCHEDULER``. dask is imported only here, and only then
(``pip install 'mdcalc[dask]'``).

Both run the same streaming loop (:func:`mdcalc.runs.pool.stream`): chunks grow to about
a second of work on a cluster, results come back in input order, and a chunk lost
with its worker is run again (dask's retries). Items are computed one by one and
independently, so a result does not depend on the chunk or the machine it ran on.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from typing import Any, Protocol, TypeVar

from mdcalc.errors import InputError, Problem

T = TypeVar("T")
R = TypeVar("R")

#: A cluster task aims at this much work [s]: its scheduling costs a few ms.
CHUNK_SECONDS = 1.0
MAX_CHUNK = 4096
#: Times a chunk is run again when its worker is lost.
RETRIES = 2
#: Seconds to reach a scheduler before giving up.
CONNECT_SECONDS = 10


class Mapper(Protocol):
    """``map`` over a pool or a cluster, streamed in input order."""

    description: str

    def __call__(
        self,
        func: Callable[[T], R],
        items: Sequence[T],
        on_done: Callable[[], None] | None = None,
        on_error: Callable[[T, BaseException], R] | None = None,
    ) -> Iterator[R]: ...


class PoolMapper:
    def __init__(self, jobs: int) -> None:
        self.jobs = jobs
        self.description = f"process pool, {jobs} jobs" if jobs > 1 else "in this process (1 job)"

    def __call__(self, func: Any, items: Any, on_done: Any = None, on_error: Any = None) -> Any:
        from mdcalc.runs.pool import pool_map

        return pool_map(func, items, self.jobs, on_done, on_error)


class DaskMapper:
    def __init__(self, client: Any, description: str) -> None:
        self.client = client
        self.description = description

    def __call__(self, func: Any, items: Any, on_done: Any = None, on_error: Any = None) -> Any:
        return dask_map(self.client, func, items, on_done, on_error)


def scheduler_of(option: str | None) -> str | None:
    """The scheduler asked for: the option, else ``MDCALC_SCHEDULER``, else None."""
    chosen = option if option is not None else os.environ.get("MDCALC_SCHEDULER")
    return chosen.strip() or None if chosen is not None else None


@contextmanager
def executor(scheduler: str | None, jobs: int) -> Iterator[Mapper]:
    """A mapper for the pool (``scheduler`` None) or for a cluster, closed after."""
    if scheduler is None:
        yield PoolMapper(jobs)
        return
    client, cluster = connect(scheduler)
    try:
        workers = len(client.scheduler_info().get("workers", {}))
        yield DaskMapper(client, f"dask {scheduler} ({workers} workers)")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def connect(scheduler: str) -> tuple[Any, Any]:
    """(client, cluster or None) for ``tcp://HOST:PORT`` or ``local:N``."""
    where = f"--scheduler {scheduler}"
    try:
        import distributed
    except ImportError:
        raise InputError(
            where,
            [Problem("needs dask.distributed, which is not installed: pip install 'mdcalc[dask]'")],
        ) from None
    import logging

    if scheduler.startswith("local:"):
        count = scheduler.removeprefix("local:")
        if not count.isdigit() or not 1 <= int(count) <= 256:
            raise InputError(where, [Problem("local:N takes N from 1 to 256 worker processes")])
        cluster = distributed.LocalCluster(
            n_workers=int(count),
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
            # the scheduler's HTTP routes (health, metrics) listen all the same: on a
            # port of the system's choosing, not 8787, where a second cluster at the
            # same time warned "Port 8787 is already in use"
            scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
            # a worker's heartbeat that meets the closing scheduler logs an ERROR
            # with its traceback (dask/distributed#7192), after a run that went well;
            # a block that fails is retried and reported by mdcalc itself
            silence_logs=logging.CRITICAL,
        )
        return distributed.Client(cluster), cluster
    if "://" not in scheduler:
        raise InputError(where, [Problem("expected tcp://HOST:PORT or local:N")])
    try:
        client = distributed.Client(scheduler, timeout=CONNECT_SECONDS)
    except (OSError, TimeoutError) as exc:
        raise InputError(where, [Problem(f"cannot reach the scheduler: {exc}")]) from None
    return client, None


def dask_map(
    client: Any,
    func: Callable[[T], R],
    items: Sequence[T],
    on_done: Callable[[], None] | None = None,
    on_error: Callable[[T, BaseException], R] | None = None,
) -> Iterator[R]:
    """``map(func, items)`` on a dask cluster, streamed in input order; a chunk whose
    worker died is retried RETRIES times, then each of its items goes to
    ``on_error`` (else the error goes up)."""
    import distributed

    from mdcalc.runs.pool import _run_chunk, stream

    threads = sum(client.nthreads().values()) or 1

    def submit(chunk: Sequence[T]) -> Any:
        return client.submit(_run_chunk, func, list(chunk), retries=RETRIES, pure=False)

    def first_done(running: set[Any]) -> set[Any]:
        return set(distributed.wait(list(running), return_when="FIRST_COMPLETED").done)

    futures: list[Any] = []

    def tracked(chunk: Sequence[T]) -> Any:
        futures.append(future := submit(chunk))
        return future

    try:
        yield from stream(
            tracked, first_done, items, 2 * threads, CHUNK_SECONDS, on_done, on_error, MAX_CHUNK
        )
    finally:
        client.cancel([f for f in futures if not f.done()])
