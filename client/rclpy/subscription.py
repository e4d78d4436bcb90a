"""``rclpy.subscription.Subscription``: what ``node.create_subscription`` returns, the bus's
subscription with rclpy's properties (``topic_name``, ``qos_profile``, ``raw``, ``event_handlers``)
and calls. A ``raw`` subscription's callback gets each message as CDR bytes, as the wire carries
it; a callback of two arguments gets the message and its ``MessageInfo``."""

from __future__ import annotations

import inspect
import time
from collections.abc import Callable
from enum import Enum
from typing import TYPE_CHECKING, Any, Generic, TypedDict, TypeVar

from node_runtime.bus import Subscription as BusSubscription
from rclpy._matching import peers
from rclpy.qos import QoSProfile

if TYPE_CHECKING:
    from rclpy.callback_groups import CallbackGroup
    from rclpy.event_handler import EventHandler

MsgT = TypeVar("MsgT")


class MessageInfo(TypedDict):
    source_timestamp: int
    received_timestamp: int
    publication_sequence_number: int | None
    reception_sequence_number: int | None
    publisher_gid: dict[str, Any]


# The bus's queues keep messages alone: the info a callback gets is this subscription's count of
# them (a publisher's own count when it is the only one) and the time it takes them, and no GID.
_NO_GID = {"implementation_identifier": "rmw_zenoh_cpp", "data": bytes(16)}


class Subscription(BusSubscription, Generic[MsgT]):
    """Receives one message type on one topic; the executor runs its callback per message."""

    class CallbackType(Enum):
        MessageOnly = 0
        WithMessageInfo = 1

    qos_profile: QoSProfile
    callback_group: CallbackGroup | None = None
    event_handlers: list[EventHandler]
    raw = False

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.qos_profile = QoSProfile(depth=self.depth)
        self.event_handlers = []
        self._received = 0

    def get_publisher_count(self) -> int:
        """Publishers of this topic and type, in this process and in others."""
        return len(peers(self))

    def destroy(self) -> None:
        for handler in self.event_handlers:
            handler.destroy()
        super().destroy()

    def __enter__(self) -> Subscription[MsgT]:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.destroy()

    def adapt(self, callback: Callable[..., Any]) -> Callable[..., Any]:
        """What the executor calls with each message: ``callback`` itself, or a wrapper giving it
        the CDR bytes (``raw``) or the message info too (a callback of two arguments)."""
        kind = callback_type(callback)
        if not self.raw and kind is Subscription.CallbackType.MessageOnly:
            return callback
        raw = self.raw

        def deliver(msg: Any) -> Any:
            if raw:
                from rclpy.serialization import serialize_message

                msg = serialize_message(msg)
            if kind is Subscription.CallbackType.MessageOnly:
                return callback(msg)
            self._received += 1
            now = time.time_ns()
            info: MessageInfo = {
                "source_timestamp": now,
                "received_timestamp": now,
                "publication_sequence_number": self._received,
                "reception_sequence_number": None,
                "publisher_gid": dict(_NO_GID),
            }
            return callback(msg, info)

        deliver.__qualname__ = getattr(callback, "__qualname__", "callback")
        return deliver


def callback_type(callback: Callable[..., Any]) -> Subscription.CallbackType:
    """rclpy's rule: a callback that takes one argument gets the message, two the message and its
    info; anything else is refused."""
    signature = inspect.signature(callback)
    for kind, args in (
        (Subscription.CallbackType.MessageOnly, 1),
        (Subscription.CallbackType.WithMessageInfo, 2),
    ):
        try:
            signature.bind(*([object()] * args))
        except TypeError:
            continue
        return kind
    raise RuntimeError(
        "Subscription.__init__(): callback should be either be callable with one argument"
        "(to get only the message) or two (to get message and message info)"
    )


__all__ = ["MessageInfo", "Subscription"]
