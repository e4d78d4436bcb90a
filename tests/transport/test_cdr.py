"""node_runtime/transport/cdr.py writes the bytes rosbags writes (an independent CDR encoder, which the
app's bags and Foxglove use) for every type the lab knows, reads them back to an equal message,
and refuses bytes that are not a message with WireError."""

from __future__ import annotations

import struct
from typing import Any

import pytest

from node_runtime.msgs import Message, get_service_type, get_type, service_names, type_names
from node_runtime.msgs._base import Field
from node_runtime.msgs.idl import FLOAT_TYPES, INT_RANGES
from node_runtime.msgs.wire import WireError, serialize
from node_runtime.transport.cdr import decode, encode

ALL = [get_type(n) for n in type_names()] + [
    part for s in service_names() for part in (get_service_type(s).Request, get_service_type(s).Response)
]


def filled(cls: type[Message], depth: int = 0) -> Message:
    """A message with no field at its default: every value, length and nesting differs from it."""
    msg = cls()
    for i, f in enumerate(cls.FIELDS):
        count = f.size if f.size is not None else min(3, f.bound if f.bound is not None else 3)
        if f.array:
            setattr(msg, f.name, [_item(f, i + k, depth) for k in range(count)])
        else:
            setattr(msg, f.name, _item(f, i, depth))
    return msg


def _item(f: Field, i: int, depth: int) -> Any:
    kind = f.kind
    if not isinstance(kind, str):
        return filled(kind, depth + 1) if depth < 3 else kind()
    if kind == "bool":
        return i % 2 == 0
    if kind in INT_RANGES:
        lo, hi = INT_RANGES[kind]
        return hi - i if i % 2 else max(lo, -5 - i)
    if kind in FLOAT_TYPES:
        return 1.5 + i
    text = f"héllo {i} ✓"
    return text[: f.string_bound] if f.string_bound is not None else text


@pytest.mark.parametrize("cls", ALL, ids=lambda c: c.TYPE)
def test_default_message_has_rosbags_bytes_and_reads_back(cls: type[Message]) -> None:
    msg = cls()
    assert encode(msg) == serialize(msg)
    assert decode(cls, encode(msg)) == msg


@pytest.mark.parametrize("cls", ALL, ids=lambda c: c.TYPE)
def test_filled_message_has_rosbags_bytes_and_reads_back(cls: type[Message]) -> None:
    msg = filled(cls)
    assert encode(msg) == serialize(msg)
    back = decode(cls, encode(msg))
    assert back == msg and back.to_dict() == msg.to_dict()


def test_trailing_padding_is_accepted_as_rclpy_sends_it() -> None:
    key = filled(get_type("keyboard_msgs/msg/Key"))
    assert decode(type(key), encode(key) + b"\x00\x00\x00") == key


@pytest.mark.parametrize(
    ("data", "problem"),
    [
        (b"", "header"),
        (b"\x00\x00\x00\x00" + struct.pack("<I", 3) + b"hi\x00", "header"),  # big-endian
        (b"\x00\x01\x00\x00" + struct.pack("<I", 30) + b"hi\x00", "do not decode"),  # longer than the bytes
        (b"\x00\x01\x00\x00" + struct.pack("<I", 3) + b"hi!", "do not decode"),  # no NUL
        (b"\x00\x01\x00\x00" + struct.pack("<I", 3) + b"\xff\xfe\x00", "do not decode"),  # not UTF-8
        (b"\x00\x01\x00\x00\x02", "do not decode"),  # cut short
    ],
)
def test_bytes_that_are_no_string_message_are_refused(data: bytes, problem: str) -> None:
    with pytest.raises(WireError, match=problem):
        decode(get_type("std_msgs/msg/String"), data)


def test_a_sequence_count_beyond_the_bytes_is_refused_before_reading_it() -> None:
    cls = get_type("tf2_msgs/msg/TFMessage")
    data = b"\x00\x01\x00\x00" + struct.pack("<I", 2**31)
    with pytest.raises(WireError, match="items"):
        decode(cls, data)
    assert decode(cls, b"\x00\x01\x00\x00" + struct.pack("<I", 0)) == cls()  # an empty one reads


def test_a_bounded_sequence_longer_than_its_bound_is_refused() -> None:
    """ParameterDescriptor's ranges are ``T[<=1]``: two items on the wire are not a descriptor."""
    cls = get_type("rcl_interfaces/msg/ParameterDescriptor")
    msg = filled(cls)
    assert len(msg.integer_range) == 1 and decode(cls, encode(msg)) == msg
    object.__setattr__(msg, "integer_range", [*msg.integer_range] * 2)  # as another process could send
    with pytest.raises(WireError, match="integer_range"):
        decode(cls, encode(msg))
