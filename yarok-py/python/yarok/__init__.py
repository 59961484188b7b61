"""yarok from Python: worlds composed from reusable MJCF components, simulated in MuJoCo (or
driven on real hardware) by yarok's Rust runtime, as Gymnasium environments.

>>> import yarok
>>> world = yarok.World("digit_world")                   # a bundled world, in `sim`
>>> observation = world.reset(episode=0)                 # dict of numpy arrays
>>> observation = world.advance(0.05, action=None)       # 50 ms of platform time
>>> world.close()
>>> yarok.run("digit_world", "demonstrate", settings=["behaviour/episodes=20"],
...           dataset="demos")                          # demonstrations, as a LeRobot dataset

Gymnasium environments are registered as ``yarok/PickPlace-v0`` and ``yarok/TactilePress-v0``;
``yarok.YarokEnv`` makes any world an environment with your own task (reward, success, reset),
and ``yarok.YarokVectorEnv`` steps N copies on N Rust threads; ``yarok.for_learners(env)``
keys an environment's observations as Stable-Baselines3 and CleanRL-style loops take them.
"""

import os

from ._native import (
    UR_JOINT_SPEED,
    World,
    Worlds,
    YarokError,
    after_fork_in_child,
    run,
    use_bundled_mujoco,
)
from .env import Task, YarokEnv
from .vector import YarokVectorEnv
from .wrappers import LearnerKeys, for_learners
from . import tasks
from .registration import register_environments

__all__ = [
    "LearnerKeys",
    "Task",
    "UR_JOINT_SPEED",
    "World",
    "Worlds",
    "YarokEnv",
    "YarokError",
    "YarokVectorEnv",
    "for_learners",
    "register_environments",
    "run",
    "tasks",
]

# A wheel built by scripts/build-wheel.sh carries MuJoCo in the package: found there, so that
# it runs on machines where yarok was never built.
_BUNDLED_MUJOCO = os.path.join(os.path.dirname(__file__), "mujoco")
if os.path.isdir(_BUNDLED_MUJOCO):
    use_bundled_mujoco(_BUNDLED_MUJOCO)
register_environments()
os.register_at_fork(after_in_child=after_fork_in_child)
