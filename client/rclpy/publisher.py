"""``rclpy.publisher.Publisher``: what ``node.create_publisher`` returns, the bus's publisher with
rclpy's properties (``topic_name``, ``qos_profile``, ``event_handlers``) and calls."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Generic, TypeVar

from node_runtime.bus import Publisher as BusPublisher
from rclpy._matching import peers
from rclpy.duration import Duration
from rclpy.qos import QoSProfile

if TYPE_CHECKING:
    from rclpy.callback_groups import CallbackGroup
    from rclpy.event_handler import EventHandler

MsgT = TypeVar("MsgT")


class Publisher(BusPublisher, Generic[MsgT]):
    """Sends one message type on one topic; ``publish`` takes the message or its CDR bytes."""

    qos_profile: QoSProfile
    callback_group: CallbackGroup | None = None
    event_handlers: list[EventHandler]
    published_count = 0  # publishes so far (a deadline event's clock)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.qos_profile = QoSProfile(depth=self.depth)
        self.event_handlers = []

    def publish(self, msg: Any) -> None:  # type: ignore[override]  # rclpy's returns nothing
        """Send ``msg``; bytes are taken as the message in CDR (``raw`` subscriptions' form)."""
        if isinstance(msg, (bytes, bytearray, memoryview)):
            from rclpy.serialization import deserialize_message

            msg = deserialize_message(bytes(msg), self.msg_type)
        elif not isinstance(msg, self.msg_type):
            raise TypeError(f"Expected {self.msg_type}, got {type(msg)}")
        super().publish(msg)
        self.published_count += 1

    def get_subscription_count(self) -> int:
        """Subscriptions of this topic and type, in this process and in others."""
        return len(peers(self))

    def assert_liveliness(self) -> None:
        """Nothing to do: liveliness is the endpoint's token on the graph, there while it lives."""

    def wait_for_all_acked(self, timeout: Duration | None = None) -> bool:
        """True: the transport keeps no acknowledgements to wait for."""
        return True

    def destroy(self) -> None:
        for handler in self.event_handlers:
            handler.destroy()
        super().destroy()

    def __enter__(self) -> Publisher[MsgT]:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.destroy()


__all__ = ["Publisher"]
