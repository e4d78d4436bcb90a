"""``rclpy.service_introspection``: a service's or client's events on ``<service>/_service_event``.

``configure_introspection(clock, qos, state)`` on a ``Service`` or ``Client`` publishes, for every
call, a ``<Srv>_Event`` message (service_msgs/ServiceEventInfo with the request and response
when the state is CONTENTS, without them at METADATA): a client says REQUEST_SENT and
RESPONSE_RECEIVED, a service REQUEST_RECEIVED and RESPONSE_SENT. OFF removes the publisher.
"""

from __future__ import annotations

from enum import IntEnum
from typing import Any

from node_runtime.msgs import Message, get_type
from rclpy.qos import QoSProfile

EVENT_SUFFIX = "/_service_event"
GID_BYTES = 16


class ServiceIntrospectionState(IntEnum):
    OFF = 0
    METADATA = 1
    CONTENTS = 2


class Introspection:
    """The event publisher of one service or client, while its introspection is on."""

    def __init__(self, entity: Any) -> None:
        self._entity = entity
        self.state = ServiceIntrospectionState.OFF
        self._publisher: Any = None
        self._clock: Any = None
        self.calls = 0  # a service's requests so far (the number its events carry)

    def configure(self, clock: Any, qos: QoSProfile, state: ServiceIntrospectionState) -> None:
        state = ServiceIntrospectionState(state)
        node = self._entity.node
        if self._publisher is not None and state is ServiceIntrospectionState.OFF:
            node.destroy_publisher(self._publisher)
            self._publisher = None
        elif self._publisher is None and state is not ServiceIntrospectionState.OFF:
            self._publisher = node.create_publisher(
                event_message(self._entity.srv_type),
                self._entity.service_name + EVENT_SUFFIX,
                qos,
                event_callbacks=_no_events(),
            )
        self.state, self._clock = state, clock

    def emit(
        self,
        kind: int,
        sequence_number: int,
        client_gid: bytes,
        request: Message | None,
        response: Message | None,
    ) -> None:
        """Publish one event (``kind``: ServiceEventInfo's REQUEST_SENT ...), if introspection is on."""
        publisher = self._publisher
        if publisher is None or publisher.destroyed:
            return
        info = get_type("service_msgs/msg/ServiceEventInfo")(
            event_type=kind,
            stamp=self._clock.now().to_msg(),
            client_gid=list(client_gid[:GID_BYTES]),
            sequence_number=sequence_number,
        )
        contents = self.state is ServiceIntrospectionState.CONTENTS
        event = publisher.msg_type(
            info=info,
            request=[request] if contents and request is not None else [],
            response=[response] if contents and response is not None else [],
        )
        publisher.publish(event)


_EVENTS: dict[str, type[Message]] = {}


def event_message(srv_type: Any) -> type[Message]:
    """``<Srv>.Event``, the message a service's events travel in: the service type's own if its
    package declares it, else made here once as rosidl makes it (the info, then at most one
    request and one response)."""
    declared = getattr(srv_type, "Event", None)
    if declared is not None:
        return declared  # type: ignore[no-any-return]
    name = f"{srv_type.TYPE}_Event"
    if name not in _EVENTS:
        from node_runtime.msgs._base import define_message
        from node_runtime.msgs.idl import parse_message

        text = (
            f"service_msgs/ServiceEventInfo info\n{srv_type.Request.TYPE}[<=1] request\n"
            f"{srv_type.Response.TYPE}[<=1] response\n"
        )
        module = srv_type.__module__ if srv_type.__module__.endswith(".srv") else __name__
        _EVENTS[name] = define_message(parse_message(name, text), module)
    return _EVENTS[name]


def _no_events() -> Any:
    from rclpy.event_handler import PublisherEventCallbacks

    return PublisherEventCallbacks(use_default_callbacks=False)


__all__ = ["ServiceIntrospectionState"]
