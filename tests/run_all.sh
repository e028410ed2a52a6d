#!/usr/bin/env bash
# Every check and test of noncirc: formatting, lints, Rust tests, then the Python package.
set -euo pipefail
cd "$(dirname "$0")/.."

# Each stage's wall time, printed as it ends and as a table when the command ends (CI's
# limit is 90 minutes on a shared 2-core machine: this shows where they go).
STAGE="" STAGE_START=$SECONDS TIMES=""
stage() {
  end_stage
  STAGE=$1 STAGE_START=$SECONDS
  echo "== $1"
}
end_stage() {
  if [ -n "$STAGE" ]; then
    local took=$((SECONDS - STAGE_START))
    echo "-- ${took} s: $STAGE"
    TIMES+=$(printf '%6d s  %s' "$took" "$STAGE")$'\n'
  fi
  STAGE=""
}
report_times() {
  local status=$?
  end_stage
  # A run ended early leaves no install behind it (see PIP_PID below).
  if [ -n "${PIP_PID:-}" ]; then
    pkill -P "$PIP_PID" 2>/dev/null || true
    kill "$PIP_PID" 2>/dev/null || true
  fi
  echo "== stage times (total ${SECONDS} s, exit ${status})"
  printf '%s' "$TIMES"
}
trap report_times EXIT

# One build profile for every stage (Cargo.toml's `ci`: release without LTO): the Rust
# tests build it, and the CLI the Python and browser tests run, the examples and the
# Python wheel reuse it instead of building the release profile again.
PROFILE=ci
export NONCIRC_PROFILE=$PROFILE NONCIRC_BIN="$PWD/target/$PROFILE/noncirc"

# Clippy's lints, every warning denied, on every crate of the workspace each stage builds:
# Cargo runs the workspace's crates through clippy-driver (RUSTC_WORKSPACE_WRAPPER, which
# `cargo clippy` sets itself for a check-only build). The tests, benches and examples
# (`cargo test --all-targets`), the WebAssembly module, the library without figures and
# the Python extension are linted as they are compiled: what `cargo clippy --workspace
# --all-targets -- -D warnings` checks, without a second build of the workspace (89 s;
# the same binaries' tests ran 83 s against 88 s without it). Tools installed with `cargo
# install` and the nightly fuzz build run without it: their warnings are not ours.
CLIPPY_DRIVER=$(command -v clippy-driver) || {
  echo "no clippy-driver: install clippy (rustup component add clippy)" >&2
  exit 1
}
export RUSTC_WORKSPACE_WRAPPER=$CLIPPY_DRIVER RUSTFLAGS="${RUSTFLAGS:+$RUSTFLAGS }-D warnings"
NO_LINTS=(env -u RUSTC_WORKSPACE_WRAPPER -u RUSTFLAGS)

# The Python packages (mostly downloads) install in the background while the Rust stages
# build; the Python stage waits for them and shows their log if they failed.
VENV=.venv PIP_PID="" PIP_LOG=$(mktemp)
if [ -f python/pyproject.toml ]; then
  (
    [ -x "$VENV/bin/python" ] || python3 -m venv "$VENV"
    "$VENV/bin/python" -m pip install --quiet --upgrade pip
    "$VENV/bin/python" -m pip install --quiet -r python/requirements-dev.txt
  ) >"$PIP_LOG" 2>&1 &
  PIP_PID=$!
fi

stage "cargo fmt --check; the core's layers point one way"
cargo fmt --all -- --check
python3 scripts/check_layers.py
stage "the core builds for the browser (linted): the design studio's WebAssembly module"
bash studio/build.sh
stage "the library builds without figures (linted); the Python extension without the CLI's crates"
cargo check -p noncirc --no-default-features --all-targets
if cargo tree -p noncirc-py -e normal | grep -E "^[^a-z]*(clap|indicatif|ctrlc|plotters) "; then
  echo "the Python extension must not depend on the crates above" >&2
  exit 1
fi
stage "cargo test (every target compiled through clippy)"
# Default members (core, library, CLI; maturin builds the extension), every target in one
# invocation: the benches compile and run once as tests (no timing) against the same build
# of the library (a second `cargo test --benches` selected other features and compiled it
# again, about three minutes); then the doc tests, which `--all-targets` leaves out.
cargo test --profile "$PROFILE" --all-targets
cargo test --profile "$PROFILE" --doc

stage "fuzz targets (scene files, checkpoints): 20 000 fixed-seed runs each from the corpus"
# cargo-fuzz needs nightly Rust; both are installed here if missing. The runs are
# deterministic (-seed, -runs); new inputs go to a temporary directory, not the corpus.
if command -v rustup >/dev/null; then
  rustup toolchain list | grep -q '^nightly' || rustup toolchain install nightly --profile minimal
  # A debug build of the tool (it only drives Cargo and libFuzzer): half the install time.
  command -v cargo-fuzz >/dev/null || "${NO_LINTS[@]}" cargo install cargo-fuzz --locked --debug --version 0.13.2
  FUZZ_TMP=$(mktemp -d)
  for target in scene checkpoint; do
    mkdir -p "$FUZZ_TMP/$target"
    # No AddressSanitizer: noncirc's own code has no `unsafe`, so the memory errors it finds
    # cannot occur, and it slows both the build and the runs; panics, aborts and hangs
    # are still caught. Sixteen codegen units (cargo-fuzz's default is one): the build
    # takes 83 s instead of 98 s on two cores, the 20 000 runs 2 s either way.
    "${NO_LINTS[@]}" cargo +nightly fuzz run -O --sanitizer none --codegen-units 16 "$target" "$FUZZ_TMP/$target" "fuzz/corpus/$target" -- \
      -seed=1 -runs=20000 -artifact_prefix="$FUZZ_TMP/" 2>&1 | tail -1
  done
  rm -rf "$FUZZ_TMP"
fi

if [ -f python/pyproject.toml ]; then
  stage "Python package (the abi3 wheel built, installed with pip, tested)"
  if ! wait "$PIP_PID"; then
    cat "$PIP_LOG" >&2
    echo "installing python/requirements-dev.txt into $VENV failed (its log is above)" >&2
    exit 1
  fi
  PIP_PID=""
  rm -f "$PIP_LOG"
  # As a user installs it (README): the wheel, not the source tree. The tests import the
  # installed package (python/ is not on their path, so a build `maturin develop` left in
  # python/noncirc is not what they test; the check below says where it comes from).
  WHEELS=$(mktemp -d)
  (cd python && ../"$VENV"/bin/maturin build --profile "$PROFILE" --strip --quiet --out "$WHEELS")
  "$VENV/bin/python" -m pip install --quiet --force-reinstall --no-deps "$WHEELS"/noncirc-*-abi3-*.whl
  rm -rf "$WHEELS"
  PY="$PWD/$VENV/bin/python"
  (cd /tmp && "$PY" -c \
    'import noncirc, sys; assert "site-packages" in noncirc.__file__, noncirc.__file__; print("testing the installed wheel:", noncirc.__file__)')
  # The CLI the teeth peers' tests run: the one `cargo test` built. Not `cargo build -p
  # noncirc-cli`: without the tests' dev-dependencies Cargo unifies other features (serde's
  # `alloc`, among others) and builds the CLI and everything under it again (86 s).
  [ -x "$NONCIRC_BIN" ] || { echo "no CLI at $NONCIRC_BIN: the cargo test stage builds it" >&2; exit 1; }
  # One worker per core (pytest-xdist): 76 s instead of 121 s on two cores.
  "$VENV/bin/python" -m pytest python/tests -q -p no:cacheprovider -n auto

  stage "examples/: the papers' figures (as PNG and PDF) and a multi-objective study"
  EXAMPLES_OUT=$(mktemp -d)
  NONCIRC=$NONCIRC_BIN bash examples/paper_figures.sh "$EXAMPLES_OUT" png,pdf
  "$VENV/bin/python" examples/multi_objective.py --seeds 2 --out "$EXAMPLES_OUT/front.csv"
  rm -rf "$EXAMPLES_OUT"
fi

stage "the design studio in a browser (Playwright driving Debian's chromium; docs/studio.md)"
# .ci/run installs chromium and Node.js; elsewhere set CHROMIUM to a Chromium binary.
CHROMIUM=${CHROMIUM:-/usr/bin/chromium}
if [ ! -x "$CHROMIUM" ]; then
  echo "no Chromium at $CHROMIUM: install Debian's chromium (apt-get install chromium) or set CHROMIUM" >&2
  exit 1
fi
# The native side of the speed comparison, `cargo run --example evaluation_time`, is the
# build the cargo test stage made (the same features and lints: nothing is built again).
(cd studio && npm ci --no-audit --no-fund --loglevel=error && CHROMIUM="$CHROMIUM" npm test)
