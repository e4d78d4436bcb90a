"""The lab's message types in rosbags' typestores, and their RIHS01 type hashes, as ROS 2 and
rmw_zenoh use them (node_runtime/msgs/wire.py turns messages into CDR bytes with the same stores).

Two of rosbags' habits are corrected on the way in: it hashes ``char`` as CHAR where rosidl
hashes it as UINT8 (both are one byte on the wire), and it names service parts ``pkg/srv/msg/X``
where a service's type description names them ``pkg/srv/X``. A service's hash covers its request,
response and event message (REP-2016), so the event type is declared here as rosidl generates it.
The lab's own types' hashes are looked up in a table generated with the message classes
(node_runtime/msgs/generated/type_hashes.py); a student's own type's hash comes from a typestore of
that type and what it nests alone.
"""

from __future__ import annotations

import re
import threading
from functools import cache
from typing import TYPE_CHECKING, Any

from node_runtime.msgs import catalog
from node_runtime.msgs._base import message_class
from node_runtime.msgs.action_spec import action_description_text
from node_runtime.msgs.definitions import Definitions, lab_definitions
from node_runtime.msgs.generated.type_hashes import TYPE_HASHES

if TYPE_CHECKING:
    from rosbags.typesys.store import Typestore

SERVICE_EVENT_INFO = "service_msgs/msg/ServiceEventInfo"


_CHAR = re.compile(r"^(\s*)char(?=[\s\[])", re.MULTILINE)
_BYTE = re.compile(r"^(\s*)byte(?=[\s\[])", re.MULTILINE)


def _for_rosbags(text: str, *, byte_as_uint8: bool = False) -> str:
    # rosidl's type description (and so the hash) treats char as uint8; the bytes are the same.
    # rosbags packs byte as a signed int8, where ROS's byte (octet) is 0..255: for CDR, uint8.
    text = _CHAR.sub(r"\1uint8", text)
    return _BYTE.sub(r"\1uint8", text) if byte_as_uint8 else text


def _fix_srv_names(types: dict[str, Any]) -> dict[str, Any]:
    """rosbags names a service's parts, and the messages a ``.srv`` names bare, ``pkg/srv/msg/X``:
    the parts are ``pkg/srv/X``, the messages of the package ``pkg/msg/X``."""
    parts = {name.replace("/srv/msg/", "/srv/") for name in types}

    def fix(value: Any) -> Any:
        if isinstance(value, tuple):
            return tuple(fix(v) for v in value)
        if not isinstance(value, str) or "/srv/msg/" not in value:
            return value
        part = value.replace("/srv/msg/", "/srv/")
        return part if part in parts else value.replace("/srv/msg/", "/msg/")

    return {fix(name): (consts, [(n, fix(d)) for n, d in fields]) for name, (consts, fields) in types.items()}


def _service_types(name: str, request: str, response: str, byte_as_uint8: bool) -> dict[str, Any]:
    from rosbags.typesys import get_types_from_msg

    event = f"{SERVICE_EVENT_INFO} info\n{name}_Request[<=1] request\n{name}_Response[<=1] response"
    whole = f"{name}_Request request_message\n{name}_Response response_message\n{name}_Event event_message"
    types: dict[str, Any] = {}
    for suffix, text in (("_Request", request), ("_Response", response), ("_Event", event), ("", whole)):
        types.update(get_types_from_msg(_for_rosbags(text, byte_as_uint8=byte_as_uint8), f"{name}{suffix}"))
    return _fix_srv_names(types)


@cache
def _parsed(name: str, text: str, for_hashing: bool) -> dict[str, Any]:
    """rosbags' parse of one definition (the slow part of a typestore), kept: a typestore is built
    again whenever a student's types change, and the lab's own are the same every time."""
    from rosbags.typesys import get_types_from_msg

    return dict(get_types_from_msg(_for_rosbags(text, byte_as_uint8=not for_hashing), name))


@cache
def _parsed_service(name: str, request: str, response: str, for_hashing: bool) -> dict[str, Any]:
    return _service_types(name, request, response, not for_hashing)


def _types(definitions: Definitions, for_hashing: bool) -> dict[str, Any]:
    types: dict[str, Any] = {}
    for name, spec in definitions.messages.items():
        types.update(_parsed(name, spec.text, for_hashing))
    for name, service in definitions.services.items():
        types.update(_parsed_service(name, service.request.text, service.response.text, for_hashing))
    if for_hashing:  # an action's own type is never on the wire; only its hash is asked for
        for name, action in definitions.actions.items():
            types.update(_parsed(name, action_description_text(action), for_hashing))
    return types


def build_typestore(
    definitions: Definitions, *, for_hashing: bool = False, base: Typestore | None = None
) -> Typestore:
    """A rosbags typestore holding exactly ``definitions`` (and the event types of its services),
    laid out for CDR, or ``for_hashing`` with byte kept as rosidl's BYTE. With ``base``, its types
    are copied and only those ``definitions`` adds are registered (rosbags writes and runs code for
    every type it registers, which takes long for the lab's dozens)."""
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.EMPTY)
    types = _types(definitions, for_hashing)
    if base is not None:
        store.fielddefs.update(base.fielddefs)
        store.types.update(base.types)
        store.cache.update(base.cache)
        types = {name: t for name, t in types.items() if name not in base.fielddefs}
    if types:
        store.register(types)
    return store


@cache
def _lab_store(for_hashing: bool) -> Typestore:
    return build_typestore(lab_definitions(), for_hashing=for_hashing)


# rosbags gives a message without fields one uint8 member of this name, as IDL structs need one.
EMPTY_STRUCT_MEMBER = "structure_needs_at_least_one_member"


# The CDR typestore of the catalog's current generation, holding the types used so far.
_cdr: tuple[int, Typestore] | None = None
_cdr_lock = threading.Lock()


def typestore(type_name: str | None = None) -> Typestore:
    """rosbags' typestore for CDR, laid out for what the catalog holds now (a new one when it
    changes). It holds the types asked for so far: ``type_name`` and what it nests are registered
    at their first use, since rosbags parses, writes and runs code for each type it registers, and
    a process uses a few of the hundreds ROS 2's packages define. With no name, every type."""
    global _cdr
    current = _cdr  # every message after its type's first: no lock
    if current is not None and current[0] == catalog.generation() and type_name in current[1].fielddefs:
        return current[1]
    with _cdr_lock:
        generation = catalog.generation()
        if _cdr is None or _cdr[0] != generation:
            from rosbags.typesys import Stores, get_typestore

            _cdr = (generation, get_typestore(Stores.EMPTY))
        store = _cdr[1]
        if type_name is None or type_name not in store.fielddefs:
            definitions = catalog.definitions()
            picked = definitions if type_name is None else _closure(definitions, type_name)
            types = {n: t for n, t in _types(picked, for_hashing=False).items() if n not in store.fielddefs}
            if types:
                _mark_empty_structs(types)
                store.register(types)
        return store


def _mark_empty_structs(types: dict[str, Any]) -> None:
    """rosbags gives a message without fields one member, as IDL structs need one: its class
    answers for it."""
    for name in types:
        try:
            cls = message_class(name)
        except KeyError:  # a service's whole or an event rosbags makes: no class of the lab's
            continue
        if not cls.FIELDS:
            setattr(cls, EMPTY_STRUCT_MEMBER, 0)


def _closure(definitions: Definitions, type_name: str) -> Definitions:
    """The part of ``definitions`` a hash of ``type_name`` reads: the type (a message, a service,
    a service's part or an action) and every type it nests, at any depth."""
    picked = Definitions({}, {}, {})
    for suffix in ("_Request", "_Response", "_Event"):  # a service's part: hashed with its service
        if type_name.endswith(suffix) and type_name.removesuffix(suffix) in definitions.services:
            type_name = type_name.removesuffix(suffix)
    pending = [type_name]
    while pending:
        name = pending.pop()
        if name in definitions.services and name not in picked.services:
            service = picked.services[name] = definitions.services[name]
            pending += [SERVICE_EVENT_INFO, *service.request.dependencies(), *service.response.dependencies()]
        elif name in definitions.actions and name not in picked.actions:
            action = picked.actions[name] = definitions.actions[name]
            pending += [m.name for m in action.messages] + [s.name for s in action.services]
        elif name in definitions.messages and name not in picked.messages:
            spec = picked.messages[name] = definitions.messages[name]
            pending += spec.dependencies()
    return picked


@cache
def _hash(type_name: str, generation: int) -> str:
    store = build_typestore(_closure(catalog.definitions(), type_name), for_hashing=True)
    return str(store.hash_rihs01(type_name))


def type_hash(type_name: str) -> str:
    """``RIHS01_<sha256 hex>`` of a message or service type, computed from its definition (the
    lab's own types' from the generated table)."""
    known = TYPE_HASHES.get(type_name)
    return known if known is not None else computed_type_hash(type_name)


def computed_type_hash(type_name: str) -> str:
    """``type_name``'s hash computed from its definition and what it nests, without the table."""
    return _hash(type_name, catalog.generation())


def computed_type_hashes(definitions: Definitions) -> dict[str, str]:
    """Every hash a typestore of ``definitions`` can give, computed (for the generated table)."""
    own = definitions is lab_definitions()
    store = _lab_store(True) if own else build_typestore(definitions, for_hashing=True)
    return {name: str(store.hash_rihs01(name)) for name in sorted(store.fielddefs)}
