"""Every vectorized sweep kernel agrees with the point-by-point path.

Written once for all problems: a problem module that offers ``sweep(case, grid)``
and ``SWEEP_KEYS`` is checked on each of its shipped cases, varying every key of
``SWEEP_KEYS`` the case holds over a small grid around its value.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mdcalc.problems import PROBLEMS
from tests.conftest import CASES, SHORTER, shorter

KERNELS = [name for name, spec in PROBLEMS.items() if hasattr(spec.load(), "SWEEP_KEYS")]


def test_closed_form_problems_have_kernels():
    # The closed-form problems the README names; a guard that can fail.
    assert {"braking", "clutch", "mount", "coupling", "hoist"} <= set(KERNELS)


def tolerance(module, key: str, closed_form: float) -> tuple[float, float]:
    """(rel, abs) of a key: ``closed_form`` relative, or the module's ODE_REFERENCED
    entry for a key whose reference is an ODE run (a number: relative; a pair:
    relative and absolute, for an error measured against that reference)."""
    given = getattr(module, "ODE_REFERENCED", {}).get(key, closed_form)
    return (float(given), 0.0) if isinstance(given, int | float) else given


def _held(data: dict, key: str):
    node = data
    for part in key.split("."):
        if isinstance(node, list) and part.isdigit() and int(part) < len(node):
            node = node[int(part)]
            continue
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node if isinstance(node, int | float) and not isinstance(node, bool) else None


def _grid(data: dict, keys: dict[str, str], model) -> list[str]:
    """Three values of every kernel key the case holds, within the field's bounds."""
    from mdcalc.input.casefile import is_integer_field

    varies = []
    for key in keys:
        value = _held(data, key)
        if value is None or value == 0:
            continue
        loc = tuple(key.split("."))
        if is_integer_field(model, loc):
            low = value if value < 50 else value - 2  # bounds are small counts
            varies.append(f"{key}={low}:{low + 2}:3")
        else:  # below the value: the upper bounds (ratios <= 1) hold
            varies.append(f"{key}={0.8 * value!r}:{float(value)!r}:3")
    return varies


#: Keys varied at once (3 points each; 27 points at most). A mechanism's point is a
#: whole ODE reference and Kovylin's rows, up to 2 s on the crank press: one key; so
#: for a rope whose points run long references (0.4-0.7 s a point); two for the
#: hoists and mine hoists, whose points take 0.1-0.2 s (a grid of 9: 40 s of CI less).
KEYS_VARIED = {"mechanism": 1, "mine-hoist": 2, "hoist": 2, "stiff_rope.toml": 1}

CASE_FILES = [
    (name, path)
    for name in KERNELS
    for path in sorted((CASES / name).glob("*.toml"))
    + sorted((CASES / "extreme").glob(f"{name}_*.toml"))
]


@pytest.mark.parametrize(("name", "path"), CASE_FILES, ids=[f"{n}:{p.name}" for n, p in CASE_FILES])
def test_kernel_equals_point_by_point(name: str, path: Path, monkeypatch, tmp_path):
    import tomllib

    import tomli_w

    from mdcalc.errors import InputError
    from mdcalc.runs import sweep as sweeps
    from mdcalc.runs.sweep import evaluate, parse_vary, plan

    module = PROBLEMS[name].load()
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    if path.name in SHORTER:
        data = shorter(path, data)
        path = tmp_path / path.name
        path.write_text(tomli_w.dumps(data), encoding="utf-8")
    varies = _grid(data, module.SWEEP_KEYS, module.Case)
    varies = varies[: KEYS_VARIED.get(path.name, KEYS_VARIED.get(name, 3))]
    if not varies:
        pytest.skip("the case holds no key the kernel varies")
    try:
        sweep = plan(path, [parse_vary(v) for v in varies])
    except InputError as exc:  # a grid corner outside a cross-field rule
        pytest.skip(f"grid not valid here: {exc}")
    from mdcalc.input.casefile import validate
    from mdcalc.runs.sweep import choose_results

    # Ask the kernel first: a scene it hands back (an ODE, a no-answer point) would
    # otherwise run point by point twice before the skip (minutes for rope scenes).
    mesh = np.meshgrid(*[np.asarray(a, dtype=float) for a in sweep.axes], indexing="ij")
    grid = {v.key: m.ravel() for v, m in zip(sweep.varies, mesh, strict=True)}
    answer = module.sweep(validate(module.Case, sweep.case), grid)
    wanted, _ = choose_results(sweep, [])
    if answer is None or not all(key in answer for key in wanted):
        pytest.skip("the scene needs the point-by-point path (an ODE or a no-answer point)")
    fast = evaluate(sweep, [], 1)
    with monkeypatch.context() as patch:
        patch.setattr(module, "sweep", lambda case, grid, wanted=None: None)
        # each point's references alone (no ODE check rows), as a study's sample runs
        patch.setattr(sweeps, "reference_only_fits", lambda *args: True)
        slow = evaluate(sweep, [], 1)
    if not fast.vectorized:
        pytest.skip("the scene needs the point-by-point path (an ODE)")
    assert not slow.vectorized
    assert list(fast.status) == list(slow.status)  # declined points solved alone
    for key in fast.keys:
        rtol, atol = tolerance(module, key, 1e-11)
        np.testing.assert_allclose(
            fast.columns[key], slow.columns[key], rtol=rtol, atol=atol, err_msg=key
        )
        assert list(np.isnan(fast.columns[key])) == list(np.isnan(slow.columns[key])), key


def test_a_huge_grid_is_refused_before_it_is_built(cli):
    # 10¹¹ points of one key, and 10⁴ × 10⁴ in two: exit 2 at once, not a hang.
    lecture = CASES / "braking" / "lecture.toml"
    one = cli("sweep", lecture, "--vary", "vehicle.mass=1:2:100000000000")
    two = cli("sweep", lecture, "--vary", "vehicle.mass=1:2:10000", "--vary", "gravity=9:10:10000")
    for result in (one, two):
        assert result.exit_code == 2, result.stderr
        assert "the limit is 10,000,000" in result.stderr


def test_a_branch_that_holds_nowhere_on_the_grid_is_not_run():
    # xp.where runs only the branch that holds when the condition is the same over
    # the whole grid, and still gives the grid's shape; a mixed one blends both.
    from mdcalc.core.xp import arrays

    xp, ran = arrays(), []

    def branch(name: str, value: float):
        return lambda: ran.append(name) or (value, np.array([value] * 3))

    speed = np.array([1.0, 2.0, 3.0])
    same = xp.where(speed > 0.0, branch("then", 1.0), branch("else", 2.0))
    assert ran == ["then"]
    assert [list(column) for column in same] == [[1.0] * 3, [1.0] * 3]
    ran.clear()
    assert list(xp.where(speed > 5.0, lambda: speed, lambda: 0.0)) == [0.0] * 3
    mixed = xp.where(speed > 1.5, branch("then", 1.0), branch("else", 2.0))
    assert ran == ["then", "else"]
    assert list(mixed[0]) == [2.0, 1.0, 1.0]


def test_the_braking_kernel_is_bit_identical_whether_branches_are_skipped_or_blended(
    monkeypatch,
):
    # The lecture scene (no drag, no stop in the reaction) takes one branch of each
    # condition over a whole grid; blending both as before gives the same bits.
    from mdcalc.core import xp
    from mdcalc.input.casefile import read_case, validate

    module = PROBLEMS["braking"].load()
    case = validate(module.Case, read_case(CASES / "braking" / "lecture.toml"))
    mass, speed = np.meshgrid(np.linspace(800, 3000, 40), np.linspace(5, 50, 30))
    grid = {"vehicle.mass": mass.ravel(), "vehicle.initial_speed": speed.ravel()}
    skipped = module.sweep(case, grid)

    def blend(self, condition, then, otherwise):
        with np.errstate(all="ignore"):
            if np.ndim(condition) == 0:
                return then() if condition else otherwise()
            chosen, other = then(), otherwise()
            if isinstance(chosen, tuple):
                return tuple(np.where(condition, a, b) for a, b in zip(chosen, other, strict=True))
            return np.where(condition, chosen, other)

    monkeypatch.setattr(xp.Arrays, "where", blend)
    blended = module.sweep(case, grid)
    assert skipped.keys() == blended.keys()
    for key in skipped:
        assert np.shape(skipped[key]) == np.shape(blended[key]) == (1200,), key
        np.testing.assert_array_equal(skipped[key], blended[key], err_msg=key)


def test_a_heavy_kernel_sweep_runs_in_blocks_on_the_pool_bit_identical(monkeypatch):
    # A kernel whose first block of points takes long (here: any) sends the other
    # blocks to the pool, as a study's samples go: the columns and statuses of the
    # sweep run whole in this process, bit for bit, no-answer points solved alone.
    from mdcalc.runs import kernel
    from mdcalc.runs import sweep as sweeps

    case = CASES / "mine-hoist" / "seed_1025.toml"
    varies = ["hoist.rope_stiffness=5e5:1.2e6:25", "loads.load_torque=4e5:1.05e6:20"]
    plan = sweeps.plan(case, [sweeps.parse_vary(v) for v in varies])
    wanted = ["mu12_first_swing", "mu23_first_swing_time", "peak_moment_23"]
    here = sweeps.evaluate(plan, wanted, 1)
    monkeypatch.setattr(sweeps, "BLOCK", 97)
    monkeypatch.setattr(kernel, "HEAVY_BLOCK_SECONDS", 0.0)
    monkeypatch.setattr(kernel, "PROBE", 40)  # two probes here, then pieces on the pool
    shipped = []
    real = kernel.kernel_parts

    def spy(*args):
        parts, where = real(*args)
        shipped.append(where)
        return parts, where

    monkeypatch.setattr(kernel, "kernel_parts", spy)
    pooled = sweeps.evaluate(plan, wanted, 2)
    assert here.vectorized and pooled.vectorized
    assert shipped == ["process pool, 2 jobs"]
    assert list(pooled.status) == list(here.status) and 3 in set(here.status.tolist())
    for key in here.keys:
        assert np.array_equal(here.columns[key], pooled.columns[key], equal_nan=True), key


def test_a_heavy_kernel_goes_to_the_pool_in_large_equal_pieces():
    # Pieces of 512 rows ran the adhesion-limited car's ODE kernel at a fifth of its
    # rate in pieces of 16 384 (each call pays its steps' Python work once): a piece
    # is a job's share (four a job), at least PROBE rows, at most a block; the
    # blocks' rows are cut end to end into pieces of equal size, a multiple of the
    # jobs in number (a small remainder left a job idle), no more than the rows.
    from mdcalc.runs.kernel import BLOCK, PROBE, _pieces, piece_size

    assert piece_size(99_000, 2) == 12_375
    assert piece_size(10**6, 2) == BLOCK
    assert piece_size(2_000, 2) == PROBE
    assert piece_size(99_000, 0) == 24_750
    for rows, jobs, count in ((200_000 - 2 * PROBE, 2, 8), (10**6, 2, 16), (10**6, 3, 18),
                              (1_100, 2, 4), (600, 3, 3), (1, 2, 1), (5, 8, 5)):  # fmt: skip
        pieces = _pieces(np.arange(rows), jobs)
        sizes = [len(p) for p in pieces]
        assert len(pieces) == count, (rows, jobs, sizes)
        assert max(sizes) - min(sizes) <= 1 and min(sizes) >= 1
        assert max(sizes) <= max(piece_size(rows, jobs), 1)
        assert np.array_equal(np.concatenate(pieces), np.arange(rows))


#: Eight arrays of 1 MB, filled and freed 50 times (as the stages of a block's
#: integration step are): with glibc's defaults each round gets fresh pages from the
#: system (about 10⁵ page faults here), with steady_heap none.
HEAP_ROUNDS = """
import resource, sys
import numpy as np
if sys.argv[1] == "steady":
    from mdcalc.runs.kernel import steady_heap
    steady_heap()
[np.ones(1 << 17) for _ in range(8)]  # the heap grown once
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(50):
    arrays = [np.ones(1 << 17) for _ in range(8)]
    del arrays
print(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)
"""


def test_a_kernel_process_keeps_its_freed_arrays_for_the_next_ones():
    import subprocess
    import sys

    def faults(how: str) -> int:
        done = subprocess.run([sys.executable, "-c", HEAP_ROUNDS, how],
                              capture_output=True, text=True, check=True)  # fmt: skip
        return int(done.stdout)

    plain = faults("plain")
    if plain < 10_000:
        pytest.skip(f"this C library keeps freed memory by itself ({plain} page faults)")
    assert faults("steady") < 1_000 < plain


def test_a_python_without_ctypes_leaves_the_heap_as_it_is(monkeypatch):
    import sys

    from mdcalc.runs.kernel import steady_heap

    monkeypatch.setitem(sys.modules, "ctypes", None)  # import ctypes raises ImportError
    assert steady_heap.__wrapped__() is None


def test_a_kernel_block_keeps_the_heap_steady_in_its_process(monkeypatch):
    import tomllib

    from mdcalc.runs import kernel

    calls = []
    monkeypatch.setattr(kernel, "steady_heap", lambda: calls.append(1))
    path = CASES / "braking" / "dry.toml"
    scene = tomllib.loads(path.read_text("utf-8"))
    scene.pop("expect", None)
    run = kernel.KernelChunk("braking", path, scene, ["vehicle.mass"], ["braking_force"])
    part = run(np.array([[1000.0], [2000.0]]))
    assert calls and part is not None and part["braking_force"][1] > part["braking_force"][0]


def test_the_pool_stream_of_pieces_runs_to_its_end(monkeypatch):
    # A pool's stream left suspended at its last piece kept the pool's manager
    # thread alive to the interpreter's exit, where Python 3.11's exit hook raced it
    # to a closed pipe (an OSError printed after the study's output, 2 runs in 10):
    # once the blocks are read, the stream has ended (and shut its pool down).
    from mdcalc.input.model import DECLINED
    from mdcalc.runs import kernel
    from mdcalc.runs.cluster import PoolMapper

    streams = []

    class Spy(PoolMapper):
        def __call__(self, func, items, on_done=None, on_error=None):
            def stream():
                for item in items:
                    yield func(item)

            streams.append(stream())
            return streams[-1]

    def run(block):
        return {"x": 2.0 * block[:, 0], DECLINED: np.zeros(len(block), dtype=bool)}

    monkeypatch.setattr(kernel, "HEAVY_BLOCK_SECONDS", 0.0)
    monkeypatch.setattr(kernel, "PROBE", 4)
    blocks = [np.arange(30.0)[:, None], np.arange(30.0, 50.0)[:, None]]
    parts, where = kernel.kernel_parts(run, blocks, Spy(2))
    joined = [part["x"] for _, part in zip(blocks, parts, strict=True)]
    assert where == "process pool, 2 jobs" and len(streams) == 1
    assert np.array_equal(np.concatenate(joined), 2.0 * np.arange(50.0))
    assert streams[0].gi_frame is None  # ended, not suspended


def test_pieces_of_a_block_join_with_a_lost_piece_failing_only_its_rows():
    # _joined: a piece lost on the pool fails its own rows (LOST, with the reason),
    # not the block; every piece lost gives the LostBlock; a declined piece, or
    # pieces whose keys differ, leave the block to the point-by-point path.
    from mdcalc.input.model import DECLINED
    from mdcalc.runs.kernel import LOST, LOST_REASON, LostBlock, _joined

    def piece(values: list[float], declined: list[bool]) -> dict:
        return {"x": np.array(values), DECLINED: np.array(declined)}

    a, b = piece([1.0, 2.0], [False, True]), piece([3.0], [False])
    gone = LostBlock("worker died")
    whole = _joined([a, gone, b], [2, 3, 1])
    assert np.array_equal(whole["x"], [1.0, 2.0, np.nan, np.nan, np.nan, 3.0], equal_nan=True)
    assert whole[DECLINED].tolist() == [False, True, False, False, False, False]
    assert whole[LOST].tolist() == [False, False, True, True, True, False]
    assert whole[LOST_REASON] == "worker died"
    assert LOST not in _joined([a, b], [2, 1])
    assert _joined([gone, gone], [2, 1]) is gone
    assert _joined([a, None], [2, 1]) is None
    assert _joined([a, {"y": np.array([1.0]), DECLINED: np.array([False])}], [2, 1]) is None


def test_pieces_that_span_blocks_are_cut_back_into_the_blocks():
    # The pool's pieces run the blocks' rows end to end, in a multiple of the jobs,
    # so that the jobs end together: a piece's answer is cut where a block ends, and
    # a piece lost for good marks its rows in each block it spans.
    from mdcalc.input.model import DECLINED
    from mdcalc.runs.kernel import LOST, LostBlock, _Fragments, _joined, _split

    pieces = _split(np.arange(13.0), 3)
    assert [len(p) for p in pieces] == [4, 4, 5]

    def answer(piece):
        return {"x": 2.0 * piece, DECLINED: piece > 11}

    answers = [answer(pieces[0]), LostBlock("lost"), answer(pieces[2])]
    flow = _Fragments(iter(answers), [len(p) for p in pieces])
    blocks = [_joined(*flow.take(n)) for n in (3, 6, 4)]
    assert blocks[0]["x"].tolist() == [0.0, 2.0, 4.0] and LOST not in blocks[0]
    assert blocks[1]["x"][:1].tolist() == [6.0] and np.isnan(blocks[1]["x"][1:5]).all()
    assert blocks[1]["x"][5] == 16.0 and blocks[1][LOST].tolist() == [0, 1, 1, 1, 1, 0]
    assert blocks[2]["x"].tolist() == [18.0, 20.0, 22.0, 24.0] and LOST not in blocks[2]
    assert blocks[2][DECLINED].tolist() == [False, False, False, True]


def test_value_at_finds_a_number_or_says_none():
    # the kernels' one question before they vary a key: a field, a list entry, a
    # table entry; None past a list's end, in a section the case leaves out, or for
    # a name the model does not have (no IndexError, no AttributeError)
    import tomllib

    from mdcalc.input.casefile import CaseText, validate
    from mdcalc.input.model import value_at

    module = PROBLEMS["acceleration"].load()
    path = CASES / "acceleration" / "vaz2106.toml"
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data.pop("expect", None)
    case = validate(module.Case, CaseText(path, "", data))
    gears = data["transmission"]["gear_ratios"]
    assert value_at(case, "transmission.gear_ratios.0") == gears[0]
    assert value_at(case, f"transmission.gear_ratios.{len(gears)}") is None
    assert value_at(case, "vehicle.mass") == data["vehicle"]["mass"]
    assert value_at(case, "vehicle.no_such_field") is None
    assert value_at(case, "transmission.gear_ratios.x") is None
    if "lecture" not in data:
        assert value_at(case, "lecture.traction_coefficient") is None


def _tiled_and_whole(monkeypatch, problem: str, case: str, grid: dict, tile: int):
    """A kernel's answer over ``grid`` computed whole and in tiles of ``tile`` rows."""
    import importlib
    import tomllib

    from mdcalc.input.casefile import CaseText, validate

    module = PROBLEMS[problem].load()
    kernel = importlib.import_module(f"mdcalc.problems.{problem}.kernel")
    path = CASES / problem / case
    data = shorter(path, tomllib.loads(path.read_text(encoding="utf-8")))
    data.pop("expect", None)
    model = validate(module.Case, CaseText(path, "", data))
    whole = kernel.sweep(model, grid)
    monkeypatch.setattr(kernel, "TILE_ROWS", tile)
    tiled = kernel.sweep(model, grid)
    assert whole is not None and tiled is not None and list(tiled) == list(whole)
    for key, values in whole.items():
        assert np.array_equal(values, tiled[key], equal_nan=True), key
    return tiled


def test_a_chain_kernel_in_tiles_gives_each_row_its_own_numbers(monkeypatch):
    # resonance's modal solution runs TILE_ROWS chains a call (its arrays stay in
    # the cache): a block of more tiles than one, with a declined row (no damping
    # moves in mode 2 where the cranks' damping is zero) in its last tile, gives the
    # numbers of the block computed whole, bit for bit.
    from mdcalc.input.model import DECLINED

    rng = np.random.default_rng(3)
    grid = {
        "chain.stiffnesses.6": 2.0e4 * rng.uniform(0.8, 1.2, 1000),
        "chain.damping.0": np.where(np.arange(1000) == 990, 0.0, 1.0),
        "resonance.harmonic_torque": 50.0,
    }
    for k in range(1, 6):
        grid[f"chain.damping.{k}"] = grid["chain.damping.0"]
    tiled = _tiled_and_whole(monkeypatch, "resonance", "inline_six.toml", grid, 128)
    assert tiled[DECLINED].tolist() == [k == 990 for k in range(1000)]


def test_tiles_whose_keys_differ_leave_the_block_whole():
    # in_tiles joins tiles only where each gives the same keys: else None, and the
    # kernel computes the block whole (a later tile without a key raised KeyError)
    from mdcalc.input.model import in_tiles

    def kernel(case, grid, wanted):
        x = np.asarray(grid["x"])
        out = {"double": 2.0 * x}
        if x[0] >= 10:  # a tile with a key the first has not
            out["extra"] = x
        return out

    whole = in_tiles(kernel, None, {"x": np.arange(12.0), "y": 3.0}, None, 4)
    assert whole is not None and whole["double"].tolist() == [2.0 * k for k in range(12)]
    assert in_tiles(kernel, None, {"x": np.arange(15.0)}, None, 5) is None
    assert in_tiles(kernel, None, {"x": np.arange(4.0)}, None, 4) is None  # one tile: whole


def test_a_block_is_cut_into_tiles_of_equal_size():
    # 21 845 rows (a third of a 64 Ki block) in tiles of at most 16 384: two of
    # 10 922 and 10 923, not 16 384 and a small tile of 5461 at a lower rate
    from mdcalc.input.model import in_tiles

    sizes = []

    def kernel(case, grid, wanted):
        sizes.append(np.size(grid["x"]))
        return {"x": np.asarray(grid["x"])}

    out = in_tiles(kernel, None, {"x": np.arange(21_845.0)}, None, 16_384)
    assert out is not None and np.array_equal(out["x"], np.arange(21_845.0))
    assert sizes == [10_922, 10_923]
    sizes.clear()
    in_tiles(kernel, None, {"x": np.arange(65_536.0)}, None, 16_384)
    assert sizes == [16_384] * 4
    for size, rows in ((10, 3), (699, 719), (700, 7), (701, 7), (13, 4)):
        sizes.clear()
        out = in_tiles(kernel, None, {"x": np.arange(float(size))}, None, rows)
        assert (out is None) == (size <= rows)
        if out is not None:
            assert np.array_equal(out["x"], np.arange(float(size)))
            assert len(sizes) == -(-size // rows) and max(sizes) - min(sizes) <= 1 <= min(sizes)
            assert max(sizes) <= rows


def test_a_variator_drive_kernel_in_tiles_gives_each_row_its_own_numbers(monkeypatch):
    # where each sample has its own drive, the variator's kernel solves TILE_ROWS
    # samples a call: the numbers of the block computed whole, bit for bit
    inertia = 0.05 * np.random.default_rng(5).uniform(0.8, 1.2, 300)
    grid = {"drive.driven_inertia": inertia}
    _tiled_and_whole(monkeypatch, "variator", "vk_variator.toml", grid, 64)


@pytest.mark.parametrize(
    ("problem", "case", "key", "rows", "tile"),
    [
        ("acceleration", "lecture.toml", "vehicle.mass", 24, 16),
        # a kink each revolution; 24 rows in 16 + 8 took 22 s on CI's cores
        ("mechanism", "crank_press.toml", "parameters.Mr", 6, 4),
    ],
)
def test_an_ode_kernel_in_tiles_gives_each_row_its_own_numbers(
    monkeypatch, problem, case, key, rows, tile
):
    # the ODE references step every row with its own error control: two tiles
    # give the whole block's numbers, bit for bit
    import tomllib

    data = tomllib.loads((CASES / problem / case).read_text(encoding="utf-8"))
    value = _held(data, key)
    assert value is not None
    column = value * np.random.default_rng(6).uniform(0.9, 1.0, rows)
    _tiled_and_whole(monkeypatch, problem, case, {key: column}, tile)


def _columns(block):
    """A kernel's answer with columns of one value (one of them NaN, one big-endian),
    one of 0 and -0 (two values bit for bit), and one that varies."""
    n = len(block)
    return {
        "same": np.full(n, 0.1 * block[0, 0]),
        "nan": np.full(n, np.nan),
        "zeros": np.where(np.arange(n) % 2 == 0, 0.0, -0.0),
        "varies": block[:, 0] / 3.0,
        "declined": np.zeros(n, dtype=bool),
        "big_endian": np.full(n, 2.5, dtype=">f8"),
    }


def test_a_pools_answers_come_back_compact_and_bit_for_bit():
    # Compact: a column of one value, bit for bit, crosses from a pool's process as
    # that value and is filled out as it is unpickled; 0 and -0 are two values;
    # the answers equal the kernel's run here, bit for bit, and here Compact gives
    # the answer as it is
    import pickle

    from mdcalc.runs.kernel import Compact, _Filled
    from mdcalc.runs.pool import pool_map

    blocks = [np.arange(5000.0)[:, None] + k for k in range(4)]
    answer = _columns(blocks[0])
    packed = {key: _Filled.of(values) for key, values in answer.items()}
    assert {k for k, v in packed.items() if isinstance(v, _Filled)} == {
        "same",
        "nan",
        "declined",
        "big_endian",
    }
    assert len(pickle.dumps(packed)) < 0.5 * len(pickle.dumps(answer))
    assert Compact(_columns)(blocks[0]).keys() == answer.keys()
    assert all(isinstance(v, np.ndarray) for v in Compact(_columns)(blocks[0]).values())
    for got, block in zip(pool_map(Compact(_columns), blocks, 2), blocks, strict=True):
        want = _columns(block)
        for key, values in want.items():
            assert type(got[key]) is np.ndarray and got[key].dtype == values.dtype
            assert got[key].tobytes() == values.tobytes()
