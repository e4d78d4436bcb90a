"""What crosses the domain bridge, on Zenoh's threads: samples, and service calls with their replies.

Samples and requests cross as bytes, so no type needs to be known; each gets a new rmw_zenoh
attachment (the bridge's own GID and sequence numbers, the source timestamp kept), and one without
an attachment is dropped, as rmw_zenoh drops it. A call to ``/<world>/<service>`` in the class
domain goes to the world's server as a call of the bridge's own, and the caller gets the world's
reply under its own sequence number and GID, as rmw_zenoh's client matches it. At most
``MAX_CALLS_PER_WORLD`` calls wait on one world at once; one more is refused with an error reply.
"""

from __future__ import annotations

import itertools
import struct
import threading
import time
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import zenoh

from node_runtime.transport.attachment import ATTACHMENT_BYTES
from node_runtime.transport.domain_routes import BridgeStats, Route
from node_runtime.transport.keys import GID_BYTES, EntityKind, EntityToken, data_key

MAX_CALLS_PER_WORLD = 32  # service calls waiting on one world's servers at once
CALL_TIMEOUT_S = 60.0  # a call the world has not answered by then is given up
_SEQUENCE = struct.Struct("<q")


@dataclass
class Mirror:
    """One route as declared: its token and entities in the class domain and in the world."""

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

    def stamp(self, source: bytes) -> bytes:
        """rmw_zenoh's attachment with the bridge's next sequence number and GID, ``source``'s timestamp."""
        return _SEQUENCE.pack(next(self.seq)) + source[8:16] + self.tail


def _rmw_attachment(raw: Any) -> bytes | None:
    """``raw``'s bytes when it is rmw_zenoh's attachment, else None."""
    source = raw.to_bytes() if raw is not None else b""
    return source if len(source) == ATTACHMENT_BYTES and source[16] == GID_BYTES else None


class Crossing:
    """Carries samples and calls for the mirrors of one bridge, counting them in ``stats``."""

    def __init__(self, session: Any, class_domain: int, stats: BridgeStats) -> None:
        self.session = session
        self.class_domain = class_domain
        self.stats = stats
        self._lock = threading.Lock()
        self._calls: Counter[int] = Counter()  # service calls waiting, by world domain

    def forward(self, mirror: Mirror, sample: zenoh.Sample) -> None:
        """A sample of ``mirror``'s topic: out into the class domain, or into the world."""
        source = _rmw_attachment(sample.attachment)
        target = mirror.class_side if mirror.route.kind is EntityKind.PUBLISHER else mirror.world_side
        if source is None or target is None:
            self.stats.dropped += 1  # not rmw_zenoh's attachment: dropped, as rmw_zenoh drops it
            return
        try:
            target.put(sample.payload, attachment=mirror.stamp(source))
        except (zenoh.ZError, RuntimeError):  # undeclared while this sample was on its way
            self.stats.dropped += 1
            return
        if mirror.route.kind is EntityKind.PUBLISHER:
            self.stats.out += 1
        else:
            self.stats.into += 1

    def call(self, mirror: Mirror, query: Any) -> None:  # zenoh.Query; its drop() is untyped
        """A call to ``/<world>/<service>`` in the class domain: the same request goes to the world's
        server, and each reply goes back under the caller's own sequence number and GID."""
        domain_id = mirror.route.domain_id
        key = data_key(
            self.class_domain, mirror.token.topic or "", mirror.route.dds_type, mirror.route.type_hash
        )
        source = _rmw_attachment(query.attachment)
        why = self._refusal(mirror, query, key, source)
        if source is None or why:
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

        world_key = data_key(domain_id, mirror.route.topic, mirror.route.dds_type, mirror.route.type_hash)
        try:
            self.session.get(
                world_key,
                zenoh.handlers.Callback(on_reply, finished),
                target=zenoh.QueryTarget.ALL_COMPLETE,
                consolidation=zenoh.ConsolidationMode.NONE,
                payload=query.payload,
                attachment=mirror.stamp(source),
                timeout=CALL_TIMEOUT_S,
                allowed_destination=zenoh.Locality.REMOTE,
            )
        except (zenoh.ZError, RuntimeError):  # the session is closing
            self.stats.refused += 1
            finished()

    def _refusal(self, mirror: Mirror, query: Any, key: str, source: bytes | None) -> str:
        """Why a call is refused ("" when it goes on, holding one of its world's call places)."""
        if str(query.key_expr) != key:  # a pattern (0/**) would call every world's servers at once
            return f"a call names one service, not a pattern: {query.key_expr}"
        if source is None or query.payload is None:
            return "a request without rmw_zenoh's attachment"
        domain_id = mirror.route.domain_id
        with self._lock:
            if self._calls[domain_id] >= MAX_CALLS_PER_WORLD:
                return f"more than {MAX_CALLS_PER_WORLD} calls are waiting on {mirror.namespace}"
            self._calls[domain_id] += 1
        return ""
