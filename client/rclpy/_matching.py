"""Which endpoints a publisher or subscription matches, here and in other processes, and whether
their QoS profiles agree: what ``get_subscription_count``, the matched events and the
incompatible-QoS events count.

Endpoints match when they name the same topic with the same type, as rmw_zenoh matches them (it
delivers whatever the profiles say); a pair whose profiles DDS would refuse to pair still raises
rclpy's incompatible-QoS event, so a program learns what another middleware would do.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from typing import Any

from node_runtime.bus import Publisher as BusPublisher
from node_runtime.bus import Subscription as BusSubscription
from node_runtime.transport.keys import EntityKind
from rclpy.qos import DurabilityPolicy, QoSPolicyKind, QoSProfile, ReliabilityPolicy

_INFINITE = 0  # ns: rmw's "no deadline"


@dataclass(frozen=True)
class Offer:
    """The policies of one endpoint that decide compatibility (rmw's enum values; 0 = default)."""

    reliability: int
    durability: int
    deadline_ns: int


def offer_of(endpoint: Any) -> Offer:
    """A local endpoint's policies: its rclpy profile, else the bus's wire QoS, else the defaults."""
    profile = getattr(endpoint, "qos_profile", None)
    if isinstance(profile, QoSProfile):
        deadline = profile.deadline.nanoseconds
        return Offer(int(profile.reliability), int(profile.durability), max(0, deadline))
    wire = getattr(endpoint, "qos", None)
    return Offer(getattr(wire, "reliability", 0), getattr(wire, "durability", 0), _INFINITE)


def _remote_offer(qos: Any) -> Offer:
    sec, nsec = qos.deadline
    return Offer(qos.reliability, qos.durability, sec * 1_000_000_000 + nsec)


def incompatible_policy(offered: Offer, requested: Offer) -> QoSPolicyKind | None:
    """The policy for which a publisher's offer cannot serve a subscription's request, as DDS
    decides it; None when they agree."""
    if (
        requested.reliability == ReliabilityPolicy.RELIABLE
        and offered.reliability == ReliabilityPolicy.BEST_EFFORT
    ):
        return QoSPolicyKind.RELIABILITY
    if (
        requested.durability == DurabilityPolicy.TRANSIENT_LOCAL
        and offered.durability == DurabilityPolicy.VOLATILE
    ):
        return QoSPolicyKind.DURABILITY
    if requested.deadline_ns != _INFINITE and (
        offered.deadline_ns == _INFINITE or offered.deadline_ns > requested.deadline_ns
    ):
        return QoSPolicyKind.DEADLINE
    return None


def _remote(node: Any) -> Any:
    """The remote graph of the node's process, or None (no Zenoh: ROS2LAB_NO_ZENOH, the app)."""
    bridge = getattr(getattr(node, "_rcl_context", None), "bridge", None)
    return None if bridge is None else bridge.remote


def peers(endpoint: BusPublisher | BusSubscription) -> list[Offer]:
    """The offers of every live endpoint of the other kind on the same topic with the same type."""
    topic = endpoint.topic
    node = endpoint.node
    local: list[Any] = (
        list(topic.subscriptions) if isinstance(endpoint, BusPublisher) else list(topic.publishers)
    )
    found = [offer_of(e) for e in local if not e.destroyed and e.node._state == "active"]
    remote = _remote(node)
    if remote is not None:
        kind = EntityKind.SUBSCRIPTION if isinstance(endpoint, BusPublisher) else EntityKind.PUBLISHER
        # The executor's pass changes the remote graph under the bus's lock; a count asked from
        # another thread (a loop on get_subscription_count while spin runs) reads it under it too.
        lock = node._bus.lock
        with lock if lock is not None else contextlib.nullcontext():
            remote_endpoints = remote.endpoints((kind,))
        type_name = endpoint.msg_type.TYPE
        found += [
            _remote_offer(e.qos)
            for e in remote_endpoints
            if e.name == topic.name and e.type_name == type_name
        ]
    return found


def incompatible_peers(endpoint: BusPublisher | BusSubscription) -> list[QoSPolicyKind]:
    """For each peer DDS would refuse, the policy it would refuse it for."""
    own = offer_of(endpoint)
    out = []
    for peer in peers(endpoint):
        offered, requested = (own, peer) if isinstance(endpoint, BusPublisher) else (peer, own)
        policy = incompatible_policy(offered, requested)
        if policy is not None:
            out.append(policy)
    return out
