"""Type information for yarok's native extension, built from Rust with PyO3: worlds stepped
from Python, their features, and ``run`` for a bundled world's behaviour."""

from os import PathLike
from typing import Any, Sequence, final

import numpy.typing as npt

__all__ = [
    "YarokError",
    "Features",
    "World",
    "Worlds",
    "run",
    "after_fork_in_child",
    "use_bundled_mujoco",
    "DIGIT_WORLD_START_REGION",
    "DIGIT_WORLD_START_YAW",
    "UR_JOINT_SPEED",
]

_Observation = dict[str, npt.NDArray[Any]]
"""Observation keys (``observation.state``, ``observation.images.…``) to numpy arrays."""

_Placement = tuple[str, Sequence[float], Sequence[float]]
"""A free body's name, its position (x, y, z) and orientation quaternion (w, x, y, z)."""

class YarokError(RuntimeError):
    """What yarok refused or what failed in a world, in yarok's words."""

@final
class Features:
    """What a world's observations and actions hold."""

    @property
    def state_names(self) -> list[str]: ...
    @property
    def environment_names(self) -> list[str]: ...
    @property
    def images(self) -> list[tuple[str, tuple[int, int, int]]]: ...
    @property
    def action_names(self) -> list[str]: ...
    @property
    def action_ranges(self) -> list[tuple[float, float]]: ...
    @property
    def timestep(self) -> float: ...

@final
class World:
    """One world, stepped from Python on a thread of its own."""

    def __new__(
        cls,
        world: str,
        env: str = "sim",
        settings: Sequence[str] = ...,
        config: Sequence[str] = ...,
        cameras: Sequence[str] = ...,
        camera_size: tuple[int, int] = ...,
    ) -> World: ...
    def reset(self, episode: int, placements: Sequence[_Placement] = ...) -> _Observation: ...
    def step(self, action: npt.ArrayLike | None = None, ticks: int = 1) -> _Observation: ...
    def advance(self, seconds: float, action: npt.ArrayLike | None = None) -> _Observation: ...
    def advance_periods(
        self, periods: int, seconds: float, action: npt.ArrayLike | None = None
    ) -> _Observation: ...
    def close(self) -> None: ...
    def __enter__(self) -> World: ...
    def __exit__(self, *_exception: object) -> bool: ...
    @property
    def features(self) -> Features: ...
    @property
    def time(self) -> float: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def ticks(self) -> int: ...

@final
class Worlds:
    """``count`` copies of one world, stepped together on threads of their own."""

    def __new__(
        cls,
        world: str,
        count: int,
        env: str = "sim",
        settings: Sequence[str] = ...,
        config: Sequence[str] = ...,
        cameras: Sequence[str] = ...,
        camera_size: tuple[int, int] = ...,
    ) -> Worlds: ...
    def reset(
        self, worlds: Sequence[tuple[int, int, Sequence[_Placement]]]
    ) -> list[_Observation]: ...
    def advance(
        self, seconds: float, actions: Sequence[npt.ArrayLike | None]
    ) -> list[_Observation]: ...
    def close(self) -> None: ...
    @property
    def features(self) -> Features: ...
    @property
    def warnings(self) -> list[list[str]]: ...
    def __len__(self) -> int: ...

def run(
    world: str,
    behaviour: str | None = None,
    env: str = "sim",
    settings: Sequence[str] = ...,
    config: Sequence[str] = ...,
    dataset: str | PathLike[str] | None = None,
) -> None: ...
def after_fork_in_child() -> None: ...
def use_bundled_mujoco(dir: str | PathLike[str]) -> bool: ...

DIGIT_WORLD_START_REGION: list[list[float]]
DIGIT_WORLD_START_YAW: float
UR_JOINT_SPEED: float
