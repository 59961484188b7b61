"""Environment steps a second, side by side in one run: yarok's pick-and-place environment
against robosuite 1.5.2's ``Lift`` (a Panda, its default controller, 20 Hz control, MuJoCo
3.3.0), without camera observations and with one 84×84 camera; yarok with both DIGITs' tactile
images; yarok's vector environment with 2 worlds against 1 (tactile images on); and the cost
of stepping from Python against the same world stepped from Rust (``World.advance_periods``:
the same actions, ticks and observations, without returning to Python between periods).

Run by ``bash scripts/bench-python.sh`` (which installs robosuite and MuJoCo into the
project's cache). Every environment is stepped with actions that hold the arm where it starts
and open the gripper (robosuite: zero deltas), after a warm-up; each figure is the best of
``--rounds`` (default 3) timed runs of ``--steps`` steps.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("MUJOCO_GL", "egl")

import gymnasium  # noqa: E402
import numpy as np  # noqa: E402

import yarok  # noqa: E402

CONTROL_HZ = 20.0


def best_rate(step, steps: int, rounds: int) -> float:
    """Steps a second: the best of `rounds` timed runs of `steps` calls of `step`."""
    for _ in range(min(steps, 20)):
        step()
    rates = []
    for _ in range(rounds):
        start = time.perf_counter()
        for _ in range(steps):
            step()
        rates.append(steps / (time.perf_counter() - start))
    return max(rates)


def robosuite_lift(camera: bool, steps: int, rounds: int) -> float:
    import robosuite

    env = robosuite.make(
        "Lift",
        robots="Panda",
        has_renderer=False,
        has_offscreen_renderer=camera,
        use_camera_obs=camera,
        camera_names="agentview",
        camera_heights=84,
        camera_widths=84,
        control_freq=int(CONTROL_HZ),
        horizon=10**9,
    )
    env.reset()
    action = np.zeros(env.action_dim)
    rate = best_rate(lambda: env.step(action), steps, rounds)
    env.close()
    return rate


def holding_action(env) -> np.ndarray:
    """The gripper open, the arm's joints where they are."""
    features = env.unwrapped.world.features
    observation, _ = env.reset(seed=0)
    state = dict(zip(features.state_names, observation["observation.state"]))
    action = [0.0 if name.endswith("gripper/position") else state[name] for name in features.action_names]
    return np.asarray(action, dtype=np.float32)


def yarok_pick_place(task: yarok.tasks.PickPlace, steps: int, rounds: int) -> float:
    env = yarok.YarokEnv(task)
    action = holding_action(env)
    rate = best_rate(lambda: env.step(action), steps, rounds)
    env.close()
    return rate


def yarok_vector(num_envs: int, steps: int, rounds: int) -> float:
    """Environment steps a second over all `num_envs` worlds."""
    envs = yarok.YarokVectorEnv(yarok.tasks.PickPlace(), num_envs=num_envs, max_episode_steps=10**9)
    single = yarok.YarokEnv(yarok.tasks.PickPlace())
    action = holding_action(single)
    single.close()
    envs.reset(seed=0)
    actions = np.tile(action, (num_envs, 1))
    rate = best_rate(lambda: envs.step(actions), steps, rounds) * num_envs
    envs.close()
    return rate


def python_overhead(steps: int, rounds: int) -> tuple[float, float]:
    """DigitWorld stepped a control period at a time from Python and from Rust: steps/s each."""
    env = yarok.YarokEnv(yarok.tasks.PickPlace())
    action = holding_action(env).tolist()
    world = env.unwrapped.world
    period = 1.0 / CONTROL_HZ
    from_python = best_rate(lambda: world.advance(period, action), steps, rounds)
    from_rust = []
    world.advance_periods(20, period, action)
    for _ in range(rounds):
        start = time.perf_counter()
        world.advance_periods(steps, period, action)
        from_rust.append(steps / (time.perf_counter() - start))
    env.close()
    return from_python, max(from_rust)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    steps, rounds = args.steps, args.rounds
    bare = yarok.tasks.PickPlace(world="pick_and_place_world", render_camera=None)
    camera = yarok.tasks.PickPlace(
        world="pick_and_place_world", cameras=("overview",), camera_size=(84, 84)
    )
    rates = {
        "robosuite Lift, no camera": robosuite_lift(False, steps, rounds),
        "yarok PickPlace, no camera": yarok_pick_place(bare, steps, rounds),
        "robosuite Lift, one 84x84 camera": robosuite_lift(True, steps, rounds),
        "yarok PickPlace, one 84x84 camera": yarok_pick_place(camera, steps, rounds),
        "yarok PickPlace-v0, both DIGITs": yarok_pick_place(yarok.tasks.PickPlace(), steps, rounds),
        "yarok vector env, 1 world (DIGITs)": yarok_vector(1, steps, rounds),
        "yarok vector env, 2 worlds (DIGITs)": yarok_vector(2, steps, rounds),
    }
    from_python, from_rust = python_overhead(steps, rounds)
    rates["DigitWorld stepped from Python"] = from_python
    rates["DigitWorld stepped from Rust"] = from_rust
    for name, rate in rates.items():
        print(f"{name:<40} {rate:10.1f} steps/s")
    print()
    ratios = [
        ("yarok / robosuite, no camera (goal >= 10)",
         rates["yarok PickPlace, no camera"] / rates["robosuite Lift, no camera"]),
        ("yarok / robosuite, one 84x84 camera (goal >= 5)",
         rates["yarok PickPlace, one 84x84 camera"] / rates["robosuite Lift, one 84x84 camera"]),
        ("yarok with both DIGITs / robosuite without camera (goal > 1)",
         rates["yarok PickPlace-v0, both DIGITs"] / rates["robosuite Lift, no camera"]),
        ("vector env, 2 worlds / 1 (goal >= 1.8)",
         rates["yarok vector env, 2 worlds (DIGITs)"] / rates["yarok vector env, 1 world (DIGITs)"]),
        ("Python's cost per step, % (goal <= 10)", (from_rust / from_python - 1) * 100),
    ]
    for name, ratio in ratios:
        print(f"{name:<62} {ratio:8.2f}")


if __name__ == "__main__":
    main()
