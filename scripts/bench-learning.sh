#!/usr/bin/env bash
# A success rate, measured (yarok-py/benches/learning.py): demonstrations recorded by yarok,
# LeRobot's training and evaluation unchanged, on held-out seeds of yarok/PickPlace-v0. Uses the
# LeRobot venv of scripts/setup-lerobot.sh, builds yarok's package into it, and runs the
# benchmark with the arguments given (--demos N --steps N --episodes N --out DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
python="$(bash scripts/setup-lerobot.sh)"
"$(dirname "$python")/pip" install -q --disable-pip-version-check --force-reinstall --no-deps ./yarok-py
exec python3 scripts/results.py learning "$python" yarok-py/benches/learning.py "$@"
