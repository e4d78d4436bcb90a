"""The Foxglove WebSocket server, fed from the bus: Foxglove and Lichtblick attach.

Every topic is advertised as a channel with ``encoding: cdr``, ``schemaEncoding: ros2msg`` and
its full definition (dependencies concatenated, as ROS 2's MCAP profile carries them), so the
3D, Plot, Raw Messages and Publish panels work without extensions. A topic is subscribed on
the bus only while some client subscribes to its channel, so idle channels cost nothing.
Clients may publish (the Publish and Teleop panels), in CDR or JSON, onto topics of a type this
lab knows; what the REST API refuses (a NaN setpoint) is refused here too.

The server is the app's own (server/services/bridges/foxglove_server.py), guarded as the app's port is:
foxglove-sdk's server would listen on a port of its own that checks nothing.
"""

from __future__ import annotations

import itertools
import json
import logging
from collections.abc import Callable

from node_runtime.bus import Bus, Node, Publisher, RosTime, Subscription, TopicTypeError
from node_runtime.msgs import Message, MessageError, UnknownTypeError, get_type
from node_runtime.msgs.wire import WireError, definition_closure_text, deserialize, serialize
from server.services.bridges.foxglove_protocol import ChannelInfo, ClientChannel
from server.services.bridges.foxglove_server import FoxgloveServer, Guard
from server.services.bridges.inbound import check_inbound

log = logging.getLogger("bridges.foxglove")
SYNC_PERIOD_S = 0.25  # how often new and vanished topics are (un)advertised
MAX_CLIENT_TOPICS = 64  # topics clients may create by publishing
SUBSCRIPTION_DEPTH = 100


class FoxgloveBridgeNode(Node):
    """Hidden node ``_foxglove_bridge``: bus topics → channels, client channels → publishers."""

    def __init__(self, limits_name: Callable[[str], str] | None = None) -> None:
        super().__init__("_foxglove_bridge")
        # The name whose limits (node_runtime/limits.py) a client's message must keep: the topic's own,
        # or on a class's graph the world's topic under /<world>.
        self.limits_name = limits_name or (lambda topic: topic)
        self.channels: dict[str, tuple[ChannelInfo, type[Message]]] = {}
        self.subscribers: dict[int, int] = {}  # channel id → clients subscribed to it
        self.forwarding: dict[str, Subscription] = {}  # topic → the bus subscription feeding its channel
        self.publishers_by_topic: dict[str, Publisher] = {}
        self.refused = 0
        self.server: FoxgloveServer | None = None  # set by FoxgloveBridge: whom channels are announced to
        self._channel_ids = itertools.count(1)
        self._graph_version: tuple[int, int] | None = None
        self.sync()
        self.create_timer(SYNC_PERIOD_S, self.sync)

    # -- bus → Foxglove ----------------------------------------------------
    def sync(self) -> None:
        """Advertise new topics (this process's, and those only other processes declare, with a
        type this lab knows), unadvertise vanished ones (or ones that changed type). Not while the
        server has no client: the list is brought up to date when one comes (``channel_list``). A
        class's graph changes with every node that starts, and each sync walked all of it on the
        loop the worlds tick on (a few milliseconds each, four times a second while a class
        started its nodes), for channels nobody was there to see."""
        if self.server is not None and not self.server.sessions:
            return
        self._sync_now()

    def _sync_now(self) -> None:
        version = self.bus.topics_version
        if version == self._graph_version:
            return
        self._graph_version = version
        current = self.bus.known_topics()
        for name, (channel, msg_type) in list(self.channels.items()):
            if current.get(name) is not msg_type:
                self._drop_subscription(name)
                self.subscribers.pop(channel.id, None)
                del self.channels[name]
                if self.server is not None:
                    self.server.unadvertise(channel.id)
        for name, msg_type in current.items():
            if name not in self.channels:
                schema = definition_closure_text(msg_type.TYPE)
                channel = ChannelInfo(next(self._channel_ids), name, msg_type.TYPE, schema)
                self.channels[name] = (channel, msg_type)
                if self.server is not None:
                    self.server.advertise(channel)

    def channel_list(self) -> list[ChannelInfo]:
        """Every channel, the list brought up to date first (a client that comes asks this before
        it is among the server's sessions, so what changed meanwhile is advertised to it once)."""
        self._sync_now()
        return [channel for channel, _ in self.channels.values()]

    def _channel_topic(self, channel_id: int) -> str | None:
        return next((name for name, (ch, _) in self.channels.items() if ch.id == channel_id), None)

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
            if self.server is not None:
                stamp = RosTime.from_seconds(self.bus.clock.now()).nanoseconds
                self.server.log(channel.id, serialize(msg), stamp)

        self.forwarding[topic] = self.create_subscription(msg_type, topic, forward, SUBSCRIPTION_DEPTH)

    def _drop_subscription(self, topic: str) -> None:
        sub = self.forwarding.pop(topic, None)
        if sub is not None:
            self.destroy_subscription(sub)

    # -- Foxglove → bus ----------------------------------------------------
    def client_message(self, channel: ClientChannel, data: bytes) -> str | None:
        """Publish a client's message; why not, if it is refused (for the client's status)."""
        if self.state != "active":
            return "the bridge is stopping"
        try:
            self._publish(channel, data)
        except (MessageError, UnknownTypeError, TopicTypeError, WireError, ValueError) as exc:
            self.refused += 1
            log.warning("refused a client message on %s: %s", channel.topic, exc)
            return f"{channel.topic}: {exc}"
        return None

    def _publish(self, advertised: ClientChannel, data: bytes) -> None:
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


class FoxgloveBridge:
    """The bridge node and the guarded server it feeds; ``await start(host, port)`` listens."""

    def __init__(
        self,
        bus: Bus,
        guard: Guard,
        name: str = "teleop-lab",
        limits_name: Callable[[str], str] | None = None,
    ) -> None:
        with bus.activate():
            self.node = FoxgloveBridgeNode(limits_name)
        self.server = FoxgloveServer(name, self.node, guard)
        self.node.server = self.server

    @property
    def port(self) -> int:
        return self.server.port

    async def start(self, host: str, port: int) -> int:
        """Listen on ``host:port`` (OSError if taken); the node is stopped then too."""
        try:
            return await self.server.start(host, port)
        except OSError:
            self.node.destroy_node()
            raise

    async def stop(self) -> None:
        await self.server.stop()
        self.node.server = None
        if self.node.state != "destroyed":
            self.node.destroy_node()
