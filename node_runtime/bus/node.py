"""``Node``: rclpy's API shape on this bus (create_publisher, create_subscription, create_timer ...)."""

from __future__ import annotations

import logging
from collections import deque
from collections.abc import Callable
from typing import Any, Literal

from node_runtime.bus.clock import NodeClock
from node_runtime.bus.endpoints import Publisher, Subscription, Timer, qos_depth, transient_local
from node_runtime.bus.errors import DestroyedError
from node_runtime.bus.graph import Bus, current_bus, current_overrides
from node_runtime.bus.names import resolve_topic_name, validate_namespace, validate_node_name
from node_runtime.bus.parameters import NodeParameters, Parameter
from node_runtime.bus.services import ServiceCallback, ServiceClient, ServiceServer
from node_runtime.console import world_logger
from node_runtime.msgs import Log, Message, Service

NodeState = Literal["active", "crashed", "destroyed"]
_LEVELS = {"debug": 10, "info": 20, "warn": 30, "error": 40, "fatal": 50}


def node_logger_name(world: str | None, fully_qualified_name: str) -> str:
    """The Python logger of a node's lines: ``node.ns.name`` alone, ``world.<world>.ns.name`` in a
    class server, so one level (``--world-log-level``) governs every world's nodes at once."""
    dotted = fully_qualified_name.replace("/", ".")
    return f"{world_logger(world)}{dotted}" if world else f"node{dotted}"


def ros_logger_name(fully_qualified_name: str) -> str:
    """The name rcl gives a node's logger: its namespace and name joined by dots, with no
    leading one (``/turtlesim2/sim`` logs as ``turtlesim2.sim``, ``/talker`` as ``talker``); the
    name its lines print in brackets and carry on /rosout."""
    return fully_qualified_name.lstrip("/").replace("/", ".")


class NodeLogger:
    """``node.get_logger()``: Python logging under the node's name, echoed on /rosout."""

    def __init__(self, node: Node) -> None:
        self._node = node
        self.name = ros_logger_name(node.fully_qualified_name)
        self._py = logging.getLogger(node_logger_name(node._bus.label, node.fully_qualified_name))

    def _log(self, level: str, msg: Any) -> None:
        text = str(msg)
        console = self._node._bus.console
        if console is not None:
            console(_LEVELS[level], self.name, text)
        else:
            self._py.log(_LEVELS[level], "[%s] %s", self.name, text)
        self._node._emit_log(_LEVELS[level], text)

    def debug(self, msg: Any) -> None:
        self._log("debug", msg)

    def info(self, msg: Any) -> None:
        self._log("info", msg)

    def warning(self, msg: Any) -> None:
        self._log("warn", msg)

    warn = warning

    def error(self, msg: Any) -> None:
        self._log("error", msg)

    def fatal(self, msg: Any) -> None:
        self._log("fatal", msg)


class Node(NodeParameters):
    """A participant in the graph. Subclass it as in rclpy: ``super().__init__('MyNode')``."""

    # What the create_* calls make: rclpy's client library gives its own subclasses (rclpy.publisher ...).
    _publisher_class: type[Publisher] = Publisher
    _subscription_class: type[Subscription] = Subscription
    _timer_class: type[Timer] = Timer
    _service_class: type[ServiceServer] = ServiceServer

    def __init__(
        self,
        node_name: str,
        *,
        namespace: str | None = None,
        context: Bus | None = None,
        parameter_overrides: dict[str, Any] | None = None,
        **_ignored: Any,
    ) -> None:
        overrides = current_overrides()
        self._bus = context if context is not None else current_bus()
        self._name = validate_node_name(overrides.name if overrides and overrides.name else node_name)
        ns = overrides.namespace if overrides and overrides.namespace else namespace
        self._namespace = validate_namespace(ns or "/")
        self._remap = dict(overrides.remappings) if overrides else {}
        self._param_overrides = dict(parameter_overrides or {})
        if overrides:
            for params_file in overrides.files:
                self._param_overrides.update(params_file.for_node(self.fully_qualified_name))
            self._param_overrides.update(overrides.parameters)
        self._parameters: dict[str, Parameter] = {}
        self._param_callbacks: list[Callable[[list[Parameter]], Any]] = []
        self._descriptors = {}
        self._origin: dict[str, str] = {}  # package, executable, launch file: set by the launcher
        self.publishers: list[Publisher] = []
        self.subscriptions: list[Subscription] = []
        self.timers: list[Timer] = []
        self.services: list[ServiceServer] = []
        self.clients: list[ServiceClient] = []
        self._state: NodeState = "active"
        self._crash_reason: str | None = None
        self._clock = NodeClock(self._bus.clock)
        self._logger = NodeLogger(self)
        self._rosout: Publisher | None = None
        self._bus.add_node(self)
        self._rosout = self.create_publisher(Log, "/rosout", 1000)
        self._start_parameters()

    # -- what the lab's server reads of its own nodes ---------------------
    # Kept under private names: rclpy's Node has no such attributes, so a student's subclass may
    # use these names for its own (``self.state = False``); the lab's rclpy Node leaves them free.
    @property
    def bus(self) -> Bus:
        return self._bus

    @property
    def state(self) -> NodeState:
        return self._state

    @property
    def crash_reason(self) -> str | None:
        return self._crash_reason

    @property
    def origin(self) -> dict[str, str]:
        """The package, executable and launch file a launcher started it from."""
        return self._origin

    @origin.setter
    def origin(self, origin: dict[str, str]) -> None:
        self._origin = origin

    # -- identity --------------------------------------------------------
    def get_name(self) -> str:
        return self._name

    def get_namespace(self) -> str:
        return self._namespace

    @property
    def fully_qualified_name(self) -> str:
        return self._namespace.rstrip("/") + "/" + self._name

    def get_fully_qualified_name(self) -> str:
        return self.fully_qualified_name

    def get_logger(self) -> NodeLogger:
        return self._logger

    def get_clock(self) -> NodeClock:
        return self._clock

    def resolve_topic_name(self, topic: str) -> str:
        return resolve_topic_name(topic, self._name, self._namespace, self._remap)

    # -- endpoints -------------------------------------------------------
    def _check_alive(self) -> None:
        if self._state == "destroyed":
            raise DestroyedError(f"node {self.fully_qualified_name} was destroyed")

    def create_publisher(
        self, msg_type: type[Message], topic: str, qos_profile: Any, *, hand_over: bool = False
    ) -> Publisher:
        """rclpy's call. ``hand_over`` (the lab's own nodes): every message this publisher sends is
        built for that publish and never changed after it, so the bus shares it instead of copying."""
        self._check_alive()
        depth = qos_depth(qos_profile)
        t = self._bus.topic(self.resolve_topic_name(topic), msg_type)
        pub = self._publisher_class(self, t, msg_type, depth, hand_over=hand_over)
        pub.qos = None if isinstance(qos_profile, int) else qos_profile
        if transient_local(pub.qos):
            pub.history = deque(maxlen=depth)
        t.publishers.append(pub)
        self.publishers.append(pub)
        self._bus.endpoint_added(pub)
        return pub

    def create_subscription(
        self,
        msg_type: type[Message],
        topic: str,
        callback: Callable[[Any], Any],
        qos_profile: Any,
        *,
        read_only: bool = False,
    ) -> Subscription:
        """rclpy's call. ``read_only`` (the lab's own nodes): ``callback`` never changes a message it
        gets, so it gets the one the topic shares (its latest) rather than a copy of its own."""
        self._check_alive()
        depth = qos_depth(qos_profile)
        t = self._bus.topic(self.resolve_topic_name(topic), msg_type)
        sub = self._subscription_class(self, t, msg_type, callback, depth, read_only=read_only)
        sub.qos = None if isinstance(qos_profile, int) else qos_profile
        t.subscriptions.append(sub)
        self.subscriptions.append(sub)
        self._bus.endpoint_added(sub)
        if transient_local(sub.qos):
            if self._bus.lock is None:
                t.hand_history(sub)
            else:
                with self._bus.lock:
                    t.hand_history(sub)
        return sub

    def create_timer(self, timer_period_sec: float, callback: Callable[[], Any]) -> Timer:
        self._check_alive()
        timer = self._timer_class(self, timer_period_sec, callback, self._bus.clock.now())
        self.timers.append(timer)
        self._bus.schedule(timer)
        return timer

    def create_service(
        self, srv_type: type[Service], srv_name: str, callback: ServiceCallback, **_qos: Any
    ) -> ServiceServer:
        """Serve ``srv_name``: ``callback(request, response)`` fills and returns the response."""
        self._check_alive()
        channel = self._bus.service(self.resolve_topic_name(srv_name), srv_type)
        server = self._service_class(self, channel, callback)
        channel.servers.append(server)
        self.services.append(server)
        self._bus.endpoint_added(server)
        return server

    def create_client(self, srv_type: type[Service], srv_name: str, **_qos: Any) -> ServiceClient:
        self._check_alive()
        channel = self._bus.service(self.resolve_topic_name(srv_name), srv_type)
        client = ServiceClient(self, channel)
        channel.clients.append(client)
        self.clients.append(client)
        self._bus.endpoint_added(client)
        return client

    def destroy_service(self, server: ServiceServer) -> bool:
        if server.destroyed:
            return False
        server.destroyed = True
        server.channel.servers.remove(server)
        self.services.remove(server)
        self._bus.drop_service_if_unused(server.channel)
        self._bus.endpoint_removed(server)
        return True

    def destroy_client(self, client: ServiceClient) -> bool:
        if client.destroyed:
            return False
        client.destroyed = True
        client.channel.clients.remove(client)
        self.clients.remove(client)
        self._bus.drop_service_if_unused(client.channel)
        self._bus.endpoint_removed(client)
        return True

    def destroy_publisher(self, pub: Publisher) -> bool:
        if pub.destroyed:
            return False
        pub.destroyed = True
        pub.topic.publishers.remove(pub)
        self.publishers.remove(pub)
        self._bus.drop_topic_if_unused(pub.topic)
        self._bus.endpoint_removed(pub)
        return True

    def destroy_subscription(self, sub: Subscription) -> bool:
        if sub.destroyed:
            return False
        sub.destroyed = True
        sub.queue.clear()
        sub.topic.subscriptions.remove(sub)
        self.subscriptions.remove(sub)
        self._bus.drop_topic_if_unused(sub.topic)
        self._bus.endpoint_removed(sub)
        return True

    def destroy_timer(self, timer: Timer) -> bool:
        timer.cancel()
        if timer in self.timers:
            self.timers.remove(timer)
            return True
        return False

    def destroy_node(self) -> bool:
        if self._state == "destroyed":
            return False
        for timer in list(self.timers):
            self.destroy_timer(timer)
        for sub in list(self.subscriptions):
            self.destroy_subscription(sub)
        for pub in list(self.publishers):
            self.destroy_publisher(pub)
        for server in list(self.services):
            self.destroy_service(server)
        for client in list(self.clients):
            self.destroy_client(client)
        self._state = "destroyed"
        self._bus.remove_node(self)
        return True

    # -- faults ----------------------------------------------------------
    def mark_crashed(self, exc: BaseException) -> None:
        """Stop this node's callbacks (its process died) but keep it visible, as crashed."""
        if self._state != "active":
            return
        self._state = "crashed"
        self._crash_reason = f"{type(exc).__name__}: {exc}"
        for timer in self.timers:
            timer.cancel()
        for sub in self.subscriptions:
            sub.queue.clear()
        self._bus.node_crashed(self, exc)

    def _emit_log(self, level: int, text: str) -> None:
        if self._rosout is None or self._rosout.destroyed:
            return
        now = self._bus.clock.now()
        sec = int(now)
        msg = Log(level=level, name=ros_logger_name(self.fully_qualified_name), msg=text[:4096])
        object.__setattr__(msg.stamp, "sec", sec)
        object.__setattr__(msg.stamp, "nanosec", min(int((now - sec) * 1e9), 999_999_999))
        self._rosout.publish(msg)
