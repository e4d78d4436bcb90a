"""rclpy's middleware events: ``event_callbacks=`` on ``create_publisher`` and ``create_subscription``.

Delivered: matched (a publisher and a subscription of the topic and type meet or part, in this
process or another), incompatible QoS (a peer whose reliability, durability or deadline DDS
would refuse; by default a warning, as rclpy logs it) and deadline missed (a period of the
profile's deadline without a message). Accepted and never raised, as the lab's transport cannot
tell them: liveliness, message lost, incompatible type. Each event's callback runs on the
executor in the entity's callback group, with what changed since it last ran.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import IntEnum
from typing import TYPE_CHECKING, Any

from node_runtime.bus import Publisher as BusPublisher
from rclpy._matching import incompatible_peers, peers
from rclpy.guard_condition import GuardCondition
from rclpy.logging import get_logger
from rclpy.qos import QoSPolicyKind, qos_policy_name_from_kind

if TYPE_CHECKING:
    from rclpy.callback_groups import CallbackGroup


class QoSPublisherEventType(IntEnum):
    RCL_PUBLISHER_OFFERED_DEADLINE_MISSED = 0
    RCL_PUBLISHER_LIVELINESS_LOST = 1
    RCL_PUBLISHER_OFFERED_INCOMPATIBLE_QOS = 2
    RCL_PUBLISHER_INCOMPATIBLE_TYPE = 3
    RCL_PUBLISHER_MATCHED = 4


class QoSSubscriptionEventType(IntEnum):
    RCL_SUBSCRIPTION_REQUESTED_DEADLINE_MISSED = 0
    RCL_SUBSCRIPTION_LIVELINESS_CHANGED = 1
    RCL_SUBSCRIPTION_REQUESTED_INCOMPATIBLE_QOS = 2
    RCL_SUBSCRIPTION_MESSAGE_LOST = 3
    RCL_SUBSCRIPTION_INCOMPATIBLE_TYPE = 4
    RCL_SUBSCRIPTION_MATCHED = 5


class UnsupportedEventTypeError(Exception):
    """An event the middleware cannot raise (rclpy's; the lab accepts every event instead)."""


# The events' infos, named as rclpy's (the rmw structs its bindings expose) and by rclpy's aliases.
@dataclass
class _Counted:
    total_count: int = 0
    total_count_change: int = 0


class rmw_requested_deadline_missed_status_t(_Counted):
    pass


class rmw_offered_deadline_missed_status_t(_Counted):
    pass


class rmw_liveliness_lost_status_t(_Counted):
    pass


class rmw_message_lost_status_t(_Counted):
    pass


class rmw_incompatible_type_status_t(_Counted):
    pass


@dataclass
class rmw_liveliness_changed_status_t:
    alive_count: int = 0
    not_alive_count: int = 0
    alive_count_change: int = 0
    not_alive_count_change: int = 0


@dataclass
class rmw_requested_qos_incompatible_event_status_t(_Counted):
    last_policy_kind: QoSPolicyKind = QoSPolicyKind.INVALID


@dataclass
class rmw_matched_status_t(_Counted):
    current_count: int = 0
    current_count_change: int = 0


QoSRequestedDeadlineMissedInfo = rmw_requested_deadline_missed_status_t
QoSOfferedDeadlineMissedInfo = rmw_offered_deadline_missed_status_t
QoSLivelinessLostInfo = rmw_liveliness_lost_status_t
QoSMessageLostInfo = rmw_message_lost_status_t
IncompatibleTypeInfo = rmw_incompatible_type_status_t
QoSLivelinessChangedInfo = rmw_liveliness_changed_status_t
QoSRequestedIncompatibleQoSInfo = rmw_requested_qos_incompatible_event_status_t
QoSOfferedIncompatibleQoSInfo = QoSRequestedIncompatibleQoSInfo
QoSSubscriptionMatchedInfo = rmw_matched_status_t
QoSPublisherMatchedInfo = rmw_matched_status_t


class EventHandler:
    """One event of one publisher or subscription: it looks again whenever the graph changes (or
    its deadline timer ticks) and, when something changed, has the executor run ``callback``."""

    def __init__(
        self,
        *,
        callback_group: CallbackGroup,
        callback: Callable[[Any], Any],
        event_type: IntEnum,
        parent: Any,
    ) -> None:
        self.callback = callback
        self.callback_group = callback_group
        self.event_type = event_type
        self.parent = parent
        self._guard = GuardCondition(parent.node, self._run, callback_group)
        self._total = self._told_total = 0

    def _run(self) -> None:
        info = self.take()
        if info is not None:
            self.callback(info)

    def take(self) -> Any:
        """The event's info since the last take, or None if nothing changed."""
        return None

    def destroy(self) -> None:
        self._guard.destroy()


class _GraphEvent(EventHandler):
    """An event recomputed on every change of the graph (the bus's listeners)."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._bus = self.parent.node._bus
        self._bus.graph_listeners.append(self.look)
        self.look()

    def look(self) -> None:
        if self.parent.destroyed:
            self.destroy()
        elif self.changed():
            self._guard.trigger()

    def changed(self) -> bool:
        raise NotImplementedError

    def destroy(self) -> None:
        if self.look in self._bus.graph_listeners:
            self._bus.graph_listeners.remove(self.look)
        super().destroy()


class MatchedEvent(_GraphEvent):
    def __init__(self, **kwargs: Any) -> None:
        self._current = self._told_current = 0
        super().__init__(**kwargs)

    def changed(self) -> bool:
        current = len(peers(self.parent))
        if current == self._current:
            return False
        self._total += max(0, current - self._current)
        self._current = current
        return True

    def take(self) -> QoSSubscriptionMatchedInfo | None:
        if self._current == self._told_current and self._total == self._told_total:
            return None
        info = QoSSubscriptionMatchedInfo(
            total_count=self._total,
            total_count_change=self._total - self._told_total,
            current_count=self._current,
            current_count_change=self._current - self._told_current,
        )
        self._told_total, self._told_current = self._total, self._current
        return info


class IncompatibleQoSEvent(_GraphEvent):
    """Counts each peer DDS would refuse once, as it is discovered."""

    def __init__(self, **kwargs: Any) -> None:
        self._seen = 0
        self._last = QoSPolicyKind.INVALID
        super().__init__(**kwargs)

    def changed(self) -> bool:
        policies = incompatible_peers(self.parent)
        grew = len(policies) > self._seen
        if grew:
            self._total += len(policies) - self._seen
            self._last = policies[-1]
        self._seen = len(policies)
        return grew

    def take(self) -> QoSRequestedIncompatibleQoSInfo | None:
        if self._total == self._told_total:
            return None
        info = QoSRequestedIncompatibleQoSInfo(self._total, self._total - self._told_total, self._last)
        self._told_total = self._total
        return info


class DeadlineEvent(EventHandler):
    """A timer of the profile's deadline: a period without a message (a publish, for a publisher)
    counts one miss."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        period_s = self.parent.qos_profile.deadline.nanoseconds / 1e9
        self._last_seen = self._sent()
        self._timer = self.parent.node.create_timer(period_s, self._tick, self.callback_group)

    def _sent(self) -> int:
        if isinstance(self.parent, BusPublisher):
            return int(getattr(self.parent, "published_count", 0))
        return int(self.parent.topic.publish_count)

    def _tick(self) -> None:
        if self.parent.destroyed:
            self.destroy()
            return
        sent = self._sent()
        if sent == self._last_seen:
            self._total += 1
            self._run()
        self._last_seen = sent

    def take(self) -> Any:
        if self._total == self._told_total:
            return None
        kind = (
            QoSOfferedDeadlineMissedInfo
            if isinstance(self.parent, BusPublisher)
            else QoSRequestedDeadlineMissedInfo
        )
        info = kind(self._total, self._total - self._told_total)
        self._told_total = self._total
        return info

    def destroy(self) -> None:
        self.parent.node.destroy_timer(self._timer)
        super().destroy()


class _Silent(EventHandler):
    """An event the lab's transport cannot tell: accepted, never raised."""


def _warn_incompatible(node: Any, topic_name: str, publisher: bool) -> Callable[[Any], None]:
    logger = get_logger(node.get_logger().name)
    other, verb, effect = (
        ("subscription", "requesting", "sent to") if publisher else ("publisher", "offering", "received from")
    )

    def warn(event: QoSRequestedIncompatibleQoSInfo) -> None:
        logger.warning(
            f"New {other} discovered on topic '{topic_name}', {verb} incompatible QoS. No messages "
            f"will be {effect} it. Last incompatible policy: {qos_policy_name_from_kind(event.last_policy_kind)}"
        )

    return warn


def _handlers(
    callbacks: Any, group: CallbackGroup, entity: Any, topic_name: str, publisher: bool
) -> list[EventHandler]:
    kinds = QoSPublisherEventType if publisher else QoSSubscriptionEventType
    prefix = "RCL_PUBLISHER_" if publisher else "RCL_SUBSCRIPTION_"
    deadline = "OFFERED_DEADLINE_MISSED" if publisher else "REQUESTED_DEADLINE_MISSED"
    incompatible = "OFFERED_INCOMPATIBLE_QOS" if publisher else "REQUESTED_INCOMPATIBLE_QOS"
    wanted: list[tuple[Callable[[Any], Any] | None, str, type[EventHandler]]] = [
        (callbacks.deadline, deadline, DeadlineEvent),
        (callbacks.liveliness, "LIVELINESS_LOST" if publisher else "LIVELINESS_CHANGED", _Silent),
        (getattr(callbacks, "message_lost", None), "MESSAGE_LOST", _Silent),
        (callbacks.incompatible_type, "INCOMPATIBLE_TYPE", _Silent),
        (callbacks.matched, "MATCHED", MatchedEvent),
    ]
    qos_callback = callbacks.incompatible_qos
    if qos_callback is None and callbacks.use_default_callbacks:
        qos_callback = _warn_incompatible(entity.node, topic_name, publisher)
    wanted.insert(1, (qos_callback, incompatible, IncompatibleQoSEvent))
    out: list[EventHandler] = []
    for callback, name, kind in wanted:
        if callback is None:
            continue
        if kind is DeadlineEvent and entity.qos_profile.deadline.nanoseconds <= 0:
            kind = _Silent  # no deadline in the profile: nothing can be missed
        event_type = kinds[prefix + name]
        out.append(kind(callback_group=group, callback=callback, event_type=event_type, parent=entity))
    return out


class SubscriptionEventCallbacks:
    """The callbacks a subscription's events call (keyword arguments, as rclpy's)."""

    def __init__(
        self,
        *,
        deadline: Callable[[QoSRequestedDeadlineMissedInfo], Any] | None = None,
        incompatible_qos: Callable[[QoSRequestedIncompatibleQoSInfo], Any] | None = None,
        liveliness: Callable[[QoSLivelinessChangedInfo], Any] | None = None,
        message_lost: Callable[[QoSMessageLostInfo], Any] | None = None,
        incompatible_type: Callable[[IncompatibleTypeInfo], Any] | None = None,
        matched: Callable[[QoSSubscriptionMatchedInfo], Any] | None = None,
        use_default_callbacks: bool = True,
    ) -> None:
        self.deadline = deadline
        self.incompatible_qos = incompatible_qos
        self.liveliness = liveliness
        self.message_lost = message_lost
        self.incompatible_type = incompatible_type
        self.matched = matched
        self.use_default_callbacks = use_default_callbacks

    def create_event_handlers(
        self, callback_group: CallbackGroup, subscription: Any, topic_name: str
    ) -> list[EventHandler]:
        """The handlers of ``subscription`` (``topic_name`` as the node's code wrote it)."""
        return _handlers(self, callback_group, subscription, topic_name, publisher=False)


class PublisherEventCallbacks:
    """The callbacks a publisher's events call (keyword arguments, as rclpy's)."""

    def __init__(
        self,
        *,
        deadline: Callable[[QoSOfferedDeadlineMissedInfo], Any] | None = None,
        liveliness: Callable[[QoSLivelinessLostInfo], Any] | None = None,
        incompatible_qos: Callable[[QoSRequestedIncompatibleQoSInfo], Any] | None = None,
        incompatible_type: Callable[[IncompatibleTypeInfo], Any] | None = None,
        matched: Callable[[QoSPublisherMatchedInfo], Any] | None = None,
        use_default_callbacks: bool = True,
    ) -> None:
        self.deadline = deadline
        self.liveliness = liveliness
        self.incompatible_qos = incompatible_qos
        self.incompatible_type = incompatible_type
        self.matched = matched
        self.use_default_callbacks = use_default_callbacks

    def create_event_handlers(
        self, callback_group: CallbackGroup, publisher: Any, topic_name: str
    ) -> list[EventHandler]:
        """The handlers of ``publisher`` (``topic_name`` as the node's code wrote it)."""
        return _handlers(self, callback_group, publisher, topic_name, publisher=True)


QoSEventHandler = EventHandler

__all__ = [
    "EventHandler",
    "IncompatibleTypeInfo",
    "PublisherEventCallbacks",
    "QoSEventHandler",
    "QoSLivelinessChangedInfo",
    "QoSLivelinessLostInfo",
    "QoSMessageLostInfo",
    "QoSOfferedDeadlineMissedInfo",
    "QoSOfferedIncompatibleQoSInfo",
    "QoSPublisherEventType",
    "QoSPublisherMatchedInfo",
    "QoSRequestedDeadlineMissedInfo",
    "QoSRequestedIncompatibleQoSInfo",
    "QoSSubscriptionEventType",
    "QoSSubscriptionMatchedInfo",
    "SubscriptionEventCallbacks",
    "UnsupportedEventTypeError",
]
