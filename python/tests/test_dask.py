"""Scale-out over a Dask LocalCluster: chunked batches and independent search islands."""

import numpy as np
import pytest

distributed = pytest.importorskip("distributed")

from noncirc import Scene, evaluate_batch  # noqa: E402
from noncirc.dask import chunk_size, evaluate_batch_distributed, islands  # noqa: E402


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as c:
            yield c


def batch(n):
    scene = Scene.builtin("paper-search")
    params = scene.free_parameters()
    lo = np.array([p[1] for p in params])
    hi = np.array([p[2] for p in params])
    return scene, lo + np.random.default_rng(2).random((n, len(params))) * (hi - lo)


def test_chunks_are_a_few_per_thread_and_hold_a_tenth_of_a_second():
    scene, x = batch(200_000)
    # 200 000 designs are seconds of work: four chunks per thread.
    assert chunk_size(scene, x, 0.1, threads=2) == 25_000
    # 2 000 designs are about 40 ms: one chunk, not dozens of tiny ones.
    assert chunk_size(scene, x[:2000], 0.1, threads=2) == 2000
    # The same input gives the same chunks (timing noise no longer multiplies them).
    assert len({chunk_size(scene, x, 0.1, threads=2) for _ in range(5)}) == 1


def test_distributed_batch_equals_the_local_one(client):
    scene, x = batch(2000)
    remote = evaluate_batch_distributed(client, scene, x, min_chunk_seconds=0.005)
    local = evaluate_batch(scene, x)
    assert remote.chunks >= 2 and remote.errors == local.errors
    for key in ["x", "values", "violations", "cv", "goals", "valid", "measures"]:
        assert np.array_equal(getattr(remote, key), getattr(local, key), equal_nan=key in ("values", "violations", "measures")), key


def test_islands_run_independent_searches(client):
    scene = Scene.builtin("paper-search")
    results = islands(client, scene, [1, 2], algorithm="de", budget=3000)
    assert [r.seed for r in results] == [1, 2]
    assert all(r.evaluations >= 3000 for r in results)
