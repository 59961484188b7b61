"""The registered tasks: a pick-and-place in DigitWorld and a press on the tactile rig."""

from __future__ import annotations

import math
from dataclasses import dataclass

import gymnasium
import numpy as np

from ._native import DIGIT_WORLD_START_REGION, DIGIT_WORLD_START_YAW
from .env import Task

TABLE_HEIGHT = 0.4
"""The table top's height in PickAndPlaceWorld and DigitWorld (metres, world frame)."""

GRIPPER_OPEN = 10
"""Below this measured position (of 0 open … 255 closed) the gripper counts as open."""


def _yaw(angle: float) -> tuple[float, float, float, float]:
    return (float(np.cos(angle / 2)), 0.0, 0.0, float(np.sin(angle / 2)))


def _pose(observation: dict[str, np.ndarray], index: int) -> np.ndarray:
    """The position of the free body whose pose starts at ``index`` in the environment state."""
    return observation["observation.environment_state"][index : index + 3]


TARGET_SPOT_RADIUS = 0.05
"""The radius (metres) of DigitWorld's target spot, the disc the block is put on."""


@dataclass
class PickPlace(Task):
    """DigitWorld: put the medium block (3.5 cm) on the target spot. Won when the block rests
    wholly on the spot (a disc of 5 cm radius) with the gripper open: its centre within
    ``tolerance`` of the spot's, by default the radius less the block's half diagonal (2.5 cm),
    so that no corner overhangs the disc whatever the block's yaw. Each episode starts with the
    block at a place and yaw drawn from the seed, within the arm's reach and clear of the other
    blocks: the region ``yarok.run("digit_world", "demonstrate")`` draws its demonstrations'
    starts from.

    The reward is dense: minus the block's distance to the target (metres), plus 1 when won.
    """

    world: str = "digit_world"
    description: str = "pick up the block and put it on the target"
    target: tuple[float, float] = (0.42, 0.38)
    block: str = "medium"
    block_size: float = 0.035
    region: tuple[tuple[float, float], tuple[float, float]] = tuple(
        tuple(bounds) for bounds in DIGIT_WORLD_START_REGION
    )
    max_yaw: float = DIGIT_WORLD_START_YAW
    tolerance: float | None = None
    render_camera: str | None = "overview"

    def __post_init__(self):
        if self.tolerance is None:
            self.tolerance = TARGET_SPOT_RADIUS - self.block_size * math.sqrt(2) / 2

    def bind(self, features) -> None:
        names = features.environment_names
        # On hardware nothing measures the block: no reward, never won (the time limit ends
        # each episode).
        block = f"{self.block}/block/x"
        self.block_index = names.index(block) if block in names else None
        self.gripper_index = features.state_names.index("arm/gripper/position")

    def placements(self, rng):
        (x_low, x_high), (y_low, y_high) = self.region
        position = (
            float(rng.uniform(x_low, x_high)),
            float(rng.uniform(y_low, y_high)),
            TABLE_HEIGHT + self.block_size / 2,
        )
        yaw = _yaw(float(rng.uniform(-self.max_yaw, self.max_yaw)))
        return [(f"{self.block}/block", position, yaw)]

    def distance(self, observation) -> float:
        # Python floats: numpy's scalar arithmetic costs more than the step's own Python.
        x, y, _ = _pose(observation, self.block_index).tolist()
        return math.hypot(x - self.target[0], y - self.target[1])

    def success(self, observation) -> bool:
        if self.block_index is None:
            return False
        x, y, z = _pose(observation, self.block_index).tolist()
        resting = abs(z - (TABLE_HEIGHT + self.block_size / 2)) < 0.003
        # The gripper's measured position, 0 (open) to 255 (closed).
        gripper_open = float(observation["observation.state"][self.gripper_index]) < GRIPPER_OPEN
        near = math.hypot(x - self.target[0], y - self.target[1]) < self.tolerance
        return near and resting and gripper_open

    def reward(self, observation, action) -> float:
        if self.block_index is None:
            return 0.0
        return -self.distance(observation) + (1.0 if self.success(observation) else 0.0)


DIGIT_GEL_CENTRE_MM = (160.0, 160.0, 18.0)
"""Where the tactile rig's DIGIT gel is, in the printer's coordinates (millimetres): the middle of
its face (the rig's ``sensor_pos``) and the height of the untouched gel's surface there."""


@dataclass
class TactilePress(Task):
    """The tactile rig with a DIGIT: press the indenter into the gel until the sensor's image
    changes by a target amount (mean absolute change of its pixels from the first frame of the
    episode, in grey levels), drawn from the seed between 2 and 6. The action is the printer
    head's target (millimetres) within the task's workspace over the gel's middle: ``x`` and
    ``y`` within ``reach`` of it, ``z`` from ``above`` over the gel's surface to ``below`` it
    (the head moves there from home in the episode's first steps). Won when the change has
    stayed within 0.5 of the target for ``hold_steps`` steps in a row (a press held, not one
    passed through on the way down).

    Goal-conditioned: the observation holds the target as ``observation.desired_goal`` and the
    change now as ``observation.achieved_goal`` (one number each, grey levels), so that one
    policy learns every target.
    """

    world: str = "tactile_rig_world"
    description: str = "press the indenter until the sensor's image changes by the target"
    settings: tuple[str, ...] = ('sensor="digit"',)
    control_hz: float = 20.0
    tolerance: float = 0.5
    reach: float = 1.0
    above: float = 2.0
    below: float = 2.0
    hold_steps: int = 5

    def action_bounds(self, low, high):
        x, y, surface = DIGIT_GEL_CENTRE_MM
        return (
            np.array([x - self.reach, y - self.reach, surface - self.below]),
            np.array([x + self.reach, y + self.reach, surface + self.above]),
        )

    def __post_init__(self):
        self.target = 4.0
        self._reference: np.ndarray | None = None
        self._held = 0

    def placements(self, rng):
        self.target = float(rng.uniform(2.0, 6.0))
        self._reference = None
        self._held = 0
        return []

    def change(self, observation) -> float:
        image = observation["observation.images.sensor.image"].astype(np.float32)
        if self._reference is None:
            self._reference = image
        return float(np.abs(image - self._reference).mean())

    def reward(self, observation, action) -> float:
        return -abs(self.change(observation) - self.target)

    def success(self, observation) -> bool:
        # Called once a step (by the environment, after the reward): counts the steps held.
        within = abs(self.change(observation) - self.target) < self.tolerance
        self._held = self._held + 1 if within else 0
        return self._held >= self.hold_steps

    def goal_spaces(self):
        change = gymnasium.spaces.Box(0.0, 255.0, (1,), np.float32)
        return {"observation.desired_goal": change, "observation.achieved_goal": change}

    def goals(self, observation):
        return {
            "observation.desired_goal": np.array([self.target], dtype=np.float32),
            "observation.achieved_goal": np.array([self.change(observation)], dtype=np.float32),
        }
