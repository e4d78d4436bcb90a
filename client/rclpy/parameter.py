"""rclpy's Parameter: a name, a typed value (``Parameter.Type``) and its rcl_interfaces messages."""

from __future__ import annotations

from enum import IntEnum
from typing import Any

from rcl_interfaces.msg import Parameter as ParameterMsg
from rcl_interfaces.msg import ParameterType, ParameterValue

from node_runtime.params_file import SEPARATOR, read_params_file, value_from_text

PARAMETER_SEPARATOR_STRING = SEPARATOR

_ARRAYS = {
    "BYTE_ARRAY": bytes,
    "BOOL_ARRAY": bool,
    "INTEGER_ARRAY": int,
    "DOUBLE_ARRAY": float,
    "STRING_ARRAY": str,
}
_FIELDS = {
    1: "bool_value",
    2: "integer_value",
    3: "double_value",
    4: "string_value",
    5: "byte_array_value",
    6: "bool_array_value",
    7: "integer_array_value",
    8: "double_array_value",
    9: "string_array_value",
}


class Parameter:
    class Type(IntEnum):  # rclpy's: str() of one is its number
        NOT_SET = ParameterType.PARAMETER_NOT_SET
        BOOL = ParameterType.PARAMETER_BOOL
        INTEGER = ParameterType.PARAMETER_INTEGER
        DOUBLE = ParameterType.PARAMETER_DOUBLE
        STRING = ParameterType.PARAMETER_STRING
        BYTE_ARRAY = ParameterType.PARAMETER_BYTE_ARRAY
        BOOL_ARRAY = ParameterType.PARAMETER_BOOL_ARRAY
        INTEGER_ARRAY = ParameterType.PARAMETER_INTEGER_ARRAY
        DOUBLE_ARRAY = ParameterType.PARAMETER_DOUBLE_ARRAY
        STRING_ARRAY = ParameterType.PARAMETER_STRING_ARRAY

        @classmethod
        def from_parameter_value(cls, value: Any) -> Parameter.Type:
            """The type a Python value has as a parameter; TypeError if it has none."""
            if value is None:
                return cls.NOT_SET
            for kind, test in ((cls.BOOL, bool), (cls.INTEGER, int), (cls.DOUBLE, float), (cls.STRING, str)):
                if isinstance(value, test):
                    return kind
            if isinstance(value, bytes):
                return cls.BYTE_ARRAY
            if isinstance(value, list | tuple) and value:
                for name, element in _ARRAYS.items():
                    if all(type(v) is element for v in value):
                        return cls[name]
            if isinstance(value, list | tuple) and not value:
                return cls.STRING_ARRAY  # rclpy cannot tell an empty array's type either
            raise TypeError(f"{value!r} is not a parameter value (bool, int, float, str or a list of one)")

        def check(self, value: Any) -> bool:
            try:
                return Parameter.Type.from_parameter_value(value) == self
            except TypeError:
                return False

    def __init__(self, name: str, type_: Parameter.Type | None = None, value: Any = None) -> None:
        if type_ is None:
            type_ = Parameter.Type.from_parameter_value(value)
        elif not isinstance(type_, Parameter.Type):
            raise TypeError(f"type_ must be a Parameter.Type, got {type_!r}")
        if type_ != Parameter.Type.NOT_SET and not type_.check(value):
            raise ValueError(f"parameter {name!r}: {value!r} is not a {type_.name}")
        self._name = name
        self._type = type_
        self._value = value

    @property
    def name(self) -> str:
        return self._name

    @property
    def type_(self) -> Parameter.Type:
        return self._type

    @property
    def value(self) -> Any:
        return self._value

    @value.setter
    def value(self, value: Any) -> None:  # the bus's tools set a value they have checked
        self._value = value
        self._type = Parameter.Type.from_parameter_value(value)

    def get_parameter_value(self) -> ParameterValue:
        msg = ParameterValue(type=self._type.value)
        if self._type != Parameter.Type.NOT_SET:
            value = self._value
            setattr(
                msg, _FIELDS[self._type.value], list(value) if isinstance(value, tuple | bytes) else value
            )
        return msg

    def to_parameter_msg(self) -> ParameterMsg:
        return ParameterMsg(name=self._name, value=self.get_parameter_value())

    @classmethod
    def from_parameter_msg(cls, msg: ParameterMsg) -> Parameter:
        kind = cls.Type(msg.value.type)
        value: Any = None if kind == cls.Type.NOT_SET else getattr(msg.value, _FIELDS[kind.value])
        if hasattr(value, "tolist"):  # a numeric sequence is an array.array
            value = value.tolist()
        return cls(msg.name, kind, value)

    def __repr__(self) -> str:
        return f"Parameter(name={self._name!r}, type_={self._type.name}, value={self._value!r})"


def parameter_value_to_python(parameter_value: ParameterValue) -> Any:
    """The Python value a ParameterValue message holds (None when NOT_SET)."""
    kind = parameter_value.type
    if kind == ParameterType.PARAMETER_NOT_SET:
        return None
    if kind not in _FIELDS:
        raise RuntimeError(f"unexpected parameter type {kind}")
    value = getattr(parameter_value, _FIELDS[kind])
    return value.tolist() if hasattr(value, "tolist") else list(value) if kind >= 5 else value


def get_parameter_value(string_value: str) -> ParameterValue:
    """A ParameterValue from text, typed as ``ros2 param set`` types its argument."""
    value = value_from_text(string_value)
    if isinstance(value, list) and not value:
        return ParameterValue(type=ParameterType.PARAMETER_BOOL_ARRAY)  # rclpy's choice for []
    return Parameter("", value=value).get_parameter_value()


def parameter_dict_from_yaml_file(
    parameter_file: str,
    use_wildcard: bool = False,
    target_nodes: list[str] | None = None,
    namespace: str = "",
) -> dict[str, ParameterMsg]:
    """A parameters file's parameters as messages by name: every node's (``/**`` first when
    ``use_wildcard``), or only ``target_nodes``' sections; ``namespace`` prefixes each name."""
    parsed = read_params_file(parameter_file)
    if target_nodes:
        known = [node for node, _ in parsed.sections]
        missing = [n for n in target_nodes if n not in known]
        if missing:
            raise RuntimeError(
                f"Param file does not contain parameters for {missing[0]}, only for nodes: {known}"
            )
        values: dict[str, Any] = {}
        for node, params in parsed.sections:
            if node in target_nodes or (use_wildcard and node == "/**"):
                values.update(params)
    else:
        values = parsed.every_section(use_wildcard)
    return {
        namespace + name: Parameter(namespace + name, value=value).to_parameter_msg()
        for name, value in values.items()
    }


__all__ = [
    "PARAMETER_SEPARATOR_STRING",
    "Parameter",
    "get_parameter_value",
    "parameter_dict_from_yaml_file",
    "parameter_value_to_python",
]
