"""The Foxglove WebSocket server (``foxglove-sdk``), fed from the bus: Foxglove and Lichtblick attach.

Every topic is advertised as a channel with ``encoding: cdr``, ``schemaEncoding: ros2msg`` and
its full definition (dependencies concatenated, as ROS 2's MCAP profile carries them), so the
3D, Plot, Raw Messages and Publish panels work without extensions. A topic is subscribed on
the bus only while some client subscribes to its channel, so idle channels cost nothing.
Clients may publish (the Publish and Teleop panels), in CDR or JSON, onto topics of a type this
lab knows; what the REST API refuses (a NaN setpoint) is refused here too.

foxglove-sdk checks neither Origin nor Host, so its server listens on loopback on an ephemeral
port and the app's guarded front (server/bridges/front.py) is what clients connect to. Its
listener callbacks arrive on the SDK's threads and are handed to the app's loop before they
touch the bus; those hand-offs are bounded.
"""

from __future__ import annotations

import asyncio
import json
import logging
import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import foxglove
from foxglove import Channel, Schema
from foxglove.websocket import Capability, ChannelView, Client, ClientChannel, ServerListener, StatusLevel

from server.bus import Bus, Node, Publisher, RosTime, Subscription, TopicTypeError
from server.msgs import Message, MessageError, UnknownTypeError, get_type
from server.msgs.wire import WireError, definition_closure_text, deserialize, serialize

from .inbound import check_inbound

log = logging.getLogger("bridges.foxglove")
SYNC_PERIOD_S = 0.25  # how often new and vanished topics are (un)advertised
MAX_PENDING = 1000  # client messages handed to the loop and not yet published
MAX_CLIENT_TOPICS = 64  # topics clients may create by publishing
SUBSCRIPTION_DEPTH = 100


@dataclass(frozen=True)
class Advertised:
    """A channel a client advertised, to publish on."""

    topic: str
    encoding: str
    schema_name: str


class FoxgloveBridgeNode(Node):
    """Hidden node ``_foxglove_bridge``: bus topics → channels, client channels → publishers."""

    def __init__(self, context: foxglove.Context, limits_name: Callable[[str], str] | None = None) -> None:
        super().__init__("_foxglove_bridge")
        self.context = context
        # The name whose limits (server/limits.py) a client's message must keep: the topic's own,
        # or on a class's graph the world's topic under /<world>.
        self.limits_name = limits_name or (lambda topic: topic)
        self.channels: dict[str, tuple[Channel, type[Message]]] = {}
        self.subscribers: dict[int, int] = {}  # channel id → clients subscribed to it
        self.forwarding: dict[str, Subscription] = {}  # topic → the bus subscription feeding its channel
        self.publishers_by_topic: dict[str, Publisher] = {}
        self.client_channels: dict[tuple[int, int], Advertised] = {}
        self.refused = 0
        self.server: Any = None  # set by FoxgloveBridge once the server runs (for status messages)
        self._graph_version: tuple[int, int] | None = None
        self.sync()
        self.create_timer(SYNC_PERIOD_S, self.sync)

    # -- bus → Foxglove ----------------------------------------------------
    def sync(self) -> None:
        """Advertise new topics (this process's, and those only other processes declare, with a
        type this lab knows), unadvertise vanished ones (or ones that changed type)."""
        version = self.bus.topics_version
        if version == self._graph_version:
            return
        self._graph_version = version
        current = self.bus.known_topics()
        for name, (channel, msg_type) in list(self.channels.items()):
            if current.get(name) is not msg_type:
                self._drop_subscription(name)
                self.subscribers.pop(channel.id(), None)
                channel.close()
                del self.channels[name]
        for name, msg_type in current.items():
            if name not in self.channels:
                schema = Schema(
                    name=msg_type.TYPE,
                    encoding="ros2msg",
                    data=definition_closure_text(msg_type.TYPE).encode(),
                )
                channel = Channel(name, message_encoding="cdr", schema=schema, context=self.context)
                self.channels[name] = (channel, msg_type)

    def _channel_topic(self, channel_id: int) -> str | None:
        return next((name for name, (ch, _) in self.channels.items() if ch.id() == channel_id), None)

    def client_subscribed(self, channel_id: int) -> None:
        topic = self._channel_topic(channel_id)
        if topic is None:
            return  # a channel closed meanwhile
        self.subscribers[channel_id] = self.subscribers.get(channel_id, 0) + 1
        if topic not in self.forwarding:
            self._subscribe(topic)

    def client_unsubscribed(self, channel_id: int) -> None:
        left = self.subscribers.get(channel_id, 0) - 1
        if left > 0:
            self.subscribers[channel_id] = left
            return
        self.subscribers.pop(channel_id, None)
        topic = self._channel_topic(channel_id)
        if topic is not None:
            self._drop_subscription(topic)

    def _subscribe(self, topic: str) -> None:
        channel, msg_type = self.channels[topic]

        def forward(msg: Message) -> None:
            stamp = RosTime.from_seconds(self.bus.clock.now()).nanoseconds
            channel.log(serialize(msg), log_time=stamp)

        self.forwarding[topic] = self.create_subscription(msg_type, topic, forward, SUBSCRIPTION_DEPTH)

    def _drop_subscription(self, topic: str) -> None:
        sub = self.forwarding.pop(topic, None)
        if sub is not None:
            self.destroy_subscription(sub)

    # -- Foxglove → bus ----------------------------------------------------
    def client_advertised(self, key: tuple[int, int], channel: Advertised) -> None:
        self.client_channels[key] = channel

    def client_unadvertised(self, key: tuple[int, int]) -> None:
        self.client_channels.pop(key, None)

    def client_message(self, key: tuple[int, int], data: bytes) -> None:
        advertised = self.client_channels.get(key)
        if advertised is None:
            return
        try:
            self._publish(advertised, data)
        except (MessageError, UnknownTypeError, TopicTypeError, WireError, ValueError) as exc:
            self.refused += 1
            log.warning("refused a client message on %s: %s", advertised.topic, exc)
            if self.server is not None:
                self.server.publish_status(f"{advertised.topic}: {exc}"[:500], StatusLevel.Warning)

    def _publish(self, advertised: Advertised, data: bytes) -> None:
        topic = self.resolve_topic_name(advertised.topic)
        existing = self.bus.topic_type(topic)  # here or in another process
        msg_type = get_type(advertised.schema_name) if advertised.schema_name else None
        if msg_type is None:
            if existing is None:
                raise ValueError(f"{topic} does not exist and the client gave no type")
            msg_type = existing
        if existing is not None and existing is not msg_type:
            raise TopicTypeError(f"{topic} carries {existing.TYPE}, not {msg_type.TYPE}")
        as_json = None
        if advertised.encoding == "cdr":
            message = deserialize(msg_type.TYPE, data)
        elif advertised.encoding == "json":
            as_json = json.loads(data)
            message = msg_type.from_dict(as_json)
        else:
            raise ValueError(f"encoding {advertised.encoding!r} is not supported (cdr, json)")
        check_inbound(self.limits_name(topic), message, as_json)
        self._publisher(topic, msg_type).publish(message)

    def _publisher(self, topic: str, msg_type: type[Message]) -> Publisher:
        pub = self.publishers_by_topic.get(topic)
        if pub is None or pub.msg_type is not msg_type:
            if pub is None and len(self.publishers_by_topic) >= MAX_CLIENT_TOPICS:
                raise ValueError(
                    f"clients already publish on {MAX_CLIENT_TOPICS} topics; no more may be created"
                )
            pub = self.publishers_by_topic[topic] = self.create_publisher(msg_type, topic, 10)
        return pub


class _Listener(ServerListener):
    """foxglove-sdk's ServerListener: called on the SDK's threads, hands everything to the loop."""

    def __init__(self, node: FoxgloveBridgeNode, loop: asyncio.AbstractEventLoop) -> None:
        self.node = node
        self.loop = loop
        self.pending = 0
        self.dropped = 0
        self._lock = threading.Lock()

    def _hand_over(self, fn: Any, *args: Any, droppable: bool = False) -> None:
        with self._lock:
            if droppable and self.pending >= MAX_PENDING:
                self.dropped += 1
                return
            self.pending += 1
        try:
            self.loop.call_soon_threadsafe(self._run, fn, args)
        except RuntimeError:  # the loop closed: the app is stopping
            with self._lock:
                self.pending -= 1

    def _run(self, fn: Any, args: tuple[Any, ...]) -> None:
        with self._lock:
            self.pending -= 1
        if self.node.state == "active":
            fn(*args)

    def on_subscribe(self, client: Client, channel: ChannelView) -> None:
        self._hand_over(self.node.client_subscribed, channel.id)

    def on_unsubscribe(self, client: Client, channel: ChannelView) -> None:
        self._hand_over(self.node.client_unsubscribed, channel.id)

    def on_client_advertise(self, client: Client, channel: ClientChannel) -> None:
        advertised = Advertised(channel.topic, channel.encoding, channel.schema_name or "")
        self._hand_over(self.node.client_advertised, (client.id, channel.id), advertised)

    def on_client_unadvertise(self, client: Client, client_channel_id: int) -> None:
        self._hand_over(self.node.client_unadvertised, (client.id, client_channel_id))

    def on_message_data(self, client: Client, client_channel_id: int, data: bytes) -> None:
        self._hand_over(self.node.client_message, (client.id, client_channel_id), bytes(data), droppable=True)


class FoxgloveBridge:
    """The SDK's server on loopback (ephemeral port) and the node that feeds it."""

    def __init__(
        self,
        bus: Bus,
        loop: asyncio.AbstractEventLoop,
        name: str = "teleop-lab",
        limits_name: Callable[[str], str] | None = None,
    ) -> None:
        self.context = foxglove.Context()
        with bus.activate():
            self.node = FoxgloveBridgeNode(self.context, limits_name)
        self.listener = _Listener(self.node, loop)
        self.server = foxglove.start_server(
            name=name,
            host="127.0.0.1",
            port=0,
            capabilities=[Capability.ClientPublish],
            supported_encodings=["cdr", "json"],
            server_listener=self.listener,
            context=self.context,
        )
        self.node.server = self.server

    @property
    def port(self) -> int:
        """The SDK server's loopback port (only the guarded front should connect to it)."""
        return int(self.server.port)

    def stop(self) -> None:
        self.server.stop()
        for channel, _ in self.node.channels.values():
            channel.close()
        self.node.destroy_node()
