"""Typed ROS 2 message values: fields checked on assignment, JSON in and out by ROS field names.

A message class is declared by its ROS type name (``class Vector3(Message,
type_name="geometry_msgs/msg/Vector3")``); its fields, defaults and constants come from the
interface definition (server.msgs.idl), so the generated classes only add what mypy needs to
see. Messages stay mutable like rclpy's (lab code does ``self.abort.data = True``); the bus
copies a message when it is published, so a subscriber never sees a later change made by the
publisher. How each field holds its value is server.msgs._field's.
"""

from __future__ import annotations

import array
import keyword
from collections.abc import Callable, Mapping
from typing import Any, ClassVar

from ._field import Field, MessageError
from .idl import MessageSpec, ServiceSpec, lab_definitions

_CLASSES: dict[str, type[Message]] = {}


class Message:
    """Base of every message type; a subclass names its type: ``class X(Message, type_name=...)``."""

    TYPE: ClassVar[str] = ""
    SPEC: ClassVar[MessageSpec]
    FIELDS: ClassVar[tuple[Field, ...]] = ()
    _FIELD_MAP: ClassVar[dict[str, Field]] = {}
    __slots__ = ()

    def __init_subclass__(
        cls, type_name: str | None = None, spec: MessageSpec | None = None, **kwargs: Any
    ) -> None:
        super().__init_subclass__(**kwargs)
        if type_name is None:
            return
        spec = spec or lab_definitions().message(type_name)
        declared = tuple(getattr(cls, "__slots__", ()))
        if declared != tuple(f.name for f in spec.fields):
            raise TypeError(
                f"{cls.__name__} declares fields {declared}; {type_name} has "
                f"{tuple(f.name for f in spec.fields)} (regenerate: python -m server.msgs.generate)"
            )
        fields = []
        for f in spec.fields:
            if f.is_primitive:
                fields.append(Field(f, f.base))
            elif f.base in _CLASSES:
                fields.append(Field(f, _CLASSES[f.base]))
            else:
                raise TypeError(f"{type_name}.{f.name}: {f.base} has no class yet (declare it first)")
        cls.TYPE = type_name
        cls.SPEC = spec
        cls.FIELDS = tuple(fields)
        cls._FIELD_MAP = {f.name: f for f in fields}
        for constant in spec.constants:
            setattr(cls, constant.name, constant.value)
        _compile_methods(cls)
        _CLASSES[type_name] = cls

    def __init__(self, **kwargs: Any) -> None:
        for f in self.FIELDS:
            if f.name in kwargs:
                setattr(self, f.name, kwargs.pop(f.name))
            else:
                object.__setattr__(self, f.name, f.initial())
        if kwargs:
            raise TypeError(f"{self.TYPE} has no field(s) {', '.join(sorted(kwargs))}")

    def __setattr__(self, name: str, value: Any) -> None:
        field = self._FIELD_MAP.get(name)
        if field is None:
            raise AttributeError(f"{self.TYPE} has no field {name!r}")
        object.__setattr__(self, name, field.check(value, name))

    def copy(self) -> Any:
        """A deep copy that skips re-validation (the values are already checked)."""
        new = object.__new__(type(self))
        for f in self.FIELDS:
            object.__setattr__(new, f.name, f.copy_value(getattr(self, f.name)))
        return new

    def to_dict(self) -> dict[str, Any]:
        return {f.name: f.to_json(getattr(self, f.name)) for f in self.FIELDS}

    @classmethod
    def from_dict(cls, data: Any, path: str = "") -> Any:
        """Build from JSON-like data; missing fields keep defaults, unknown ones are an error."""
        if not isinstance(data, Mapping):
            raise MessageError(path, f"expected an object for {cls.TYPE}, got {type(data).__name__}")
        msg = cls()
        for key, value in data.items():
            sub = f"{path}.{key}" if path else str(key)
            field = cls._FIELD_MAP.get(key)
            if field is None:
                raise MessageError(sub, f"{cls.TYPE} has no field {key!r}")
            object.__setattr__(msg, key, field.from_json(value, sub))
        return msg

    @classmethod
    def get_fields_and_field_types(cls) -> dict[str, str]:
        """rclpy's introspection call: field name → ROS type name."""
        return {f.name: f.type_name for f in cls.FIELDS}

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return all(f.equal(getattr(self, f.name), getattr(other, f.name)) for f in self.FIELDS)

    __hash__ = None  # type: ignore[assignment]  # mutable, like rclpy's messages

    def __repr__(self) -> str:
        pkg, kind, name = self.TYPE.split("/")
        inner = ", ".join(f"{f.name}={getattr(self, f.name)!r}" for f in self.FIELDS)
        return f"{pkg}.{kind}.{name}({inner})"


def _copy_expression(field: Field, value: str) -> str:
    """Python source for what ``field.copy_value(value)`` returns."""
    if not field.array:
        return value if isinstance(field.kind, str) else f"{value}.copy()"
    if field.typecode is not None:
        return f"_array({field.typecode!r}, {value})"
    if field.numeric_array:
        return f"{value}.copy()"
    return f"list({value})" if isinstance(field.kind, str) else f"[v.copy() for v in {value}]"


def _compile_methods(cls: type[Message]) -> None:
    """``__init__`` and ``copy`` written out for this class's fields, as dataclasses writes its
    methods: the same results as Message's loops over FIELDS, without their per-field overhead
    (messages are built and copied on every publish). Slots are set through their descriptors,
    past the checking ``__setattr__``; values given to ``__init__`` still go through Field.check."""
    names = [f.name for f in cls.FIELDS]
    if any(keyword.iskeyword(n) or n in ("self", "new") or n.startswith("_") for n in names):
        return  # a name Python would not take as a parameter: the generic methods serve
    env: dict[str, Any] = {
        "_new": object.__new__, "_array": array.array, "_missing": _MISSING, "_type": cls.TYPE, "_sorted": sorted, "_type_of": type,
    }  # fmt: skip
    params, init_lines, copy_lines = [], [], []
    for i, f in enumerate(cls.FIELDS):
        env[f"_set{i}"] = cls.__dict__[f.name].__set__  # the slot's own setter
        env[f"_check{i}"] = f.check
        if not f.array and isinstance(f.kind, str):
            env[f"_default{i}"] = f.default  # immutable: shared by every message
            initial = f"_default{i}"
        elif not f.array:
            env[f"_kind{i}"] = f.kind
            initial = f"_kind{i}()"
        else:
            env[f"_initial{i}"] = f.initial
            initial = f"_initial{i}()"
        params.append(f"{f.name}=_missing")
        value = f"{initial} if {f.name} is _missing else _check{i}({f.name}, {f.name!r})"
        if f.exact is not None:  # Field.check's first test, inline: a float, a bool, a nested message
            env[f"_exact{i}"] = f.exact
            value = f"{f.name} if _type_of({f.name}) is _exact{i} else {value}"  # a field may be named type
        init_lines.append(f"    _set{i}(self, {value})")
        copy_lines.append(f"    _set{i}(new, {_copy_expression(f, 'self.' + f.name)})")
    source = "\n".join([
        f"def __init__(self, {', '.join(['*', *params, '**unknown'] if params else ['**unknown'])}):",
        *init_lines,
        "    if unknown:",
        "        raise TypeError(f\"{_type} has no field(s) {', '.join(_sorted(unknown))}\")",
        "def copy(self):",
        "    new = _new(type(self))",
        *copy_lines,
        "    return new",
    ])  # fmt: skip
    exec(compile(source, f"<{cls.TYPE} methods>", "exec"), env)
    for name in ("__init__", "copy"):
        method: Callable[..., Any] = env[name]
        method.__qualname__ = f"{cls.__qualname__}.{name}"
        setattr(cls, name, method)


_MISSING: Any = object()


class Service:
    """Base of every service type: ``Request`` and ``Response`` message classes, as in rclpy."""

    TYPE: ClassVar[str] = ""
    Request: ClassVar[type[Message]]
    Response: ClassVar[type[Message]]

    def __init_subclass__(
        cls, type_name: str | None = None, spec: ServiceSpec | None = None, **kwargs: Any
    ) -> None:
        super().__init_subclass__(**kwargs)
        if type_name is None:
            return
        spec = spec or lab_definitions().services[type_name]
        if spec.request.name != cls.Request.TYPE or spec.response.name != cls.Response.TYPE:
            raise TypeError(f"{cls.__name__}: Request/Response do not match {type_name}")
        cls.TYPE = type_name


def define_message(spec: MessageSpec) -> type[Message]:
    """A message class made at run time from a parsed definition (its nested types must exist)."""
    namespace = {"__slots__": tuple(f.name for f in spec.fields), "__module__": __name__}
    return type(spec.name.rsplit("/", 1)[1], (Message,), namespace, type_name=spec.name, spec=spec)


def message_class(type_name: str) -> type[Message]:
    """The class declared for a full type name (KeyError if none)."""
    return _CLASSES[type_name]


def message_classes() -> dict[str, type[Message]]:
    return dict(_CLASSES)
