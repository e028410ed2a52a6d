"""Spreading noncirc over a Dask `distributed` cluster.

Per-design tasks drown in scheduler overhead (a design takes tens of microseconds), so
`evaluate_batch_distributed` splits a batch into a few chunks per worker thread, each of at
least `min_chunk_seconds` (0.1 s) of work, timed on this machine first. `islands` runs an
island model: a search per seed, each a task, exchanging their best members every epoch. Scenes pickle, so the same code runs on a
`LocalCluster` or a real cluster.
"""

from __future__ import annotations

import dataclasses
import math
import os
import tempfile
import time
import warnings
from dataclasses import dataclass
from typing import Any, Optional, Sequence

import numpy as np

from . import _noncirc
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


def seconds_per_design(scene: Scene, x: np.ndarray, **kwargs: Any) -> float:
    """The time one design of `x` takes on one thread of this machine (s): the fastest of
    three runs of up to 256 rows after a warm-up, so one slow run does not multiply the
    number of tasks (timing 16 designs once gave 175 to 3 847 chunks for the same input)."""
    if len(x) == 0:
        return 0.0
    evaluate_batch(scene, x[:16], threads=1, **kwargs)
    probe = x[:256]
    per_design = math.inf
    for _ in range(3):
        start = time.perf_counter()
        evaluate_batch(scene, probe, threads=1, **kwargs)
        per_design = min(per_design, (time.perf_counter() - start) / len(probe))
    return per_design


def chunk_size(
    scene: Scene,
    x: np.ndarray,
    min_chunk_seconds: float = 0.1,
    threads: int = 1,
    per_design: Optional[float] = None,
    **kwargs: Any,
) -> int:
    """Rows per task: `CHUNKS_PER_THREAD` chunks per worker thread (`threads` in all), but
    none holding less than `min_chunk_seconds` of work, at `per_design` seconds a design
    (by default `seconds_per_design` measures it)."""
    if len(x) == 0:
        return 1
    if per_design is None:
        per_design = seconds_per_design(scene, x, **kwargs)
    if not (math.isfinite(per_design) and per_design >= 0):
        raise ValueError(f"per_design must be a finite time in seconds ≥ 0, got {per_design}")
    if not (math.isfinite(min_chunk_seconds) and min_chunk_seconds > 0):
        raise ValueError(f"min_chunk_seconds must be a finite time in seconds > 0, got {min_chunk_seconds}")
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


def _epoch(
    scene: Scene,
    seed: int,
    budget: int,
    state: Optional[bytes],
    immigrants: Optional[str],
    emigrants: int,
    last: bool,
    kwargs: dict,
) -> tuple[bytes, str, SearchResult]:
    """One island's epoch: its search from `state` (None: a new one), with `immigrants`
    taken in first, on to `budget` evaluations in all; returns the new state, the members
    it sends on, and its result so far. The state travels as checkpoint bytes, so the
    epoch may run on any worker. Only the `last` epoch warns of a search with no feasible
    design yet."""
    with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings():
        if not last:
            warnings.simplefilter("ignore", RuntimeWarning)
        path = os.path.join(folder, "island.ckpt")
        if state is None:
            result = optimise(
                scene, seed=seed, budget=budget, threads=1, progress=False, checkpoint=path, **kwargs
            )
        else:
            with open(path, "wb") as f:
                f.write(state)
            if immigrants is not None:
                _noncirc.immigrate(path, immigrants)
            result = optimise(resume=path, budget=budget, threads=1, progress=False, checkpoint=path)
        with open(path, "rb") as f:
            state = f.read()
        return state, _noncirc.emigrants(path, emigrants), result


def islands(
    client,
    scene: Scene,
    seeds: Sequence[int],
    *,
    epochs: int = 4,
    migrants: int = 2,
    budget: Optional[int] = None,
    **kwargs: Any,
) -> list[SearchResult]:
    """An island model: one search per seed, each a task, that run in `epochs` equal
    parts of `budget` evaluations each (the scene's budget by default); after each part
    every island sends its `migrants` best members to the next island of the ring (seed
    order), which takes them in place of its worst. Results in seed order.

    Deterministic: the same seeds give the same results on any cluster, whatever the
    workers and the order tasks finish in (each epoch waits for the ring's previous one).
    With `migrants=0` (or `epochs=1`) the islands are independent, and each equals
    `optimise(scene, seed=s, budget=budget, **kwargs)`. Migration needs a population:
    `algorithm` `de`, `nsga2` or `nsga3`."""
    seeds = list(seeds)
    if epochs < 1:
        raise ValueError(f"epochs = {epochs}: expected 1 or more")
    if migrants < 0:
        raise ValueError(f"migrants = {migrants}: expected 0 or more")
    if not seeds:
        return []
    total = budget if budget is not None else int(scene.get("search.budget"))
    states: list[Optional[bytes]] = [None] * len(seeds)
    outgoing: list[Optional[str]] = [None] * len(seeds)
    results: list[SearchResult] = []
    for epoch in range(epochs):
        until = math.ceil(total * (epoch + 1) / epochs)
        # Island i takes in what island i − 1 sent at the end of the last epoch.
        incoming = [outgoing[i - 1] if migrants and len(seeds) > 1 else None for i in range(len(seeds))]
        futures = client.map(
            _epoch,
            [scene] * len(seeds),
            seeds,
            [until] * len(seeds),
            states,
            incoming,
            [migrants] * len(seeds),
            [epoch == epochs - 1] * len(seeds),
            [kwargs] * len(seeds),
            pure=False,
        )
        done = client.gather(futures)
        states = [d[0] for d in done]
        outgoing = [d[1] for d in done]
        results = [d[2] for d in done]
    return results
