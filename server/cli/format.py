"""Messages and statistics printed as ros2 prints them (``ros2 topic echo``'s YAML, ``topic hz``'s lines).

ros2 turns a message into an ordered mapping and hands it to ``yaml.dump``; doing the same with
the message's JSON gives the same text: ``x: 5.0``, ``frame_id: ''``, ``data: 'a: b'``.
"""

from __future__ import annotations

import sys
from collections.abc import Mapping, Sequence
from typing import Any

import yaml

from server.cli.client import CliError

DEFAULT_TRUNCATE_LENGTH = 128  # ros2 topic echo's default for strings and arrays


class FieldError(CliError):
    """``--field`` names a field the message does not have."""


def parse_field(text: str | None) -> list[str] | None:
    """``--field pose.position`` → ``["pose", "position"]``; empty parts are ignored, as ros2 does."""
    if text is None:
        return None
    parts = [p for p in text.split(".") if p]
    if not parts:
        raise FieldError(f"Invalid field value '{text}'")
    return parts


def select_field(msg: Any, field: Sequence[str]) -> Any:
    """The part of ``msg`` that ``field`` names (``["pose", "position"]`` → the position)."""
    value = msg
    for i, name in enumerate(field):
        if not isinstance(value, Mapping) or name not in value:
            where = ".".join(field[:i]) or "the message"
            raise FieldError(f"Invalid field '{'.'.join(field)}': {where} has no field '{name}'")
        value = value[name]
    return value


def _convert(value: Any, truncate_length: int | None, no_arr: bool) -> Any:
    """Truncate long strings and arrays, or abbreviate arrays (``--no-arr``), as ros2 does."""
    if isinstance(value, Mapping):
        return {k: _convert(v, truncate_length, no_arr) for k, v in value.items()}
    if isinstance(value, list):
        if no_arr:
            return f"<sequence length: {len(value)}>"
        items = [_convert(v, truncate_length, no_arr) for v in value]
        if truncate_length is not None and len(items) > truncate_length:
            return [*items[:truncate_length], "..."]
        return items
    if isinstance(value, str) and truncate_length is not None and len(value) > truncate_length:
        return value[:truncate_length] + "..."
    return value


def message_to_yaml(
    msg: Mapping[str, Any], *, truncate_length: int | None = DEFAULT_TRUNCATE_LENGTH, no_arr: bool = False
) -> str:
    """A message as ``ros2 topic echo`` prints it: block YAML, fields in order, nested ones indented."""
    text: str = yaml.dump(
        _convert(msg, truncate_length, no_arr),
        allow_unicode=True,
        width=sys.maxsize,
        default_flow_style=False,
        sort_keys=False,
    )
    return text


def echo_text(
    msg: Mapping[str, Any],
    field: Sequence[str] | None = None,
    *,
    truncate_length: int | None = DEFAULT_TRUNCATE_LENGTH,
    no_arr: bool = False,
) -> str:
    """One message of ``ros2 topic echo`` with its ``---`` line; a primitive field prints bare."""
    value = select_field(msg, field) if field else msg
    if isinstance(value, Mapping):
        return message_to_yaml(value, truncate_length=truncate_length, no_arr=no_arr) + "---\n"
    return f"{_convert(value, truncate_length, no_arr)}\n---\n"  # ros2 print()s a bare value


def hz_report(stats: Mapping[str, Any]) -> str:
    """``ros2 topic hz``'s two lines. Its ``window`` counts messages, one more than the periods."""
    return (
        f"average rate: {stats['rate_hz']:.3f}\n"
        f"\tmin: {stats['min_s']:.3f}s max: {stats['max_s']:.3f}s "
        f"std dev: {stats['std_dev_s']:.5f}s window: {stats['window'] + 1}"
    )
