#!/usr/bin/env bash
# Writes every JSON output of the CLI over the built-in scenes and a fixed set of designs
# into DIR, so that a refactoring can be checked byte for byte:
#   scripts/golden.sh BIN DIR   (BIN: a noncirc binary; then `diff -r DIR_BEFORE DIR_AFTER`)
set -euo pipefail
bin=$1
out=$2
mkdir -p "$out"
run() { # name, then the command's arguments
  local name=$1
  shift
  "$bin" "$@" --format json >"$out/$name.json" 2>"$out/$name.err" || echo "exit $?" >>"$out/$name.err"
}
for scene in paper paper-search transplanter moving-box ellipse-gear; do
  run "evaluate-$scene" evaluate "$scene"
  run "gear-$scene" gear "$scene"
done
run box-default box
run box-transplanter box transplanter
run sweep-r7 sweep paper --param 'gear.curve.radii_mm[6]' --from 10 --to 30 --steps 5 \
  --measure removal_length_mm --measure picking_branch_gap_mm
run sweep-gamma0 sweep paper --param train.gamma0_deg --from -80 --to -20 --steps 7
# Designs around the paper's, one parameter at a time and several at once (fixed values).
i=0
for set in "train.beta0_deg=-47" "train.phi0_deg=70" "train.arm_length_mm=160" \
  "gear.curve.radii_mm[4]=40" "gear.curve.radii_mm[9]=70" "agronomy.tray_normal_deg=135" \
  "gear.curve.kind=\"bspline\"" "train.sun_frame=\"ground\"" "train.pusher_side=\"right\"" \
  "resolution.samples_per_turn=360"; do
  i=$((i + 1))
  run "design-$i" evaluate paper --set "$set" --set train.gamma0_deg=-50
done
# Random designs: fixed pseudo-random values for the twelve radii and the train's angles.
for seed in 1 2 3 4 5 6; do
  sets=$(python3 -c "
import random
r = random.Random($seed)
print(' '.join(f'--set gear.curve.radii_mm[{i}]={r.uniform(35, 70):.3f}' for i in range(12)),
      f'--set train.gamma0_deg={r.uniform(-70, -30):.3f}', f'--set train.beta0_deg={r.uniform(-60, -30):.3f}')")
  # shellcheck disable=SC2086
  run "random-$seed" evaluate paper $sets
done
for algorithm in guided de cmaes nsga2 nsga3; do
  run "optimise-$algorithm" optimise --algorithm "$algorithm" --budget 3000 --seed 3 --threads 2
done
run optimise-de-1-thread optimise --budget 3000 --seed 3 --threads 1
# CAD exports: the gear command's, and those of evaluate --plot (the train's own pair) for
# both sun frames and rotation senses; the figures themselves are left out (slow to draw).
"$bin" gear paper --export "$out/export-gear" >/dev/null 2>>"$out/export.err"
for set in "train.rotation=\"clockwise\"" "train.rotation=\"counterclockwise\"" \
  "train.sun_frame=\"ground\""; do
  name=$(echo "$set" | tr -cd 'a-z_=')
  tmp=$(mktemp -d)
  "$bin" evaluate paper --set "$set" --plot "$tmp" >/dev/null 2>>"$out/export.err"
  mkdir -p "$out/export-$name"
  cp "$tmp"/*.csv "$tmp"/pitch_curves.dxf "$tmp"/pitch_curves.svg "$out/export-$name/"
  rm -rf "$tmp"
done
sed -i '/^wrote /d' "$out/export.err"
# Wall-clock times are the one thing allowed to differ.
python3 - "$out"/optimise-*.json <<'PY'
import json, sys
for path in sys.argv[1:]:
  def strip(v):
      if isinstance(v, dict):
          return {k: strip(x) for k, x in v.items() if "seconds" not in k}
      if isinstance(v, list):
          return [strip(x) for x in v]
      return v
  with open(path) as f:
      data = json.load(f)
  with open(path, "w") as f:
      json.dump(strip(data), f, indent=1, sort_keys=True)
PY
