"""Every run ends with a plain answer (issue 20, item 5): one shipped case per problem,
each numeric field set in turn to 1e-12, 1e12, 1e17, 5e-324, 2.2e-308, 1e-300 and the
edges of its validated bounds, run with a small --time-limit. Every run exits 0, 2 or
3 (never 70, never a hang), says why in one stderr line when it is 2 or 3, writes no
NaN or infinity, and comes back within its budget + 1 s.

Fields, bounds and the values to try are read from each problem's ``Case`` model
(``tests/test_fuzz.py``'s reader), so a field or a problem added later is probed
without new code; ``PROBE_CASES`` must name a case for every registered problem.
"""

from __future__ import annotations

import math
import time
import tomllib

import pytest
import tomli_w

from mdcalc.problems import PROBLEMS
from tests.conftest import CASES, strict_json, walk_finite
from tests.test_fuzz import LIMIT, Node, dotted, numbers, replaced, top

#: The case each problem is probed from: a scene that runs every part of its solver.
PROBE_CASES = {
    "braking": "braking/drag_build_up.toml",
    "acceleration": "acceleration/lecture.toml",
    "hoist": "hoist/crane.toml",
    "mount": "mount/example_9_1.toml",
    "coupling": "extreme/coupling_heavily_damped_pulse.toml",
    "mine-hoist": "mine-hoist/seed_1025.toml",
    "variator": "variator/vk_variator.toml",
    "clutch": "clutch/fig2_differentiated.toml",
    "mechanism": "mechanism/crank_press.toml",
    "resonance": "resonance/inline_six.toml",
}
#: The probe's time limit per run [s]; a run must be back within BUDGET + 1 s.
BUDGET = 1.0
EXTREMES = (1e-12, 1e12, 1e17)
#: A subnormal float, the smallest normal one and one a few products from underflow
#: (issue 33, item 7): refused by the models' floor (exit 2), never exit 70.
TINY = (5e-324, 2.2e-308, 1e-300)


def values_to_try(here: Node) -> list[float | int]:
    """1e-12, 1e12, 1e17, the tiny values and just inside each finite bound of the
    field."""
    out: list[float] = list(EXTREMES) + ([] if here.integer else list(TINY))
    if here.lo > -LIMIT:
        out.append(math.nextafter(here.lo, math.inf) if here.lo_open else here.lo)
        if here.lo_open and here.lo == 0.0:
            out.append(1e-300)
    if here.hi < LIMIT:
        out.append(math.nextafter(here.hi, -math.inf) if here.hi_open else here.hi)
    if here.integer:
        return sorted({int(v) for v in out if v >= 1 or v == 0})
    return sorted(set(out))


def probes() -> list[tuple[str, str, tuple[str | int, ...], float | int]]:
    out = []
    for name, case in PROBE_CASES.items():
        data = tomllib.loads((CASES / case).read_text(encoding="utf-8"))
        data.pop("expect", None)
        for path, here in numbers(data, top(name)):
            if any(isinstance(k, int) and k > 0 for k in path):
                continue  # one element of an array stands for the array
            out.extend((name, case, path, value) for value in values_to_try(here))
    return out


PROBES = probes()


def test_every_problem_has_a_probe_case():
    assert set(PROBE_CASES) == set(PROBLEMS)


@pytest.mark.parametrize(
    ("name", "case", "path", "value"),
    PROBES,
    ids=[f"{n}-{dotted(p)}={v!r}" for n, _, p, v in PROBES],
)
def test_every_run_ends_with_a_plain_answer(cli, write_case, name, case, path, value):
    data = tomllib.loads((CASES / case).read_text(encoding="utf-8"))
    data.pop("expect", None)
    file = write_case(tomli_w.dumps(replaced(data, path, value)))
    start = time.perf_counter()
    result = cli(name, file, "--json", "--time-limit", str(BUDGET))
    seconds = time.perf_counter() - start
    assert result.exit_code in (0, 2, 3), (result.exit_code, result.stderr[-2000:])
    assert seconds < BUDGET + 1.0, f"{seconds:.2f} s"
    lines = result.stderr.strip().splitlines()
    if result.exit_code == 0:
        assert lines == [], lines  # no warnings from numpy or scipy
        walk_finite(strict_json(result.stdout))
    else:
        assert len(lines) == 1 or result.exit_code == 2, lines
        assert all(line.startswith(f"{file}") for line in lines), lines
        assert "Traceback" not in result.stderr
    if result.exit_code == 3:
        walk_finite(strict_json(result.stdout))
