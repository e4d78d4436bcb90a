"""Typed ROS 2 message values: fields checked on assignment, JSON in and out by ROS field names.

A message class is declared by its ROS type name (``class Vector3(Message,
type_name="geometry_msgs/msg/Vector3")``); its fields, defaults and constants come from the
interface definition (server.msgs.idl), so the generated classes only add what mypy needs to
see. Messages stay mutable like rclpy's (lab code does ``self.abort.data = True``); the bus
copies a message when it is published, so a subscriber never sees a later change made by the
publisher. Numeric arrays are numpy arrays (as rclpy's fixed-size arrays are); arrays of strings
and of messages are lists.
"""

from __future__ import annotations

import keyword
import math
import sys
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, ClassVar

if TYPE_CHECKING:
    import numpy as np

from .idl import FLOAT_TYPES, INT_RANGES, STRING_TYPES, FieldSpec, MessageSpec, lab_definitions

MAX_STRING_CHARS = 65536
MAX_ARRAY_ITEMS = 65536
FLOAT32_MAX = 3.4028234663852886e38
# numpy (about 20 MiB resident) is imported at the first numeric array, so a node process whose
# messages have none never loads it; until something imports it, no value can be a numpy one.
NUMPY_DTYPES: dict[str, str] = {
    "bool": "bool",
    "byte": "uint8",
    "char": "uint8",
    "int8": "int8",
    "uint8": "uint8",
    "int16": "int16",
    "uint16": "uint16",
    "int32": "int32",
    "uint32": "uint32",
    "int64": "int64",
    "uint64": "uint64",
    "float32": "float32",
    "float64": "float64",
}
# Any, so that isinstance keeps a checked value's type open (it may be numpy's)
_PLAIN_SCALARS: tuple[tuple[Any, ...], ...] = ((bool,), (int,), (int, float))
_numpy_scalars: tuple[tuple[Any, ...], ...] | None = None
_CLASSES: dict[str, type[Message]] = {}


def _numpy() -> Any:
    import numpy

    return numpy


def _scalar_types() -> tuple[tuple[Any, ...], ...]:
    """The types a bool, an integer and a number may have: Python's, and numpy's once it is loaded."""
    global _numpy_scalars
    if _numpy_scalars is not None:
        return _numpy_scalars
    numpy = sys.modules.get("numpy")
    if numpy is None:
        return _PLAIN_SCALARS
    _numpy_scalars = ((bool, numpy.bool_), (int, numpy.integer), (int, float, numpy.integer, numpy.floating))
    return _numpy_scalars


def _is_ndarray(value: Any) -> bool:
    numpy = sys.modules.get("numpy")
    return numpy is not None and isinstance(value, numpy.ndarray)


class MessageError(ValueError):
    """A message value does not fit its type; ``path`` names the field (``pose.position.x``)."""

    def __init__(self, path: str, problem: str) -> None:
        self.path = path
        self.problem = problem
        super().__init__(f"{path}: {problem}" if path else problem)


def check_primitive(kind: str, value: Any, path: str, bound: int | None = None) -> Any:
    """``value`` as a field of ROS type ``kind`` holds it, or a MessageError naming ``path``."""
    bools, integers, numbers = _scalar_types()
    if kind == "bool":
        if not isinstance(value, bools):
            raise MessageError(path, f"expected a bool, got {type(value).__name__}")
        return bool(value)
    if kind in INT_RANGES:
        if isinstance(value, bools) or not isinstance(value, integers):
            raise MessageError(path, f"expected an integer ({kind}), got {type(value).__name__} {value!r}")
        lo, hi = INT_RANGES[kind]
        if not lo <= value <= hi:
            raise MessageError(path, f"{value} is out of range for {kind} ({lo}..{hi})")
        return int(value)
    if kind in FLOAT_TYPES:
        if isinstance(value, bools) or not isinstance(value, numbers):
            raise MessageError(path, f"expected a number ({kind}), got {type(value).__name__}")
        try:
            number = float(value)
        except OverflowError:
            raise MessageError(path, f"{value} is out of range for {kind}") from None
        if kind == "float32" and math.isfinite(number) and abs(number) > FLOAT32_MAX:
            raise MessageError(path, f"{number} is out of range for float32")
        return number
    if kind in STRING_TYPES:
        if not isinstance(value, str):
            raise MessageError(path, f"expected a string, got {type(value).__name__}")
        limit = MAX_STRING_CHARS if bound is None else bound
        if len(value) > limit:
            raise MessageError(path, f"string longer than {limit} characters")
        return value
    raise MessageError(path, f"unsupported field kind {kind}")


class Field:
    """One field of a message class: its spec, and ``kind``, the primitive name or message class
    of one value (of one element, for an array)."""

    __slots__ = ("array", "bound", "default", "exact", "kind", "name", "size", "spec", "string_bound")

    def __init__(self, spec: FieldSpec, kind: str | type[Message]) -> None:
        self.spec = spec
        self.name = spec.name
        self.kind = kind
        self.array = spec.is_array
        self.size = spec.array_size
        self.bound = spec.array_bound
        self.string_bound = spec.string_bound
        if spec.default is not None:
            self.default: Any = spec.default
        elif isinstance(kind, str):
            self.default = (
                False if kind == "bool" else "" if kind in STRING_TYPES else 0.0 if kind in FLOAT_TYPES else 0
            )
        else:
            self.default = None
        # A value of exactly this type is stored as it is: a float for float64, a bool, a message of
        # the field's own class. check_primitive would return it unchanged; this skips its tests.
        self.exact: type | None = None
        if not self.array:
            self.exact = float if kind == "float64" else bool if kind == "bool" else None
            if not isinstance(kind, str):
                self.exact = kind

    @property
    def type_name(self) -> str:
        """The field's ROS type: ``float64``, ``std_msgs/msg/Header``, ``float64[9]``, ``int32[<=5]``."""
        return self.spec.type_text

    @property
    def numeric_array(self) -> bool:
        return self.array and isinstance(self.kind, str) and self.kind not in STRING_TYPES

    def initial(self) -> Any:
        """A fresh default value for a new message."""
        if not self.array:
            return self.default if isinstance(self.kind, str) else self.kind()
        if self.numeric_array:
            kind = str(self.kind)
            if isinstance(self.default, list):
                return _numpy().array(self.default, dtype=NUMPY_DTYPES[kind])
            return _numpy().zeros(self.size or 0, dtype=NUMPY_DTYPES[kind])
        if isinstance(self.kind, str):
            return list(self.default) if isinstance(self.default, list) else [""] * (self.size or 0)
        return [self.kind() for _ in range(self.size or 0)]

    def check(self, value: Any, path: str) -> Any:
        """``value`` as this field stores it (a MessageError naming ``path`` if it does not fit)."""
        if type(value) is self.exact:
            return value
        if not self.array:
            if isinstance(self.kind, str):
                return check_primitive(self.kind, value, path, self.string_bound)
            if not isinstance(value, self.kind):
                raise MessageError(path, f"expected {self.kind.TYPE}, got {type(value).__name__}")
            return value
        items = self._check_length(value, path)
        if self.numeric_array:
            return self._numeric_array(items, path)
        kind = self.kind
        if isinstance(kind, str):
            return [check_primitive(kind, v, f"{path}[{i}]", self.string_bound) for i, v in enumerate(items)]
        for i, item in enumerate(items):
            if not isinstance(item, kind):
                raise MessageError(f"{path}[{i}]", f"expected {kind.TYPE}, got {type(item).__name__}")
        return list(items)

    def _check_length(self, value: Any, path: str) -> Sequence[Any] | np.ndarray[Any, Any]:
        ndarray = _is_ndarray(value)
        if isinstance(value, str | bytes | Mapping) or not (ndarray or isinstance(value, Sequence)):
            raise MessageError(path, f"expected an array ({self.type_name}), got {type(value).__name__}")
        if ndarray and value.ndim != 1:
            raise MessageError(path, f"expected a one-dimensional array, got shape {value.shape}")
        n = len(value)
        if self.size is not None and n != self.size:
            raise MessageError(path, f"expected exactly {self.size} items, got {n}")
        limit = self.bound if self.bound is not None else MAX_ARRAY_ITEMS
        if n > limit:
            raise MessageError(path, f"more than {limit} items ({n})")
        checked: Sequence[Any] | np.ndarray[Any, Any] = value
        return checked

    def _numeric_array(self, items: Sequence[Any] | np.ndarray[Any, Any], path: str) -> np.ndarray[Any, Any]:
        kind = str(self.kind)
        dtype = NUMPY_DTYPES[kind]
        numpy = _numpy()
        if isinstance(items, numpy.ndarray) and items.dtype == dtype:
            return items.copy()  # type: ignore[no-any-return]
        checked = [check_primitive(kind, v, f"{path}[{i}]") for i, v in enumerate(items)]
        return numpy.array(checked, dtype=dtype)  # type: ignore[no-any-return]

    def copy_value(self, value: Any) -> Any:
        if not self.array:
            return value if isinstance(self.kind, str) else value.copy()
        if self.numeric_array:
            return value.copy()
        return list(value) if isinstance(self.kind, str) else [v.copy() for v in value]

    def to_json(self, value: Any) -> Any:
        if not self.array:
            return value if isinstance(self.kind, str) else value.to_dict()
        if self.numeric_array:
            return value.tolist()
        return list(value) if isinstance(self.kind, str) else [v.to_dict() for v in value]

    def from_json(self, value: Any, path: str) -> Any:
        if self.array and not isinstance(self.kind, str):
            items = self._check_length(value, path)
            return [self.kind.from_dict(v, f"{path}[{i}]") for i, v in enumerate(items)]
        if not self.array and not isinstance(self.kind, str):
            return self.kind.from_dict(value, path)
        return self.check(value, path)

    def equal(self, a: Any, b: Any) -> bool:
        return bool(_numpy().array_equal(a, b)) if self.numeric_array else bool(a == b)


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
        "_new": object.__new__, "_missing": _MISSING, "_type": cls.TYPE, "_sorted": sorted, "_type_of": type,
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

    def __init_subclass__(cls, type_name: str | None = None, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if type_name is None:
            return
        spec = lab_definitions().services[type_name]
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
