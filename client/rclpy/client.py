"""rclpy's Client: ``call_async`` (a Future), ``call`` (blocks this thread until the executor,
spinning in another, completes it), ``wait_for_service`` and the calls' introspection."""

from __future__ import annotations

import contextlib
import time
from typing import TYPE_CHECKING, Any

from node_runtime.bus import Future, ServiceClient
from node_runtime.msgs import Message
from rclpy._wait_set import Response
from rclpy.qos import QoSProfile, qos_profile_services_default
from rclpy.service_introspection import Introspection, ServiceIntrospectionState

if TYPE_CHECKING:
    from rclpy.callback_groups import CallbackGroup

WAIT_POLL_S = 0.02  # how often wait_for_service looks at the graph
REQUEST_SENT, RESPONSE_RECEIVED = 0, 3  # service_msgs/ServiceEventInfo's event types


class Client(ServiceClient):
    callback_group: CallbackGroup | None = None
    qos_profile: QoSProfile = qos_profile_services_default

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._introspection = Introspection(self)
        self._sequence = 0

    given_name: str | None = None  # the name as the node's code wrote it (rclpy's ``srv_name``)

    @property
    def srv_name(self) -> str:
        return self.given_name if self.given_name is not None else self.channel.name

    @property
    def service_name(self) -> str:
        """The name resolved (namespace, remappings), as the graph shows it."""
        return self.channel.name

    def wait_for_service(self, timeout_sec: float | None = None) -> bool:
        """True once a server of this service is in the graph; False after ``timeout_sec``."""
        end = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        while True:
            self._refresh_graph()
            if self.service_is_ready():
                return True
            if end is not None and time.monotonic() >= end:
                return False
            time.sleep(WAIT_POLL_S)

    def _refresh_graph(self) -> None:
        """Take in what the graph said while no thread spins (rclpy learns it in the background;
        here the executor's pass does, and a constructor waits before any spin)."""
        core = getattr(getattr(self.node, "_rcl_context", None), "executor", None)
        if core is not None and core.spinning_threads:
            return  # the spinning thread keeps the graph current
        bus = self.node._bus
        with bus.lock if bus.lock is not None else contextlib.nullcontext():
            for poll in list(bus.pollers):
                poll()

    def new_future(self) -> Future[Message]:
        return Response(self)  # completed by the executor that takes the response, as in rclpy

    def call_async(self, request: Message) -> Future[Message]:
        future = super().call_async(request)
        # As rclpy's client: the request is forgotten when it is done (a task of the executor then).
        future.add_done_callback(self.remove_pending_request)
        self._sequence += 1
        introspection = self._introspection
        if introspection.state is not ServiceIntrospectionState.OFF:
            sequence, gid = self._sequence, self.gid()
            introspection.emit(REQUEST_SENT, sequence, gid, request, None)

            def received(done: Future[Message]) -> None:
                if not done.cancelled() and done.exception() is None:
                    introspection.emit(RESPONSE_RECEIVED, sequence, gid, None, done.result())

            future.add_done_callback(received)
        return future

    def gid(self) -> bytes:
        """This client's GID on the graph (its token's), or zeros without one."""
        bridge = getattr(getattr(self.node, "_rcl_context", None), "bridge", None)
        gid = None if bridge is None else bridge.gid_of(self)
        return gid if gid is not None else bytes(16)

    def call(self, request: Message, timeout_sec: float | None = None) -> Any:
        """The response; for a caller on another thread than the executor's, as in rclpy (on the
        spinning thread itself it would wait for ever). TimeoutError if ``timeout_sec`` passes, as
        rclpy 9 raises."""
        future = self.call_async(request)
        if not future.wait(timeout_sec):
            self.remove_pending_request(future)
            raise TimeoutError()
        return future.result()

    def remove_pending_request(self, future: Future[Any]) -> None:
        future.cancel()

    def configure_introspection(
        self,
        clock: Any,
        service_event_qos_profile: QoSProfile,
        introspection_state: ServiceIntrospectionState,
    ) -> None:
        """Publish this client's calls on ``<service>/_service_event`` (OFF stops)."""
        self._introspection.configure(clock, service_event_qos_profile, introspection_state)

    def __enter__(self) -> Client:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.destroy()


__all__ = ["Client"]
