"""Which front-end reads a launch file, by its name, as ``ros2 launch`` tells them: Python for
``.py`` (``x.launch.py``, ``x_launch.py``), YAML for ``.yaml``/``.yml``, else XML (``.xml``,
``.launch``)."""

from __future__ import annotations

from pathlib import Path

from server.services.launch.xml_tree import Element, load_tree
from server.services.launch.yaml_tree import load_yaml_tree

YAML_SUFFIXES = (".yaml", ".yml")


def is_yaml(path: str | Path) -> bool:
    return Path(path).suffix.lower() in YAML_SUFFIXES


def load_frontend_tree(data: bytes, file: str) -> Element:
    """The checked element tree of an XML or YAML launch file."""
    return load_yaml_tree(data, file) if is_yaml(file) else load_tree(data, file)
