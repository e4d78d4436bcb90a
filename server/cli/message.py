"""Messages as a user types them (``ros2 topic pub``'s YAML) and as ros2 prints them back (``repr``)."""

from __future__ import annotations

import math
from typing import Any

import yaml

from server.cli.client import CliError


class MessageTextError(CliError):
    """The MSG argument is not a YAML/JSON mapping of plain values."""


def parse_message(text: str) -> dict[str, Any]:
    """``"{x: 5.0, y: 5.0}"``, ``'{"x": 5}'`` or ``"data: true"`` → a dict; empty text → ``{}``."""
    try:
        value = yaml.safe_load(text) if text.strip() else {}
    except yaml.YAMLError as exc:
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise MessageTextError(f"the message is not valid YAML: {problem}") from None
    if value is None:
        value = {}
    if not isinstance(value, dict):
        raise MessageTextError("The passed value needs to be a dictionary in YAML format")
    _check_plain(value, "")
    return value


def _check_plain(value: Any, path: str) -> None:
    """Only what JSON carries: YAML also reads dates, bytes and NaN, which no message field takes."""
    where = path or "the message"
    if isinstance(value, dict):
        for key, item in value.items():
            if not isinstance(key, str):
                raise MessageTextError(f"{where}: field names are text, got {key!r}")
            _check_plain(item, f"{path}.{key}" if path else key)
    elif isinstance(value, list):
        for i, item in enumerate(value):
            _check_plain(item, f"{path}[{i}]")
    elif isinstance(value, float):
        if not math.isfinite(value):
            raise MessageTextError(f"{where}: {value} is not a finite number")
    elif value is not None and not isinstance(value, (bool, int, str)):
        raise MessageTextError(f"{where}: {value!r} is not a number, text or bool (quote it for text)")


def filled_message(default: dict[str, Any], given: dict[str, Any]) -> dict[str, Any]:
    """``given`` over the type's ``default`` message, as the publisher sends it: every field, and an
    integer in a float field as a float (``{x: 5}`` is published as ``x=5.0``)."""
    out = dict(default)
    for name, value in given.items():
        base = default.get(name)
        if isinstance(base, dict) and isinstance(value, dict):
            out[name] = filled_message(base, value)
        elif isinstance(base, float) and isinstance(value, int) and not isinstance(value, bool):
            out[name] = float(value)
        else:
            out[name] = value
    return out


def python_type_name(type_name: str) -> str:
    """``geometry_msgs/msg/Vector3`` (or ``geometry_msgs/Vector3``) → ``geometry_msgs.msg.Vector3``."""
    parts = type_name.strip("/").split("/")
    if len(parts) == 2:
        parts.insert(1, "msg")
    return ".".join(parts)


def message_repr(type_name: str, msg: dict[str, Any]) -> str:
    """What rclpy's ``repr`` prints: ``geometry_msgs.msg.Vector3(x=5.0, y=5.0, z=10.0)``.

    Nested messages print as dicts: their type names are not in the JSON.
    """
    inner = ", ".join(f"{name}={value!r}" for name, value in msg.items())
    return f"{python_type_name(type_name)}({inner})"
