"""Reinforcement learning out of the box: Stable-Baselines3's own environment checker and PPO
updates through ``yarok.for_learners`` for each registered environment, PPO learning
TactilePress (the reinforcement benchmark's short run), and PyTorch training in the same
process as a rendering yarok world, in either import order.

Stable-Baselines3 and PyTorch are installed by ``scripts/setup-lerobot.sh`` beside LeRobot;
where they are missing these tests are skipped, unless ``YAROK_REQUIRE_LEROBOT=1`` (as
``scripts/test.sh`` runs them), which makes their absence a failure.
"""

import os
import subprocess
import sys

import pytest

if os.environ.get("YAROK_REQUIRE_LEROBOT") != "1":
    pytest.importorskip("stable_baselines3")

import gymnasium  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.env_checker import check_env  # noqa: E402

import yarok  # noqa: E402
from yarok.registration import ENVIRONMENTS  # noqa: E402


@pytest.mark.parametrize("env_id", sorted(ENVIRONMENTS))
def test_stable_baselines3_checks_and_trains_ppo_through_for_learners(env_id):
    env = yarok.for_learners(gymnasium.make(env_id), images=False)
    try:
        check_env(env, warn=True)
        model = PPO("MultiInputPolicy", env, n_steps=32, batch_size=16, n_epochs=2, device="cpu")
        before = [parameter.detach().clone() for parameter in model.policy.parameters()]
        model.learn(total_timesteps=64)
        assert model.num_timesteps == 64
        after = list(model.policy.parameters())
        assert any((a != b).any() for a, b in zip(after, before)), "PPO updated nothing"
    finally:
        env.close()


TRAIN_BESIDE_A_WORLD = """
import sys
order = sys.argv[1]
if order == "torch first":
    import torch
import gymnasium, numpy as np, yarok
env = gymnasium.make("yarok/TactilePress-v0")
observation, _ = env.reset(seed=0)
for _ in range(3):
    observation, *_ = env.step(env.action_space.sample())
image = observation["observation.images.sensor.image"]
assert image.std() > 0, "the DIGIT rendered nothing"
import torch
net = torch.nn.Sequential(torch.nn.Linear(3, 16), torch.nn.ReLU(), torch.nn.Linear(16, 1))
optimizer = torch.optim.Adam(net.parameters(), lr=1e-3)
features = torch.tensor(image.reshape(-1, 3)[:256], dtype=torch.float32) / 255
loss = net(features).square().mean()
loss.backward()
optimizer.step()
observation, *_ = env.step(env.action_space.sample())
env.close()
print("trained", float(loss))
"""


@pytest.mark.parametrize("order", ["yarok first", "torch first"])
def test_pytorch_trains_beside_a_rendering_world(order):
    done = subprocess.run(
        [sys.executable, "-c", TRAIN_BESIDE_A_WORLD, order],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, (done.returncode, done.stdout[-2000:], done.stderr[-4000:])
    assert done.stdout.startswith("trained"), done.stdout


def test_ppo_learns_to_press_as_the_reinforcement_benchmark_measures():
    """The CI version of ``scripts/bench-reinforcement.sh``: a short PPO run through
    ``yarok.for_learners`` wins most held-out presses, where the untrained policy wins none."""
    bench = os.path.join(os.path.dirname(__file__), "..", "benches", "reinforcement.py")
    done = subprocess.run(
        [
            *(sys.executable, bench),
            *("--steps", "20000", "--every", "10000"),
            *("--episodes", "10", "--min-success", "0.5"),
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert done.returncode == 0, (done.stdout[-3000:], done.stderr[-3000:])
    assert "success   0.0 %  (untrained)" in done.stdout, done.stdout
