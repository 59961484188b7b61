#!/usr/bin/env bash
# Regenerates yarok-mjc/src/sys.rs from the MuJoCo headers (needs libclang, e.g.
# `apt-get install libclang-dev`). Run it after bumping MuJoCo; commit the result.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
if [ -n "${MUJOCO_DIR:-}" ]; then
  mujoco=$MUJOCO_DIR
else
  mujoco=${YAROK_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/yarok}/mujoco-4.0.1
  python3 "$here/scripts/fetch_mujoco.py" "$mujoco"
fi
cargo run --release --manifest-path "$here/bindgen/Cargo.toml" -- "$mujoco/include" "$here/src/sys.rs"
rustfmt --edition 2024 "$here/src/sys.rs"
echo "wrote $here/src/sys.rs"
