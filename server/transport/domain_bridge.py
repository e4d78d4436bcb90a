"""Every world's topics in the class's own ROS domain, under the world's name: ``/ada/uav/sensors/gps``
there is world ada's ``/uav/sensors/gps``. ROS 2's ``domain_bridge`` with a namespace remap, run
on the class server's Zenoh session.

- Worlds stay ROS domains of their own, which the router's access control keeps apart; only the
  class's login reaches the class domain, so this is the instructor's view of the whole class
  (their ROS 2 tools, or ``ros2lab run`` with the instructor's token).
- Each topic a world publishes gets a publisher there (a liveliness token of node
  ``/<world>/domain_bridge``, the world's type, hash and QoS). Its samples cross only while
  something in the class domain subscribes (Zenoh's matching status): only then does the bridge
  subscribe in the world, so a world nobody watches costs nothing.
- Each topic a world subscribes gets a subscription there; what is published on it in the class
  domain goes into the world (``ros2 topic pub /ada/uav/input/position ...`` flies ada's drone).
- Each service a world serves gets a server there (``ros2 service call /ada/rocket/reset ...``
  resets ada's rocket): the bridge passes the request into the world as a call of its own and
  answers the caller with the world's reply, under the caller's sequence number and GID, as
  rmw_zenoh's client matches it. At most ``MAX_CALLS_PER_WORLD`` calls wait on one world at once;
  one more is refused with an error reply.
- A world's entity is bridged only under a fully qualified ROS name (server/bus/names.py) and a
  type and hash of plain name characters: ``/ada`` + ``m/uav/sensors/gps`` would otherwise be world
  ``adam``'s GPS. Any other is ignored and counted, by world (``refused_names``).
- Samples and requests cross as bytes, so no type needs to be known; each gets a new rmw_zenoh
  attachment (the bridge's own GID and sequence numbers, the source timestamp kept), and one
  without an attachment is dropped, as rmw_zenoh drops it.
- Declarations happen on the bridge's own thread, which brings what is declared in line with what
  the graph asks for; Zenoh's threads only record a change or pass a sample on (congestion
  control DROP: a slow watcher never holds anything up). What one world's graph can make the
  bridge declare is bounded.
"""

from __future__ import annotations

import itertools
import logging
import re
import struct
import threading
import time
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import zenoh

from ..bus.names import is_fully_qualified
from .attachment import ATTACHMENT_BYTES
from .keys import ADMIN_SPACE, GID_BYTES, EntityKind, EntityToken, QoS, data_key

log = logging.getLogger("transport.domain_bridge")
NODE_NAME = "domain_bridge"
MAX_TOKENS_PER_DOMAIN = 4096  # a world's graph tokens the bridge reads; more are ignored
MAX_ROUTES_PER_WORLD = 512  # topics and services bridged for one world
MAX_CALLS_PER_WORLD = 32  # service calls waiting on one world's servers at once
CALL_TIMEOUT_S = 60.0  # a call the world has not answered by then is given up
BRIDGED = (EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION, EntityKind.SERVICE)
_SEQUENCE = struct.Struct("<q")
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


@dataclass
class _Mirror:
    route: Route
    namespace: str  # /<world>
    token: EntityToken  # in the class domain
    handle: Any  # its liveliness token
    class_side: Any  # publisher (out), subscriber (into) or queryable (service) in the class domain
    world_side: Any = None  # subscriber (out, while matched) or publisher (into) in the world
    matching: bool = False
    seq: Iterator[int] = field(default_factory=lambda: itertools.count(1))
    listener: Any = None
    tail: bytes = b""  # the attachment's last 17 bytes: GID length and the bridge's GID

    def __post_init__(self) -> None:
        self.tail = bytes([GID_BYTES]) + self.token.gid  # computed once: a GID hashes its token


class DomainBridge:
    """Mirrors the worlds ``set_world`` names into ``class_domain`` until ``close``."""

    def __init__(self, session: zenoh.Session, class_domain: int, stats: BridgeStats | None = None) -> None:
        self.session: Any = session
        self.class_domain = class_domain
        self.zid = str(session.zid())
        self.stats = stats if stats is not None else BridgeStats()  # the caller's, to outlive this bridge
        self._lock = threading.Lock()  # guards what Zenoh's threads and the callers change
        self._worlds: dict[int, str] = {}  # ROS domain → world name
        self._endpoints: dict[str, tuple[Route, QoS]] = {}  # token key → what it asks to bridge
        self._per_domain: Counter[int] = Counter()
        self._calls: Counter[int] = Counter()  # service calls waiting, by world domain
        self._ignored: set[int] = set()  # domains over a limit, told once
        self._mirrors: dict[Route, _Mirror] = {}  # the bridge thread's alone
        self._nodes: dict[int, tuple[str, Any, int]] = {}  # domain → namespace, node token, node id
        self._ids = itertools.count(1)
        self._wake = threading.Event()
        self._closed = False
        self._graph: Any = self.session.liveliness().declare_subscriber(
            f"{ADMIN_SPACE}/**", self._on_token, history=True
        )
        self._thread = threading.Thread(target=self._run, name="domain-bridge", daemon=True)
        self._thread.start()

    # -- what callers change ----------------------------------------------------------------
    def set_world(self, domain_id: int, name: str) -> None:
        """World ``name`` runs in ``domain_id``: show it as ``/<name>``."""
        if domain_id == self.class_domain:
            raise ValueError("a world cannot share the class's own domain")
        with self._lock:
            self._worlds[domain_id] = name
        self._wake.set()

    def drop_world(self, domain_id: int) -> None:
        with self._lock:
            self._worlds.pop(domain_id, None)
        self._wake.set()

    def routes(self) -> dict[str, list[str]]:
        """What is bridged now, by world: ``out /ada/uav/sensors/gps`` (watched: ``out*``), ``in ...``
        or ``srv /ada/rocket/reset``."""
        out: dict[str, list[str]] = {}
        for mirror in list(self._mirrors.values()):
            kind = mirror.route.kind
            way = (
                "srv"
                if kind is EntityKind.SERVICE
                else "in"
                if kind is EntityKind.SUBSCRIPTION
                else "out*"
                if mirror.world_side
                else "out"
            )
            out.setdefault(mirror.namespace.strip("/"), []).append(f"{way} {mirror.token.topic}")
        return {world: sorted(names) for world, names in sorted(out.items())}

    def refused_names(self) -> dict[str, int]:
        """Entities ignored for their names, by world (``domain <d>`` where no world is known)."""
        with self._lock:
            worlds = dict(self._worlds)
            counts = dict(self.stats.bad_names)
        return {worlds.get(d, f"domain {d}"): n for d, n in sorted(counts.items())}

    def close(self) -> None:
        self._closed = True
        self._wake.set()
        self._thread.join(timeout=10)
        self._graph.undeclare()
        for mirror in list(self._mirrors.values()):
            self._undeclare(mirror)
        self._mirrors.clear()
        for _ns, handle, _id in self._nodes.values():
            handle.undeclare()
        self._nodes.clear()

    # -- Zenoh's threads: record, wake ------------------------------------------------------
    def _on_token(self, sample: zenoh.Sample) -> None:
        key = str(sample.key_expr)
        if sample.kind != zenoh.SampleKind.PUT:
            with self._lock:
                gone = self._endpoints.pop(key, None)
                if gone is not None:
                    self._per_domain[gone[0].domain_id] -= 1
            if gone is not None:
                self._wake.set()
            return
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
            return
        if not (
            is_fully_qualified(token.topic) and _PLAIN.match(token.dds_type) and _PLAIN.match(token.type_hash)
        ):
            with self._lock:
                self.stats.bad_names[token.domain_id] += 1
            return
        route = Route(token.domain_id, token.kind, token.topic, token.dds_type, token.type_hash)
        with self._lock:
            if key in self._endpoints:
                return
            if self._per_domain[route.domain_id] >= MAX_TOKENS_PER_DOMAIN:
                self._tell_once(route.domain_id, f"more than {MAX_TOKENS_PER_DOMAIN} graph tokens")
                return
            self._endpoints[key] = (route, token.qos)
            self._per_domain[route.domain_id] += 1
        self._wake.set()

    def _on_matching(self, mirror: _Mirror, status: Any) -> None:
        mirror.matching = bool(status.matching)
        self._wake.set()

    def _tell_once(self, domain_id: int, why: str) -> None:
        if domain_id not in self._ignored:
            self._ignored.add(domain_id)
            log.warning("ROS domain %d: %s; the rest of that world is not bridged", domain_id, why)

    # -- samples, on Zenoh's threads ----------------------------------------------------------
    def _forward(self, mirror: _Mirror, sample: zenoh.Sample) -> None:
        raw = sample.attachment
        source = raw.to_bytes() if raw is not None else b""
        target = mirror.class_side if mirror.route.kind is EntityKind.PUBLISHER else mirror.world_side
        if len(source) != ATTACHMENT_BYTES or source[16] != GID_BYTES or target is None:
            self.stats.dropped += 1  # not rmw_zenoh's attachment: dropped, as rmw_zenoh drops it
            return
        # rmw_zenoh's attachment with the bridge's sequence number and GID, the source's timestamp.
        attachment = _SEQUENCE.pack(next(mirror.seq)) + source[8:16] + mirror.tail
        try:
            target.put(sample.payload, attachment=attachment)
        except (zenoh.ZError, RuntimeError):  # undeclared while this sample was on its way
            self.stats.dropped += 1
            return
        if mirror.route.kind is EntityKind.PUBLISHER:
            self.stats.out += 1
        else:
            self.stats.into += 1

    # -- service calls, on Zenoh's threads -----------------------------------------------------
    def _call(self, mirror: _Mirror, query: Any) -> None:  # zenoh.Query; its drop() is untyped
        """A call to ``/<world>/<service>`` in the class domain: the same request goes to the world's
        server, and each reply goes back under the caller's own sequence number and GID."""
        raw = query.attachment
        source = raw.to_bytes() if raw is not None else b""
        domain_id = mirror.route.domain_id
        key = data_key(
            self.class_domain, mirror.token.topic or "", mirror.route.dds_type, mirror.route.type_hash
        )
        why = ""
        if str(query.key_expr) != key:  # a pattern (0/**) would call every world's servers at once
            why = f"a call names one service, not a pattern: {query.key_expr}"
        elif len(source) != ATTACHMENT_BYTES or source[16] != GID_BYTES or query.payload is None:
            why = "a request without rmw_zenoh's attachment"
        else:
            with self._lock:
                if self._calls[domain_id] >= MAX_CALLS_PER_WORLD:
                    why = f"more than {MAX_CALLS_PER_WORLD} calls are waiting on {mirror.namespace}"
                else:
                    self._calls[domain_id] += 1
        if why:
            self.stats.refused += 1
            query.reply_err(why.encode())
            query.drop()
            return
        caller_seq, caller_gid = source[:8], source[16:]

        def on_reply(reply: zenoh.Reply) -> None:
            if reply.ok is None:
                query.reply_err(reply.err.payload if reply.err is not None else b"the world failed")
                return
            got = reply.ok.attachment
            answer = got.to_bytes() if got is not None else b""
            stamp = answer[8:16] if len(answer) == ATTACHMENT_BYTES else _SEQUENCE.pack(time.time_ns())
            query.reply(key, reply.ok.payload, attachment=caller_seq + stamp + caller_gid)
            self.stats.calls += 1

        def finished() -> None:  # every reply is in, or the call timed out: the caller's call ends
            with self._lock:
                self._calls[domain_id] -= 1
            query.drop()

        attachment = _SEQUENCE.pack(next(mirror.seq)) + source[8:16] + mirror.tail
        world_key = data_key(domain_id, mirror.route.topic, mirror.route.dds_type, mirror.route.type_hash)
        try:
            self.session.get(
                world_key, zenoh.handlers.Callback(on_reply, finished),
                target=zenoh.QueryTarget.ALL_COMPLETE, consolidation=zenoh.ConsolidationMode.NONE,
                payload=query.payload, attachment=attachment, timeout=CALL_TIMEOUT_S,
                allowed_destination=zenoh.Locality.REMOTE,
            )  # fmt: skip
        except (zenoh.ZError, RuntimeError):  # the session is closing
            self.stats.refused += 1
            finished()

    # -- the bridge's thread: declare what the graph asks for ----------------------------------
    def _run(self) -> None:
        while True:
            self._wake.wait()
            self._wake.clear()
            if self._closed:
                return
            try:
                self._reconcile()
            except Exception:  # one bad round must not end the bridge
                log.exception("bridging the worlds into the class domain failed; trying again")
                time.sleep(0.5)
                self._wake.set()

    def _wanted(self) -> dict[Route, tuple[str, QoS]]:
        with self._lock:
            worlds = dict(self._worlds)
            endpoints = list(self._endpoints.values())
        wanted: dict[Route, tuple[str, QoS]] = {}
        per_world: Counter[int] = Counter()
        for route, qos in endpoints:
            world = worlds.get(route.domain_id)
            if world is None or route in wanted:
                continue
            if per_world[route.domain_id] >= MAX_ROUTES_PER_WORLD:
                self._tell_once(route.domain_id, f"more than {MAX_ROUTES_PER_WORLD} topics")
                continue
            per_world[route.domain_id] += 1
            wanted[route] = (f"/{world}", qos)
        return wanted

    def _reconcile(self) -> None:
        wanted = self._wanted()
        for route, mirror in list(self._mirrors.items()):
            if route not in wanted or wanted[route][0] != mirror.namespace:
                self._undeclare(self._mirrors.pop(route))
        needed = {(route.domain_id, namespace) for route, (namespace, _qos) in wanted.items()}
        for domain_id, (namespace, handle, _id) in list(self._nodes.items()):
            if (domain_id, namespace) not in needed:
                handle.undeclare()
                del self._nodes[domain_id]
        for route, (namespace, qos) in wanted.items():
            if self._closed:
                return
            if route not in self._mirrors:
                self._mirrors[route] = self._declare(route, namespace, qos)
        for mirror in self._mirrors.values():  # a world's topic crosses out only while watched
            if mirror.route.kind is not EntityKind.PUBLISHER:
                continue
            if mirror.matching and mirror.world_side is None:
                mirror.world_side = self.session.declare_subscriber(
                    data_key(mirror.route.domain_id, mirror.route.topic, mirror.route.dds_type,
                             mirror.route.type_hash),
                    lambda sample, m=mirror: self._forward(m, sample),
                    allowed_origin=zenoh.Locality.REMOTE,
                )  # fmt: skip
            elif not mirror.matching and mirror.world_side is not None:
                mirror.world_side.undeclare()
                mirror.world_side = None

    def _node(self, domain_id: int, namespace: str) -> int:
        known = self._nodes.get(domain_id)
        if known is not None and known[0] == namespace:
            return known[2]
        if known is not None:
            known[1].undeclare()
        node_id = next(self._ids)
        token = EntityToken(
            self.class_domain, self.zid, node_id, node_id, EntityKind.NODE, namespace, NODE_NAME
        )
        self._nodes[domain_id] = (namespace, self.session.liveliness().declare_token(token.key), node_id)
        return node_id

    def _declare(self, route: Route, namespace: str, qos: QoS) -> _Mirror:
        node_id = self._node(route.domain_id, namespace)
        token = EntityToken(
            self.class_domain, self.zid, node_id, next(self._ids), route.kind, namespace, NODE_NAME,
            topic=namespace + route.topic, dds_type=route.dds_type, type_hash=route.type_hash, qos=qos,
        )  # fmt: skip
        class_key = data_key(self.class_domain, namespace + route.topic, route.dds_type, route.type_hash)
        world_key = data_key(route.domain_id, route.topic, route.dds_type, route.type_hash)
        if route.kind is EntityKind.PUBLISHER:
            # REMOTE: only a subscriber outside this session counts as a watcher.
            zpub = self.session.declare_publisher(
                class_key, congestion_control=zenoh.CongestionControl.DROP,
                allowed_destination=zenoh.Locality.REMOTE,
            )  # fmt: skip
            mirror = _Mirror(route, namespace, token, None, zpub)
            mirror.listener = zpub.declare_matching_listener(
                lambda status, m=mirror: self._on_matching(m, status)
            )
            mirror.matching = bool(zpub.matching_status.matching)  # after the listener: no change missed
        elif route.kind is EntityKind.SERVICE:
            mirror = _Mirror(route, namespace, token, None, None)
            mirror.class_side = self.session.declare_queryable(
                class_key,
                lambda query, m=mirror: self._call(m, query),
                complete=True,
                allowed_origin=zenoh.Locality.REMOTE,
            )
        else:
            zpub = self.session.declare_publisher(
                world_key, congestion_control=zenoh.CongestionControl.DROP,
                allowed_destination=zenoh.Locality.REMOTE,
            )  # fmt: skip
            mirror = _Mirror(route, namespace, token, None, None, world_side=zpub)
            mirror.class_side = self.session.declare_subscriber(
                class_key,
                lambda sample, m=mirror: self._forward(m, sample),
                allowed_origin=zenoh.Locality.REMOTE,
            )
        mirror.handle = self.session.liveliness().declare_token(token.key)
        return mirror

    @staticmethod
    def _undeclare(mirror: _Mirror) -> None:
        for entity in (mirror.listener, mirror.world_side, mirror.class_side, mirror.handle):
            if entity is not None:
                entity.undeclare()
        mirror.world_side = None
