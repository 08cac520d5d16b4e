"""``make bench``: the figures of the performance page (docs/performance.md).

Each figure is a ratio or a rate measured in this one run, so that a slow or busy
machine slows both sides alike. Nothing here asserts a time: it prints the figures
and the issue's targets beside them. Run from the repository root.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
MDCALC = str(Path(sys.executable).parent / "mdcalc")
PYTHON = sys.executable
REPEATS = 15


def wall(command: list[str]) -> float:
    """Seconds the command took; it must succeed (a quick failure is no figure)."""
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, check=False)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"bench: {' '.join(command)[:300]}: exit {done.returncode}\n{done.stderr}")
    return seconds


def best_of_interleaved(a: list[str], b: list[str], repeats: int = REPEATS) -> tuple[float, float]:
    """Best wall time of each command, the runs interleaved (a, b, a, b, ...)."""
    times_a, times_b = [], []
    for _ in range(repeats):
        times_a.append(wall(a))
        times_b.append(wall(b))
    return min(times_a), min(times_b)


def row(name: str, figure: str, target: str, met: bool) -> None:
    print(f"{name:58s} {figure:>28s}   target {target:10s} {'met' if met else 'MISSED'}")


#: The floor of the stack the design card fixes: the CLI framework, the model
#: library and the terminal renderer, imported and nothing done.
FLOOR = "import typer; from pydantic import BaseModel; import rich.console, rich.table"


def compiled(root: Path = ROOT) -> None:
    """Byte-compile mdcalc as an installed wheel is (pip compiles at install), so that
    an editable checkout under PYTHONDONTWRITEBYTECODE is not charged for compiling
    its modules on every start (~40 ms)."""
    import compileall

    compileall.compile_dir(str(root / "mdcalc"), quiet=1)


def startup() -> None:
    compiled()
    lecture = str(ROOT / "cases" / "braking" / "lecture.toml")
    base, ours = best_of_interleaved([PYTHON, "-c", FLOOR], [MDCALC, "braking", lecture])
    ratio = ours / base
    row(
        "mdcalc braking lecture.toml (piped) / the stack's floor",
        f"{ours * 1e3:.0f} / {base * 1e3:.0f} ms = {ratio:.2f}",
        "<= 1.2",
        ratio <= 1.2,
    )
    base, ours = best_of_interleaved([PYTHON, "-c", "import typer"], [MDCALC, "--help"])
    ratio = ours / base
    row(
        "mdcalc --help / python -c 'import typer'",
        f"{ours * 1e3:.0f} / {base * 1e3:.0f} ms = {ratio:.2f}",
        "<= 1.2",
        ratio <= 1.2,
    )


#: One scene per problem, for the start-up of a single command against another checkout.
STARTUP_CASES = [
    ("--help", None),
    ("braking", "braking/lecture.toml"),
    ("clutch", "clutch/fig2_differentiated.toml"),
    ("hoist", "hoist/lift.toml"),
    ("mount", "mount/example_9_1.toml"),
    ("coupling", "coupling/example_8_1.toml"),
    ("acceleration", "acceleration/lecture.toml"),
    ("mine-hoist", "mine-hoist/seed_1025.toml"),
    ("variator", "variator/two_disk_absorber.toml"),
    ("mechanism", "mechanism/crank_press.toml"),
    ("resonance", "resonance/inline_six.toml"),
]


def console_entry(root: Path) -> tuple[str, str]:
    """(module, function) of the ``mdcalc`` console script in the checkout at
    ``root``, as its pyproject.toml names it (``mdcalc.cli.launch:main``; before the
    layers, ``mdcalc.launch:main``)."""
    import tomllib

    with (root / "pyproject.toml").open("rb") as handle:
        entry = tomllib.load(handle)["project"]["scripts"]["mdcalc"]
    module, _, function = entry.partition(":")
    return module, function


def from_source(root: Path) -> list[str]:
    """mdcalc run from the checkout at ``root`` rather than the installed one (the
    editable install's finder is set aside), in this same interpreter and venv, through
    that checkout's console script."""
    module, function = console_entry(root)
    code = (
        "import sys\n"
        "sys.meta_path = [f for f in sys.meta_path if 'editable' not in repr(f).lower()]\n"
        f"sys.path.insert(0, {str(root)!r})\n"
        f"from {module} import {function}\n"
        "sys.argv[0] = 'mdcalc'\n"
        f"sys.exit({function}())\n"
    )
    return [PYTHON, "-c", code]


def startup_against(other: Path) -> None:
    """Start-up of one scene of every problem, this checkout against ``other`` (for
    example the commit before a refactoring), interleaved in one run."""
    print(f"start-up, this checkout against {other} (best of {REPEATS}, interleaved):")
    compiled()
    compiled(other)
    total_theirs = total_ours = 0.0
    for problem, case in STARTUP_CASES:
        args = [problem] if case is None else [problem, str(ROOT / "cases" / case)]
        if case is not None and not (other / "cases" / case).exists():
            continue
        theirs, ours = best_of_interleaved(from_source(other) + args, from_source(ROOT) + args)
        total_theirs, total_ours = total_theirs + theirs, total_ours + ours
        print(
            f"  {' '.join([problem, *(case and [case] or [])]):58s} "
            f"{theirs * 1e3:6.0f} -> {ours * 1e3:6.0f} ms  ({ours / theirs:.2f})"
        )
    print(
        f"  {'all of them':58s} {total_theirs * 1e3:6.0f} -> {total_ours * 1e3:6.0f} ms  "
        f"({total_ours / total_theirs:.2f})"
    )


def braking_cases(folder: Path, count: int) -> Path:
    """``count`` generated braking case files (seeded) in a new folder."""
    cases = folder
    cases.mkdir()
    import random

    rng = random.Random(2026)
    for i in range(count):
        (cases / f"case_{i:06d}.toml").write_text(
            'problem = "braking"\n'
            f"[vehicle]\nmass = {rng.uniform(800, 3000):.1f}\n"
            f"initial_speed_kmh = {rng.uniform(30, 150):.1f}\n"
            f"[road]\nadhesion = {rng.uniform(0.1, 0.9):.3f}\nresistance = 0.015\n"
            f"[driver]\nreaction_time = {rng.uniform(0.5, 1.5):.2f}\nbuild_up_time = 0.2\n",
            encoding="utf-8",
        )
    return cases


def batch(folder: Path) -> None:
    cases = braking_cases(folder / "cases", 1000)
    best = min(wall([MDCALC, "run", str(cases), "--jobs", "2", "--json"]) for _ in range(3))
    rate = 1000 / best
    row(
        "mdcalc run: 1000 braking cases, --jobs 2 --json (wall)",
        f"{best:.2f} s = {rate:.0f} cases/s",
        ">= 1000/s",
        rate >= 1000,
    )
    out = folder / "out"
    best = min(
        wall([MDCALC, "run", str(cases), "--jobs", "2", "--out", str(out)]) for _ in range(3)
    )
    rate = 1000 / best
    row(
        "mdcalc run: the same, --out DIR (1000 files written)",
        f"{best:.2f} s = {rate:.0f} cases/s",
        ">= 1000/s",
        rate >= 1000,
    )


def sweep(folder: Path) -> None:
    lecture = str(ROOT / "cases" / "braking" / "lecture.toml")
    grid = ["--vary", "vehicle.mass=800:3000:1000", "--vary", "vehicle.initial_speed=5:50:1000"]
    best = min(wall([MDCALC, "sweep", lecture, *grid]) for _ in range(3))
    row(
        "mdcalc sweep: 10^6 braking points, summary on stdout", f"{best:.2f} s", "<= 2 s", best <= 2
    )
    csv = folder / "sweep.csv"
    best = min(wall([MDCALC, "sweep", lecture, *grid, "--out", str(csv)]) for _ in range(3))
    row("mdcalc sweep: the same, --out sweep.csv (75 MB)", f"{best:.2f} s", "<= 0.8 s", best <= 0.8)


def growth(folder: Path) -> None:
    """The cost of growth: ``run`` over 10³, 10⁴, 10⁵ generated braking files and
    ``sweep`` over 10³ … 10⁶ braking points (``--out .csv``), whole commands, with the
    cost per item and the marginal cost between sizes (start-up excluded)."""
    print("growth (whole command; per item; marginal per item from the size before):")
    previous: tuple[int, float] | None = None
    for count in (1_000, 10_000, 100_000):
        cases = braking_cases(folder / f"growth_{count}", count)
        seconds = wall([MDCALC, "run", str(cases), "--jobs", "2", "--json"])
        _growth_row("run --jobs 2 --json", count, seconds, previous)
        previous = (count, seconds)
        shutil.rmtree(cases, ignore_errors=True)
    lecture = str(ROOT / "cases" / "braking" / "lecture.toml")
    previous = None
    for side in (32, 100, 317, 1000):
        count = side * side
        grid = [
            "--vary",
            f"vehicle.mass=800:3000:{side}",
            "--vary",
            f"vehicle.initial_speed=5:50:{side}",
        ]
        csv = folder / "growth.csv"
        seconds = wall([MDCALC, "sweep", lecture, *grid, "--out", str(csv)])
        _growth_row("sweep --out .csv (braking)", count, seconds, previous)
        previous = (count, seconds)


def _growth_row(what: str, count: int, seconds: float, previous: tuple[int, float] | None) -> None:
    per = seconds / count * 1e6
    marginal = ""
    if previous is not None:
        marginal = f", marginal {(seconds - previous[1]) / (count - previous[0]) * 1e6:.1f} µs"
    print(f"  {what:32s} {count:>9,} items  {seconds:7.2f} s  {per:8.1f} µs/item{marginal}")


def timed(run: Callable[[], object], repeats: int = 5) -> float:
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - start)
    return best


def mine_hoist() -> None:
    import numpy as np

    from mdcalc.core import chain as chains
    from mdcalc.core.ode import TooManySteps, linear_oscillator_maxima
    from mdcalc.input.casefile import read_case, validate
    from mdcalc.problems import mine_hoist
    from mdcalc.problems.mine_hoist.modal import dynamics, first_swing_factors, frequency_ratio
    from mdcalc.problems.mine_hoist.ode_rows import STIFF_RATIO
    from mdcalc.problems.mine_hoist.scene import scene_at

    for name, target in (("seed_1025", 0.1), ("stiff_chord", 0.2)):
        case = validate(mine_hoist.Case, read_case(ROOT / "cases" / "mine-hoist" / f"{name}.toml"))
        scene = scene_at(case)
        dyn = dynamics(scene)
        a, f = chains.moment_equations(scene.chain, scene.torques)
        r = np.array(dyn.static)
        exact = first_swing_factors(scene)
        modal = timed(lambda: first_swing_factors(scene))  # noqa: B023
        stiff = frequency_ratio(dyn) >= STIFF_RATIO
        for method in ("DOP853", "Radau") if stiff else ("DOP853",):
            outcome: dict[str, float] = {}

            def run(method: str = method, outcome: dict[str, float] = outcome) -> None:
                peaks, _, _ = linear_oscillator_maxima(
                    a * r[None, :] / r[:, None],  # noqa: B023
                    f / r,  # noqa: B023
                    dyn.period,  # noqa: B023
                    1e-10,
                    method,
                    max_evaluations=400_000,
                )
                outcome["mu12"], outcome["mu23"] = peaks[0], peaks[1]

            try:
                seconds = timed(run, repeats=3 if not stiff else 1)
            except TooManySteps:
                row(f"mine-hoist {name}: ODE {method} rtol 1e-10", "> 4e5 evaluations", "", False)
                continue
            error = max(abs(outcome[k] - exact[k]) / exact[k] for k in ("mu12", "mu23"))
            row(
                f"mine-hoist {name} (β₂/β₁ {frequency_ratio(dyn):.0f}): ODE {method} 1e-10",
                f"{seconds * 1e3:.0f} ms, err {error:.1e}",
                f"<= {target * 1e3:.0f} ms",
                seconds <= target,
            )
        row(f"mine-hoist {name}: modal solution (the reference)", f"{modal * 1e3:.2f} ms", "", True)


#: One scene per problem for the study rates, and the key each study draws (±5 %).
RATE_SCENES = [
    ("braking", "braking/dry.toml", "vehicle.mass"),
    ("mount", "mount/example_9_1.toml", "mounts.static_deflection"),
    ("coupling", "coupling/example_8_1.toml", "coupling.absorption"),
    ("clutch", "clutch/fig2_differentiated.toml", "clutch.spring_force"),
    ("hoist (no rope)", "studies/hoist_load.toml", "load.mass"),
    ("hoist (rope)", "hoist/crane.toml", "load.mass"),
    ("mine-hoist", "studies/mine_hoist_rope.toml", "hoist.rope_stiffness"),
    ("resonance", "resonance/inline_six.toml", "chain.stiffnesses.6"),
    ("resonance Mathieu", "resonance/mathieu.toml", "mathieu.damping"),
    ("variator", "variator/two_disk_absorber.toml", "absorber.inertia"),
    ("variator pendulum", "variator/pendulum.toml", "pendulum.order"),
    ("variator drive", "variator/vk_variator.toml", "drive.driven_inertia"),
    ("mechanism", "studies/mechanism_inertia.toml", "inertia.value"),
    ("mechanism tables", "mechanism/tabulated_press.toml", "motion.start_speed"),
    ("acceleration", "acceleration/lecture.toml", "vehicle.mass"),
    ("acceleration adhesion", "acceleration/high_power.toml", "vehicle.mass"),
]

#: Sizes of a kernel scene's two studies where 10⁶ samples would take minutes (the
#: mechanism with tables at 5·10⁴ and 2·10⁵: at 10³ and 5·10³ the pool's pieces are
#: 512 rows, a third of the rate of pieces of thousands, and between 10⁴ and 5·10⁴
#: its rate came out up to a third above that of larger studies).
KERNEL_SIZES = {
    "resonance Mathieu": (10_000, 100_000),
    "variator drive": (10_000, 100_000),
    "mechanism tables": (50_000, 200_000),
}


def study_rates(folder: Path) -> None:
    """Issue 31's table: the marginal samples per second of a study of every
    problem (the study's own sampling_seconds at two sizes, so set-up is left out),
    and its ratio to braking's kernel in the same run. A kernel problem is measured
    at 10⁵ and 10⁶ samples (KERNEL_SIZES: fewer for the Mathieu points, 8 ODE runs a
    sample, the variator's drive and a mechanism with tables), one that runs sample
    by sample at 8 and 24 (2 jobs)."""
    import tomllib

    print("study rates (marginal samples/s between two sizes; one key ±5 %, default results):")
    base_rate = None
    for name, case, key in RATE_SCENES:
        data = tomllib.loads((ROOT / "cases" / case).read_text("utf-8"))
        for extra in ("expect", "study"):
            data.pop(extra, None)
        how, seconds = _study_rate(folder, name, data, key, 8)  # which way, before hours
        sizes = KERNEL_SIZES.get(name, (100_000, 1_000_000)) if "kernel" in how else (8, 24)
        timings = [
            (n, seconds if n == 8 else _study_rate(folder, name, data, key, n)[1]) for n in sizes
        ]
        (n1, t1), (n2, t2) = timings[0], timings[-1]
        rate = (n2 - n1) / max(t2 - t1, 1e-9)
        base_rate = rate if base_rate is None else base_rate
        print(f"  {name:16s} {key:28s} {how[:34]:34s} {rate:12.3g}  ({rate / base_rate:.2g})")
    print(
        "  targets (issue 31): >= 1e5 closed-form and modal keys, >= 2e4 mechanism, "
        "acceleration, >= 1e3 Mathieu stability"
    )


def _study_rate(
    folder: Path, name: str, data: dict[str, Any], key: str, samples: int
) -> tuple[str, float]:
    """(how, sampling_seconds) of a study of ``data`` drawing ``key`` ±5 %."""
    import json

    import tomli_w

    node: Any = data
    for part in key.split("."):
        node = node[int(part)] if isinstance(node, list) else node[part]
    study = {"samples": samples, "seed": 1, "inputs": {key: {"nominal": node, "tol": "±5 %"}}}
    path = folder / "rate.toml"
    path.write_text(tomli_w.dumps({**data, "study": study}), encoding="utf-8")
    done = subprocess.run([MDCALC, "study", str(path), "--json", "--jobs", "2"],
                          capture_output=True, text=True, check=False)  # fmt: skip
    if done.returncode != 0:
        raise SystemExit(f"bench: {name}: exit {done.returncode}: {done.stderr[:300]}")
    document = json.loads(done.stdout)
    return document["how"], document["sampling_seconds"]


def studies(folder: Path) -> None:
    """10⁶ braking samples (the kernel), 10⁴ mine-hoist samples on the pool against a
    LocalCluster of 2 workers, one Sobol study."""
    braking = (ROOT / "cases" / "studies" / "braking_adhesion.toml").read_text("utf-8")
    big = folder / "braking_1e6.toml"
    big.write_text(
        braking.replace("samples = 100_000", "samples = 1_000_000")
        .replace("sensitivity = true", "sensitivity = false")
        .split("[expect]")[0],
        encoding="utf-8",
    )
    best = min(wall([MDCALC, "study", str(big)]) for _ in range(3))
    row("mdcalc study: 10^6 braking samples (kernel, LHS, units)", f"{best:.2f} s",
        "<= 1 s (issue 31)", best <= 1)  # fmt: skip
    plain = folder / "braking_1e6_plain.toml"
    plain.write_text(
        big.read_text("utf-8")
        .replace('sampler = "lhs"', 'sampler = "random"')
        .replace('mean = "1500 kg", sd = "75 kg"', "mean = 1500, sd = 75"),
        encoding="utf-8",
    )
    best = min(wall([MDCALC, "study", str(plain)]) for _ in range(3))
    row("  the same, random draws, plain numbers", f"{best:.2f} s", "<= 1 s",
        best <= 1)  # fmt: skip
    mine = (ROOT / "cases" / "studies" / "mine_hoist_rope.toml").read_text("utf-8")
    many = folder / "mine_1e4.toml"
    many.write_text(
        mine.replace("samples = 512", "samples = 10_000")
        .replace("sensitivity = true", "sensitivity = false")
        .split("[expect]")[0],
        encoding="utf-8",
    )
    pool = wall([MDCALC, "study", str(many), "--jobs", "2", "--out", str(folder / "pool.csv")])
    dask = wall([MDCALC, "study", str(many), "--scheduler", "local:2",
                 "--out", str(folder / "dask.csv")])  # fmt: skip
    same = (folder / "pool.csv").read_bytes() == (folder / "dask.csv").read_bytes()
    row("mdcalc study: 10^4 mine-hoist samples, pool of 2", f"{pool:.1f} s", "", True)
    row(
        "  the same on a LocalCluster of 2 (dask), cluster/pool",
        f"{dask:.1f} s, ratio {dask / pool:.2f}",
        "identical",
        same,
    )
    sobol = ROOT / "cases" / "studies" / "coupling_scatter.toml"
    best = min(wall([MDCALC, "study", str(sobol)]) for _ in range(3))
    row("mdcalc study: coupling, 10^5 samples + Sobol (4096 runs)", f"{best:.2f} s", "", True)


def main() -> None:
    os.environ.pop("NO_COLOR", None)
    print(f"mdcalc benchmarks: {os.cpu_count()} cores, Python {sys.version.split()[0]}")
    if len(sys.argv) == 3 and sys.argv[1] == "--against":
        startup_against(Path(sys.argv[2]).resolve())
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        startup()
        batch(folder)
        sweep(folder)
        mine_hoist()
        studies(folder)
        study_rates(folder)
        growth(folder)
        shutil.rmtree(folder / "cases", ignore_errors=True)


if __name__ == "__main__":
    main()
