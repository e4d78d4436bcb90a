"""The bus: topics, nodes and the queues the executor drains. One per app (or per test)."""

from __future__ import annotations

import heapq
import itertools
import logging
import threading
from collections import deque
from collections.abc import Callable, Iterator, Mapping
from collections.abc import Set as AbstractSet
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

from node_runtime.bus.clock import Clock, SystemClock
from node_runtime.bus.errors import NoBusError, TopicTypeError, UnknownNodeError, UnknownTopicError
from node_runtime.bus.services import Future, PendingCall, ServiceChannel, ServiceClient, check_service_type
from node_runtime.bus.topic import Tap, Topic
from node_runtime.msgs import Message, Service, UnknownTypeError, get_type

if TYPE_CHECKING:
    from node_runtime.bus.endpoints import Subscription, Timer
    from node_runtime.bus.node import Node
    from node_runtime.params_file import ParamsFile


class GraphObserver(Protocol):
    """Told of every node and endpoint as it comes and goes (the transport declares them outside)."""

    def node_added(self, node: Node) -> None: ...

    def node_removed(self, node: Node) -> None: ...

    def endpoint_added(self, endpoint: object) -> None: ...

    def endpoint_removed(self, endpoint: object) -> None: ...


class RemoteServices(Protocol):
    """Where calls go that no node of this process serves (the Zenoh transport)."""

    def has_server(self, name: str, srv_type: type[Service]) -> bool: ...

    def call(self, client: ServiceClient, request: Message, future: Future[Message]) -> None: ...


class RemoteTopics(Protocol):
    """The topics other processes declare on the graph (the Zenoh transport's RemoteGraph)."""

    version: int  # moves whenever they change

    def topic_types(self) -> Mapping[str, AbstractSet[str]]:
        """Every topic name another process publishes or subscribes to, with the types it gives."""
        ...


# Told of every message a topic delivers, with who sent it: the publishing ``Publisher`` of this
# process, or the GID of another process's (bytes); None when not known (server/world/checkpoints).
log = logging.getLogger("bus")
_current_bus: ContextVar[Bus | None] = ContextVar("current_bus", default=None)


@dataclass(frozen=True)
class NodeOverrides:
    """What a launch says about a node it starts: rclpy's ``--ros-args`` in data form."""

    name: str | None = None
    namespace: str | None = None
    parameters: dict[str, Any] = field(default_factory=dict)
    remappings: dict[str, str] = field(default_factory=dict)
    files: tuple[
        ParamsFile, ...
    ] = ()  # ``--params-file``s: each node takes its sections, then ``parameters``


_overrides: ContextVar[NodeOverrides | None] = ContextVar("node_overrides", default=None)


# A node process (the rclpy client library) has one bus for the whole process, set by rclpy.init().
_process_bus: Bus | None = None
_process_overrides: NodeOverrides | None = None


def set_process_bus(bus: Bus | None, overrides: NodeOverrides | None = None) -> None:
    """Make ``bus`` the one every node of this process joins when no bus is active (rclpy.init)."""
    global _process_bus, _process_overrides
    _process_bus, _process_overrides = bus, overrides


def current_bus() -> Bus:
    bus = _current_bus.get() or _process_bus
    if bus is None:
        raise NoBusError(
            "no bus to join: call rclpy.init() first (or, in the app, create nodes inside a launch or "
            "inside `with bus.activate():`)"
        )
    return bus


def current_overrides() -> NodeOverrides | None:
    if _current_bus.get() is not None:
        return _overrides.get()
    return _process_overrides


class Bus:
    """The graph of nodes and topics, plus the ready queue and timer heap an Executor drains."""

    def __init__(self, clock: Clock | None = None) -> None:
        self.clock: Clock = clock or SystemClock()
        self.topics: dict[str, Topic] = {}
        self.services: dict[str, ServiceChannel] = {}
        self.remote_services: RemoteServices | None = None
        self.remote_topics: RemoteTopics | None = None
        self.nodes: list[Node] = []
        self.graph_version = 0
        self.crash_handlers: list[Callable[[Node, BaseException], None]] = []
        self._ready: deque[Subscription] = deque()
        self._calls: deque[PendingCall] = deque()
        self._timers: list[tuple[float, int, Timer]] = []
        self._seq = itertools.count()
        self._wakers: list[Callable[[], None]] = []
        self.observers: list[GraphObserver] = []
        # Called after every change of the graph, here or (through the transport) elsewhere: rclpy's
        # matched and incompatible-QoS events look again. A listener must be quick and not raise.
        self.graph_listeners: list[Callable[[], None]] = []
        # Called at the start of every executor pass, on the executor's thread (the transport's inbox).
        self.pollers: list[Callable[[], None]] = []
        # Set by a running executor: wakes it from another thread.
        self.threadsafe_waker: Callable[[], None] | None = None
        # Held by every executor pass and every publish when nodes of this bus may run on several
        # threads (a node process whose student spins in one thread and publishes from another);
        # None in the app, where everything runs on the event loop's thread.
        self.lock: threading.RLock | None = None
        # Prints a node's log line (level, node name, text); the app logs through Python's logging.
        self.console: Callable[[int, str, str], None] | None = None
        self.taps: dict[str, Tap] = {}  # by topic name: see set_tap
        self.devices: dict[str, Any] = {}  # hardware the nodes may use: 'keyboard', 'display'
        # A class server's world: its name, which its nodes' log lines carry (None: the lab alone).
        self.label: str | None = None
        # Timer calls run, and those skipped because a call ran a whole period or more late (a
        # timer keeps its phase): how well this bus's timers kept their rates, summed.
        self.timer_calls = 0
        self.timer_calls_skipped = 0

    def tagged(self, text: str) -> str:
        """``text`` for the console, with the world's name in front in a class server."""
        return f"[{self.label}] {text}" if self.label else text

    # -- membership ------------------------------------------------------
    @contextmanager
    def activate(self, overrides: NodeOverrides | None = None) -> Iterator[Bus]:
        """Nodes created inside this block join this bus (with ``overrides`` from a launch)."""
        token = _current_bus.set(self)
        otoken = _overrides.set(overrides)
        try:
            yield self
        finally:
            _overrides.reset(otoken)
            _current_bus.reset(token)

    def add_node(self, node: Node) -> None:
        if any(n.fully_qualified_name == node.fully_qualified_name for n in self.nodes):
            log.warning(
                "a node named %s already exists; ROS allows this but tools will be confused",
                node.fully_qualified_name,
            )
        self.nodes.append(node)
        self.graph_changed()
        for observer in self.observers:
            observer.node_added(node)

    def remove_node(self, node: Node) -> None:
        if node in self.nodes:
            self.nodes.remove(node)
            self.graph_changed()
            for observer in self.observers:
                observer.node_removed(node)

    def endpoint_added(self, endpoint: object) -> None:
        self.graph_changed()
        for observer in self.observers:
            observer.endpoint_added(endpoint)

    def endpoint_removed(self, endpoint: object) -> None:
        self.graph_changed()
        for observer in self.observers:
            observer.endpoint_removed(endpoint)

    def get_node(self, name: str) -> Node:
        fq = name if name.startswith("/") else "/" + name
        for node in self.nodes:
            if node.fully_qualified_name == fq:
                return node
        raise UnknownNodeError(name)

    def graph_changed(self) -> None:
        self.graph_version += 1
        for listener in list(self.graph_listeners):
            listener()

    # -- topics ----------------------------------------------------------
    def topic(self, name: str, msg_type: type[Message]) -> Topic:
        """The topic of that name, created with ``msg_type`` if new; a type conflict is an error."""
        topic = self.topics.get(name)
        if topic is None:
            topic = self.topics[name] = Topic(self, name, msg_type)
            self.graph_changed()
        elif topic.msg_type is not msg_type:
            raise TopicTypeError(f"{name} carries {topic.msg_type.TYPE}; {msg_type.TYPE} conflicts with it")
        return topic

    def set_tap(self, name: str, tap: Tap | None) -> None:
        """Have ``tap`` told of every message topic ``name`` delivers (now or once it exists), with
        its source; None removes it. One tap a topic: it must be quick and must not raise."""
        if tap is None:
            self.taps.pop(name, None)
        else:
            self.taps[name] = tap
        topic = self.topics.get(name)
        if topic is not None:
            topic.tap = tap

    def known_topics(self) -> dict[str, type[Message]]:
        """Every topic a bridge (Foxglove, rosbridge) can carry: this bus's, and each one only other
        processes declare, when this lab knows its type. A name other processes give two types is
        left out: those endpoints never meet on the wire, and a bridge's channel has one type."""
        known = {name: topic.msg_type for name, topic in self.topics.items()}
        remote = self.remote_topics
        if remote is not None:
            for name, type_names in remote.topic_types().items():
                if name in known or len(type_names) != 1:
                    continue
                try:
                    known[name] = get_type(next(iter(type_names)))
                except UnknownTypeError:
                    continue  # a student's own type, or one in DDS form only: nothing to decode it with
        return known

    def topic_type(self, name: str) -> type[Message] | None:
        """The type of topic ``name`` here, or else as other processes declare it (``known_topics``)."""
        topic = self.topics.get(name)
        return topic.msg_type if topic is not None else self.known_topics().get(name)

    @property
    def topics_version(self) -> tuple[int, int]:
        """Moves whenever ``known_topics`` may have changed."""
        remote = self.remote_topics
        return self.graph_version, remote.version if remote is not None else -1

    def get_topic(self, name: str) -> Topic:
        try:
            return self.topics[name]
        except KeyError:
            raise UnknownTopicError(name) from None

    def drop_topic_if_unused(self, topic: Topic) -> None:
        if not topic.publishers and not topic.subscriptions and self.topics.get(topic.name) is topic:
            del self.topics[topic.name]
            self.graph_changed()

    # -- services --------------------------------------------------------
    def service(self, name: str, srv_type: type[Service]) -> ServiceChannel:
        """The service of that name, created with ``srv_type`` if new; a type conflict is an error."""
        channel = self.services.get(name)
        if channel is None:
            channel = self.services[name] = ServiceChannel(self, name, srv_type)
            self.graph_changed()
        else:
            check_service_type(channel, srv_type)
        return channel

    def drop_service_if_unused(self, channel: ServiceChannel) -> None:
        if not channel.servers and not channel.clients and self.services.get(channel.name) is channel:
            del self.services[channel.name]
            self.graph_changed()

    def queue_call(self, call: PendingCall) -> None:
        """A request for a server of this bus; the executor runs its callback."""
        self._calls.append(call)
        self._wake()

    # -- scheduling ------------------------------------------------------
    def schedule(self, timer: Timer) -> None:
        heapq.heappush(self._timers, (timer.next_deadline_s, next(self._seq), timer))
        self._wake()

    def add_waker(self, waker: Callable[[], None]) -> None:
        self._wakers.append(waker)

    def remove_waker(self, waker: Callable[[], None]) -> None:
        if waker in self._wakers:
            self._wakers.remove(waker)

    def _wake(self) -> None:
        for waker in self._wakers:
            waker()

    def wake_threadsafe(self) -> None:
        """From any thread: have the executor run a pass soon (its pollers first)."""
        waker = self.threadsafe_waker
        if waker is not None:
            waker()

    def node_crashed(self, node: Node, exc: BaseException) -> None:
        self.graph_changed()
        for handler in list(self.crash_handlers):
            try:
                handler(node, exc)
            except Exception:  # a broken handler must not take the executor down
                log.exception("crash handler failed for %s", node.fully_qualified_name)
