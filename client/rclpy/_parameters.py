"""rclpy's parameter API on a node, as rclpy behaves: declared, typed parameters with descriptors
(read-only, ranges, dynamic typing), overrides from ``--ros-args`` (``-p``, ``--params-file``) and
the constructor, the pre-set, on-set and post-set callbacks, undeclared parameters when allowed,
and a ``/parameter_events`` message for each change. A refusal changes nothing and carries its
reason."""

from __future__ import annotations

import warnings
from collections.abc import Callable, Sequence
from typing import Any

from rcl_interfaces.msg import (
    ListParametersResult,
    ParameterDescriptor,
    ParameterEvent,
    ParameterType,
    ParameterValue,
    SetParametersResult,
)
from rcl_interfaces.srv import ListParameters

from node_runtime.bus.parameter_checks import override_as_declared, refusal
from node_runtime.bus.parameter_values import parameter_event
from rclpy.exceptions import (
    InvalidParameterException,
    InvalidParameterTypeException,
    InvalidParameterValueException,
    ParameterAlreadyDeclaredException,
    ParameterImmutableException,
    ParameterNotDeclaredException,
    ParameterUninitializedException,
)
from rclpy.parameter import PARAMETER_SEPARATOR_STRING, Parameter, parameter_value_to_python
from rclpy.qos import qos_profile_parameter_events

OnSet = Callable[[list[Parameter]], SetParametersResult]
PreSet = Callable[[list[Parameter]], list[Parameter]]
PostSet = Callable[[list[Parameter]], None]
NOT_SET = Parameter.Type.NOT_SET


class ParameterAPI:
    """Mixed into rclpy's Node (before the bus's Node, whose parameter table it keeps)."""

    _parameters: dict[str, Any]

    def _start_parameters(self) -> None:
        """The bus's Node starts its parameters at its creation; rclpy's does in _init_parameters,
        once its overrides and its own publisher's QoS are known."""

    def _init_parameters(
        self, overrides: dict[str, Any], allow_undeclared: bool, declare_overrides: bool
    ) -> None:
        """Called once by Node.__init__, after the node has joined the bus."""
        self._descriptors: dict[str, ParameterDescriptor] = {}
        self._pre_set: list[PreSet] = []
        self._on_set: list[OnSet] = []
        self._post_set: list[PostSet] = []
        self._allow_undeclared_parameters = allow_undeclared
        self._parameter_overrides = overrides
        self._parameter_event_publisher: Any = None
        self._parameter_event_publisher = self.create_publisher(  # type: ignore[attr-defined]
            ParameterEvent, "/parameter_events", qos_profile_parameter_events
        )
        if declare_overrides:
            self.declare_parameters(
                "", [(n, v, ParameterDescriptor()) for n, v in overrides.items()], ignore_override=True
            )
        if not self.has_parameter("use_sim_time"):
            self.declare_parameter("use_sim_time", False)
        if not self.has_parameter("start_type_description_service"):  # rclpy's, for its service
            self.declare_parameter(
                "start_type_description_service",
                True,
                ParameterDescriptor(
                    description="If enabled, start the ~/get_type_description service.", read_only=True
                ),
            )

    # -- declaring -----------------------------------------------------------------------------
    def declare_parameter(
        self,
        name: str,
        value: Any = None,
        descriptor: ParameterDescriptor | None = None,
        ignore_override: bool = False,
    ) -> Parameter:
        if value is None and descriptor is None:
            return self.declare_parameters("", [(name,)], ignore_override)[0]
        return self.declare_parameters(
            "", [(name, value, descriptor or ParameterDescriptor())], ignore_override
        )[0]

    def _declared(
        self, name: str, entry: tuple[Any, ...], ignore_override: bool
    ) -> tuple[Parameter, ParameterDescriptor]:
        second = entry[1] if len(entry) > 1 else None
        given = entry[2] if len(entry) > 2 else ParameterDescriptor()
        if not isinstance(given, ParameterDescriptor):
            raise TypeError(f"Third element {given} in parameters list is not a ParameterDescriptor.")
        descriptor: ParameterDescriptor = given.copy()
        if len(entry) == 1:
            warnings.warn(
                f"when declaring parameter named '{name}', declaring a parameter only providing its name "
                "is deprecated: pass a default value, a Parameter.Type or a descriptor with dynamic_typing",
                stacklevel=4,
            )
            descriptor.dynamic_typing = True
        value = None
        if isinstance(second, Parameter.Type):
            if second == NOT_SET:
                raise ValueError(f"Cannot declare parameter {{{name}}} as statically typed of type NOT_SET")
            if descriptor.dynamic_typing:
                raise ValueError(
                    f"When declaring parameter {{{name}}} passing a descriptor with `dynamic_typing=True` "
                    "is not allowed when the parameter type is provided"
                )
            descriptor.type = second.value
        else:
            value = parameter_value_to_python(second) if isinstance(second, ParameterValue) else second
            if not descriptor.dynamic_typing:
                descriptor.type = Parameter.Type.from_parameter_value(value).value
                if descriptor.type == ParameterType.PARAMETER_NOT_SET:
                    raise ValueError(
                        "Cannot declare a statically typed parameter with default value of type PARAMETER_NOT_SET"
                    )
        if not ignore_override and name in self._parameter_overrides:
            value = override_as_declared(self._parameter_overrides[name], descriptor)
        descriptor.name = name
        return Parameter(name, value=value), descriptor

    def declare_parameters(
        self, namespace: str, parameters: Sequence[tuple[Any, ...]], ignore_override: bool = False
    ) -> list[Parameter]:
        declared: list[Parameter] = []
        descriptors: dict[str, ParameterDescriptor] = {}
        for index, entry in enumerate(parameters):
            if not 1 <= len(entry) <= 3:
                raise TypeError(
                    f"Invalid parameter tuple length at index {index} in parameters list: {entry}"
                )
            if not isinstance(entry[0], str):
                raise TypeError(f"First element {entry[0]} at index {index} in parameters list is not a str.")
            name = f"{namespace}.{entry[0]}" if namespace else entry[0]
            if not name or name.startswith(".") or ".." in name:
                raise InvalidParameterException(name)
            param, descriptors[name] = self._declared(name, entry, ignore_override)
            declared.append(param)
        already = [p.name for p in declared if p.name in self._parameters]
        if already:
            raise ParameterAlreadyDeclaredException(already)
        for param in declared:
            result = self._set_common([param], descriptors, allow_not_set=True)
            if not result.successful:
                if result.reason.startswith("Wrong parameter type"):
                    raise InvalidParameterTypeException(
                        param, Parameter.Type(descriptors[param.name].type).name
                    )
                raise InvalidParameterValueException(param.name, param.value, result.reason)
        return [self._parameters[p.name] for p in declared]

    def undeclare_parameter(self, name: str) -> None:
        if not self.has_parameter(name):
            raise ParameterNotDeclaredException(name)
        if self._descriptors[name].read_only:
            raise ParameterImmutableException(name)
        gone = self._parameters.pop(name)
        del self._descriptors[name]
        self._publish_event(deleted=[gone])

    # -- reading -------------------------------------------------------------------------------
    def has_parameter(self, name: str) -> bool:
        return name in self._parameters

    def get_parameter(self, name: str) -> Parameter:
        if name in self._parameters:
            param: Parameter = self._parameters[name]
            if param.type_ != NOT_SET or self._descriptors[name].dynamic_typing:
                return param
            raise ParameterUninitializedException(name)
        if self._allow_undeclared_parameters:
            return Parameter(name, NOT_SET, None)
        raise ParameterNotDeclaredException(name)

    def get_parameters(self, names: Sequence[str]) -> list[Parameter]:
        return [self.get_parameter(n) for n in names]

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        alternative = alternative_value if alternative_value is not None else Parameter(name, NOT_SET)
        param = self._parameters.get(name)
        return alternative if param is None or param.type_ == NOT_SET else param

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        start = prefix + PARAMETER_SEPARATOR_STRING if prefix else ""
        return {n[len(start) :]: p for n, p in self._parameters.items() if n.startswith(start)}

    def get_parameter_type(self, name: str) -> int:
        if name in self._parameters:
            return int(self._parameters[name].type_.value)
        if self._allow_undeclared_parameters:
            return int(NOT_SET.value)
        raise ParameterNotDeclaredException(name)

    def get_parameter_types(self, names: Sequence[str]) -> list[int]:
        return [self.get_parameter_type(n) for n in names]

    def describe_parameter(self, name: str) -> ParameterDescriptor:
        if name in self._descriptors:
            return self._descriptors[name].copy()  # type: ignore[no-any-return]
        if self._allow_undeclared_parameters:
            return ParameterDescriptor()
        raise ParameterNotDeclaredException(name)

    def describe_parameters(self, names: Sequence[str]) -> list[ParameterDescriptor]:
        return [self.describe_parameter(n) for n in names]

    def list_parameters(self, prefixes: Sequence[str], depth: int) -> ListParametersResult:
        """Names under ``prefixes`` (all if none) at most ``depth`` separators deep (0: any)."""
        if depth < 0:
            raise ValueError("The depth must be greater than or equal to zero")
        recursive = depth == ListParameters.Request.DEPTH_RECURSIVE
        result = ListParametersResult()

        def shallow(name: str) -> bool:
            return recursive or name.count(PARAMETER_SEPARATOR_STRING) < depth

        def wanted(name: str) -> bool:
            if not prefixes:
                return shallow(name)
            return any(
                name == p or (name.startswith(p + PARAMETER_SEPARATOR_STRING) and shallow(name[len(p) + 1 :]))
                for p in prefixes
            )

        for name in filter(wanted, self._parameters):
            result.names.append(name)
            prefix = name.rpartition(PARAMETER_SEPARATOR_STRING)[0]
            if prefix and prefix not in result.prefixes:
                result.prefixes.append(prefix)
        return result

    # -- callbacks -----------------------------------------------------------------------------
    def add_pre_set_parameters_callback(self, callback: PreSet) -> None:
        self._pre_set.insert(0, callback)

    def add_on_set_parameters_callback(self, callback: OnSet) -> None:
        self._on_set.insert(0, callback)

    def add_post_set_parameters_callback(self, callback: PostSet) -> None:
        self._post_set.insert(0, callback)

    def remove_pre_set_parameters_callback(self, callback: PreSet) -> None:
        self._pre_set.remove(callback)

    def remove_on_set_parameters_callback(self, callback: OnSet) -> None:
        self._on_set.remove(callback)

    def remove_post_set_parameters_callback(self, callback: PostSet) -> None:
        self._post_set.remove(callback)

    # -- setting -------------------------------------------------------------------------------
    def set_parameters(self, parameter_list: Sequence[Parameter]) -> list[SetParametersResult]:
        """Each parameter on its own, in order, as rclpy does; one result each."""
        return [self.set_parameters_atomically([p]) for p in parameter_list]

    def set_parameters_atomically(self, parameter_list: Sequence[Parameter]) -> SetParametersResult:
        """All or none; ParameterNotDeclaredException for an undeclared name (unless allowed)."""
        params = list(parameter_list)
        if self._pre_set:
            params = [p for callback in self._pre_set for p in callback(list(parameter_list))]
            if not params:
                return SetParametersResult(
                    successful=False,
                    reason="parameter list cannot be empty, this might be due to "
                    "pre_set_parameters_callback modifying the original parameters list.",
                )
        if not all(isinstance(p, Parameter) for p in params):
            raise TypeError(f"parameter must be instance of type '{Parameter!r}'")
        undeclared = [p.name for p in params if p.name not in self._parameters]
        if undeclared and not self._allow_undeclared_parameters:
            raise ParameterNotDeclaredException(undeclared)
        return self._set_common(params)

    def _set_common(
        self,
        params: list[Parameter],
        descriptors: dict[str, ParameterDescriptor] | None = None,
        allow_not_set: bool = False,
    ) -> SetParametersResult:
        for param in params:
            descriptor = (descriptors or self._descriptors).get(param.name)
            if descriptor is not None:
                reason = refusal(
                    param.name,
                    param.value,
                    descriptor,
                    kind=param.type_.value,
                    check_read_only=descriptors is None,
                    declared=self.has_parameter(param.name),
                )
                if reason is not None:
                    return SetParametersResult(successful=False, reason=reason)
                if descriptor.dynamic_typing:  # rclpy's descriptor takes the type it was given
                    descriptor.type = param.type_.value
        for callback in self._on_set:
            result = callback(params)
            if not result.successful:
                return result
        new: list[Parameter] = []
        changed: list[Parameter] = []
        deleted: list[Parameter] = []
        for param in params:
            if not allow_not_set and param.type_ == NOT_SET:
                deleted.append(param)
                self._parameters.pop(param.name, None)
                self._descriptors.pop(param.name, None)
                continue
            if descriptors is not None:
                self._descriptors[param.name] = descriptors[param.name]
            elif param.name not in self._descriptors:
                self._descriptors[param.name] = ParameterDescriptor(name=param.name, dynamic_typing=True)
            (new if self.get_parameter_or(param.name).type_ == NOT_SET else changed).append(param)
            self._parameters[param.name] = param
        self._publish_event(new, changed, deleted)
        for post in self._post_set:
            post(params)
        return SetParametersResult(successful=True)

    def _publish_event(
        self,
        new: Sequence[Parameter] = (),
        changed: Sequence[Parameter] = (),
        deleted: Sequence[Parameter] = (),
    ) -> None:
        publisher = self._parameter_event_publisher
        if publisher is None or publisher.destroyed:
            return
        publisher.publish(
            parameter_event(
                self.get_fully_qualified_name(),  # type: ignore[attr-defined]
                self.get_clock().now().to_msg(),  # type: ignore[attr-defined]
                [p.to_parameter_msg() for p in new],
                [p.to_parameter_msg() for p in changed],
                [p.to_parameter_msg() for p in deleted],
            )
        )


__all__ = ["ParameterAPI"]
