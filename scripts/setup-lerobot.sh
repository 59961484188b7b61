#!/usr/bin/env bash
# LeRobot (Apache-2.0), for the test of the learning loop (yarok-py/tests/test_lerobot_loop.py),
# once per machine: a venv in ${YAROK_CACHE_DIR:-~/.cache/yarok}/lerobot on Python 3.12 or
# later (LeRobot 0.5 and later need it; pyenv's when the system has none), with LeRobot and the
# extras its documentation names for reading datasets and training ('lerobot[dataset,training]',
# which bring PyTorch, BSD-3-Clause), Stable-Baselines3 (MIT: the reinforcement-learning tests)
# and pytest. Test-only: yarok never imports LeRobot or Stable-Baselines3.
# Prints the venv's python.
set -euo pipefail

venv="${YAROK_CACHE_DIR:-$HOME/.cache/yarok}/lerobot"
if [ ! -x "$venv/bin/python" ]; then
  python=""
  for candidate in python3.13 python3.12 "$HOME"/.pyenv/versions/3.13*/bin/python3 \
    "$HOME"/.pyenv/versions/3.12*/bin/python3; do
    if command -v "$candidate" >/dev/null 2>&1 \
      && "$candidate" -c "import sys, venv; sys.exit(sys.version_info < (3, 12))" 2>/dev/null; then
      python="$candidate"
      break
    fi
  done
  if [ -z "$python" ]; then
    echo "error: LeRobot needs Python 3.12 or later; none found (python3.12, python3.13 or pyenv's)" >&2
    exit 1
  fi
  "$python" -m venv "$venv" >&2
fi
if ! "$venv/bin/python" -c "import lerobot, pytest, datasets, torch, stable_baselines3" 2>/dev/null; then
  echo "setup: installing LeRobot 0.6.1 (with PyTorch), Stable-Baselines3 and pytest into $venv" >&2
  "$venv/bin/pip" install -q --disable-pip-version-check "lerobot[dataset,training]==0.6.1" \
    "stable-baselines3==2.9.2" "pytest==8.4.2" >&2
fi
echo "$venv/bin/python"
