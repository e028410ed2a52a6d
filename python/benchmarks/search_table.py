"""The table of docs/search.md: every algorithm on the default scene, 10 seeds, from random starts.

    cargo build --release && python3 python/benchmarks/search_table.py [seeds]

Runs `noncirc optimise --format json` (budget 60 000, population 48, 2 threads) and prints
the Markdown table and each algorithm's best margins.
"""

import json
import statistics
import subprocess
import sys

ALGORITHMS = ["guided", "de", "cmaes", "nsga2", "nsga3"]
# (lower, upper, scale) as in docs/search.md and the core's `scale`; the seedling-push margin is left out.
BOUNDS = {
    "interference": (0.0, None, 1.0),
    "picking_angle": (-5.0, 15.0, 10.0),
    "pushing_angle": (45.0, 65.0, 10.0),
    "angle_difference": (50.0, 60.0, 5.0),
    "ground_clearance": (20.0, None, 2.0),
    "trajectory_height": (260.0, None, 26.0),
    "module": (2.5, None, 1.0),
    "picking_admissible": (0.0, None, 1.0),
}


def margins(objectives):
    out = {}
    for name, (lo, hi, _) in BOUNDS.items():
        v = objectives[name]
        out[name] = min(v - lo, hi - v) if hi is not None else v - lo
    return out


def least_normalised(m):
    return min(m[name] / BOUNDS[name][2] for name in m)


def run(algorithm, seed):
    out = subprocess.run(
        ["target/release/noncirc", "optimise", "--format", "json", "--quiet", "--algorithm", algorithm,
         "--seed", str(seed), "--budget", "60000", "--population", "48", "--threads", "2"],
        check=True, capture_output=True, text=True,
    ).stdout
    return json.loads(out)


def main(seeds=10):
    print("| algorithm | feasible runs | median evaluations to first feasible | median seconds to first feasible "
          "| median total seconds | median least normalised margin | median module (mm) |")
    print("|---|---|---|---|---|---|---|")
    best = {}
    for algorithm in ALGORITHMS:
        runs = [run(algorithm, seed) for seed in range(1, seeds + 1)]
        ok = [r for r in runs if r["feasible"]]
        med = lambda xs: statistics.median(xs) if xs else float("nan")  # noqa: E731
        first = [r["first_feasible_evaluations"] for r in ok]
        first_s = [r["seconds_to_first_feasible"] for r in ok]
        least = [least_normalised(margins(r["objectives"])) for r in ok]
        print(f"| {algorithm} | {len(ok)}/{seeds} | {med(first):.0f} | {med(first_s):.2f} | "
              f"{med([r['seconds'] for r in runs]):.2f} | {med(least):.3f} | "
              f"{med([r['objectives']['module'] for r in ok]):.3f} |")
        if ok:
            top = max(ok, key=lambda r: least_normalised(margins(r["objectives"])))
            best[algorithm] = {k: round(v, 3) for k, v in margins(top["objectives"]).items()}
    print()
    for algorithm, m in best.items():
        print(f"- {algorithm}: {m}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 10)
