"""The wide probe behind the reliability figures (docs/reliability.md) (not part of `make test`).

Every numeric field of 21 shipped cases (all ten problems) set in turn to 1e-12,
1e12, 1e17 and just inside its bounds, each run in-process through the CLI with
``--json --time-limit BUDGET`` under a watchdog of BUDGET + 5 s, two processes at a
time. Prints each run that fails (exit 70, a hang, more than one stderr line for exit
2/3, stderr output for exit 0, NaN/inf in the JSON) and the counts.

    .venv/bin/python bench/probe.py [--budget 5] [--jobs 2]
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
import tempfile
import time
import tomllib
from collections import Counter
from multiprocessing import Pool
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import tomli_w  # noqa: E402

from tests.test_fuzz import dotted, numbers, replaced, top  # noqa: E402
from tests.test_probe import values_to_try  # noqa: E402

CASES = ROOT / "cases"
PROBED = """braking/lecture.toml extreme/braking_drag_only_driver_delay.toml
acceleration/lecture.toml acceleration/constant_force_drag.toml
hoist/crane.toml hoist/stiff_rope.toml
mount/example_9_1.toml extreme/mount_overdamped_resonance.toml
coupling/overdamped.toml extreme/coupling_heavily_damped_pulse.toml coupling/harmonic.toml
mine-hoist/seed_1025.toml mine-hoist/light_sheave.toml
variator/absorber_damped.toml variator/drive_resonance.toml variator/vk_variator.toml
clutch/fig2_differentiated.toml
mechanism/crank_press.toml mechanism/motor_startup.toml
resonance/inline_six.toml resonance/mathieu.toml""".split()


class Hang(BaseException):
    pass


def case_data(relative: str) -> dict[str, Any]:
    data = tomllib.loads((CASES / relative).read_text(encoding="utf-8"))
    data.pop("expect", None)
    return data


def runs() -> list[tuple[str, str, tuple[str | int, ...], float]]:
    out = []
    for relative in PROBED:
        data = case_data(relative)
        for path, here in numbers(data, top(data["problem"])):
            out.extend((relative, data["problem"], path, v) for v in values_to_try(here))
    return out


def finite_json(text: str) -> bool:
    """Does ``text`` parse as JSON without NaN or Infinity tokens?"""

    def refuse(token: str) -> Any:
        raise ValueError(token)

    try:
        json.loads(text, parse_constant=refuse)
    except ValueError:
        return False
    return True


def one(job: tuple[str, str, tuple[str | int, ...], float, float]) -> tuple[Any, ...]:
    from typer.testing import CliRunner

    from mdcalc.cli.app import app

    relative, name, path, value, budget = job
    with tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False) as handle:
        handle.write(tomli_w.dumps(replaced(case_data(relative), path, value)))
    args = [name, handle.name, "--json", "--time-limit", str(budget)]

    def hang(*_: Any) -> None:
        raise Hang

    signal.signal(signal.SIGALRM, hang)
    signal.setitimer(signal.ITIMER_REAL, budget + 5.0)
    start = time.perf_counter()
    try:
        result = CliRunner().invoke(app, args)
        code, stdout, stderr = result.exit_code, result.stdout, result.stderr
    except Hang:
        code, stdout, stderr = "hang", "", ""
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        os.unlink(handle.name)
    seconds = time.perf_counter() - start
    bad = []
    if code not in (0, 2, 3):
        bad.append(f"exit {code}")
    lines = stderr.strip().splitlines()
    if code == 3 and len(lines) != 1:
        bad.append("not one stderr line")
    if code == 0 and lines:
        bad.append("stderr output")
    if code in (0, 3) and not finite_json(stdout):
        bad.append("non-finite number")
    return relative, dotted(path), value, code, seconds, bad, stderr.strip()[-300:]


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--budget", type=float, default=5.0)
    parser.add_argument("--jobs", type=int, default=2)
    options = parser.parse_args()
    jobs = [(*run, options.budget) for run in runs()]
    print(f"{len(jobs)} runs over {len(PROBED)} cases, --time-limit {options.budget:g}")
    results = []
    with Pool(options.jobs, maxtasksperchild=20) as pool:
        for result in pool.imap_unordered(one, jobs):
            results.append(result)
            if result[5]:
                print("FAILED", *result[:4], f"{result[4]:.2f} s", result[5], result[6])
    codes = Counter(r[3] for r in results)
    failed = sum(1 for r in results if r[5])
    longest = max(r[4] for r in results)
    over = sum(1 for r in results if r[4] > 1.0)
    print(
        f"{len(results)} runs, {failed} failed; exits {dict(sorted(codes.items(), key=str))}; "
        f"{over} over 1 s, the longest {longest:.2f} s"
    )


if __name__ == "__main__":
    main()
