"""rclpy's GuardCondition: ``trigger()`` from any thread has the executor run its callback once."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, cast

from node_runtime.bus import Future
from node_runtime.bus.services import PendingCall, ServiceServer
from rclpy.callback_groups import CallbackGroup, GroupedCallback

if TYPE_CHECKING:
    from node_runtime.bus import Node


class GuardCondition:
    """Queued on the bus as a call is, so the executor (any of them) runs ``callback`` in its
    group; triggers that come before it runs collapse into one run, as rcl's do."""

    def __init__(self, node: Node, callback: Callable[[], Any] | None, callback_group: CallbackGroup) -> None:
        self.node = node
        self.callback = GroupedCallback(callback or (lambda: None), callback_group)
        self.callback_group = callback_group
        self.destroyed = False
        self._pending = False

    @property
    def active(self) -> bool:
        return not self.destroyed and self.node._state == "active"

    def handle(self, _request: object) -> object:
        """Run the callback; what it returned (the coroutine of an ``async def`` one, to await)."""
        self._pending = False
        return self.callback()

    def answer(self, _call: PendingCall) -> object:
        return self.handle(None)

    def trigger(self) -> None:
        if self.destroyed or self._pending:
            return
        self._pending = True
        bus = self.node._bus
        call = PendingCall(cast(ServiceServer, self), cast(Any, None), Future())
        if bus.lock is None:
            bus.queue_call(call)
        else:
            with bus.lock:
                bus.queue_call(call)
        bus.wake_threadsafe()

    def destroy(self) -> None:
        self.destroyed = True


__all__ = ["GuardCondition"]
