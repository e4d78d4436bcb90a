"""rclpy's ActionServer: goals arrive on ``<action>/_action/send_goal``, are cancelled on
``cancel_goal``, answered on ``get_result``; feedback and the goals' status are published on the
``feedback`` and ``status`` topics, as rcl_action lays an action out."""

from __future__ import annotations

import threading
import time
import traceback
from collections.abc import Callable
from enum import Enum
from typing import Any, cast

from node_runtime.bus import Future
from node_runtime.msgs import Message
from node_runtime.msgs.generated.action_msgs import GoalInfo, GoalStatus, GoalStatusArray
from rclpy._context import RCLError
from rclpy.action._goals import ACTIVE, CANCELING, action_names, next_status, serve_later
from rclpy.action.cancel import goals_to_cancel
from rclpy.executors import await_or_execute
from rclpy.qos import QoSProfile, qos_profile_action_status_default


class GoalResponse(Enum):
    REJECT = 1
    ACCEPT = 2


class CancelResponse(Enum):
    REJECT = 1
    ACCEPT = 2


def default_goal_callback(goal_request: Any) -> GoalResponse:
    """Accept every goal."""
    return GoalResponse.ACCEPT


def default_cancel_callback(cancel_request: Any) -> CancelResponse:
    """Cancel nothing."""
    return CancelResponse.REJECT


def default_handle_accepted_callback(goal_handle: ServerGoalHandle) -> None:
    """Execute the goal."""
    goal_handle.execute()


class ServerGoalHandle:
    """One accepted goal, as the execute callback sees it."""

    def __init__(self, server: ActionServer, goal_info: Any, request: Any) -> None:
        self._server = server
        self._goal_info = goal_info
        self._request = request
        self._status = GoalStatus.STATUS_ACCEPTED
        self._result: Future[Message] = Future()
        self._lock = threading.Lock()
        self.done_at: float | None = None

    @property
    def request(self) -> Any:
        return self._request

    @property
    def goal_id(self) -> Any:
        return self._goal_info.goal_id

    @property
    def goal_info(self) -> Any:
        return self._goal_info

    @property
    def status(self) -> int:
        return self._status

    @property
    def is_active(self) -> bool:
        return self._status in ACTIVE

    @property
    def is_cancel_requested(self) -> bool:
        return self._status == CANCELING

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ServerGoalHandle) and self.goal_id == other.goal_id

    __hash__ = None  # type: ignore[assignment]

    def _update_state(self, event: str) -> None:
        with self._lock:
            self._status = next_status(self._status, event)
            if not self.is_active:
                self.done_at = time.monotonic()
        self._server.publish_status()

    def execute(self, execute_callback: Callable[[Any], Any] | None = None) -> None:
        """Start executing: the execute callback runs on the executor, after this returns."""
        if not self.is_cancel_requested:  # cancelled before it started: its callback still decides
            self._update_state("execute")
        self._server.notify_execute(self, execute_callback)

    def publish_feedback(self, feedback: Message) -> None:
        action_type = self._server.action_type
        if not isinstance(feedback, action_type.Feedback):
            raise TypeError(f"feedback must be a {action_type.Feedback.TYPE}, not {type(feedback).__name__}")
        message = action_type.Impl.FeedbackMessage(goal_id=self.goal_id, feedback=feedback)
        self._server.feedback_publisher.publish(message)

    def succeed(self) -> None:
        self._update_state("succeed")

    def abort(self) -> None:
        self._update_state("abort")

    def canceled(self) -> None:
        self._update_state("canceled")

    def destroy(self) -> None:
        self._server.forget(self)


class ActionServer:
    """``ActionServer(node, Fibonacci, 'fibonacci', execute_callback, goal_callback=...,
    cancel_callback=..., handle_accepted_callback=...)``, as in rclpy."""

    def __init__(
        self,
        node: Any,
        action_type: Any,
        action_name: str,
        execute_callback: Callable[[ServerGoalHandle], Any],
        *,
        callback_group: Any = None,
        goal_callback: Callable[[Any], Any] = default_goal_callback,
        handle_accepted_callback: Callable[[ServerGoalHandle], Any] = default_handle_accepted_callback,
        cancel_callback: Callable[[ServerGoalHandle], Any] = default_cancel_callback,
        goal_service_qos_profile: Any = None,
        result_service_qos_profile: Any = None,
        cancel_service_qos_profile: Any = None,
        feedback_pub_qos_profile: Any = None,
        status_pub_qos_profile: Any = None,
        result_timeout: float = 900,
    ) -> None:
        self.node = node
        self.action_type = action_type
        self.group = callback_group or node.default_callback_group
        self.destroyed = False
        self.result_timeout_s = result_timeout
        self.register_execute_callback(execute_callback)
        self.register_goal_callback(goal_callback)
        self.register_cancel_callback(cancel_callback)
        self.register_handle_accepted_callback(handle_accepted_callback)
        self._goals: dict[bytes, ServerGoalHandle] = {}
        self._lock = threading.RLock()
        impl, names = action_type.Impl, action_names(action_name)
        self._send_goal = serve_later(
            node, impl.SendGoalService, names["send_goal"], self._on_goal, self.group
        )
        self._cancel = serve_later(
            node, impl.CancelGoalService, names["cancel_goal"], self._on_cancel, self.group
        )
        self._result = serve_later(
            node, impl.GetResultService, names["get_result"], self._on_result, self.group
        )
        self.feedback_publisher = node.create_publisher(
            impl.FeedbackMessage, names["feedback"], feedback_pub_qos_profile or QoSProfile(depth=10)
        )
        self._status_publisher = node.create_publisher(
            GoalStatusArray, names["status"], status_pub_qos_profile or qos_profile_action_status_default
        )

    # -- rclpy's registration calls ----------------------------------------------------------
    def register_execute_callback(self, execute_callback: Callable[[ServerGoalHandle], Any]) -> None:
        if not callable(execute_callback):
            raise TypeError("Failed to register goal execution callback: not callable")
        self._execute_callback = execute_callback

    def register_goal_callback(self, goal_callback: Callable[[Any], Any] | None) -> None:
        self._goal_callback = goal_callback or default_goal_callback

    def register_cancel_callback(self, cancel_callback: Callable[[ServerGoalHandle], Any] | None) -> None:
        self._cancel_callback = cancel_callback or default_cancel_callback

    def register_handle_accepted_callback(self, callback: Callable[[ServerGoalHandle], Any] | None) -> None:
        self._handle_accepted_callback = callback or default_handle_accepted_callback

    # -- the three services ------------------------------------------------------------------
    async def _on_goal(self, request: Any, future: Future[Message]) -> None:
        goal_id = bytes(request.goal_id.uuid)
        response = self.action_type.Impl.SendGoalService.Response()
        accepted = False
        if goal_id not in self._goals:
            verdict = await await_or_execute(self._goal_callback, request.goal)
            if not isinstance(verdict, GoalResponse):
                self.node.get_logger().warning(
                    "Goal request callback did not return a GoalResponse type. Rejecting goal."
                )
            accepted = verdict == GoalResponse.ACCEPT
        if not accepted:
            future.set_result(response)
            return
        info = GoalInfo(goal_id=request.goal_id, stamp=self.node.get_clock().now().to_msg())
        handle = ServerGoalHandle(self, info, request.goal)
        with self._lock:
            self._expire()
            self._goals[goal_id] = handle
        response.accepted, response.stamp = True, info.stamp
        future.set_result(response)
        self.publish_status()
        await await_or_execute(self._handle_accepted_callback, handle)

    async def _on_cancel(self, request: Any, future: Future[Message]) -> None:
        response = self.action_type.Impl.CancelGoalService.Response()
        with self._lock:
            handles = list(self._goals.values())
        candidates, response.return_code = goals_to_cancel(request.goal_info, handles)
        for handle in candidates:
            if await await_or_execute(self._cancel_callback, handle) != CancelResponse.ACCEPT:
                continue
            try:  # the goal may have ended while its cancel callback ran
                handle._update_state("cancel_goal")
            except RCLError:
                continue
            response.goals_canceling.append(handle.goal_info)
        if candidates and not response.goals_canceling:
            response.return_code = response.ERROR_REJECTED
        future.set_result(response)

    def _on_result(self, request: Any, future: Future[Message]) -> None:
        handle = self._goals.get(bytes(request.goal_id.uuid))
        if handle is None:
            response = self.action_type.Impl.GetResultService.Response(status=GoalStatus.STATUS_UNKNOWN)
            future.set_result(response)
            return
        handle._result.add_done_callback(lambda done: future.set_result(cast(Message, done.result()).copy()))

    # -- executing ---------------------------------------------------------------------------
    def notify_execute(self, handle: ServerGoalHandle, callback: Callable[[Any], Any] | None) -> None:
        """Have the node's executor run the execute callback as a task of its own (outside the
        server's callback group), as rclpy does; a node in no executor runs no goal."""
        executor = getattr(self.node, "executor", None)
        if executor is not None:
            executor.create_task(self._execute_goal, callback or self._execute_callback, handle)

    async def _execute_goal(self, callback: Callable[[Any], Any], handle: ServerGoalHandle) -> None:
        logger = self.node.get_logger()
        try:
            result = await await_or_execute(callback, handle)
        except Exception as exc:
            result = self.action_type.Result()
            logger.error(f"Error raised in execute callback: {exc}")
            traceback.print_exc()
        if handle.is_active:
            logger.warning(f"Goal state not set, assuming aborted. Goal ID: {handle.goal_id.uuid}")
            handle.abort()
        if not isinstance(result, self.action_type.Result):
            result = self.action_type.Result()
        response = self.action_type.Impl.GetResultService.Response(status=handle.status, result=result)
        handle._result.set_result(response)

    # -- status ------------------------------------------------------------------------------
    def publish_status(self) -> None:
        with self._lock:
            statuses = [GoalStatus(goal_info=h.goal_info, status=h.status) for h in self._goals.values()]
        if not self.destroyed:
            self._status_publisher.publish(GoalStatusArray(status_list=statuses))

    def _expire(self) -> None:
        """Forget goals whose result has been kept ``result_timeout`` seconds, as rcl_action does."""
        now = time.monotonic()
        for key, handle in list(self._goals.items()):
            if handle.done_at is not None and now - handle.done_at > self.result_timeout_s:
                del self._goals[key]

    def forget(self, handle: ServerGoalHandle) -> None:
        with self._lock:
            self._goals.pop(bytes(handle.goal_id.uuid), None)

    def destroy(self) -> None:
        if self.destroyed:
            return
        self.destroyed = True
        for server in (self._send_goal, self._cancel, self._result):
            self.node.destroy_service(server)
        self.node.destroy_publisher(self.feedback_publisher)
        self.node.destroy_publisher(self._status_publisher)


__all__ = ["ActionServer", "CancelResponse", "GoalResponse", "ServerGoalHandle"]
