"""One bus, two reaches: the bus's nodes and endpoints declared on Zenoh as rmw_zenoh declares them.

- Every node and endpoint gets its liveliness token, so other processes (and a real ROS 2 with
  rmw_zenoh) see it in their graph; every remote token lands in the RemoteGraph.
- A publisher also puts on Zenoh, but only while something outside this process subscribes
  (Zenoh's matching status): in-process nodes keep the fast path with no serialization. Puts use
  congestion control DROP, so a slow peer never holds up the sim loop.
- One Zenoh subscriber per topic with local subscriptions takes remote samples only (its own
  process's are delivered locally already); each goes through the bounded Inbox to the executor's
  thread, where it is decoded and delivered with the same keep-last semantics.
- A service server answers Zenoh queries; a client with no local server queries Zenoh, the
  reply matched to its call by the attachment's sequence number and GID.
Nothing here runs on Zenoh's threads but Inbox puts; everything else runs on the executor's.
"""

from __future__ import annotations

import itertools
import logging
import threading
import time
from dataclasses import dataclass, field
from typing import Any, cast

import zenoh
import zenoh.ext

from ..bus import Bus, Clock, Future, Node, Publisher, ServiceClient, ServiceServer, Subscription, SystemClock
from ..bus.services import PendingCall
from ..limits import RateLimit
from ..msgs import Message, Service
from ..msgs.wire import WireError, dds_type_name, deserialize, prepare, serialize, type_hash
from .attachment import Attachment
from .inbox import Inbox
from .keys import (
    BEST_EFFORT,
    TRANSIENT_LOCAL,
    EntityKind,
    EntityToken,
    QoS,
    data_key,
    keep_last,
    liveliness_prefix,
)
from .remote_graph import RemoteGraph

log = logging.getLogger("transport")
QUERY_TIMEOUT_S = 3600.0  # a ROS 2 call waits as long as it takes; Zenoh needs some bound
SERVICE_QOS = keep_last(10)


@dataclass
class Stats:
    sent: int = 0
    received: int = 0
    no_attachment: int = 0  # dropped, as rmw_zenoh drops them
    over_rate: int = 0  # dropped: more samples a second than the bridge takes (a class world's flood)
    undecodable: int = 0
    queries: int = 0
    replies: int = 0


def _wire_qos(depth: int, qos: Any) -> QoS:
    """The token's QoS: keep-last ``depth``, and the profile's reliability and durability (rmw's
    enum values; 0, the system's default, is rmw_zenoh's: reliable, volatile)."""
    return keep_last(
        depth,
        best_effort=getattr(qos, "reliability", 0) == BEST_EFFORT,
        transient_local=getattr(qos, "durability", 0) == TRANSIENT_LOCAL,
    )


class _RemotePublisher:
    """The Zenoh side of one bus publisher: its own GID and sequence numbers from 1."""

    def __init__(self, zpub: zenoh.Publisher | zenoh.ext.AdvancedPublisher, gid: bytes, stats: Stats) -> None:
        self.zpub: Any = cast(Any, zpub)  # its stubs call matching_status a bool; it is a MatchingStatus
        self.gid = gid
        self.seq = 0
        self.stats = stats
        self.listener: Any = None
        if isinstance(zpub, zenoh.Publisher):
            self.matching = bool(self.zpub.matching_status.matching)
            self.listener = zpub.declare_matching_listener(self._on_matching)
        else:  # a transient-local publisher's cache keeps samples for subscribers still to come
            self.matching = True

    def _on_matching(self, status: zenoh.MatchingStatus) -> None:  # Zenoh's thread: one attribute
        self.matching = bool(status.matching)

    def put(self, msg: Message) -> None:
        if not self.matching:
            return
        self.seq += 1
        attachment = Attachment(self.seq, time.time_ns(), self.gid).pack()
        self.zpub.put(serialize(msg), attachment=attachment)
        self.stats.sent += 1

    def close(self) -> None:
        if self.listener is not None:
            self.listener.undeclare()
        self.zpub.undeclare()


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
        self._client_seq: dict[int, int] = {}
        self._closed = False
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
            self.domain_id, self.zid, node_id, node_id, EntityKind.NODE, node.get_namespace(), node.get_name(),
            enclave=self.enclave,
        )  # fmt: skip

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
            self.domain_id, self.zid, node_token.node_id, next(self._ids), kind, node_token.namespace,
            node_token.node_name, enclave=self.enclave, topic=name, dds_type=dds_type_name(type_name),
            type_hash=type_hash(type_name), qos=_wire_qos(depth, qos),
        )  # fmt: skip

    def endpoint_added(self, endpoint: object) -> None:
        if self._closed:
            return
        if isinstance(endpoint, Publisher | Subscription):
            prepare(endpoint.msg_type.TYPE)
        elif isinstance(endpoint, ServiceServer | ServiceClient):
            prepare(endpoint.srv_type.Request.TYPE)
            prepare(endpoint.srv_type.Response.TYPE)
        if isinstance(endpoint, Publisher):
            self._add_publisher(endpoint)
        elif isinstance(endpoint, Subscription):
            self._add_subscription(endpoint)
        elif isinstance(endpoint, ServiceServer):
            self._add_server(endpoint)
        elif isinstance(endpoint, ServiceClient):
            token = self._endpoint_token(
                endpoint.node, EntityKind.CLIENT, endpoint.srv_name, endpoint.srv_type.TYPE, 10
            )
            self._declare(endpoint, token)

    def endpoint_removed(self, endpoint: object) -> None:
        if isinstance(endpoint, Publisher):
            endpoint.remote = None
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
            if isinstance(handle, _RemotePublisher):
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
        reliability = (
            zenoh.Reliability.BEST_EFFORT
            if token.qos.reliability == BEST_EFFORT
            else zenoh.Reliability.RELIABLE
        )
        zpub: zenoh.Publisher | zenoh.ext.AdvancedPublisher
        if token.qos.durability == TRANSIENT_LOCAL:
            # As rmw_zenoh: an advanced publisher whose cache answers late subscribers' history queries.
            zpub = zenoh.ext.declare_advanced_publisher(
                self.session, key, congestion_control=zenoh.CongestionControl.DROP, reliability=reliability,
                allowed_destination=zenoh.Locality.REMOTE, cache=zenoh.ext.CacheConfig(max_samples=pub.depth),
                publisher_detection=True,
            )  # fmt: skip
        else:
            # REMOTE: this process's own subscriptions get the message from the bus, and only other
            # processes count as matching (so a topic nobody else wants is never serialized).
            zpub = self.session.declare_publisher(
                key,
                congestion_control=zenoh.CongestionControl.DROP,
                reliability=reliability,
                allowed_destination=zenoh.Locality.REMOTE,
            )
        remote = _RemotePublisher(zpub, token.gid, self.stats)
        pub.remote = remote
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
                self.session, key, on_sample,
                allowed_origin=zenoh.Locality.REMOTE,
                history=zenoh.ext.HistoryConfig(detect_late_publishers=True, max_samples=sub.depth),
                subscriber_detection=True,
            )  # fmt: skip
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
            server.node, EntityKind.SERVICE, server.srv_name, server.srv_type.TYPE, 10
        )
        key = data_key(self.domain_id, server.srv_name, token.dds_type or "", token.type_hash or "")

        def on_query(query: zenoh.Query) -> None:
            self.inbox.post(("query", server, query))

        queryable = self.session.declare_queryable(
            key, on_query, complete=True, allowed_origin=zenoh.Locality.REMOTE
        )
        self._declare(server, token, queryable)

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
        self.inbox.put_sample(
            topic, (sample.payload.to_bytes(), att.source_timestamp_ns), self._keep.get(topic, 1)
        )

    def _on_token(self, sample: zenoh.Sample) -> None:
        self.inbox.post(("token", str(sample.key_expr), sample.kind == zenoh.SampleKind.PUT))

    # -- the executor's pass -------------------------------------------------------------------
    def poll(self) -> None:
        events, samples = self.inbox.take()
        graph_changed = False
        for event in events:
            kind = event[0]
            if kind == "token":
                changed = self.remote.apply(event[1], event[2])
                graph_changed |= changed
                if changed and event[2]:
                    self._warn_on_same_name(event[1])
            elif kind == "query":
                self._answer(event[1], event[2])
            elif kind == "reply":
                self._complete(event[1], event[2], event[3])
        if graph_changed:
            self.bus.graph_changed()
        for name, payloads in samples.items():
            topic = self.bus.topics.get(name)
            if topic is None:
                continue
            for payload, stamp_ns in payloads:
                try:
                    msg = deserialize(topic.msg_type.TYPE, payload)
                except WireError as exc:
                    self.stats.undecodable += 1
                    log.debug("dropped a sample on %s: %s", name, exc)
                    continue
                self.stats.received += 1
                published_s = stamp_ns / 1e9 if stamp_ns > 0 else None
                topic.deliver(msg, published_s, handed_over=True)  # just decoded: nobody else has it

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

    # -- services ------------------------------------------------------------------------------
    def _answer(self, server: ServiceServer, query: Any) -> None:
        self.stats.queries += 1
        raw = query.attachment.to_bytes() if query.attachment is not None else None
        request_att = Attachment.unpack(raw)
        if request_att is None or not server.active or query.payload is None:
            query.reply_err(b"request without rmw_zenoh's attachment, or no such server")
            query.drop()
            return
        try:
            request = deserialize(server.srv_type.Request.TYPE, query.payload.to_bytes())
        except WireError as exc:
            query.reply_err(str(exc).encode())
            query.drop()
            return
        future: Future[Message] = Future()
        key = str(query.key_expr)

        def reply(done: Future[Message]) -> None:
            response = done.result()
            if response is not None:
                att = Attachment(request_att.sequence_number, time.time_ns(), request_att.gid).pack()
                query.reply(key, serialize(response), attachment=att)
            query.drop()

        future.add_done_callback(reply)
        self.bus.queue_call(PendingCall(server, request, future))

    def has_server(self, name: str, srv_type: type[Service]) -> bool:
        return self.remote.has_server(name, dds_type_name(srv_type.TYPE))

    def call(self, client: ServiceClient, request: Message, future: Future[Message]) -> None:
        entity = self._entities.get(id(client))
        if entity is None:
            return
        seq = self._client_seq.get(id(client), 0) + 1
        self._client_seq[id(client)] = seq
        att = Attachment(seq, time.time_ns(), entity.token.gid).pack()
        key = data_key(
            self.domain_id, client.srv_name, entity.token.dds_type or "", entity.token.type_hash or ""
        )
        response_type = client.srv_type.Response.TYPE
        self.session.get(
            key,
            lambda reply: self.inbox.post(("reply", future, reply, response_type)),
            target=zenoh.QueryTarget.ALL_COMPLETE,
            consolidation=zenoh.ConsolidationMode.NONE,
            payload=serialize(request),
            attachment=att,
            timeout=QUERY_TIMEOUT_S,
        )

    def _complete(self, future: Future[Message], reply: zenoh.Reply, response_type: str) -> None:
        if future.done() or reply.ok is None:
            return
        try:
            future.set_result(deserialize(response_type, reply.ok.payload.to_bytes()))
            self.stats.replies += 1
        except WireError as exc:
            log.warning("undecodable service reply: %s", exc)

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
