"""The Dask bar of docs/python.md: 50 000 designs on a 2-worker LocalCluster against the
local call (2 threads), 5 runs each, medians with their range.

    python3 python/benchmarks/dask_timing.py
"""

import statistics
import time

import numpy as np
from distributed import Client, LocalCluster

from noncirc import Scene, evaluate_batch
from noncirc.dask import evaluate_batch_distributed


def main(n=50_000, runs=5):
    scene = Scene.builtin("paper-search")
    lo, hi = (np.array([p[k] for p in scene.free_parameters()]) for k in (1, 2))
    x = lo + np.random.default_rng(0).random((n, len(lo))) * (hi - lo)
    local, remote, chunks = [], [], set()
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            evaluate_batch_distributed(client, scene, x[:5000])  # warm the workers
            for _ in range(runs):
                t = time.perf_counter()
                evaluate_batch(scene, x, threads=2)
                local.append(time.perf_counter() - t)
                t = time.perf_counter()
                r = evaluate_batch_distributed(client, scene, x)
                remote.append(time.perf_counter() - t)
                chunks.add(r.chunks)
    ratios = [r / l for r, l in zip(remote, local)]
    fmt = lambda v: f"{statistics.median(v):.3f} [{min(v):.3f}, {max(v):.3f}]"
    print(f"local (2 threads) s:      {fmt(local)}")
    print(f"distributed (2 workers) s: {fmt(remote)}, chunks {sorted(chunks)}")
    print(f"ratio:                    {fmt(ratios)}")


if __name__ == "__main__":
    main()
