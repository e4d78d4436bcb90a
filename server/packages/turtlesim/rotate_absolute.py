"""A turtle's ``rotate_absolute`` action, laid out on the bus as rcl_action lays out an action:
``NAME/rotate_absolute/_action/`` ``send_goal``, ``cancel_goal`` and ``get_result`` services, and
``feedback`` and ``status`` topics, so ``ros2lab action send_goal`` and a student's ActionClient
reach it.

As turtlesim's, it accepts every goal and executes it at once; a new goal aborts the one before,
and so does a velocity command; a cancel is accepted. Each frame of the turtle it sends the
remaining angle as feedback, and when the turtle faces the goal it succeeds with the angle turned.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from node_runtime.bus import Future, ServiceServer
from node_runtime.bus.endpoints import TRANSIENT_LOCAL
from node_runtime.msgs import Message
from node_runtime.msgs.generated.action_msgs import (
    CancelGoal,
    CancelGoal_Request,
    CancelGoal_Response,
    GoalInfo,
    GoalStatus,
    GoalStatusArray,
)
from node_runtime.msgs.generated.turtlesim import (
    RotateAbsolute,
    RotateAbsolute_Feedback,
    RotateAbsolute_Result,
)
from sim.turtlesim import Rotation, Turtle

if TYPE_CHECKING:
    from node_runtime.bus import Node
    from node_runtime.bus.services import PendingCall

KEPT_GOALS = 16  # ended goals whose result can still be asked for
ERROR_NONE, ERROR_UNKNOWN_GOAL_ID = 0, 2  # CancelGoal's return codes


@dataclass(frozen=True)
class StatusQoS:
    """The action status topic's QoS: the last status kept for late subscribers."""

    depth: int = 1
    durability: int = TRANSIENT_LOCAL


class ResultServer(ServiceServer):
    """``get_result``: answered when the goal ends, not when asked."""

    def __init__(self, node: Node, name: str, on_call: Callable[[Message, Future[Message]], None]) -> None:
        channel = node.bus.service(node.resolve_topic_name(name), RotateAbsolute.Impl.GetResultService)
        super().__init__(node, channel, lambda _request, response: response)
        self.on_call = on_call
        channel.servers.append(self)
        node.services.append(self)
        node.bus.endpoint_added(self)

    def answer(self, call: PendingCall) -> None:
        self.on_call(call.request, call.future)


@dataclass
class Goal:
    info: GoalInfo
    status: int = GoalStatus.STATUS_EXECUTING
    delta_rad: float = 0.0
    waiting: list[Future[Message]] = field(default_factory=list)

    @property
    def key(self) -> bytes:
        return bytes(self.info.goal_id.uuid)


class RotateAbsoluteServer:
    def __init__(self, node: Node, turtle_name: str, turtle: Callable[[], Turtle]) -> None:
        self.node, self.turtle = node, turtle
        base = f"{turtle_name}/rotate_absolute/_action/"
        impl = RotateAbsolute.Impl
        self.services: list[ServiceServer] = [
            node.create_service(impl.SendGoalService, base + "send_goal", self.on_send_goal),
            node.create_service(CancelGoal, base + "cancel_goal", self.on_cancel_goal),
            ResultServer(node, base + "get_result", self.on_get_result),
        ]
        self.feedback_pub = node.create_publisher(impl.FeedbackMessage, base + "feedback", 10)
        self.status_pub = node.create_publisher(GoalStatusArray, base + "status", StatusQoS())
        self.goals: dict[bytes, Goal] = {}
        self.active: Goal | None = None

    def on_send_goal(self, request: Any, response: Any) -> Any:
        if self.active is not None:
            self.node.get_logger().warning(
                "Rotation goal received before a previous goal finished. Aborting previous goal"
            )
            self._end(self.active, GoalStatus.STATUS_ABORTED)
        stamp = self.node.get_clock().now().to_msg()
        goal = Goal(GoalInfo(goal_id=request.goal_id, stamp=stamp))
        self.goals[goal.key] = self.active = goal
        self.turtle().rotate_to(request.goal.theta)
        while len(self.goals) > KEPT_GOALS:
            del self.goals[next(iter(self.goals))]
        response.accepted, response.stamp = True, stamp
        self._publish_status()
        return response

    def on_cancel_goal(
        self, request: CancelGoal_Request, response: CancelGoal_Response
    ) -> CancelGoal_Response:
        goal = self.active
        wanted = bytes(request.goal_info.goal_id.uuid)
        if goal is None or (any(wanted) and wanted != goal.key):
            response.return_code = ERROR_UNKNOWN_GOAL_ID
            return response
        goal.status = GoalStatus.STATUS_CANCELING
        response.return_code, response.goals_canceling = ERROR_NONE, [goal.info]
        self._publish_status()
        return response

    def on_get_result(self, request: Message, future: Future[Message]) -> None:
        goal = self.goals.get(bytes(request.goal_id.uuid))  # type: ignore[attr-defined]
        if goal is None:
            future.set_result(RotateAbsolute.Impl.GetResultService.Response(status=GoalStatus.STATUS_UNKNOWN))
        elif goal.status in (GoalStatus.STATUS_EXECUTING, GoalStatus.STATUS_CANCELING):
            goal.waiting.append(future)
        else:
            future.set_result(self._result(goal))

    def before_frame(self) -> None:
        """A goal being canceled ends before the turtle's next frame, the turtle stopped."""
        if self.active is not None and self.active.status == GoalStatus.STATUS_CANCELING:
            self.node.get_logger().info("Rotation goal canceled")
            self.turtle().stop()
            self._end(self.active, GoalStatus.STATUS_CANCELED)

    def after_frame(self, rotation: Rotation | None) -> None:
        goal = self.active
        if goal is None or rotation is None:
            return
        goal.delta_rad = rotation.delta_rad
        feedback = RotateAbsolute_Feedback(remaining=rotation.remaining_rad)
        self.feedback_pub.publish(
            RotateAbsolute.Impl.FeedbackMessage(goal_id=goal.info.goal_id, feedback=feedback)
        )
        if rotation.done:
            self.node.get_logger().info("Rotation goal completed successfully")
            self._end(goal, GoalStatus.STATUS_SUCCEEDED)

    def abort(self) -> None:
        """A velocity command came: the goal under way ends."""
        if self.active is not None:
            self.node.get_logger().warning("Velocity command received during rotation goal. Aborting goal")
            self.turtle().heading_goal_rad = None
            self._end(self.active, GoalStatus.STATUS_ABORTED)

    def _end(self, goal: Goal, status: int) -> None:
        goal.status = status
        if goal is self.active:
            self.active = None
        for future in goal.waiting:
            future.set_result(self._result(goal))
        goal.waiting.clear()
        self._publish_status()

    def _result(self, goal: Goal) -> Message:
        result = RotateAbsolute_Result(delta=goal.delta_rad)
        return RotateAbsolute.Impl.GetResultService.Response(status=goal.status, result=result)

    def _publish_status(self) -> None:
        statuses = [GoalStatus(goal_info=g.info, status=g.status) for g in self.goals.values()]
        self.status_pub.publish(GoalStatusArray(status_list=statuses))

    def destroy(self) -> None:
        for goal in list(self.goals.values()):
            if goal.waiting:
                self._end(goal, GoalStatus.STATUS_ABORTED)
        for server in self.services:
            self.node.destroy_service(server)
        self.node.destroy_publisher(self.feedback_pub)
        self.node.destroy_publisher(self.status_pub)
