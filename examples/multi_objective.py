"""A multi-objective study: how large a module can the gears have, against how slowly the
arm's tip meets the seedling, among three-arm designs that meet every agronomic objective?

noncirc's NSGA-II runs from random starts in the three-arm paper's search space (17
parameters: 12 pitch-curve radii, Φ0, β0, S, H1, γ0) with two goals, the module (mm,
maximised) and the tip's speed relative to the seedling at picking (m/s, minimised), over
several seeds. Each run's confirmed Pareto set is merged with the others', the merged set is
filtered to its non-dominated designs with pymoo's sorting (an independent implementation),
and the designs are written to a CSV with the goals in their units and the 17 parameters.
CI runs it (tests/run_all.sh) with `--seeds 2`.

    python examples/multi_objective.py [--seeds N] [--out front.csv]
"""

from __future__ import annotations

import argparse
import sys

import numpy as np
from pymoo.util.nds.non_dominated_sorting import NonDominatedSorting

import noncirc


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, default=5, help="NSGA-II runs, seeds 1..N")
    parser.add_argument("--out", default="front.csv", help="the merged front (CSV)")
    args = parser.parse_args()

    scene = noncirc.Scene.builtin("paper-search").with_set(
        "search.goals", ["module", "picking_tip_speed"]
    )
    designs = []
    print(f"{'seed':>4} {'feasible':>8} {'front':>5} {'module (mm)':>14} {'tip speed (m/s)':>16}")
    for seed in range(1, args.seeds + 1):
        result = noncirc.optimise(scene, algorithm="nsga2", seed=seed, progress=False)
        front = [d for d in result.pareto if d.cv == 0.0]
        module = [d.goals["module_mm"] for d in front]
        speed = [d.goals["picking_tip_speed_m_s"] for d in front]
        span = lambda v: f"{min(v):.2f}–{max(v):.2f}" if v else "–"  # noqa: E731
        print(f"{seed:>4} {str(result.feasible):>8} {len(front):>5} {span(module):>14} {span(speed):>16}")
        designs.extend(front)
    if not designs:
        print("no run found a feasible design", file=sys.stderr)
        return 1

    # Non-dominated among all runs, as pymoo sorts them (all minimised: the module negated).
    f = np.array([[-d.goals["module_mm"], d.goals["picking_tip_speed_m_s"]] for d in designs])
    best = NonDominatedSorting().do(f, only_non_dominated_front=True)
    merged = sorted((designs[i] for i in best), key=lambda d: d.goals["module_mm"])
    names = list(merged[0].parameters)
    with open(args.out, "w", encoding="utf-8") as out:
        out.write(",".join(["module_mm", "picking_tip_speed_m_s", *names]) + "\n")
        for d in merged:
            row = [d.goals["module_mm"], d.goals["picking_tip_speed_m_s"], *d.parameters.values()]
            out.write(",".join(f"{v:.6g}" for v in row) + "\n")

    # Every design written meets every objective: confirmed again here, independently of
    # the search, by evaluating its scene at the default resolution.
    for d in merged:
        design = scene.with_values(names, [d.parameters[n] for n in names])
        evaluation = noncirc.evaluate(design)
        assert evaluation.feasible, d
    m = [d.goals["module_mm"] for d in merged]
    v = [d.goals["picking_tip_speed_m_s"] for d in merged]
    print(
        f"merged front: {len(merged)} designs of {len(designs)}, module {min(m):.2f}–{max(m):.2f} mm, "
        f"tip speed {min(v):.2f}–{max(v):.2f} m/s; each re-evaluated feasible; written to {args.out}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
