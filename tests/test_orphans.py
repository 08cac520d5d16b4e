"""No worker outlives its command: a study, sweep or batch killed outright (SIGKILL, as
a CI timeout or the out-of-memory killer ends it) leaves no process computing on.

Before, the pool's workers of a mine-hoist study went on for minutes after
``kill -9`` of their parent. Each test starts a long command, waits until its
workers compute, kills the command with SIGKILL and requires every process it had
started to have ended within two seconds (a zombie counts as ended: it computes
nothing, and in a container whose first process reaps no one it stays listed).
"""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

from tests.conftest import MDCALC, MINE_STUDY

#: The workers must be gone this long after their parent [s]; they poll every 0.2 s.
GRACE_SECONDS = 2.0


def children() -> dict[int, int]:
    """pid -> parent pid of every process this machine lists."""
    found = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            found[int(entry.name)] = int(stat.rpartition(")")[2].split()[1])
    return found


def descendants(root: int) -> set[int]:
    table = children()
    found, frontier = set(), {root}
    while frontier:
        frontier = {pid for pid, parent in table.items() if parent in frontier} - found
        found |= frontier
    return found


def computing(pid: int) -> bool:
    """The process exists and is not a zombie."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rpartition(")")[2].split()[0] != "Z"


def kill_and_watch(command: list[str], cwd: Path, workers: int) -> None:
    process = subprocess.Popen(
        command,
        cwd=cwd,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,  # its own group: the cleanup below reaches every one
    )
    started: set[int] = set()
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and process.poll() is None:
            started = {pid for pid in descendants(process.pid) if computing(pid)}
            if len(started) >= workers:
                break
            time.sleep(0.1)
        assert len(started) >= workers, f"the command started {len(started)} workers"
        time.sleep(1.0)  # into the samples
        assert process.poll() is None, "the command ended before it could be killed"
        os.kill(process.pid, signal.SIGKILL)
        process.wait()
        end = time.monotonic() + GRACE_SECONDS
        while time.monotonic() < end and any(computing(pid) for pid in started):
            time.sleep(0.05)
        left = sorted(pid for pid in started if computing(pid))
        assert left == [], f"still running {GRACE_SECONDS} s after kill -9 of their parent"
    finally:
        for pid in started:
            if computing(pid):
                os.kill(pid, signal.SIGKILL)
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


@pytest.fixture
def long_study(tmp_path: Path) -> Path:
    """Hours of mine-hoist samples one by one (about 200 a second on one core)."""
    study = tmp_path / "long.toml"
    study.write_text(MINE_STUDY.format(samples=10**6, seed=1), encoding="utf-8")
    return study


def test_pool_workers_end_with_a_killed_study(long_study):
    kill_and_watch([str(MDCALC), "study", str(long_study), "--jobs", "2"], long_study.parent, 2)


def test_pool_workers_end_with_a_killed_batch(tmp_path):
    # run over many slow files: the pool of mdcalc run, check and sweep.
    for index in range(400):
        (tmp_path / f"m{index:03d}.toml").write_text(
            "\n".join(line for line in MINE_STUDY.split("[study]")[0].splitlines()).replace(
                "ode = false", "ode = true"
            ),
            encoding="utf-8",
        )
    kill_and_watch([str(MDCALC), "run", ".", "--jobs", "2", "--json"], tmp_path, 2)


def test_cluster_workers_end_with_a_killed_study(long_study):
    pytest.importorskip("distributed")
    command = [str(MDCALC), "study", str(long_study), "--scheduler", "local:2"]
    kill_and_watch(command, long_study.parent, 2)
