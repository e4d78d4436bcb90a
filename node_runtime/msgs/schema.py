"""A message type's JSON form as JSON Schema, and its definition as ``ros2 interface show`` prints it."""

from __future__ import annotations

from typing import Any

from node_runtime.msgs import catalog
from node_runtime.msgs._base import Message
from node_runtime.msgs._field import FLOAT32_MAX, MAX_ARRAY_ITEMS, MAX_STRING_CHARS, Field
from node_runtime.msgs.idl import FLOAT_TYPES, INT_RANGES, STRING_TYPES

JSON_SCHEMA_DIALECT = "https://json-schema.org/draft/2020-12/schema"


def _primitive_schema(kind: str, string_bound: int | None) -> dict[str, Any]:
    if kind == "bool":
        return {"type": "boolean"}
    if kind in INT_RANGES:
        lo, hi = INT_RANGES[kind]
        return {"type": "integer", "minimum": lo, "maximum": hi}
    if kind in FLOAT_TYPES:
        return (
            {"type": "number", "minimum": -FLOAT32_MAX, "maximum": FLOAT32_MAX}
            if kind == "float32"
            else {"type": "number"}
        )
    if kind in STRING_TYPES:
        return {"type": "string", "maxLength": MAX_STRING_CHARS if string_bound is None else string_bound}
    raise ValueError(f"no JSON Schema for field kind {kind!r}")


def _field_schema(field: Field) -> dict[str, Any]:
    if isinstance(field.kind, str):
        item = _primitive_schema(field.kind, field.string_bound)
        item["description"] = (
            field.kind if field.string_bound is None else f"{field.kind}<={field.string_bound}"
        )
    else:
        item = _object_schema(field.kind)
    if not field.array:
        if isinstance(field.kind, str):
            item["default"] = field.default
        return item
    schema: dict[str, Any] = {"type": "array", "items": item, "description": field.type_name}
    if field.size is not None:
        schema.update(minItems=field.size, maxItems=field.size)
    else:
        schema["maxItems"] = field.bound if field.bound is not None else MAX_ARRAY_ITEMS
    return schema


def _object_schema(msg_type: type[Message]) -> dict[str, Any]:
    return {
        "title": msg_type.TYPE,
        "type": "object",
        "properties": {f.name: _field_schema(f) for f in msg_type.FIELDS},
        "additionalProperties": False,
        "default": msg_type().to_dict(),
    }


def type_schema(msg_type: type[Message]) -> dict[str, Any]:
    """A draft 2020-12 JSON Schema of a message's JSON form. Every field is optional, since a
    missing one keeps its default; ``description`` of a primitive field is its ROS type."""
    return {"$schema": JSON_SCHEMA_DIALECT, **_object_schema(msg_type)}


def interface_text(type_name: str, *, depth: int = 0) -> str:
    """The definition as ``ros2 interface show`` prints it: each nested type's definition follows
    the field that uses it, indented one tab further, without its comments and blank lines."""
    definitions = catalog.definitions()
    if type_name in definitions.actions:
        action = definitions.actions[type_name]
        parts = [_expanded(part.name, depth) for part in (action.goal, action.result, action.feedback)]
        return "\n".join([*parts[0], "---", *parts[1], "---", *parts[2]]) + "\n"
    if type_name in definitions.services:
        service = definitions.services[type_name]
        request = _expanded(service.request.name, depth)
        response = _expanded(service.response.name, depth)
        return "\n".join([*request, "---", *response]) + "\n"
    return "\n".join(_expanded(type_name, depth)) + "\n"


def _expanded(type_name: str, depth: int) -> list[str]:
    spec = catalog.definitions().message(type_name)
    by_name = {f.name: f for f in spec.fields}
    lines: list[str] = []
    for raw in spec.text.splitlines():
        if depth and (not raw.strip() or raw.lstrip().startswith("#")):
            continue  # a nested definition shows its fields only, as ros2 does without --all-comments
        lines.append("\t" * depth + raw if raw.strip() else raw)
        words = raw.split("#", 1)[0].split()
        field = by_name.get(words[1]) if len(words) >= 2 and "=" not in raw.split("#", 1)[0] else None
        if field is not None and not field.is_primitive:
            lines += _expanded(field.base, depth + 1)
    return lines
