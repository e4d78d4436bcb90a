"""``ParameterValue(value, value_type=...)`` and ``ParameterFile(path)`` in a Node's parameters."""

from __future__ import annotations

from typing import Any


class ParameterValue:
    """A parameter's value, performed and, with ``value_type``, converted to that type."""

    def __init__(self, value: Any, *, value_type: Any = None) -> None:
        self.value = value
        self.value_type = value_type


class ParameterFile:
    """A parameters file in ROS 2's layout; ``allow_substs`` is taken as given (the file is read
    as it is)."""

    def __init__(self, param_file: Any, *, allow_substs: Any = False) -> None:
        self.param_file = param_file
        self.allow_substs = allow_substs


__all__ = ["ParameterFile", "ParameterValue"]
