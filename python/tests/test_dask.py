"""Scale-out over a Dask LocalCluster: chunked batches and independent search islands."""

import numpy as np
import pytest

distributed = pytest.importorskip("distributed")

from noncirc import NoncircError, Scene, evaluate_batch, optimise  # noqa: E402
from noncirc.dask import chunk_size, evaluate_batch_distributed, islands, seconds_per_design  # noqa: E402


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
    # The rule, at an injected time per design (the machine's speed is not under test).
    scene, x = batch(200_000)
    # 200 000 designs at 20 µs are 4 s of work: four chunks per thread.
    assert chunk_size(scene, x, 0.1, threads=2, per_design=20e-6) == 25_000
    # 2 000 designs at 20 µs are 40 ms: one chunk, not dozens of tiny ones.
    assert chunk_size(scene, x[:2000], 0.1, threads=2, per_design=20e-6) == 2000
    # 20 000 designs at 20 µs are 0.4 s: four chunks of at least 0.1 s, not eight.
    assert chunk_size(scene, x[:20_000], 0.1, threads=2, per_design=20e-6) == 5000
    # Ten times slower designs: the thread count caps the chunks.
    assert chunk_size(scene, x[:20_000], 0.1, threads=2, per_design=200e-6) == 2500
    assert chunk_size(scene, x[:0], 0.1, threads=2, per_design=20e-6) == 1
    with pytest.raises(ValueError, match="per_design"):
        chunk_size(scene, x, 0.1, threads=2, per_design=float("nan"))
    with pytest.raises(ValueError, match="min_chunk_seconds"):
        chunk_size(scene, x, 0.0, threads=2, per_design=20e-6)


def test_the_measured_time_per_design_gives_a_chunk_within_the_rule():
    # Whatever the load: a positive, finite time, and a chunk between a quarter of a
    # thread's share and the whole batch.
    scene, x = batch(20_000)
    per_design = seconds_per_design(scene, x)
    assert 0 < per_design < 1
    size = chunk_size(scene, x, 0.1, threads=2)
    assert 20_000 // 8 <= size <= 20_000


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


def test_islands_without_migrants_are_the_independent_searches(client):
    # Epochs resume each island's checkpoint: with no migrants, exactly the searches alone.
    scene = Scene.builtin("paper-search")
    results = islands(client, scene, [1, 2], epochs=3, migrants=0, algorithm="de", budget=3000)
    for seed, r in zip([1, 2], results):
        alone = optimise(scene, algorithm="de", seed=seed, budget=3000, threads=1, progress=False)
        assert r.best == alone.best
        assert r.evaluations == alone.evaluations


def test_islands_exchange_migrants_deterministically(client):
    scene = Scene.builtin("paper-search")
    kwargs = dict(epochs=3, migrants=3, algorithm="de", budget=6000)
    first = islands(client, scene, [1, 2, 3], **kwargs)
    again = islands(client, scene, [1, 2, 3], **kwargs)
    assert [r.best for r in first] == [r.best for r in again]
    assert [r.evaluations for r in first] == [r.evaluations for r in again]
    # Migration changed the searches: they are not the independent ones.
    alone = islands(client, scene, [1, 2, 3], **{**kwargs, "migrants": 0})
    assert [r.best for r in first] != [r.best for r in alone]


def test_migrants_of_another_scene_or_algorithm_are_refused(tmp_path):
    from noncirc import _noncirc

    a, b = tmp_path / "a.ckpt", tmp_path / "b.ckpt"
    scene = Scene.builtin("paper-search")
    optimise(scene, algorithm="de", seed=1, budget=500, checkpoint=a, progress=False)
    other = scene.with_set("train.carrier_speed_rpm", 61.0)
    optimise(other, algorithm="de", seed=1, budget=500, checkpoint=b, progress=False)
    sent = _noncirc.emigrants(a, 2)
    with pytest.raises(NoncircError, match="migrants from a search of another problem"):
        _noncirc.immigrate(b, sent)
    c = tmp_path / "c.ckpt"
    optimise(scene, algorithm="cmaes", seed=1, budget=500, checkpoint=c, progress=False)
    with pytest.raises(NoncircError, match="no population"):
        _noncirc.immigrate(c, sent)
    with pytest.raises(Exception, match="not the text of emigrants"):
        _noncirc.immigrate(a, "{}")
