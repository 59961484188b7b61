#!/usr/bin/env bash
# Reinforcement learning, measured (yarok-py/benches/reinforcement.py): Stable-Baselines3's PPO
# on yarok/TactilePress-v0 through yarok.for_learners, the success rate on held-out seeds as it
# learns. Uses the venv of scripts/setup-lerobot.sh (Stable-Baselines3 and PyTorch beside
# LeRobot), builds yarok's package into it, and runs the benchmark with the arguments given
# (--steps N --every N --episodes N --min-success R).
set -euo pipefail
cd "$(dirname "$0")/.."
python="$(bash scripts/setup-lerobot.sh)"
"$(dirname "$python")/pip" install -q --disable-pip-version-check --force-reinstall --no-deps ./yarok-py
exec python3 scripts/results.py reinforcement "$python" yarok-py/benches/reinforcement.py "$@"
