"""The checkpoints a lab checks: this lab's three, then any a lab adds by name (``module:NAME``)."""

from __future__ import annotations

import importlib
from collections.abc import Iterable

from server.world.checkpoints import fly_to_point, keyboard_abort, launch_and_keys
from server.world.checkpoints.declared import Checkpoint

LAB_CHECKPOINTS: tuple[Checkpoint, ...] = (
    keyboard_abort.CHECKPOINT,
    fly_to_point.CHECKPOINT,
    launch_and_keys.CHECKPOINT,
)


class CheckpointLoadError(ValueError):
    pass


def load(extra: Iterable[str] = ()) -> tuple[Checkpoint, ...]:
    """The lab's checkpoints and those ``extra`` names (``package.module:NAME``), in that order."""
    out = list(LAB_CHECKPOINTS)
    for spec in extra:
        module_name, _, attr = spec.partition(":")
        try:
            found = getattr(importlib.import_module(module_name), attr)
        except (ImportError, AttributeError, ValueError) as exc:
            raise CheckpointLoadError(f"checkpoint {spec!r}: {exc}") from None
        if not isinstance(found, Checkpoint):
            raise CheckpointLoadError(f"checkpoint {spec!r} is a {type(found).__name__}, not a Checkpoint")
        if any(c.name == found.name for c in out):
            raise CheckpointLoadError(f"checkpoint {spec!r}: the name {found.name!r} is taken")
        out.append(found)
    return tuple(out)
