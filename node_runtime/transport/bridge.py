"""One bus, two reaches: the bus's nodes and endpoints declared on Zenoh as rmw_zenoh declares them.

- Every node and endpoint gets its liveliness token, so other processes (and a real ROS 2 with
  rmw_zenoh) see it in their graph; every remote token lands in the RemoteGraph.
- A publisher also puts on Zenoh, but only while something outside this process subscribes
  (publishing.py).
- One Zenoh subscriber per topic with local subscriptions takes remote samples only (its own
  process's are delivered locally already); each goes through the bounded Inbox to the executor's
  thread, where it is decoded and delivered with the same keep-last semantics.
- A service server answers Zenoh queries; a client with no local server queries Zenoh
  (service_link.py).
Nothing here runs on Zenoh's threads but Inbox puts; everything else runs on the executor's.
"""

from __future__ import annotations

import itertools
import logging
import threading
from dataclasses import dataclass, field
from typing import Any

import zenoh
import zenoh.ext

from node_runtime.bus import (
    Bus,
    Clock,
    Future,
    Node,
    Publisher,
    ServiceClient,
    ServiceServer,
    Subscription,
    SystemClock,
)
from node_runtime.limits import RateLimit
from node_runtime.msgs import Message, Service
from node_runtime.msgs.wire import WireError, dds_type_name, type_hash
from node_runtime.transport.attachment import Attachment
from node_runtime.transport.cdr import decode
from node_runtime.transport.inbox import Inbox
from node_runtime.transport.keys import TRANSIENT_LOCAL, EntityKind, EntityToken, data_key, liveliness_prefix
from node_runtime.transport.publishing import RemotePublisher, Stats, declare_remote_publisher, wire_qos
from node_runtime.transport.remote_graph import RemoteGraph
from node_runtime.transport.service_link import ServiceLink

log = logging.getLogger("transport")
MAX_EVENTS_PER_POLL = 256  # graph tokens, service queries and replies handled in one executor pass


@dataclass
class _Entity:
    token: EntityToken
    handle: Any  # the declared liveliness token
    extra: list[Any] = field(default_factory=list)  # declared Zenoh objects to undeclare with it


class ZenohBridge:
    """Joins a bus to a Zenoh session (the app's router, or a node process's peer session)."""

    def __init__(
        self,
        bus: Bus,
        session: zenoh.Session,
        domain_id: int = 0,
        *,
        enclave: str = "/",
        samples_hz: float | None = None,
        clock: Clock | None = None,
    ) -> None:
        self.bus = bus
        self.session: Any = session
        self.domain_id = domain_id
        self.enclave = enclave
        self.zid = str(session.zid())
        self.stats = Stats()
        self.remote = RemoteGraph(self.zid, domain_id)
        self.inbox = Inbox(bus.wake_threadsafe)
        # Samples from other processes, at most samples_hz a second (bursts of one second's): a
        # class world's flood is dropped here, on Zenoh's thread, before it costs a decode. The
        # bucket is taken from several Zenoh threads: hence its lock.
        self._budget = (
            RateLimit(clock or SystemClock(), samples_hz, max(1, int(samples_hz)))
            if samples_hz is not None
            else None
        )
        self._budget_lock = threading.Lock()
        self._ids = itertools.count(1)
        self._node_ids: dict[int, int] = {}
        self._entities: dict[int, _Entity] = {}
        self._topic_subscribers: dict[str, Any] = {}
        self._history_topics: set[str] = set()  # those whose subscriber asks publishers for history
        self._keep: dict[str, int] = {}  # samples an inbox queue keeps per topic: its deepest subscription
        # This process's publishers: their samples reach its subscriptions on the bus already, so
        # one that comes back over Zenoh (a late subscription's history query, which a publisher's
        # cache in this very session answers) is dropped, not delivered twice.
        self._own_gids: set[bytes] = set()
        self._closed = False
        self.services = ServiceLink(bus, session, self.inbox, self.remote, self.stats)
        bus.observers.append(self)
        bus.pollers.append(self.poll)
        bus.remote_services = self
        bus.remote_topics = self.remote
        for node in list(bus.nodes):
            self.node_added(node)
            for endpoint in [*node.publishers, *node.subscriptions, *node.services, *node.clients]:
                self.endpoint_added(endpoint)
        self._graph_sub: Any = session.liveliness().declare_subscriber(
            liveliness_prefix(domain_id), self._on_token, history=True
        )

    def settle_graph(self, timeout_s: float = 1.0) -> None:
        """Fill the remote graph with what exists now (one liveliness query), so that a node made
        right after can tell whether its name is taken. Blocks up to ``timeout_s``."""
        for reply in self.session.liveliness().get(liveliness_prefix(self.domain_id), timeout=timeout_s):
            if reply.ok is not None:
                self.remote.apply(str(reply.ok.key_expr), True)

    # -- graph observer (executor's thread) ----------------------------------------------------
    def _node_token(self, node: Node, node_id: int) -> EntityToken:
        return EntityToken(
            self.domain_id,
            self.zid,
            node_id,
            node_id,
            EntityKind.NODE,
            node.get_namespace(),
            node.get_name(),
            enclave=self.enclave,
        )

    def node_added(self, node: Node) -> None:
        if self._closed or id(node) in self._node_ids:
            return
        node_id = next(self._ids)
        self._node_ids[id(node)] = node_id
        token = self._node_token(node, node_id)
        self._entities[id(node)] = _Entity(token, self.session.liveliness().declare_token(token.key))

    def node_removed(self, node: Node) -> None:
        self._undeclare(id(node))
        self._node_ids.pop(id(node), None)

    def _endpoint_token(
        self, node: Node, kind: EntityKind, name: str, type_name: str, depth: int, qos: Any = None
    ) -> EntityToken:
        node_token = self._entities[id(node)].token
        return EntityToken(
            self.domain_id,
            self.zid,
            node_token.node_id,
            next(self._ids),
            kind,
            node_token.namespace,
            node_token.node_name,
            enclave=self.enclave,
            topic=name,
            dds_type=dds_type_name(type_name),
            type_hash=type_hash(type_name),
            qos=wire_qos(depth, qos),
        )

    def endpoint_added(self, endpoint: object) -> None:
        if self._closed:
            return
        # Messages go through cdr.py, which generates no code: nothing to prepare before a
        # Ctrl-C can land (rosbags' generated code once had to be built here).
        if isinstance(endpoint, Publisher):
            self._add_publisher(endpoint)
        elif isinstance(endpoint, Subscription):
            self._add_subscription(endpoint)
        elif isinstance(endpoint, ServiceServer):
            self._add_server(endpoint)
        elif isinstance(endpoint, ServiceClient):
            token = self._endpoint_token(
                endpoint.node, EntityKind.CLIENT, endpoint.channel.name, endpoint.srv_type.TYPE, 10
            )
            self._declare(endpoint, token)

    def endpoint_removed(self, endpoint: object) -> None:
        if isinstance(endpoint, Publisher):
            endpoint.remote = None
            entity = self._entities.get(id(endpoint))
            if entity is not None:
                self._own_gids.discard(entity.token.gid)
        elif isinstance(endpoint, ServiceClient):
            self.services.forget(endpoint)
        self._undeclare(id(endpoint))
        if isinstance(endpoint, Subscription):
            topic = endpoint.topic
            if not any(s is not endpoint and not s.destroyed for s in topic.subscriptions):
                subscriber = self._topic_subscribers.pop(topic.name, None)
                self._history_topics.discard(topic.name)
                if subscriber is not None:
                    subscriber.undeclare()
                self._keep.pop(topic.name, None)
                self.inbox.forget(topic.name)

    def _declare(self, endpoint: object, token: EntityToken, *extra: Any) -> None:
        self._entities[id(endpoint)] = _Entity(
            token, self.session.liveliness().declare_token(token.key), list(extra)
        )

    def _undeclare(self, key: int) -> None:
        entity = self._entities.pop(key, None)
        if entity is None:
            return
        for handle in entity.extra:
            if isinstance(handle, RemotePublisher):
                handle.close()
            else:
                handle.undeclare()
        entity.handle.undeclare()

    def _add_publisher(self, pub: Publisher) -> None:
        token = self._endpoint_token(
            pub.node, EntityKind.PUBLISHER, pub.topic_name, pub.msg_type.TYPE, pub.depth, pub.qos
        )
        key = data_key(self.domain_id, pub.topic_name, token.dds_type or "", token.type_hash or "")
        assert token.qos is not None
        remote = declare_remote_publisher(self.session, key, token.qos, pub.depth, token.gid, self.stats)
        pub.remote = remote
        self._own_gids.add(token.gid)
        self._declare(pub, token, remote)

    def _add_subscription(self, sub: Subscription) -> None:
        token = self._endpoint_token(
            sub.node, EntityKind.SUBSCRIPTION, sub.topic_name, sub.msg_type.TYPE, sub.depth, sub.qos
        )
        self._declare(sub, token)
        name = sub.topic_name
        self._keep[name] = max(self._keep.get(name, 1), sub.depth)
        key = data_key(self.domain_id, name, token.dds_type or "", token.type_hash or "")
        assert token.qos is not None
        if token.qos.durability == TRANSIENT_LOCAL and name not in self._history_topics:
            # As rmw_zenoh: an advanced subscriber that asks late-found publishers' caches for history.
            old = self._topic_subscribers.pop(name, None)

            def on_sample(sample: zenoh.Sample, name: str = name) -> None:
                self._on_sample(name, sample)

            self._topic_subscribers[name] = zenoh.ext.declare_advanced_subscriber(
                self.session,
                key,
                on_sample,
                allowed_origin=zenoh.Locality.REMOTE,
                history=zenoh.ext.HistoryConfig(detect_late_publishers=True, max_samples=sub.depth),
                subscriber_detection=True,
            )
            self._history_topics.add(name)
            if old is not None:
                old.undeclare()
        elif name not in self._topic_subscribers:
            self._topic_subscribers[name] = self.session.declare_subscriber(
                key,
                lambda sample, name=name: self._on_sample(name, sample),
                allowed_origin=zenoh.Locality.REMOTE,
            )

    def _add_server(self, server: ServiceServer) -> None:
        token = self._endpoint_token(
            server.node, EntityKind.SERVICE, server.channel.name, server.srv_type.TYPE, 10
        )
        key = data_key(self.domain_id, server.channel.name, token.dds_type or "", token.type_hash or "")
        self._declare(server, token, self.services.serve(server, key))

    # -- Zenoh's threads: only hand over -------------------------------------------------------
    def _on_sample(self, topic: str, sample: zenoh.Sample) -> None:
        if self._budget is not None:
            with self._budget_lock:
                taken = self._budget.take()
            if not taken:
                self.stats.over_rate += 1
                return
        attachment = sample.attachment
        raw = attachment.to_bytes() if attachment is not None else None
        att = Attachment.unpack(raw)
        if att is None:
            self.stats.no_attachment += 1
            return
        if att.gid in self._own_gids:  # a set read from Zenoh's thread: one membership test
            self.stats.echoes += 1
            return
        self.inbox.put_sample(
            topic, (sample.payload.to_bytes(), att.source_timestamp_ns, att.gid), self._keep.get(topic, 1)
        )

    def _on_token(self, sample: zenoh.Sample) -> None:
        self.inbox.post(("token", str(sample.key_expr), sample.kind == zenoh.SampleKind.PUT))

    # -- the executor's pass -------------------------------------------------------------------
    def poll(self) -> None:
        """Zenoh's hand-ins, on the executor's thread: at most ``MAX_EVENTS_PER_POLL`` events a
        pass (a class's burst of joins brings hundreds of tokens at once; the rest wait for the
        next pass, which is asked for, so one pass never holds the loop for all of them), then
        every sample taken (each topic's are bounded by its keep-last depth)."""
        events, samples = self.inbox.take(MAX_EVENTS_PER_POLL)
        if len(events) == MAX_EVENTS_PER_POLL and self.inbox.left():
            self.bus.wake_threadsafe()
        graph_changed = False
        for event in events:
            kind = event[0]
            if kind == "token":
                changed = self.remote.apply(event[1], event[2])
                graph_changed |= changed
                if changed and event[2]:
                    self._warn_on_same_name(event[1])
            elif kind == "query":
                self.services.answer(event[1], event[2])
            elif kind == "reply":
                self.services.complete(event[1], event[2], event[3])
        if graph_changed:
            self.bus.graph_changed()
        for name, payloads in samples.items():
            topic = self.bus.topics.get(name)
            if topic is None:
                continue
            for payload, stamp_ns, gid in payloads:
                try:
                    msg = decode(topic.msg_type, payload)
                except WireError as exc:
                    self.stats.undecodable += 1
                    log.debug("dropped a sample on %s: %s", name, exc)
                    continue
                self.stats.received += 1
                published_s = stamp_ns / 1e9 if stamp_ns > 0 else None
                # just decoded: nobody else has it; the GID names its publisher (RemoteGraph.publisher)
                topic.deliver(msg, published_s, handed_over=True, source=gid)

    def _warn_on_same_name(self, key: str) -> None:
        """A node of another process took the name of one of ours: say so, as ROS does."""
        token = EntityToken.parse(key)
        if token is None or token.kind is not EntityKind.NODE:
            return
        for node in self.bus.nodes:
            if node.fully_qualified_name == token.node_fqn and not node.get_name().startswith("_"):
                node.get_logger().warning(
                    f"a node named {token.node_fqn} already exists in the graph (another process): ROS "
                    "allows this, but tools and logs will mix the two up"
                )

    # -- services (the bus's RemoteServices) --------------------------------------------------
    def has_server(self, name: str, srv_type: type[Service]) -> bool:
        return self.services.has_server(name, srv_type)

    def gid_of(self, endpoint: object) -> bytes | None:
        """The GID of a node's or endpoint's token (service events name a client by it)."""
        entity = self._entities.get(id(endpoint))
        return None if entity is None else entity.token.gid

    def call(self, client: ServiceClient, request: Message, future: Future[Message]) -> None:
        entity = self._entities.get(id(client))
        if entity is not None:
            self.services.call(client, entity.token, request, future)

    # -- life ----------------------------------------------------------------------------------
    def close(self) -> None:
        """Undeclare everything (other processes see these nodes go); the session stays open."""
        if self._closed:
            return
        self._closed = True
        for node in list(self.bus.nodes):
            for endpoint in [*node.publishers, *node.subscriptions, *node.services, *node.clients]:
                self.endpoint_removed(endpoint)
            self.node_removed(node)
        for key in list(self._entities):
            self._undeclare(key)
        for subscriber in self._topic_subscribers.values():
            subscriber.undeclare()
        self._topic_subscribers.clear()
        self._graph_sub.undeclare()
        if self in self.bus.observers:
            self.bus.observers.remove(self)
        if self.poll in self.bus.pollers:
            self.bus.pollers.remove(self.poll)
        if self.bus.remote_services is self:
            self.bus.remote_services = None
        if self.bus.remote_topics is self.remote:
            self.bus.remote_topics = None
