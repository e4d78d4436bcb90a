"""``rclpy.service.Service``: what ``node.create_service`` returns, the bus's service server with
rclpy's properties (``srv_name``, ``service_name``, ``qos_profile``) and its introspection."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from node_runtime.bus import ServiceServer
from node_runtime.msgs import Message
from rclpy.qos import QoSProfile, qos_profile_services_default
from rclpy.service_introspection import Introspection, ServiceIntrospectionState

if TYPE_CHECKING:
    from rclpy.callback_groups import CallbackGroup

# service_msgs/ServiceEventInfo's event types
REQUEST_RECEIVED, RESPONSE_SENT = 1, 2
NO_CLIENT = bytes(16)


class Service(ServiceServer):
    """Answers each request with ``callback(request, response)``."""

    callback_group: CallbackGroup | None = None
    qos_profile: QoSProfile = qos_profile_services_default

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._introspection = Introspection(self)

    given_name: str | None = None  # the name as the node's code wrote it (rclpy's ``srv_name``)

    @property
    def srv_name(self) -> str:
        return self.given_name if self.given_name is not None else self.channel.name

    @property
    def service_name(self) -> str:
        """The name resolved (namespace, remappings), as the graph shows it."""
        return self.channel.name

    def handle(self, request: Message) -> Message:
        if self._introspection.state is ServiceIntrospectionState.OFF:
            return super().handle(request)
        # The bus hands a service its request alone: the calling client's GID and number stay unknown.
        # Counted on the shared introspection: an async service answers through a copy of itself.
        introspection = self._introspection
        introspection.calls += 1
        number = introspection.calls
        introspection.emit(REQUEST_RECEIVED, number, NO_CLIENT, request, None)
        response = super().handle(request)
        introspection.emit(RESPONSE_SENT, number, NO_CLIENT, None, response)
        return response

    def configure_introspection(
        self,
        clock: Any,
        service_event_qos_profile: QoSProfile,
        introspection_state: ServiceIntrospectionState,
    ) -> None:
        """Publish this service's calls on ``<service>/_service_event`` (OFF stops)."""
        self._introspection.configure(clock, service_event_qos_profile, introspection_state)

    def __enter__(self) -> Service:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.destroy()


__all__ = ["Service"]
