"""The same environment on the real robot: ``yarok/PickPlace-v0`` with ``env="real"`` drives a
UR5e and its 2F-85 through yarok's real drivers, here against the project's fake UR controller
(``yarok-test``'s ``fake-ur-controller``, a process of its own speaking the controller's
protocols, and running yarok's streaming program as a controller would): each action reaches
the arm as a target message to the one streaming program at the control rate, and the gripper
as a position request; ``close()`` stops the arm with ``stopj``, and so do Ctrl-C (which
reaches Python as ``KeyboardInterrupt``), SIGTERM and SIGHUP; a killed process's program stops
the arm by itself."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import gymnasium
import numpy as np
import pytest

import yarok  # noqa: F401  (registers the environments)

REPOSITORY = Path(__file__).resolve().parents[2]
STEPS = 20


@pytest.fixture
def fake_controller():
    """The fake controller's process, started; its output is read once it has ended."""
    subprocess.run(
        ["cargo", "build", "-q", "--locked", "-p", "yarok-test", "--bin", "fake-ur-controller"],
        cwd=REPOSITORY,
        check=True,
    )
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPOSITORY / "target"))
    process = subprocess.Popen(
        [target / "debug/fake-ur-controller"],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    yield process
    if process.poll() is None:
        process.kill()
        process.wait()


def real_env(fake_controller, **kwargs):
    """``yarok/PickPlace-v0`` on the real robot, its arm and gripper the fake controller's
    (whose first line names its address)."""
    host = fake_controller.stdout.readline().split()[1]
    return gymnasium.make(
        "yarok/PickPlace-v0",
        env="real",
        task_kwargs={"world": "pick_and_place_world"},
        settings=[
            f'interfaces/arm/host="{host}"',
            f'interfaces/arm/gripper/host="{host}"',
            # Any free port for the streaming program: tests may run side by side.
            "interfaces/arm/reverse_port=0",
        ],
        **kwargs,
    )


def script_line(said: str) -> str:
    """The URScript of the fake's ``script SECONDS LINE``."""
    return said.split(" ", 2)[2]


def script_times(said: list[str], prefix: str) -> list[float]:
    """When each URScript line starting with ``prefix`` arrived at the fake (seconds)."""
    return [
        float(line.split(" ", 2)[1])
        for line in said
        if line.startswith("script ") and script_line(line).startswith(prefix)
    ]


def targets(said: list[str]) -> list[tuple[float, float, np.ndarray]]:
    """Each target the streaming program read: when (seconds), its period, its joints."""
    found = []
    for line in said:
        words = line.split()
        if words[0] == "message" and words[2] == "Servo":
            found.append((float(words[1]), float(words[3]), np.array([float(w) for w in words[4:10]])))
    return found


def program_ends(said: list[str]) -> list[tuple[float, str]]:
    """When each streaming program ended (seconds), and why."""
    return [
        (float(line.split()[1]), line.split(" ", 3)[3])
        for line in said
        if line.startswith("program ") and line.split()[2] == "ended"
    ]


def test_actions_reach_the_real_arm_as_targets_at_the_control_rate_and_close_stops_it(
    fake_controller,
):
    env = real_env(fake_controller, max_episode_steps=STEPS)
    observation, _ = env.reset(seed=0)
    # Nothing measures the blocks on hardware; the arm's joints are measured.
    assert observation["observation.environment_state"].shape == (0,)
    state = observation["observation.state"]
    start = state[1:7]
    assert np.allclose(start, [0.0, -np.pi / 2, np.pi / 2, -np.pi / 2, -np.pi / 2, 0.0], atol=1e-3)
    sent = []
    for step in range(STEPS):
        action = np.concatenate([[100.0], start + [0.01 * (step + 1), 0, 0, 0, 0, 0]]).astype(np.float32)
        observation, reward, terminated, truncated, info = env.step(action)
        sent.append(action)
        assert reward == 0.0 and not terminated
    assert truncated
    # The arm followed: its pan measured near the last targets (the fake's program reaches each
    # target within its period).
    assert abs(observation["observation.state"][1] - sent[-1][1]) < 0.02
    env.close()
    fake_controller.stdin.close()
    said = fake_controller.stdout.read().splitlines()
    fake_controller.wait(timeout=10)

    scripts = [script_line(line) for line in said if line.startswith("script ")]
    programs = [line for line in scripts if line.startswith("def yarok_stream():")]
    assert len(programs) == 1, scripts
    streamed = targets(said)
    # One target per action, with the control period, each where the approach to the action's
    # joint targets is due: never asking a joint beyond its speed limit, and, once the arm has
    # sped up to the targets' pace, the action's targets themselves.
    assert len(streamed) == STEPS, said
    periods = [period for _, period, _ in streamed]
    # The control period, to the platform's tick (10 ms) as each action is picked up and a
    # busy machine's jitter.
    assert all(abs(period - 0.05) <= 0.02 for period in periods[1:]), periods
    assert abs(np.mean(periods[1:]) - 0.05) < 0.005, periods
    before = start
    for _, period, joints in streamed:
        asked = np.abs(joints - before).max() / period
        assert asked <= yarok.UR_JOINT_SPEED + 1e-6, (joints, asked)
        before = joints
    # (Within a milliradian: a period a tick shorter than the last asks a little more speed
    # than the limits' acceleration gives at once.)
    for (_, _, joints), action in list(zip(streamed, sent))[STEPS // 2 :]:
        assert np.allclose(joints, action[1:], atol=1e-3), joints
    # Closed: stopj after the last target, and the program ended.
    assert script_times(said, "stopj(")[-1] > streamed[-1][0], said
    assert program_ends(said), said
    # The gripper was asked for position 100 (Robotiq's POS register).
    gripper = [line for line in said if line.startswith("gripper ")]
    assert any("POS 100" in line for line in gripper), gripper


def test_a_stalled_or_slow_policy_gets_fresh_observations_and_the_arm_no_burst(fake_controller):
    """Ten steps at 20 Hz, a 2 s stall (a model warming up), ten more at 20 Hz, then ten at
    12.5 Hz: every target asks no joint beyond its speed limit, none comes in a burst, the
    step after the stall says how late it was, and its observation is where the arm is then."""
    env = real_env(fake_controller)
    observation, _ = env.reset(seed=0)
    start = observation["observation.state"][1:7].astype(np.float64)
    sent, lates = [], []
    for step in range(30):
        if step == 10:
            time.sleep(2.0)
        if step >= 20:
            time.sleep(0.03)  # a policy that thinks 30 ms: 12.5 Hz with the 50 ms step
        action = np.concatenate([[0.0], start + [0.02 * (step + 1), 0, 0, 0, 0, 0]])
        observation, _, _, _, info = env.step(action.astype(np.float32))
        lates.append(info.get("late_seconds", 0.0))
        sent.append(action[1:])
        if step == 9:
            held = observation["observation.state"][1]
    # The stalled step: late by the stall, its observation the arm holding the last target.
    assert 1.9 < lates[10] < 2.2, lates
    assert abs(held - sent[9][0]) < 0.02
    assert not any(late > 0.0 for late in lates[:10])
    # The arm followed to the last target at the control rate's pace.
    assert abs(observation["observation.state"][1] - sent[-1][0]) < 0.03
    env.close()
    fake_controller.stdin.close()
    said = fake_controller.stdout.read().splitlines()
    fake_controller.wait(timeout=10)
    streamed = targets(said)
    assert len(streamed) == 30, said
    before = start
    for _, period, joints in streamed:
        asked = np.abs(joints - before).max() / period
        assert asked <= yarok.UR_JOINT_SPEED + 1e-6, (joints, asked)
        before = joints
    # No burst (queued targets sent back to back arrive within a millisecond of each other).
    arrived = np.array([at for at, _, _ in streamed])
    assert np.diff(arrived).min() > 0.005, np.diff(arrived)
    # One program streamed throughout: the stall kept it alive, and nothing ended it early.
    assert len(program_ends(said)) == 1, program_ends(said)


CTRL_C_SCRIPT = """
import sys, gymnasium, numpy as np, yarok
env = gymnasium.make("yarok/PickPlace-v0", env="real", task_kwargs={"world": "pick_and_place_world"},
                     settings=[f'interfaces/arm/host="{sys.argv[1]}"',
                               f'interfaces/arm/gripper/host="{sys.argv[1]}"',
                               "interfaces/arm/reverse_port=0"])
observation, _ = env.reset(seed=0)
action = np.concatenate([[0.0], observation["observation.state"][1:7]]).astype(np.float32)
env.step(action)
print("stepping", flush=True)
env.unwrapped.world.advance(600.0)
"""


@pytest.mark.parametrize(
    "signum, said",
    [
        (signal.SIGINT, "KeyboardInterrupt"),
        (signal.SIGTERM, ""),
        (signal.SIGHUP, ""),
    ],
)
def test_ctrl_c_sigterm_and_sighup_end_the_run_and_stop_the_real_arm(fake_controller, signum, said):
    host = fake_controller.stdout.readline().split()[1]
    python = subprocess.Popen(
        [sys.executable, "-c", CTRL_C_SCRIPT, host],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert python.stdout.readline().strip() == "stepping"
    python.send_signal(signum)
    _, errors = python.communicate(timeout=20)
    assert python.returncode != 0
    if signum != signal.SIGINT:
        assert python.returncode == 128 + signum, (python.returncode, errors)
    assert said in errors, errors
    fake_controller.stdin.close()
    said = fake_controller.stdout.read().splitlines()
    assert script_times(said, "stopj(")[-1] > targets(said)[-1][0], said


def test_a_killed_process_leaves_the_streaming_program_to_stop_the_arm(fake_controller):
    """SIGKILL: no handler runs, no ``stopj`` is sent; the streaming program on the controller
    finds its connection gone (or its watchdog, 0.2 s, runs out) and stops the arm itself,
    within the watchdog of the last word it had."""
    host = fake_controller.stdout.readline().split()[1]
    python = subprocess.Popen(
        [sys.executable, "-c", CTRL_C_SCRIPT, host],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert python.stdout.readline().strip() == "stepping"
    time.sleep(0.3)
    python.kill()
    python.communicate(timeout=20)
    time.sleep(0.5)
    fake_controller.stdin.close()
    said = fake_controller.stdout.read().splitlines()
    assert not script_times(said, "stopj("), "nobody was left to send stopj"
    ends = program_ends(said)
    assert len(ends) == 1, said
    ended_at, why = ends[0]
    last_word = max(float(line.split()[1]) for line in said if line.startswith("message "))
    assert ended_at - last_word < 0.2 + 0.05, (ended_at, last_word, why)


@pytest.mark.parametrize(
    "fault, named",
    [
        ("protective stop", "PROTECTIVE_STOP"),
        ("emergency stop", "ROBOT_EMERGENCY_STOP"),
        ("power off", "POWER_OFF"),
        ("mute gripper", "gripper"),
    ],
)
def test_a_stop_reaches_the_caller_within_half_a_second_and_nothing_more_is_streamed(
    fake_controller, fault, named
):
    """A fault mid-episode: the next steps raise ``YarokError`` naming it within 0.5 s, and the
    arm is sent nothing more: the streaming program ended with the stop, or the run ended."""
    env = real_env(fake_controller)
    observation, _ = env.reset(seed=0)
    start = observation["observation.state"][1:7].astype(np.float64)

    def action(step):
        return np.concatenate([[0.0], start + [0.005 * step, 0, 0, 0, 0, 0]]).astype(np.float32)

    for step in range(5):
        env.step(action(step))
    fake_controller.stdin.write(fault + "\n")
    fake_controller.stdin.flush()
    told = time.monotonic()
    with pytest.raises(yarok.YarokError) as raised:
        for step in range(5, 200):
            env.step(action(step))
    late = time.monotonic() - told
    assert named in str(raised.value), raised.value
    assert late < 0.5, (late, raised.value)
    env.close()
    fake_controller.stdin.close()
    said = fake_controller.stdout.read().splitlines()
    ends = program_ends(said)
    assert len(ends) == 1, said
    assert all(at <= ends[0][0] for at, _, _ in targets(said)), said


def test_a_3_rad_jump_is_approached_at_the_joint_speed_limit(fake_controller):
    """An action 3 rad from where the arm is, held at 20 Hz: every target the program reads is
    within the joint speed limit of the one before, the approach goes at that limit, and the arm
    arrives."""
    env = real_env(fake_controller)
    observation, _ = env.reset(seed=0)
    start = observation["observation.state"][1:7].astype(np.float64)
    action = np.concatenate([[0.0], start + [3.0, 0, 0, 0, 0, 0]]).astype(np.float32)
    for _ in range(40):
        observation, *_ = env.step(action)
    assert abs(observation["observation.state"][1] - action[1]) < 0.02
    env.close()
    fake_controller.stdin.close()
    said = fake_controller.stdout.read().splitlines()
    read = targets(said)
    # The first target is approached from where the arm was measured as the stream began,
    # which the arm, holding, may have left by a few micro-radians since the reset's
    # observation.
    first_period, first = read[0][1], read[0][2]
    assert np.abs(first - start).max() <= yarok.UR_JOINT_SPEED * first_period + 1e-5
    fastest = 0.0
    for (_, _, before), (_, period, joints) in zip(read, read[1:]):
        fastest = max(fastest, np.abs(joints - before).max() / period)
    # To the messages' resolution: a micro-radian at each end over a 50 ms period.
    assert fastest <= yarok.UR_JOINT_SPEED + 4e-5, fastest
    assert fastest > 0.9 * yarok.UR_JOINT_SPEED, fastest


def test_a_late_dashboard_never_stalls_the_stream(fake_controller):
    """The dashboard answering 0.3 s late (the once-a-second remote-control check runs beside
    the stream): 60 steps at 20 Hz reach the program as 60 targets, none more than 0.15 s after
    the one before and none in a burst."""
    env = real_env(fake_controller)
    observation, _ = env.reset(seed=0)
    start = observation["observation.state"][1:7].astype(np.float64)
    fake_controller.stdin.write("late dashboard 0.3\n")
    fake_controller.stdin.flush()
    for step in range(60):
        action = np.concatenate([[0.0], start + [0.005 * step, 0, 0, 0, 0, 0]]).astype(np.float32)
        env.step(action)
    env.close()
    fake_controller.stdin.close()
    said = fake_controller.stdout.read().splitlines()
    arrived = np.array([at for at, _, _ in targets(said)])
    assert len(arrived) == 60, said
    gaps = np.diff(arrived[1:])
    assert gaps.max() < 0.15, gaps
    assert gaps.min() > 0.005, gaps
