"""The Zenoh side of a bus publisher, as rmw_zenoh declares one.

A publisher puts on Zenoh only while something outside this process subscribes (Zenoh's matching
status): in-process nodes keep the fast path with no serialization. Puts use congestion control
DROP, so a slow peer never holds up the sim loop. A TRANSIENT_LOCAL publisher is Zenoh's advanced
publisher, whose cache answers late subscribers' history queries.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any, cast

import zenoh
import zenoh.ext

from node_runtime.msgs import Message
from node_runtime.transport.attachment import Attachment
from node_runtime.transport.cdr import encode
from node_runtime.transport.keys import BEST_EFFORT, TRANSIENT_LOCAL, QoS, keep_last


@dataclass
class Stats:
    """What one bridge carried and dropped, since it opened."""

    sent: int = 0
    received: int = 0
    no_attachment: int = 0  # dropped, as rmw_zenoh drops them
    echoes: int = 0  # dropped: this process's own samples, come back (the bus delivered them already)
    over_rate: int = 0  # dropped: more samples a second than the bridge takes (a class world's flood)
    undecodable: int = 0
    queries: int = 0
    replies: int = 0


def wire_qos(depth: int, qos: Any) -> QoS:
    """The token's QoS: keep-last ``depth``, and the profile's reliability and durability (rmw's
    enum values; 0, the system's default, is rmw_zenoh's: reliable, volatile)."""
    return keep_last(
        depth,
        best_effort=getattr(qos, "reliability", 0) == BEST_EFFORT,
        transient_local=getattr(qos, "durability", 0) == TRANSIENT_LOCAL,
    )


class RemotePublisher:
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
        self.zpub.put(encode(msg), attachment=attachment)
        self.stats.sent += 1

    def close(self) -> None:
        if self.listener is not None:
            self.listener.undeclare()
        self.zpub.undeclare()


def declare_remote_publisher(
    session: Any, key: str, qos: QoS, depth: int, gid: bytes, stats: Stats
) -> RemotePublisher:
    """Declare the publisher on ``key`` with the token's reliability and durability."""
    reliability = (
        zenoh.Reliability.BEST_EFFORT if qos.reliability == BEST_EFFORT else zenoh.Reliability.RELIABLE
    )
    zpub: zenoh.Publisher | zenoh.ext.AdvancedPublisher
    if qos.durability == TRANSIENT_LOCAL:
        zpub = zenoh.ext.declare_advanced_publisher(
            session,
            key,
            congestion_control=zenoh.CongestionControl.DROP,
            reliability=reliability,
            allowed_destination=zenoh.Locality.REMOTE,
            cache=zenoh.ext.CacheConfig(max_samples=depth),
            publisher_detection=True,
        )
    else:
        # REMOTE: this process's own subscriptions get the message from the bus, and only other
        # processes count as matching (so a topic nobody else wants is never serialized).
        zpub = session.declare_publisher(
            key,
            congestion_control=zenoh.CongestionControl.DROP,
            reliability=reliability,
            allowed_destination=zenoh.Locality.REMOTE,
        )
    return RemotePublisher(zpub, gid, stats)
