"""The showroom of this crate, exported to Python by ``yarok_py::module!``: opened by its tag,
made a Gymnasium environment by a task, and its turntable used by a template file."""

from __future__ import annotations

import math
from dataclasses import dataclass

from gymnasium.utils.env_checker import check_env
import numpy as np
import pytest
import yarok

import my_turntable_py

QUARTER_TURN = math.pi / 2


@dataclass
class TurnTheTable(yarok.Task):
    """Turn the showroom's turntable to a quarter turn; won within 0.02 rad of it."""

    world: str = "showroom"
    extension: str = "my_turntable_py"
    description: str = "turn the table a quarter turn"

    def bind(self, features) -> None:
        self.angle_index = features.state_names.index("table/hinge")

    def reward(self, observation, action) -> float:
        return -abs(float(observation["observation.state"][self.angle_index]) - QUARTER_TURN)

    def success(self, observation) -> bool:
        return self.reward(observation, None) > -0.02


def test_the_showroom_opens_by_its_tag_with_the_turntable_as_its_features():
    with my_turntable_py.World("showroom") as world:
        features = world.features
        assert features.state_names == ["table/hinge"]
        assert features.action_names == ["table/servo"]
        observation = world.reset(episode=0)
        assert observation["observation.state"] == pytest.approx([0.0], abs=1e-6)


def test_the_showroom_is_a_gymnasium_environment_whose_table_turns_to_the_action():
    env = yarok.YarokEnv(TurnTheTable())
    try:
        check_env(env, skip_render_check=True)
        observation, _ = env.reset(seed=0)
        assert not env.task.success(observation)
        for _ in range(60):  # 3 s at 20 Hz
            observation, reward, terminated, truncated, info = env.step(
                np.array([QUARTER_TURN], dtype=np.float32)
            )
            if terminated:
                break
        assert info["is_success"]
        assert observation["observation.state"][0] == pytest.approx(QUARTER_TURN, abs=0.02)
    finally:
        env.close()


def test_a_template_file_uses_the_turntable_by_its_tag(tmp_path):
    path = tmp_path / "two_tables.xml"
    path.write_text(
        """<mujoco>
  <worldbody>
    <turntable name="small" radius="0.1"/>
    <body pos="1 0 0"><turntable name="large" radius="0.3"/></body>
  </worldbody>
</mujoco>
"""
    )
    with my_turntable_py.World(str(path)) as world:
        assert world.features.state_names == ["small/hinge", "large/hinge"]
        world.reset(episode=0)
        observation = world.advance(2.0, action=[0.5, -0.5])
        assert observation["observation.state"] == pytest.approx([0.5, -0.5], abs=0.02)


def test_its_errors_are_yaroks_naming_its_worlds():
    with pytest.raises(yarok.YarokError, match='no world "showrom"; did you mean `showroom`'):
        my_turntable_py.World("showrom")
    assert my_turntable_py.YarokError is yarok.YarokError
    # `run` runs the bundled worlds' demo behaviours; the showroom has none to offer.
    with pytest.raises(yarok.YarokError, match='no bundled world "showroom"'):
        my_turntable_py.run("showroom")
