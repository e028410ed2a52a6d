"""noncirc's speed-up over the NumPy implementation, for one batch of designs, in one run.

Each timing is the best of 3 repetitions: this VM's speed swings by tens of per cent
within seconds, and the best repetition is the one least disturbed.

    python python/benchmarks/bench_numpy.py [n_designs]
"""

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
import noncirc  # noqa: E402
from numpy_model import PAPER, evaluate  # noqa: E402


def best_of(repeats: int, run) -> float:
    """The least wall time (s) of `repeats` calls of `run`."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def main(n: int = 2000) -> None:
    scene = noncirc.Scene.builtin("paper-search")
    params = scene.free_parameters()
    names = [p[0] for p in params]
    lo, hi = np.array([p[1] for p in params]), np.array([p[2] for p in params])
    x = lo + np.random.default_rng(7).random((n, len(params))) * (hi - lo)
    evaluate(x[:8], names, PAPER)
    noncirc.evaluate_batch(scene, x[:8])
    t_numpy = best_of(3, lambda: evaluate(x, names, PAPER))
    rows = [("numpy (vectorised, 1 core)", t_numpy)]
    for threads in (1, 2):
        t = best_of(3, lambda: noncirc.evaluate_batch(scene, x, threads=threads))
        rows.append((f"noncirc, {threads} thread(s)", t))
    print(f"{n} designs, 120 samples per turn, all objectives")
    for name, t in rows:
        print(f"  {name:<28} {t * 1e3:9.1f} ms  {n / t:12,.0f} designs/s  speed-up {t_numpy / t:6.1f}x")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 2000)
