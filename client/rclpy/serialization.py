"""``rclpy.serialization``: a message to its CDR bytes and back, as the wire carries them."""

from __future__ import annotations

from typing import Any

from node_runtime.msgs import Message
from node_runtime.transport.cdr import decode, encode


def serialize_message(message: Any) -> bytes:
    if not isinstance(message, Message):
        raise TypeError(f"serialize_message takes a message, not {type(message).__name__}")
    return encode(message)


def deserialize_message(serialized_message: bytes, message_type: type[Any]) -> Any:
    """The message of ``message_type`` those bytes hold; ValueError if they hold none."""
    if not (isinstance(message_type, type) and issubclass(message_type, Message)):
        raise TypeError(f"deserialize_message needs a message type, not {message_type!r}")
    try:
        return decode(message_type, serialized_message)
    except Exception as exc:  # WireError: rclpy raises from rmw's deserializer
        raise ValueError(
            f"cannot deserialize {len(serialized_message)} bytes as {message_type.TYPE}: {exc}"
        ) from None


__all__ = ["deserialize_message", "serialize_message"]
