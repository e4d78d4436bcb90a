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
- A world's entity is bridged only under a fully qualified ROS name and a type and hash of plain
  name characters; any other is ignored and counted, by world (``refused_names``). Which routes are
  wanted: domain_routes.py.
- Samples and requests cross as bytes, so no type needs to be known; each gets a new rmw_zenoh
  attachment, and one without an attachment is dropped, as rmw_zenoh drops it (domain_crossing.py).
- Declarations happen on the bridge's own thread, which brings what is declared in line with what
  the graph asks for; Zenoh's threads only record a change or pass a sample on (congestion
  control DROP: a slow watcher never holds anything up). What one world's graph can make the
  bridge declare is bounded.
- The bridge's thread shares the interpreter with the worlds' event loop, so its work is kept
  small and in slices: a change looks at the worlds it touched only (a student's node joining
  one world costs that world's routes, not the whole class's: with 30 worlds of about 190 routes
  each, going over every route cost the thread about 35 ms of CPU per node joined, holding the
  interpreter, against about 1 ms now), a watcher's coming or going looks at that mirror only,
  and after every ``SLICE`` declarations the thread pauses ``SLICE_PAUSE_S`` so that the loop
  (the students' calls, the worlds' ticks) runs between them.
"""

from __future__ import annotations

import itertools
import logging
import threading
import time
from collections import deque
from typing import Any

import zenoh

from node_runtime.transport.domain_crossing import Crossing, Mirror
from node_runtime.transport.domain_routes import BridgeStats, Route, RouteTable
from node_runtime.transport.keys import ADMIN_SPACE, EntityKind, EntityToken, QoS, data_key

log = logging.getLogger("transport.domain_bridge")
NODE_NAME = "domain_bridge"
SLICE = 16  # declarations (or undeclarations) in a row before the bridge's thread pauses
SLICE_PAUSE_S = 0.002  # long enough for the loop's thread to take the interpreter and run a while


class DomainBridge:
    """Mirrors the worlds ``set_world`` names into ``class_domain`` until ``close``."""

    def __init__(self, session: zenoh.Session, class_domain: int, stats: BridgeStats | None = None) -> None:
        self.session: Any = session
        self.class_domain = class_domain
        self.zid = str(session.zid())
        self.stats = stats if stats is not None else BridgeStats()  # the caller's, to outlive this bridge
        self._table = RouteTable(class_domain, self.zid, self.stats)
        self._crossing = Crossing(self.session, class_domain, self.stats)
        self._mirrors: dict[Route, Mirror] = {}  # the bridge thread's alone
        self._in_domain: dict[int, dict[Route, Mirror]] = {}  # the same, by world's domain
        self._nodes: dict[int, tuple[str, Any, int]] = {}  # domain → namespace, node token, node id
        self._ids = itertools.count(1)
        self._wake = threading.Event()
        self._watch_changed: deque[Mirror] = deque()  # mirrors whose watchers came or went (Zenoh's threads)
        self._done_in_slice = 0
        # Counts: reconciling passes, the routes they looked at, and the pauses between slices.
        self.passes = self.routes_looked_at = self.pauses = 0
        self._closed = False
        self._graph: Any = self.session.liveliness().declare_subscriber(
            f"{ADMIN_SPACE}/**", self._on_token, history=True
        )
        self._thread = threading.Thread(target=self._run, name="domain-bridge", daemon=True)
        self._thread.start()

    # -- what callers change ----------------------------------------------------------------
    def set_world(self, domain_id: int, name: str) -> None:
        """World ``name`` runs in ``domain_id``: show it as ``/<name>``."""
        self._table.set_world(domain_id, name)
        self._wake.set()

    def drop_world(self, domain_id: int) -> None:
        self._table.drop_world(domain_id)
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
        return self._table.refused_names()

    def close(self) -> None:
        self._closed = True
        self._wake.set()
        self._thread.join(timeout=10)
        self._graph.undeclare()
        for mirror in list(self._mirrors.values()):
            self._undeclare(mirror)
        self._mirrors.clear()
        self._in_domain.clear()
        for _ns, handle, _id in self._nodes.values():
            handle.undeclare()
        self._nodes.clear()

    # -- Zenoh's threads: record, wake ------------------------------------------------------
    def _on_token(self, sample: zenoh.Sample) -> None:
        if self._table.record(sample):
            self._wake.set()

    def _on_matching(self, mirror: Mirror, status: Any) -> None:
        mirror.matching = bool(status.matching)
        self._watch_changed.append(mirror)
        self._wake.set()

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

    def _reconcile(self) -> None:
        """One pass: the worlds whose tokens changed since the last, then the mirrors whose
        watchers came or went."""
        self.passes += 1
        self._done_in_slice = 0
        changed = self._table.take_changed()
        for i, domain_id in enumerate(changed):
            if self._closed:
                return
            try:
                self._reconcile_world(domain_id)
            except Exception:
                self._table.touch(*changed[i:])  # looked at again in the next pass
                raise
        while self._watch_changed and not self._closed:
            mirror = self._watch_changed.popleft()
            try:
                self._follow_watchers(mirror)
            except Exception:
                self._watch_changed.appendleft(mirror)  # followed again in the next pass
                raise

    def _reconcile_world(self, domain_id: int) -> None:
        """Bring one world's mirrors in line with its routes."""
        namespace, wanted = self._table.wanted_in(domain_id)
        mirrors = self._in_domain.setdefault(domain_id, {})
        self.routes_looked_at += len(wanted) + len(mirrors)
        for route, mirror in list(mirrors.items()):
            if route not in wanted or mirror.namespace != namespace:
                self._undeclare(mirrors.pop(route))
                del self._mirrors[route]
                self._slice_done()
        known = self._nodes.get(domain_id)
        if known is not None and (not wanted or known[0] != namespace):
            known[1].undeclare()
            del self._nodes[domain_id]
        for route, qos in wanted.items():
            if self._closed:
                return
            if route in mirrors:
                continue
            assert namespace is not None  # a domain with no world wants nothing
            mirror = self._declare(route, namespace, qos)
            mirrors[route] = self._mirrors[route] = mirror
            self._follow_watchers(mirror)
            self._slice_done()
        if not mirrors:
            del self._in_domain[domain_id]

    def _follow_watchers(self, mirror: Mirror) -> None:
        """A world's topic crosses out only while watched: subscribe in the world while the
        mirror's publisher has a watcher in the class domain, and not otherwise."""
        if mirror.route.kind is not EntityKind.PUBLISHER or self._mirrors.get(mirror.route) is not mirror:
            return  # not a topic going out, or a mirror undeclared since
        if mirror.matching and mirror.world_side is None:
            mirror.world_side = self.session.declare_subscriber(
                data_key(
                    mirror.route.domain_id,
                    mirror.route.topic,
                    mirror.route.dds_type,
                    mirror.route.type_hash,
                ),
                lambda sample, m=mirror: self._crossing.forward(m, sample),
                allowed_origin=zenoh.Locality.REMOTE,
            )
        elif not mirror.matching and mirror.world_side is not None:
            mirror.world_side.undeclare()
            mirror.world_side = None

    def _slice_done(self) -> None:
        """One more declaration in this slice; a full slice pauses the thread (see SLICE)."""
        self._done_in_slice += 1
        if self._done_in_slice >= SLICE:
            self._done_in_slice = 0
            self.pauses += 1
            time.sleep(SLICE_PAUSE_S)

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

    def _declare(self, route: Route, namespace: str, qos: QoS) -> Mirror:
        node_id = self._node(route.domain_id, namespace)
        token = EntityToken(
            self.class_domain,
            self.zid,
            node_id,
            next(self._ids),
            route.kind,
            namespace,
            NODE_NAME,
            topic=namespace + route.topic,
            dds_type=route.dds_type,
            type_hash=route.type_hash,
            qos=qos,
        )
        class_key = data_key(self.class_domain, namespace + route.topic, route.dds_type, route.type_hash)
        world_key = data_key(route.domain_id, route.topic, route.dds_type, route.type_hash)
        if route.kind is EntityKind.PUBLISHER:
            # REMOTE: only a subscriber outside this session counts as a watcher.
            zpub = self.session.declare_publisher(
                class_key,
                congestion_control=zenoh.CongestionControl.DROP,
                allowed_destination=zenoh.Locality.REMOTE,
            )
            mirror = Mirror(route, namespace, token, None, zpub)
            mirror.listener = zpub.declare_matching_listener(
                lambda status, m=mirror: self._on_matching(m, status)
            )
            mirror.matching = bool(zpub.matching_status.matching)  # after the listener: no change missed
        elif route.kind is EntityKind.SERVICE:
            mirror = Mirror(route, namespace, token, None, None)
            mirror.class_side = self.session.declare_queryable(
                class_key,
                lambda query, m=mirror: self._crossing.call(m, query),
                complete=True,
                allowed_origin=zenoh.Locality.REMOTE,
            )
        else:
            zpub = self.session.declare_publisher(
                world_key,
                congestion_control=zenoh.CongestionControl.DROP,
                allowed_destination=zenoh.Locality.REMOTE,
            )
            mirror = Mirror(route, namespace, token, None, None, world_side=zpub)
            mirror.class_side = self.session.declare_subscriber(
                class_key,
                lambda sample, m=mirror: self._crossing.forward(m, sample),
                allowed_origin=zenoh.Locality.REMOTE,
            )
        mirror.handle = self.session.liveliness().declare_token(token.key)
        return mirror

    @staticmethod
    def _undeclare(mirror: Mirror) -> None:
        for entity in (mirror.listener, mirror.world_side, mirror.class_side, mirror.handle):
            if entity is not None:
                entity.undeclare()
        mirror.world_side = None
