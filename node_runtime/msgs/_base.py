"""Typed ROS 2 message values: fields checked on assignment, JSON in and out by ROS field names.

A message class is declared by its ROS type name (``class Vector3(Message,
type_name="geometry_msgs/msg/Vector3")``); its fields, defaults and constants come from the
interface definition (node_runtime.msgs.idl), so the generated classes only add what mypy needs to
see. Messages stay mutable like rclpy's (lab code does ``self.abort.data = True``); the bus
copies a message when it is published, so a subscriber never sees a later change made by the
publisher. How each field holds its value is node_runtime.msgs._field's. Classes are also made at run time from parsed definitions (a student's own
interfaces): :func:`define_message` and :func:`define_service`.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping
from typing import Any, ClassVar

from node_runtime.msgs._field import FLOAT32_MAX, MAX_ARRAY_ITEMS, MAX_STRING_CHARS, Field, MessageError
from node_runtime.msgs.compiled import compile_methods
from node_runtime.msgs.definitions import lab_definitions
from node_runtime.msgs.idl import MessageSpec, ServiceSpec, parse_message

__all__ = [
    "FLOAT32_MAX",
    "MAX_ARRAY_ITEMS",
    "MAX_STRING_CHARS",
    "Field",
    "Message",
    "MessageError",
    "Service",
    "define_message",
    "define_service",
    "load_generated",
    "message_class",
    "message_classes",
    "service_class",
    "service_classes",
]

_CLASSES: dict[str, type[Message]] = {}
_SERVICES: dict[str, type[Service]] = {}


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
                f"{tuple(f.name for f in spec.fields)} (regenerate: python -m node_runtime.msgs.generate)"
            )
        fields = []
        for f in spec.fields:
            if f.is_primitive:
                fields.append(Field(f, f.base))
            elif (nested := _declared(f.base)) is not None:
                fields.append(Field(f, nested))
            else:
                raise TypeError(f"{type_name}.{f.name}: {f.base} has no class yet (declare it first)")
        cls.TYPE = type_name
        cls.SPEC = spec
        cls.FIELDS = tuple(fields)
        cls._FIELD_MAP = {f.name: f for f in fields}
        for constant in spec.constants:
            setattr(cls, constant.name, constant.value)
        compile_methods(cls)
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


class _EventType:
    """``<Srv>.Event``, as rosidl generates it beside Request and Response: the message a
    service's introspection events travel in (the call's info, then at most one request and one
    response). Made at its first use, once per service type."""

    def __get__(self, _instance: object, owner: type[Service]) -> type[Message]:
        made = owner.__dict__.get("_event")
        if made is None:
            text = (
                "service_msgs/ServiceEventInfo info\n"
                f"{owner.Request.TYPE}[<=1] request\n{owner.Response.TYPE}[<=1] response\n"
            )
            made = define_message(parse_message(f"{owner.TYPE}_Event", text), owner.__module__)
            owner._event = made
        return made


class Service:
    """Base of every service type: ``Request``, ``Response`` and ``Event`` message classes, as in
    rclpy."""

    TYPE: ClassVar[str] = ""
    Request: ClassVar[type[Message]]
    Response: ClassVar[type[Message]]
    Event: ClassVar[type[Message]] = _EventType()  # type: ignore[assignment]
    _event: ClassVar[type[Message] | None] = None

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
        _SERVICES[type_name] = cls


def define_message(spec: MessageSpec, module: str = __name__) -> type[Message]:
    """A message class made at run time from a parsed definition (its nested types must exist);
    ``module`` is where it says it lives (``tutorial_interfaces.msg``)."""
    namespace = {"__slots__": tuple(f.name for f in spec.fields), "__module__": module}
    return type(spec.name.rsplit("/", 1)[1], (Message,), namespace, type_name=spec.name, spec=spec)


def define_service(spec: ServiceSpec, module: str = __name__) -> type[Service]:
    """A service class and its Request and Response classes, made at run time from a definition."""
    namespace = {
        "Request": define_message(spec.request, module),
        "Response": define_message(spec.response, module),
        "__module__": module,
    }
    return type(spec.name.rsplit("/", 1)[1], (Service,), namespace, type_name=spec.name, spec=spec)


def load_generated(package: str | None = None) -> bool:
    """Import the generated module of the lab's ``package`` (every one if None), whose classes
    declare themselves as it runs; False if the lab generates no such package. A process loads
    only the packages whose types it uses (each costs a few milliseconds to declare)."""
    from node_runtime.msgs.generated import PACKAGES  # names only: generated/__init__.py imports no module

    if package is not None and package not in PACKAGES:
        return False
    for name in PACKAGES if package is None else (package,):
        importlib.import_module(f"{__package__}.generated.{name}")
    return True


def _declared(type_name: str) -> type[Message] | None:
    cls = _CLASSES.get(type_name)
    if cls is None and load_generated(type_name.split("/")[0]):
        cls = _CLASSES.get(type_name)
    return cls


def message_class(type_name: str) -> type[Message]:
    """The class declared for a full type name (KeyError if none)."""
    cls = _declared(type_name)
    if cls is None:
        raise KeyError(type_name)
    return cls


def message_classes() -> dict[str, type[Message]]:
    load_generated()
    return dict(_CLASSES)


def service_class(type_name: str) -> type[Service]:
    """The class declared for ``pkg/srv/Name`` (KeyError if none)."""
    if type_name not in _SERVICES:
        load_generated(type_name.split("/")[0])
    return _SERVICES[type_name]


def service_classes() -> dict[str, type[Service]]:
    load_generated()
    return dict(_SERVICES)
