"""ROS parameter values as text: a value typed as rcl types ``-p name:=value`` and ``ros2 param
set``'s argument (YAML: ``5``, ``2.0``, ``true``, ``[1, 2]``; anything else is a string), and ros2's
parameter files (``node_name: {ros__parameters: {...}}``, ``/**`` for every node, namespaces as
``/ns/node`` or nested keys, nested parameter maps joined by ``.``)."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

PARAMETERS_KEY = "ros__parameters"
WILDCARD = "/**"
SEPARATOR = "."
MAX_FILE_BYTES = 1_000_000  # a parameters file is a few kB; a bigger one is not one


class ParamsFileError(ValueError):
    """A parameters file that cannot be read or is not ros2's layout; the text names file and line."""


def value_from_text(text: str) -> Any:
    """``text`` typed as rcl types a parameter's value: YAML scalars and uniform lists keep their
    type (an int list with a float in it stays mixed, so it is a string, as in rclpy)."""
    import yaml  # here and below: a node process without parameters never loads PyYAML

    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        return text
    return typed_value(value, text)


def typed_value(value: Any, text: str | None = None) -> Any:
    """A YAML value as a parameter value: bool, int, float, str or a list of one of them; anything
    else (a map, a mixed list, null) is the text it was written as."""
    if isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, list) and value:
        for kind in (bool, int, float, str):
            if all(type(v) is kind for v in value):
                return value
    return text if text is not None else str(value)


@dataclass(frozen=True)
class ParamsFile:
    """A parsed parameters file: each node pattern with its flat parameters, in file order."""

    path: str
    sections: tuple[tuple[str, dict[str, Any]], ...]

    def for_node(self, fully_qualified_name: str) -> dict[str, Any]:
        """What the file gives a node, later matching sections winning (as rcl applies them)."""
        out: dict[str, Any] = {}
        for pattern, params in self.sections:
            if node_matches(pattern, fully_qualified_name):
                out.update(params)
        return out

    def every_section(self, use_wildcard: bool = True) -> dict[str, Any]:
        """Every node's parameters, ``/**`` first, as ``ros2 param load`` sends them."""
        out: dict[str, Any] = {}
        if use_wildcard:
            for pattern, params in self.sections:
                if pattern == WILDCARD:
                    out.update(params)
        for pattern, params in self.sections:
            if pattern != WILDCARD:
                out.update(params)
        return out


def node_matches(pattern: str, fully_qualified_name: str) -> bool:
    """rcl's node-name match: ``*`` stands for one name token, ``**`` for any number of them; a
    pattern without a leading ``/`` is relative to any namespace only when it is a bare name."""
    pattern = pattern if pattern.startswith("/") else "/" + pattern
    parts = []
    for token in pattern.split("/")[1:]:
        parts.append("(/[^/]+)*" if token == "**" else "/" + re.escape(token).replace(r"\*", "[^/]*"))
    return re.fullmatch("".join(parts), fully_qualified_name) is not None


def _flatten(prefix: str, params: dict[Any, Any], where: str, out: dict[str, Any]) -> None:
    for key, value in params.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            _flatten(name + SEPARATOR, value, where, out)
        elif value == [] or typed_value(value, None) is value:
            out[name] = value
        else:  # null, a date, a list of mixed or nested things
            raise ParamsFileError(f"{where}: parameter '{name}' has no value a ROS parameter can hold")


def _sections(node: str, body: Any, path: str, out: list[tuple[str, dict[str, Any]]]) -> None:
    if not isinstance(body, dict):
        raise ParamsFileError(f"{path}: '{node}' is not a map with {PARAMETERS_KEY}")
    for key, value in body.items():
        if key == PARAMETERS_KEY:
            if not isinstance(value, dict):
                raise ParamsFileError(f"{path}: {node}: {PARAMETERS_KEY} is not a map of parameters")
            params: dict[str, Any] = {}
            _flatten("", value, f"{path}: {node}", params)
            out.append((node, params))
        else:  # a namespace nested as a key: ``ns: {node: {ros__parameters: ...}}``
            _sections(node.rstrip("/") + "/" + str(key).strip("/"), value, path, out)


def parse_params_text(text: str, path: str) -> ParamsFile:
    """``text`` (a file's contents) as a parameters file; ``path`` names it in errors."""
    import yaml

    try:
        document = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{path}:{mark.line + 1}" if mark is not None else path
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise ParamsFileError(f"{where}: not valid YAML: {problem}") from None
    if not isinstance(document, dict) or not document:
        raise ParamsFileError(
            f"{path}: not a parameters file (expected node_name: {{{PARAMETERS_KEY}: ...}})"
        )
    sections: list[tuple[str, dict[str, Any]]] = []
    for node, body in document.items():
        _sections(str(node), body, path, sections)
    return ParamsFile(path, tuple(sections))


def read_params_file(path: str | Path) -> ParamsFile:
    """Read and parse the file at ``path``; a ParamsFileError names what is wrong."""
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise ParamsFileError(f"{path}: cannot read it: {exc.strerror}") from None
    if len(data) > MAX_FILE_BYTES:
        raise ParamsFileError(f"{path}: larger than {MAX_FILE_BYTES} bytes; not a parameters file")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise ParamsFileError(f"{path}: not UTF-8 text") from None
    return parse_params_text(text, str(path))


__all__ = [
    "PARAMETERS_KEY",
    "SEPARATOR",
    "WILDCARD",
    "ParamsFile",
    "ParamsFileError",
    "node_matches",
    "parse_params_text",
    "read_params_file",
    "typed_value",
    "value_from_text",
]
