"""One field of a message class: what a value must be to fit it, and how it is copied, compared
and turned into JSON. Fixed-size numeric arrays are numpy arrays, numeric sequences
``array.array``s (as rclpy makes them), sequences of bools, arrays of strings and of messages lists."""

from __future__ import annotations

import array
import math
import sys
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, TypeAlias

from node_runtime.msgs.idl import FLOAT_TYPES, INT_RANGES, STRING_TYPES, FieldSpec

if TYPE_CHECKING:
    from node_runtime.msgs._base import Message

MAX_STRING_CHARS = 65536
MAX_ARRAY_ITEMS = 65536
FLOAT32_MAX = 3.4028234663852886e38
# numpy (about 20 MiB resident) is imported at the first fixed-size numeric array, so a node
# process whose messages have none never loads it; until something imports it, no value can be a
# numpy one.
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


# A sequence (``T[]``, ``T[<=N]``) of numbers is an ``array.array`` of this type code, as rclpy
# makes it (so ``append`` works and it prints as ``array('i', [0, 1])``); fixed-size arrays are numpy.
# A sequence of bools is a list of bools, as rclpy makes it (array.array has no bool). Neither
# needs numpy, so a message with such sequences (rcl_interfaces' ParameterValue, which every
# node's /parameter_events carries) does not load it.
ARRAY_TYPECODES = {
    "byte": "B",
    "char": "B",
    "int8": "b",
    "uint8": "B",
    "int16": "h",
    "uint16": "H",
    "int32": "i",
    "uint32": "I",
    "int64": "q",
    "uint64": "Q",
    "float32": "f",
    "float64": "d",
}
if TYPE_CHECKING:  # what the generated classes annotate a sequence field with
    IntArray: TypeAlias = array.array[int]
    FloatArray: TypeAlias = array.array[float]
else:  # array.array takes no subscript at run time before Python 3.12
    IntArray = FloatArray = array.array


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

    __slots__ = (
        "array",
        "bound",
        "default",
        "exact",
        "kind",
        "name",
        "numeric",
        "size",
        "spec",
        "string_bound",
        "typecode",
    )

    def __init__(self, spec: FieldSpec, kind: str | type[Message]) -> None:
        self.spec = spec
        self.name = spec.name
        self.kind = kind
        self.array = spec.is_array
        self.size = spec.array_size
        self.bound = spec.array_bound
        self.string_bound = spec.string_bound
        self.typecode = ARRAY_TYPECODES.get(kind) if spec.is_sequence and isinstance(kind, str) else None
        self.numeric = (
            self.array
            and isinstance(kind, str)
            and kind not in STRING_TYPES
            and not (kind == "bool" and spec.is_sequence)
        )
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
        """An array of numbers: an ``array.array`` (a sequence) or a numpy array (fixed size)."""
        return self.numeric

    def initial(self) -> Any:
        """A fresh default value for a new message."""
        if not self.array:
            return self.default if isinstance(self.kind, str) else self.kind()
        if self.typecode is not None:
            return array.array(self.typecode, self.default or [])
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
        if self.typecode == "B" and isinstance(value, bytes | bytearray | memoryview):
            data = bytes(value)  # raw bytes for a uint8[] (rclpy takes them; PointCloud2's data)
            self._check_length(array.array("B", data), path)
            return array.array("B", data)
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

    def _check_length(self, value: Any, path: str) -> Any:
        ndarray = _is_ndarray(value)
        if isinstance(value, str | bytes | Mapping) or not (
            ndarray or isinstance(value, Sequence | array.array)
        ):
            raise MessageError(path, f"expected an array ({self.type_name}), got {type(value).__name__}")
        if ndarray and value.ndim != 1:
            raise MessageError(path, f"expected a one-dimensional array, got shape {value.shape}")
        n = len(value)
        if self.size is not None and n != self.size:
            raise MessageError(path, f"expected exactly {self.size} items, got {n}")
        limit = self.bound if self.bound is not None else MAX_ARRAY_ITEMS
        if n > limit:
            raise MessageError(path, f"more than {limit} items ({n})")
        return value

    def _numeric_array(self, items: Any, path: str) -> Any:
        kind = str(self.kind)
        dtype = NUMPY_DTYPES[kind]
        code = self.typecode
        if code is not None:
            if isinstance(items, array.array) and items.typecode == code:
                return array.array(code, items)
            if _is_ndarray(items) and items.dtype == dtype:
                return array.array(code, items.tobytes())
            return array.array(code, [check_primitive(kind, v, f"{path}[{i}]") for i, v in enumerate(items)])
        numpy = _numpy()
        if isinstance(items, numpy.ndarray) and items.dtype == dtype:
            return items.copy()
        checked = [check_primitive(kind, v, f"{path}[{i}]") for i, v in enumerate(items)]
        return numpy.array(checked, dtype=dtype)

    def copy_value(self, value: Any) -> Any:
        if not self.array:
            return value if isinstance(self.kind, str) else value.copy()
        if self.typecode is not None:
            return array.array(self.typecode, value)
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
        if isinstance(a, array.array) and isinstance(b, array.array):
            return a == b
        return bool(_numpy().array_equal(a, b)) if self.numeric_array else bool(a == b)
