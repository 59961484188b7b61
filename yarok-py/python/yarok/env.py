"""YarokEnv: a yarok world as a Gymnasium environment, with a Task giving its reward, success
and randomised start."""

from __future__ import annotations

import atexit
import importlib
import signal
import threading
import time
import weakref
from dataclasses import dataclass
from types import ModuleType
from typing import Any, Sequence

import gymnasium
import numpy as np

from ._native import YarokError


@dataclass
class Task:
    """What makes a world an environment: which world, how each episode starts, the reward and
    when it is won. Subclass it and override what your task needs.

    ``placements(rng)`` returns the free bodies to put somewhere when an episode begins,
    ``[(body, (x, y, z), (qw, qx, qy, qz)), ...]`` (body names as in
    ``World.environment_names``, without the ``/x`` suffix); draw from ``rng`` only, so that a
    seed gives the same start every time.

    ``world`` is a bundled world's tag, a template file's path, or a world of your own crate's
    extension module (built with ``yarok_py::module!``), whose import name is ``extension``.
    """

    world: str = "digit_world"
    description: str = ""
    settings: Sequence[str] = ()
    cameras: Sequence[str] = ()
    camera_size: tuple[int, int] = (84, 84)
    control_hz: float = 20.0
    render_camera: str | None = None
    extension: str = "yarok._native"

    def bind(self, features) -> None:
        """Called once the world has started, with its ``features`` (names of the state,
        environment state and action): where a task finds the indices it reads."""

    def placements(self, rng: np.random.Generator) -> list[tuple[str, tuple, tuple]]:
        return []

    def reward(self, observation: dict[str, np.ndarray], action: np.ndarray) -> float:
        return 0.0

    def success(self, observation: dict[str, np.ndarray]) -> bool:
        return False

    def action_bounds(self, low: np.ndarray, high: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The bounds of the task's actions, given the world's ranges ``low`` and ``high``
        (float64, one per number of the action): the whole ranges by default. A task whose work
        is in one place narrows them to its workspace (as a rig keeps a printer's head over the
        sensor); actions beyond the bounds are clipped to them. They must lie within the
        world's ranges."""
        return low, high

    def goal_spaces(self) -> dict[str, gymnasium.spaces.Box]:
        """Observations the task adds to the world's (a goal-conditioned task's goal), by key:
        ``observation.desired_goal`` and ``observation.achieved_goal`` by Gymnasium-Robotics'
        convention. None by default."""
        return {}

    def goals(self, observation: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        """The values of ``goal_spaces()``' keys for ``observation``: called on every
        observation, the reset's first, after ``placements``."""
        return {}


def observation_space(world) -> gymnasium.spaces.Dict:
    """The observation space of a world's ``features``: the LeRobot dataset's features, same keys and shapes."""
    spaces: dict[str, gymnasium.spaces.Space] = {
        "observation.state": gymnasium.spaces.Box(
            -np.inf, np.inf, (len(world.state_names),), np.float32
        ),
        "observation.environment_state": gymnasium.spaces.Box(
            -np.inf, np.inf, (len(world.environment_names),), np.float32
        ),
    }
    for key, shape in world.images:
        spaces[key] = gymnasium.spaces.Box(0, 255, shape, np.uint8)
    return gymnasium.spaces.Dict(spaces)


def native(task: Task) -> ModuleType:
    """The extension module that opens ``task``'s world: yarok's own, or your crate's."""
    return importlib.import_module(task.extension)


def action_ranges(world, task: Task) -> np.ndarray:
    """The ranges of ``task``'s actions in a world (its ``features``), lowest and highest per
    number (float64): the world's, narrowed by ``Task.action_bounds``."""
    world_ranges = np.array(world.action_ranges, dtype=np.float64).reshape(-1, 2)
    low, high = (
        np.asarray(bound, dtype=np.float64)
        for bound in task.action_bounds(world_ranges[:, 0].copy(), world_ranges[:, 1].copy())
    )
    if low.shape != world_ranges[:, 0].shape or high.shape != low.shape:
        raise ValueError(
            f"{type(task).__name__}.action_bounds gave bounds of shapes {low.shape} and "
            f"{high.shape}; the action has {len(world_ranges)} numbers ({world.action_names})"
        )
    outside = (low < world_ranges[:, 0]) | (high > world_ranges[:, 1]) | (low > high)
    if outside.any():
        names = [name for name, out in zip(world.action_names, outside) if out]
        raise ValueError(
            f"{type(task).__name__}.action_bounds: the bounds of {names} are not an interval "
            f"within the world's ranges {world_ranges[outside].tolist()}"
        )
    return np.stack([low, high], axis=1)


def action_space(ranges: np.ndarray) -> gymnasium.spaces.Box:
    """The action space of action ``ranges`` (``action_ranges``): the numbers within them, as
    float32 bounds that lie inside them (a bound rounded to float32 can fall just outside a
    float64 limit, as 2π does), so that every action in the space is taken."""
    low = ranges[:, 0].astype(np.float32)
    high = ranges[:, 1].astype(np.float32)
    low = np.where(low.astype(np.float64) < ranges[:, 0], np.nextafter(low, np.float32(np.inf)), low)
    high = np.where(
        high.astype(np.float64) > ranges[:, 1], np.nextafter(high, np.float32(-np.inf)), high
    )
    return gymnasium.spaces.Box(low, high, dtype=np.float32)


class YarokEnv(gymnasium.Env):
    """A yarok world as a Gymnasium environment.

    Observations are the world's LeRobot features (``observation.state``,
    ``observation.environment_state``, ``observation.images.*``), the action its ``action``
    (each component's targets: an arm's joints in radians, a gripper's position 0-255), so a
    policy trained on a dataset ``yarok run WORLD --dataset DIR`` wrote takes them unchanged.
    Each step sets the action (clipped to the action space's bounds: the world's ranges, or
    the task's workspace within them; any action is taken, the bounds and beyond) and advances ``1 / control_hz`` seconds of platform time; a step
    in which MuJoCo warned (an unstable state it reset, a full contact buffer) ends the episode
    truncated, with ``info["warnings"]`` saying what. ``reset(seed=s)`` puts the world back to
    its start and places the task's bodies as drawn from ``s``: the same seed, the same
    episode, bit for bit.

    ``env="real"`` drives the real robot through yarok's drivers with the same actions;
    ``close()`` stops it (devices left safe), as do an exception, Ctrl-C, SIGTERM and SIGHUP
    (raised as ``SystemExit`` where the program set no handler of its own) and the end of the
    program. A safety stop of the arm raises ``YarokError`` naming it at the next ``step``.
    The robot does not wait for the policy: the real world goes on between steps, each step
    ends one control period after the last one ended, and a step that comes after its period
    ended says how late in ``info["late_seconds"]`` (the arm held its last target meanwhile;
    the observation is the newest measured), raising ``YarokError`` beyond
    ``max_late_seconds`` when that is given.
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 20}

    def __init__(
        self,
        task: Task | None = None,
        env: str = "sim",
        settings: Sequence[str] = (),
        config: Sequence[str] = (),
        render_mode: str | None = None,
        max_late_seconds: float | None = None,
    ):
        self.task = task if task is not None else Task()
        cameras = list(self.task.cameras)
        if render_mode == "rgb_array" and self.task.render_camera not in (None, *cameras):
            cameras.append(self.task.render_camera)
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode {render_mode!r}: yarok renders 'rgb_array' only")
        self.render_mode = render_mode
        self.environment = env
        if env == "real":
            _stop_on_termination()
        self.world = native(self.task).World(
            self.task.world,
            env=env,
            settings=[*self.task.settings, *settings],
            config=list(config),
            cameras=cameras,
            camera_size=tuple(self.task.camera_size),
        )
        if env == "real":
            _REAL_ENVS.add(self)
        self.task.bind(self.world.features)
        spaces = observation_space(self.world.features).spaces
        if self.task.render_camera is not None and self.task.render_camera not in self.task.cameras:
            spaces.pop(f"observation.images.{self.task.render_camera}", None)
        spaces.update(self.task.goal_spaces())
        self.observation_space = gymnasium.spaces.Dict(spaces)
        self._observed_keys = set(spaces)
        # Read once: each read of `World.features` copies every name.
        features = self.world.features
        ranges = action_ranges(features, self.task)
        self.action_space = action_space(ranges)
        self._timestep = features.timestep
        self._low, self._high = ranges[:, 0], ranges[:, 1]
        self.metadata = {**self.metadata, "render_fps": self.task.control_hz}
        self._episodes = 0
        self._start_tick = 0
        self._max_late = max_late_seconds
        self._stepped_at = time.monotonic()
        self._last: dict[str, np.ndarray] | None = None

    def _keep(self, observation: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        self._last = observation
        kept = {key: value for key, value in observation.items() if key in self._observed_keys}
        kept.update(self.task.goals(observation))
        return kept

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        placements = self.task.placements(self.np_random)
        if self.environment != "sim":
            # Outside `sim` nothing moves a body by itself: the objects are where they are.
            placements = []
        observation = self.world.reset(self._episodes, placements)
        self._stepped_at = time.monotonic()
        self._episodes += 1
        self._start_tick = self.world.ticks
        return self._keep(observation), {"time": 0.0}

    def step(self, action):
        action = np.clip(np.asarray(action, dtype=np.float64), self._low, self._high)
        period = 1.0 / self.task.control_hz
        late = 0.0
        if self.environment != "sim":
            # The robot does not wait while the policy thinks: a real world goes on between
            # steps, a step ends a period after the last one did (the control rate kept), and
            # a step that comes after its period ended is late.
            late = time.monotonic() - self._stepped_at - period
            if self._max_late is not None and late > self._max_late:
                raise YarokError(
                    f"the step came {late:.3f} s after its control period ({period} s) ended, "
                    f"over max_late_seconds={self._max_late}: the robot held its last target"
                )
        observation = self.world.advance(period, action.tolist())
        self._stepped_at = time.monotonic()
        reward = float(self.task.reward(observation, action))
        success = bool(self.task.success(observation))
        elapsed = (self.world.ticks - self._start_tick) * self._timestep
        info = {"is_success": success, "time": elapsed}
        # MuJoCo went wrong in the step (an unstable state it reset, a full contact buffer):
        # the episode ends there, truncated, and says why, rather than going on from a world
        # that moved without a cause.
        warnings = self.world.warnings
        if warnings:
            info["warnings"] = warnings
        if late > 0.0:
            info["late_seconds"] = late
        return self._keep(observation), reward, success, bool(warnings), info

    @property
    def task_description(self) -> str:
        """What the task asks, in words (the dataset's task; LeRobot's evaluation reads it)."""
        return self.task.description

    def render(self):
        if self.render_mode != "rgb_array" or self._last is None:
            return None
        key = _render_key(self.task, self._last)
        return None if key is None else self._last[key]

    def close(self):
        if getattr(self, "world", None) is not None:
            self.world.close()


def _render_key(task: Task, observation: dict[str, np.ndarray]) -> str | None:
    if task.render_camera is not None:
        return f"observation.images.{task.render_camera}"
    images = [key for key in observation if key.startswith("observation.images.")]
    return images[0] if images else None


_REAL_ENVS: "weakref.WeakSet[YarokEnv]" = weakref.WeakSet()


@atexit.register
def _close_real_envs() -> None:
    """A run that ends with a real environment open stops its devices (the arm's ``stopj``)."""
    for env in list(_REAL_ENVS):
        try:
            env.close()
        except Exception:  # noqa: BLE001 - closing the others matters more at exit
            pass


def _terminate(signum, _frame) -> None:
    raise SystemExit(128 + signum)


def _stop_on_termination() -> None:
    """SIGTERM and SIGHUP end a run that drives real hardware as Ctrl-C does, as the command
    line's ``yarok run`` does: raised in Python (``SystemExit``), so that a world waited on
    stops its devices and the open environments are closed. A handler the program set itself
    is left as it is."""
    if threading.current_thread() is not threading.main_thread():
        return
    for signum in (signal.SIGTERM, signal.SIGHUP):
        if signal.getsignal(signum) is signal.SIG_DFL:
            signal.signal(signum, _terminate)
