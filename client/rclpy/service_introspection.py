"""``rclpy.service_introspection``: a service's or client's events on ``<service>/_service_event``.

``configure_introspection(clock, qos, state)`` on a ``Service`` or ``Client`` publishes, for every
call, a ``<Srv>_Event`` message (service_msgs/ServiceEventInfo with the request and response
when the state is CONTENTS, without them at METADATA): a client says REQUEST_SENT and
RESPONSE_RECEIVED, a service REQUEST_RECEIVED and RESPONSE_SENT. OFF removes the publisher.
"""

from __future__ import annotations

from enum import IntEnum
from typing import Any

from server.msgs import Message, get_type

from .qos import QoSProfile

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

    def configure(self, clock: Any, qos: QoSProfile, state: ServiceIntrospectionState) -> None:
        state = ServiceIntrospectionState(state)
        event_type = getattr(self._entity.srv_type, "Event", None)
        if state is not ServiceIntrospectionState.OFF and event_type is None:
            raise RuntimeError(
                f"{self._entity.srv_type.TYPE} has no Event message in this lab's interfaces: "
                "service introspection cannot describe its calls"
            )
        node = self._entity.node
        if self._publisher is not None and state is ServiceIntrospectionState.OFF:
            node.destroy_publisher(self._publisher)
            self._publisher = None
        elif self._publisher is None and state is not ServiceIntrospectionState.OFF:
            self._publisher = node.create_publisher(
                event_type, self._entity.service_name + EVENT_SUFFIX, qos, event_callbacks=_no_events()
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
            event_type=kind, stamp=self._clock.now().to_msg(), client_gid=list(client_gid[:GID_BYTES]),
            sequence_number=sequence_number,
        )  # fmt: skip
        contents = self.state is ServiceIntrospectionState.CONTENTS
        event = publisher.msg_type(
            info=info,
            request=[request] if contents and request is not None else [],
            response=[response] if contents and response is not None else [],
        )
        publisher.publish(event)


def _no_events() -> Any:
    from .event_handler import PublisherEventCallbacks

    return PublisherEventCallbacks(use_default_callbacks=False)


__all__ = ["ServiceIntrospectionState"]
