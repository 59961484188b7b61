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
        home = np.array([0.0, 2.93, -1.23, 1.67, -2.01, -1.5708, -1.78], dtype=np.float32)
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
        target = [0.0, 3.23, -1.33, 1.77, -2.11, -1.47, -1.58]  # moves of 0.1 to 0.3 rad from the start
        observation = world.advance(1.0, action=target)
        joints = [features.state_names.index(name) for name in features.action_names[1:]]
        reached = observation["observation.state"][joints]
        assert np.allclose(reached, target[1:], atol=2e-3), reached


def test_yaroks_refusals_are_python_exceptions_in_yaroks_words():
    with pytest.raises(yarok.YarokError, match='no world "digit_wrld".*digit_world'):
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
        actions = np.tile(np.array([0.0, 2.93, -1.23, 1.67, -2.01, -1.5708, -1.78], dtype=np.float32), (2, 1))
        _, _, _, truncated, _ = envs.step(actions)
        assert not truncated.any()
        _, _, _, truncated, infos = envs.step(actions)
        assert truncated.all()
        assert infos["_is_success"].all() and infos["is_success"].shape == (2,)
        # Next-step autoreset: this step resets, reward 0, not done, a new start; its infos'
        # masks say no world reported a step.
        after, rewards, terminated, truncated, infos = envs.step(actions)
        assert not (terminated | truncated).any() and (rewards == 0).all()
        assert not infos["_is_success"].any()
        assert after["observation.images.arm.gripper.left_digit.image"].shape == (2, 320, 240, 3)
    finally:
        envs.close()


@pytest.mark.parametrize("env_id", sorted(ENVIRONMENTS))
def test_every_action_in_the_space_is_taken_and_random_ones_keep_the_world_steady(env_id):
    env = gymnasium.make(env_id)
    try:
        env.reset(seed=0)
        # The bounds themselves, which float32 rounds (2π becomes 6.2831854820251465).
        for action in (env.action_space.high, env.action_space.low):
            env.step(action)
        # The world's own ranges and beyond are clipped to them, never refused.
        env.step(env.action_space.high.astype(np.float64) + 1.0)
        env.action_space.seed(1)
        features = env.unwrapped.world.features
        arm = [features.state_names.index(name) for name in features.action_names
               if name.startswith("arm/") and name != "arm/gripper/position"]
        period = 1.0 / env.unwrapped.task.control_hz
        # Streamed targets go through the arm's speed limit (180°/s): the joints move no
        # further than that in a step but when the arm strikes something (the table, a block:
        # it starts 15 cm above them, and random targets drive it into them), and MuJoCo never
        # goes unstable (it would warn, reset the world and end the episode).
        most = yarok.UR_JOINT_SPEED * period + 1e-3
        faster = 0
        observation, _ = env.reset(seed=1)
        for _ in range(1000):
            before = observation["observation.state"]
            observation, _, terminated, truncated, info = env.step(env.action_space.sample())
            assert "warnings" not in info, info
            moved = np.abs(observation["observation.state"][arm] - before[arm])
            faster += bool((moved > most).any())
            assert np.isfinite(observation["observation.state"]).all()
            if terminated or truncated:
                observation, _ = env.reset()
        assert faster <= 30, f"{faster} of 1000 steps moved a joint faster than 180°/s"
    finally:
        env.close()


def test_tactile_press_holds_its_goal_in_the_observation():
    env = gymnasium.make("yarok/TactilePress-v0")
    try:
        firsts = [env.reset(seed=seed)[0] for seed in range(5)]
        goals = {float(first["observation.desired_goal"][0]) for first in firsts}
        assert len(goals) == 5, "five seeds, five targets to press to"
        assert all(first["observation.achieved_goal"][0] == 0.0 for first in firsts)
        task = env.unwrapped.task
        assert all(2.0 <= goal <= 6.0 for goal in goals)
        assert float(firsts[-1]["observation.desired_goal"][0]) == pytest.approx(task.target)
        assert env.observation_space["observation.desired_goal"].contains(
            firsts[0]["observation.desired_goal"]
        )
    finally:
        env.close()


def test_tactile_press_acts_over_the_gel_and_is_won_by_a_press_held_not_passed_through():
    env = gymnasium.make("yarok/TactilePress-v0")
    try:
        task = env.unwrapped.task
        x, y, surface = yarok.tasks.DIGIT_GEL_CENTRE_MM
        world = np.array(env.unwrapped.world.features.action_ranges)
        assert (env.action_space.low >= world[:, 0]).all()
        assert (env.action_space.high <= world[:, 1]).all()
        assert env.action_space.contains(np.array([x, y, surface], dtype=np.float32))
        # Beyond the workspace, clipped to it: the head goes to the workspace's corner.
        env.reset(seed=0)
        for _ in range(20):
            observation, *_ = env.step(np.array([0.0, 0.0, 400.0], dtype=np.float32))
        low, high = env.action_space.low, env.action_space.high
        corner = [low[0], low[1], high[2]]
        assert observation["observation.state"] == pytest.approx(corner, abs=0.01)
        assert observation["observation.achieved_goal"][0] == 0.0, "the gel touched from above it"

        def press(depth, steps):
            env.reset(seed=3)
            changes, wins = [], []
            for _ in range(steps):
                action = np.array([x, y, surface - depth], dtype=np.float32)
                observation, _, terminated, _, info = env.step(action)
                changes.append(float(observation["observation.achieved_goal"][0]))
                wins.append(info["is_success"])
                if terminated:
                    break
            return changes, wins

        changes, _ = press(-0.3, 20)
        assert changes[-1] == 0.0, "0.3 mm over the gel's surface touches nothing"
        # Deeper and deeper in 0.05 mm steps: the change passes through the target's band
        # without a win, as no depth is held.
        env.reset(seed=3)
        target, passed, won = task.target, False, False
        for step in range(60):
            depth = 0.05 * max(step - 5, 0)
            observation, _, terminated, _, info = env.step(
                np.array([x, y, surface - depth], dtype=np.float32)
            )
            change = float(observation["observation.achieved_goal"][0])
            passed |= abs(change - target) < task.tolerance
            won |= info["is_success"]
        assert passed and not won and change > target + 1
        # The depth that gives the target change, found by bisection, held: won after
        # hold_steps steps within the band, and not before.
        shallow, deep = 0.0, 2.0
        for _ in range(12):
            middle = (shallow + deep) / 2
            changes, _ = press(middle, 12)
            shallow, deep = (middle, deep) if changes[-1] < target else (shallow, middle)
        changes, wins = press((shallow + deep) / 2, 40)
        within = [abs(change - target) < task.tolerance for change in changes]
        first = within.index(True)
        assert wins[-1] and all(within[first:])
        assert len(wins) == first + task.hold_steps and not any(wins[:-1])
    finally:
        env.close()


@pytest.mark.parametrize("env_id", sorted(ENVIRONMENTS))
def test_for_learners_keys_observations_without_dots_or_empty_features(env_id):
    made = gymnasium.make(env_id)
    env = yarok.for_learners(made)
    try:
        observation, _ = env.reset(seed=0)
        assert set(observation) == set(env.observation_space.spaces)
        for key, space in env.observation_space.spaces.items():
            assert "." not in key and np.prod(space.shape) > 0, key
            assert space.contains(observation[key]), key
        flat = gymnasium.wrappers.FlattenObservation(yarok.for_learners(made, images=False))
        vector, _ = flat.reset(seed=0)
        assert vector.ndim == 1 and flat.observation_space.contains(vector)
    finally:
        env.close()


def test_for_learners_rescales_actions_to_minus_one_one_onto_the_action_space():
    made = gymnasium.make("yarok/TactilePress-v0")
    env = yarok.for_learners(made, images=False)
    try:
        assert (env.action_space.low == -1).all() and (env.action_space.high == 1).all()
        env.reset(seed=0)
        low, high = made.action_space.low, made.action_space.high
        for rescaled, expected in ((-1.0, low), (1.0, high), (0.0, (low + high) / 2)):
            for _ in range(30):
                observation, *_ = env.step(np.full(3, rescaled, dtype=np.float32))
            assert observation["state"] == pytest.approx(expected, abs=0.01), rescaled
    finally:
        env.close()


def test_a_refused_action_in_a_vector_env_advances_no_world():
    envs = yarok.YarokVectorEnv(yarok.tasks.PickPlace(), num_envs=2)
    try:
        envs.reset(seed=[5, 5])
        actions = np.tile(np.array([0.0, 0.0, -1.8, 1.8, -1.57, -1.57, 0.0]), (2, 1))
        refused = actions.copy()
        refused[1, 3] = np.nan
        with pytest.raises(yarok.YarokError, match="world 1: .*arm/elbow.*no world was advanced"):
            envs.step(refused)
        after, *_ = envs.step(actions)
        # The same start and the same actions: the two worlds are still one step for one step.
        for key, value in after.items():
            assert np.array_equal(value[0], value[1]), key
    finally:
        envs.close()


def test_a_world_stepped_from_a_second_thread_raises_there_instead_of_deadlocking():
    import threading
    import time

    with yarok.World("digit_world") as world:
        world.reset(0)
        stepping = threading.Thread(target=lambda: world.advance(60.0))
        stepping.start()
        time.sleep(0.3)
        with pytest.raises(yarok.YarokError, match="busy with a call from another thread"):
            world.advance(0.01)
        stepping.join(timeout=120)
        assert not stepping.is_alive()
        world.advance(0.01)


def test_a_world_in_a_fork_of_a_process_with_worlds_is_refused_naming_spawn_which_works(capfd):
    import time

    # Gymnasium's async vector env makes one environment in this process, then forks: each
    # child's world is refused at once (the child says why; the parent sees its pipe break).
    started = time.monotonic()
    with pytest.raises(Exception):
        envs = gymnasium.make_vec("yarok/TactilePress-v0", num_envs=2, vectorization_mode="async")
        try:
            envs.reset(seed=0)
        finally:
            envs.close(terminate=True)
    assert time.monotonic() - started < 30
    assert 'multiprocessing\'s "spawn" method' in capfd.readouterr().err
    envs = gymnasium.make_vec(
        "yarok/TactilePress-v0",
        num_envs=2,
        vectorization_mode="async",
        vector_kwargs={"context": "spawn"},
    )
    try:
        observations, _ = envs.reset(seed=0)
        observations, *_ = envs.step(envs.action_space.sample())
        assert observations["observation.desired_goal"].shape == (2, 1)
    finally:
        envs.close()


CTRL_C_IN_WORLDS = """
import yarok
worlds = yarok.Worlds("digit_world", 2)
worlds.reset([(0, 0, []), (1, 1, [])])
print("stepping", flush=True)
worlds.advance(600.0, [None, None])
"""


def test_ctrl_c_in_worlds_advance_stops_every_world_within_2_s():
    import signal
    import subprocess
    import sys
    import time

    python = subprocess.Popen(
        [sys.executable, "-c", CTRL_C_IN_WORLDS], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    assert python.stdout.readline().strip() == "stepping"
    time.sleep(1.0)
    sent = time.monotonic()
    python.send_signal(signal.SIGINT)
    _, errors = python.communicate(timeout=60)
    took = time.monotonic() - sent
    assert "KeyboardInterrupt" in errors, errors
    assert took < 2.0, f"{took:.1f} s from Ctrl-C to the end of the run"


def test_what_mujoco_warns_of_in_a_step_is_reported_and_ends_the_episode_truncated():
    with yarok.World("digit_world") as world:
        world.reset(0)
        assert world.warnings == []
        # A body placed beyond MuJoCo's largest position: it resets the state and warns.
        world.reset(1, [("medium/block", (1e11, 0.0, 0.5), (1.0, 0.0, 0.0, 0.0))])
        assert any("position" in warning for warning in world.warnings), world.warnings
        world.advance(0.05)
        assert world.warnings == []

    env = gymnasium.make("yarok/PickPlace-v0")
    try:
        env.reset(seed=0)
        world = env.unwrapped.world

        class Warned:
            """The env's world, whose last steps MuJoCo warned of."""

            warnings = ["an unstable acceleration, not a number or too large (the state was reset)"]

            def __getattr__(self, name):
                return getattr(world, name)

        env.unwrapped.world = Warned()
        _, _, terminated, truncated, info = env.step(env.action_space.sample())
        assert truncated and not terminated
        assert info["warnings"] == Warned.warnings
        env.unwrapped.world = world
    finally:
        env.close()


OWN_WORLD = """<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <ur5e name="arm">
      <robotiq_2f85 name="gripper" parent="flange">
        <digit name="left_digit" parent="left_pad" pos="0 -0.0066 0.01875"
               quat="0.7071067811865476 0.7071067811865476 0 0"/>
      </robotiq_2f85>
    </ur5e>
    <block name="cube" size="0.04" pos="0.5 0.2 0.02"/>
  </worldbody>
</mujoco>
"""


def test_a_world_of_your_own_from_a_template_file_is_an_environment(tmp_path):
    path = tmp_path / "my_world.xml"
    path.write_text(OWN_WORLD)
    env = yarok.YarokEnv(yarok.Task(world=str(path)))
    try:
        features = env.world.features
        assert features.action_names[0] == "arm/gripper/position"
        assert "cube/block/x" in features.environment_names
        observation, _ = env.reset(seed=0)
        image = observation["observation.images.arm.gripper.left_digit.image"]
        assert image.dtype == np.uint8 and image.std() > 0
        start = observation["observation.state"][:7].copy()
        target = start.copy()
        target[1] += 0.2  # the shoulder pan, 0.2 rad
        for _ in range(20):
            observation, *_ = env.step(target)
        assert observation["observation.state"][1] == pytest.approx(target[1], abs=2e-3)
        cube = observation["observation.environment_state"][:3]
        assert cube == pytest.approx([0.5, 0.2, 0.02], abs=1e-3)
    finally:
        env.close()
    with pytest.raises(yarok.YarokError, match="no template file"):
        yarok.World(str(tmp_path / "missing.xml"))
