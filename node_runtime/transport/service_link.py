"""A bus's services over Zenoh, as rmw_zenoh's: a server answers queries, a client queries.

A service server is a queryable on the service key; a query carries the request's CDR and an
attachment (sequence number, client GID), and the reply's attachment echoes them. A client with
no server in its own process queries Zenoh, and its reply is matched to its call by the future
the query was made for. Zenoh's threads only post to the inbox; requests and replies are decoded
and handled on the executor's thread.
"""

from __future__ import annotations

import logging
import time
from typing import Any

import zenoh

from node_runtime.bus import Bus, Future, ServiceClient, ServiceServer
from node_runtime.bus.services import PendingCall
from node_runtime.msgs import Message, Service
from node_runtime.msgs.wire import WireError, dds_type_name
from node_runtime.transport.attachment import Attachment
from node_runtime.transport.cdr import decode, encode
from node_runtime.transport.inbox import Inbox
from node_runtime.transport.keys import EntityToken, data_key
from node_runtime.transport.publishing import Stats
from node_runtime.transport.remote_graph import RemoteGraph

log = logging.getLogger("transport")
QUERY_TIMEOUT_S = 3600.0  # a ROS 2 call waits as long as it takes; Zenoh needs some bound


class ServiceLink:
    """Serves this bus's servers to other processes and calls theirs for its clients."""

    def __init__(self, bus: Bus, session: Any, inbox: Inbox, remote: RemoteGraph, stats: Stats) -> None:
        self.bus = bus
        self.session = session
        self.inbox = inbox
        self.remote = remote
        self.stats = stats
        self._client_seq: dict[int, int] = {}

    def serve(self, server: ServiceServer, key: str) -> Any:
        """Declare ``server``'s queryable on ``key``; its queries go through the inbox."""

        def on_query(query: zenoh.Query) -> None:
            self.inbox.post(("query", server, query))

        return self.session.declare_queryable(
            key, on_query, complete=True, allowed_origin=zenoh.Locality.REMOTE
        )

    def answer(self, server: ServiceServer, query: Any) -> None:
        """Queue a query's request for ``server``; the reply goes when its callback has answered."""
        self.stats.queries += 1
        raw = query.attachment.to_bytes() if query.attachment is not None else None
        request_att = Attachment.unpack(raw)
        if request_att is None or not server.active or query.payload is None:
            query.reply_err(b"request without rmw_zenoh's attachment, or no such server")
            query.drop()
            return
        try:
            request = decode(server.srv_type.Request, query.payload.to_bytes())
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
                query.reply(key, encode(response), attachment=att)
            query.drop()

        future.add_done_callback(reply)
        self.bus.queue_call(PendingCall(server, request, future))

    def has_server(self, name: str, srv_type: type[Service]) -> bool:
        return self.remote.has_server(name, dds_type_name(srv_type.TYPE))

    def call(
        self, client: ServiceClient, token: EntityToken, request: Message, future: Future[Message]
    ) -> None:
        """Query the service for ``client`` (whose liveliness token is ``token``)."""
        seq = self._client_seq.get(id(client), 0) + 1
        self._client_seq[id(client)] = seq
        att = Attachment(seq, time.time_ns(), token.gid).pack()
        key = data_key(token.domain_id, client.channel.name, token.dds_type or "", token.type_hash or "")
        response_type = client.srv_type.Response
        self.session.get(
            key,
            lambda reply: self.inbox.post(("reply", future, reply, response_type)),
            target=zenoh.QueryTarget.ALL_COMPLETE,
            consolidation=zenoh.ConsolidationMode.NONE,
            payload=encode(request),
            attachment=att,
            timeout=QUERY_TIMEOUT_S,
        )

    def forget(self, client: ServiceClient) -> None:
        self._client_seq.pop(id(client), None)

    def complete(self, future: Future[Message], reply: zenoh.Reply, response_type: type[Message]) -> None:
        if future.done() or reply.ok is None:
            return
        try:
            future.set_result(decode(response_type, reply.ok.payload.to_bytes()))
            self.stats.replies += 1
        except WireError as exc:
            log.warning("undecodable service reply: %s", exc)
