"""The interface types this process knows: the lab's own, and those added while it runs.

A student's interface packages (read from a workspace by node_runtime.ament.interfaces) are added
here as parsed definitions. Their messages, services and actions become classes like the lab's own, found
by name (node_runtime.msgs.registry), with their CDR layout and RIHS01 hash (node_runtime.msgs.wire) and their
text (``interface show``, bags, Foxglove), with no build step. A type that cannot load (it nests a
type no package declares, or one that did not load itself, or it redefines one of the lab's own)
is left out and named in one line with its file and line; every other type loads.

``generation()`` changes whenever the added types do, so what is computed from the definitions
(typestores, hashes) is computed again. Lookups that miss call the refreshers (a lab registers
its workspace's), so a package a student adds while the lab runs is found on first use.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterable

from node_runtime.msgs._action import define_action
from node_runtime.msgs._base import define_message, define_service
from node_runtime.msgs.action_spec import ActionSpec
from node_runtime.msgs.definitions import Definitions, lab_definitions
from node_runtime.msgs.idl import MessageSpec, ServiceSpec

_lock = threading.Lock()
_added: dict[str, Definitions] = {}  # by source (a workspace's path)
_merged = lab_definitions()
_generation = 0
_refreshers: list[Callable[[], object]] = []


def definitions() -> Definitions:
    """Every type known now: the lab's own and the added ones."""
    return _merged


def added(source: str) -> Definitions:
    """The types added at run time from ``source`` (a workspace)."""
    return _added.get(source, Definitions({}, {}))


def generation() -> int:
    """A number that changes whenever the known types change."""
    return _generation


def _parts(services: Iterable[ServiceSpec]) -> list[MessageSpec]:
    return [part for s in services for part in (s.request, s.response)]


def _resolve(
    source: str, messages: list[MessageSpec], services: list[ServiceSpec], broken: frozenset[str]
) -> tuple[dict[str, MessageSpec], dict[str, ServiceSpec], list[str]]:
    """The types that can load, in dependency order, and one line for each that cannot; they may
    nest the lab's types and those of other sources."""
    lab = lab_definitions()
    lab_names = set(lab.messages) | {p.name for p in _parts(lab.services.values())}
    own = {s.name for s in messages} | {p.name for p in _parts(services)}
    available = set(lab_names)
    for other, defs in _added.items():
        if other != source:
            available |= (set(defs.messages) | {p.name for p in _parts(defs.services.values())}) - own
    problems: list[str] = []
    pending: dict[str, MessageSpec] = {}
    for spec in messages:
        if spec.name not in lab_names:
            pending[spec.name] = spec
        elif _differs(spec, lab.messages.get(spec.name)):
            problems.append(f"{spec.source}: {spec.name} differs from the lab's own; the lab's is used")
    loaded: dict[str, MessageSpec] = {}
    progress = True
    while progress:
        progress = False
        for name, spec in list(pending.items()):
            if all(dep in available for dep in spec.dependencies()):
                loaded[name] = pending.pop(name)
                available.add(name)
                progress = True
    declared = {s.name for s in messages} | broken
    for spec in pending.values():
        problems.append(_missing(spec, available, declared))
    loaded_services: dict[str, ServiceSpec] = {}
    for service in services:
        if service.name in lab.services:
            lab_service = lab.services[service.name]
            if _differs(service.request, lab_service.request) or _differs(
                service.response, lab_service.response
            ):
                problems.append(
                    f"{service.source}: {service.name} differs from the lab's own; the lab's is used"
                )
            continue
        missing = [
            _missing(p, available, declared)
            for p in (service.request, service.response)
            if not all(dep in available for dep in p.dependencies())
        ]
        if missing:
            problems.append(missing[0])
        else:
            loaded_services[service.name] = service
    return loaded, loaded_services, problems


def _resolve_actions(
    actions: list[ActionSpec], available: set[str], declared: set[str]
) -> tuple[dict[str, ActionSpec], list[str]]:
    """The actions whose parts nest only known types (their own parts among them)."""
    loaded: dict[str, ActionSpec] = {}
    problems: list[str] = []
    lab = lab_definitions().actions
    for action in actions:
        if action.name in lab:
            continue  # the lab's own (a course's copy): the lab's is used
        parts = [*action.messages, *_parts(action.services)]
        known = available | {p.name for p in parts}
        missing = [
            _missing(p, known, declared) for p in parts if not all(d in known for d in p.dependencies())
        ]
        if missing:
            problems.append(missing[0])
        else:
            loaded[action.name] = action
    return loaded, problems


def _differs(spec: MessageSpec, own: MessageSpec | None) -> bool:
    """A copy of one of the lab's own types (keyboard_msgs from the course) is the lab's; a
    different definition under its name is refused, since the lab's nodes use the lab's."""
    return own is None or (spec.fields, spec.constants) != (own.fields, own.constants)


def _missing(spec: MessageSpec, available: set[str], declared: set[str]) -> str:
    dep = next(d for d in spec.dependencies() if d not in available)
    if dep in declared:
        return f"{spec.where(dep)}: {dep} did not load (see its own error)"
    return f"{spec.where(dep)}: unknown type {dep}"


def replace_added(
    source: str,
    messages: Iterable[MessageSpec],
    services: Iterable[ServiceSpec],
    actions: Iterable[ActionSpec] = (),
    broken: Iterable[str] = (),
) -> list[str]:
    """Make these the types added from ``source``, in place of those it added before; returns one
    line per type left out. ``broken`` names types whose files did not parse (a type that nests
    one is said not to have loaded). Definitions the same as before keep their classes."""
    global _merged, _generation
    with _lock:
        loaded, loaded_services, problems = _resolve(
            source, list(messages), list(services), frozenset(broken)
        )
        lab = lab_definitions()
        available = set(lab.messages) | {p.name for p in _parts(lab.services.values())} | set(loaded)
        available |= {p.name for p in _parts(loaded_services.values())}
        for other, defs in _added.items():
            if other != source:
                available |= set(defs.messages) | {p.name for p in _parts(defs.services.values())}
        loaded_actions, action_problems = _resolve_actions(list(actions), available, set(broken))
        now = Definitions(
            {**loaded, **{m.name: m for a in loaded_actions.values() for m in a.messages}},
            {**loaded_services, **{s.name: s for a in loaded_actions.values() for s in a.services}},
            loaded_actions,
        )
        if now == added(source):
            return problems + action_problems
        for spec in loaded.values():
            define_message(spec, module=f"{spec.package}.msg")
        for service in loaded_services.values():
            define_service(service, module=f"{service.name.split('/')[0]}.srv")
        for action in loaded_actions.values():
            define_action(action)
        _added[source] = now
        merged = Definitions(dict(lab.messages), dict(lab.services), dict(lab.actions))
        for defs in _added.values():
            merged.messages.update(defs.messages)
            merged.services.update(defs.services)
            merged.actions.update(defs.actions)
        _merged = merged
        _generation += 1
    return problems + action_problems


def add_refresher(refresh: Callable[[], object]) -> None:
    """Call ``refresh`` when a lookup misses (once per function, however often it is added)."""
    if refresh not in _refreshers:
        _refreshers.append(refresh)


def refresh() -> None:
    """Let every refresher add what is new (a package a student just wrote)."""
    for refresher in list(_refreshers):
        refresher()
