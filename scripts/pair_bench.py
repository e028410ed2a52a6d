#!/usr/bin/env python3
"""Times this tree against an earlier revision in alternating pairs, so that a slow spell
of the machine hits both halves of a pair: a criterion bench, or a CLI command.

    python3 scripts/pair_bench.py bench REV BENCH FILTER [--rounds N]
    python3 scripts/pair_bench.py cli REV [--rounds N] -- ARGS...

for example `bench 75e0fbd evaluation population_default_resolution` or
`cli 75e0fbd -- optimise paper-search --threads 2` (issue 37's start; docs/performance.md).
REV's build is made in a git worktree under `target/pair/` with a target directory of its
own (and kept there for the next run), this tree's with cargo as usual. Each round runs
both sides once, the order alternating: a bench with `--warm-up-time 1
--measurement-time 3`, keeping each benchmark's criterion median; a command as `noncirc
ARGS...` (which must succeed), keeping its wall time. Printed: each side's median over
the rounds with its lowest and highest, and the median of the paired ratios (REV's time
over this tree's: above 1 means this tree is faster) with its range. On a machine whose
speed moves from hour to hour, the paired ratio is the figure to read.
"""

import argparse
import functools
import json
import os
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PAIR = ROOT / "target" / "pair"

# criterion's line for a benchmark's time: `name  time: [low median high]` (the name may
# stand alone on the line before when it is long).
TIME = re.compile(r"time:\s+\[\S+ \S+ (\S+) (ns|µs|us|ms|s) ")
TO_MICROSECONDS = {"ns": 1e-3, "µs": 1.0, "us": 1.0, "ms": 1e3, "s": 1e6}


def built(target: list[str], name: str, cwd: Path, target_dir: Path | None = None) -> Path:
    """Builds the executable `name` with cargo's `target` arguments in `cwd` (release) and
    returns it."""
    env = None if target_dir is None else dict(os.environ, CARGO_TARGET_DIR=str(target_dir))
    out = subprocess.run(
        ["cargo", *target, "--message-format=json"],
        cwd=cwd,
        env=env,
        check=True,
        stdout=subprocess.PIPE,  # the JSON messages; cargo's progress goes to stderr
        text=True,
    ).stdout
    for line in out.splitlines():
        msg = json.loads(line)
        if msg.get("reason") == "compiler-artifact" and msg["target"]["name"] == name:
            if msg.get("executable"):
                return Path(msg["executable"])
    sys.exit(f"pair_bench: cargo built no executable {name!r} in {cwd}")


def bench_target(bench: str) -> tuple[list[str], str]:
    """cargo's arguments that build criterion bench `bench` without running it, and its name."""
    return ["bench", "-p", "noncirc", "--bench", bench, "--no-run"], bench


# cargo's arguments that build the CLI, and its name.
CLI_TARGET = (["build", "--release", "-p", "noncirc-cli", "--bin", "noncirc"], "noncirc")


def revision_binary(rev: str, target: tuple[list[str], str]) -> Path:
    """Builds `target` as revision `rev` has it, in a worktree of its own, and returns a copy
    of its executable (the worktree is removed)."""
    commit = subprocess.run(
        ["git", "rev-parse", "--verify", f"{rev}^{{commit}}"],
        cwd=ROOT,
        check=True,
        capture_output=True,
        text=True,
    ).stdout.strip()
    args, name = target
    copy = PAIR / "bin" / f"{commit[:12]}-{name}"
    if copy.exists():
        return copy
    tree = PAIR / f"src-{commit[:12]}"
    git = {"cwd": ROOT, "check": True, "capture_output": True}
    subprocess.run(["git", "worktree", "add", "--detach", "--force", str(tree), commit], **git)
    try:
        executable = built(args, name, tree, PAIR / "target")
        copy.parent.mkdir(parents=True, exist_ok=True)
        copy.write_bytes(executable.read_bytes())
        copy.chmod(0o755)
    finally:
        subprocess.run(["git", "worktree", "remove", "--force", str(tree)], **git)
    return copy


def bench_medians(binary: Path, filt: str) -> dict[str, float]:
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


def wall_time(binary: Path, args: list[str]) -> dict[str, float]:
    """The wall time (µs) of one run of `binary args` in `target/pair/run` (its outputs, if
    any, land there), by the command's words."""
    run = PAIR / "run"
    run.mkdir(exist_ok=True)
    start = time.perf_counter()
    subprocess.run([str(binary), *args], cwd=run, check=True, capture_output=True)
    return {"noncirc " + " ".join(args): (time.perf_counter() - start) * 1e6}


def spread(values: list[float], digits: int) -> str:
    """`median [lowest, highest]` of `values`."""
    low, mid, high = (f"{v:.{digits}f}" for v in (min(values), statistics.median(values), max(values)))
    return f"{mid} [{low}, {high}]"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    modes = parser.add_subparsers(dest="mode", required=True)
    bench = modes.add_parser("bench", help="a criterion bench")
    bench.add_argument("rev", help="the earlier revision (a commit, tag or branch)")
    bench.add_argument("bench", help="the bench target, e.g. evaluation or robustness")
    bench.add_argument("filter", help="criterion's filter, e.g. population_default_resolution")
    cli = modes.add_parser("cli", help="a noncirc command, timed whole")
    cli.add_argument("rev", help="the earlier revision (a commit, tag or branch)")
    cli.add_argument("args", nargs="+", help="the command's arguments, after --")
    for mode in (bench, cli):
        mode.add_argument("--rounds", type=int, default=5, help="pairs to run (default 5)")
    args = parser.parse_args()
    if args.rounds < 1:
        sys.exit(f"pair_bench: --rounds must be at least 1, got {args.rounds}")
    PAIR.mkdir(parents=True, exist_ok=True)
    if args.mode == "bench":
        target = bench_target(args.bench)
        run = functools.partial(bench_medians, filt=args.filter)
    else:
        target = CLI_TARGET
        run = functools.partial(wall_time, args=args.args)
    sides = {
        args.rev: revision_binary(args.rev, target),
        "this tree": built(*target, ROOT),
    }
    times: dict[str, dict[str, list[float]]] = {}
    for r in range(args.rounds):
        order = list(sides) if r % 2 == 0 else list(sides)[::-1]
        for side in order:
            for name, t in run(sides[side]).items():
                times.setdefault(name, {}).setdefault(side, []).append(t)
        print(f"round {r + 1} of {args.rounds} done", file=sys.stderr)
    if not times:  # only a bench's filter can match nothing
        sys.exit(f"pair_bench: no benchmark of {args.bench!r} matches {args.filter!r}")
    old, new = sides
    print(f"{args.rounds} alternating pairs; µs, median [lowest, highest]")
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
