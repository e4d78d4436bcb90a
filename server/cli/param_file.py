"""What ``param set`` and ``param load`` read on this side of the wire: a value typed from text as
rclpy types it, and a parameters file's parameters (``node: {ros__parameters: {...}}``, ``/**``
first, nested names joined by ``.``) as ``ros2 param load`` sends them to one node.

The CLI imports nothing of the server (it works against any lab it can reach), so this is its own
reading of the layout that node processes read with ``server.bus.params_file``.
"""

from __future__ import annotations

from typing import Any

import yaml

from .client import CliError

PARAMETERS_KEY = "ros__parameters"
WILDCARD = "/**"
MAX_FILE_BYTES = 1_000_000


class ParamFileError(CliError):
    """A parameters file that cannot be read or is not ros2's layout; names file and line."""


def value_from_text(text: str) -> Any:
    """YAML scalars and uniform lists keep their type; anything else is the text (rclpy's rule)."""
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        return text
    return value if _plain(value) else text


def _plain(value: Any) -> bool:
    if isinstance(value, bool | int | float | str):
        return True
    return isinstance(value, list) and (
        not value or any(all(type(v) is kind for v in value) for kind in (bool, int, float, str))
    )


def _flatten(prefix: str, params: dict[Any, Any], where: str, out: dict[str, Any]) -> None:
    for key, value in params.items():
        if isinstance(value, dict):
            _flatten(f"{prefix}{key}.", value, where, out)
        elif _plain(value):
            out[f"{prefix}{key}"] = value
        else:
            raise ParamFileError(f"{where}: parameter '{prefix}{key}' has no value a ROS parameter can hold")


def _sections(node: str, body: Any, path: str, out: list[tuple[str, dict[str, Any]]]) -> None:
    if not isinstance(body, dict):
        raise ParamFileError(f"{path}: '{node}' is not a map with {PARAMETERS_KEY}")
    for key, value in body.items():
        if key == PARAMETERS_KEY:
            if not isinstance(value, dict):
                raise ParamFileError(f"{path}: {node}: {PARAMETERS_KEY} is not a map of parameters")
            params: dict[str, Any] = {}
            _flatten("", value, f"{path}: {node}", params)
            out.append((node, params))
        else:
            _sections(f"{node.rstrip('/')}/{key}", value, path, out)


def load_params(path: str, use_wildcard: bool = True) -> dict[str, Any]:
    """Every section's parameters, ``/**``'s first (when ``use_wildcard``), as rclpy loads a file."""
    try:
        with open(path, "rb") as f:
            text = f.read(MAX_FILE_BYTES + 1).decode("utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise ParamFileError(f"{path}: cannot read it: {getattr(exc, 'strerror', None) or exc}") from None
    try:
        document = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{path}:{mark.line + 1}" if mark is not None else path
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise ParamFileError(f"{where}: not valid YAML: {problem}") from None
    if not isinstance(document, dict) or not document:
        raise ParamFileError(f"{path}: not a parameters file (expected node_name: {{{PARAMETERS_KEY}: ...}})")
    sections: list[tuple[str, dict[str, Any]]] = []
    for node, body in document.items():
        _sections(str(node), body, path, sections)
    out: dict[str, Any] = {}
    for node, params in sorted(sections, key=lambda s: s[0] != WILDCARD):  # stable: /** first
        if use_wildcard or node != WILDCARD:
            out.update(params)
    return out
