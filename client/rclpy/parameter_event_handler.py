"""``rclpy.parameter_event_handler``: callbacks on /parameter_events, for one parameter of one node
or for every event (the docs' "Monitoring for parameter changes" tutorial)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from rcl_interfaces.msg import Parameter as ParameterMsg
from rcl_interfaces.msg import ParameterEvent

from rclpy.qos import QoSProfile, qos_profile_parameter_events


class ParameterCallbackHandle:
    """What add_parameter_callback gives back, for remove_parameter_callback."""

    def __init__(self, parameter_name: str, node_name: str, callback: Callable[[ParameterMsg], Any]) -> None:
        self.parameter_name = parameter_name
        self.node_name = node_name
        self.callback = callback


class ParameterEventCallbackHandle:
    """What add_parameter_event_callback gives back, for remove_parameter_event_callback."""

    def __init__(self, callback: Callable[[ParameterEvent], Any]) -> None:
        self.callback = callback


class ParameterEventHandler:
    """Subscribes to /parameter_events for ``node``; each event first reaches the callbacks of the
    parameters it declares or changes, then every event callback, the latest added first."""

    def __init__(
        self, node: Any, qos_profile: QoSProfile = qos_profile_parameter_events, callback_group: Any = None
    ) -> None:
        self.node = node
        self._parameter_callbacks: dict[tuple[str, str], list[ParameterCallbackHandle]] = {}
        self._event_callbacks: list[ParameterEventCallbackHandle] = []
        self.parameter_event_subscription = node.create_subscription(
            ParameterEvent, "/parameter_events", self._on_event, qos_profile, callback_group=callback_group
        )

    def destroy(self) -> None:
        self.node.destroy_subscription(self.parameter_event_subscription)

    def _resolved(self, node_name: str) -> str:
        """A node name as events carry it: a relative one is in this node's namespace."""
        if node_name.startswith("/"):
            return node_name
        namespace: str = self.node.get_namespace()
        return namespace.rstrip("/") + "/" + node_name

    def add_parameter_callback(
        self, parameter_name: str, node_name: str, callback: Callable[[ParameterMsg], Any]
    ) -> ParameterCallbackHandle:
        handle = ParameterCallbackHandle(parameter_name, self._resolved(node_name), callback)
        self._parameter_callbacks.setdefault((parameter_name, handle.node_name), []).insert(0, handle)
        return handle

    def remove_parameter_callback(self, handle: ParameterCallbackHandle) -> None:
        key = (handle.parameter_name, handle.node_name)
        handles = self._parameter_callbacks.get(key, [])
        if handle not in handles:
            raise RuntimeError("Callback doesn't exist")
        handles.remove(handle)
        if not handles:
            del self._parameter_callbacks[key]

    def add_parameter_event_callback(
        self, callback: Callable[[ParameterEvent], Any]
    ) -> ParameterEventCallbackHandle:
        handle = ParameterEventCallbackHandle(callback)
        self._event_callbacks.insert(0, handle)
        return handle

    def remove_parameter_event_callback(self, handle: ParameterEventCallbackHandle) -> None:
        if handle not in self._event_callbacks:
            raise RuntimeError("Callback doesn't exist")
        self._event_callbacks.remove(handle)

    def _on_event(self, event: ParameterEvent) -> None:
        for (name, node_name), handles in list(self._parameter_callbacks.items()):
            parameter = self.get_parameter_from_event(event, name, node_name)
            if parameter is not None:
                for handle in list(handles):
                    handle.callback(parameter)
        for event_handle in list(self._event_callbacks):
            event_handle.callback(event)

    @staticmethod
    def get_parameter_from_event(
        event: ParameterEvent, parameter_name: str, node_name: str
    ) -> ParameterMsg | None:
        """The parameter ``parameter_name`` as ``event`` declares or changes it, if it is of ``node_name``."""
        if event.node != node_name:
            return None
        for parameter in [*event.new_parameters, *event.changed_parameters]:
            if parameter.name == parameter_name:
                return parameter
        return None

    @staticmethod
    def get_parameters_from_event(event: ParameterEvent) -> list[ParameterMsg]:
        """Every parameter ``event`` declares or changes."""
        return [*event.new_parameters, *event.changed_parameters]


__all__ = ["ParameterCallbackHandle", "ParameterEventCallbackHandle", "ParameterEventHandler"]
