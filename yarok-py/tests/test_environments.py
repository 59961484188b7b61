"""yarok's Python package: worlds, the registered Gymnasium environments and the vector env,
checked with Gymnasium's own checker."""

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import yarok
from yarok.registration import ENVIRONMENTS


@pytest.mark.parametrize("env_id", sorted(ENVIRONMENTS))
def test_gymnasiums_checker_passes(env_id):
    env = gymnasium.make(env_id, render_mode="rgb_array")
    try:
        check_env(env.unwrapped, skip_render_check=False)
        frame = env.unwrapped.render()
        assert frame is not None and frame.dtype == np.uint8 and frame.shape[2] == 3
    finally:
        env.close()


def episode(env, seed, actions):
    observation, _ = env.reset(seed=seed)
    frames = [observation]
    for action in actions:
        observation, *_ = env.step(action)
        frames.append(observation)
    return frames


def test_a_seed_gives_the_same_episode_bit_for_bit_and_another_seed_another_start():
    env = gymnasium.make("yarok/PickPlace-v0")
    try:
        start = env.unwrapped.world.features
        rng = np.random.default_rng(7)
        low, high = env.action_space.low, env.action_space.high
        # Small moves about the start, the gripper closing: the DIGITs' images change.
        home = np.array([0.0, 0.0, -1.9, 1.9, -1.57, -1.57, 0.0], dtype=np.float32)
        actions = [np.clip(home + rng.normal(0, 0.02, 7).astype(np.float32) + [20 * i, 0, 0, 0, 0, 0, 0], low, high)
                   for i in range(8)]
        first = episode(env, 3, actions)
        again = episode(env, 3, actions)
        other = episode(env, 4, actions)
        for a, b in zip(first, again):
            assert a.keys() == b.keys()
            for key in a:
                assert np.array_equal(a[key], b[key]), key
        block = start.environment_names.index("medium/block/x")
        assert not np.array_equal(
            first[0]["observation.environment_state"][block : block + 2],
            other[0]["observation.environment_state"][block : block + 2],
        )
        # The start the task drew is where the block is.
        x, y = first[0]["observation.environment_state"][block : block + 2]
        (x_low, x_high), (y_low, y_high) = env.unwrapped.task.region
        assert x_low <= x <= x_high and y_low <= y <= y_high
    finally:
        env.close()


def test_the_observation_keys_and_shapes_are_the_worlds_features():
    with yarok.World("digit_world", cameras=["overview"], camera_size=(96, 64)) as world:
        features = world.features
        observation = world.reset(0)
        assert set(observation) == {
            "observation.state",
            "observation.environment_state",
            *[key for key, _ in features.images],
        }
        assert observation["observation.state"].shape == (len(features.state_names),)
        assert observation["observation.environment_state"].shape == (len(features.environment_names),)
        assert dict(features.images)["observation.images.overview"] == (64, 96, 3)
        assert features.action_names[0] == "arm/gripper/position"
        # Each actuated component is observed where its actuators are, by the same names.
        assert features.state_names == features.action_names
        assert features.action_names[1:] == [
            f"arm/{joint}"
            for joint in ["shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3"]
        ]


def test_an_action_drives_the_arm_to_its_joint_targets():
    with yarok.World("digit_world") as world:
        features = world.features
        world.reset(0)
        target = [0.0, 0.3, -1.7, 1.8, -1.5, -1.6, 0.2]
        observation = world.advance(1.0, action=target)
        joints = [features.state_names.index(name) for name in features.action_names[1:]]
        reached = observation["observation.state"][joints]
        assert np.allclose(reached, target[1:], atol=2e-3), reached


def test_yaroks_refusals_are_python_exceptions_in_yaroks_words():
    with pytest.raises(yarok.YarokError, match='no bundled world "digit_wrld".*digit_world'):
        yarok.World("digit_wrld")
    with yarok.World("digit_world") as world:
        world.reset(0)
        with pytest.raises(yarok.YarokError, match="the action has 2 numbers; this world's has 7"):
            world.step([0.0, 1.0])
        with pytest.raises(yarok.YarokError, match="arm/elbow is 9.*outside its range"):
            world.step([0.0, 0.0, -1.9, 9.0, -1.57, -1.57, 0.0])


def test_the_vector_env_steps_worlds_on_threads_and_resets_them_the_next_step():
    envs = yarok.YarokVectorEnv(yarok.tasks.PickPlace(), num_envs=2, max_episode_steps=2)
    try:
        observations, _ = envs.reset(seed=[5, 5])
        state = observations["observation.environment_state"]
        assert state.shape == (2, 21)
        assert np.array_equal(state[0], state[1]), "the same seed, the same start"
        actions = np.tile(np.array([0.0, 0.0, -1.9, 1.9, -1.57, -1.57, 0.0], dtype=np.float32), (2, 1))
        _, _, _, truncated, _ = envs.step(actions)
        assert not truncated.any()
        _, _, _, truncated, _ = envs.step(actions)
        assert truncated.all()
        # Next-step autoreset: this step resets, reward 0, not done, a new start.
        after, rewards, terminated, truncated, _ = envs.step(actions)
        assert not (terminated | truncated).any() and (rewards == 0).all()
        assert after["observation.images.arm.gripper.left_digit.image"].shape == (2, 320, 240, 3)
    finally:
        envs.close()
