"""Spreading noncirc over a Dask `distributed` cluster.

Per-design tasks drown in scheduler overhead (a design takes tens of microseconds), so
`evaluate_batch_distributed` splits a batch into a few chunks per worker thread, each of at
least `min_chunk_seconds` (0.1 s) of work, timed on this machine first. `islands` runs
independent searches, one per task. Scenes pickle, so the same code runs on a
`LocalCluster` or a real cluster.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np

from ._noncirc import Scene
from .api import evaluate_batch, optimise
from .results import Batch, SearchResult


@dataclass(frozen=True)
class DistributedBatch(Batch):
    """A `Batch` evaluated on a cluster, and into how many tasks it was split."""

    chunks: int = 1


def _chunk(scene: Scene, x: np.ndarray, kwargs: dict) -> Batch:
    return evaluate_batch(scene, x, threads=1, **kwargs)


#: Chunks per worker thread: enough that a slow chunk does not leave the others idle.
CHUNKS_PER_THREAD = 4


def chunk_size(
    scene: Scene, x: np.ndarray, min_chunk_seconds: float = 0.1, threads: int = 1, **kwargs: Any
) -> int:
    """Rows per task: `CHUNKS_PER_THREAD` chunks per worker thread (`threads` in all), but
    none holding less than `min_chunk_seconds` of work. The time per design is the fastest
    of three runs of up to 256 rows after a warm-up, so one slow run does not multiply the
    number of tasks (timing 16 designs once gave 175 to 3 847 chunks for the same input)."""
    if len(x) == 0:
        return 1
    evaluate_batch(scene, x[:16], threads=1, **kwargs)
    probe = x[:256]
    per_design = math.inf
    for _ in range(3):
        start = time.perf_counter()
        evaluate_batch(scene, probe, threads=1, **kwargs)
        per_design = min(per_design, (time.perf_counter() - start) / len(probe))
    by_time = max(1, math.floor(len(x) * per_design / min_chunk_seconds))
    chunks = min(CHUNKS_PER_THREAD * max(threads, 1), by_time)
    return math.ceil(len(x) / chunks)


def evaluate_batch_distributed(
    client, scene: Scene, x: np.ndarray, *, min_chunk_seconds: float = 0.1, **kwargs: Any
) -> DistributedBatch:
    """`evaluate_batch` over the cluster's workers, in chunks; same result, same order."""
    x = np.ascontiguousarray(x, dtype=np.float64)
    threads = sum(w.get("nthreads", 1) for w in client.scheduler_info()["workers"].values())
    size = chunk_size(scene, x, min_chunk_seconds, threads, **kwargs)
    pieces = [x[i : i + size] for i in range(0, len(x), size)]
    futures = client.map(_chunk, [scene] * len(pieces), pieces, [kwargs] * len(pieces), pure=False)
    parts: list[Batch] = client.gather(futures)
    merged: dict[str, Any] = {}
    for field in dataclasses.fields(Batch):
        first = getattr(parts[0], field.name)
        if isinstance(first, np.ndarray):
            merged[field.name] = np.concatenate([getattr(p, field.name) for p in parts])
        elif field.name == "errors":
            merged[field.name] = [e for p in parts for e in p.errors]
        else:
            merged[field.name] = first
    return DistributedBatch(**merged, chunks=len(pieces))


def _island(scene: Scene, seed: int, kwargs: dict) -> SearchResult:
    return optimise(scene, seed=seed, threads=1, progress=False, **kwargs)


def islands(client, scene: Scene, seeds: Sequence[int], **kwargs: Any) -> list[SearchResult]:
    """Independent searches, one per seed and task; results in seed order."""
    futures = client.map(_island, [scene] * len(seeds), list(seeds), [kwargs] * len(seeds), pure=False)
    return client.gather(futures)
