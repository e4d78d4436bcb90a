"""A bus node's parameter values as ``rcl_interfaces`` carries them: the ParameterType of a Python
value, a value to and from a ParameterValue message, and the descriptors the lab's nodes declare theirs
with (read-only, a double range). What a descriptor allows is ``node_runtime.bus.parameter_checks``."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from node_runtime.msgs.generated.builtin_interfaces import Time
from node_runtime.msgs.generated.rcl_interfaces import (
    FloatingPointRange,
    Parameter,
    ParameterDescriptor,
    ParameterEvent,
    ParameterType,
    ParameterValue,
)

NOT_SET = ParameterType.PARAMETER_NOT_SET
BOOL, INTEGER, DOUBLE = (
    ParameterType.PARAMETER_BOOL,
    ParameterType.PARAMETER_INTEGER,
    ParameterType.PARAMETER_DOUBLE,
)
STRING, BYTE_ARRAY = ParameterType.PARAMETER_STRING, ParameterType.PARAMETER_BYTE_ARRAY
BOOL_ARRAY, INTEGER_ARRAY = ParameterType.PARAMETER_BOOL_ARRAY, ParameterType.PARAMETER_INTEGER_ARRAY
DOUBLE_ARRAY, STRING_ARRAY = ParameterType.PARAMETER_DOUBLE_ARRAY, ParameterType.PARAMETER_STRING_ARRAY
# ParameterValue's field for each type, in ParameterType's order (its slots after ``type``).
FIELDS: tuple[str | None, ...] = (None, *ParameterValue.__slots__[1:])
_SCALARS = ((bool, BOOL), (int, INTEGER), (float, DOUBLE), (str, STRING))


def type_of(value: Any) -> int:
    """The ParameterType of ``value``; a list's is its items' (an empty list reads as a string
    array, as nothing says otherwise); ValueError for what no parameter can hold."""
    if value is None:
        return NOT_SET
    for kind, code in _SCALARS:
        if type(value) is kind:
            return code
    if isinstance(value, bytes):
        return BYTE_ARRAY
    if isinstance(value, list | tuple):
        for kind, code in _SCALARS:
            if all(type(v) is kind for v in value):
                return STRING_ARRAY if not value else code + 5
    raise ValueError(f"{value!r} is no value a ROS parameter can hold")


def to_value_msg(value: Any) -> ParameterValue:
    """``value`` as a ParameterValue."""
    kind = type_of(value)
    msg = ParameterValue(type=kind)
    field = FIELDS[kind]
    if field is not None:
        setattr(msg, field, list(value) if isinstance(value, bytes | tuple) else value)
    return msg


def from_value_msg(msg: ParameterValue) -> Any:
    """The Python value a ParameterValue holds (None when not set); arrays as lists."""
    kind = int(msg.type)
    if not 0 <= kind < len(FIELDS):
        raise ValueError(f"parameter type {kind} is no ParameterType")
    field = FIELDS[kind]
    if field is None:
        return None
    held = getattr(msg, field)
    if kind == BYTE_ARRAY:
        return bytes(int(b) for b in held)
    if kind in (INTEGER_ARRAY, DOUBLE_ARRAY):
        cast = int if kind == INTEGER_ARRAY else float
        return [cast(v) for v in held]
    return list(held) if kind >= BOOL_ARRAY else held


def read_only(description: str = "") -> ParameterDescriptor:
    """The descriptor of a parameter a node reads once, when it starts."""
    return ParameterDescriptor(description=description, read_only=True)


def double_range(
    low: float, high: float, description: str = "", *, fixed: bool = False
) -> ParameterDescriptor:
    """The descriptor of a double parameter in ``low..high`` (inclusive); ``fixed``: read-only."""
    bounds = FloatingPointRange(from_value=low, to_value=high, step=0.0)
    return ParameterDescriptor(description=description, read_only=fixed, floating_point_range=[bounds])


def parameter_event(
    node: str,
    stamp: Time,
    new: Sequence[Parameter] = (),
    changed: Sequence[Parameter] = (),
    deleted: Sequence[Parameter] = (),
) -> ParameterEvent:
    """The ParameterEvent a node publishes on ``/parameter_events`` for one declaration or one set,
    as rclpy does (in-app nodes and node processes alike)."""
    return ParameterEvent(
        stamp=stamp,
        node=node,
        new_parameters=list(new),
        changed_parameters=list(changed),
        deleted_parameters=list(deleted),
    )


__all__ = [
    "BOOL",
    "BOOL_ARRAY",
    "BYTE_ARRAY",
    "DOUBLE",
    "DOUBLE_ARRAY",
    "FIELDS",
    "INTEGER",
    "INTEGER_ARRAY",
    "NOT_SET",
    "STRING",
    "STRING_ARRAY",
    "double_range",
    "from_value_msg",
    "parameter_event",
    "read_only",
    "to_value_msg",
    "type_of",
]
