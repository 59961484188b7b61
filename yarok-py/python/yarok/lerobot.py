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
