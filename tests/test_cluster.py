"""``--scheduler``: a study, a sweep and a batch on a dask.distributed cluster give
the numbers of this machine's pool, bit for bit; a worker killed mid-study has its
chunk run again. The clusters are LocalClusters on 127.0.0.1 that close with the
test."""

from __future__ import annotations

import os
import signal
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import CASES, MINE_STUDY, run_script

distributed = pytest.importorskip("distributed")


def study_path(tmp_path: Path, samples: int) -> Path:
    path = tmp_path / "study.toml"
    path.write_text(MINE_STUDY.format(samples=samples, seed=21), encoding="utf-8")
    return path


def run_on(path: Path, mapper, on_done=None):
    from mdcalc.input.casefile import read_case
    from mdcalc.runs.study import run

    return run(read_case(path), mapper, time_limit=20.0, on_done=on_done)


@pytest.fixture(scope="module")
def cluster():
    from distributed import Client, LocalCluster

    with (
        LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
        ) as local,
        Client(local) as client,
    ):
        yield client


def same(a, b) -> None:
    assert np.array_equal(a.samples, b.samples)
    for key in a.keys:
        assert np.array_equal(a.evaluated.values[key], b.evaluated.values[key], equal_nan=True)
    assert np.array_equal(a.evaluated.status, b.evaluated.status)
    assert a.values() == b.values()


def test_a_study_on_a_cluster_is_bit_identical_to_the_pool(tmp_path, cluster):
    from mdcalc.runs.cluster import DaskMapper, PoolMapper

    path = study_path(tmp_path, 120)
    pooled = run_on(path, PoolMapper(2))
    clustered = run_on(path, DaskMapper(cluster, "test cluster"))
    same(pooled, clustered)
    assert not clustered.evaluated.counts


def test_a_killed_worker_has_its_chunk_run_again(tmp_path, cluster, monkeypatch):
    from mdcalc.problems import PROBLEMS
    from mdcalc.runs.cluster import DaskMapper, PoolMapper

    monkeypatch.setattr(PROBLEMS["mine-hoist"].load(), "sweep", None)  # one by one

    path = study_path(tmp_path, 300)
    reference = run_on(path, PoolMapper(1))
    pids = cluster.run(os.getpid)
    victim = sorted(pids.values())[0]
    seen = [0]

    def kill_once(n: int) -> None:
        seen[0] += n
        if seen[0] == 20:  # chunks are in flight on both workers now
            os.kill(victim, signal.SIGKILL)

    killed = run_on(path, DaskMapper(cluster, "test cluster"), kill_once)
    assert seen[0] == 300 and victim not in cluster.run(os.getpid).values()  # it did die
    same(reference, killed)
    assert not killed.evaluated.counts


def test_a_vectorized_study_on_a_cluster_is_bit_identical(tmp_path, cluster, monkeypatch):
    import importlib

    from mdcalc.runs.cluster import DaskMapper, PoolMapper

    evaluate = importlib.import_module("mdcalc.runs.study.evaluate")
    monkeypatch.setattr(evaluate, "KERNEL_CHUNK", 997)  # many chunks on the cluster
    text = (CASES / "studies" / "braking_adhesion.toml").read_text("utf-8")
    path = tmp_path / "braking.toml"
    path.write_text(text.replace("samples = 100_000", "samples = 5000"), encoding="utf-8")
    here = run_on(path, PoolMapper(1))
    there = run_on(path, DaskMapper(cluster, "test cluster"))
    assert here.evaluated.vectorized and there.evaluated.vectorized
    same(here, there)


def test_kernel_blocks_of_a_modal_problem_run_on_the_cluster_bit_identical(
    tmp_path, cluster, monkeypatch
):
    # The mine-hoist kernel (modes, maxima in time) in blocks of 997 samples on the
    # workers: the values of the study run in this process, bit for bit.
    import importlib

    from mdcalc.runs.cluster import DaskMapper, PoolMapper

    evaluate = importlib.import_module("mdcalc.runs.study.evaluate")
    monkeypatch.setattr(evaluate, "KERNEL_CHUNK", 997)
    path = study_path(tmp_path, 6000)
    here = run_on(path, PoolMapper(1))
    there = run_on(path, DaskMapper(cluster, "test cluster"))
    assert here.evaluated.vectorized and there.evaluated.vectorized
    assert there.how == "vectorized kernel, blocks on test cluster"
    same(here, there)
    assert not there.evaluated.counts


def test_a_kernel_block_lost_for_good_counts_its_samples_as_failed(tmp_path, monkeypatch):
    # A block whose worker died past the retries: its samples fail with the reason,
    # the other blocks keep their values.
    import importlib

    from mdcalc.runs.cluster import PoolMapper

    evaluate = importlib.import_module("mdcalc.runs.study.evaluate")
    monkeypatch.setattr(evaluate, "KERNEL_CHUNK", 50)
    path = study_path(tmp_path, 200)
    whole = run_on(path, PoolMapper(1))

    class LosesTheSecond:
        description = "a cluster that loses a block"

        def __call__(self, func, items, on_done=None, on_error=None):
            for index, item in enumerate(items):
                if index == 1:
                    yield on_error(item, RuntimeError("worker died 3 times"))
                else:
                    yield func(item)

    lossy = run_on(path, LosesTheSecond())
    assert lossy.evaluated.counts == {"internal error": 50}
    assert lossy.evaluated.reasons["internal error"] == [
        "samples 50 to 99: lost on the cluster: RuntimeError: worker died 3 times"
    ]
    assert list(lossy.evaluated.status[50:100]) == [70] * 50
    assert np.isnan(lossy.evaluated.values["mu23_first_swing"][50:100]).all()
    keep = np.r_[0:50, 100:200]
    for key in whole.keys:
        assert np.array_equal(lossy.evaluated.values[key][keep], whole.evaluated.values[key][keep])


def test_a_kernel_sweep_runs_in_blocks_on_the_cluster_bit_identical(cluster, monkeypatch):
    # A mine-hoist sweep through its kernel, in blocks of 97 points on the workers:
    # the columns and statuses of the sweep run in this process, bit for bit, the
    # point whose scene has no answer solved alone in both.
    from mdcalc.runs import sweep as sweeps
    from mdcalc.runs.cluster import DaskMapper

    monkeypatch.setattr(sweeps, "BLOCK", 97)
    case = CASES / "mine-hoist" / "seed_1025.toml"
    varies = ["hoist.rope_stiffness=5e5:1.2e6:25", "loads.load_torque=4e5:1.05e6:20"]
    plan = sweeps.plan(case, [sweeps.parse_vary(v) for v in varies])
    wanted = ["mu12_first_swing", "mu23_first_swing", "peak_moment_23"]
    here = sweeps.evaluate(plan, wanted, 1)
    there = sweeps.evaluate(plan, wanted, 1, mapper=DaskMapper(cluster, "test cluster"))
    assert here.vectorized and there.vectorized
    assert list(there.status) == list(here.status) and 3 in set(here.status.tolist())
    for key in here.keys:
        assert np.array_equal(here.columns[key], there.columns[key], equal_nan=True), key


def test_a_local_cluster_s_workers_keep_dask_s_shutdown_noise_to_themselves():
    # A worker's heartbeat that met the closing scheduler printed an ERROR with its
    # traceback after a study that went well (1 run in 4): local:N's workers log
    # only CRITICAL messages (mdcalc reports a failed block itself).
    import logging

    from mdcalc.runs.cluster import connect

    client, cluster = connect("local:1")
    try:
        levels = client.run(_stderr_levels)
    finally:
        client.close()
        cluster.close()
    assert list(levels.values()) == [[logging.CRITICAL]]


def test_two_local_clusters_at_once_take_ports_of_their_own():
    # The scheduler's HTTP routes listened on 127.0.0.1:8787 with the dashboard off:
    # a second cluster at the same time warned that the port was in use.
    import warnings

    from mdcalc.runs.cluster import connect

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        first = connect("local:1")
        second = connect("local:1")
        try:
            ports = [c.scheduler.http_server.port for _, c in (first, second)]
        finally:
            for client, cluster in (first, second):
                client.close()
                cluster.close()
    assert 8787 not in ports and len(set(ports)) == 2
    assert not [w for w in caught if "already in use" in str(w.message)]


def _stderr_levels() -> list[int]:
    """In a worker: the levels of the handlers that print dask's log to stderr."""
    import logging
    import sys

    handlers = logging.getLogger("distributed").handlers
    return [h.level for h in handlers if getattr(h, "stream", None) is sys.stderr]


def test_the_command_line_takes_local_n_and_the_environment(tmp_path):
    path = study_path(tmp_path, 24)
    out_pool, out_dask = tmp_path / "pool.csv", tmp_path / "dask.csv"
    pooled = run_script("study", path, "--out", out_pool, "--jobs", "2")
    assert pooled.returncode == 0, pooled.stderr
    env = {**os.environ, "MDCALC_SCHEDULER": "local:1"}
    clustered = run_script("study", path, "--out", out_dask, env=env)
    assert clustered.returncode == 0, clustered.stderr
    assert "dask local:1" in clustered.stdout
    assert out_pool.read_bytes() == out_dask.read_bytes()


def test_sweep_and_run_take_the_scheduler(tmp_path):
    case = CASES / "mine-hoist" / "seed_1025.toml"
    args = [
        "sweep",
        case,
        "--vary",
        "hoist.rope_stiffness=800e3:1000e3:4",
        "--result",
        "mu12_first_swing",
    ]
    pooled = run_script(*args, "--out", tmp_path / "a.csv")
    clustered = run_script(*args, "--out", tmp_path / "b.csv", "--scheduler", "local:2")
    assert pooled.returncode == clustered.returncode == 0, clustered.stderr
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()
    done = run_script("run", CASES / "braking", "--scheduler", "local:2", "--json")
    assert done.returncode == 0, done.stderr
    assert "dask local:2" in done.stderr


@pytest.mark.parametrize(
    "address, message",
    [("local:0", "1 to 256"), ("nonsense", "tcp://HOST:PORT"),
     ("tcp://127.0.0.1:9", "cannot reach")],
)  # fmt: skip
def test_a_bad_scheduler_is_exit_2(tmp_path, address, message, cli, monkeypatch):
    from mdcalc.runs import cluster

    monkeypatch.setattr(cluster, "CONNECT_SECONDS", 1)  # a refused port: dask retries
    done = cli("study", study_path(tmp_path, 4), "--scheduler", address)
    assert done.exit_code == 2, done.stderr
    assert message in done.stderr and "Traceback" not in done.stderr
