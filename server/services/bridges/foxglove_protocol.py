"""The Foxglove WebSocket protocol's messages, as the app's server speaks them (``foxglove.sdk.v1``,
which Foxglove offers; ``foxglove.websocket.v1``, its older name, which Lichtblick offers).

Only what a live server with client publishing needs: ``serverInfo``, ``status``, ``advertise`` and
``unadvertise`` (JSON text frames) and message data (binary: opcode 1, uint32 subscription id,
uint64 log time in ns, little-endian, then the CDR payload) to the client; ``subscribe``,
``unsubscribe``, ``advertise``, ``unadvertise`` and client message data (opcode 1, uint32 client
channel id, payload) from it. Anything else a client sends is a ``ProtocolError`` naming it.
"""

from __future__ import annotations

import json
import struct
from dataclasses import dataclass
from enum import IntEnum
from typing import Any

SUBPROTOCOLS = ("foxglove.sdk.v1", "foxglove.websocket.v1")
MESSAGE_DATA = 0x01  # a binary frame's opcode, both ways
_SERVER_DATA = struct.Struct("<BIQ")
_CLIENT_DATA = struct.Struct("<BI")
MAX_ENTRIES = 1024  # subscriptions or channels in one client message
UINT32_MAX = 2**32 - 1


class StatusLevel(IntEnum):
    INFO = 0
    WARNING = 1
    ERROR = 2


class ProtocolError(ValueError):
    """A client message this server does not understand; the text says what was wrong."""


@dataclass(frozen=True)
class ChannelInfo:
    """A channel the server advertises: one bus topic, CDR with its ros2msg definition."""

    id: int
    topic: str
    schema_name: str
    schema: str

    def to_json(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "topic": self.topic,
            "encoding": "cdr",
            "schemaName": self.schema_name,
            "schema": self.schema,
            "schemaEncoding": "ros2msg",
        }


@dataclass(frozen=True)
class ClientChannel:
    """A channel a client advertised, to publish on."""

    id: int
    topic: str
    encoding: str
    schema_name: str


@dataclass(frozen=True)
class Subscribe:
    subscriptions: tuple[tuple[int, int], ...]  # (subscription id, channel id)


@dataclass(frozen=True)
class Unsubscribe:
    subscription_ids: tuple[int, ...]


@dataclass(frozen=True)
class Advertise:
    channels: tuple[ClientChannel, ...]


@dataclass(frozen=True)
class Unadvertise:
    channel_ids: tuple[int, ...]


ClientOp = Subscribe | Unsubscribe | Advertise | Unadvertise


# -- to the client ----------------------------------------------------------
def server_info(name: str, session_id: str, supported_encodings: tuple[str, ...]) -> str:
    return json.dumps(
        {
            "op": "serverInfo",
            "name": name,
            "capabilities": ["clientPublish"],
            "supportedEncodings": list(supported_encodings),
            "metadata": {},
            "sessionId": session_id,
        }
    )


def status(level: StatusLevel, message: str) -> str:
    return json.dumps({"op": "status", "level": int(level), "message": message})


def advertise(channels: list[ChannelInfo]) -> str:
    return json.dumps({"op": "advertise", "channels": [c.to_json() for c in channels]})


def unadvertise(channel_ids: list[int]) -> str:
    return json.dumps({"op": "unadvertise", "channelIds": channel_ids})


def message_data(subscription_id: int, log_time_ns: int, payload: bytes) -> bytes:
    return _SERVER_DATA.pack(MESSAGE_DATA, subscription_id, log_time_ns) + payload


# -- from the client --------------------------------------------------------
def client_data(frame: bytes) -> tuple[int, bytes]:
    """A binary frame's (client channel id, payload)."""
    if len(frame) < _CLIENT_DATA.size or frame[0] != MESSAGE_DATA:
        raise ProtocolError("a binary frame is opcode 1, a uint32 channel id and the message")
    _, channel_id = _CLIENT_DATA.unpack_from(frame)
    return channel_id, frame[_CLIENT_DATA.size :]


def client_op(text: str) -> ClientOp:
    """A text frame's operation."""
    try:
        msg = json.loads(text)
    except ValueError:
        raise ProtocolError("a text frame is one JSON object") from None
    if not isinstance(msg, dict):
        raise ProtocolError("a text frame is one JSON object")
    op = msg.get("op")
    if op == "subscribe":
        subs = _entries(msg, "subscriptions", dict)
        return Subscribe(tuple((_uint(s, "id"), _uint(s, "channelId")) for s in subs))
    if op == "unsubscribe":
        return Unsubscribe(tuple(_uint32(i) for i in _entries(msg, "subscriptionIds", int)))
    if op == "advertise":
        return Advertise(tuple(_client_channel(c) for c in _entries(msg, "channels", dict)))
    if op == "unadvertise":
        return Unadvertise(tuple(_uint32(i) for i in _entries(msg, "channelIds", int)))
    raise ProtocolError(
        f"operation {str(op)[:40]!r} is not served here (subscribe, unsubscribe, advertise, unadvertise)"
    )


def _entries(msg: dict[str, Any], key: str, kind: type) -> list[Any]:
    value = msg.get(key)
    if not isinstance(value, list) or len(value) > MAX_ENTRIES or not all(isinstance(v, kind) for v in value):
        raise ProtocolError(f"{msg['op']}: {key!r} is a list of at most {MAX_ENTRIES} {kind.__name__}s")
    return value


def _uint32(value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= UINT32_MAX:
        raise ProtocolError(f"an id is a uint32, got {str(value)[:40]}")
    return value


def _uint(entry: dict[str, Any], key: str) -> int:
    return _uint32(entry.get(key))


def _text(entry: dict[str, Any], key: str, default: str | None = None) -> str:
    value = entry.get(key, default)
    if not isinstance(value, str) or len(value) > 256:
        raise ProtocolError(f"advertise: {key!r} is a string of at most 256 characters")
    return value


def _client_channel(entry: dict[str, Any]) -> ClientChannel:
    return ClientChannel(
        _uint(entry, "id"), _text(entry, "topic"), _text(entry, "encoding"), _text(entry, "schemaName", "")
    )
