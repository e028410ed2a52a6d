"""Spreading noncirc over a Dask `distributed` cluster.

Per-design tasks drown in scheduler overhead (a design takes tens of microseconds), so
`evaluate_batch_distributed` splits a batch into chunks of at least `min_chunk_seconds` of
work each, timed on this machine first. `islands` runs independent searches, one per
task. Scenes pickle, so the same code runs on a `LocalCluster` or a real cluster.
"""

from __future__ import annotations

import math
import time
from typing import Any, Sequence

import numpy as np

from ._noncirc import Scene, evaluate_batch, optimise


def _chunk(scene: Scene, x: np.ndarray, kwargs: dict) -> dict:
    return evaluate_batch(scene, x, threads=1, **kwargs)


def chunk_size(scene: Scene, x: np.ndarray, min_chunk_seconds: float = 0.01, **kwargs: Any) -> int:
    """Rows per task so that each task holds at least `min_chunk_seconds` of work."""
    probe = x[: min(len(x), 16)]
    start = time.perf_counter()
    evaluate_batch(scene, probe, threads=1, **kwargs)
    per_design = max((time.perf_counter() - start) / max(len(probe), 1), 1e-7)
    return max(1, math.ceil(min_chunk_seconds / per_design))


def evaluate_batch_distributed(
    client, scene: Scene, x: np.ndarray, *, min_chunk_seconds: float = 0.01, **kwargs: Any
) -> dict:
    """`evaluate_batch` over the cluster's workers, in chunks; same result, same order."""
    x = np.ascontiguousarray(x, dtype=np.float64)
    size = chunk_size(scene, x, min_chunk_seconds, **kwargs)
    pieces = [x[i : i + size] for i in range(0, len(x), size)]
    futures = client.map(_chunk, [scene] * len(pieces), pieces, [kwargs] * len(pieces), pure=False)
    parts = client.gather(futures)
    merged = {}
    for key, first in parts[0].items():
        if isinstance(first, np.ndarray):
            merged[key] = np.concatenate([p[key] for p in parts])
        elif key == "errors":
            merged[key] = [e for p in parts for e in p[key]]
        else:
            merged[key] = first
    merged["chunks"] = len(pieces)
    return merged


def _island(scene: Scene, seed: int, kwargs: dict) -> dict:
    result = optimise(scene, seed=seed, threads=1, **kwargs)
    result.pop("best_scene", None)
    return result


def islands(client, scene: Scene, seeds: Sequence[int], **kwargs: Any) -> list[dict]:
    """Independent searches, one per seed and task; results in seed order."""
    futures = client.map(_island, [scene] * len(seeds), list(seeds), [kwargs] * len(seeds), pure=False)
    return client.gather(futures)
