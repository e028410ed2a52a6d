#!/usr/bin/env python3
"""Times a criterion bench of this tree against the same bench of an earlier revision, in
alternating pairs, so that a slow spell of the machine hits both halves of a pair.

    python3 scripts/pair_bench.py REV BENCH FILTER [--rounds N]

for example `python3 scripts/pair_bench.py 75e0fbd evaluation population_default_resolution`
(issue 37's start; docs/performance.md). REV's bench is built in a git worktree under
`target/pair/` with a target directory of its own, this tree's with cargo as usual. Each
round runs both binaries once (`--warm-up-time 1 --measurement-time 3`), the order
alternating, and keeps each benchmark's criterion median. Printed per benchmark: each
side's median over the rounds with its lowest and highest, and the median of the paired
ratios (REV's time over this tree's: above 1 means this tree is faster) with its range.
On a machine whose speed moves from hour to hour, the paired ratio is the figure to read.
"""

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PAIR = ROOT / "target" / "pair"

# criterion's line for a benchmark's time: `name  time: [low median high]` (the name may
# stand alone on the line before when it is long).
TIME = re.compile(r"time:\s+\[\S+ \S+ (\S+) (ns|µs|us|ms|s) ")
TO_MICROSECONDS = {"ns": 1e-3, "µs": 1.0, "us": 1.0, "ms": 1e3, "s": 1e6}


def bench_binary(bench: str, cwd: Path, target_dir: Path | None = None) -> Path:
    """Builds `bench` in `cwd` (release, not run) and returns its executable."""
    env = None if target_dir is None else dict(os.environ, CARGO_TARGET_DIR=str(target_dir))
    out = subprocess.run(
        ["cargo", "bench", "-p", "noncirc", "--bench", bench, "--no-run", "--message-format=json"],
        cwd=cwd,
        env=env,
        check=True,
        stdout=subprocess.PIPE,  # the JSON messages; cargo's progress goes to stderr
        text=True,
    ).stdout
    for line in out.splitlines():
        msg = json.loads(line)
        if msg.get("reason") == "compiler-artifact" and msg["target"]["name"] == bench:
            if msg.get("executable"):
                return Path(msg["executable"])
    sys.exit(f"pair_bench: cargo built no executable for bench {bench!r} in {cwd}")


def revision_binary(rev: str, bench: str) -> Path:
    """Builds `bench` as revision `rev` has it, in a worktree of its own, and returns a copy
    of its executable (the worktree is removed)."""
    commit = subprocess.run(
        ["git", "rev-parse", "--verify", f"{rev}^{{commit}}"],
        cwd=ROOT,
        check=True,
        capture_output=True,
        text=True,
    ).stdout.strip()
    copy = PAIR / "bin" / f"{commit[:12]}-{bench}"
    if copy.exists():
        return copy
    tree = PAIR / f"src-{commit[:12]}"
    git = {"cwd": ROOT, "check": True, "capture_output": True}
    subprocess.run(["git", "worktree", "add", "--detach", "--force", str(tree), commit], **git)
    try:
        built = bench_binary(bench, tree, PAIR / "target")
        copy.parent.mkdir(parents=True, exist_ok=True)
        copy.write_bytes(built.read_bytes())
        copy.chmod(0o755)
    finally:
        subprocess.run(["git", "worktree", "remove", "--force", str(tree)], **git)
    return copy


def medians(binary: Path, filt: str) -> dict[str, float]:
    """Each benchmark's criterion median (µs) from one run of `binary` over `filt`."""
    # Run in target/pair: criterion keeps its baselines under the working directory.
    out = subprocess.run(
        [str(binary), "--bench", filt, "--noplot", "--warm-up-time", "1", "--measurement-time", "3"],
        cwd=PAIR,
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    found, name = {}, None
    for line in out.splitlines():
        words = line.split()
        if words and not line.startswith(" ") and words[0] not in ("Benchmarking", "Found"):
            name = words[0]
        m = TIME.search(line)
        if m and name:
            found[name] = float(m.group(1)) * TO_MICROSECONDS[m.group(2)]
    return found


def spread(values: list[float], digits: int) -> str:
    """`median [lowest, highest]` of `values`."""
    low, mid, high = (f"{v:.{digits}f}" for v in (min(values), statistics.median(values), max(values)))
    return f"{mid} [{low}, {high}]"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("rev", help="the earlier revision (a commit, tag or branch)")
    parser.add_argument("bench", help="the bench target, e.g. evaluation or robustness")
    parser.add_argument("filter", help="criterion's filter, e.g. population_default_resolution")
    parser.add_argument("--rounds", type=int, default=5, help="pairs to run (default 5)")
    args = parser.parse_args()
    if args.rounds < 1:
        sys.exit(f"pair_bench: --rounds must be at least 1, got {args.rounds}")
    PAIR.mkdir(parents=True, exist_ok=True)
    sides = {
        args.rev: revision_binary(args.rev, args.bench),
        "this tree": bench_binary(args.bench, ROOT),
    }
    times: dict[str, dict[str, list[float]]] = {}
    for r in range(args.rounds):
        order = list(sides) if r % 2 == 0 else list(sides)[::-1]
        for side in order:
            for name, t in medians(sides[side], args.filter).items():
                times.setdefault(name, {}).setdefault(side, []).append(t)
        print(f"round {r + 1} of {args.rounds} done", file=sys.stderr)
    if not times:
        sys.exit(f"pair_bench: no benchmark of {args.bench!r} matches {args.filter!r}")
    old, new = sides
    print(f"{args.rounds} alternating pairs; µs per iteration, median [lowest, highest]")
    for name, by_side in times.items():
        a, b = by_side.get(old, []), by_side.get(new, [])
        if len(a) != len(b) or not a:
            print(f"{name}: not run by both sides ({len(a)} and {len(b)} runs)")
            continue
        ratios = [x / y for x, y in zip(a, b)]
        print(f"{name}\n  {old}: {spread(a, 1)}\n  {new}: {spread(b, 1)}")
        print(f"  paired {old}/{new}: {spread(ratios, 3)}")


if __name__ == "__main__":
    try:
        main()
    except subprocess.CalledProcessError as e:
        last = (e.stderr or "").strip().splitlines()[-1:] if isinstance(e.stderr, str) else []
        command = " ".join(map(str, e.cmd))
        sys.exit(f"pair_bench: {command} failed (exit {e.returncode})" + "".join(f": {x}" for x in last))
