"""Typed ROS 2 message values: fields checked on assignment, JSON in and out by ROS field names.

Messages stay mutable like rclpy's (lab code does ``self.abort.data = True``); the bus copies a
message when it is published, so a subscriber never sees a later change made by the publisher.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

INT_RANGES: dict[str, tuple[int, int]] = {
    "int8": (-(2**7), 2**7 - 1),
    "uint8": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1),
    "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1),
    "uint64": (0, 2**64 - 1),
}
FLOAT_TYPES = ("float32", "float64")
MAX_STRING_CHARS = 65536


class MessageError(ValueError):
    """A message value does not fit its type; ``path`` names the field (``pose.position.x``)."""

    def __init__(self, path: str, problem: str) -> None:
        self.path = path
        self.problem = problem
        super().__init__(f"{path}: {problem}" if path else problem)


@dataclass(frozen=True)
class Field:
    """One field: ``kind`` is a ROS primitive name (``float64``) or a message class."""

    name: str
    kind: str | type[Message]
    default: Any = None

    @property
    def type_name(self) -> str:
        return self.kind if isinstance(self.kind, str) else self.kind.TYPE


def _check_primitive(kind: str, value: Any, path: str) -> Any:
    if kind == "bool":
        if not isinstance(value, bool):
            raise MessageError(path, f"expected a bool, got {type(value).__name__}")
        return value
    if kind in INT_RANGES:
        if isinstance(value, bool) or not isinstance(value, int):
            raise MessageError(path, f"expected an integer ({kind}), got {type(value).__name__} {value!r}")
        lo, hi = INT_RANGES[kind]
        if not lo <= value <= hi:
            raise MessageError(path, f"{value} is out of range for {kind} ({lo}..{hi})")
        return value
    if kind in FLOAT_TYPES:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise MessageError(path, f"expected a number ({kind}), got {type(value).__name__}")
        value = float(value)
        if kind == "float32" and math.isfinite(value) and abs(value) > 3.4028234663852886e38:
            raise MessageError(path, f"{value} is out of range for float32")
        return value
    if kind == "string":
        if not isinstance(value, str):
            raise MessageError(path, f"expected a string, got {type(value).__name__}")
        if len(value) > MAX_STRING_CHARS:
            raise MessageError(path, f"string longer than {MAX_STRING_CHARS} characters")
        return value
    raise MessageError(path, f"unsupported field kind {kind}")


class Message:
    """Base of every message type. Subclasses set ``TYPE`` and ``FIELDS``."""

    TYPE: ClassVar[str] = ""
    FIELDS: ClassVar[tuple[Field, ...]] = ()
    _FIELD_MAP: ClassVar[dict[str, Field]] = {}
    __slots__ = ()

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls._FIELD_MAP = {f.name: f for f in cls.FIELDS}

    def __init__(self, **kwargs: Any) -> None:
        for f in self.FIELDS:
            if f.name in kwargs:
                setattr(self, f.name, kwargs.pop(f.name))
            elif isinstance(f.kind, str):
                object.__setattr__(self, f.name, f.default)
            else:
                object.__setattr__(self, f.name, f.kind())
        if kwargs:
            raise TypeError(f"{self.TYPE} has no field(s) {', '.join(sorted(kwargs))}")

    def __setattr__(self, name: str, value: Any) -> None:
        field = self._FIELD_MAP.get(name)
        if field is None:
            raise AttributeError(f"{self.TYPE} has no field {name!r}")
        if isinstance(field.kind, str):
            value = _check_primitive(field.kind, value, name)
        elif not isinstance(value, field.kind):
            raise MessageError(name, f"expected {field.kind.TYPE}, got {type(value).__name__}")
        object.__setattr__(self, name, value)

    def copy(self) -> Message:
        """A deep copy that skips re-validation (the values are already checked)."""
        new = object.__new__(type(self))
        for f in self.FIELDS:
            v = getattr(self, f.name)
            object.__setattr__(new, f.name, v if isinstance(f.kind, str) else v.copy())
        return new

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for f in self.FIELDS:
            v = getattr(self, f.name)
            out[f.name] = v if isinstance(f.kind, str) else v.to_dict()
        return out

    @classmethod
    def from_dict(cls, data: Any, path: str = "") -> Message:
        """Build from JSON-like data; missing fields keep defaults, unknown ones are an error."""
        if not isinstance(data, Mapping):
            raise MessageError(path, f"expected an object for {cls.TYPE}, got {type(data).__name__}")
        msg = cls()
        for key, value in data.items():
            sub = f"{path}.{key}" if path else str(key)
            field = cls._FIELD_MAP.get(key)
            if field is None:
                raise MessageError(sub, f"{cls.TYPE} has no field {key!r}")
            if isinstance(field.kind, str):
                object.__setattr__(msg, key, _check_primitive(field.kind, value, sub))
            else:
                object.__setattr__(msg, key, field.kind.from_dict(value, sub))
        return msg

    @classmethod
    def get_fields_and_field_types(cls) -> dict[str, str]:
        """rclpy's introspection call: field name → ROS type name."""
        return {f.name: f.type_name for f in cls.FIELDS}

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return all(getattr(self, f.name) == getattr(other, f.name) for f in self.FIELDS)

    def __repr__(self) -> str:
        pkg, _, name = self.TYPE.split("/")
        inner = ", ".join(f"{f.name}={getattr(self, f.name)!r}" for f in self.FIELDS)
        return f"{pkg}.msg.{name}({inner})"


def define(type_name: str, fields: list[Field], namespace: dict[str, Any] | None = None) -> type[Message]:
    """Create a message class with slots for its fields (and optional constants)."""
    attrs: dict[str, Any] = {
        "TYPE": type_name,
        "FIELDS": tuple(fields),
        "__slots__": tuple(f.name for f in fields),
    }
    attrs.update(namespace or {})
    return type(type_name.rsplit("/", 1)[1], (Message,), attrs)
