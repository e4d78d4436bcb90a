"""Typed attribute values of launch XML: booleans, parameters (as ROS launch types them), outputs
and namespaces."""

from __future__ import annotations

import re
from typing import cast

from server.services.launch.description import ParamScalar, ParamValue

_INT = re.compile(r"[-+]?[0-9]+\Z")
_FLOAT = re.compile(r"[-+]?([0-9]+\.[0-9]*|\.[0-9]+|[0-9]+(?=[eE]))([eE][-+]?[0-9]+)?\Z")
OUTPUTS = ("screen", "log", "both", "own_log", "full")


def parse_bool(text: str) -> bool | None:
    lowered = text.strip().lower()
    if lowered in ("true", "1"):
        return True
    if lowered in ("false", "0"):
        return False
    return None


def _typed_scalar(text: str) -> ParamScalar:
    text = text.strip()
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"":
        return text[1:-1]
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    if _INT.match(text):
        return int(text)
    if _FLOAT.match(text):
        return float(text)
    return text


def typed_param(text: str) -> ParamValue:
    """Type a parameter value as ROS launch does: bool, int, float, a uniform ``[...]`` list, or str."""
    stripped = text.strip()
    if not (stripped.startswith("[") and stripped.endswith("]")):
        return _typed_scalar(text)
    raw_items = _split_list(stripped[1:-1])
    if any(item.strip().startswith("[") for item in raw_items):
        raise ValueError(f"{stripped} nests lists, which a ROS parameter cannot hold")
    items = [_typed_scalar(item) for item in raw_items]
    kinds = sorted({type(item).__name__ for item in items})
    if len(kinds) > 1:
        hint = " (write 1.0, not 1, in a list of floats)" if kinds == ["float", "int"] else ""
        raise ValueError(f"{stripped} mixes {' and '.join(kinds)}; a ROS parameter list holds one type{hint}")
    return cast(ParamValue, items)


def _split_list(body: str) -> list[str]:
    if not body.strip():
        return []
    items: list[str] = []
    current: list[str] = []
    quote: str | None = None
    for char in body:
        if quote is None and char == ",":
            items.append("".join(current))
            current = []
            continue
        if quote is None and char in "'\"":
            quote = char
        elif char == quote:
            quote = None
        current.append(char)
    items.append("".join(current))
    return items


def join_namespace(outer: str | None, inner: str) -> str | None:
    if not inner:
        return outer
    if inner.startswith("/"):
        return inner
    return (outer or "").rstrip("/") + "/" + inner
