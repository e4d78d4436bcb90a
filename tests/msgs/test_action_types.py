"""Action types from ``.action`` definitions: the parts and wire types rosidl derives, rclpy's
class shape, a definition given as text at run time, and numeric sequences as rclpy keeps them."""

from __future__ import annotations

import array

import numpy as np
import pytest
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

from node_runtime.msgs import get_action_type, type_names
from node_runtime.msgs._action import action_type_from_text
from node_runtime.msgs.action_spec import parse_action
from node_runtime.msgs.definitions import Definitions
from node_runtime.msgs.idl import DefinitionError
from node_runtime.msgs.wire import build_typestore, dds_type_name, deserialize, ros_type_name, serialize


def test_fibonacci_has_rclpy_shape_and_rosidl_wire_types() -> None:
    fib = get_action_type("example_interfaces/Fibonacci")
    assert fib.TYPE == "example_interfaces/action/Fibonacci"
    assert (fib.Goal.TYPE, fib.Result.TYPE, fib.Feedback.TYPE) == (
        "example_interfaces/action/Fibonacci_Goal",
        "example_interfaces/action/Fibonacci_Result",
        "example_interfaces/action/Fibonacci_Feedback",
    )
    impl = fib.Impl
    assert impl.SendGoalService.Request.get_fields_and_field_types() == {
        "goal_id": "unique_identifier_msgs/msg/UUID",
        "goal": "example_interfaces/action/Fibonacci_Goal",
    }
    assert impl.SendGoalService.Response.get_fields_and_field_types() == {
        "accepted": "bool",
        "stamp": "builtin_interfaces/msg/Time",
    }
    assert impl.GetResultService.Response.get_fields_and_field_types() == {
        "status": "int8",
        "result": "example_interfaces/action/Fibonacci_Result",
    }
    assert impl.FeedbackMessage.get_fields_and_field_types() == {
        "goal_id": "unique_identifier_msgs/msg/UUID",
        "feedback": "example_interfaces/action/Fibonacci_Feedback",
    }
    assert (impl.CancelGoalService.TYPE, impl.GoalStatusMessage.TYPE) == (
        "action_msgs/srv/CancelGoal",
        "action_msgs/msg/GoalStatusArray",
    )
    assert "example_interfaces/action/Fibonacci_Goal" not in type_names()  # an action's part, not a message


def test_wire_type_names_are_rmw_zenohs() -> None:
    assert dds_type_name("example_interfaces/action/Fibonacci_SendGoal") == (
        "example_interfaces::action::dds_::Fibonacci_SendGoal_"
    )
    assert ros_type_name("example_interfaces::action::dds_::Fibonacci_FeedbackMessage_") == (
        "example_interfaces/action/Fibonacci_FeedbackMessage"
    )


def test_sequences_are_arrays_that_append_and_print_as_rclpy_and_fixed_arrays_stay_numpy() -> None:
    fib = get_action_type("action_tutorials_interfaces/action/Fibonacci")
    feedback = fib.Feedback()
    feedback.partial_sequence = [0, 1]
    feedback.partial_sequence.append(1)
    assert repr(feedback.partial_sequence) == "array('i', [0, 1, 1])"
    message = fib.Impl.FeedbackMessage(feedback=feedback)
    message.goal_id.uuid = list(range(16))
    back = deserialize(message.TYPE, serialize(message))
    assert back == message and isinstance(back.feedback.partial_sequence, array.array)
    assert isinstance(back.goal_id.uuid, np.ndarray) and back.goal_id.uuid.dtype == np.uint8
    copied = message.copy()
    copied.feedback.partial_sequence.append(2)
    assert list(message.feedback.partial_sequence) == [0, 1, 1]  # a copy shares no array
    with pytest.raises(ValueError, match=r"partial_sequence\[0\]: 2147483648 is out of range for int32"):
        fib.Feedback(partial_sequence=[2**31])


def test_action_defined_from_text_at_run_time_gets_classes_and_hashes_as_rosbags_does() -> None:
    text = "# count up to\nint32 target\n---\nbool done\n---\nint32 at\n"
    spec = parse_action("counter_msgs/action/Count", text)
    count = action_type_from_text("counter_msgs", "Count", text)
    assert count.Goal(target=3).target == 3 and count.Impl.SendGoalService.TYPE.endswith("Count_SendGoal")
    assert get_action_type("counter_msgs/Count") is count
    # rosbags' own typestore, fed by hand, agrees with the one the lab builds from the definition
    store = get_typestore(Stores.EMPTY)
    store.register(get_types_from_msg("int32 target", "counter_msgs/action/Count_Goal"))
    mine = build_typestore(Definitions({m.name: m for m in spec.messages}, {}), for_hashing=True)
    assert mine.hash_rihs01("counter_msgs/action/Count_Goal") == store.hash_rihs01(
        "counter_msgs/action/Count_Goal"
    )


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ("int32 a\n---\nint32 b\n", "an action has two '---' lines, found 1"),
        ("int32 a\n---\nint32 b\n---\nint32 c\n---\n", "an action has two '---' lines, found 3"),
        ("int32 a\n---\nbadtype! b\n---\n", "counter_msgs/action/Bad_Result:3: expected 'TYPE NAME'"),
    ],
)
def test_bad_action_definition_names_what_is_wrong(text: str, problem: str) -> None:
    with pytest.raises(DefinitionError, match=problem):
        parse_action("counter_msgs/action/Bad", text)


def test_action_name_must_have_the_action_kind() -> None:
    with pytest.raises(DefinitionError, match="pkg/action/Name"):
        parse_action("counter_msgs/msg/Count", "int32 a\n---\n---\n")
