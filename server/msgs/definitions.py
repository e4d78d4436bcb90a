"""Sets of interface definitions by full type name: the lab's own (``interfaces/<pkg>/{msg,srv}/``),
read once, and any other folder laid out the same way."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from .idl import DefinitionError, MessageSpec, ServiceSpec, parse_message, parse_service

INTERFACES_DIR = Path(__file__).resolve().parent / "interfaces"


@dataclass(frozen=True)
class Definitions:
    """Every interface found under a directory, by full type name."""

    messages: dict[str, MessageSpec]
    services: dict[str, ServiceSpec]

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
    for path in sorted(root.glob("*/msg/*.msg")) + sorted(root.glob("*/srv/*.srv")):
        package, kind = path.parts[-3], path.parts[-2]
        yield f"{package}/{kind}/{path.stem}", kind, path


def load_definitions(root: Path) -> Definitions:
    """Read every ``<pkg>/msg/*.msg`` and ``<pkg>/srv/*.srv`` under ``root``; checks references."""
    messages: dict[str, MessageSpec] = {}
    services: dict[str, ServiceSpec] = {}
    for name, kind, path in _interface_files(root):
        text = path.read_text(encoding="utf-8")
        source = f"{path.parts[-3]}/{kind}/{path.name}"  # as the lab's own files are named in errors
        if kind == "msg":
            messages[name] = parse_message(name, text, source=source)
        else:
            services[name] = parse_service(name, text, source=source)
    definitions = Definitions(messages, services)
    known = set(messages) | {p.name for s in services.values() for p in (s.request, s.response)}
    for spec in list(messages.values()) + [p for s in services.values() for p in (s.request, s.response)]:
        for dep in spec.dependencies():
            if dep not in known:
                raise DefinitionError(f"{spec.where(dep)}: unknown type {dep}")
    return definitions


@cache
def lab_definitions() -> Definitions:
    """The lab's own interfaces (this package's ``interfaces/`` folder)."""
    return load_definitions(INTERFACES_DIR)
