"""TypeScript declarations from JSON Schema: the subset pydantic and the message schemas write
(objects, arrays, tuples, unions, nullables, literals, ``$ref`` to ``$defs``, maps).

The page's types are generated from the Python declarations through this (api/typescript.py),
so the shapes the server sends are written once.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

Schema = Mapping[str, Any]
REF_PREFIX = "#/$defs/"
PRIMITIVES = {
    "string": "string",
    "integer": "number",
    "number": "number",
    "boolean": "boolean",
    "null": "null",
}
IDENTIFIER_START = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_$"


class UnsupportedSchema(ValueError):
    """A schema construct this generator does not translate."""


def ts_type(schema: Schema, *, required_all: bool = False, indent: str = "") -> str:
    """The TypeScript type of ``schema``; ``required_all``: every object property is present
    (a message as the server sends it, though its schema lets a client leave fields out)."""
    if "$ref" in schema:
        ref = str(schema["$ref"])
        if not ref.startswith(REF_PREFIX):
            raise UnsupportedSchema(f"only local $defs references are supported, got {ref!r}")
        return ref.removeprefix(REF_PREFIX)
    if "const" in schema:
        return json.dumps(schema["const"])
    if "enum" in schema:
        return " | ".join(json.dumps(v) for v in schema["enum"])
    for key in ("anyOf", "oneOf"):
        if key in schema:
            members = [_grouped(ts_type(s, required_all=required_all, indent=indent)) for s in schema[key]]
            return " | ".join(dict.fromkeys(members))
    kind = schema.get("type")
    if isinstance(kind, list):
        return " | ".join(
            ts_type({**schema, "type": k}, required_all=required_all, indent=indent) for k in kind
        )
    if kind in PRIMITIVES:
        return PRIMITIVES[kind]
    if kind == "array":
        return _array(schema, required_all, indent)
    if kind == "object" or "properties" in schema:
        return _object(schema, required_all, indent)
    if kind is None:
        return "unknown"  # {} in JSON Schema: any value
    raise UnsupportedSchema(f"no TypeScript for JSON Schema type {kind!r}")


def declaration(name: str, schema: Schema, *, required_all: bool = False) -> str:
    """``export interface name {...}`` for an object with properties, else ``export type``."""
    doc = _doc(schema.get("description"), "")
    if schema.get("type") == "object" and "properties" in schema:
        return f"{doc}export interface {name} {_object(schema, required_all, '')}\n"
    return f"{doc}export type {name} = {ts_type(schema, required_all=required_all)};\n"


def _grouped(text: str) -> str:
    return f"({text})" if " | " in text and not text.startswith("{") else text


def _array(schema: Schema, required_all: bool, indent: str) -> str:
    if "prefixItems" in schema:
        items = [ts_type(s, required_all=required_all, indent=indent) for s in schema["prefixItems"]]
        return f"[{', '.join(items)}]"
    item = ts_type(schema.get("items", {}), required_all=required_all, indent=indent)
    size = schema.get("minItems")
    if size is not None and size == schema.get("maxItems") and size <= 4:  # a vector: a tuple
        return f"[{', '.join([item] * int(size))}]"
    return f"{_grouped(item)}[]"


def _object(schema: Schema, required_all: bool, indent: str) -> str:
    properties: Mapping[str, Schema] = schema.get("properties", {})
    extra = schema.get("additionalProperties")
    if not properties:
        value = (
            ts_type(extra, required_all=required_all, indent=indent)
            if isinstance(extra, Mapping)
            else "unknown"
        )
        return f"Record<string, {value}>"
    required = set(schema.get("required", ())) if not required_all else set(properties)
    inner = indent + "  "
    lines = ["{"]
    for name, prop in properties.items():
        key = (
            name
            if name[0] in IDENTIFIER_START and name.replace("$", "_").isidentifier()
            else json.dumps(name)
        )
        optional = "" if name in required else "?"
        lines.append(_doc(prop.get("description"), inner).rstrip("\n"))
        lines.append(f"{inner}{key}{optional}: {ts_type(prop, required_all=required_all, indent=inner)};")
    lines.append(f"{indent}}}")
    return "\n".join(line for line in lines if line)


def _doc(description: object, indent: str) -> str:
    if not isinstance(description, str) or not description:
        return ""
    text = " ".join(description.split()).replace("*/", "*\\/")
    return f"{indent}/** {text} */\n"
