"""YarokVectorEnv: N copies of a task's world, each on its own Rust thread, stepped at once."""

from __future__ import annotations

import copy
from typing import Any, Sequence

import gymnasium
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from .env import Task, action_ranges, action_space, native, observation_space


class YarokVectorEnv(VectorEnv):
    """``num_envs`` copies of ``task``'s world stepped in parallel: every step sends each world
    its action and waits for all without the GIL, so N worlds use N cores. Observations and
    actions are the single environment's, stacked along a first axis. Episodes restart as
    Gymnasium 1.x's default (next-step autoreset): the step after an episode ends resets that
    world and returns its first observation, with reward 0 and not done.
    """

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(
        self,
        task: Task,
        num_envs: int,
        env: str = "sim",
        settings: Sequence[str] = (),
        config: Sequence[str] = (),
        max_episode_steps: int | None = None,
    ):
        self.num_envs = num_envs
        self.tasks = [copy.deepcopy(task) for _ in range(num_envs)]
        self.worlds = native(task).Worlds(
            task.world,
            num_envs,
            env=env,
            settings=[*task.settings, *settings],
            config=list(config),
            cameras=list(task.cameras),
            camera_size=tuple(task.camera_size),
        )
        for each in self.tasks:
            each.bind(self.worlds.features)
        spaces = observation_space(self.worlds.features).spaces
        spaces.update(task.goal_spaces())
        self.single_observation_space = gymnasium.spaces.Dict(spaces)
        ranges = action_ranges(self.worlds.features, task)
        self.single_action_space = action_space(ranges)
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)
        self._low, self._high = ranges[:, 0], ranges[:, 1]
        self.max_episode_steps = max_episode_steps
        self._episodes = 0
        self._steps = np.zeros(num_envs, dtype=np.int64)
        self._needs_reset = np.zeros(num_envs, dtype=bool)
        self._rngs: list[np.random.Generator] = [np.random.default_rng() for _ in range(num_envs)]

    def _stack(self, observations: list[dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
        for task, observation in zip(self.tasks, observations):
            observation.update(task.goals(observation))
        return {
            key: np.stack([observation[key] for observation in observations])
            for key in self.single_observation_space.spaces
        }

    def _reset_requests(self, indices):
        requests = []
        for index in indices:
            placements = self.tasks[index].placements(self._rngs[index])
            requests.append((int(index), self._episodes, placements))
            self._episodes += 1
            self._steps[index] = 0
        return requests

    def reset(self, *, seed: int | Sequence[int] | None = None, options: dict[str, Any] | None = None):
        if seed is not None:
            seeds = [seed + i for i in range(self.num_envs)] if isinstance(seed, int) else list(seed)
            self._rngs = [np.random.default_rng(s) for s in seeds]
        observations = self.worlds.reset(self._reset_requests(range(self.num_envs)))
        self._needs_reset[:] = False
        return self._stack(observations), {}

    def step(self, actions):
        actions = np.clip(np.asarray(actions, dtype=np.float64), self._low, self._high)
        resetting = np.flatnonzero(self._needs_reset)
        seconds = 1.0 / self.tasks[0].control_hz
        stepped = self.worlds.advance(
            seconds,
            [None if self._needs_reset[i] else actions[i].tolist() for i in range(self.num_envs)],
        )
        if len(resetting):
            for index, observation in zip(
                resetting, self.worlds.reset(self._reset_requests(resetting))
            ):
                stepped[index] = observation
        rewards = np.zeros(self.num_envs)
        terminated = np.zeros(self.num_envs, dtype=bool)
        truncated = np.zeros(self.num_envs, dtype=bool)
        successes = np.zeros(self.num_envs, dtype=bool)
        warnings = self.worlds.warnings
        for index in range(self.num_envs):
            if self._needs_reset[index]:
                continue
            # MuJoCo went wrong in the step: that world's episode ends there, truncated.
            if warnings[index]:
                truncated[index] = True
            task, observation = self.tasks[index], stepped[index]
            self._steps[index] += 1
            rewards[index] = task.reward(observation, actions[index])
            successes[index] = terminated[index] = task.success(observation)
            truncated[index] |= (
                self.max_episode_steps is not None and self._steps[index] >= self.max_episode_steps
            )
        stepped_now = ~self._needs_reset
        self._needs_reset = terminated | truncated
        # Gymnasium's vector infos: each key beside its `_key` mask of the worlds that set it
        # (a world that was reset this step reports nothing).
        infos = {"is_success": successes, "_is_success": stepped_now}
        return self._stack(stepped), rewards, terminated, truncated, infos

    def close_extras(self, **kwargs):
        self.worlds.close()
