"""lifecycle_msgs: generated from ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins) by `python -m node_runtime.msgs.generate`; do not edit."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

from node_runtime.msgs._base import Message, Service


class State(Message, type_name="lifecycle_msgs/msg/State"):
    """lifecycle_msgs/msg/State: Primary state definitions as depicted in:"""

    __slots__ = (
        "id",
        "label",
    )
    PRIMARY_STATE_UNKNOWN: ClassVar[int]
    PRIMARY_STATE_UNCONFIGURED: ClassVar[int]
    PRIMARY_STATE_INACTIVE: ClassVar[int]
    PRIMARY_STATE_ACTIVE: ClassVar[int]
    PRIMARY_STATE_FINALIZED: ClassVar[int]
    TRANSITION_STATE_CONFIGURING: ClassVar[int]
    TRANSITION_STATE_CLEANINGUP: ClassVar[int]
    TRANSITION_STATE_SHUTTINGDOWN: ClassVar[int]
    TRANSITION_STATE_ACTIVATING: ClassVar[int]
    TRANSITION_STATE_DEACTIVATING: ClassVar[int]
    TRANSITION_STATE_ERRORPROCESSING: ClassVar[int]
    id: int
    label: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            id: int = ...,
            label: str = ...,
        ) -> None: ...


class Transition(Message, type_name="lifecycle_msgs/msg/Transition"):
    """lifecycle_msgs/msg/Transition: Default values for transitions as described in:"""

    __slots__ = (
        "id",
        "label",
    )
    TRANSITION_CREATE: ClassVar[int]
    TRANSITION_CONFIGURE: ClassVar[int]
    TRANSITION_CLEANUP: ClassVar[int]
    TRANSITION_ACTIVATE: ClassVar[int]
    TRANSITION_DEACTIVATE: ClassVar[int]
    TRANSITION_UNCONFIGURED_SHUTDOWN: ClassVar[int]
    TRANSITION_INACTIVE_SHUTDOWN: ClassVar[int]
    TRANSITION_ACTIVE_SHUTDOWN: ClassVar[int]
    TRANSITION_DESTROY: ClassVar[int]
    TRANSITION_ON_CONFIGURE_SUCCESS: ClassVar[int]
    TRANSITION_ON_CONFIGURE_FAILURE: ClassVar[int]
    TRANSITION_ON_CONFIGURE_ERROR: ClassVar[int]
    TRANSITION_ON_CLEANUP_SUCCESS: ClassVar[int]
    TRANSITION_ON_CLEANUP_FAILURE: ClassVar[int]
    TRANSITION_ON_CLEANUP_ERROR: ClassVar[int]
    TRANSITION_ON_ACTIVATE_SUCCESS: ClassVar[int]
    TRANSITION_ON_ACTIVATE_FAILURE: ClassVar[int]
    TRANSITION_ON_ACTIVATE_ERROR: ClassVar[int]
    TRANSITION_ON_DEACTIVATE_SUCCESS: ClassVar[int]
    TRANSITION_ON_DEACTIVATE_FAILURE: ClassVar[int]
    TRANSITION_ON_DEACTIVATE_ERROR: ClassVar[int]
    TRANSITION_ON_SHUTDOWN_SUCCESS: ClassVar[int]
    TRANSITION_ON_SHUTDOWN_FAILURE: ClassVar[int]
    TRANSITION_ON_SHUTDOWN_ERROR: ClassVar[int]
    TRANSITION_ON_ERROR_SUCCESS: ClassVar[int]
    TRANSITION_ON_ERROR_FAILURE: ClassVar[int]
    TRANSITION_ON_ERROR_ERROR: ClassVar[int]
    TRANSITION_CALLBACK_SUCCESS: ClassVar[int]
    TRANSITION_CALLBACK_FAILURE: ClassVar[int]
    TRANSITION_CALLBACK_ERROR: ClassVar[int]
    id: int
    label: str

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            id: int = ...,
            label: str = ...,
        ) -> None: ...


class TransitionDescription(Message, type_name="lifecycle_msgs/msg/TransitionDescription"):
    """lifecycle_msgs/msg/TransitionDescription: The transition id and label of this description."""

    __slots__ = (
        "transition",
        "start_state",
        "goal_state",
    )
    transition: Transition
    start_state: State
    goal_state: State

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            transition: Transition = ...,
            start_state: State = ...,
            goal_state: State = ...,
        ) -> None: ...


class TransitionEvent(Message, type_name="lifecycle_msgs/msg/TransitionEvent"):
    """lifecycle_msgs/msg/TransitionEvent: The time point at which this event occurred."""

    __slots__ = (
        "timestamp",
        "transition",
        "start_state",
        "goal_state",
    )
    timestamp: int
    transition: Transition
    start_state: State
    goal_state: State

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            timestamp: int = ...,
            transition: Transition = ...,
            start_state: State = ...,
            goal_state: State = ...,
        ) -> None: ...


class ChangeState_Request(Message, type_name="lifecycle_msgs/srv/ChangeState_Request"):
    """lifecycle_msgs/srv/ChangeState_Request: The requested transition."""

    __slots__ = ("transition",)
    transition: Transition

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            transition: Transition = ...,
        ) -> None: ...


class ChangeState_Response(Message, type_name="lifecycle_msgs/srv/ChangeState_Response"):
    """lifecycle_msgs/srv/ChangeState_Response: Indicates whether the service was able to initiate the state transition"""

    __slots__ = ("success",)
    success: bool

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            success: bool = ...,
        ) -> None: ...


class GetAvailableStates_Request(Message, type_name="lifecycle_msgs/srv/GetAvailableStates_Request"):
    """lifecycle_msgs/srv/GetAvailableStates_Request"""

    __slots__ = ()


class GetAvailableStates_Response(Message, type_name="lifecycle_msgs/srv/GetAvailableStates_Response"):
    """lifecycle_msgs/srv/GetAvailableStates_Response: Array of possible states that can be transitioned to."""

    __slots__ = ("available_states",)
    available_states: list[State]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            available_states: Sequence[State] = ...,
        ) -> None: ...


class GetAvailableTransitions_Request(
    Message, type_name="lifecycle_msgs/srv/GetAvailableTransitions_Request"
):
    """lifecycle_msgs/srv/GetAvailableTransitions_Request"""

    __slots__ = ()


class GetAvailableTransitions_Response(
    Message, type_name="lifecycle_msgs/srv/GetAvailableTransitions_Response"
):
    """lifecycle_msgs/srv/GetAvailableTransitions_Response: An array of the possible start_state-goal_state transitions"""

    __slots__ = ("available_transitions",)
    available_transitions: list[TransitionDescription]

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            available_transitions: Sequence[TransitionDescription] = ...,
        ) -> None: ...


class GetState_Request(Message, type_name="lifecycle_msgs/srv/GetState_Request"):
    """lifecycle_msgs/srv/GetState_Request"""

    __slots__ = ()


class GetState_Response(Message, type_name="lifecycle_msgs/srv/GetState_Response"):
    """lifecycle_msgs/srv/GetState_Response: The current state-machine state of the node."""

    __slots__ = ("current_state",)
    current_state: State

    if TYPE_CHECKING:

        def __init__(
            self,
            *,
            current_state: State = ...,
        ) -> None: ...


class ChangeState(Service, type_name="lifecycle_msgs/srv/ChangeState"):
    """lifecycle_msgs/srv/ChangeState: call with a ChangeState.Request, answered with a ChangeState.Response."""

    Request = ChangeState_Request
    Response = ChangeState_Response


class GetAvailableStates(Service, type_name="lifecycle_msgs/srv/GetAvailableStates"):
    """lifecycle_msgs/srv/GetAvailableStates: call with a GetAvailableStates.Request, answered with a GetAvailableStates.Response."""

    Request = GetAvailableStates_Request
    Response = GetAvailableStates_Response


class GetAvailableTransitions(Service, type_name="lifecycle_msgs/srv/GetAvailableTransitions"):
    """lifecycle_msgs/srv/GetAvailableTransitions: call with a GetAvailableTransitions.Request, answered with a GetAvailableTransitions.Response."""

    Request = GetAvailableTransitions_Request
    Response = GetAvailableTransitions_Response


class GetState(Service, type_name="lifecycle_msgs/srv/GetState"):
    """lifecycle_msgs/srv/GetState: call with a GetState.Request, answered with a GetState.Response."""

    Request = GetState_Request
    Response = GetState_Response


__all__ = [
    "ChangeState",
    "ChangeState_Request",
    "ChangeState_Response",
    "GetAvailableStates",
    "GetAvailableStates_Request",
    "GetAvailableStates_Response",
    "GetAvailableTransitions",
    "GetAvailableTransitions_Request",
    "GetAvailableTransitions_Response",
    "GetState",
    "GetState_Request",
    "GetState_Response",
    "State",
    "Transition",
    "TransitionDescription",
    "TransitionEvent",
]
