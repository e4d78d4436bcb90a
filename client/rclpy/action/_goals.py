"""What an action's server and client share: the goal state machine (rcl_action's), goal ids,
the wire names, and a service server that answers a call later."""

from __future__ import annotations

import uuid
from collections.abc import Callable
from typing import Any

from node_runtime.bus import Future
from node_runtime.bus.services import PendingCall, ServiceServer
from node_runtime.msgs import Message
from node_runtime.msgs.generated.action_msgs import GoalStatus
from rclpy._context import RCLError

ACCEPTED, EXECUTING, CANCELING = (
    GoalStatus.STATUS_ACCEPTED,
    GoalStatus.STATUS_EXECUTING,
    GoalStatus.STATUS_CANCELING,
)
SUCCEEDED, CANCELED, ABORTED = (
    GoalStatus.STATUS_SUCCEEDED,
    GoalStatus.STATUS_CANCELED,
    GoalStatus.STATUS_ABORTED,
)
ACTIVE = frozenset({ACCEPTED, EXECUTING, CANCELING})
STATUS_NAMES = {
    GoalStatus.STATUS_UNKNOWN: "UNKNOWN",
    ACCEPTED: "ACCEPTED",
    EXECUTING: "EXECUTING",
    CANCELING: "CANCELING",
    SUCCEEDED: "SUCCEEDED",
    CANCELED: "CANCELED",
    ABORTED: "ABORTED",
}

# (state, event) → next state, as rcl_action's goal state machine allows them.
_TRANSITIONS = {
    (ACCEPTED, "execute"): EXECUTING,
    (ACCEPTED, "cancel_goal"): CANCELING,
    (EXECUTING, "cancel_goal"): CANCELING,
    (EXECUTING, "succeed"): SUCCEEDED,
    (EXECUTING, "abort"): ABORTED,
    (CANCELING, "succeed"): SUCCEEDED,
    (CANCELING, "abort"): ABORTED,
    (CANCELING, "canceled"): CANCELED,
}


def next_status(status: int, event: str) -> int:
    """The state ``event`` takes a goal in ``status`` to; RCLError if the machine forbids it."""
    try:
        return _TRANSITIONS[(status, event)]
    except KeyError:
        raise RCLError(
            f"Failed to update goal state: goal_handle attempted invalid transition from state "
            f"{STATUS_NAMES.get(status, status)} with event {event.upper()}"
        ) from None


def new_goal_id() -> bytes:
    return uuid.uuid4().bytes


def action_names(action_name: str) -> dict[str, str]:
    """The services and topics an action is made of, as rcl_action names them."""
    base = action_name.rstrip("/") + "/_action/"
    return {part: base + part for part in ("send_goal", "cancel_goal", "get_result", "feedback", "status")}


class LaterServer(ServiceServer):
    """A service server whose handler gets the call's future and completes it when it can (the
    result of a goal still running), so the executor is not held meanwhile; an ``async def``
    handler is awaited by the executor."""

    in_waitable = True  # part of an action, which rclpy's executor looks at before the rest

    def __init__(self, node: Any, channel: Any, handler: Callable[[Message, Future[Message]], Any]) -> None:
        super().__init__(node, channel, handler)

    def answer(self, call: PendingCall) -> Any:
        return self.callback(call.request, call.future)  # an async handler's coroutine, to await


def serve_later(
    node: Any, srv_type: Any, name: str, handler: Callable[[Message, Future[Message]], Any], group: Any
) -> LaterServer:
    """``node.create_service`` for a :class:`LaterServer`."""
    node._check_alive()
    channel = node._bus.service(node.resolve_topic_name(name), srv_type)
    server = LaterServer(node, channel, handler)
    server.callback = node._grouped(handler, group, server)
    channel.servers.append(server)
    node.services.append(server)
    node._bus.endpoint_added(server)
    return server
