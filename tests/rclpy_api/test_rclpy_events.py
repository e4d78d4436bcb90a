"""rclpy.event_handler beyond what the differential programs show: deadline events on a clock the
test moves, the default incompatible-QoS warning, and matched events and counts across two
processes' Zenoh sessions (two contexts, each a peer of one router)."""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest
import rclpy
from rclpy.duration import Duration
from rclpy.event_handler import (
    PublisherEventCallbacks,
    QoSOfferedDeadlineMissedInfo,
    QoSRequestedDeadlineMissedInfo,
    SubscriptionEventCallbacks,
)
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import QoSProfile, ReliabilityPolicy
from std_msgs.msg import String
from support.app import free_port

from node_runtime.bus import ManualClock
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.session import open_session

WAIT_S = 5.0


def run_ready(executor: SingleThreadedExecutor) -> None:
    """Run what is ready now, without waiting (a round runs each ready entity once)."""
    for _ in range(5):
        executor.spin_once(timeout_sec=0)


@pytest.fixture
def ctx(monkeypatch: pytest.MonkeyPatch) -> Iterator[tuple[rclpy.Context, ManualClock]]:
    monkeypatch.setenv("ROS2LAB_NO_ZENOH", "1")
    context = rclpy.Context()
    with rclpy.init(args=[], context=context):
        clock = ManualClock(100.0)
        assert context.bus is not None
        context.bus.clock = clock
        yield context, clock


def test_a_deadline_missed_counts_each_period_without_a_message(
    ctx: tuple[rclpy.Context, ManualClock],
) -> None:
    context, clock = ctx
    node = Node("watch", context=context)
    qos = QoSProfile(depth=1, deadline=Duration(seconds=0.1))
    requested: list[QoSRequestedDeadlineMissedInfo] = []
    offered: list[QoSOfferedDeadlineMissedInfo] = []
    pub = node.create_publisher(
        String, "beat", qos, event_callbacks=PublisherEventCallbacks(deadline=offered.append)
    )
    node.create_subscription(
        String,
        "beat",
        lambda _msg: None,
        qos,
        event_callbacks=SubscriptionEventCallbacks(deadline=requested.append),
    )
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    clock.set(100.05)
    pub.publish(String(data="on time"))
    clock.set(100.1)
    run_ready(executor)
    assert (requested, offered) == ([], [])  # a message came within the period
    clock.set(100.2)
    run_ready(executor)
    clock.set(100.3)
    run_ready(executor)
    assert [(e.total_count, e.total_count_change) for e in requested] == [(1, 1), (2, 1)]
    assert [type(e) for e in offered] == [QoSOfferedDeadlineMissedInfo] * 2


def test_an_incompatible_subscription_is_warned_of_as_rclpy_words_it(
    ctx: tuple[rclpy.Context, ManualClock], capsys: pytest.CaptureFixture[str]
) -> None:
    context, _clock = ctx
    node = Node("qos_talker", context=context)
    node.create_publisher(String, "chatter", QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT))
    node.create_subscription(
        String,
        "chatter",
        lambda _msg: None,
        1,
        event_callbacks=SubscriptionEventCallbacks(use_default_callbacks=False),
    )
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    run_ready(executor)
    lines = [line for line in capsys.readouterr().err.splitlines() if "incompatible" in line]
    assert len(lines) == 1, lines  # the publisher's default warning; the subscription asked for none
    assert lines[0].startswith("[WARN]") and lines[0].endswith(
        "[qos_talker]: New subscription discovered on topic 'chatter', requesting incompatible QoS. "
        "No messages will be sent to it. Last incompatible policy: RELIABILITY"
    )


@pytest.fixture
def two_processes(monkeypatch: pytest.MonkeyPatch) -> Iterator[tuple[rclpy.Context, rclpy.Context]]:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    router: Any = open_session(ZenohSettings(mode="router", listen=(endpoint,)))
    monkeypatch.delenv("ROS2LAB_NO_ZENOH", raising=False)
    monkeypatch.setenv("ROS_DOMAIN_ID", "0")
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", f"connect/endpoints={json.dumps([endpoint])}")
    first, second = rclpy.Context(), rclpy.Context()
    try:
        with rclpy.init(args=[], context=first), rclpy.init(args=[], context=second):
            yield first, second
    finally:
        router.close()


def spin_until(executors: list[SingleThreadedExecutor], condition: Callable[[], bool], what: str) -> None:
    end = time.monotonic() + WAIT_S
    while not condition():
        if time.monotonic() > end:
            pytest.fail(f"timed out after {WAIT_S} s waiting for {what}")
        for executor in executors:
            executor.spin_once(timeout_sec=0.02)


def test_a_subscription_in_another_process_matches_and_unmatches(
    two_processes: tuple[rclpy.Context, rclpy.Context],
) -> None:
    first, second = two_processes
    talker, listener = Node("talker", context=first), Node("listener", context=second)
    matched: list[Any] = []
    pub = talker.create_publisher(
        String, "chatter", 10, event_callbacks=PublisherEventCallbacks(matched=matched.append)
    )
    executors = [SingleThreadedExecutor(context=first), SingleThreadedExecutor(context=second)]
    executors[0].add_node(talker)
    executors[1].add_node(listener)
    sub = listener.create_subscription(String, "chatter", lambda _msg: None, 10)
    listener.create_subscription(String, "other", lambda _msg: None, 10)  # another topic: no match
    spin_until(executors, lambda: bool(matched) and matched[-1].current_count == 1, "the remote match")
    assert pub.get_subscription_count() == 1
    assert (matched[-1].total_count, matched[-1].current_count_change) == (1, 1)
    spin_until(executors, lambda: sub.get_publisher_count() == 1, "the listener seeing the talker")
    listener.destroy_subscription(sub)
    spin_until(executors, lambda: matched[-1].current_count == 0, "the remote unmatch")
    assert (matched[-1].total_count, matched[-1].current_count_change) == (1, -1)
    assert pub.get_subscription_count() == 0
