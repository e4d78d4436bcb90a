"""Sets of interface definitions by full type name: the lab's (its own packages in
``interfaces/<pkg>/{msg,srv,action}/`` and ROS 2's in ``ros_interfaces/``, extracted from PyPI's
wheels at set-up by node_runtime/ros_wheels.py), read once, and any other folder laid out the same way."""

from __future__ import annotations

import hashlib
import os
import pickle
import sys
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING

from node_runtime.msgs.idl import DefinitionError, MessageSpec, ServiceSpec, parse_message, parse_service

if TYPE_CHECKING:
    from node_runtime.msgs.action_spec import ActionSpec

INTERFACES_DIR = Path(__file__).resolve().parent / "interfaces"  # the lab's own, kept here
ROS_INTERFACES_DIR = Path(__file__).resolve().parent / "ros_interfaces"  # ROS 2's, not committed


@dataclass(frozen=True)
class Definitions:
    """Every interface found under a directory, by full type name."""

    messages: dict[str, MessageSpec]
    services: dict[str, ServiceSpec]
    actions: dict[str, ActionSpec] = field(default_factory=dict)

    def message(self, name: str) -> MessageSpec:
        spec = self.messages.get(name)
        if spec is None:
            for service in self.services.values():
                for part in (service.request, service.response):
                    if part.name == name:
                        return part
            raise KeyError(name)
        return spec

    def closure(self, name: str) -> list[MessageSpec]:
        """``name``'s spec and every type it depends on, depth first, each once."""
        seen: dict[str, MessageSpec] = {}

        def visit(type_name: str) -> None:
            if type_name in seen:
                return
            spec = self.message(type_name)
            seen[type_name] = spec
            for dep in spec.dependencies():
                visit(dep)

        visit(name)
        return list(seen.values())


def _interface_files(root: Path) -> Iterator[tuple[str, str, Path]]:
    found = sorted(root.glob("*/msg/*.msg")) + sorted(root.glob("*/srv/*.srv"))
    for path in found + sorted(root.glob("*/action/*.action")):
        package, kind = path.parts[-3], path.parts[-2]
        yield f"{package}/{kind}/{path.stem}", kind, path


def _files(roots: tuple[Path, ...]) -> Iterator[tuple[str, str, Path]]:
    """Every root's files; a package is in one root only."""
    owner: dict[str, Path] = {}
    for root in roots:
        for name, kind, path in _interface_files(root):
            package = name.split("/")[0]
            if owner.setdefault(package, root) != root:
                raise DefinitionError(f"{package} is both in {owner[package]} and in {root}")
            yield name, kind, path


def load_definitions(root: Path, *more: Path) -> Definitions:
    """Read every ``<pkg>/msg/*.msg``, ``<pkg>/srv/*.srv`` and ``<pkg>/action/*.action`` under
    ``root`` (and ``more``); an action adds the messages and services derived from it. Checks
    references."""
    from node_runtime.msgs.action_spec import parse_action  # it builds on idl's grammar

    messages: dict[str, MessageSpec] = {}
    services: dict[str, ServiceSpec] = {}
    actions: dict[str, ActionSpec] = {}
    for name, kind, path in _files((root, *more)):
        text = path.read_text(encoding="utf-8")
        source = f"{path.parts[-3]}/{kind}/{path.name}"  # as the lab's own files are named in errors
        if kind == "msg":
            messages[name] = parse_message(name, text, source=source)
        elif kind == "srv":
            services[name] = parse_service(name, text, source=source)
        else:
            action = actions[name] = parse_action(name, text, source=source)
            messages.update((m.name, m) for m in action.messages)
            services.update((s.name, s) for s in action.services)
    definitions = Definitions(messages, services, actions)
    known = set(messages) | {p.name for s in services.values() for p in (s.request, s.response)}
    for spec in list(messages.values()) + [p for s in services.values() for p in (s.request, s.response)]:
        for dep in spec.dependencies():
            if dep not in known:
                raise DefinitionError(f"{spec.where(dep)}: unknown type {dep}")
    return definitions


class MissingDefinitionsError(DefinitionError):
    """ROS 2's definitions were not extracted: the set-up did not run here."""


@cache
def lab_definitions() -> Definitions:
    """The lab's interfaces: its own (``interfaces/``) and ROS 2's (``ros_interfaces/``)."""
    if not (ROS_INTERFACES_DIR / "std_msgs").is_dir():
        raise MissingDefinitionsError(
            f"ROS 2's interface definitions (std_msgs, geometry_msgs, ...) are not in {ROS_INTERFACES_DIR}:"
            " run `python -m node_runtime.ros_wheels` to take them from PyPI (scripts/run.sh and"
            " scripts/test.sh run it)"
        )
    return _cached(INTERFACES_DIR, ROS_INTERFACES_DIR)


# Every process that imports the messages reads the lab's definitions: parsed, some 60 ms of CPU
# for ~250 files; unpickled, ~3 ms. The parsed set is kept beside ROS 2's definitions (a folder
# of the checkout's, which only the set-up and the developer write), under a key of every file it
# came from and of the parser's own modules, so an edit to either parses again. It sits in a
# __pycache__ folder, as Python's own compiled files do, so no packaging ships it.
_PARSED = ROS_INTERFACES_DIR / "__pycache__" / "parsed.pickle"
_PARSER = ("idl.py", "action_spec.py", "definitions.py")


def _key(roots: tuple[Path, ...]) -> str:
    here = Path(__file__).resolve().parent
    files = [here / name for name in _PARSER] + [p for root in roots for _, _, p in _interface_files(root)]
    stats = [(str(p), p.stat().st_size, p.stat().st_mtime_ns) for p in files]
    return hashlib.sha256(repr((sys.version, stats)).encode()).hexdigest()


def _cached(*roots: Path) -> Definitions:
    key = _key(roots)
    try:
        with _PARSED.open("rb") as stored:
            if pickle.load(stored) == key:
                found = pickle.load(stored)
                if isinstance(found, Definitions):
                    return found
    except (OSError, EOFError, pickle.UnpicklingError, AttributeError, ValueError, TypeError):
        pass  # none yet, or of another version: parsed again below
    definitions = load_definitions(*roots)
    try:  # written whole or not at all (a process reading it meanwhile sees the old one)
        _PARSED.parent.mkdir(mode=0o755, exist_ok=True)
        with tempfile.NamedTemporaryFile("wb", dir=_PARSED.parent, delete=False) as new:
            pickle.dump(key, new)
            pickle.dump(definitions, new)
        os.chmod(new.name, 0o644)  # node processes of other users read it too
        os.replace(new.name, _PARSED)
    except OSError:
        pass  # a read-only checkout (a sandboxed node): parsing each time is only slower
    return definitions
