#!/usr/bin/env bash
# Builds yarok's Python wheel once, to install anywhere: the extension stripped, and MuJoCo
# (its shared library and licence) carried inside the package as yarok/mujoco, where the package
# finds it on import — so `pip install yarok-….whl` runs on a machine with no Rust, no yarok
# cache and no build. The wheel is written to the folder given (default target/wheels).
set -euo pipefail
cd "$(dirname "$0")/.."
out="$(realpath -m "${1:-target/wheels}")"
bash scripts/setup.sh
bash scripts/setup-python.sh
cache="${YAROK_CACHE_DIR:-$HOME/.cache/yarok}"
mujoco="${MUJOCO_DIR:-$cache/mujoco-4.0.1}"
# Fetched as the build would (nothing to do when it is there already).
[ -n "${MUJOCO_DIR:-}" ] || python3 yarok-mjc/scripts/fetch_mujoco.py "$mujoco"
bundled=yarok-py/python/yarok/mujoco
rm -rf "$bundled"
mkdir -p "$bundled/lib"
cp "$mujoco/lib/libmujoco.so.4.0.1" "$bundled/lib/"
{
  echo "MuJoCo 4.0.1 (lib/libmujoco.so.4.0.1, from PyPI's mujoco-core wheel), Copyright"
  echo "DeepMind Technologies Limited, licensed under the Apache License, Version 2.0:"
  echo
  cat LICENSE-APACHE
} >"$bundled/LICENSE"
trap 'rm -rf "$bundled"' EXIT
mkdir -p "$out"
"$cache/python/bin/pip" wheel -q --disable-pip-version-check --no-deps -w "$out" ./yarok-py
ls "$out"/yarok-*.whl
