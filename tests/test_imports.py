"""Closed-form commands and --help must not pay for heavy imports."""

from __future__ import annotations

import subprocess
import sys

from tests.conftest import CASES

PROBE = """
import sys
sys.argv = ["mdcalc", *{args!r}]
from mdcalc.cli import main
try:
    main()
except SystemExit:
    pass
heavy = sorted({{m.split(".")[0] for m in sys.modules}} & {{"scipy", "matplotlib", "pint"}})
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
