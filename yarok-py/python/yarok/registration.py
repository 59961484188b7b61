"""The Gymnasium ids of yarok's tasks."""

import gymnasium

ENVIRONMENTS = {
    "yarok/PickPlace-v0": ("yarok.tasks:PickPlace", 400),
    "yarok/TactilePress-v0": ("yarok.tasks:TactilePress", 100),
}


def _make(task: str, **kwargs):
    from importlib import import_module

    from .env import YarokEnv

    module, name = task.split(":")
    task_kwargs = kwargs.pop("task_kwargs", {})
    return YarokEnv(getattr(import_module(module), name)(**task_kwargs), **kwargs)


def register_environments() -> None:
    """Registers ``yarok/PickPlace-v0`` and ``yarok/TactilePress-v0`` (done on import)."""
    for env_id, (task, steps) in ENVIRONMENTS.items():
        if env_id not in gymnasium.registry:
            gymnasium.register(
                env_id,
                entry_point="yarok.registration:_make",
                kwargs={"task": task},
                max_episode_steps=steps,
            )
