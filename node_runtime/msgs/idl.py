"""ROS 2 interface definitions (``.msg`` and ``.srv`` text) read into specs.

The definitions under ``interfaces/<pkg>/{msg,srv}/`` are the single source of every message
type: its fields and defaults (for the Python classes and their checks), its constants, its
JSON Schema, its CDR layout and RIHS01 hash (node_runtime.msgs.wire) and what ``interface show``
prints. The grammar is rosidl's, for what the lab's interfaces use: primitives, ``string<=N``,
nested types (``Point``, ``std_msgs/Header``), arrays ``T[N]``, ``T[<=N]`` and ``T[]``, default
values after a field and constants ``TYPE NAME=VALUE``.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass, field
from typing import Any

INT_RANGES: dict[str, tuple[int, int]] = {
    "byte": (0, 2**8 - 1),
    "char": (0, 2**8 - 1),
    "int8": (-(2**7), 2**7 - 1),
    "uint8": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1),
    "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1),
    "uint64": (0, 2**64 - 1),
}
FLOAT_TYPES = frozenset({"float32", "float64"})
STRING_TYPES = frozenset({"string", "wstring"})
PRIMITIVES = frozenset({"bool", *INT_RANGES, *FLOAT_TYPES, *STRING_TYPES})
SERVICE_SEPARATOR = "---"
_NAME = re.compile(r"[a-zA-Z][a-zA-Z0-9_]*\Z")
_TYPE = re.compile(r"(?P<base>[A-Za-z][\w/]*)(?:<=(?P<strbound>\d+))?(?:\[(?P<array>(?:<=)?\d*)\])?\Z")


class DefinitionError(ValueError):
    """An interface file that does not parse; names the file and line."""


@dataclass(frozen=True)
class FieldSpec:
    """One field. ``base`` is a primitive (``float64``) or a full type name (``std_msgs/msg/Header``).

    ``array_size`` is None for a single value, N for ``T[N]``; ``array_bound`` is N for
    ``T[<=N]``; ``is_sequence`` is true for ``T[]`` and ``T[<=N]``. ``string_bound`` is N for
    ``string<=N``. ``default`` is the value written in the definition, or None.
    """

    name: str
    base: str
    array_size: int | None = None
    array_bound: int | None = None
    is_sequence: bool = False
    string_bound: int | None = None
    default: Any = None
    line: int = field(default=0, compare=False)  # where the definition declares it (1-based)

    @property
    def is_array(self) -> bool:
        return self.array_size is not None or self.is_sequence

    @property
    def is_primitive(self) -> bool:
        return self.base in PRIMITIVES

    @property
    def type_text(self) -> str:
        """The type as a definition writes it, with full names for nested types."""
        text = self.base + (f"<={self.string_bound}" if self.string_bound is not None else "")
        if self.array_size is not None:
            return f"{text}[{self.array_size}]"
        if self.is_sequence:
            return f"{text}[<={self.array_bound}]" if self.array_bound is not None else f"{text}[]"
        return text


@dataclass(frozen=True)
class ConstantSpec:
    name: str
    base: str
    value: Any
    line: int = field(default=0, compare=False)


@dataclass(frozen=True)
class MessageSpec:
    """A message type: ``pkg/msg/Name`` (or ``pkg/srv/Name_Request``), fields and constants in order."""

    name: str
    fields: tuple[FieldSpec, ...]
    constants: tuple[ConstantSpec, ...]
    text: str
    source: str = field(default="", compare=False)  # the file, as errors name it

    @property
    def package(self) -> str:
        return self.name.split("/")[0]

    def dependencies(self) -> tuple[str, ...]:
        """Nested message types, each once, in order of first use."""
        return tuple(dict.fromkeys(f.base for f in self.fields if not f.is_primitive))

    def where(self, dependency: str) -> str:
        """``source:line`` of the first field that nests ``dependency``."""
        line = next((f.line for f in self.fields if f.base == dependency), 0)
        return f"{self.source or self.name}:{line}" if line else self.source or self.name


@dataclass(frozen=True)
class ServiceSpec:
    """A service type ``pkg/srv/Name``: a request and a response message."""

    name: str
    request: MessageSpec
    response: MessageSpec
    text: str
    source: str = field(default="", compare=False)


def _full_type_name(base: str, package: str) -> str:
    """``Point`` → ``<package>/msg/Point``; ``std_msgs/Header`` → ``std_msgs/msg/Header``."""
    if base in PRIMITIVES:
        return base
    if base == "Header":
        return "std_msgs/msg/Header"
    parts = base.split("/")
    if len(parts) == 1:
        return f"{package}/msg/{base}"
    if len(parts) == 2:
        return f"{parts[0]}/msg/{parts[1]}"
    if len(parts) == 3 and parts[1] in ("msg", "srv", "action"):
        return base
    raise ValueError(f"bad type name {base!r}")


def _literal(base: str, text: str) -> Any:
    """A default or constant value as rosidl reads it: numbers, true/false, quoted or bare strings."""
    text = text.strip()
    if base in STRING_TYPES:
        if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"":
            return ast.literal_eval(text)
        return text
    if base == "bool":
        lowered = text.lower()
        if lowered in ("true", "1"):
            return True
        if lowered in ("false", "0"):
            return False
        raise ValueError(f"{text!r} is not a bool")
    expected = "a number" if base in FLOAT_TYPES else "an integer"
    try:
        value = ast.literal_eval(text)
    except (ValueError, SyntaxError):
        raise ValueError(f"{text!r} is not {expected}") from None
    if base in FLOAT_TYPES:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ValueError(f"{text!r} is not a number")
        return float(value)
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"{text!r} is not an integer")
    lo, hi = INT_RANGES[base]
    if not lo <= value <= hi:
        raise ValueError(f"{value} is out of range for {base}")
    return value


def _array_literal(base: str, text: str) -> list[Any]:
    text = text.strip()
    if not (text.startswith("[") and text.endswith("]")):
        raise ValueError(f"an array default is written [a, b, ...], got {text!r}")
    inner = text[1:-1].strip()
    return [_literal(base, item) for item in inner.split(",")] if inner else []


def _strip_comment(line: str) -> str:
    """Drop a ``#`` comment, but not a ``#`` inside a quoted string value."""
    quote = ""
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = ""
        elif ch in "'\"":
            quote = ch
        elif ch == "#":
            return line[:i]
    return line


def _parse_line(line: str, package: str, number: int) -> FieldSpec | ConstantSpec:
    type_text, _, rest = line.strip().partition(" ")
    rest = rest.strip()
    match = _TYPE.match(type_text)
    if match is None or not rest:
        raise ValueError(f"expected 'TYPE NAME', got {line.strip()!r}")
    base = _full_type_name(match["base"], package)
    string_bound = int(match["strbound"]) if match["strbound"] else None
    if string_bound is not None and base not in STRING_TYPES:
        raise ValueError(f"only strings take a bound, not {base}")
    if "=" in rest.split(" ", 1)[0] or re.match(r"[A-Za-z]\w*\s*=", rest):
        name, _, value = rest.partition("=")
        name = name.strip()
        if base not in PRIMITIVES or match["array"] is not None:
            raise ValueError(f"constant {name} must have a primitive type")
        if not re.fullmatch(r"[A-Z][A-Z0-9_]*", name):
            raise ValueError(f"constant names are UPPER_CASE, got {name!r}")
        return ConstantSpec(name, base, _literal(base, value), number)
    name, _, default_text = rest.partition(" ")
    if not _NAME.match(name) or "__" in name:
        raise ValueError(f"bad field name {name!r}")
    array = match["array"]
    size = bound = None
    if array is not None and array and not array.startswith("<="):
        size = int(array)
    elif array:
        bound = int(array[2:])
    default: Any = None
    if default_text.strip():
        if base not in PRIMITIVES:
            raise ValueError(f"field {name}: only primitive fields take a default")
        default = _array_literal(base, default_text) if array is not None else _literal(base, default_text)
    return FieldSpec(
        name=name,
        base=base,
        array_size=size,
        array_bound=bound,
        is_sequence=array is not None and size is None,
        string_bound=string_bound,
        default=default,
        line=number,
    )


def parse_message(name: str, text: str, *, source: str | None = None, first_line: int = 1) -> MessageSpec:
    """Parse one message definition; ``name`` is its full type name (``pkg/msg/Name``). Errors
    name ``source`` (else ``name``) and the line, counted from ``first_line``."""
    package = name.split("/")[0]
    fields: list[FieldSpec] = []
    constants: list[ConstantSpec] = []
    for number, raw in enumerate(text.splitlines(), start=first_line):
        line = _strip_comment(raw).strip()
        if not line:
            continue
        try:
            item = _parse_line(line, package, number)
        except (ValueError, SyntaxError) as exc:
            raise DefinitionError(f"{source or name}:{number}: {exc}") from None
        if any(f.name == item.name for f in fields) or any(c.name == item.name for c in constants):
            raise DefinitionError(f"{source or name}:{number}: {item.name!r} defined twice")
        if isinstance(item, ConstantSpec):
            constants.append(item)
        else:
            fields.append(item)
    return MessageSpec(name, tuple(fields), tuple(constants), text, source or name)


def parse_service(name: str, text: str, *, source: str | None = None) -> ServiceSpec:
    """Parse a ``.srv``: request, ``---``, response; the parts are ``Name_Request``/``Name_Response``."""
    lines = text.splitlines()
    marks = [i for i, line in enumerate(lines) if _strip_comment(line).strip() == SERVICE_SEPARATOR]
    if len(marks) != 1:
        where = f"{source or name}:{marks[1] + 1}" if len(marks) > 1 else source or name
        raise DefinitionError(f"{where}: a service has one '---' line, found {len(marks)}")
    request = "\n".join(lines[: marks[0]])
    response = "\n".join(lines[marks[0] + 1 :])
    return ServiceSpec(
        name,
        parse_message(f"{name}_Request", request, source=source),
        parse_message(f"{name}_Response", response, source=source, first_line=marks[0] + 2),
        text,
        source or name,
    )
