"""The time budget keeps finished answers (issue 33, item 5): a closed-form or modal
reference answers under a limit of 0.2 s, in a fresh process where the imports a
method needs (scipy.integrate: 0.3 s) are paid once; those imports stop the clock
rather than the scene; a no-answer's reason is printed once on a terminal."""

from __future__ import annotations

import json
import os
import subprocess
import time

import pytest

from mdcalc.core import budget
from tests.conftest import CASES, MDCALC

#: Shipped cases whose every Methods table has a closed-form or modal reference.
CLOSED_FORM = [
    "hoist/lift.toml",
    "braking/dry.toml",
    "coupling/example_8_1.toml",
    "mine-hoist/seed_1025.toml",
    "variator/two_disk_absorber.toml",
    "variator/vk_variator.toml",
    "resonance/inline_six.toml",
    "clutch/fig2_differentiated.toml",
    "mount/example_9_1.toml",
]


@pytest.mark.parametrize("case", CLOSED_FORM)
def test_a_closed_form_reference_answers_within_0_2_s(case):
    problem = (CASES / case).read_text("utf-8").split('problem = "')[1].split('"')[0]
    done = subprocess.run(
        [str(MDCALC), problem, str(CASES / case), "--json", "--time-limit", "0.2"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    for section in report["sections"]:
        if section["kind"] == "methods":
            reference = [row for row in section["rows"] if row["reference"]]
            assert reference and reference[0]["seconds"] is not None, section["title"]
            assert "in place of" not in reference[0]["note"], section["title"]


def test_an_import_stops_the_clock():
    with budget.limit(10.0) as limit:
        before = list(limit.deadlines)
        with budget.paused():
            time.sleep(0.05)
        assert all(a - b >= 0.05 for a, b in zip(limit.deadlines, before, strict=True))
    with budget.limit(0.01) as limit, budget.paused():
        time.sleep(0.2)  # the alarm ticks and passes: no OverBudget while paused
        assert limit.paused == 1


def test_a_no_answer_is_said_once_on_a_terminal(tmp_path):
    log = tmp_path / "both.txt"
    with open(log, "w", encoding="utf-8") as both:  # stdout and stderr one file
        done = subprocess.run(
            [str(MDCALC), "hoist", str(CASES / "hoist" / "cannot_start.toml")],
            stdout=both,
            stderr=both,
            timeout=60,
            env={**os.environ, "NO_COLOR": "1"},
        )
    assert done.returncode == 3
    assert log.read_text("utf-8").count("the motor cannot start the load") == 1
    apart = subprocess.run(
        [str(MDCALC), "hoist", str(CASES / "hoist" / "cannot_start.toml")],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert "cannot start" in apart.stdout and "error: no answer" in apart.stderr
