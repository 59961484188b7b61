#!/usr/bin/env bash
# yarok's Python environments against robosuite, side by side in one run
# (yarok-py/benches/environments.py): installs robosuite 1.5.2 (MIT) with the MuJoCo it supports
# (mujoco 3.3.0, Apache-2.0; with MuJoCo 4 robosuite 1.5.2 fails at start) and Gymnasium into a
# venv of the project's cache, ${YAROK_CACHE_DIR:-~/.cache/yarok}/bench, builds yarok's package
# into it, and runs the benchmark with the arguments given (--steps N --rounds N).
set -euo pipefail
cd "$(dirname "$0")/.."
venv="${YAROK_CACHE_DIR:-$HOME/.cache/yarok}/bench"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import robosuite, mujoco, gymnasium" 2>/dev/null; then
  echo "bench: installing robosuite 1.5.2, mujoco 3.3.0 and gymnasium into $venv"
  "$venv/bin/pip" install -q --disable-pip-version-check "robosuite==1.5.2" "mujoco==3.3.0" \
    "gymnasium==1.2.2"
fi
"$venv/bin/pip" install -q --disable-pip-version-check --force-reinstall --no-deps ./yarok-py
exec python3 scripts/results.py python "$venv/bin/python" yarok-py/benches/environments.py "$@"
