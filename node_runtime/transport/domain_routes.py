"""What the domain bridge is asked to bridge: each world's graph tokens, read into routes.

Zenoh's threads hand every liveliness token of the class's graph to ``RouteTable.record``; the
bridge's own thread takes the domains whose routes may have changed since it last looked
(``take_changed``) and asks ``wanted_in`` for each one's routes to declare now, so that a node
joining one world costs the bridge that world's routes, not the whole class's. Only an entity of a world the
bridge was told of (``set_world``) is wanted, under a fully qualified ROS name (node_runtime/bus/names.py)
and a type and hash of plain name characters: ``/ada`` + ``m/uav/sensors/gps`` would otherwise be
world ``adam``'s GPS. Any other is ignored and counted, by world. What one world's graph can make
the bridge declare is bounded (``MAX_TOKENS_PER_DOMAIN``, ``MAX_ROUTES_PER_WORLD``).
"""

from __future__ import annotations

import logging
import re
import threading
from collections import Counter
from dataclasses import dataclass, field

import zenoh

from node_runtime.bus.names import is_fully_qualified
from node_runtime.transport.keys import EntityKind, EntityToken, QoS

log = logging.getLogger("transport.domain_bridge")
MAX_TOKENS_PER_DOMAIN = 4096  # a world's graph tokens the bridge reads; more are ignored
MAX_ROUTES_PER_WORLD = 512  # topics and services bridged for one world
BRIDGED = (EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION, EntityKind.SERVICE)
# What a type or type hash may hold as it goes into a key: no "/", no wildcard, no "@" or "$".
_PLAIN = re.compile(r"[A-Za-z0-9_]+(::[A-Za-z0-9_]+)*\Z")


@dataclass(frozen=True)
class Route:
    """One topic or service of one world, and which way it crosses: a world's publisher (PUBLISHER)
    crosses out into the class domain, a world's subscription (SUBSCRIPTION) takes what the class
    domain sends, a world's service (SERVICE) answers the calls made in the class domain."""

    domain_id: int
    kind: EntityKind
    topic: str
    dds_type: str
    type_hash: str


@dataclass
class BridgeStats:
    out: int = 0  # samples from a world into the class domain
    into: int = 0  # samples from the class domain into a world
    dropped: int = 0  # without rmw_zenoh's attachment, or a put that failed
    calls: int = 0  # service calls answered with a world's reply
    refused: int = 0  # service calls refused: no attachment, or too many waiting on the world
    bad_names: Counter[int] = field(default_factory=Counter)  # entities ignored for their names, by domain


class RouteTable:
    """The worlds by ROS domain and the graph's tokens that ask for a route, kept apart from the
    bridge's own session ``zid`` and from ``class_domain``; safe to use from any thread."""

    def __init__(self, class_domain: int, zid: str, stats: BridgeStats) -> None:
        self.class_domain = class_domain
        self.zid = zid
        self.stats = stats
        self._lock = threading.Lock()  # guards what Zenoh's threads and the callers change
        self._worlds: dict[int, str] = {}  # ROS domain → world name
        self._endpoints: dict[str, tuple[Route, QoS]] = {}  # token key → what it asks to bridge
        self._by_domain: dict[int, dict[str, tuple[Route, QoS]]] = {}  # the same, by ROS domain
        self._changed: set[int] = set()  # domains whose wanted routes may differ from the last look
        self._ignored: set[int] = set()  # domains over a limit, told once

    def set_world(self, domain_id: int, name: str) -> None:
        """World ``name`` runs in ``domain_id``: show it as ``/<name>``."""
        if domain_id == self.class_domain:
            raise ValueError("a world cannot share the class's own domain")
        with self._lock:
            self._worlds[domain_id] = name
            self._changed.add(domain_id)

    def drop_world(self, domain_id: int) -> None:
        with self._lock:
            self._worlds.pop(domain_id, None)
            self._changed.add(domain_id)

    def refused_names(self) -> dict[str, int]:
        """Entities ignored for their names, by world (``domain <d>`` where no world is known)."""
        with self._lock:
            worlds = dict(self._worlds)
            counts = dict(self.stats.bad_names)
        return {worlds.get(d, f"domain {d}"): n for d, n in sorted(counts.items())}

    def record(self, sample: zenoh.Sample) -> bool:
        """A liveliness token came or went (Zenoh's thread): whether what is wanted may have changed."""
        key = str(sample.key_expr)
        if sample.kind != zenoh.SampleKind.PUT:
            with self._lock:
                gone = self._endpoints.pop(key, None)
                if gone is not None:
                    domain_id = gone[0].domain_id
                    del self._by_domain[domain_id][key]
                    if not self._by_domain[domain_id]:
                        del self._by_domain[domain_id]
                    self._changed.add(domain_id)
            return gone is not None
        token = EntityToken.parse(key)
        if (
            token is None
            or token.zid == self.zid
            or token.domain_id == self.class_domain
            or token.kind not in BRIDGED
            or token.topic is None
            or token.dds_type is None
            or token.type_hash is None
            or token.qos is None
        ):
            return False
        if not (
            is_fully_qualified(token.topic) and _PLAIN.match(token.dds_type) and _PLAIN.match(token.type_hash)
        ):
            with self._lock:
                self.stats.bad_names[token.domain_id] += 1
            return False
        route = Route(token.domain_id, token.kind, token.topic, token.dds_type, token.type_hash)
        with self._lock:
            if key in self._endpoints:
                return False
            in_domain = self._by_domain.setdefault(route.domain_id, {})
            if len(in_domain) >= MAX_TOKENS_PER_DOMAIN:
                self._tell_once(route.domain_id, f"more than {MAX_TOKENS_PER_DOMAIN} graph tokens")
                return False
            self._endpoints[key] = in_domain[key] = (route, token.qos)
            self._changed.add(route.domain_id)
        return True

    def touch(self, *domain_ids: int) -> None:
        """Have these domains looked at again, as if their tokens had changed."""
        with self._lock:
            self._changed.update(domain_ids)

    def take_changed(self) -> list[int]:
        """The domains whose wanted routes may have changed since the last call (a token came or
        went, a world was named or dropped), in order; each is reported once."""
        with self._lock:
            changed, self._changed = sorted(self._changed), set()
        return changed

    def wanted_in(self, domain_id: int) -> tuple[str | None, dict[Route, QoS]]:
        """The namespace (``/<world>``; None when no world runs in ``domain_id``) and the routes of
        that domain to declare now, with the QoS each is declared with, in the order their tokens came."""
        with self._lock:
            world = self._worlds.get(domain_id)
            endpoints = list(self._by_domain.get(domain_id, {}).values()) if world is not None else []
        if world is None:
            return None, {}
        wanted: dict[Route, QoS] = {}
        for route, qos in endpoints:
            if route in wanted:
                continue
            if len(wanted) >= MAX_ROUTES_PER_WORLD:
                self._tell_once(domain_id, f"more than {MAX_ROUTES_PER_WORLD} topics")
                break
            wanted[route] = qos
        return f"/{world}", wanted

    def wanted(self) -> dict[Route, tuple[str, QoS]]:
        """Every route to declare now, with the namespace (``/<world>``) and QoS it is declared with."""
        with self._lock:
            domains = sorted(self._worlds)
        out: dict[Route, tuple[str, QoS]] = {}
        for domain_id in domains:
            namespace, routes = self.wanted_in(domain_id)
            if namespace is not None:
                out.update({route: (namespace, qos) for route, qos in routes.items()})
        return out

    def _tell_once(self, domain_id: int, why: str) -> None:
        if domain_id not in self._ignored:
            self._ignored.add(domain_id)
            log.warning("ROS domain %d: %s; the rest of that world is not bridged", domain_id, why)
