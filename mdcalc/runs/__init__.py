"""Runs: cases computed, one or many, in this process, a pool or a cluster.

- ``runner.py``: one case: read -> validate -> solve -> report under the time
  budget, shared by the commands, check, run, sweep and study; floating point giving up is
  a scene without an answer (exit 3).
- ``pool.py``: case-file collection and the process pool: results streamed in input
  order, workers killed on Ctrl-C and ending by themselves when the parent is killed;
  where the caller takes failures as results (run, sweep, study), a worker killed by
  the system costs only the item that killed it.
- ``cluster.py``: ``--scheduler``: the pool or a dask.distributed cluster behind one
  mapper.
- ``kernel.py``: a problem's vectorized kernel on a block of samples or grid points,
  for the pool or the cluster, and a block lost for good.
- ``batch.py``: ``mdcalc run``: one outcome per file, in input order.
- ``check.py``: ``mdcalc check``: the ``[expect]`` tables.
- ``sweep.py``: ``mdcalc sweep``: the grid, vectorized kernels or point-by-point
  runs, CSV/JSON.
- ``study/``: ``mdcalc study``: uncertain inputs, samples, statistics, sensitivity.

Imports nothing eagerly.
"""
