"""The part of the ROS graph that lives in other processes, as their liveliness tokens tell it.

Tokens come and go with their entities (a process that exits or is killed drops all of its own).
Queries here answer what ``ros2 node list``, ``topic list -t`` and ``topic info`` need; types are
given in ROS form (``std_msgs/msg/Bool``), or in DDS form when the name has another shape.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any, TypeVar

from node_runtime.msgs.wire import ros_type_name
from node_runtime.transport.keys import RMW_ZENOH_DEFAULT_QOS, EntityKind, EntityToken, QoS, entity_gid


@dataclass(frozen=True)
class RemoteNode:
    name: str  # fully qualified, /ns/name
    namespace: str
    zid: str  # the Zenoh session (process) it runs in
    location: str  # "process <pid>" for a process the app started, else "zenoh:<session>"


@dataclass(frozen=True)
class RemoteEndpoint:
    kind: EntityKind
    node: str  # fully qualified name of its node
    name: str  # topic or service name
    type_name: str  # ROS name when it has ROS's shape, else the DDS name as sent
    type_hash: str
    depth: int
    zid: str
    qos: QoS = RMW_ZENOH_DEFAULT_QOS  # the profile its token gives (rclpy's incompatible-QoS events)


_T = TypeVar("_T")
MAX_SESSIONS_REMEMBERED = 1024
_TOPIC_KINDS = frozenset({EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION})


class RemoteGraph:
    """Tokens of every session but ``own_zid``, by key."""

    def __init__(self, own_zid: str, domain_id: int) -> None:
        self.own_zid = own_zid
        self.domain_id = domain_id
        self._tokens: dict[str, EntityToken] = {}
        self._publishers: dict[bytes, str] = {}  # a publisher's GID (its samples carry it) → its key
        self.version = 0
        self.malformed = 0
        self._labels: dict[str, str] = {}
        # Node names each session has declared, kept after it is gone (a died process's nodes).
        self._seen: OrderedDict[str, list[str]] = OrderedDict()
        # What the queries below answered, with the version they answered at: a page's topic and
        # node lists ask every second, and a class server's loop built each answer anew (a few
        # milliseconds a call with two nodes, its worlds' ticks waiting meanwhile).
        self._cache: dict[object, tuple[int, Any]] = {}

    def name_session(self, zid: str, label: str) -> None:
        """Say where a session runs (``process 1234``), for the locations the graph shows."""
        self._labels[zid] = label
        self.version += 1

    def location(self, zid: str) -> str:
        return self._labels.get(zid) or f"zenoh:{zid[:8]}"

    def apply(self, key: str, alive: bool) -> bool:
        """A token appeared (``alive``) or went; returns whether the graph changed."""
        if not alive:
            gone = self._tokens.pop(key, None)
            if gone is None:
                return False
            if gone.kind is EntityKind.PUBLISHER:
                self._publishers.pop(entity_gid(key), None)
            self.version += 1
            return True
        token = EntityToken.parse(key)
        if token is None:
            self.malformed += 1
            return False
        if token.zid == self.own_zid or token.domain_id != self.domain_id or key in self._tokens:
            return False
        self._tokens[key] = token
        if token.kind is EntityKind.PUBLISHER:
            self._publishers[entity_gid(key)] = key
        if token.kind is EntityKind.NODE:
            names = self._seen.setdefault(token.zid, [])
            if token.node_fqn not in names:
                names.append(token.node_fqn)
            self._seen.move_to_end(token.zid)
            while len(self._seen) > MAX_SESSIONS_REMEMBERED:
                self._seen.popitem(last=False)
        self.version += 1
        return True

    def drop_session(self, zid: str) -> bool:
        gone = [k for k, t in self._tokens.items() if t.zid == zid]
        for key in gone:
            if self._tokens.pop(key).kind is EntityKind.PUBLISHER:
                self._publishers.pop(entity_gid(key), None)
        if gone:
            self.version += 1
        return bool(gone)

    def publisher(self, gid: bytes) -> tuple[str, str] | None:
        """The node (fully qualified) and session of the publisher whose samples carry ``gid``."""
        key = self._publishers.get(gid)
        token = self._tokens.get(key) if key is not None else None
        return (token.node_fqn, token.zid) if token is not None else None

    def _answer(self, key: object, build: Callable[[], _T]) -> _T:
        """``build()``'s answer as of this version of the graph, kept until the graph changes."""
        cached = self._cache.get(key)
        if cached is None or cached[0] != self.version:
            cached = self._cache[key] = (self.version, build())
        answer: _T = cached[1]
        return answer

    def nodes(self) -> list[RemoteNode]:
        return list(self._answer("nodes", self._nodes))

    def _nodes(self) -> list[RemoteNode]:
        return sorted(
            (
                RemoteNode(t.node_fqn, t.namespace, t.zid, self.location(t.zid))
                for t in self._tokens.values()
                if t.kind is EntityKind.NODE
            ),
            key=lambda n: (n.name, n.zid),
        )

    def endpoints(self, kinds: Iterable[EntityKind] | None = None) -> list[RemoteEndpoint]:
        wanted = frozenset(kinds) if kinds is not None else frozenset(EntityKind) - {EntityKind.NODE}
        return list(self._answer(wanted, lambda: self._endpoints(wanted)))

    def _endpoints(self, wanted: frozenset[EntityKind]) -> list[RemoteEndpoint]:
        out = []
        for t in self._tokens.values():
            if t.kind not in wanted or t.topic is None or t.dds_type is None:
                continue
            out.append(
                RemoteEndpoint(
                    kind=t.kind,
                    node=t.node_fqn,
                    name=t.topic,
                    type_name=ros_type_name(t.dds_type) or t.dds_type,
                    type_hash=t.type_hash or "",
                    depth=t.qos.depth if t.qos is not None else 0,
                    zid=t.zid,
                    qos=t.qos or RMW_ZENOH_DEFAULT_QOS,
                )
            )
        return sorted(out, key=lambda e: (e.name, e.kind.value, e.node))

    def topic_types(self) -> Mapping[str, frozenset[str]]:
        """Every topic name other sessions publish or subscribe to, with the types they give it
        (the same mapping until the graph changes: not to be changed by the caller)."""
        return self._answer("topic_types", self._topic_types)

    def _topic_types(self) -> dict[str, frozenset[str]]:
        out: dict[str, set[str]] = {}
        for e in self.endpoints(_TOPIC_KINDS):
            out.setdefault(e.name, set()).add(e.type_name)
        return {k: frozenset(v) for k, v in out.items()}

    def has_server(self, service: str, dds_type: str) -> bool:
        return any(
            t.kind is EntityKind.SERVICE and t.topic == service and t.dds_type == dds_type
            for t in self._tokens.values()
        )

    def names_seen(self, zid: str) -> list[str]:
        """The nodes session ``zid`` declared, whether or not it is still there."""
        return list(self._seen.get(zid, ()))

    def sessions(self) -> set[str]:
        return {t.zid for t in self._tokens.values()}
