"""A workspace's interface packages: their ``.msg`` and ``.srv`` files as types, with no build step.

A package declares its interfaces as ROS 2 does: the files named in ``rosidl_generate_interfaces``
of its ``CMakeLists.txt`` (``${VAR}`` of a ``set(VAR ...)`` expanded); without that call, a package
that is a member of ``rosidl_interface_packages`` (package.xml) has every ``msg/*.msg`` and
``srv/*.srv`` and ``action/*.action``. The types are added to this process's catalog (node_runtime.msgs.catalog), so they are
found by name like the lab's own. A file that does not parse, a type it nests that no package
declares, or a file the CMakeLists names that is not there, is one line naming the file and line
(``problems``); the package's other types and the rest of the workspace still load.

A lab, and a node process on first import of such a package, read the workspace through
:func:`workspace_interfaces`, which reads it again whenever its interface files change.
"""

from __future__ import annotations

import logging
import re
import threading
from dataclasses import dataclass, field
from pathlib import Path

from node_runtime.ament.manifest import MANIFEST, WorkspaceError, read_manifest
from node_runtime.ament.workspace import find_packages
from node_runtime.msgs import catalog
from node_runtime.msgs.action_spec import ActionSpec, parse_action
from node_runtime.msgs.idl import DefinitionError, MessageSpec, ServiceSpec, parse_message, parse_service

CMAKE = "CMakeLists.txt"
KINDS = {".msg": "msg", ".srv": "srv", ".action": "action"}
_ROSIDL = re.compile(r"\brosidl_generate_interfaces\s*\(([^)]*)\)", re.IGNORECASE)
_SET = re.compile(r"\bset\s*\(\s*(\w+)([^)]*)\)", re.IGNORECASE)
_VAR = re.compile(r"\$\{(\w+)\}")
_TYPE_NAME = re.compile(r"[A-Z][A-Za-z0-9]*\Z")
log = logging.getLogger("interfaces")


@dataclass(frozen=True)
class InterfaceFile:
    """One interface file of a package, and where it is declared."""

    path: Path
    type_name: str  # pkg/msg/Name or pkg/srv/Name
    declared_at: str


@dataclass
class InterfacePackage:
    name: str
    path: Path
    files: list[InterfaceFile] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)


def _words(text: str) -> list[tuple[str, int]]:
    """CMake arguments with the line each starts on (comments dropped, quotes taken off)."""
    words = []
    for number, line in enumerate(text.splitlines(), start=1):
        for word in re.findall(r'"[^"]*"|[^\s"]+', line.split("#", 1)[0]):
            words.append((word.strip('"'), number))
    return words


def _declared_files(package: str, folder: Path) -> tuple[list[tuple[str, str]], bool]:
    """(file relative to the package, ``CMakeLists.txt:LINE``) per file ``rosidl_generate_interfaces``
    names, and whether the CMakeLists calls it at all."""
    cmake = folder / CMAKE
    if not cmake.is_file():
        return [], False
    text = cmake.read_text(encoding="utf-8", errors="replace")
    plain = "\n".join(line.split("#", 1)[0] for line in text.splitlines())
    variables = {"PROJECT_NAME": [package]}
    for match in _SET.finditer(plain):
        variables[match[1]] = [w for w, _ in _words(match[2])]
    found: list[tuple[str, str]] = []
    called = False
    for match in _ROSIDL.finditer(plain):
        called = True
        first_line = plain.count("\n", 0, match.start(1)) + 1
        for word, offset in _words(match[1])[1:]:
            expanded = [word]
            whole = _VAR.fullmatch(word)
            if whole is not None:
                expanded = variables.get(whole[1], [])
            for item in expanded:
                if item.endswith(tuple(KINDS)):
                    found.append((item, f"{cmake}:{first_line + offset - 1}"))
    return found, called


def package_interfaces(name: str, folder: Path, member: bool) -> InterfacePackage:
    """The interface files of one package (``member``: of ``rosidl_interface_packages``)."""
    package = InterfacePackage(name, folder)
    declared, called = _declared_files(name, folder)
    if not called and member:
        declared = [
            (str(p.relative_to(folder)), str(folder / MANIFEST))
            for kind in KINDS.values()
            for p in sorted((folder / kind).glob(f"*.{kind}"))
        ]
    for rel, where in declared:
        path = folder / rel
        kind = KINDS[path.suffix]
        if not path.is_file():
            package.problems.append(f"{where}: no file {rel} in {folder}")
        elif path.parent.name != kind or not _TYPE_NAME.match(path.stem):
            package.problems.append(f"{where}: {rel}: a {kind} is {kind}/CamelCaseName.{kind}")
        else:
            package.files.append(InterfaceFile(path, f"{name}/{kind}/{path.stem}", where))
    return package


@dataclass
class Parsed:
    """What a workspace's interface files hold, and the names of those that did not parse."""

    messages: list[MessageSpec] = field(default_factory=list)
    services: list[ServiceSpec] = field(default_factory=list)
    actions: list[ActionSpec] = field(default_factory=list)
    broken: list[str] = field(default_factory=list)


def _parse(package: InterfacePackage, parsed: Parsed) -> None:
    for item in package.files:
        try:
            text = item.path.read_text(encoding="utf-8")
            kind, source = item.type_name.split("/")[1], str(item.path)
            if kind == "msg":
                parsed.messages.append(parse_message(item.type_name, text, source=source))
            elif kind == "srv":
                parsed.services.append(parse_service(item.type_name, text, source=source))
            else:
                parsed.actions.append(parse_action(item.type_name, text, source=source))
        except DefinitionError as exc:
            package.problems.append(str(exc))
            parsed.broken.append(item.type_name)
        except (OSError, UnicodeDecodeError) as exc:
            package.problems.append(f"{item.path}: cannot read it: {exc}")
            parsed.broken.append(item.type_name)


class WorkspaceInterfaces:
    """The interface packages of one workspace, added to the catalog and kept current."""

    def __init__(self, workspace: Path) -> None:
        self.workspace = workspace
        self.source = str(workspace.resolve())
        self.packages: dict[str, InterfacePackage] = {}
        self.problems: list[str] = []  # every package's, and the types the catalog left out
        self._left_out: list[str] = []
        self.log_problems = False  # a lab logs each new problem; a node process reports it on import
        self._lock = threading.Lock()
        self._seen: tuple[tuple[str, int, int], ...] | None = None

    def _fingerprint(self, folders: list[Path]) -> tuple[tuple[str, int, int], ...]:
        stamps = []
        for folder in folders:
            paths = [
                folder / MANIFEST,
                folder / CMAKE,
                *(p for kind in KINDS.values() for p in folder.glob(f"{kind}/*")),
            ]
            for path in paths:
                try:
                    stat = path.stat()
                except OSError:
                    continue
                stamps.append((str(path), stat.st_mtime_ns, stat.st_size))
        return tuple(sorted(stamps))

    def sync(self) -> list[str]:
        """Read the workspace's interfaces again if any of their files changed; the problems."""
        with self._lock:
            found = find_packages(self.workspace)
            members = [p for p in found.packages.values() if p.build_type is not None]
            fingerprint = self._fingerprint([p.path for p in members])
            if fingerprint == self._seen:
                return self.problems
            self._seen = fingerprint
            packages: dict[str, InterfacePackage] = {}
            parsed = Parsed()
            for pkg in members:
                try:
                    manifest = read_manifest(pkg.path / MANIFEST)
                except WorkspaceError:
                    continue  # find_packages reports it
                interfaces = package_interfaces(pkg.name, pkg.path, manifest.interfaces)
                if not interfaces.files and not interfaces.problems:
                    continue
                packages[pkg.name] = interfaces
                _parse(interfaces, parsed)
            left_out = catalog.replace_added(
                self.source, parsed.messages, parsed.services, parsed.actions, parsed.broken
            )
            self.packages = packages
            self._left_out = left_out
            before, self.problems = (
                self.problems,
                [p for i in packages.values() for p in i.problems] + left_out,
            )
            if self.log_problems:
                for problem in self.problems:
                    if problem not in before:
                        log.error(problem)
            return self.problems

    def problem_of(self, type_name: str) -> str | None:
        """Why ``pkg/msg/Name`` (``pkg/srv/Name``, ``pkg/action/Name``) of this workspace did not
        load, if it did not."""
        package = self.packages.get(type_name.split("/")[0])
        if package is None:
            return None
        files = [str(f.path) for f in package.files if f.type_name == type_name]
        problems = self.package_problems(package.name)
        return next((p for p in problems if p.split(":", 1)[0] in files), None)

    def package_problems(self, name: str) -> list[str]:
        """The problems of one package: its own, and its types the catalog left out."""
        package = self.packages.get(name)
        if package is None:
            return []
        own = [str(f.path) for f in package.files]
        return package.problems + [p for p in self._left_out if p.split(":", 1)[0] in own]


_instances: dict[str, WorkspaceInterfaces] = {}
_instances_lock = threading.Lock()


def workspace_interfaces(workspace: Path, *, log_problems: bool = False) -> WorkspaceInterfaces:
    """The one reader of ``workspace`` in this process, read now and refreshed by the catalog on
    a lookup of a type it does not know; ``log_problems`` logs each problem as it appears."""
    key = str(workspace.resolve())
    with _instances_lock:
        reader = _instances.get(key)
        if reader is None:
            reader = _instances[key] = WorkspaceInterfaces(workspace)
            catalog.add_refresher(reader.sync)
    if log_problems and not reader.log_problems:
        reader.log_problems = True
        for problem in reader.problems:
            log.error(problem)
    reader.sync()
    return reader
