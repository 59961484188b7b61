"""Reinforcement learning, measured: Stable-Baselines3's PPO on ``yarok/TactilePress-v0``
through ``yarok.for_learners``, its success rate on held-out seeds beside the untrained policy.

Run by ``bash scripts/bench-reinforcement.sh`` (Stable-Baselines3 from
``scripts/setup-lerobot.sh``). PPO (``MultiInputPolicy``, the hyper-parameters below) learns
from the state and the goals (``images=False``: the head's position, the target change and the
change so far), observations normalised by ``VecNormalize``, for ``--steps`` environment steps
on the CPU; every ``--every`` steps the deterministic policy is evaluated on ``--episodes``
seeds from 100 000 (the training episodes draw their seeds from 0), which prints the learning
curve. ``--min-success`` makes a final success rate below it a failure (exit 1), as CI's short
run uses it.
"""

from __future__ import annotations

import argparse
import sys
import time

import gymnasium

import yarok

ENV_ID = "yarok/TactilePress-v0"
HELD_OUT_SEED = 100_000
PPO_SETTINGS = dict(
    n_steps=512,
    batch_size=64,
    n_epochs=10,
    learning_rate=3e-4,
    gamma=0.95,
    gae_lambda=0.95,
    ent_coef=0.0,
    policy_kwargs=dict(net_arch=[64, 64]),
)


def make_env() -> gymnasium.Env:
    return yarok.for_learners(gymnasium.make(ENV_ID), images=False)


def success_rate(model, normalize, episodes: int) -> float:
    """The share of ``episodes`` held-out seeds the deterministic policy wins."""
    env = make_env()
    won = 0
    try:
        for episode in range(episodes):
            observation, _ = env.reset(seed=HELD_OUT_SEED + episode)
            while True:
                batch = {key: value[None] for key, value in observation.items()}
                action, _ = model.predict(normalize.normalize_obs(batch), deterministic=True)
                observation, _, terminated, truncated, info = env.step(action[0])
                if terminated or truncated:
                    won += bool(info.get("is_success", False))
                    break
    finally:
        env.close()
    return won / episodes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=30_000)
    parser.add_argument("--every", type=int, default=5_000)
    parser.add_argument("--episodes", type=int, default=50)
    parser.add_argument("--min-success", type=float, default=None)
    arguments = parser.parse_args()

    import torch
    from stable_baselines3 import PPO
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.vec_env import VecNormalize

    torch.manual_seed(0)
    torch.set_num_threads(1)
    training = VecNormalize(make_vec_env(make_env, n_envs=1, seed=0), norm_reward=False)
    model = PPO("MultiInputPolicy", training, seed=0, device="cpu", **PPO_SETTINGS)
    untrained = success_rate(model, training, arguments.episodes)
    print(f"{ENV_ID}, {arguments.episodes} held-out seeds from {HELD_OUT_SEED}:")
    print(f"  steps {0:>7}  success {100 * untrained:5.1f} %  (untrained)", flush=True)
    seconds = 0.0
    success = untrained
    while model.num_timesteps < arguments.steps:
        start = time.process_time()
        model.learn(arguments.every, reset_num_timesteps=False)
        seconds += time.process_time() - start
        training.training = False
        success = success_rate(model, training, arguments.episodes)
        training.training = True
        print(
            f"  steps {model.num_timesteps:>7}  success {100 * success:5.1f} %  "
            f"(training so far {seconds / 60:.1f} CPU-min)",
            flush=True,
        )
    training.close()
    print(
        f"PPO, {model.num_timesteps} steps in {seconds / 60:.1f} CPU-minutes of training: "
        f"{100 * success:.0f} % of {arguments.episodes} held-out seeds (untrained "
        f"{100 * untrained:.0f} %)"
    )
    if arguments.min_success is not None and success < arguments.min_success:
        sys.exit(f"success {success:.2f} is below --min-success {arguments.min_success}")


if __name__ == "__main__":
    main()
