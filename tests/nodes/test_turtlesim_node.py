"""turtlesim_node and mimic on the bus: turtlesim's names, its services, its parameters, its lines."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from node_runtime.bus import Bus, Executor, ManualClock, Node, NodeOverrides, Parameter
from node_runtime.msgs import Message, Twist
from node_runtime.msgs.generated.action_msgs import CancelGoal, GoalInfo, GoalStatus
from node_runtime.msgs.generated.std_srvs import Empty
from node_runtime.msgs.generated.turtlesim import (
    Color,
    Kill,
    Pose,
    RotateAbsolute,
    SetPen,
    Spawn,
    TeleportAbsolute,
)
from node_runtime.msgs.generated.unique_identifier_msgs import UUID
from server.packages.turtlesim.mimic import MimicNode
from server.packages.turtlesim.turtlesim_node import TurtlesimNode

from .conftest import Recorder

Record = Callable[[dict[str, type[Message]]], Recorder]
START = "Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]"


def call(bus: Bus, executor: Executor, srv: Any, service: str, **request: Any) -> Any:
    caller = next((n for n in bus.nodes if n.get_name() == "caller"), None) or Node("caller", context=bus)
    future = caller.create_client(srv, service).call_async(srv.Request(**request))
    executor.spin_some()
    assert future.done()
    return future.result()


def test_turtlesim_node_graph_and_first_lines_are_turtlesims(
    bus: Bus, executor: Executor, record: Record
) -> None:
    rec = record({"/turtle1/pose": Pose, "/turtle1/color_sensor": Color})
    with bus.activate():
        node = TurtlesimNode()
    executor.spin_some()
    assert node.get_fully_qualified_name() == "/turtlesim"
    assert rec.logs("turtlesim") == ["Starting turtlesim with node name /turtlesim", START]
    assert {
        "/spawn",
        "/kill",
        "/clear",
        "/reset",
        "/turtle1/set_pen",
        "/turtle1/teleport_absolute",
        "/turtle1/teleport_relative",
    } <= set(bus.services)
    assert bus.get_topic("/turtle1/cmd_vel").msg_type is Twist
    executor.spin_until(1.0)
    assert len(rec.got["/turtle1/pose"]) == 62  # a frame every 16 ms
    pose = rec.got["/turtle1/pose"][-1][1]
    assert (pose.x, pose.y, pose.theta) == pytest.approx((5.544445, 5.544445, 0.0), abs=1e-6)
    assert rec.got["/turtle1/color_sensor"][-1][1] == Color(r=255, g=255, b=255)


def test_turtlesim_node_in_a_namespace_names_everything_below_it(bus: Bus) -> None:
    with bus.activate(NodeOverrides(name="sim", namespace="/turtlesim1")):
        TurtlesimNode()
    assert {"/turtlesim1/spawn", "/turtlesim1/turtle1/set_pen"} <= set(bus.services)
    assert bus.get_topic("/turtlesim1/turtle1/pose").msg_type is Pose


def test_turtlesim_node_cmd_vel_moves_the_turtle_for_a_second(
    bus: Bus, clock: ManualClock, executor: Executor, record: Record
) -> None:
    rec = record({"/turtle1/pose": Pose})
    with bus.activate():
        TurtlesimNode()
    Node("teleop", context=bus).create_publisher(Twist, "/turtle1/cmd_vel", 10).publish(
        Twist(linear=Twist().linear.__class__(x=2.0))
    )
    executor.spin_until(3.0)
    poses = [m for _, m in rec.got["/turtle1/pose"]]
    assert max(p.linear_velocity for p in poses) == 2.0
    assert poses[-1].linear_velocity == 0.0
    assert poses[-1].x == pytest.approx(5.544445 + 2.0 * 62 * 0.016, abs=1e-5)  # the frames up to 0.992 s


def test_turtlesim_node_teleport_spawn_kill_and_their_errors(
    bus: Bus, executor: Executor, record: Record
) -> None:
    rec = record({"/turtle1/pose": Pose})
    with bus.activate():
        node = TurtlesimNode()
    call(bus, executor, TeleportAbsolute, "/turtle1/teleport_absolute", x=1.0, y=2.0, theta=0.5)
    executor.spin_for(0.016)
    pose = rec.got["/turtle1/pose"][-1][1]
    assert (pose.x, pose.y, pose.theta) == pytest.approx((1.0, 2.0, 0.5))
    assert call(bus, executor, Spawn, "/spawn", x=2.0, y=2.0, theta=0.2, name="").name == "turtle2"
    assert "/turtle2/pose" in bus.topics and "/turtle2/set_pen" in bus.services
    assert call(bus, executor, Spawn, "/spawn", x=2.0, y=2.0, name="turtle2").name == ""
    assert call(bus, executor, Spawn, "/spawn", name="bad name").name == ""
    call(bus, executor, Kill, "/kill", name="turtle2")
    call(bus, executor, Kill, "/kill", name="turtle2")
    assert "/turtle2/pose" not in bus.topics and "/turtle2/set_pen" not in bus.services
    assert sorted(node.world.turtles) == ["turtle1"]
    assert rec.logs("turtlesim")[2:] == [
        "Spawning turtle [turtle2] at x=[2.000000], y=[2.000000], theta=[0.200000]",
        "A turtle named [turtle2] already exists",
        "A turtle cannot be named [bad name]: invalid topic name 'bad name/pose': token 'bad name' may contain "
        "only letters, digits and underscores",
        "Tried to kill turtle [turtle2], which does not exist",
    ]


def test_turtlesim_node_set_pen_colors_the_path_and_reset_starts_over(
    bus: Bus, executor: Executor, record: Record
) -> None:
    rec = record({"/turtle1/color_sensor": Color})
    with bus.activate():
        node = TurtlesimNode()
    call(bus, executor, SetPen, "/turtle1/set_pen", r=255, g=0, b=0, width=5, off=0)
    call(bus, executor, TeleportAbsolute, "/turtle1/teleport_absolute", x=1.0, y=1.0)
    call(bus, executor, TeleportAbsolute, "/turtle1/teleport_absolute", x=1.0, y=3.0)
    call(bus, executor, TeleportAbsolute, "/turtle1/teleport_absolute", x=1.0, y=2.0)
    executor.spin_for(0.032)
    assert rec.got["/turtle1/color_sensor"][-1][1] == Color(r=255, g=0, b=0)
    call(bus, executor, Spawn, "/spawn", x=3.0, y=3.0, name="")
    call(bus, executor, Empty, "/reset")
    assert sorted(node.world.turtles) == ["turtle1"] and "/turtle2/pose" not in bus.topics
    assert rec.logs("turtlesim")[-2:] == ["Resetting turtlesim.", START]


def test_turtlesim_node_background_parameters_are_turtlesims(bus: Bus, executor: Executor) -> None:
    with bus.activate(NodeOverrides(parameters={"background_g": 10})):
        node = TurtlesimNode()
    assert node.background == (69, 10, 255)
    assert node.describe_parameter("background_r").description == "Red channel of the background color"
    node.set_parameters([Parameter("background_r", 150)])
    executor.spin_some()
    assert node.background == (150, 10, 255)  # the window would repaint now
    with pytest.raises(ValueError, match="background_b"):
        node.set_parameters([Parameter("background_b", 256)])
    assert node.get_parameter("background_b").value == 255


def test_turtlesim_node_holonomic_turtle_moves_sideways(bus: Bus, executor: Executor, record: Record) -> None:
    rec = record({"/turtle1/pose": Pose})
    with bus.activate(NodeOverrides(parameters={"holonomic": True})):
        TurtlesimNode()
    cmd = Twist()
    cmd.linear.y = 1.0
    Node("teleop", context=bus).create_publisher(Twist, "/turtle1/cmd_vel", 10).publish(cmd)
    executor.spin_until(0.5)
    pose = rec.got["/turtle1/pose"][-1][1]
    assert pose.x == pytest.approx(5.544445, abs=1e-5) and pose.y > 5.9


def test_mimic_turns_a_pose_into_the_same_velocities(bus: Bus, executor: Executor, record: Record) -> None:
    rec = record({"/output/cmd_vel": Twist})
    with bus.activate():
        node = MimicNode()
    assert node.get_name() == "turtle_mimic"
    pub = Node("leader", context=bus).create_publisher(Pose, "/input/pose", 10)
    pub.publish(Pose(x=1.0, linear_velocity=2.0, angular_velocity=-1.5))
    executor.spin_some()
    twist = rec.got["/output/cmd_vel"][-1][1]
    assert (twist.linear.x, twist.angular.z, twist.linear.y) == (2.0, -1.5, 0.0)


def send_goal(bus: Bus, executor: Executor, theta: float, goal_id: int) -> tuple[Any, Any]:
    """A rotate_absolute goal to turtle1, as an ActionClient sends it; (its acceptance, its result's future)."""
    impl = RotateAbsolute.Impl
    uuid = UUID(uuid=[goal_id] * 16)
    accepted = call(
        bus,
        executor,
        impl.SendGoalService,
        "/turtle1/rotate_absolute/_action/send_goal",
        goal_id=uuid,
        goal=RotateAbsolute.Goal(theta=theta),
    )
    caller = next(n for n in bus.nodes if n.get_name() == "caller")
    result = caller.create_client(impl.GetResultService, "/turtle1/rotate_absolute/_action/get_result")
    return accepted, result.call_async(impl.GetResultService.Request(goal_id=uuid))


def test_turtlesim_node_rotate_absolute_turns_to_the_goal_with_feedback(
    bus: Bus, executor: Executor, record: Record
) -> None:
    rec = record(
        {
            "/turtle1/rotate_absolute/_action/feedback": RotateAbsolute.Impl.FeedbackMessage,
            "/turtle1/pose": Pose,
        }
    )
    with bus.activate():
        TurtlesimNode()
    accepted, result = send_goal(bus, executor, 1.0, goal_id=7)
    assert accepted.accepted
    executor.spin_for(0.5)
    assert not result.done()
    executor.spin_for(1.0)
    assert result.done()
    answer = result.result()
    assert answer.status == GoalStatus.STATUS_SUCCEEDED
    assert answer.result.delta == pytest.approx(-1.0, abs=0.02)
    remaining = [m.feedback.remaining for _, m in rec.got["/turtle1/rotate_absolute/_action/feedback"]]
    assert remaining[0] == pytest.approx(1.0) and remaining == sorted(remaining, reverse=True)
    assert rec.got["/turtle1/pose"][-1][1].theta == pytest.approx(1.0, abs=0.02)
    assert rec.logs("turtlesim")[-1] == "Rotation goal completed successfully"


def test_turtlesim_node_rotate_absolute_aborted_by_a_new_goal_and_a_velocity(
    bus: Bus, executor: Executor, record: Record
) -> None:
    rec = record({})
    with bus.activate():
        TurtlesimNode()
    _, first = send_goal(bus, executor, 3.0, goal_id=1)
    _, second = send_goal(bus, executor, -3.0, goal_id=2)
    executor.spin_for(0.1)
    assert first.result().status == GoalStatus.STATUS_ABORTED and not second.done()
    Node("teleop", context=bus).create_publisher(Twist, "/turtle1/cmd_vel", 10).publish(Twist())
    executor.spin_for(0.1)
    assert second.result().status == GoalStatus.STATUS_ABORTED
    assert rec.logs("turtlesim")[-2:] == [
        "Rotation goal received before a previous goal finished. Aborting previous goal",
        "Velocity command received during rotation goal. Aborting goal",
    ]


def test_turtlesim_node_rotate_absolute_canceled_stops_the_turtle(
    bus: Bus, executor: Executor, record: Record
) -> None:
    rec = record({"/turtle1/pose": Pose})
    with bus.activate():
        TurtlesimNode()
    _, result = send_goal(bus, executor, 3.0, goal_id=3)
    executor.spin_for(0.2)
    unknown = call(
        bus,
        executor,
        CancelGoal,
        "/turtle1/rotate_absolute/_action/cancel_goal",
        goal_info=GoalInfo(goal_id=UUID(uuid=[9] * 16)),
    )
    assert (unknown.return_code, unknown.goals_canceling) == (2, [])
    canceling = call(
        bus,
        executor,
        CancelGoal,
        "/turtle1/rotate_absolute/_action/cancel_goal",
        goal_info=GoalInfo(goal_id=UUID(uuid=[3] * 16)),
    )
    assert canceling.return_code == 0 and len(canceling.goals_canceling) == 1
    executor.spin_for(0.1)
    assert result.result().status == GoalStatus.STATUS_CANCELED
    assert rec.got["/turtle1/pose"][-1][1].angular_velocity == 0.0
    assert rec.logs("turtlesim")[-1] == "Rotation goal canceled"
