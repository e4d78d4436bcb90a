"""rclpy's ActionClient: ``send_goal_async`` (a future of a ClientGoalHandle), feedback to a
callback, ``get_result_async`` and ``cancel_goal_async`` on the handle, and each goal's status
from the action's status topic."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any, cast

from node_runtime.msgs import Message
from node_runtime.msgs.generated.action_msgs import CancelGoal, GoalStatus, GoalStatusArray
from node_runtime.msgs.generated.unique_identifier_msgs import UUID
from rclpy.action._goals import ACTIVE, action_names, new_goal_id
from rclpy.executors import await_or_execute
from rclpy.qos import QoSProfile, qos_profile_action_status_default
from rclpy.task import Future

WAIT_POLL_S = 0.02  # how often wait_for_server looks at the graph
MAX_FINISHED_TRACKED = 1000  # goals with a result whose final status has not come (yet)


class ClientGoalHandle:
    """A goal sent by an ActionClient: ``accepted``, ``status``, ``get_result_async()``,
    ``cancel_goal_async()``."""

    def __init__(self, action_client: ActionClient, goal_id: Any, goal_response: Any) -> None:
        self._action_client = action_client
        self._goal_id = goal_id
        self._goal_response = goal_response
        self._status = GoalStatus.STATUS_UNKNOWN

    @property
    def goal_id(self) -> Any:
        return self._goal_id

    @property
    def stamp(self) -> Any:
        return self._goal_response.stamp

    @property
    def accepted(self) -> bool:
        return bool(self._goal_response.accepted)

    @property
    def status(self) -> int:
        return self._status

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ClientGoalHandle) and self._goal_id == other._goal_id

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"ClientGoalHandle <id: {self.goal_id.uuid}, accepted: {self.accepted}, status: {self.status}>"

    def cancel_goal_async(self) -> Future[Message]:
        """A future of the CancelGoal response (its ``goals_canceling`` lists this goal if the
        server agreed)."""
        return self._action_client._cancel_goal_async(self)

    def get_result_async(self) -> Future[Message]:
        """A future of the GetResult response: ``.result`` and ``.status``."""
        if not self.accepted:
            raise TypeError("Action goal was not accepted")
        return self._action_client._get_result_async(self)

    def cancel_goal(self) -> Any:
        return _wait(self.cancel_goal_async())

    def get_result(self) -> Any:
        return _wait(self.get_result_async())


def _wait(future: Future[Any]) -> Any:
    """Block until another thread's executor completes ``future`` (rclpy's synchronous calls)."""
    future.wait()
    return future.result()


class ActionClient:
    """``ActionClient(node, Fibonacci, 'fibonacci')``, as in rclpy."""

    def __init__(
        self,
        node: Any,
        action_type: Any,
        action_name: str,
        *,
        callback_group: Any = None,
        goal_service_qos_profile: Any = None,
        result_service_qos_profile: Any = None,
        cancel_service_qos_profile: Any = None,
        feedback_sub_qos_profile: Any = None,
        status_sub_qos_profile: Any = None,
    ) -> None:
        self._node = node
        self._action_type = action_type
        self._action_name = action_name
        group = callback_group or node.default_callback_group
        impl, names = action_type.Impl, action_names(action_name)
        self._goal_client = node.create_client(impl.SendGoalService, names["send_goal"], callback_group=group)
        self._cancel_client = node.create_client(
            impl.CancelGoalService, names["cancel_goal"], callback_group=group
        )
        self._result_client = node.create_client(
            impl.GetResultService, names["get_result"], callback_group=group
        )
        self._feedback_sub = node.create_subscription(
            impl.FeedbackMessage,
            names["feedback"],
            self._on_feedback,
            feedback_sub_qos_profile or QoSProfile(depth=10),
            callback_group=group,
        )
        self._status_sub = node.create_subscription(
            GoalStatusArray,
            names["status"],
            self._on_status,
            status_sub_qos_profile or qos_profile_action_status_default,
            callback_group=group,
        )
        for entity in (self._goal_client, self._cancel_client, self._result_client):
            entity.in_waitable = True  # an action's, which rclpy's executor looks at first
        for entity in (self._feedback_sub, self._status_sub):
            entity.in_waitable = True
        self._goal_handles: dict[bytes, ClientGoalHandle] = {}
        self._feedback_callbacks: dict[bytes, Callable[[Any], Any]] = {}
        self._finished: set[bytes] = set()

    # -- the server ----------------------------------------------------------------------------
    def server_is_ready(self) -> bool:
        """True once a server answers all three of the action's services."""
        clients = (self._goal_client, self._cancel_client, self._result_client)
        return all(c.service_is_ready() for c in clients)

    def wait_for_server(self, timeout_sec: float | None = None) -> bool:
        """Wait until :meth:`server_is_ready`; False after ``timeout_sec``."""
        end = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        while True:
            self._goal_client._refresh_graph()
            if self.server_is_ready():
                return True
            if end is not None and time.monotonic() >= end:
                return False
            time.sleep(WAIT_POLL_S)

    # -- goals ---------------------------------------------------------------------------------
    def send_goal_async(
        self, goal: Any, feedback_callback: Callable[[Any], Any] | None = None, goal_uuid: Any = None
    ) -> Future[ClientGoalHandle]:
        """Send ``goal``; the future completes with a ClientGoalHandle once the server answers."""
        if not isinstance(goal, self._action_type.Goal):
            raise TypeError(f"goal must be a {self._action_type.Goal.TYPE}, not {type(goal).__name__}")
        goal_id = goal_uuid if goal_uuid is not None else UUID(uuid=list(new_goal_id()))
        key = bytes(goal_id.uuid)
        if feedback_callback is not None:
            self._feedback_callbacks[key] = feedback_callback
        request = self._action_type.Impl.SendGoalService.Request(goal_id=goal_id, goal=goal)
        outcome: Future[ClientGoalHandle] = Future()

        def answered(done: Future[Message]) -> None:
            outcome._set_executor(getattr(self._node, "executor", None))  # its callbacks run there
            failure = done.exception()
            if done.cancelled() or failure is not None:
                self._feedback_callbacks.pop(key, None)
                if failure is not None:
                    outcome.set_exception(failure)
                else:
                    outcome.cancel()
                return
            handle = ClientGoalHandle(self, goal_id, done.result())
            if handle.accepted:
                handle._status = max(handle._status, GoalStatus.STATUS_ACCEPTED)
                self._goal_handles[key] = handle
            else:
                self._feedback_callbacks.pop(key, None)
            outcome.set_result(handle)

        self._goal_client.call_async(request).add_done_callback(answered)
        return outcome

    def send_goal(self, goal: Any, **kwargs: Any) -> Any:
        """Send ``goal`` and wait for its result (for a caller on another thread than the executor)."""
        handle = _wait(self.send_goal_async(goal, **kwargs))
        return None if handle is None or not handle.accepted else handle.get_result()

    def _cancel_goal_async(self, handle: ClientGoalHandle) -> Future[Message]:
        request = CancelGoal.Request()
        request.goal_info.goal_id = handle.goal_id
        return cast(Future[Message], self._cancel_client.call_async(request))

    def _get_result_async(self, handle: ClientGoalHandle) -> Future[Message]:
        key = bytes(handle.goal_id.uuid)
        request = self._action_type.Impl.GetResultService.Request(goal_id=handle.goal_id)
        future = cast(Future[Message], self._result_client.call_async(request))

        def finished(done: Future[Message]) -> None:
            response = done.result() if not done.cancelled() and done.exception() is None else None
            if response is not None:
                handle._status = int(cast(Any, response).status)
            # Feedback sent before the result may still be on its way (it travels on a topic, the
            # result on a service): the goal is forgotten when its final status comes, after both.
            self._finished.add(key)
            if len(self._finished) > MAX_FINISHED_TRACKED:
                self._forget(next(iter(self._finished)))

        future.add_done_callback(finished)
        return future

    # -- topics --------------------------------------------------------------------------------
    async def _on_feedback(self, message: Any) -> None:
        callback = self._feedback_callbacks.get(bytes(message.goal_id.uuid))
        if callback is not None:
            await await_or_execute(callback, message)

    def _on_status(self, message: Any) -> None:
        for status in message.status_list:
            key = bytes(status.goal_info.goal_id.uuid)
            handle = self._goal_handles.get(key)
            if handle is not None:
                handle._status = int(status.status)
            if key in self._finished and status.status not in ACTIVE:
                self._forget(key)

    def _forget(self, key: bytes) -> None:
        self._finished.discard(key)
        self._feedback_callbacks.pop(key, None)
        self._goal_handles.pop(key, None)

    def destroy(self) -> None:
        for client in (self._goal_client, self._cancel_client, self._result_client):
            self._node.destroy_client(client)
        for sub in (self._feedback_sub, self._status_sub):
            self._node.destroy_subscription(sub)


__all__ = ["ActionClient", "ClientGoalHandle"]
