"""Services on the bus, with rclpy's shape: ``create_service``, ``create_client``, ``call_async``.

A call never runs the server's callback inside ``call_async``: it is queued, and the executor
runs it as it runs subscription callbacks; the client's future completes when the callback
returns. A call to a service no node in this process serves goes to the bus's remote handler
(the Zenoh transport) when there is one; with none, it waits, as a ROS 2 call to an absent
service does (``wait_for_service`` tells the two apart).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from node_runtime.bus.errors import DestroyedError, TopicTypeError
from node_runtime.msgs import Message, Service

if TYPE_CHECKING:
    from node_runtime.bus.graph import Bus
    from node_runtime.bus.node import Node

T = TypeVar("T")
ServiceCallback = Callable[[Any, Any], Any]


_EVENT_MADE = threading.Lock()  # two threads that wait on one future share one event


class Future(Generic[T]):
    """rclpy's Future: a result (or exception) that arrives later; done callbacks run once it does."""

    def __init__(self) -> None:
        self._done = False
        self._cancelled = False
        self._result: T | None = None
        self._exception: BaseException | None = None
        self._callbacks: list[Callable[[Future[T]], Any]] = []
        # Made by the first ``wait``: most futures (an executor's task for each callback) are
        # never waited on by a thread, and an Event is a condition, a lock and their calls.
        self._event: threading.Event | None = None

    def done(self) -> bool:
        return self._done

    def cancelled(self) -> bool:
        return self._cancelled

    def cancel(self) -> None:
        if not self._done:
            self._cancelled = True
            self._finish()

    def result(self) -> T | None:
        """The result, or None while not done; raises the exception a failed call set."""
        if self._exception is not None:
            raise self._exception
        return self._result

    def exception(self) -> BaseException | None:
        return self._exception

    def set_result(self, result: T) -> None:
        if not self._done:
            self._result = result
            self._finish()

    def set_exception(self, exc: BaseException) -> None:
        if not self._done:
            self._exception = exc
            self._finish()

    def add_done_callback(self, callback: Callable[[Future[T]], Any]) -> None:
        if self._done:
            callback(self)
        else:
            self._callbacks.append(callback)

    def wait(self, timeout_s: float | None = None) -> bool:
        """Block this thread until done (for a caller on another thread than the executor)."""
        with _EVENT_MADE:
            if self._event is None:
                self._event = threading.Event()
            event = self._event
        # ``_finish`` marks the future done before it looks for the event: either it sees this
        # event and sets it, or it was done before this line.
        return True if self._done else event.wait(timeout_s)

    def _set_event(self) -> None:
        event = self._event
        if event is not None:
            event.set()

    def _finish(self) -> None:
        self._done = True
        self._set_event()
        callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            callback(self)


@dataclass
class PendingCall:
    """A request queued for a server's callback, and the future its client waits on."""

    server: ServiceServer
    request: Message
    future: Future[Message]


class ServiceChannel:
    """A named service with one type; exists while some node serves or calls it."""

    def __init__(self, bus: Bus, name: str, srv_type: type[Service]) -> None:
        self.bus = bus
        self.name = name
        self.srv_type = srv_type
        self.servers: list[ServiceServer] = []
        self.clients: list[ServiceClient] = []
        self.calls = 0


class ServiceServer:
    """What ``node.create_service`` returns: answers each request with ``callback(request, response)``."""

    def __init__(self, node: Node, channel: ServiceChannel, callback: ServiceCallback) -> None:
        self.node = node
        self.channel = channel
        self.srv_type = channel.srv_type
        self.callback = callback
        self.destroyed = False

    @property
    def srv_name(self) -> str:
        return self.channel.name

    @property
    def active(self) -> bool:
        return not self.destroyed and self.node._state == "active"

    def handle(self, request: Message) -> Message:
        """Run the callback for one request; the response it returns must be of the service's type."""
        response = self.callback(request, self.srv_type.Response())
        if type(response) is not self.srv_type.Response:
            raise TypeError(
                f"service {self.srv_name} callback returned {type(response).__name__}, "
                f"not {self.srv_type.Response.TYPE}"
            )
        return response

    def answer(self, call: PendingCall) -> None:
        """Answer a queued call (a server that answers later, as an action's result service does,
        overrides this and completes ``call.future`` itself)."""
        call.future.set_result(self.handle(call.request))

    def destroy(self) -> None:
        self.node.destroy_service(self)


class ServiceClient:
    """What ``node.create_client`` returns: ``call_async(request)`` gives a Future of the response."""

    def __init__(self, node: Node, channel: ServiceChannel) -> None:
        self.node = node
        self.channel = channel
        self.srv_type = channel.srv_type
        self.destroyed = False

    @property
    def srv_name(self) -> str:
        return self.channel.name

    def service_is_ready(self) -> bool:
        bus = self.node._bus
        if any(s.active for s in self.channel.servers):
            return True
        remote = bus.remote_services
        return remote is not None and remote.has_server(self.channel.name, self.srv_type)

    def new_future(self) -> Future[Message]:
        """The future a call completes (rclpy's client gives one its executor completes)."""
        return Future()

    def call_async(self, request: Message) -> Future[Message]:
        if self.destroyed:
            raise DestroyedError(f"client of {self.srv_name} was destroyed")
        if type(request) is not self.srv_type.Request:
            raise TopicTypeError(
                f"service {self.srv_name} takes {self.srv_type.Request.TYPE}, not {type(request).__name__}"
            )
        future = self.new_future()
        request = request.copy()
        self.channel.calls += 1
        server = next((s for s in self.channel.servers if s.active), None)
        bus = self.node._bus
        if server is not None:
            bus.queue_call(PendingCall(server, request, future))
        elif bus.remote_services is not None:
            bus.remote_services.call(self, request, future)
        return future

    def destroy(self) -> None:
        self.node.destroy_client(self)


def check_service_type(channel: ServiceChannel, srv_type: type[Service]) -> None:
    if channel.srv_type is not srv_type:
        raise TopicTypeError(
            f"service {channel.name} is a {channel.srv_type.TYPE}; {srv_type.TYPE} conflicts with it"
        )
