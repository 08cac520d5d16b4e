"""Closed-form commands and --help must not pay for heavy imports."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.conftest import CASES

PROBE = """
import sys
sys.argv = ["mdcalc", *{args!r}]
from mdcalc.cli.launch import main
try:
    main()
except SystemExit:
    pass
heavy = sorted(set(sys.modules) & {{"scipy", "matplotlib", "pint"}})
print("HEAVY", heavy, file=sys.stderr)
"""


def heavy_modules(*args: str) -> str:
    done = subprocess.run(
        [sys.executable, "-c", PROBE.format(args=list(args))],
        capture_output=True,
        text=True,
        timeout=120,
    )
    return done.stderr.strip().splitlines()[-1]


def test_help_imports_nothing_heavy():
    assert heavy_modules("--help") == "HEAVY []"


def test_help_loads_neither_pydantic_nor_numpy_nor_rich():
    # `mdcalc --help` should cost little more than `import typer` (make bench).
    probe = PROBE.replace('{{"scipy", "matplotlib", "pint"}}', '{{"pydantic", "numpy", "rich"}}')
    done = subprocess.run(
        [sys.executable, "-c", probe.format(args=["--help"])],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.stderr.strip().splitlines()[-1] == "HEAVY []"


def test_a_plain_batch_on_a_pipe_loads_neither_typer_nor_rich():
    """`mdcalc run PATH --json` takes the direct path, and its summary on a pipe is
    the plain text rich would print: neither is imported (issue 22)."""
    probe = PROBE.replace('{{"scipy", "matplotlib", "pint"}}', '{{"typer", "rich", "click"}}')
    args = ["run", str(CASES / "braking"), "--jobs", "1", "--json"]
    done = subprocess.run(
        [sys.executable, "-c", probe.format(args=args)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert "mdcalc run: " in done.stderr  # the summary was printed
    assert done.stderr.strip().splitlines()[-1] == "HEAVY []"


def test_closed_form_braking_does_not_import_scipy():
    assert heavy_modules("braking", str(CASES / "braking" / "lecture.toml")) == "HEAVY []"


def test_hoist_without_rope_does_not_import_scipy():
    assert heavy_modules("hoist", str(CASES / "hoist" / "lift.toml")) == "HEAVY []"


def test_drag_scene_does_use_scipy():
    # The guard above can fail: with drag the ODE methods run.
    assert heavy_modules("braking", str(CASES / "braking" / "drag.toml")) == "HEAVY ['scipy']"


def test_mount_is_closed_form_and_does_not_import_scipy():
    for case in ("example_9_1", "resonance_damped", "isolation"):
        assert heavy_modules("mount", str(CASES / "mount" / f"{case}.toml")) == "HEAVY []"


def test_mine_hoist_without_ode_rows_does_not_import_scipy(tmp_path):
    # The modal solution is numpy only; scipy comes in with the ODE rows alone.
    case = (CASES / "mine-hoist" / "seed_1025.toml").read_text(encoding="utf-8")
    off = tmp_path / "no_ode.toml"
    off.write_text(case.replace("[loads]", "[analysis]\node = false\n\n[loads]"), encoding="utf-8")
    assert heavy_modules("mine-hoist", str(off)) == "HEAVY []"
    assert heavy_modules("mine-hoist", str(CASES / "mine-hoist" / "seed_1025.toml")) == (
        "HEAVY ['scipy']"
    )


def test_variator_closed_form_parts_do_not_import_scipy(tmp_path):
    # Absorber, pendulum, and a drive without ODE rows are numpy only.
    for case in ("two_disk_absorber", "absorber_damped", "pendulum"):
        assert heavy_modules("variator", str(CASES / "variator" / f"{case}.toml")) == "HEAVY []"
    text = (CASES / "variator" / "drive_undamped.toml").read_text(encoding="utf-8")
    off = tmp_path / "no_ode.toml"
    off.write_text(text.replace("[expect]", "ode = false\n\n[expect]"), encoding="utf-8")
    assert heavy_modules("variator", str(off)) == "HEAVY []"
    assert heavy_modules("variator", str(CASES / "variator" / "drive_undamped.toml")) == (
        "HEAVY ['scipy']"
    )


@pytest.mark.parametrize(
    "case",
    [
        "braking/lecture.toml",
        "braking/dry.toml",
        "clutch/fig2_differentiated.toml",
        "mount/example_9_1.toml",
        "mount/isolation.toml",
        "hoist/lift.toml",
        "coupling/harmonic.toml",
    ],
)
def test_closed_form_scenes_load_no_numpy(case):
    # Their closed forms are written once for floats and arrays (core/xp.py): a single
    # scene takes the float path, and only a sweep's kernel brings numpy in.
    problem = (CASES / case).parent.name
    probe = PROBE.replace('{{"scipy", "matplotlib", "pint"}}', '{{"numpy", "scipy"}}')
    done = subprocess.run(
        [sys.executable, "-c", probe.format(args=[problem, str(CASES / case)])],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.stderr.strip().splitlines()[-1] == "HEAVY []"


# ------------------------------------------------ every case file, every problem
#
# Written once for every registered problem: a scene may load scipy only when one of
# its methods declares it (``Method.imports``); pint only when the case writes a
# number as a quantity string (its report then has a "units" section); matplotlib
# never (only --plot loads it). Two processes in all: the first learns
# what each case's methods declare, the second runs the undeclared ones through the
# CLI, one after another, and names the first case after which a heavy module showed.

DECLARED = """
import json, sys
from pathlib import Path
from mdcalc.errors import InputError
from mdcalc.output.report import MethodsTable
from mdcalc.runs.runner import run_case
out = {}
for name in sys.argv[1:]:
    try:
        report = run_case(Path(name))
    except InputError:
        continue
    rows = [row for s in report.sections if isinstance(s, MethodsTable) for row in s.rows]
    units = ["pint"] if any(getattr(s, "key", "") == "units" for s in report.sections) else []
    if rows:  # a scene without a Methods table (a stall, say) declares nothing: skipped
        out[name] = sorted({m.split(".")[0] for row in rows for m in row.imports} | {*units})
print(json.dumps(out))
"""

UNDECLARED = """
import contextlib, io, sys
from mdcalc.cli.launch import main
HEAVY = {"scipy", "pint", "matplotlib"}
for name in sys.argv[1:]:
    problem = name.split("::")[0]
    sys.argv = ["mdcalc", problem, name.split("::")[1]]
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        try:
            main()
        except SystemExit:
            pass
    heavy = sorted({m.split(".")[0] for m in sys.modules} & HEAVY)
    if heavy:
        print("FIRST", name, heavy)
        break
else:
    print("CLEAN", len(sys.argv))
"""


def _problem_of(path) -> str:
    import tomllib

    try:
        return str(tomllib.loads(path.read_text(encoding="utf-8")).get("problem", ""))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError):
        return ""


def test_no_case_loads_a_heavy_module_its_methods_do_not_declare():
    import json

    from mdcalc.problems import PROBLEMS

    files = [
        p
        for p in sorted(CASES.rglob("*.toml"))
        if _problem_of(p) in PROBLEMS and p.parent.name != "studies"
    ]
    assert {_problem_of(p) for p in files} == set(PROBLEMS), "a problem without cases"
    done = subprocess.run(
        [sys.executable, "-c", DECLARED, *map(str, files)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr
    declared = json.loads(done.stdout)
    undeclared = [name for name, modules in declared.items() if not {"scipy", "pint"} & {*modules}]
    assert any("pint" in modules for modules in declared.values()), "no case with units"
    # The guard can fail: some scenes do declare scipy, and the rest are many.
    assert len(undeclared) >= len(PROBLEMS) and len(undeclared) < len(declared)
    jobs = [f"{_problem_of(CASES.parent / n)}::{n}" for n in undeclared]
    done = subprocess.run(
        [sys.executable, "-c", UNDECLARED, *jobs], capture_output=True, text=True, timeout=600
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("CLEAN"), done.stdout


def test_quantity_strings_load_pint_and_plain_numbers_do_not():
    # The same scene both ways: pint is paid for only where a unit string is written.
    plain = heavy_modules("coupling", str(CASES / "coupling" / "example_8_1.toml"))
    units = heavy_modules("coupling", str(CASES / "coupling" / "example_8_1_units.toml"))
    assert "pint" not in plain
    assert "pint" in units


def test_a_scene_skips_pydantic_plugin_discovery_but_not_the_loader():
    # importlib.metadata (17 ms) is what pydantic's plugin loader imports; with
    # PYDANTIC_DISABLE_PLUGINS the stand-in answers "no plugins" and forwards the rest.
    probe = PROBE.replace('{{"scipy", "matplotlib", "pint"}}', '{{"importlib.metadata"}}')
    done = subprocess.run(
        [sys.executable, "-c", probe.format(args=["braking", str(CASES / "braking/lecture.toml")])],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.stderr.strip().splitlines()[-1] == "HEAVY []"
    forwarded = (
        "import sys\n"
        "from mdcalc.cli.startup import no_plugin_discovery\n"
        "import os; os.environ['PYDANTIC_DISABLE_PLUGINS'] = '__all__'\n"
        "no_plugin_discovery()\n"
        "from pydantic.plugin._loader import get_plugins, PYDANTIC_ENTRY_POINT_GROUP\n"
        "from pydantic import BaseModel\n"
        "class A(BaseModel):\n    x: float\n"
        "print(list(get_plugins()), PYDANTIC_ENTRY_POINT_GROUP, A(x=1).x)\n"
    )
    done = subprocess.run([sys.executable, "-c", forwarded], capture_output=True, text=True)
    assert done.stdout.split() == ["[]", "pydantic", "1.0"], done.stderr


def test_a_latin_hypercube_study_in_the_fields_units_loads_neither_pint_nor_scipy_stats(
    tmp_path,
):
    # the shipped braking study: LHS, a normal mass "1500 kg" ± "75 kg" (kg is the
    # field's unit); its Sobol design (SALib, scipy) is left out here
    text = (CASES / "studies" / "braking_adhesion.toml").read_text(encoding="utf-8")
    case = tmp_path / "study.toml"
    probe = PROBE.replace('{{"scipy", "matplotlib", "pint"}}', '{{"scipy.stats", "pint"}}')

    def heavy(study: str) -> str:
        case.write_text(study, encoding="utf-8")
        done = subprocess.run(
            [sys.executable, "-c", probe.format(args=["study", str(case), "--json"])],
            capture_output=True,
            text=True,
            timeout=120,
        )
        return done.stderr.strip().splitlines()[-1]

    study = text.replace("sensitivity = true", "sensitivity = false")
    study = study.replace("samples = 100_000", "samples = 2000")
    assert heavy(study) == "HEAVY []"
    # a string in another unit still goes to pint
    assert heavy(study.replace('sd = "75 kg"', 'sd = "0.075 t"')) == "HEAVY ['pint']"
