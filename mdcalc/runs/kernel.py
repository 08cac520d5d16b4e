"""A problem's vectorized kernel on a block of samples or grid points, picklable
so that a process pool or a dask cluster can run it (studies and sweeps), and what
a block lost for good becomes."""

from __future__ import annotations

import copy
import functools
import itertools
import time
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mdcalc.input.casefile import CaseText, validate
from mdcalc.input.model import DECLINED, equal_ends

#: Samples or grid points a kernel block holds: 64 Ki of a closed form take a few
#: tens of ms, of a modal solution with its maxima in time about a second.
BLOCK = 65_536
#: A kernel whose block the probes say would take longer than this has its blocks
#: cut into pieces for the process pool (when it has more than one job).
HEAVY_BLOCK_SECONDS = 0.2

#: glibc's malloc (mallopt's parameters): arrays up to 32 MB from the heap (the most
#: its own threshold grows to), and up to 64 MB of freed memory at the heap's top
#: kept for the next arrays, not handed back to the system.
M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3
TRIM_BYTES, MMAP_BYTES = 64 << 20, 32 << 20


@functools.cache  # once a process: a forked one inherits the parent's settings
def steady_heap() -> None:
    """Keep a kernel's freed arrays in the process for its next ones (glibc only;
    elsewhere nothing). By default glibc hands the top of the heap back to the system
    as soon as 2 × its mmap threshold is free there, and a block's arrays of a few
    hundred kB, freed and asked for again at each step of an integration, are then
    fresh pages each time: 2·10⁵ page faults in one block of 25 000 rows of
    tabulated_press.toml, a third of its time. A process then keeps up to 64 MB it
    has freed, below the peak its kernel reached anyway."""
    import sys

    if not sys.platform.startswith("linux"):
        return
    try:
        import ctypes

        mallopt = ctypes.CDLL(None).mallopt  # the C library Python runs on
    except (ImportError, OSError, AttributeError):  # no ctypes, or a C library without it
        return
    mallopt(M_TRIM_THRESHOLD, TRIM_BYTES)
    mallopt(M_MMAP_THRESHOLD, MMAP_BYTES)


class KernelChunk:
    """The problem's kernel on a block of samples (picklable for a pool or cluster)."""

    def __init__(
        self,
        problem: str,
        path: Path,
        scene: dict[str, Any],
        keys: Sequence[str],
        wanted: Sequence[str],
        check_rows: bool = False,
    ) -> None:
        self.problem = problem
        self.path = str(path)
        self.scene = scene
        self.keys = list(keys)
        self.wanted = list(wanted)
        #: Validate every row's scene (a study whose box of drawn values crosses a
        #: cross-field rule): an invalid row is declined, to be solved alone (its
        #: validation then says why), and the valid rows stay vectorized.
        self.check_rows = check_rows

    def invalid_rows(self, module: Any, block: Any) -> Any:
        """The rows of ``block`` whose scene the problem's model refuses."""
        import numpy as np

        from mdcalc.errors import InputError
        from mdcalc.input.casefile import set_key

        locs = [tuple(int(p) if p.isdigit() else p for p in k.split(".")) for k in self.keys]
        invalid = np.zeros(len(block), dtype=bool)
        for i, row in enumerate(block.tolist()):
            data = copy.deepcopy(self.scene)
            for loc, value in zip(locs, row, strict=True):
                set_key(data, loc, float(value))
            try:
                validate(module.Case, CaseText(Path(self.path), "", data))
            except (InputError, ArithmeticError):
                invalid[i] = True
        return invalid

    def __call__(self, block: Any) -> dict[str, Any] | None:
        import numpy as np

        from mdcalc.problems import PROBLEMS

        module: Any = PROBLEMS[self.problem].load()
        steady_heap()
        n = len(block)
        invalid = self.invalid_rows(module, block) if self.check_rows else np.zeros(n, dtype=bool)
        valid = np.flatnonzero(~invalid)
        part = {k: np.full(n, np.nan) for k in self.wanted}
        part[DECLINED] = invalid.copy()  # invalid rows: solved alone, where they are refused
        if not valid.size:
            return part
        out = self._kernel(module, block[valid])
        if out is None:
            return None
        for k in self.wanted:
            part[k][valid] = out[k]
        part[DECLINED][valid] = out[DECLINED]
        return part

    def _kernel(self, module: Any, block: Any) -> dict[str, Any] | None:
        """The problem's kernel on the rows of ``block`` (valid scenes): the wanted
        values and the declined mask over the rows, or None (point by point)."""
        import warnings

        import numpy as np

        model = validate(module.Case, CaseText(Path(self.path), "", copy.deepcopy(self.scene)))
        grid = {key: np.ascontiguousarray(block[:, j]) for j, key in enumerate(self.keys)}
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore", RuntimeWarning)
                out = module.sweep(model, grid, self.wanted)
        except (ArithmeticError, ValueError, MemoryError):
            return None  # the samples go point by point, where each is judged alone
        if out is None or any(k not in out for k in self.wanted):
            return None
        n = len(block)
        part = {
            k: np.array(np.broadcast_to(np.asarray(out[k], dtype=float), (n,))) for k in self.wanted
        }
        declined = out.get(DECLINED)
        part[DECLINED] = (
            np.zeros(n, dtype=bool)
            if declined is None
            else np.array(np.broadcast_to(np.asarray(declined, dtype=bool), (n,)))
        )
        return part


@dataclass
class LostBlock:
    """A block of samples whose kernel run was lost for good (its worker died past
    the retries): its samples count as failed."""

    reason: str


def lost_block(block: Any, error: BaseException) -> LostBlock:
    return LostBlock(f"lost on the cluster: {type(error).__name__}: {error}")


#: Rows of the first two calls of a kernel on the process pool, timed: the first
#: pays the one-off imports, the second says what a row costs.
PROBE = 512
#: Pieces a job of the pool gets of the samples, where the blocks allow: as few as
#: balance the load, since every call of an ODE kernel pays its steps' Python work
#: once for all its rows (the adhesion-limited car: 2950 rows/s in one process in
#: pieces of 512, 13 800 in pieces of 16 384).
PIECES_PER_JOB = 4


def kernel_parts(run: KernelChunk, blocks: Sequence[Any], mapper: Any) -> tuple[Iterable[Any], str]:
    """Each block's kernel answer, in block order, and where the blocks ran ("" for
    this process). On the process pool two probes of :data:`PROBE` rows run here
    and time a row: a kernel whose block would take longer than HEAVY_BLOCK_SECONDS
    (a modal solution and its maxima in time, an ODE reference) has the blocks' rows
    cut, end to end, into pieces of equal size that the pool's processes run, then
    cut back into the blocks: a piece holds a job's share of the samples
    (PIECES_PER_JOB a job), at least PROBE rows (fewer where every job then gets
    one), at most a block (a kernel whose arrays outgrow the cache tiles it), and the
    pieces are a multiple of the jobs in number, so that the jobs end together (a
    last block's small remainder left one job idle for most of a piece: a tenth of a
    2·10⁵-sample study); a lighter one runs here; a piece lost for good (its process
    died past the retries) marks its rows in the blocks' answers (:data:`LOST`),
    in each block it spans. On a cluster every block
    goes to the workers, retried where one dies; a block lost for good comes back as
    a :class:`LostBlock`. The numbers are the same either way: each row's are its
    own."""
    from mdcalc.runs.cluster import PoolMapper

    if not isinstance(mapper, PoolMapper):
        return mapper(run, blocks, on_error=lost_block), mapper.description
    total = sum(len(block) for block in blocks)
    if mapper.jobs <= 1 or len(blocks[0]) <= 2 * PROBE:
        return map(run, blocks), ""
    head = blocks[0]
    probes = [run(head[:PROBE])]
    clock = time.perf_counter()
    probes.append(run(head[PROBE : 2 * PROBE]))
    per_row = (time.perf_counter() - clock) / len(head[PROBE : 2 * PROBE])
    if per_row * min(BLOCK, total) <= HEAVY_BLOCK_SECONDS:
        tail = head[2 * PROBE :]
        first = _joined([*probes, run(tail)], [PROBE, PROBE, len(tail)])
        return itertools.chain([first], map(run, blocks[1:])), ""
    import numpy as np

    rest = [head[2 * PROBE :], *blocks[1:]]
    pieces = _pieces(np.concatenate(rest), mapper.jobs)  # a piece may span two blocks
    answers = iter(mapper(Compact(run), pieces, on_error=lost_block))
    flow = _Fragments(answers, [len(p) for p in pieces])

    def joined() -> Iterable[Any]:
        for index, block in enumerate(rest):
            parts, sizes = flow.take(len(block))
            if index == 0:
                parts, sizes = [*probes, *parts], [PROBE, PROBE, *sizes]
            yield _joined(parts, sizes)
        # Run the pool's stream to its end, which shuts the pool down and joins it:
        # a stream left at its last item kept the pool's manager thread alive until
        # the interpreter's exit, where Python 3.11's exit hook raced it to a closed
        # pipe ("OSError: [Errno 9] Bad file descriptor", in 2 runs of 10).
        for _ in answers:
            pass

    return joined(), mapper.description


class Compact:
    """A kernel chunk whose answer goes back from a pool's process compactly: a
    column of one value, bit for bit (most of a variator's 59 keys do not change
    with its drawn inputs), as that value, filled out again as the parent unpickles
    it (12 MB of a 25 000-row piece took the process some 30 ms to hand over, 7 %
    of its time). In the process that asks (a pool of one) the answer is as it is."""

    def __init__(self, run: KernelChunk) -> None:
        self.run = run

    def __call__(self, block: Any) -> Any:
        import multiprocessing

        answer = self.run(block)
        if not isinstance(answer, dict) or multiprocessing.parent_process() is None:
            return answer
        return {key: _Filled.of(values) for key, values in answer.items()}


class _Filled:
    """``size`` copies of ``value``: unpickled, the array np.full makes of them."""

    def __init__(self, size: int, value: Any, dtype: Any) -> None:
        self.size, self.value, self.dtype = size, value, dtype

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        import numpy as np

        return np.full, (self.size, self.value, self.dtype)

    @staticmethod
    def of(values: Any) -> Any:
        """``values`` as a _Filled where they are one value bit for bit (-0 is not
        0, and a NaN only its own payload)."""
        import numpy as np

        if not isinstance(values, np.ndarray) or values.ndim != 1 or values.size < 2:
            return values
        if not values.flags.c_contiguous or values.dtype.kind not in "biufc":
            return values  # (numbers only: a string's width is its array's)
        raw = values.view(np.int64 if values.itemsize == 8 else np.uint8)
        raw = raw.reshape(values.size, -1)
        return _Filled(values.size, values[0], values.dtype) if np.all(raw == raw[0]) else values


class _Fragments:
    """The pieces' answers in order, handed out block by block: the parts of the
    next ``rows`` rows (a piece's answer cut where a block ends) and their sizes."""

    def __init__(self, answers: Iterator[Any], sizes: list[int]) -> None:
        self.answers, self.sizes = answers, iter(sizes)
        self.part: Any = None  # the answer being handed out, from its row ``used``
        self.left = self.used = 0

    def take(self, rows: int) -> tuple[list[Any], list[int]]:
        parts, sizes = [], []
        while rows:
            if not self.left:
                self.part, self.left, self.used = next(self.answers), next(self.sizes), 0
            n = min(rows, self.left)
            parts.append(_rows(self.part, self.used, self.used + n))
            sizes.append(n)
            self.used, self.left, rows = self.used + n, self.left - n, rows - n
        return parts, sizes


def _rows(answer: Any, first: int, last: int) -> Any:
    """Rows ``first:last`` of a piece's answer (a dict of arrays; None and a lost
    piece stand for any of their rows)."""
    if answer is None or isinstance(answer, LostBlock):
        return answer
    return {k: v[first:last] for k, v in answer.items()}


def piece_size(rows: int, jobs: int) -> int:
    """Rows of a piece of a heavy kernel's blocks on a pool of ``jobs``: large, since
    a kernel's cost a call (a step of an ODE over the block) is shared by its rows,
    yet PIECES_PER_JOB a job so that the jobs end together; at least PROBE rows, at
    most a block."""
    return max(PROBE, min(BLOCK, -(-rows // (PIECES_PER_JOB * max(jobs, 1)))))


def _pieces(rows: Any, jobs: int) -> list[Any]:
    """The blocks' ``rows``, end to end, in pieces of equal size (to a row) of at
    most :func:`piece_size`, a multiple of the jobs in number, so that the jobs end
    together (as many as there are rows, at most)."""
    count = -(-len(rows) // piece_size(len(rows), jobs))
    count = -(-count // max(jobs, 1)) * max(jobs, 1)
    return _split(rows, max(1, min(count, len(rows))))


def _split(rows: Any, count: int) -> list[Any]:
    """``rows`` in ``count`` pieces of equal size (to a row)."""
    return [rows[a:b] for a, b in itertools.pairwise(equal_ends(len(rows), count))]


#: In a block's answer, the rows of a piece lost for good (the rest of the block
#: computed), and the reason.
LOST, LOST_REASON = "__lost__", "__lost_reason__"


def _joined(parts: list[Any], sizes: list[int]) -> Any:
    """The answers of consecutive pieces of one block (of ``sizes`` rows) as the
    block's answer: None if a piece was declined or the pieces' keys differ, the
    :class:`LostBlock` if every piece was lost, else each key's values end to end,
    a lost piece's rows NaN and marked in ``LOST``."""
    import numpy as np

    if any(p is None for p in parts):
        return None
    done = [p for p in parts if not isinstance(p, LostBlock)]
    if not done:
        return parts[0]
    if len(parts) == 1:
        return parts[0]
    keys = list(done[0])
    if any(list(p) != keys for p in done):
        return None
    out: dict[str, Any] = {
        key: np.concatenate(
            [
                np.full(n, False if key == DECLINED else np.nan)
                if isinstance(p, LostBlock)
                else np.asarray(p[key])
                for p, n in zip(parts, sizes, strict=True)
            ]
        )
        for key in keys
    }
    lost = [p for p in parts if isinstance(p, LostBlock)]
    if lost:
        out[LOST] = np.concatenate(
            [np.full(n, isinstance(p, LostBlock)) for p, n in zip(parts, sizes, strict=True)]
        )
        out[LOST_REASON] = lost[0].reason
    return out
