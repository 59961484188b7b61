"""Run by scripts/test.sh in a fresh venv where the wheel of scripts/build-wheel.sh was installed,
with HOME an empty folder and no Rust on PATH: yarok runs a world with tactile images on MuJoCo
from inside the installed package, not from the machine's yarok cache or build."""

import os
import shutil

import gymnasium
import numpy as np

import yarok

assert shutil.which("cargo") is None, "cargo is on PATH: this is not a machine without Rust"
package = os.path.dirname(yarok.__file__)
env = gymnasium.make("yarok/PickPlace-v0")
observation, _ = env.reset(seed=0)
for _ in range(10):
    observation, *_ = env.step(env.action_space.sample())
images = [key for key in observation if key.startswith("observation.images.")]
assert len(images) == 2, images
for key in images:
    image = observation[key]
    assert image.dtype == np.uint8 and image.ndim == 3 and image.std() > 0, key
with open("/proc/self/maps") as maps:
    mujoco = {line.split()[-1] for line in maps if "libmujoco" in line}
env.close()
assert mujoco and all(path.startswith(package) for path in mujoco), (mujoco, package)
print(f"ran yarok/PickPlace-v0 for 10 steps with {len(images)} tactile images, MuJoCo from {mujoco.pop()}")
