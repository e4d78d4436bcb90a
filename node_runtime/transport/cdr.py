"""Messages as rmw_zenoh carries them: little-endian CDR, read and written from the message classes.

The layout: a 4-byte header ``00 01 00 00``, then the fields in definition order, each primitive
aligned to its own size (at most 8) counted from after the header; a string is a uint32 length
(its UTF-8 bytes and a NUL) and the bytes; a sequence (``T[]``, ``T[<=N]``) a uint32 count and
its items, a fixed array (``T[N]``) its items alone; a nested message its fields in line; a
message without fields one zero byte. Nothing pads the end. Reading accepts trailing bytes (real
rclpy pads some messages) and checks bounds as the fields do.

rosbags writes the same bytes (node_runtime/msgs/wire.py, which the app's bags and Foxglove use), but its
code for each type is generated and imports numpy, some 20 MiB of a node process that sends
booleans; this needs nothing but ``struct``, and numpy only for a message with numeric arrays.
"""

from __future__ import annotations

import struct
from typing import Any

from node_runtime.msgs import Message, MessageError
from node_runtime.msgs.wire import WireError

HEADER = b"\x00\x01\x00\x00"
_FORMATS = {
    "bool": "?",
    "byte": "B",
    "char": "B",
    "int8": "b",
    "uint8": "B",
    "int16": "h",
    "uint16": "H",
    "int32": "i",
    "uint32": "I",
    "int64": "q",
    "uint64": "Q",
    "float32": "f",
    "float64": "d",
}
_STRUCTS = {kind: struct.Struct("<" + fmt) for kind, fmt in _FORMATS.items()}
_COUNT = _STRUCTS["uint32"]


def encode(msg: Message) -> bytes:
    """``msg`` as CDR bytes, header included."""
    buf = bytearray(HEADER)
    _write_message(buf, msg)
    return bytes(buf)


def decode(cls: type[Message], data: bytes | bytearray | memoryview) -> Message:
    """A message of ``cls`` from CDR bytes; WireError if they are not one."""
    raw = bytes(data)
    if raw[:2] != HEADER[:2]:
        raise WireError(f"{cls.TYPE}: not little-endian CDR (header {raw[:4].hex() or 'missing'})")
    reader = _Reader(raw)
    try:
        return reader.message(cls)
    except MessageError as exc:
        raise WireError(f"{cls.TYPE}: {exc}") from None
    except (struct.error, IndexError, UnicodeDecodeError, ValueError) as exc:
        raise WireError(f"{cls.TYPE}: {len(raw)} bytes do not decode: {exc}") from None


# -- writing -------------------------------------------------------------------------------------
def _align(buf: bytearray, size: int) -> None:
    pad = -(len(buf) - 4) % size
    if pad:
        buf += bytes(pad)


def _write_message(buf: bytearray, msg: Message) -> None:
    fields = type(msg).FIELDS
    if not fields:
        buf.append(0)
        return
    for f in fields:
        value = getattr(msg, f.name)
        if not f.array:
            _write_value(buf, f.kind, value)
            continue
        if f.size is None:
            _align(buf, 4)
            buf += _COUNT.pack(len(value))
        for item in value:
            _write_value(buf, f.kind, item)


def _write_value(buf: bytearray, kind: str | type[Message], value: Any) -> None:
    if not isinstance(kind, str):
        _write_message(buf, value)
    elif kind == "string":
        data = value.encode() + b"\x00"
        _align(buf, 4)
        buf += _COUNT.pack(len(data))
        buf += data
    elif kind == "wstring":
        raise WireError("wstring fields are not supported on the wire")
    else:
        packer = _STRUCTS[kind]
        _align(buf, packer.size)
        buf += packer.pack(value)


# -- reading -------------------------------------------------------------------------------------
class _Reader:
    def __init__(self, data: bytes) -> None:
        self.data = data
        self.pos = 4

    def _align(self, size: int) -> None:
        self.pos += -(self.pos - 4) % size

    def primitive(self, kind: str) -> Any:
        unpacker = _STRUCTS[kind]
        self._align(unpacker.size)
        (value,) = unpacker.unpack_from(self.data, self.pos)
        self.pos += unpacker.size
        return value

    def string(self) -> str:
        length = self.primitive("uint32")
        end = self.pos + length
        if length == 0 or end > len(self.data) or self.data[end - 1] != 0:
            raise ValueError(f"a string of {length} bytes does not fit or lacks its NUL")
        text = self.data[self.pos : end - 1].decode()
        self.pos = end
        return text

    def count(self) -> int:
        n = int(self.primitive("uint32"))
        if n > len(self.data) - self.pos:  # every item takes a byte at least
            raise ValueError(f"a sequence of {n} items in {len(self.data) - self.pos} bytes")
        return n

    def value(self, kind: str | type[Message]) -> Any:
        if not isinstance(kind, str):
            return self.message(kind)
        if kind == "string":
            return self.string()
        if kind == "wstring":
            raise ValueError("wstring fields are not supported on the wire")
        return self.primitive(kind)

    def message(self, cls: type[Message]) -> Message:
        msg = object.__new__(cls)
        if not cls.FIELDS:
            self.primitive("uint8")
            return msg
        for f in cls.FIELDS:
            if f.array:
                n = f.size if f.size is not None else self.count()
                value: Any = f.check([self.value(f.kind) for _ in range(n)], f.name)
            elif f.kind == "bool" or f.string_bound is not None:
                value = f.check(self.value(f.kind), f.name)
            else:
                value = self.value(f.kind)
            object.__setattr__(msg, f.name, value)
        return msg
