"""``interface list | show``: the lab's message types, shown as ``ros2 interface show`` prints a .msg.

The server describes a type as a JSON Schema: a message is an object whose ``title`` is its ROS
type, and a primitive field's ``description`` is its ROS type (``float64``).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Mapping
from typing import Any

from .client import ApiError, LabClient

JSON_TO_ROS = {"boolean": "bool", "integer": "int64", "number": "float64", "string": "string"}
ROS_PRIMITIVES = frozenset({
    "bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32", "uint32",
    "int64", "uint64", "string", "wstring",
})  # fmt: skip


def _resolve(schema: Mapping[str, Any], root: Mapping[str, Any]) -> Mapping[str, Any]:
    """Follow a local ``$ref`` (``#/$defs/...``), in case the server factors nested types out."""
    ref = schema.get("$ref")
    if not isinstance(ref, str) or not ref.startswith("#/"):
        return schema
    target: Any = root
    for part in ref[2:].split("/"):
        target = target.get(part, {}) if isinstance(target, Mapping) else {}
    return target if isinstance(target, Mapping) else schema


def _is_message(schema: Mapping[str, Any]) -> bool:
    return schema.get("type") == "object" or "properties" in schema


def _short_name(type_name: str, parent_pkg: str) -> str:
    """As a .msg file writes a field's type: ``Vector3`` in its own package, else ``std_msgs/Header``."""
    parts = type_name.split("/")
    if len(parts) != 3:
        return type_name
    return parts[2] if parts[0] == parent_pkg else f"{parts[0]}/{parts[2]}"


def _field_type(schema: Mapping[str, Any], root: Mapping[str, Any], parent_pkg: str) -> str:
    schema = _resolve(schema, root)
    if schema.get("type") == "array":
        return _field_type(schema.get("items", {}), root, parent_pkg) + "[]"
    if _is_message(schema):
        return _short_name(str(schema.get("title", "object")), parent_pkg)
    described = str(schema.get("description", "")).split()
    if described and described[0] in ROS_PRIMITIVES:
        return described[0]
    return JSON_TO_ROS.get(str(schema.get("type")), str(schema.get("type", "?")))


def schema_lines(
    schema: Mapping[str, Any], root: Mapping[str, Any] | None = None, depth: int = 0
) -> list[str]:
    """``float64 x`` per field; a nested message's fields follow it, one tab further in."""
    root = root if root is not None else schema
    schema = _resolve(schema, root)
    package = str(schema.get("title", "")).split("/")[0]
    lines: list[str] = []
    for name, field in schema.get("properties", {}).items():
        lines.append("\t" * depth + f"{_field_type(field, root, package)} {name}")
        inner = _resolve(field, root)
        if inner.get("type") == "array":
            inner = _resolve(inner.get("items", {}), root)
        if _is_message(inner):
            lines += schema_lines(inner, root, depth + 1)
    return lines


def interface_list(args: argparse.Namespace, client: LabClient) -> int:
    types = client.get("/api/types")
    names = sorted(t if isinstance(t, str) else t.get("name", "") for t in types)
    print("Messages:")
    for name in names:
        print(f"    {name}")
    return 0


def interface_show(args: argparse.Namespace, client: LabClient) -> int:
    try:
        schema = client.get("/api/types/" + args.type.strip("/"))
    except ApiError as exc:
        if exc.status == 404 and not exc.no_route:
            print(f"Unknown interface '{args.type}': {exc.detail}", file=sys.stderr)
            return 1
        raise
    print("\n".join(schema_lines(schema)))
    return 0


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    parser = verbs.add_parser("interface", help="Show information about ROS interfaces")
    sub = parser.add_subparsers(dest="interface_verb", required=True, metavar="VERB")

    p = sub.add_parser("list", parents=[common], help="List all interface types available")
    p.add_argument("-m", "--only-msgs", action="store_true", help="Print out only the messages (all are)")
    p.set_defaults(handler=interface_list)

    p = sub.add_parser("show", parents=[common], help="Output the interface definition")
    p.add_argument("type", help="Show an interface definition (e.g. 'std_msgs/msg/String')")
    p.set_defaults(handler=interface_show)
