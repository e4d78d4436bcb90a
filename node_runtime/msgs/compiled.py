"""A message class's ``__init__``, ``copy`` and ``to_dict`` written out for its fields, as
dataclasses writes its methods (messages are built and copied on every publish, and turned into
JSON for every frame of a topic's echo)."""

from __future__ import annotations

import array
import keyword
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from node_runtime.msgs._field import MAX_STRING_CHARS, Field
from node_runtime.msgs.idl import INT_RANGES, STRING_TYPES

if TYPE_CHECKING:
    from node_runtime.msgs._base import Message


def _copy_expression(field: Field, value: str) -> str:
    """Python source for what ``field.copy_value(value)`` returns."""
    if not field.array:
        return value if isinstance(field.kind, str) else f"{value}.copy()"
    if field.typecode is not None:
        return f"_array({field.typecode!r}, {value})"
    if field.numeric_array:
        return f"{value}.copy()"
    return f"list({value})" if isinstance(field.kind, str) else f"[v.copy() for v in {value}]"


def _json_expression(field: Field, value: str) -> str:
    """Python source for what ``field.to_json(value)`` returns."""
    if not field.array:
        return value if isinstance(field.kind, str) else f"{value}.to_dict()"
    if field.numeric_array:
        return f"{value}.tolist()"
    return f"list({value})" if isinstance(field.kind, str) else f"[v.to_dict() for v in {value}]"


def compile_methods(cls: type[Message]) -> None:
    """``__init__``, ``copy`` and ``to_dict`` written out for this class's fields, as dataclasses
    writes its methods: the same results as Message's loops over FIELDS, without their per-field
    overhead (messages are built and copied on every publish). Slots are set through their
    descriptors, past the checking ``__setattr__``; values given to ``__init__`` still go through
    Field.check."""
    names = [f.name for f in cls.FIELDS]
    if any(keyword.iskeyword(n) or n in ("self", "new") or n.startswith("_") for n in names):
        return  # a name Python would not take as a parameter: the generic methods serve
    env: dict[str, Any] = {
        "_new": object.__new__,
        "_array": array.array,
        "_missing": _MISSING,
        "_type": cls.TYPE,
        "_sorted": sorted,
        "_type_of": type,  # builtins by names no field can take: a field may be named type, int or len
        "_int": int,
        "_str": str,
        "_len": len,
    }
    params, init_lines, copy_lines, json_items = [], [], [], []
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
            value = f"{f.name} if _type_of({f.name}) is _exact{i} else {value}"
        elif not f.array and isinstance(f.kind, str) and f.kind in INT_RANGES:
            # an exact int in its type's range is kept as it is: check_primitive's test, inline
            low, high = INT_RANGES[f.kind]
            value = f"{f.name} if _type_of({f.name}) is _int and {low} <= {f.name} <= {high} else {value}"
        elif not f.array and isinstance(f.kind, str) and f.kind in STRING_TYPES:
            # so is an exact str within its bound
            bound = MAX_STRING_CHARS if f.string_bound is None else f.string_bound
            value = f"{f.name} if _type_of({f.name}) is _str and _len({f.name}) <= {bound} else {value}"
        init_lines.append(f"    _set{i}(self, {value})")
        copy_lines.append(f"    _set{i}(new, {_copy_expression(f, 'self.' + f.name)})")
        json_items.append(f"{f.name!r}: {_json_expression(f, 'self.' + f.name)}")
    lines = [
        f"def __init__(self, {', '.join(['*', *params, '**unknown'] if params else ['**unknown'])}):",
        *init_lines,
        "    if unknown:",
        "        raise TypeError(f\"{_type} has no field(s) {', '.join(_sorted(unknown))}\")",
        "def copy(self):",
        "    new = _new(type(self))",
        *copy_lines,
        "    return new",
        "def to_dict(self):",
        f"    return {{{', '.join(json_items)}}}",
    ]
    source = "\n".join(lines)
    exec(compile(source, f"<{cls.TYPE} methods>", "exec"), env)
    for name in ("__init__", "copy", "to_dict"):
        method: Callable[..., Any] = env[name]
        method.__qualname__ = f"{cls.__qualname__}.{name}"
        setattr(cls, name, method)


_MISSING: Any = object()
