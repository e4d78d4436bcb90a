"""rclpy's parameter API on a node: declared, typed parameters with descriptors (read-only,
ranges, dynamic typing), and the pre-set, on-set and post-set callbacks. A set returns
``SetParametersResult``s: a refusal changes nothing and carries the reason."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult

from .parameter import Parameter

OnSet = Callable[[list[Parameter]], SetParametersResult]
PreSet = Callable[[list[Parameter]], list[Parameter]]
PostSet = Callable[[list[Parameter]], None]


def _as_parameter(value: Any) -> Parameter:
    return value if isinstance(value, Parameter) else Parameter(value.name, value=value.value)


def _refusal(param: Parameter, descriptor: ParameterDescriptor, current: Parameter) -> str | None:
    """Why the descriptor refuses ``param`` (rclpy's wording), or None."""
    if descriptor.read_only:
        return f"Trying to set a read-only parameter: {param.name}."
    if (
        not descriptor.dynamic_typing
        and current.type_ != Parameter.Type.NOT_SET
        and param.type_ != current.type_
    ):
        return f"Wrong parameter type, expected '{current.type_}' got '{param.type_}'"
    value = param.value
    for ranges in (descriptor.floating_point_range, descriptor.integer_range):
        if ranges and isinstance(value, int | float) and not isinstance(value, bool):
            r = ranges[0]
            in_range = r.from_value <= value <= r.to_value or math.isclose(value, r.to_value)
            on_step = (
                r.step == 0
                or value in (r.from_value, r.to_value)
                or math.isclose(((value - r.from_value) / r.step) % 1.0, 0.0, abs_tol=1e-9)
            )
            if not (in_range and on_step):
                return (
                    f"Parameter {param.name} out of range. Min: {r.from_value}, Max: {r.to_value}, "
                    f"Step: {r.step}, value: {value}"
                )
    return None


class ParameterAPI:
    """Mixed into rclpy's Node (before the bus's Node, whose overrides and table it uses)."""

    _parameters: dict[str, Any]
    _param_overrides: dict[str, Any]

    def _parameter_state(self) -> tuple[dict[str, ParameterDescriptor], list[Any], list[Any], list[Any]]:
        if not hasattr(self, "_descriptors"):
            self._descriptors: dict[str, ParameterDescriptor] = {}
            self._pre_set: list[PreSet] = []
            self._on_set: list[OnSet] = []
            self._post_set: list[PostSet] = []
        return self._descriptors, self._pre_set, self._on_set, self._post_set

    def declare_parameter(
        self, name: str, value: Any = None, descriptor: ParameterDescriptor | None = None,
        ignore_override: bool = False,
    ) -> Parameter:  # fmt: skip
        descriptors, *_ = self._parameter_state()
        if name in self._parameters:
            raise ValueError(f"parameter {name!r} has already been declared")
        if isinstance(value, Parameter.Type):  # declare_parameter('x', Parameter.Type.INTEGER)
            value = None
        if not ignore_override and name in self._param_overrides:
            value = self._param_overrides[name]
        param = Parameter(name, value=value)
        descriptors[name] = descriptor or ParameterDescriptor()
        self._parameters[name] = param
        return param

    def declare_parameters(
        self, namespace: str, parameters: Sequence[tuple[Any, ...]], ignore_override: bool = False
    ) -> list[Parameter]:
        prefix = f"{namespace}." if namespace else ""
        declared = []
        for name, *rest in parameters:
            value = rest[0] if rest else None
            descriptor = rest[1] if len(rest) > 1 else None
            declared.append(self.declare_parameter(prefix + name, value, descriptor, ignore_override))
        return declared

    def get_parameter(self, name: str) -> Parameter:
        try:
            return _as_parameter(self._parameters[name])
        except KeyError:
            raise LookupError(f"parameter {name!r} was not declared") from None

    def get_parameters(self, names: Sequence[str]) -> list[Parameter]:
        return [self.get_parameter(n) for n in names]

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        if name in self._parameters:
            return self.get_parameter(name)
        return alternative_value if alternative_value is not None else Parameter(name)

    def describe_parameter(self, name: str) -> ParameterDescriptor:
        descriptors, *_ = self._parameter_state()
        param = self.get_parameter(name)
        described: ParameterDescriptor = descriptors[name].copy()
        described.name, described.type = name, param.type_.value
        return described

    def add_on_set_parameters_callback(self, callback: OnSet) -> None:
        self._parameter_state()[2].insert(0, callback)

    def remove_on_set_parameters_callback(self, callback: OnSet) -> None:
        self._parameter_state()[2].remove(callback)

    def add_pre_set_parameters_callback(self, callback: PreSet) -> None:
        self._parameter_state()[1].append(callback)

    def add_post_set_parameters_callback(self, callback: PostSet) -> None:
        self._parameter_state()[3].append(callback)

    def set_parameters(self, parameter_list: Sequence[Any]) -> list[SetParametersResult]:
        """Each parameter on its own, as rclpy does; one result each."""
        return [self.set_parameters_atomically([p]) for p in parameter_list]

    def set_parameters_atomically(self, parameter_list: Sequence[Any]) -> SetParametersResult:
        descriptors, pre_set, on_set, post_set = self._parameter_state()
        params = [_as_parameter(p) for p in parameter_list]
        for callback in pre_set:
            params = list(callback(params))
        for param in params:
            if param.name not in self._parameters:
                return SetParametersResult(
                    successful=False, reason=f"parameter {param.name!r} is not declared"
                )
            why = _refusal(param, descriptors[param.name], self.get_parameter(param.name))
            if why is not None:
                return SetParametersResult(successful=False, reason=why)
        for callback in on_set:
            result = callback(params)
            if not result.successful:
                return SetParametersResult(successful=False, reason=result.reason)
        for param in params:
            self._parameters[param.name] = param
        for post in post_set:
            post(params)
        return SetParametersResult(successful=True)


__all__ = ["ParameterAPI"]
