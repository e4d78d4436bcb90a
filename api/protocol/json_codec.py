"""JSON at the app's boundary, as RFC 8259 defines it.

In: no NaN or Infinity (Python's ``json`` accepts both), no integer beyond 64 bits (no ROS field
holds one, and a float cannot carry it), no float that overflows to infinity, and a bounded
nesting depth: ``loads``, which the strict-JSON middleware (api/middleware/strict_json.py) applies
to every JSON request body and the key channel to its frames.

Out: a node may publish NaN (ROS allows it in a float64), but JSON cannot carry it, so
``dumps`` and ``SafeJSONResponse`` write non-finite floats as null.
"""

from __future__ import annotations

import json
import math
import re
from typing import Any, NoReturn

from starlette.responses import JSONResponse

MAX_DEPTH = 32  # the deepest lab message (PoseStamped) nests 4 objects
MAX_INT = 2**64  # |n| must be below this: int64 and uint64 are the widest ROS integers
MAX_INT_DIGITS = 21
_STRING = re.compile(r'"(?:[^"\\]|\\.)*"', re.DOTALL)
_BRACKET = re.compile(r"[\[\]{}]")


class JsonRejected(ValueError):
    """Text that is not JSON this app accepts; the message says what is wrong and where."""


def _reject(problem: str) -> NoReturn:
    raise JsonRejected(problem)


def _check_depth(text: str, max_depth: int) -> None:
    depth = 0
    for bracket in _BRACKET.finditer(_STRING.sub("", text)):
        if bracket.group() in "[{":
            depth += 1
            if depth > max_depth:
                _reject(f"JSON nested deeper than {max_depth} levels")
        else:
            depth -= 1


def _parse_int(text: str) -> int:
    if len(text.lstrip("-")) > MAX_INT_DIGITS or abs(value := int(text)) >= MAX_INT:
        _reject(f"integer {text[:24]}{'...' if len(text) > 24 else ''} is out of range (|n| < 2**64)")
    return value


def _parse_float(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        _reject(f"number {text[:24]} is too large for a 64-bit float")
    return value


def _parse_constant(name: str) -> NoReturn:
    _reject(f"{name} is not a JSON number (JSON has no NaN or Infinity)")


def loads(data: str | bytes, max_depth: int = MAX_DEPTH) -> Any:
    """Parse JSON strictly; raises ``JsonRejected`` naming the problem."""
    try:
        text = data.decode("utf-8") if isinstance(data, bytes) else data
    except UnicodeDecodeError as exc:
        _reject(f"not UTF-8 text: {exc.reason} at byte {exc.start}")
    _check_depth(text, max_depth)
    try:
        return json.loads(
            text, parse_int=_parse_int, parse_float=_parse_float, parse_constant=_parse_constant
        )
    except json.JSONDecodeError as exc:
        _reject(f"malformed JSON: {exc.msg} at char {exc.pos}")


def finite_or_null(value: Any) -> Any:
    """``value`` with every non-finite float replaced by None (JSON's null)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {key: finite_or_null(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite_or_null(item) for item in value]
    return value


_ENCODER = json.JSONEncoder(ensure_ascii=False, allow_nan=False, separators=(",", ":"))


def dumps(value: Any) -> str:
    """JSON text that any JSON parser accepts (non-finite floats become null).

    Almost every value has only finite numbers, and the encoder refuses a non-finite one with a
    ValueError: a value is walked for them (``finite_or_null``) only then, not before every
    encoding (the echo sockets encode every message of a topic; the walk took half the time)."""
    try:
        return _ENCODER.encode(value)
    except ValueError:
        return _ENCODER.encode(finite_or_null(value))


class SafeJSONResponse(JSONResponse):
    """The app's default response class: ``dumps`` instead of a 500 on a NaN in a message."""

    def render(self, content: Any) -> bytes:
        return dumps(content).encode("utf-8")
