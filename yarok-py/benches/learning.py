"""A success rate, measured: yarok's scripted demonstrations → LeRobot's training, unchanged →
LeRobot's own evaluation in ``yarok/PickPlace-v0`` on held-out seeds, beside the untrained
policy and the scripted demonstrations.

Run by ``bash scripts/bench-learning.sh`` (LeRobot from ``scripts/setup-lerobot.sh``). The
steps, each timed:

1. ``--demos`` demonstrations (``yarok.run("digit_world", "demonstrate", …)``, seed 1, at the
   environment's 20 Hz), each ending with the block on its target;
2. the images removed with ``lerobot-edit-dataset`` (the policy sees ``observation.state`` and
   ``observation.environment_state``);
3. ``lerobot-train`` with ACT (``yarok.lerobot.ACT_ON_A_CPU``: chunks of 20 actions, one second,
   each executed whole) for ``--steps`` steps on the CPU;
4. LeRobot's ``eval_policy`` on ``--episodes`` seeds from 100 000 (the environment draws its
   starts with numpy from the seed; the demonstrations were drawn by yarok's own generator from
   seed 1: none is a start the policy was trained on), for the trained policy and for the same
   ACT untrained.
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import time
from pathlib import Path

import yarok
import yarok.lerobot

FPS = 20
HELD_OUT_SEED = 100_000
IMAGES = [
    "observation.images.arm.gripper.left_digit.image",
    "observation.images.arm.gripper.right_digit.image",
]


def command(name: str) -> str:
    found = shutil.which(name, path=str(Path(sys.executable).parent))
    if found is None:
        sys.exit(f"{name} is not installed beside this Python: run scripts/setup-lerobot.sh")
    return found


def timed(what: str, run) -> float:
    start = time.perf_counter()
    run()
    seconds = time.perf_counter() - start
    print(f"{what}: {seconds / 60:.1f} min", flush=True)
    return seconds


def evaluate(train_dir: Path, episodes: int, trained: bool) -> dict:
    """LeRobot's ``eval_policy`` of the policy ``train_dir`` holds, or of the same ACT untrained."""
    import torch
    from lerobot.policies.act.modeling_act import ACTPolicy
    from lerobot.policies.factory import make_pre_post_processors
    from lerobot.processor import PolicyProcessorPipeline
    from lerobot.scripts.lerobot_eval import eval_policy

    checkpoint = train_dir / "checkpoints/last/pretrained_model"
    policy = ACTPolicy.from_pretrained(checkpoint)
    if not trained:
        torch.manual_seed(0)
        policy = ACTPolicy(policy.config)
        policy.eval()
    pre, post = make_pre_post_processors(policy.config, pretrained_path=str(checkpoint))
    identity = PolicyProcessorPipeline(steps=[])
    env = yarok.lerobot.make_vector_env("yarok/PickPlace-v0", n_envs=1)
    try:
        results = eval_policy(
            env,
            policy,
            identity,
            identity,
            pre,
            post,
            n_episodes=episodes,
            start_seed=HELD_OUT_SEED,
        )
    finally:
        env.close()
    closest = sorted(
        0.0 if episode["success"] else -episode["max_reward"] for episode in results["per_episode"]
    )
    print(f"closest the block came to the target (cm): {[round(100 * d, 1) for d in closest]}")
    return results["aggregated"]


def demonstrations_placed(demos: Path) -> int:
    """How many recorded episodes end as ``PickPlace`` counts a success (their last frame)."""
    import numpy as np
    import pandas

    task = yarok.tasks.PickPlace()
    with yarok.World("digit_world") as world:
        task.bind(world.features)
    frames = pandas.read_parquet(demos / "data")
    placed = 0
    for _, rows in frames.groupby("episode_index"):
        last = rows.sort_values("frame_index").iloc[-1]
        observation = {
            key: np.asarray(last[key])
            for key in ("observation.state", "observation.environment_state")
        }
        placed += task.success(observation)
    return placed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--demos", type=int, default=160)
    parser.add_argument("--steps", type=int, default=8000)
    parser.add_argument("--episodes", type=int, default=50)
    parser.add_argument("--out", type=Path, default=Path("out/bench-learning"))
    parser.add_argument(
        "--keep-demos",
        action="store_true",
        help="train on the demonstrations an earlier run left in OUT/demos",
    )
    arguments = parser.parse_args()
    out: Path = arguments.out
    demos, states, train = out / "demos", out / "demos_states", out / "train"
    shutil.rmtree(states, ignore_errors=True)
    shutil.rmtree(train, ignore_errors=True)
    if not arguments.keep_demos:
        shutil.rmtree(demos, ignore_errors=True)
        out.mkdir(parents=True, exist_ok=True)
        timed(
            f"{arguments.demos} demonstrations",
            lambda: yarok.run(
                "digit_world",
                "demonstrate",
                settings=[
                    f"behaviour/episodes={arguments.demos}",
                    "behaviour/seed=1",
                    f"plugins/dataset/fps={FPS}",
                ],
                dataset=demos,
            ),
        )
    subprocess.run(
        [
            command("lerobot-edit-dataset"),
            "--repo_id=yarok/demos",
            f"--root={demos}",
            "--new_repo_id=yarok/demos_states",
            f"--new_root={states}",
            "--operation.type=remove_feature",
            f"--operation.feature_names={json.dumps(IMAGES)}",
        ],
        check=True,
        capture_output=True,
    )
    yarok.lerobot.floor_state_spreads(states)
    training = timed(
        f"training ACT {arguments.steps} steps on the CPU",
        lambda: subprocess.run(
            [
                command("lerobot-train"),
                "--dataset.repo_id=yarok/demos_states",
                f"--dataset.root={states}",
                *yarok.lerobot.ACT_ON_A_CPU,
                f"--steps={arguments.steps}",
                f"--save_freq={arguments.steps}",
                "--log_freq=500",
                f"--output_dir={train}",
            ],
            check=True,
        ),
    )
    trained = evaluate(train, arguments.episodes, trained=True)
    untrained = evaluate(train, arguments.episodes, trained=False)
    print(
        f"\nyarok/PickPlace-v0, {arguments.episodes} held-out seeds from {HELD_OUT_SEED}, "
        f"ACT on the state features, {arguments.demos} demonstrations, "
        f"{arguments.steps} training steps ({training / 60:.1f} min on this 2-core machine):"
    )
    print(f"  trained   success {trained['pc_success']:.0f} %  avg reward {trained['avg_sum_reward']:.2f}")
    print(f"  untrained success {untrained['pc_success']:.0f} %  avg reward {untrained['avg_sum_reward']:.2f}")
    placed = demonstrations_placed(demos)
    print(f"  scripted demonstrations: {placed} of {arguments.demos} end as the task's success")


if __name__ == "__main__":
    main()
