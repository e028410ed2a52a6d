"""The `noncirc` CLI binary the tests run: `$NONCIRC_BIN` if set (tests/run_all.sh sets it
to the build the Rust tests made, target/ci/noncirc), else `target/release/noncirc`."""

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
NONCIRC_BIN = Path(os.environ.get("NONCIRC_BIN") or ROOT / "target" / "release" / "noncirc")
