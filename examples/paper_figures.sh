#!/usr/bin/env bash
# Every figure of docs/figures/ from the command line, as a reader of the papers would make
# them: the three-arm paper's design (Yin et al. 2021: its trajectory, gear train and
# objectives, and the parameter response of its Figure 5), the moving-box paper's Figures 3
# and 11 (Zhou et al. 2018), a search from the paper's space, an NSGA-II front, the margins
# under the tolerances, the Sobol indices, two arms against three and the animation. CI runs it (tests/run_all.sh) into a temporary folder.
#
#   bash examples/paper_figures.sh [OUT_DIR] [FORMATS] [DPI]
#
# OUT_DIR defaults to docs/figures; FORMATS is a comma-separated list of svg, png and pdf
# (default png); DPI is the PNG's resolution (default 96; 300 for print).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-docs/figures}
FORMATS=${2:-png}
DPI=${3:-96}
NONCIRC=${NONCIRC:-target/release/noncirc}
[ -x "$NONCIRC" ] || cargo build --release --quiet -p noncirc-cli
mkdir -p "$OUT"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# plot NAME COMMAND…: the command's figures into $TMP/NAME.
plot() {
  local name=$1
  shift
  "$NONCIRC" "$@" --plot "$TMP/$name" --figure-format "$FORMATS" --dpi "$DPI" >/dev/null 2>"$TMP/$name.log" ||
    { cat "$TMP/$name.log" >&2; return 1; }
}
# keep NAME/FIGURE AS: copies that figure, in every format asked, to $OUT/AS.
keep() {
  local ext
  for ext in ${FORMATS//,/ }; do
    cp "$TMP/$1.$ext" "$OUT/$2.$ext"
  done
}

plot paper evaluate paper
for f in trajectory ground gears objectives; do keep "paper/$f" "$f"; done
plot box box moving-box
keep box/moving_box moving_box
plot sweep sweep paper --param 'gear.curve.radii_mm[6]' --from 10 --to 30 --steps 9
keep sweep/response_trajectories sweep_r7_trajectories
keep sweep/response_module sweep_r7_module
plot search optimise paper-search --seed 1 --out "$TMP/search-results"
keep search/convergence convergence
keep search/best/trajectory best_trajectory
keep search/best/objectives best_objectives
plot front optimise paper-search --algorithm nsga2 --seed 2 \
  --set 'search.goals=["module","picking_tip_speed"]' --out "$TMP/front-results"
keep front/pareto pareto_nsga2
plot ground_frame evaluate paper --set 'train.sun_frame="ground"'
keep ground_frame/trajectory replication_ground_frame
plot bezier evaluate paper --set 'gear.curve.kind="bezier"'
keep bezier/trajectory replication_bezier
# Robust design (docs/robustness.md): the tip-speed optimum's margins under the default
# tolerances (10 000 independent samples), and the Sobol indices of the paper's design.
"$NONCIRC" optimise paper-search --seed 1 --quiet --set 'search.goals=["picking_tip_speed"]' \
  --out "$TMP/tip-results" >/dev/null 2>&1
plot robust robustness "$TMP/tip-results/best.toml" --samples 10000 --seed 2 \
  --set tolerances.assemblies_per_part_set=1
keep robust/robustness_margins robustness_margins
plot sensitivity sensitivity paper
keep sensitivity/sensitivity sensitivity
# Two arms against three (docs/replication.md): each arm count's slowest pass through the
# tray over ten seeds at 180 picks per minute, and the two-arm scene's trajectory.
plot compare compare --seeds 1,2,3,4,5,6,7,8,9,10
keep compare/speed_comparison speed_comparison
plot two_arm evaluate two-arm
keep two_arm/trajectory two_arm_trajectory
"$NONCIRC" animate paper --out "$OUT/mechanism.gif" 2>/dev/null
echo "wrote the figures of docs/figures.md into $OUT ($FORMATS)"
