"""The learning loop with LeRobot unchanged: yarok's scripted demonstrations recorded as a
LeRobot dataset → ``lerobot-train`` (ACT, a few steps) → the checkpoint loaded by LeRobot's
own code → a full episode of ``yarok/PickPlace-v0`` driven through LeRobot's own
``eval_policy``.

LeRobot (≥ 0.5, Python ≥ 3.12) is installed by ``scripts/setup-lerobot.sh`` into the project's
cache; where it is missing this test is skipped, unless ``YAROK_REQUIRE_LEROBOT=1`` (as
``scripts/test.sh`` runs it), which makes its absence a failure.
"""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

if os.environ.get("YAROK_REQUIRE_LEROBOT") != "1":
    pytest.importorskip("lerobot")

import gymnasium  # noqa: E402
import numpy as np  # noqa: E402
from lerobot.policies.act.modeling_act import ACTPolicy  # noqa: E402
from lerobot.policies.factory import make_pre_post_processors  # noqa: E402
from lerobot.processor import PolicyProcessorPipeline  # noqa: E402
from lerobot.scripts.lerobot_eval import eval_policy  # noqa: E402

import yarok  # noqa: E402
import yarok.lerobot  # noqa: E402


def lerobot_train(*args: str) -> None:
    """Runs LeRobot's own training command, as its documentation gives it."""
    command = shutil.which("lerobot-train", path=str(Path(sys.executable).parent))
    assert command is not None, "lerobot-train is not installed beside this Python"
    done = subprocess.run([command, *args], capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-4000:]


def test_demonstrations_train_a_policy_that_lerobot_evaluates_in_the_environment(tmp_path):
    demos = tmp_path / "demos"
    yarok.run(
        "digit_world",
        "demonstrate",
        settings=["behaviour/episodes=2", "behaviour/seed=1", "plugins/dataset/fps=20"],
        dataset=demos,
    )
    info = json.loads((demos / "meta/info.json").read_text())
    assert info["total_episodes"] == 2

    # The environment observes what the dataset recorded: the same keys and shapes.
    env = gymnasium.make("yarok/PickPlace-v0")
    dataset_features = {
        key: tuple(feature["shape"])
        for key, feature in info["features"].items()
        if key.startswith("observation.")
    }
    env_features = {key: space.shape for key, space in env.observation_space.spaces.items()}
    env.close()
    # The dataset's videos are height × width × channels, as are the environment's images.
    assert env_features == dataset_features
    assert env.action_space.shape == tuple(info["features"]["action"]["shape"])

    out = tmp_path / "train"
    lerobot_train(
        "--dataset.repo_id=yarok/digit_world_demos",
        f"--dataset.root={demos}",
        "--policy.type=act",
        "--policy.device=cpu",
        "--policy.push_to_hub=false",
        "--policy.pretrained_backbone_weights=null",
        "--policy.chunk_size=20",
        "--policy.n_action_steps=20",
        "--policy.dim_model=64",
        "--policy.dim_feedforward=128",
        "--policy.n_encoder_layers=1",
        "--steps=3",
        "--batch_size=2",
        "--num_workers=0",
        "--save_freq=3",
        "--log_freq=1",
        "--wandb.enable=false",
        f"--output_dir={out}",
    )
    checkpoint = out / "checkpoints/last/pretrained_model"
    assert (checkpoint / "model.safetensors").is_file()

    policy = ACTPolicy.from_pretrained(checkpoint)
    preprocessor, postprocessor = make_pre_post_processors(
        policy.config, pretrained_path=str(checkpoint)
    )
    # The policy reads the dataset's features; the environment gives each of them.
    wanted = set(policy.config.input_features)
    assert wanted <= set(dataset_features), wanted - set(dataset_features)

    identity = PolicyProcessorPipeline(steps=[])
    envs = yarok.lerobot.make_vector_env("yarok/PickPlace-v0", n_envs=1)
    try:
        results = eval_policy(
            envs,
            policy,
            identity,
            identity,
            preprocessor,
            postprocessor,
            n_episodes=1,
            start_seed=1000,
        )
    finally:
        envs.close()
    episode = results["per_episode"][0]
    # A full episode: the barely trained policy does not succeed, so it runs to the time
    # limit of 400 steps, each reward minus the block's distance from the target (metres):
    # no reward is above the largest, so 400 of them sum to at most 400 times it.
    assert not episode["success"]
    assert -1.0 < episode["max_reward"] < 0
    assert episode["sum_reward"] <= 399 * episode["max_reward"]


def recorded_episodes(demos: Path):
    """Each episode of the dataset at ``demos``, read by pandas (pyarrow) as LeRobot reads it:
    its states, environment states and actions, one row a frame."""
    import pandas

    frames = pandas.read_parquet(demos / "data")
    for episode, rows in frames.groupby("episode_index"):
        rows = rows.sort_values("frame_index")
        yield episode, *(
            np.stack(rows[key].to_numpy())
            for key in ("observation.state", "observation.environment_state", "action")
        )


def test_each_recorded_action_leads_from_its_frame_to_the_next_and_a_policy_repeating_them_succeeds(
    tmp_path,
):
    """The dataset's ``action`` at frame t is the command for the period that follows: given to
    the environment at frame t, it brings the arm to frame t + 1's state (the convention of
    LeRobot's datasets, where the leader's command leads the follower). A policy that answers
    each observation with the action recorded at the nearest frame places the block."""
    demos = tmp_path / "demos"
    fps = 20
    yarok.run(
        "digit_world",
        "demonstrate",
        settings=["behaviour/episodes=2", "behaviour/seed=11", f"plugins/dataset/fps={fps}"],
        dataset=demos,
    )
    task = yarok.tasks.PickPlace()
    with yarok.World("digit_world") as world:
        features = world.features
        task.bind(features)
        arm = [features.state_names.index(name) for name in features.action_names[1:]]
        block = features.environment_names.index("medium/block/x")
        for episode, states, environment, actions in recorded_episodes(demos):
            pose = environment[0][block : block + 7]
            placed = [("medium/block", tuple(pose[:3]), tuple(pose[3:]))]
            observation = world.reset(2 * episode, placed)
            assert np.abs(observation["observation.state"][arm] - states[0][arm]).max() < 1e-3
            # Every frame, open loop: the action recorded at t, from where frame t left off.
            misses = []
            for t in range(len(actions) - 1):
                observation = world.advance(1.0 / fps, actions[t].tolist())
                misses.append(np.abs(observation["observation.state"][arm] - states[t + 1][arm]).max())
            moved = np.abs(np.diff(states[:, arm], axis=0)).max(axis=1)
            # The arm moves up to 0.05 rad a frame; each recorded action lands it within 10 mrad
            # of the next frame, every frame (an action equal to where the arm already was
            # would miss by each frame's motion). Mid-motion frames land within 2 mrad; a
            # motion that starts between two frames (the lift once the gripper has opened) is
            # recorded from the next frame on, so its first frames miss by the part of a frame
            # it ran (7 mrad seen).
            assert max(misses) < 1e-2, (episode, max(misses), int(np.argmax(misses)))
            assert np.median(misses) < 2e-3, (episode, np.median(misses))
            assert moved.max() > 0.02
            assert task.success(observation), f"episode {episode}: the replay did not place the block"

            # Closed loop: at step t the policy answers with the action of the recorded frame
            # nearest to what it observes among frames t - 2 … t + 2.
            recorded = np.hstack([states, environment])
            observation = world.reset(2 * episode + 1, placed)
            for t in range(len(actions)):
                now = np.hstack(
                    [observation["observation.state"], observation["observation.environment_state"]]
                )
                around = np.arange(max(t - 2, 0), min(t + 3, len(actions)))
                nearest = around[np.argmin(np.abs(recorded[around] - now).sum(axis=1))]
                observation = world.advance(1.0 / fps, actions[nearest].tolist())
            assert task.success(observation), f"episode {episode}: the policy did not place the block"


def test_the_books_install_line_is_what_the_loop_is_tested_with():
    """The book's LeRobot lines name the extras and Python this venv was made with (by
    ``scripts/setup-lerobot.sh``), so that following them gives what this test ran."""
    root = Path(__file__).resolve().parents[2]
    readme = (root / "docs" / "src" / "learning.md").read_text()
    setup = (root / "scripts" / "setup-lerobot.sh").read_text()
    line = next(line for line in readme.splitlines() if "pip install 'lerobot[" in line)
    assert line.startswith("python3.12 -m venv "), line
    extras = line.split("'lerobot[", 1)[1].split("]", 1)[0]
    assert f'"lerobot[{extras}]==' in setup, (extras, setup)
    assert sys.version_info >= (3, 12)
    for command in ["lerobot-train", "lerobot-eval"]:
        assert shutil.which(command, path=str(Path(sys.executable).parent)), command
