"""rclpy.service_introspection in one process: a service's and a client's events on
``<service>/_service_event``, with the contents, with the metadata only, and none once off."""

from __future__ import annotations

import time
from collections.abc import Iterator
from typing import Any

import pytest
import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import qos_profile_system_default
from rclpy.service_introspection import ServiceIntrospectionState, event_message
from std_srvs.srv import SetBool

WAIT_S = 5.0


@pytest.fixture
def node(monkeypatch: pytest.MonkeyPatch) -> Iterator[Node]:
    monkeypatch.setenv("ROS2LAB_NO_ZENOH", "1")
    context = rclpy.Context()
    with rclpy.init(args=[], context=context):
        yield Node("introspected", context=context)


def call(executor: SingleThreadedExecutor, client: Any, events: list[Any], count: int) -> Any:
    future = client.call_async(SetBool.Request(data=True))
    end = time.monotonic() + WAIT_S
    while not (future.done() and len(events) >= count):
        assert time.monotonic() < end, f"no answer and {count} events within {WAIT_S} s ({len(events)} came)"
        executor.spin_once(timeout_sec=0.05)
    return future.result()


def test_a_service_and_its_client_publish_each_step_of_a_call(node: Node) -> None:
    event_type = event_message(SetBool)
    assert event_type.TYPE == "std_srvs/srv/SetBool_Event" and event_message(SetBool) is event_type
    service = node.create_service(
        SetBool, "switch", lambda req, res: SetBool.Response(success=req.data, message="done")
    )
    client = node.create_client(SetBool, "switch")
    events: list[Any] = []
    node.create_subscription(event_type, "/switch/_service_event", events.append, 10)
    executor = SingleThreadedExecutor(context=node.context)
    executor.add_node(node)
    clock = node.get_clock()
    for entity in (service, client):
        entity.configure_introspection(clock, qos_profile_system_default, ServiceIntrospectionState.CONTENTS)
    assert node.count_publishers("/switch/_service_event") == 2
    assert call(executor, client, events, 4).message == "done"
    steps = sorted(
        (
            e.info.event_type,
            e.info.sequence_number,
            [r.data for r in e.request],
            [r.message for r in e.response],
        )
        for e in events
    )
    assert steps == [(0, 1, [True], []), (1, 1, [True], []), (2, 1, [], ["done"]), (3, 1, [], ["done"])]
    client_gids = {bytes(e.info.client_gid) for e in events if e.info.event_type in (0, 3)}
    assert len(client_gids) == 1 and len(next(iter(client_gids))) == 16

    events.clear()
    for entity in (service, client):
        entity.configure_introspection(clock, qos_profile_system_default, ServiceIntrospectionState.METADATA)
    call(executor, client, events, 4)
    assert sorted(
        (e.info.event_type, e.info.sequence_number, len(e.request), len(e.response)) for e in events
    ) == [(kind, 2, 0, 0) for kind in range(4)]

    for entity in (service, client):
        entity.configure_introspection(clock, qos_profile_system_default, ServiceIntrospectionState.OFF)
    assert node.count_publishers("/switch/_service_event") == 0
    events.clear()
    call(executor, client, events, 0)
    marker = node.create_publisher(event_type, "/switch/_service_event", 10)
    sent = event_type()
    sent.info.sequence_number = -1
    marker.publish(sent)  # the next event to come is this one: none came from the call
    end = time.monotonic() + WAIT_S
    while not events:
        assert time.monotonic() < end, "the marker did not arrive"
        executor.spin_once(timeout_sec=0.05)
    assert [e.info.sequence_number for e in events] == [-1]
