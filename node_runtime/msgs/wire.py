"""Messages on the wire: CDR bytes, as ROS 2 and rmw_zenoh use them, and their types' RIHS01
hashes and DDS names.

``rosbags`` writes and reads the bytes, from the typestores node_runtime/msgs/typestores.py fills with
the lab's own definitions (it also computes the hashes; this module gives them on).

A node process asks only for the hashes of the types it uses and writes its CDR itself
(node_runtime/transport/cdr.py): the lab's own types' hashes are looked up in a table generated with
the message classes (node_runtime/msgs/generated/type_hashes.py), so such a process never imports
rosbags nor builds a typestore; a student's own type's hash comes from a typestore of that
type and what it nests alone.
"""

from __future__ import annotations

import array
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

from node_runtime.msgs import catalog
from node_runtime.msgs._base import Message, message_class
from node_runtime.msgs._field import Field, MessageError
from node_runtime.msgs.typestores import (
    EMPTY_STRUCT_MEMBER,
    SERVICE_EVENT_INFO,
    build_typestore,
    computed_type_hash,
    computed_type_hashes,
    type_hash,
    typestore,
)

if TYPE_CHECKING:
    from rosbags.typesys.store import Typestore


__all__ = [
    "CDR_LE_HEADER",
    "EMPTY_STRUCT_MEMBER",
    "SERVICE_EVENT_INFO",
    "WireError",
    "build_typestore",
    "computed_type_hash",
    "computed_type_hashes",
    "dds_type_name",
    "definition_closure_text",
    "deserialize",
    "prepare",
    "ros_type_name",
    "serialize",
    "type_hash",
    "typestore",
]

CDR_LE_HEADER = b"\x00\x01\x00\x00"


class WireError(ValueError):
    """Bytes that are not a CDR message of the expected type."""


def dds_type_name(type_name: str) -> str:
    """``geometry_msgs/msg/Vector3`` → ``geometry_msgs::msg::dds_::Vector3_``, as rmw_zenoh keys it."""
    pkg, kind, name = type_name.split("/")
    return f"{pkg}::{kind}::dds_::{name}_"


def ros_type_name(dds_name: str) -> str | None:
    """The inverse of :func:`dds_type_name`; None if ``dds_name`` is not of that shape."""
    parts = dds_name.split("::")
    if (
        len(parts) != 4
        or parts[2] != "dds_"
        or not parts[3].endswith("_")
        or parts[1] not in ("msg", "srv", "action")
    ):
        return None
    return f"{parts[0]}/{parts[1]}/{parts[3][:-1]}"


def prepare(type_name: str) -> None:
    """Build rosbags' CDR code for a type and every type it nests, now rather than at the first
    message. rosbags generates that code with ``exec`` of a string, and a Ctrl-C landing inside
    such an ``exec`` marks the interpreter as ended by Ctrl-C (exit status -SIGINT) even when the
    node's own ``except KeyboardInterrupt`` catches it; endpoints call this when they are made."""
    store = typestore(type_name)
    pending, seen = [type_name], set()
    while pending:
        name = pending.pop()
        if name in seen or name not in store.fielddefs:
            continue
        seen.add(name)
        store.get_msgdef(name)
        stack: list[Any] = [store.fielddefs[name][1]]
        while stack:
            item = stack.pop()
            if isinstance(item, str):
                pending.append(item)
            elif isinstance(item, tuple | list):
                stack.extend(item)


_HOLDS_SEQUENCES: dict[str, bool] = {}


def _bool_sequence(f: Field) -> bool:
    return f.array and f.kind == "bool" and not f.numeric_array


def _holds_sequences(cls: type[Message]) -> bool:
    """Whether a message of ``cls`` holds (at any depth) a sequence of numbers or bools: an
    ``array.array`` or a list, which rosbags cannot write (it takes numpy arrays)."""
    known = _HOLDS_SEQUENCES.get(cls.TYPE)
    if known is None:
        known = _HOLDS_SEQUENCES[cls.TYPE] = any(
            f.typecode is not None
            or _bool_sequence(f)
            or (not isinstance(f.kind, str) and _holds_sequences(f.kind))
            for f in cls.FIELDS
        )
    return known


def _bools_view(values: list[bool]) -> Any:
    import numpy as np

    return np.array(values, dtype=bool)


def _numpy_view(value: Any) -> Any:
    """What rosbags writes for a message value: ``array.array`` fields as numpy arrays over the
    same memory, nested messages converted alike."""
    if isinstance(value, array.array):
        import numpy as np  # only here: a node process that never writes through rosbags never loads it

        return (
            np.frombuffer(value, dtype=value.typecode) if len(value) else np.array([], dtype=value.typecode)
        )
    if isinstance(value, list):
        return [_numpy_view(v) for v in value]
    if isinstance(value, Message):
        if not _holds_sequences(type(value)):
            return value
        views: dict[str, Any] = {}
        for f in value.FIELDS:
            item = getattr(value, f.name)
            views[f.name] = _bools_view(item) if _bool_sequence(f) else _numpy_view(item)
        return SimpleNamespace(**views)
    return value


def serialize(msg: Message) -> bytes:
    """Little-endian CDR with its 4-byte header and no trailing padding, as rmw_zenoh sends it."""
    return bytes(typestore(msg.TYPE).serialize_cdr(_numpy_view(msg), msg.TYPE))


def _nested(path: str, exc: MessageError) -> MessageError:
    return MessageError(f"{path}.{exc.path}" if exc.path else path, exc.problem)


def _field_step(f: Field) -> Any:
    """How one field's value from rosbags becomes ours; values are checked only where the wire
    could carry more than the type allows (bounded strings and sequences)."""
    name = f.name
    if isinstance(f.kind, str):
        if f.array or f.string_bound is not None:
            return lambda raw: f.check(list(raw) if f.array and not f.numeric_array else raw, name)
        if f.kind == "bool":
            return bool
        return None
    inner = _converter_for(f.kind)
    if not f.array:

        def nested(raw: Any) -> Message:
            try:
                converted: Message = inner(raw)
            except MessageError as exc:
                raise _nested(name, exc) from None
            return converted

        return nested

    def items(raw: Any) -> list[Message]:
        out = []
        for i, item in enumerate(raw):
            try:
                out.append(inner(item))
            except MessageError as exc:
                raise _nested(f"{name}[{i}]", exc) from None
        return list(f.check(out, name))

    return items


_CONVERTERS: dict[type[Message], Any] = {}


def _converter_for(cls: type[Message]) -> Any:
    converter = _CONVERTERS.get(cls)
    if converter is None:
        converter = _CONVERTERS[cls] = _make_converter(cls)
    return converter


def _make_converter(cls: type[Message]) -> Any:
    steps = [(f.name, _field_step(f)) for f in cls.FIELDS]
    setter = object.__setattr__

    def convert(raw: Any) -> Message:
        msg = object.__new__(cls)
        for name, step in steps:
            value = getattr(raw, name)
            setter(msg, name, value if step is None else step(value))
        return msg

    return convert


def deserialize(
    type_name: str, data: bytes | bytearray | memoryview, store: Typestore | None = None
) -> Message:
    """A message from CDR bytes (trailing padding accepted); WireError if they do not decode.
    ``store`` is the lab's typestore unless given (tests pass one built from other definitions)."""
    cls = message_class(type_name)
    raw_bytes = bytes(data)
    if raw_bytes[:2] != CDR_LE_HEADER[:2]:
        raise WireError(f"{type_name}: not little-endian CDR (header {raw_bytes[:4].hex() or 'missing'})")
    try:
        raw = (store or typestore(type_name)).deserialize_cdr(raw_bytes, type_name)
        converted: Message = _converter_for(cls)(raw)
        return converted
    except MessageError as exc:
        raise WireError(f"{type_name}: {exc}") from None
    except Exception as exc:  # rosbags raises struct/index/unicode errors on short or bad bytes
        raise WireError(f"{type_name}: {len(raw_bytes)} bytes do not decode: {type(exc).__name__}") from None


def definition_closure_text(type_name: str) -> str:
    """The type's definition followed by each nested type's, as ROS 2's MCAP and Foxglove's
    ``ros2msg`` schemas carry it (sections ``MSG: pkg/Type`` between lines of ``=``)."""
    specs = catalog.definitions().closure(type_name)
    parts = [specs[0].text.rstrip("\n")]
    for spec in specs[1:]:
        pkg, _, name = spec.name.split("/")
        parts.append("=" * 80 + f"\nMSG: {pkg}/{name}\n" + spec.text.rstrip("\n"))
    return "\n".join(parts) + "\n"
