"""What a ParameterDescriptor allows, checked as rclpy checks it (read-only, static typing, integer
and floating-point ranges with their steps), with rclpy's reasons."""

from __future__ import annotations

import math

from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor, SetParametersResult

from .parameter import Parameter

PARAM_REL_TOL = 1e-6  # rclpy's Node.PARAM_REL_TOL: how close a double must be to an edge or a step


def _refused(reason: str) -> SetParametersResult:
    return SetParametersResult(successful=False, reason=reason)


def apply_descriptor(
    param: Parameter, descriptor: ParameterDescriptor, declared: bool, check_read_only: bool = True
) -> SetParametersResult:
    """Whether ``descriptor`` lets ``param`` be set; a dynamically typed descriptor takes the
    parameter's type (as rclpy's does)."""
    if check_read_only and descriptor.read_only:
        return _refused(f"Trying to set a read-only parameter: {param.name}.")
    if descriptor.dynamic_typing:
        descriptor.type = param.type_.value
    elif declared and param.type_ == Parameter.Type.NOT_SET:
        return _refused("Static parameter cannot be undeclared")
    elif param.type_ != Parameter.Type.NOT_SET and param.type_.value != descriptor.type:
        return _refused(
            f"Wrong parameter type, expected '{Parameter.Type(descriptor.type)}' got '{param.type_}'"
        )
    if param.type_ == Parameter.Type.INTEGER and descriptor.integer_range:
        return _integer_range(param, descriptor.integer_range[0])
    if param.type_ == Parameter.Type.DOUBLE and descriptor.floating_point_range:
        return _floating_point_range(param, descriptor.floating_point_range[0])
    return SetParametersResult(successful=True)


def _integer_range(param: Parameter, bounds: IntegerRange) -> SetParametersResult:
    low, high = sorted((bounds.from_value, bounds.to_value))
    value = param.value
    if value in (low, high):
        return SetParametersResult(successful=True)
    if not low < value < high:
        return _refused(f"Parameter {param.name} out of range. Min: {low}, Max: {high}, value: {value}")
    if bounds.step != 0 and (value - low) % bounds.step != 0:
        return _refused(
            f"The parameter value for {param.name} is not a valid step. "
            f"Min: {low}, max: {high}, value: {value}, step: {bounds.step}"
        )
    return SetParametersResult(successful=True)


def _floating_point_range(param: Parameter, bounds: FloatingPointRange) -> SetParametersResult:
    low, high = sorted((bounds.from_value, bounds.to_value))
    value = param.value
    if math.isclose(value, low, rel_tol=PARAM_REL_TOL) or math.isclose(value, high, rel_tol=PARAM_REL_TOL):
        return SetParametersResult(successful=True)
    if not low < value < high:
        return _refused(f"Parameter {param.name} out of range Min: {low}, Max: {high}, value: {value}")
    if bounds.step != 0.0:
        steps = round((value - low) / bounds.step)
        if not math.isclose(low + steps * bounds.step, value, rel_tol=PARAM_REL_TOL):
            return _refused(
                f"The parameter value for {param.name} is not close enough to a valid step. "
                f"Min: {low}, max: {high}, value: {value}, step: {bounds.step}"
            )
    return SetParametersResult(successful=True)


__all__ = ["PARAM_REL_TOL", "apply_descriptor"]
