#!/usr/bin/env bash
# Builds the design studio's WebAssembly module into studio/pkg/: the noncirc-wasm crate
# for wasm32-unknown-unknown, then wasm-bindgen at the crate's exact version (installed
# with `cargo install --locked` when missing or of another version).
set -euo pipefail
cd "$(dirname "$0")/.."
if command -v rustup >/dev/null; then rustup target add wasm32-unknown-unknown >/dev/null 2>&1 || true; fi
version=$(sed -n 's/^wasm-bindgen = "=\(.*\)"$/\1/p' crates/noncirc-wasm/Cargo.toml)
if [ "$(wasm-bindgen --version 2>/dev/null)" != "wasm-bindgen $version" ]; then
  echo "installing wasm-bindgen-cli $version"
  # --force: a copy recorded as installed but missing or replaced is built again. --debug:
  # the tool builds in 50 s instead of 103 s on two cores and takes 2 s instead of 0.6 s
  # on the studio's module (docs/reliability.md); it is built once, run once per build.
  # Without the test command's lints (tests/run_all.sh): the tool's warnings are not ours.
  env -u RUSTC_WORKSPACE_WRAPPER -u RUSTFLAGS \
    cargo install --locked --force --debug --quiet wasm-bindgen-cli --version "$version"
fi
# The release profile unless NONCIRC_PROFILE names another (tests/run_all.sh: `ci`, the
# test command's faster build; the studio it serves is the same code).
profile=${NONCIRC_PROFILE:-release}
cargo build --profile "$profile" --quiet --target wasm32-unknown-unknown -p noncirc-wasm
wasm-bindgen --target web --no-typescript --out-dir studio/pkg \
  "target/wasm32-unknown-unknown/$profile/noncirc_wasm.wasm"
echo "studio built: studio/pkg/ ($(du -h studio/pkg/noncirc_wasm_bg.wasm | cut -f1) of WebAssembly)"
