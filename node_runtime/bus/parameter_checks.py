"""What a ParameterDescriptor lets a parameter take, checked as rclpy's Node checks it before a
set or a declaration: read-only, static typing, an integer or floating-point range with its step,
and how an override given for a declaration is taken.
The one implementation of these checks: the lab's own nodes (``node_runtime.bus.parameters``) and node
processes' rclpy (``client/rclpy``) both ask it, so both refuse the same values with rclpy's
words."""

from __future__ import annotations

import math
from typing import Any

from node_runtime.bus.parameter_values import DOUBLE, DOUBLE_ARRAY, INTEGER, NOT_SET, type_of
from node_runtime.msgs.generated.rcl_interfaces import FloatingPointRange, IntegerRange, ParameterDescriptor

PARAM_REL_TOL = 1e-6  # rclpy's Node.PARAM_REL_TOL: how close a double must be to an edge or a step


def refusal(
    name: str,
    value: Any,
    descriptor: ParameterDescriptor,
    *,
    kind: int | None = None,
    check_read_only: bool = True,
    declared: bool = True,
) -> str | None:
    """Why ``descriptor`` does not let parameter ``name`` take ``value`` (rclpy's reason), or None.

    ``kind`` is the value's ParameterType when the caller knows it (rclpy's ``Parameter.type_``),
    else the one ``value`` has. ``check_read_only`` is False for a declaration, which sets a
    read-only parameter's first value; ``declared`` is False until the name is declared, which
    is when a statically typed parameter may still be left unset. A dynamically typed descriptor
    takes any type; an integer is refused for a double parameter, as rclpy refuses it."""
    if check_read_only and descriptor.read_only:
        return f"Trying to set a read-only parameter: {name}."
    kind = type_of(value) if kind is None else int(kind)
    declared_type = int(descriptor.type)
    if not descriptor.dynamic_typing:
        if kind == NOT_SET:
            if declared:
                return "Static parameter cannot be undeclared"
        elif kind != declared_type:
            return f"Wrong parameter type, expected '{type_name(declared_type)}' got '{type_name(kind)}'"
    if kind == INTEGER and descriptor.integer_range:
        return _integer_refusal(name, value, descriptor.integer_range[0])
    if kind == DOUBLE and descriptor.floating_point_range:
        return _double_refusal(name, value, descriptor.floating_point_range[0])
    return None


def override_as_declared(value: Any, descriptor: ParameterDescriptor) -> Any:
    """An override's value as the parameter it is given for takes it: an integer (or a list of
    them) for a double (or a double array) is that double (``-p rate:=5``, a launch's ``<param
    value="5"/>``), the lab's leniency at a declaration, where rclpy would refuse the type. A set
    gets none: an integer for a double is refused there, as rclpy refuses it."""
    declared = int(descriptor.type)
    if declared == DOUBLE and type(value) is int:
        return float(value)
    integers = isinstance(value, list | tuple) and value and all(type(v) is int for v in value)
    if declared == DOUBLE_ARRAY and integers:
        return [float(v) for v in value]
    return value


def type_name(kind: int) -> str:
    """A ParameterType as rclpy's ``Parameter.Type`` prints itself: an IntEnum, so its number
    (``3`` for DOUBLE)."""
    return str(int(kind))


def _integer_refusal(name: str, value: int, bounds: IntegerRange) -> str | None:
    low, high = sorted((int(bounds.from_value), int(bounds.to_value)))
    if value in (low, high):
        return None
    if not low < value < high:
        return f"Parameter {name} out of range. Min: {low}, Max: {high}, value: {value}"
    if bounds.step and (value - low) % int(bounds.step):
        return (
            f"The parameter value for {name} is not a valid step. "
            f"Min: {low}, max: {high}, value: {value}, step: {bounds.step}"
        )
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
            return (
                f"The parameter value for {name} is not close enough to a valid step. "
                f"Min: {low}, max: {high}, value: {value}, step: {bounds.step}"
            )
    return None


__all__ = ["PARAM_REL_TOL", "override_as_declared", "refusal", "type_name"]
