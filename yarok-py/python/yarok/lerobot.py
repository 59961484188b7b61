"""yarok's environments in LeRobot's evaluation loop.

LeRobot's ``lerobot.scripts.lerobot_eval.eval_policy`` takes a Gymnasium vector environment
whose observations are keyed as LeRobot's simulation environments key them (``pixels``,
``agent_pos``, ``environment_state``) and turns them into a policy's features with its own
``preprocess_observation``. ``LeRobotKeys`` gives a yarok environment those keys, so that the
features LeRobot makes are exactly those of the dataset the policy was trained on::

    import gymnasium, yarok.lerobot
    from lerobot.scripts.lerobot_eval import eval_policy

    env = yarok.lerobot.make_vector_env("yarok/PickPlace-v0", n_envs=1)
    results = eval_policy(env, policy, identity, identity, preprocessor, postprocessor,
                          n_episodes=10, start_seed=1000)

Nothing here imports LeRobot: install it beside yarok (``pip install 'lerobot[dataset]'``,
Python 3.12 or later) to use it.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import gymnasium
import numpy as np

IMAGES = "observation.images."


class LeRobotKeys(gymnasium.ObservationWrapper):
    """A yarok environment's observations keyed as LeRobot's evaluation reads them:
    ``observation.images.K`` as ``pixels[K]``, ``observation.state`` as ``agent_pos`` and
    ``observation.environment_state`` as ``environment_state``. LeRobot's
    ``preprocess_observation`` maps them back to the dataset's keys."""

    def __init__(self, env: gymnasium.Env):
        super().__init__(env)
        spaces = env.observation_space.spaces
        pixels = {
            key.removeprefix(IMAGES): space
            for key, space in spaces.items()
            if key.startswith(IMAGES)
        }
        keyed: dict[str, gymnasium.spaces.Space] = {}
        if pixels:
            keyed["pixels"] = gymnasium.spaces.Dict(pixels)
        keyed["agent_pos"] = spaces["observation.state"]
        if "observation.environment_state" in spaces:
            keyed["environment_state"] = spaces["observation.environment_state"]
        self.observation_space = gymnasium.spaces.Dict(keyed)

    def observation(self, observation: dict[str, np.ndarray]) -> dict[str, Any]:
        keyed: dict[str, Any] = {}
        pixels = {
            key.removeprefix(IMAGES): value
            for key, value in observation.items()
            if key.startswith(IMAGES)
        }
        if pixels:
            keyed["pixels"] = pixels
        keyed["agent_pos"] = observation["observation.state"]
        if "observation.environment_state" in observation:
            keyed["environment_state"] = observation["observation.environment_state"]
        return keyed


def make_vector_env(env_id: str, n_envs: int = 1, **kwargs) -> gymnasium.vector.SyncVectorEnv:
    """``n_envs`` environments ``env_id`` (``gymnasium.make`` with ``kwargs``), keyed by
    ``LeRobotKeys``, as the vector environment LeRobot's ``eval_policy`` takes: it reads each
    one's ``task_description`` and ``_max_episode_steps`` and the ``is_success`` of its infos."""
    return gymnasium.vector.SyncVectorEnv(
        [lambda: LeRobotKeys(gymnasium.make(env_id, **kwargs)) for _ in range(n_envs)]
    )


STATE_FEATURES = ("observation.state", "observation.environment_state")

ACT_ON_A_CPU = [
    "--policy.type=act",
    "--policy.device=cpu",
    "--policy.push_to_hub=false",
    "--policy.chunk_size=20",
    "--policy.n_action_steps=20",
    "--policy.dim_model=128",
    "--policy.dim_feedforward=512",
    "--policy.n_encoder_layers=2",
    "--policy.n_decoder_layers=1",
    "--policy.use_vae=false",
    "--policy.optimizer_lr=3e-4",
    "--batch_size=64",
    "--num_workers=2",
    "--wandb.enable=false",
]
"""``lerobot-train`` arguments for ACT on yarok's state features within a CPU budget of
thousands of steps: chunks of 20 actions (one second at 20 Hz) executed whole, 128 wide, no
VAE, and a learning rate of 3e-4 (ACT's default, 1e-5, is for 100 000 steps on a GPU: within
thousands it stays far from fitting). Two loader processes beside the training one: loading
action chunks takes longer than a training step (600 steps took 109 s with two, 157 s with
one, on 2 cores)."""


def floor_state_spreads(dataset_root: str | os.PathLike[str], floor: float = 0.01) -> None:
    """Floors the standard deviations of a recorded dataset's state features
    (``meta/stats.json``), which LeRobot normalises a policy's inputs by, at ``floor`` (metres,
    radians). Blocks a task does not move rest where they start, and some joints hardly turn:
    their spreads over the demonstrations are micrometres, and normalising by them would blow a
    settling of a few micrometres up to tens of deviations — inputs the policy never saw."""
    stats_file = Path(dataset_root) / "meta" / "stats.json"
    stats = json.loads(stats_file.read_text())
    for key in STATE_FEATURES:
        if key in stats:
            stats[key]["std"] = [max(spread, floor) for spread in stats[key]["std"]]
    stats_file.write_text(json.dumps(stats, indent=2))
