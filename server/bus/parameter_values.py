"""A bus node's parameter values as ``rcl_interfaces`` carries them: the ParameterType of a Python
value, a value to and from a ParameterValue message, and what a ParameterDescriptor allows
(read-only, a type, an integer or floating-point range with its step), with rclpy's reasons."""

from __future__ import annotations

import math
from typing import Any

from ..msgs.generated.rcl_interfaces import (
    FloatingPointRange,
    IntegerRange,
    ParameterDescriptor,
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
PARAM_REL_TOL = 1e-6  # rclpy's: how close a double must be to an edge or a step


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


def refusal(
    name: str, value: Any, descriptor: ParameterDescriptor, check_read_only: bool = True
) -> str | None:
    """Why ``descriptor`` does not let parameter ``name`` take ``value`` (rclpy's words), or None."""
    if check_read_only and descriptor.read_only:
        return f"Trying to set a read-only parameter: {name}."
    kind = type_of(value)
    declared = int(descriptor.type)
    if not descriptor.dynamic_typing and declared != NOT_SET and kind != declared:
        if kind == NOT_SET:
            return "Static parameter cannot be undeclared"
        return f"Wrong parameter type, expected '{_type_name(declared)}' got '{_type_name(kind)}'"
    if kind == INTEGER and descriptor.integer_range:
        return _integer_refusal(name, value, descriptor.integer_range[0])
    if kind == DOUBLE and descriptor.floating_point_range:
        return _double_refusal(name, value, descriptor.floating_point_range[0])
    return None


def _type_name(kind: int) -> str:
    return f"Type.{(FIELDS[kind] or 'not_set').removesuffix('_value').upper()}"


def _integer_refusal(name: str, value: int, bounds: IntegerRange) -> str | None:
    low, high = sorted((int(bounds.from_value), int(bounds.to_value)))
    if value in (low, high):
        return None
    if not low < value < high:
        return f"Parameter {name} out of range. Min: {low}, Max: {high}, value: {value}"
    if bounds.step and (value - low) % int(bounds.step):
        return f"The parameter value for {name} is not a valid step. Min: {low}, max: {high}, value: {value}, step: {bounds.step}"
    return None


def _double_refusal(name: str, value: float, bounds: FloatingPointRange) -> str | None:
    low, high = sorted((float(bounds.from_value), float(bounds.to_value)))
    if math.isclose(value, low, rel_tol=PARAM_REL_TOL) or math.isclose(value, high, rel_tol=PARAM_REL_TOL):
        return None
    if not low < value < high:
        return f"Parameter {name} out of range Min: {low}, Max: {high}, value: {value}"
    if bounds.step:
        steps = round((value - low) / bounds.step)
        if not math.isclose(low + steps * bounds.step, value, rel_tol=PARAM_REL_TOL):
            return f"The parameter value for {name} is not close enough to a valid step. Min: {low}, max: {high}, value: {value}, step: {bounds.step}"
    return None


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
    "read_only",
    "refusal",
    "to_value_msg",
    "type_of",
]
