"""docs/dynamics.md's check of docs/search.md's designs: the design each search reports (the
runs of search_table.py) evaluated with the teeth's strength in place of the module bound.

    cargo build --release && python3 python/benchmarks/strength_table.py [seeds]

Each run's design is evaluated with the objectives of docs/search.md less `module` plus
`bending_safety` and `contact_safety`, its teeth cut by a rack, then by a shaper of 100
teeth. Prints how many designs change status, why, and the safety factors of those whose
teeth can be cut.
"""

import json
import statistics
import subprocess
import sys
from collections import Counter

from search_table import ALGORITHMS, run

OBJECTIVES = ["interference", "picking_angle", "pushing_angle", "angle_difference", "seedling_push",
              "ground_clearance", "trajectory_height", "picking_admissible", "bending_safety", "contact_safety"]
CUTTERS = {"rack": 'gear.teeth.cutter={kind="rack"}', "shaper of 100 teeth": 'gear.teeth.cutter={kind="shaper",teeth=100}'}


def evaluate(design, cutter):
    args = ["target/release/noncirc", "evaluate", "--format", "json", "--set", f"objectives={json.dumps(OBJECTIVES)}",
            "--set", cutter]
    for name, value in design.items():
        args += ["--set", f"{name}={value!r}"]
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode != 0:
        return {"error": done.stderr.strip().splitlines()[-1]}
    return json.loads(done.stdout)


def why(report):
    """The reason a design fails the strength check, in a few words."""
    text = report.get("strength_unavailable")
    if text is None:
        o = {x["name"]: x for x in report["objectives"]}
        failing = [k for k in ("bending_safety", "contact_safety") if o[k]["violation"] > 0]
        return "safety factor below its bound: " + ", ".join(failing) if failing else None
    for key, short in [("concave", "a concave arc the cutter cannot enter"), ("undercut", "undercut"),
                       ("pointed", "pointed teeth"), ("overlap", "teeth overlap in mesh")]:
        if key in text:
            return f"teeth cannot be cut: {short}"
    return "teeth cannot be cut: " + text[:60]


def main(seeds=10):
    runs = [run(a, s) for a in ALGORITHMS for s in range(1, seeds + 1)]
    print(f"{len(runs)} runs, {sum(r['feasible'] for r in runs)} of whose designs meet every objective with the module bound\n")
    print("| teeth cut by | feasible before → after | feasible → infeasible | infeasible → feasible | why the strength check fails (designs) | least SF median [range] | least SH median [range] |")
    print("|---|---|---|---|---|---|---|")
    for name, cutter in CUTTERS.items():
        reports = [(r["feasible"], evaluate(r["best"], cutter)) for r in runs]
        done = [(before, rep) for before, rep in reports if "error" not in rep]
        reasons = Counter(why(rep) for _, rep in done)
        cut = [rep for _, rep in done if rep.get("strength_unavailable") is None]
        value = lambda rep, k: next(o["value"] for o in rep["objectives"] if o["name"] == k)  # noqa: E731
        span = lambda xs: f"{statistics.median(xs):.1f} [{min(xs):.1f}, {max(xs):.1f}]" if xs else "—"  # noqa: E731
        lost = sum(before and not rep["feasible"] for before, rep in done)
        won = sum(not before and rep["feasible"] for before, rep in done)
        text = "; ".join(f"{k} ({n})" for k, n in reasons.most_common() if k is not None) or "—"
        refused = len(reports) - len(done)
        print(f"| {name} | {sum(b for b, _ in done)} → {sum(rep['feasible'] for _, rep in done)} | {lost} | {won} | {text}"
              f"{f'; {refused} refused' if refused else ''} | {span([value(r, 'bending_safety') for r in cut])} | "
              f"{span([value(r, 'contact_safety') for r in cut])} |")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 10)
