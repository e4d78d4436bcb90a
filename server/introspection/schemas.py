"""Message types as draft 2020-12 JSON Schemas, with ROS integer ranges and defaults."""

from __future__ import annotations

from typing import Any

from server.msgs import Message
from server.msgs._base import FLOAT_TYPES, INT_RANGES, MAX_STRING_CHARS

JSON_SCHEMA_DIALECT = "https://json-schema.org/draft/2020-12/schema"
FLOAT32_MAX = 3.4028234663852886e38


def _primitive_schema(kind: str, default: Any) -> dict[str, Any]:
    schema: dict[str, Any]
    if kind == "bool":
        schema = {"type": "boolean"}
    elif kind in INT_RANGES:
        lo, hi = INT_RANGES[kind]
        schema = {"type": "integer", "minimum": lo, "maximum": hi}
    elif kind in FLOAT_TYPES:
        schema = {"type": "number"}
        if kind == "float32":
            schema.update(minimum=-FLOAT32_MAX, maximum=FLOAT32_MAX)
    elif kind == "string":
        schema = {"type": "string", "maxLength": MAX_STRING_CHARS}
    else:
        raise ValueError(f"no JSON Schema for field kind {kind!r}")
    return {**schema, "description": kind, "default": default}


def _object_schema(msg_type: type[Message]) -> dict[str, Any]:
    properties = {
        f.name: _primitive_schema(f.kind, f.default) if isinstance(f.kind, str) else _object_schema(f.kind)
        for f in msg_type.FIELDS
    }
    return {
        "title": msg_type.TYPE,
        "type": "object",
        "properties": properties,
        "additionalProperties": False,
        "default": msg_type().to_dict(),
    }


def type_schema(msg_type: type[Message]) -> dict[str, Any]:
    """A draft 2020-12 JSON Schema of a message's JSON form. Every field is optional, since a
    missing one keeps its default; ``description`` of a primitive field is its ROS type."""
    return {"$schema": JSON_SCHEMA_DIALECT, **_object_schema(msg_type)}
