"""Broadcasters and a listener on nodes of one process (no Zenoh): the topics and QoS tf2_ros
uses, the static broadcaster's set of frames, and a buffer filled by the listener."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
import rclpy
from rclpy.duration import Duration
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.time import Time
from tf2_msgs.msg import TFMessage
from tf2_msgs.srv import FrameGraph
from tf2_ros import Buffer, StaticTransformBroadcaster, TransformBroadcaster, TransformListener

from .frames import stamped, xyz

SPINS = 50  # only bounds a broken run: each test stops spinning once what it waits for is there

TRANSIENT_LOCAL, VOLATILE, RELIABLE = 1, 2, 1


@pytest.fixture
def node(monkeypatch: pytest.MonkeyPatch) -> Iterator[Node]:
    monkeypatch.setenv("ROS2LAB_NO_ZENOH", "1")
    ctx = rclpy.Context()
    with rclpy.init(args=[], context=ctx):
        yield Node("tf_test", context=ctx)


def spin_until(executor: SingleThreadedExecutor, done: object) -> None:
    for _ in range(SPINS):
        if callable(done) and done():
            return
        executor.spin_once(timeout_sec=0.0)
    raise AssertionError("what the test waited for never came")


def test_broadcasters_and_listener_use_tf2_ros_topics_and_qos(node: Node) -> None:
    dynamic = TransformBroadcaster(node)
    static = StaticTransformBroadcaster(node)
    listener = TransformListener(Buffer(), node)
    assert (dynamic.pub_tf.topic_name, dynamic.pub_tf.qos.depth) == ("/tf", 100)
    assert dynamic.pub_tf.qos.durability in (0, VOLATILE)
    assert (static.pub_tf.topic_name, static.pub_tf.qos.depth) == ("/tf_static", 1)
    assert (static.pub_tf.qos.durability, static.pub_tf.qos.reliability) == (TRANSIENT_LOCAL, RELIABLE)
    assert (listener.tf_sub.topic_name, listener.tf_sub.qos.depth, listener.tf_sub.qos.durability) == (
        "/tf",
        100,
        VOLATILE,
    )
    assert (listener.tf_static_sub.topic_name, listener.tf_static_sub.qos.durability) == (
        "/tf_static",
        TRANSIENT_LOCAL,
    )


def test_a_listener_fills_its_buffer_from_both_topics(node: Node) -> None:
    buffer = Buffer()
    TransformListener(buffer, node)
    executor = SingleThreadedExecutor(context=node._rcl_context)
    executor.add_node(node)
    StaticTransformBroadcaster(node).sendTransform(stamped("base", "laser", 0.0, (0.2, 0.0, 0.1)))
    TransformBroadcaster(node).sendTransform(
        [stamped("odom", "base", 3.0, (1.0, 0.0, 0.0)), stamped("odom", "base", 4.0, (2.0, 0.0, 0.0))]
    )
    spin_until(executor, lambda: buffer.can_transform("odom", "laser", Time(seconds=3.5)))
    assert xyz(buffer.lookup_transform("odom", "laser", Time(seconds=3.5))) == pytest.approx((1.7, 0.0, 0.1))
    assert "broadcaster: 'default_authority'" in buffer.all_frames_as_yaml()


def test_a_static_broadcaster_resends_all_its_frames_and_replaces_a_child_sent_again(node: Node) -> None:
    heard: list[TFMessage] = []
    node.create_subscription(TFMessage, "/tf_static", heard.append, 10)
    executor = SingleThreadedExecutor(context=node._rcl_context)
    executor.add_node(node)
    static = StaticTransformBroadcaster(node)
    static.sendTransform(stamped("base", "laser", 0.0, (0.2, 0.0, 0.0)))
    static.sendTransform([stamped("base", "camera", 0.0), stamped("base", "imu", 0.0)])
    static.sendTransform(stamped("base", "laser", 0.0, (0.5, 0.0, 0.0)))
    spin_until(executor, lambda: len(heard) == 3)
    assert [[t.child_frame_id for t in m.transforms] for m in heard] == [
        ["laser"],
        ["laser", "camera", "imu"],
        ["laser", "camera", "imu"],
    ]
    assert heard[-1].transforms[0].transform.translation.x == 0.5


def test_a_task_awaiting_a_transform_resumes_once_the_listener_hears_it(node: Node) -> None:
    """examples_tf2_py's async pattern: the coroutine waits, the executor keeps spinning."""
    buffer = Buffer()
    TransformListener(buffer, node)
    executor = SingleThreadedExecutor(context=node._rcl_context)
    executor.add_node(node)

    async def find_robot() -> object:
        return await buffer.lookup_transform_async("world", "robot", Time())

    task = executor.create_task(find_robot)
    executor.spin_once(timeout_sec=0.0)
    assert not task.done()
    TransformBroadcaster(node).sendTransform(stamped("world", "robot", 2.0, (5.0, 0.0, 0.0)))
    spin_until(executor, task.done)
    found = task.result()
    assert found is not None and xyz(found) == (5.0, 0.0, 0.0)  # type: ignore[arg-type]


def test_a_buffer_given_a_node_serves_its_frames_as_yaml(node: Node) -> None:
    buffer = Buffer(node=node)
    buffer.set_transform_static(stamped("base", "laser", 0.0), "urdf")
    client = node.create_client(FrameGraph, "tf2_frames")
    executor = SingleThreadedExecutor(context=node._rcl_context)
    executor.add_node(node)
    future = client.call_async(FrameGraph.Request())
    spin_until(executor, future.done)
    answer = future.result()
    assert answer is not None and answer.frame_yaml == buffer.all_frames_as_yaml()
    assert answer.frame_yaml.startswith("laser: \n  parent: 'base'\n  broadcaster: 'urdf'\n")


def test_a_listener_with_its_own_spin_thread_feeds_a_lookup_that_blocks_the_main_thread(node: Node) -> None:
    """The blocking pattern: nobody spins but the listener's thread, the main thread waits."""
    buffer = Buffer()
    listener = TransformListener(buffer, node, spin_thread=True)
    TransformBroadcaster(node).sendTransform(stamped("world", "robot", 1.0, (0.0, 0.0, 2.0)))
    found = buffer.lookup_transform("world", "robot", Time(), timeout=Duration(seconds=10.0))
    assert xyz(found) == (0.0, 0.0, 2.0)
    listener.executor.shutdown()
    listener.dedicated_listener_thread.join(10.0)
    assert not listener.dedicated_listener_thread.is_alive()


def test_a_listener_made_after_a_static_broadcaster_of_its_own_process_gets_its_frames(node: Node) -> None:
    StaticTransformBroadcaster(node).sendTransform(stamped("base", "laser", 0.0, (0.2, 0.0, 0.1)))
    buffer = Buffer()
    TransformListener(buffer, node)  # after the one message was sent
    executor = SingleThreadedExecutor(context=node._rcl_context)
    executor.add_node(node)
    spin_until(executor, lambda: buffer.can_transform("base", "laser", Time()))
    assert xyz(buffer.lookup_transform("base", "laser", Time())) == (0.2, 0.0, 0.1)
