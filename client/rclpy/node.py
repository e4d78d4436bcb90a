"""``rclpy.node.Node`` for a node process: the lab's bus node, joined to the graph over Zenoh."""

from __future__ import annotations

import weakref
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from node_runtime.bus import INTERNAL_TOPICS
from node_runtime.bus import Node as BusNode
from node_runtime.msgs import Message
from node_runtime.msgs import Service as ServiceType
from rclpy._context import Context, default_context
from rclpy._graph_queries import GraphQueries
from rclpy._parameters import ParameterAPI
from rclpy.callback_groups import CallbackGroup, GroupedCallback, MutuallyExclusiveCallbackGroup
from rclpy.client import Client
from rclpy.clock import ROSClock
from rclpy.event_handler import PublisherEventCallbacks, SubscriptionEventCallbacks
from rclpy.guard_condition import GuardCondition
from rclpy.logging import NodeRcutilsLogger
from rclpy.logging_service import LoggingService
from rclpy.parameter import Parameter
from rclpy.parameter_service import ParameterService
from rclpy.publisher import Publisher
from rclpy.qos import QoSProfile, WireQoS, keep_depth, qos_profile_services_default
from rclpy.qos_overriding_options import QoSOverridingOptions, declare_qos_parameters
from rclpy.rate import Rate
from rclpy.service import Service
from rclpy.subscription import Subscription
from rclpy.timer import Timer

if TYPE_CHECKING:
    from rclpy.executors import Executor


def _profile(qos_or_depth: Any) -> QoSProfile:
    """rclpy's rule: a profile, or a depth that makes a keep-last one."""
    if isinstance(qos_or_depth, QoSProfile):
        return qos_or_depth
    if isinstance(qos_or_depth, int) and not isinstance(qos_or_depth, bool):
        if qos_or_depth < 0:
            raise ValueError("history depth must be greater than or equal to zero")
        return QoSProfile(depth=qos_or_depth)
    raise TypeError(f"Expected QoSProfile or int, but received {type(qos_or_depth)!r}")


def _for_bus(qos: QoSProfile) -> WireQoS:
    """The profile as the bus takes it: the depth its queue keeps, and the reliability and
    durability the Zenoh transport writes into the endpoint's token."""
    return WireQoS(keep_depth(qos), int(qos.reliability), int(qos.durability))


class _LeftToTheStudent:
    """A name the lab's bus node reads from its own nodes (``node.state`` ...) that rclpy's Node
    does not have: on an rclpy Node it is the student's to set (a non-data descriptor, so the
    instance's own value wins), and until then reading it fails as on rclpy."""

    def __set_name__(self, owner: type, name: str) -> None:
        self._name = name

    def __get__(self, node: object, owner: type | None = None) -> Any:
        if node is None:
            return self
        raise AttributeError(f"'{type(node).__name__}' object has no attribute '{self._name}'")


class Node(GraphQueries, ParameterAPI, BusNode):  # type: ignore[misc]  # rclpy's parameter API over the bus's
    """Subclass it as the handout does: ``super().__init__('KeyboardManagerNode')``."""

    def __init__(
        self,
        node_name: str,
        *,
        context: Context | None = None,
        start_parameter_services: bool = True,
        parameter_overrides: list[Parameter] | None = None,
        allow_undeclared_parameters: bool = False,
        automatically_declare_parameters_from_overrides: bool = False,
        enable_logger_service: bool = False,
        **kwargs: Any,
    ) -> None:
        self._rcl_context = context or default_context
        bus, _executor = self._rcl_context.require()
        self.default_callback_group: CallbackGroup = MutuallyExclusiveCallbackGroup()
        self.guards: list[GuardCondition] = []
        super().__init__(node_name, context=bus, **kwargs)
        self._ros_clock = ROSClock(source=bus.clock)
        self._logger: NodeRcutilsLogger = NodeRcutilsLogger(self)
        overrides = self._rcl_context.args.parameters_for(self.fully_qualified_name)
        overrides.update({p.name: p.value for p in parameter_overrides or []})
        self._init_parameters(
            overrides, allow_undeclared_parameters, automatically_declare_parameters_from_overrides
        )
        if start_parameter_services:
            self._parameter_service = ParameterService(self)
        if enable_logger_service:
            self._logger_service = LoggingService(self)
        self._warn_if_name_taken()

    bus = state = origin = crash_reason = _LeftToTheStudent()

    # -- entities, with rclpy's keywords -----------------------------------------------------
    _publisher_class = Publisher
    _subscription_class = Subscription
    _timer_class = Timer
    _service_class = Service

    @property
    def context(self) -> Context:
        return self._rcl_context

    @property
    def executor(self) -> Executor | None:
        """The executor the node was last added to, or None (rclpy's)."""
        ref = self.__dict__.get("_executor_ref")
        return None if ref is None else ref()

    @executor.setter
    def executor(self, new_executor: Executor | None) -> None:
        """Move the node to ``new_executor`` (out of the one it was in), as rclpy does."""
        current = self.executor
        if current is new_executor:
            return
        if current is not None:
            current.remove_node(self)
        if new_executor is not None:
            new_executor.add_node(self)
        self._executor_ref = None if new_executor is None else weakref.ref(new_executor)

    def _grouped(
        self, callback: Callable[..., Any], group: CallbackGroup | None, entity: object
    ) -> GroupedCallback:
        group = group or self.default_callback_group
        group.add_entity(entity)
        return GroupedCallback(callback, group)

    def create_publisher(
        self,
        msg_type: type[Message],
        topic: str,
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: PublisherEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
        publisher_class: Any = None,
        hand_over: bool = False,
    ) -> Publisher[Any]:
        qos = _profile(qos_profile)
        if qos_overriding_options is not None:
            declare_qos_parameters(True, self, self.resolve_topic_name(topic), qos, qos_overriding_options)
        pub = super().create_publisher(msg_type, topic, _for_bus(qos), hand_over=hand_over)
        assert isinstance(pub, Publisher)
        pub.qos_profile = qos
        pub.callback_group = group = callback_group or self.default_callback_group
        group.add_entity(pub)
        if event_callbacks is not None or pub.topic_name not in INTERNAL_TOPICS:
            pub.event_handlers = (event_callbacks or PublisherEventCallbacks()).create_event_handlers(
                group, pub, topic
            )
        return pub

    def create_subscription(
        self,
        msg_type: type[Message],
        topic: str,
        callback: Callable[..., Any],
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: SubscriptionEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
        raw: bool = False,
        read_only: bool = False,
    ) -> Subscription[Any]:
        qos = _profile(qos_profile)
        if qos_overriding_options is not None:
            declare_qos_parameters(False, self, self.resolve_topic_name(topic), qos, qos_overriding_options)
        sub = super().create_subscription(msg_type, topic, callback, _for_bus(qos), read_only=read_only)
        assert isinstance(sub, Subscription)
        sub.qos_profile, sub.raw = qos, raw
        sub.callback = grouped = self._grouped(sub.adapt(callback), callback_group, sub)
        sub.callback_group = group = grouped.callback_group
        if event_callbacks is not None or sub.topic_name not in INTERNAL_TOPICS:
            sub.event_handlers = (event_callbacks or SubscriptionEventCallbacks()).create_event_handlers(
                group, sub, topic
            )
        return sub

    def create_timer(
        self,
        timer_period_sec: float,
        callback: Callable[..., Any] | None,
        callback_group: CallbackGroup | None = None,
        clock: Any = None,
        autostart: bool = True,
    ) -> Timer:
        timer = super().create_timer(timer_period_sec, lambda: None)
        assert isinstance(timer, Timer)
        timer.clock_source = clock or self._ros_clock
        timer.callback = grouped = self._grouped(timer.adapt(callback), callback_group, timer)
        timer.callback_group = grouped.callback_group
        if not autostart:
            timer.cancel()
        return timer

    def create_service(  # type: ignore[override]
        self,
        srv_type: type[ServiceType],
        srv_name: str,
        callback: Callable[[Any, Any], Any],
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
    ) -> Service:
        server = super().create_service(srv_type, srv_name, callback)
        assert isinstance(server, Service)
        server.callback = grouped = self._grouped(callback, callback_group, server)
        server.callback_group, server.qos_profile = grouped.callback_group, qos_profile
        server.given_name = srv_name
        return server

    def create_client(  # type: ignore[override]
        self,
        srv_type: type[ServiceType],
        srv_name: str,
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
    ) -> Client:
        self._check_alive()
        channel = self._bus.service(self.resolve_topic_name(srv_name), srv_type)
        client = Client(self, channel)
        client.given_name = srv_name
        client.callback_group = callback_group or self.default_callback_group
        client.qos_profile = qos_profile
        channel.clients.append(client)
        self.clients.append(client)
        self._bus.endpoint_added(client)
        client.callback_group.add_entity(client)
        return client

    def create_guard_condition(
        self, callback: Callable[[], Any] | None, callback_group: CallbackGroup | None = None
    ) -> GuardCondition:
        self._check_alive()
        guard = GuardCondition(self, callback, callback_group or self.default_callback_group)
        guard.callback_group.add_entity(guard)
        self.guards.append(guard)
        return guard

    def destroy_guard_condition(self, guard: GuardCondition) -> bool:
        if guard not in self.guards:
            return False
        guard.destroy()
        self.guards.remove(guard)
        return True

    def create_callback_group(self, group_type: type[CallbackGroup]) -> CallbackGroup:
        return group_type()

    def get_clock(self) -> ROSClock:  # type: ignore[override]
        return self._ros_clock

    def get_logger(self) -> NodeRcutilsLogger:
        return self._logger

    def destroy_node(self) -> bool:
        for guard in list(self.guards):
            self.destroy_guard_condition(guard)
        return super().destroy_node()

    def _warn_if_name_taken(self) -> None:
        bridge = self._rcl_context.bridge
        if bridge is None:
            return
        if any(n.name == self.fully_qualified_name for n in bridge.remote.nodes()):
            self.get_logger().warning(
                f"a node named {self.fully_qualified_name} already exists in the graph: ROS allows this, "
                "but tools and logs will mix the two up (give this one another name with -r __node:=NAME)"
            )

    def create_rate(self, frequency: float, clock: Any = None) -> Rate:
        return Rate(frequency, self._rcl_context)

    def destroy_rate(self, rate: Rate) -> bool:
        """rclpy's: the rate's sleep() fails after it; True unless it was destroyed already."""
        alive = not rate.destroyed
        rate.destroy()
        return alive

    def get_node_names(self) -> list[str]:
        names = [n.get_name() for n in self._bus.nodes]
        bridge = self._rcl_context.bridge
        if bridge is not None:
            names += [n.name.rsplit("/", 1)[1] for n in bridge.remote.nodes()]
        return sorted(set(names))

    def get_topic_names_and_types(self) -> list[tuple[str, list[str]]]:
        found: dict[str, set[str]] = {t.name: {t.msg_type.TYPE} for t in self._bus.topics.values()}
        bridge = self._rcl_context.bridge
        if bridge is not None:
            for e in bridge.remote.endpoints():
                if "/msg/" in e.type_name:
                    found.setdefault(e.name, set()).add(e.type_name)
        return sorted((name, sorted(types)) for name, types in found.items())

    def count_publishers(self, topic_name: str) -> int:
        return self._count(topic_name, "MP")

    def count_subscribers(self, topic_name: str) -> int:
        return self._count(topic_name, "MS")

    def _count(self, topic_name: str, kind: str) -> int:
        name = self.resolve_topic_name(topic_name)
        topic = self._bus.topics.get(name)
        local = 0 if topic is None else len(topic.publishers if kind == "MP" else topic.subscriptions)
        bridge = self._rcl_context.bridge
        remote = (
            0
            if bridge is None
            else sum(1 for e in bridge.remote.endpoints() if e.name == name and e.kind == kind)
        )
        return local + remote


__all__ = ["Node", "Parameter"]
