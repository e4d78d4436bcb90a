"""``rclpy.qos_overriding_options``: QoS policies a publisher or subscription lets the user set
with parameters, as rclpy declares them: read-only ``qos_overrides.<topic>.<publisher|
subscription>[_<id>].<policy>`` parameters whose values (``--ros-args -p``, a parameters file)
replace the profile's before the entity is made."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult

from rclpy import qos as qos_module
from rclpy.duration import Duration
from rclpy.exceptions import ParameterAlreadyDeclaredException
from rclpy.qos import QoSPolicyKind, QoSProfile

if TYPE_CHECKING:
    from rclpy.node import Node

QosCallbackResult = SetParametersResult
QosCallbackType = Callable[[QoSProfile], Any]

_ENUM_POLICIES = {
    QoSPolicyKind.HISTORY: "HistoryPolicy",
    QoSPolicyKind.RELIABILITY: "ReliabilityPolicy",
    QoSPolicyKind.DURABILITY: "DurabilityPolicy",
    QoSPolicyKind.LIVELINESS: "LivelinessPolicy",
}
_DURATION_POLICIES = (QoSPolicyKind.DEADLINE, QoSPolicyKind.LIFESPAN, QoSPolicyKind.LIVELINESS_LEASE_DURATION)


class InvalidQosOverridesError(Exception):
    """The options' callback refused the profile the overrides made."""


class QoSOverridingOptions:
    """Which policies get a parameter, a callback that checks the profile they make, and an id
    that tells apart two entities of one topic."""

    def __init__(
        self,
        policy_kinds: Iterable[QoSPolicyKind],
        *,
        callback: QosCallbackType | None = None,
        entity_id: str | None = None,
    ) -> None:
        self._policy_kinds = policy_kinds
        self._callback = callback
        self._entity_id = entity_id

    @property
    def policy_kinds(self) -> Iterable[QoSPolicyKind]:
        return self._policy_kinds

    @property
    def callback(self) -> QosCallbackType | None:
        return self._callback

    @property
    def entity_id(self) -> str | None:
        return self._entity_id

    @classmethod
    def with_default_policies(
        cls, *, callback: QosCallbackType | None = None, entity_id: str | None = None
    ) -> QoSOverridingOptions:
        """History, depth and reliability, as rclpy's."""
        kinds = (QoSPolicyKind.HISTORY, QoSPolicyKind.DEPTH, QoSPolicyKind.RELIABILITY)
        return cls(policy_kinds=kinds, callback=callback, entity_id=entity_id)


def _policy_value(qos: QoSProfile, policy: QoSPolicyKind) -> Any:
    value = getattr(qos, policy.name.lower())
    if policy in _ENUM_POLICIES:
        name = str(value.name).lower()
        if name == "unknown":
            raise ValueError("User provided QoS profile is invalid")
        return name
    if isinstance(value, Duration):
        return value.nanoseconds
    return value


def _apply(qos: QoSProfile, policy: QoSPolicyKind, value: Any) -> None:
    if policy in _ENUM_POLICIES:
        enum = getattr(qos_module, _ENUM_POLICIES[policy])
        try:
            value = enum[str(value).upper()]
        except KeyError:
            raise RuntimeError(
                f"Unexpected QoS override for policy `{policy.name.lower()}`: `{value}`"
            ) from None
    elif policy in _DURATION_POLICIES:
        value = Duration(nanoseconds=int(value))
    setattr(qos, policy.name.lower(), value)


def declare_qos_parameters(
    publisher: bool, node: Node, topic_name: str, qos: QoSProfile, options: QoSOverridingOptions
) -> None:
    """Declare the options' parameters on ``node`` and set ``qos`` from their values."""
    kind = "publisher" if publisher else "subscription"
    suffix = "" if options.entity_id is None else f"_{options.entity_id}"
    for policy in options.policy_kinds:
        if not publisher and policy is QoSPolicyKind.LIFESPAN:
            continue  # a subscription has no lifespan
        policy_name = policy.name.lower()
        name = f"qos_overrides.{topic_name}.{kind}{suffix}.{policy_name}"
        descriptor = ParameterDescriptor(
            description=f"{policy_name} for {kind} `{topic_name}` with id `{options.entity_id}`",
            read_only=True,
        )
        try:
            param = node.declare_parameter(name, _policy_value(qos, policy), descriptor)
        except ParameterAlreadyDeclaredException:
            param = node.get_parameter(name)
        _apply(qos, policy, param.value)
    if options.callback is not None:
        result = options.callback(qos)
        if not result.successful:
            raise InvalidQosOverridesError(
                f"Provided QoS overrides for {kind} `{topic_name}` with id `{options.entity_id}`, "
                f"are not valid: {result.reason}"
            )


__all__ = ["InvalidQosOverridesError", "QoSOverridingOptions", "QosCallbackResult", "QosCallbackType"]
