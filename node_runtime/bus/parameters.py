"""A bus node's parameters: declared with a value and, optionally, a ParameterDescriptor (read-only,
a range), given by a launch's overrides, listed, described and set as rclpy's node does. A set
that the descriptor, the type (an integer for a double too, as rclpy) or the node's own on-set
callback refuses changes nothing and raises ValueError with the reason; ``node_runtime.bus.parameter_service``
answers ROS 2's parameter services from these.

As an rclpy node, each declares ``use_sim_time`` (false) when it is created and publishes a
``rcl_interfaces/msg/ParameterEvent`` on ``/parameter_events`` for each declaration and each
successful set (what is new, changed or deleted, with the node's name and the bus's time): only
then, never on a tick of the loop."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from node_runtime.bus.parameter_checks import override_as_declared, refusal
from node_runtime.bus.parameter_values import parameter_event, to_value_msg, type_of
from node_runtime.msgs.generated.rcl_interfaces import Parameter as ParameterMsg
from node_runtime.msgs.generated.rcl_interfaces import ParameterDescriptor, ParameterEvent

if TYPE_CHECKING:
    from node_runtime.bus.clock import NodeClock
    from node_runtime.bus.endpoints import Publisher

SEPARATOR = "."
PARAMETER_EVENTS = "/parameter_events"
PARAMETER_EVENTS_DEPTH = 1000  # rclpy's qos_profile_parameter_events keeps the last 1000


@dataclass
class Parameter:
    """rclpy's Parameter, reduced to what lab nodes use: a name and a value."""

    name: str
    value: Any


class NodeParameters:
    """Mixed into the bus's Node: its parameter table and rclpy's calls on it."""

    if TYPE_CHECKING:

        @property
        def fully_qualified_name(self) -> str: ...

        def get_clock(self) -> NodeClock: ...

        def create_publisher(
            self, msg_type: Any, topic: str, qos_profile: Any, *, hand_over: bool = ...
        ) -> Publisher: ...

    _parameters: dict[str, Parameter]
    _param_overrides: dict[str, Any]
    _param_callbacks: list[Callable[[list[Parameter]], Any]]
    _descriptors: dict[str, ParameterDescriptor]
    _parameter_events: Publisher | None = None

    def _start_parameters(self) -> None:
        """What rclpy's node does when it is created: its publisher on ``/parameter_events``, then
        ``use_sim_time`` declared (false; the lab's nodes run on the bus's clock whatever it says)."""
        self._parameter_events = self.create_publisher(
            ParameterEvent, PARAMETER_EVENTS, PARAMETER_EVENTS_DEPTH, hand_over=True
        )
        self.declare_parameter("use_sim_time", False)

    def declare_parameter(
        self, name: str, value: Any = None, descriptor: ParameterDescriptor | None = None, *_: Any, **__: Any
    ) -> Parameter:
        """Declare ``name`` with ``value`` (a launch's override wins, checked against the descriptor:
        ValueError, and the node does not start, for an override it does not allow)."""
        described = (descriptor or ParameterDescriptor()).copy()
        described.name = name
        if value is None:
            described.dynamic_typing = True
        elif not described.type:
            described.type = type_of(value)
        if name in self._param_overrides:
            value = override_as_declared(self._param_overrides[name], described)
            reason = refusal(name, value, described, check_read_only=False, declared=False)
            if reason is not None:
                raise ValueError(f"{self.fully_qualified_name}: parameter {name!r}: {reason}")
        param = Parameter(name, value)
        self._parameters[name] = param
        self._descriptors[name] = described
        self._publish_event(new=[param])
        return param

    def get_parameter(self, name: str) -> Parameter:
        try:
            return self._parameters[name]
        except KeyError:
            raise LookupError(f"parameter {name!r} of {self.fully_qualified_name} was not declared") from None

    def has_parameter(self, name: str) -> bool:
        return name in self._parameters

    def get_parameters_dict(self) -> dict[str, Any]:
        return {name: p.value for name, p in self._parameters.items()}

    def describe_parameter(self, name: str) -> ParameterDescriptor:
        """A copy of ``name``'s descriptor, its type the value's when dynamically typed."""
        self.get_parameter(name)
        described: ParameterDescriptor = self._descriptors[name].copy()
        if described.dynamic_typing:
            described.type = type_of(self._parameters[name].value)
        return described

    def list_parameter_names(self, prefixes: Sequence[str], depth: int) -> tuple[list[str], list[str]]:
        """rclpy's list_parameters: names under ``prefixes`` (all if none), at most ``depth``
        separators below them (0: any), and the prefixes of those names."""
        if depth < 0:
            raise ValueError("The depth must be greater than or equal to zero")

        def shallow(name: str) -> bool:
            return depth == 0 or name.count(SEPARATOR) < depth

        def wanted(name: str) -> bool:
            if not prefixes:
                return shallow(name)
            return any(
                name == p or (name.startswith(p + SEPARATOR) and shallow(name[len(p) + 1 :]))
                for p in prefixes
            )

        names = [n for n in self._parameters if wanted(n)]
        found: list[str] = []
        for name in names:
            prefix = name.rpartition(SEPARATOR)[0]
            if prefix and prefix not in found:
                found.append(prefix)
        return names, found

    def add_on_set_parameters_callback(self, callback: Callable[[list[Parameter]], Any]) -> None:
        """``callback(params)`` may refuse a change by returning a falsy result (or one with
        ``successful = False`` and a ``reason``), or by raising ValueError, as rclpy's
        SetParametersResult does."""
        self._param_callbacks.append(callback)

    def set_parameters(self, params: list[Parameter]) -> None:
        """Set declared parameters, all or none; ValueError (changing nothing) names a refusal."""
        checked: list[Parameter] = []
        for param in params:
            self.get_parameter(param.name)
            reason = refusal(param.name, param.value, self._descriptors[param.name])
            if reason is not None:
                raise ValueError(reason)
            checked.append(Parameter(param.name, param.value))
        for callback in self._param_callbacks:
            result = callback(checked)
            if result is not None and not getattr(result, "successful", bool(result)):
                raise ValueError(getattr(result, "reason", "") or "parameter change refused by the node")
        new: list[Parameter] = []
        changed: list[Parameter] = []
        deleted: list[Parameter] = []
        for param in checked:
            held = self._parameters[param.name]
            if param.value is None:  # a dynamically typed parameter set to nothing is undeclared
                del self._parameters[param.name], self._descriptors[param.name]
                deleted.append(param)
                continue
            (new if held.value is None else changed).append(param)
            held.value = param.value
        self._publish_event(new, changed, deleted)

    def _publish_event(
        self,
        new: Sequence[Parameter] = (),
        changed: Sequence[Parameter] = (),
        deleted: Sequence[Parameter] = (),
    ) -> None:
        """One ParameterEvent for one declaration or one set, as rclpy publishes it."""
        publisher = self._parameter_events
        if publisher is None or publisher.destroyed:
            return
        publisher.publish(
            parameter_event(
                self.fully_qualified_name,
                self.get_clock().now().to_msg(),
                [_message(p) for p in new],
                [_message(p) for p in changed],
                [_message(p) for p in deleted],
            )
        )


def _message(param: Parameter) -> ParameterMsg:
    return ParameterMsg(name=param.name, value=to_value_msg(param.value))


__all__ = ["PARAMETER_EVENTS", "SEPARATOR", "NodeParameters", "Parameter"]
