"""rclpy's callback groups: what a MultiThreadedExecutor may run at the same time.

Callbacks of one MutuallyExclusiveCallbackGroup run one at a time; those of a
ReentrantCallbackGroup may run in parallel with each other. A node's callbacks without a group go
to its default group (mutually exclusive), as in rclpy. A SingleThreadedExecutor runs everything
one at a time anyway.
"""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Callable, Iterator
from typing import Any


class CallbackGroup:
    def __init__(self) -> None:
        self.entities: list[object] = []

    def add_entity(self, entity: object) -> None:
        self.entities.append(entity)

    def has_entity(self, entity: object) -> bool:
        return any(e is entity for e in self.entities)

    def hold(self) -> contextlib.AbstractContextManager[None]:
        """Held while one of the group's callbacks runs."""
        return contextlib.nullcontext()


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    def __init__(self) -> None:
        super().__init__()
        self._lock = threading.Lock()

    @contextlib.contextmanager
    def hold(self) -> Iterator[None]:
        with self._lock:
            yield


class ReentrantCallbackGroup(CallbackGroup):
    pass


class GroupedCallback:
    """A callback that knows its group (what a node hands the executor)."""

    __slots__ = ("callback", "callback_group")

    def __init__(self, callback: Callable[..., Any], callback_group: CallbackGroup) -> None:
        self.callback = callback
        self.callback_group = callback_group

    def __call__(self, *args: Any) -> Any:
        return self.callback(*args)

    def __repr__(self) -> str:  # what a fault report names
        return getattr(self.callback, "__qualname__", repr(self.callback))


__all__ = ["CallbackGroup", "GroupedCallback", "MutuallyExclusiveCallbackGroup", "ReentrantCallbackGroup"]
