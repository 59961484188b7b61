"""yarok's environments for reinforcement-learning libraries.

yarok keys its observations as LeRobot's datasets do (``observation.state``,
``observation.images.arm.gripper.left_digit.image``). Stable-Baselines3's ``MultiInputPolicy``
refuses dotted keys (PyTorch module names), and a feature with no numbers (a world with no free
body has an empty ``observation.environment_state``) breaks learners that stack or normalise
it. ``for_learners`` gives an environment keys they take::

    import gymnasium, yarok
    from stable_baselines3 import PPO

    env = yarok.for_learners(gymnasium.make("yarok/TactilePress-v0"), images=False)
    PPO("MultiInputPolicy", env).learn(10_000)

Its actions are each number of the environment's action rescaled to [-1, 1]. With
``gymnasium.wrappers.FlattenObservation`` after it, one flat vector for CleanRL-style
loops (``RecordEpisodeStatistics``, ``NormalizeObservation``, ``ClipAction`` apply unchanged).
"""

from __future__ import annotations

import gymnasium
import numpy as np

PREFIX = "observation."


def learner_key(key: str) -> str:
    """``observation.images.arm.left_digit.image`` → ``images_arm_left_digit_image``."""
    return key.removeprefix(PREFIX).replace(".", "_")


class LearnerKeys(gymnasium.ObservationWrapper):
    """An environment's observations without dots in their keys (``observation.`` dropped, the
    other dots as ``_``), without the features that hold no number, and without the images
    when ``images`` is false."""

    def __init__(self, env: gymnasium.Env, images: bool = True):
        super().__init__(env)
        self._keys: dict[str, str] = {}
        spaces: dict[str, gymnasium.spaces.Space] = {}
        for key, space in env.observation_space.spaces.items():
            if int(np.prod(space.shape)) == 0:
                continue
            if not images and key.startswith(PREFIX + "images."):
                continue
            self._keys[key] = learner_key(key)
            spaces[self._keys[key]] = space
        if len(set(spaces)) != len(self._keys):
            raise ValueError(f"two observation keys become one: {sorted(self._keys)}")
        self.observation_space = gymnasium.spaces.Dict(spaces)

    def observation(self, observation: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        return {renamed: observation[key] for key, renamed in self._keys.items()}


def for_learners(
    env: gymnasium.Env, images: bool = True, rescale_actions: bool = True
) -> gymnasium.Env:
    """``env`` keyed for reinforcement-learning libraries (see ``LearnerKeys``), its actions
    rescaled to [-1, 1] per number (Gymnasium's ``RescaleAction``: the bounds of the action space
    map to -1 and 1), as Stable-Baselines3's and CleanRL's Gaussian policies expect; with
    ``rescale_actions=False`` the action is the environment's own."""
    keyed = LearnerKeys(env, images=images)
    if not rescale_actions:
        return keyed
    # float32 bounds: float64 ones make Gymnasium warn of precision lost to the float32 space.
    one = np.ones(keyed.action_space.shape, dtype=np.float32)
    return gymnasium.wrappers.RescaleAction(keyed, -one, one)
