"""rclpy's callback groups: when an executor may run a callback.

Before it hands out an entity's callback an executor asks the entity's group ``can_execute``;
the task that runs it asks ``beginning_execution`` (and, refused, leaves the entity ready for
later) and calls ``ending_execution`` once the callback is over, an ``async def`` one included.
Callbacks of one MutuallyExclusiveCallbackGroup run one at a time; those of a
ReentrantCallbackGroup side by side. A node's callbacks without a group go to its default group
(mutually exclusive), as in rclpy. A custom group subclasses CallbackGroup and defines the three.
"""

from __future__ import annotations

import threading
import weakref
from collections.abc import Callable
from typing import Any


class CallbackGroup:
    """The base of a group: define ``can_execute``, ``beginning_execution`` and ``ending_execution``."""

    def __init__(self) -> None:
        super().__init__()
        self.entities: set[weakref.ref[Any]] = set()

    def add_entity(self, entity: object) -> None:
        self.entities.add(weakref.ref(entity))

    def has_entity(self, entity: object) -> bool:
        return weakref.ref(entity) in self.entities

    def can_execute(self, entity: Any) -> bool:
        raise NotImplementedError()

    def beginning_execution(self, entity: Any) -> bool:
        raise NotImplementedError()

    def ending_execution(self, entity: Any) -> None:
        raise NotImplementedError()


class ReentrantCallbackGroup(CallbackGroup):
    """Its callbacks run whenever they are ready, side by side on a MultiThreadedExecutor."""

    def can_execute(self, entity: Any) -> bool:
        return True

    def beginning_execution(self, entity: Any) -> bool:
        return True

    def ending_execution(self, entity: Any) -> None:
        pass


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    """One of its callbacks at a time."""

    def __init__(self) -> None:
        super().__init__()
        self._active_entity: Any = None
        self._lock = threading.Lock()

    def can_execute(self, entity: Any) -> bool:
        with self._lock:
            return self._active_entity is None

    def beginning_execution(self, entity: Any) -> bool:
        with self._lock:
            if self._active_entity is None:
                self._active_entity = entity
                return True
        return False

    def ending_execution(self, entity: Any) -> None:
        with self._lock:
            self._active_entity = None


class GroupedCallback:
    """A callback that knows its group (what a node hands the bus)."""

    __slots__ = ("callback", "callback_group")

    def __init__(self, callback: Callable[..., Any], callback_group: CallbackGroup) -> None:
        self.callback = callback
        self.callback_group = callback_group

    def __call__(self, *args: Any) -> Any:
        return self.callback(*args)

    def __repr__(self) -> str:  # what a fault report names
        return getattr(self.callback, "__qualname__", repr(self.callback))


__all__ = ["CallbackGroup", "GroupedCallback", "MutuallyExclusiveCallbackGroup", "ReentrantCallbackGroup"]
