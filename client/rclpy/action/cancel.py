"""Which goals a cancel request names, by action_msgs' CancelGoal policy (rcl_action's):

- goal id zero, stamp zero: every goal;
- goal id zero, stamp set: every goal accepted at or before the stamp;
- goal id set, stamp zero: that goal;
- goal id set, stamp set: that goal and every goal accepted at or before the stamp.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from node_runtime.msgs.generated.action_msgs import CancelGoal_Response
from rclpy.action._goals import ACCEPTED, EXECUTING


def _nanoseconds(stamp: Any) -> int:
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


def goals_to_cancel(goal_info: Any, handles: Sequence[Any]) -> tuple[list[Any], int]:
    """The goals that may be cancelled (accepted or executing) among ``handles``, and the return
    code if they are all cancelled (``ERROR_NONE``) or why there are none."""
    wanted_id = bytes(goal_info.goal_id.uuid)
    by_id = any(wanted_id)
    stamp_ns = _nanoseconds(goal_info.stamp)
    named = [
        h
        for h in handles
        if (not by_id and stamp_ns == 0)
        or (by_id and bytes(h.goal_id.uuid) == wanted_id)
        or (stamp_ns != 0 and _nanoseconds(h.goal_info.stamp) <= stamp_ns)
    ]
    cancelable = [h for h in named if h.status in (ACCEPTED, EXECUTING)]
    if cancelable:
        return cancelable, CancelGoal_Response.ERROR_NONE
    if by_id and not named:
        return [], CancelGoal_Response.ERROR_UNKNOWN_GOAL_ID
    if named:
        return [], CancelGoal_Response.ERROR_GOAL_TERMINATED
    return [], CancelGoal_Response.ERROR_REJECTED
