"""Batches stream and stop on Ctrl-C (issue 20, item 4): results are written as each
finishes, in input order; Ctrl-C sent to the whole process group, as a terminal does,
ends `mdcalc run` within a second or two with one line, exit 130, no traceback from the
pool or its workers, no temporary file and no worker left behind."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pytest
import tomli_w

from tests.conftest import CASES, MDCALC

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX process groups")

FILES = 10


def slow_folder(tmp_path: Path, files: int = FILES) -> Path:
    """``files`` copies of a mechanism scene of about a second each (40 revolutions)."""
    data = tomllib.loads((CASES / "mechanism/crank_press.toml").read_text(encoding="utf-8"))
    data.pop("expect")
    data["motion"]["revolutions"] = 40
    folder = tmp_path / "slow"
    folder.mkdir()
    for index in range(files):
        (folder / f"c{index:02d}.toml").write_text(tomli_w.dumps(data), encoding="utf-8")
    return folder


def _interruptible() -> None:
    """Ctrl-C's default in the child, as at a terminal: a test run started in the
    background (``make test &``) hands its children SIGINT ignored, and a program
    rightly keeps ignoring it then."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def start(*args: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [str(MDCALC), *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,  # its own process group, as a shell job has
        preexec_fn=_interruptible,
    )


def wait_for(condition, seconds: float) -> None:
    end = time.monotonic() + seconds
    while not condition():
        assert time.monotonic() < end, "timed out"
        time.sleep(0.05)


def children_of(pid: int) -> list[int]:
    found = subprocess.run(["pgrep", "-g", str(pid)], capture_output=True, text=True)
    return [int(p) for p in found.stdout.split()]


def test_ctrl_c_stops_a_batch_at_once_with_one_line(tmp_path):
    folder, out = slow_folder(tmp_path), tmp_path / "out"
    process = start("run", str(folder), "--out", str(out), "--jobs", "2")
    try:
        # Streaming: the first result is on disk while the rest still run.
        wait_for(lambda: any(out.glob("*.json")), 60)
        assert process.poll() is None
        pressed = time.monotonic()
        os.killpg(process.pid, signal.SIGINT)
        stdout, stderr = process.communicate(timeout=20)
        stopped = time.monotonic() - pressed
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
    assert process.returncode == 130
    assert stderr == "mdcalc: interrupted\n"
    assert stopped < 2.0, stopped
    assert not list(out.rglob("*.tmp")) and not list(out.rglob(".*"))
    written = sorted(out.glob("*.json"))
    assert 0 < len(written) < FILES
    for path in written:  # every file written is whole
        assert json.loads(path.read_text(encoding="utf-8"))["status"] == "ok"
    time.sleep(0.3)
    assert children_of(process.pid) == []  # no worker left running


def test_results_stream_in_input_order(tmp_path):
    folder = slow_folder(tmp_path, files=6)
    process = start("run", str(folder), "--json", "--jobs", "2")
    assert process.stdout is not None
    first = process.stdout.readline()  # before the batch is over
    arrived = time.monotonic()
    rest = process.stdout.read()  # (communicate() would skip what readline buffered)
    process.communicate(timeout=120)
    finished = time.monotonic()
    assert process.returncode == 0
    assert finished - arrived > 1.0  # the first line came well before the end
    lines = [line for line in [first, *rest.splitlines()] if line.strip()]
    assert all(line.startswith('{"mdcalc"') for line in lines), lines
    cases = [json.loads(line)["case"] for line in lines]
    assert cases == sorted(str(p) for p in folder.glob("*.toml"))


def test_ctrl_c_on_one_scene_is_exit_130_without_a_traceback(tmp_path):
    data = tomllib.loads((CASES / "mechanism/crank_press.toml").read_text(encoding="utf-8"))
    data.pop("expect")
    data["motion"]["revolutions"] = 100  # over 5 s
    case = tmp_path / "long.toml"
    case.write_text(tomli_w.dumps(data), encoding="utf-8")
    process = start("mechanism", str(case))
    time.sleep(1.0)
    os.killpg(process.pid, signal.SIGINT)
    _, stderr = process.communicate(timeout=10)
    assert process.returncode == 130
    assert stderr == "mdcalc: interrupted\n"
