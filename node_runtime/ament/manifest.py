"""A package's ``package.xml``, read as colcon reads it: the name and the build type.

Only what finding and running a package needs is read (and whether it is an interface package,
a member of ``rosidl_interface_packages``); a file that does not parse, or has no
``<name>``, is a :class:`WorkspaceError` naming the file and line.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

MANIFEST = "package.xml"
DEFAULT_BUILD_TYPE = "ament_cmake"  # what colcon assumes when the export names none, as ROS does
INTERFACE_GROUP = "rosidl_interface_packages"


class WorkspaceError(LookupError):
    """A student's workspace file that cannot be used: one line naming the file (and line). A
    LookupError, as the package or executable it declares cannot be found through it."""

    def __init__(self, where: str, problem: str) -> None:
        self.where = where
        super().__init__(f"{where}: {problem}")


@dataclass(frozen=True)
class Manifest:
    name: str
    build_type: str
    path: Path  # the package.xml
    interfaces: bool = False  # <member_of_group>rosidl_interface_packages</member_of_group>


def read_manifest(path: Path) -> Manifest:
    try:
        root = ET.fromstring(path.read_bytes())
    except ET.ParseError as exc:
        line, _column = exc.position
        reason = str(exc).split(":", 1)[0]
        raise WorkspaceError(f"{path}:{line}", f"package.xml does not parse: {reason}") from None
    except OSError as exc:
        raise WorkspaceError(str(path), f"cannot read it: {exc.strerror}") from None
    if root.tag != "package":
        raise WorkspaceError(str(path), f"the root element is <{root.tag}>, not <package>")
    name = (root.findtext("name") or "").strip()
    if not name:
        raise WorkspaceError(str(path), "it has no <name>")
    build_type = (root.findtext("export/build_type") or DEFAULT_BUILD_TYPE).strip()
    groups = {(g.text or "").strip() for g in root.findall("member_of_group")}
    return Manifest(name, build_type, path, INTERFACE_GROUP in groups)
