"""A Node's ``parameters=[...]`` performed: dicts (nested ones flattened with ``.``), values typed
as launch_ros types them (a substitution's text read as YAML), and the files it names."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml
from launch import LaunchContext, Substitution
from launch.utilities import perform_typed

from launch_ros.parameter_descriptions import ParameterFile, ParameterValue

Scalar = bool | int | float | str


def _typed_text(text: str) -> Any:
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        return text
    if isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, list) and all(isinstance(v, bool | int | float | str) for v in value):
        return value
    return text


def _converted(value: Any, value_type: Any) -> Any:
    if value_type in (None, Any):
        return value
    if value_type is str:
        return str(value)
    try:
        return value_type(value) if not isinstance(value, list) else [value_type(v) for v in value]
    except (TypeError, ValueError) as exc:
        raise ValueError(
            f"parameter value {value!r} is not a {getattr(value_type, '__name__', value_type)}"
        ) from exc


def performed_value(context: LaunchContext, value: Any) -> Any:
    if isinstance(value, ParameterValue):
        inner = value.value
        if isinstance(inner, Substitution | list | tuple) and _has_substitution(inner):
            text = perform_typed(context, inner)
            return _converted(text if value.value_type is str else _typed_text(text), value.value_type)
        return _converted(performed_value(context, inner), value.value_type)
    if isinstance(value, Substitution):
        return _typed_text(perform_typed(context, value))
    if isinstance(value, list | tuple):
        if _has_substitution(value):
            if (
                all(isinstance(v, Substitution | str) for v in value)
                and any(isinstance(v, Substitution) for v in value)
                and not all(isinstance(v, Substitution) for v in value)
            ):
                return _typed_text(perform_typed(context, value))  # parts of one text
            return [performed_value(context, v) for v in value]
        return [performed_value(context, v) for v in value]
    if isinstance(value, bool | int | float | str):
        return value
    raise TypeError(f"a parameter value cannot be a {type(value).__name__}: {value!r}")


def _has_substitution(value: Any) -> bool:
    if isinstance(value, Substitution):
        return True
    return isinstance(value, list | tuple) and any(_has_substitution(v) for v in value)


def flatten(context: LaunchContext, params: Mapping[Any, Any], prefix: str = "") -> list[tuple[str, Any]]:
    out: list[tuple[str, Any]] = []
    for key, value in params.items():
        name = prefix + perform_typed(context, key)
        if isinstance(value, Mapping):
            out.extend(flatten(context, value, name + "."))
        else:
            out.append((name, performed_value(context, value)))
    return out


def evaluate_parameters(
    context: LaunchContext, parameters: list[Any]
) -> tuple[list[tuple[str, Any]], list[str]]:
    """(name, value) pairs and parameter files' paths, each in order."""
    values: list[tuple[str, Any]] = []
    files: list[str] = []
    for entry in parameters:
        if isinstance(entry, Mapping):
            values.extend(flatten(context, entry))
        elif isinstance(entry, ParameterFile):
            files.append(os.path.abspath(perform_typed(context, entry.param_file)))
        elif isinstance(entry, str | Path | Substitution | list | tuple):
            files.append(os.path.abspath(perform_typed(context, entry)))
        else:
            raise TypeError(
                f"a Node's parameters are dicts and parameters files' paths, got {type(entry).__name__}: {entry!r}"
            )
    return values, files
