"""rclpy's parameters on a node, in one process: typed values, descriptors (read-only, ranges),
and the set-parameters callbacks, whose refusal comes back with its reason and changes nothing."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
import rclpy
from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor, SetParametersResult
from rclpy.node import Node
from rclpy.parameter import Parameter


@pytest.fixture
def node(monkeypatch: pytest.MonkeyPatch) -> Iterator[Node]:
    monkeypatch.setenv("ROS2LAB_NO_ZENOH", "1")
    ctx = rclpy.Context()
    with rclpy.init(args=["--ros-args", "-p", "overridden:=7"], context=ctx):
        yield Node("params", context=ctx)


def test_the_tutorials_parameter_reads_and_sets_as_in_rclpy(node: Node) -> None:
    node.declare_parameter("my_parameter", "world")
    assert node.get_parameter("my_parameter").get_parameter_value().string_value == "world"
    (result,) = node.set_parameters([Parameter("my_parameter", Parameter.Type.STRING, "there")])
    assert result.successful and node.get_parameter("my_parameter").value == "there"
    assert node.declare_parameter("overridden", 1).value == 7  # --ros-args -p wins over the default
    assert node.get_parameters_dict()["my_parameter"] == "there"


def test_a_callback_refuses_a_value_with_its_reason_and_nothing_changes(node: Node) -> None:
    node.declare_parameter("speed", 1.0)
    seen: list[list[str]] = []

    def check(params: list[Parameter]) -> SetParametersResult:
        seen.append([p.name for p in params])
        for p in params:
            if p.name == "speed" and p.value < 0:
                return SetParametersResult(successful=False, reason="speed must not be negative")
        return SetParametersResult(successful=True)

    after: list[float] = []
    node.add_on_set_parameters_callback(check)
    node.add_post_set_parameters_callback(lambda params: after.extend(p.value for p in params))
    (refused,) = node.set_parameters([Parameter("speed", value=-2.0)])
    assert (refused.successful, refused.reason) == (False, "speed must not be negative")
    assert node.get_parameter("speed").value == 1.0 and after == []
    (accepted,) = node.set_parameters([Parameter("speed", value=2.5)])
    assert accepted.successful and node.get_parameter("speed").value == 2.5 and after == [2.5]
    assert seen == [["speed"], ["speed"]]


def test_a_pre_set_callback_may_add_parameters_to_a_set(node: Node) -> None:
    node.declare_parameter("a", 1)
    node.declare_parameter("b", 1)
    node.add_pre_set_parameters_callback(lambda ps: [*ps, Parameter("b", value=ps[0].value * 10)])
    assert node.set_parameters_atomically([Parameter("a", value=2)]).successful
    assert (node.get_parameter("a").value, node.get_parameter("b").value) == (2, 20)


@pytest.mark.parametrize(
    ("descriptor", "value", "reason"),
    [
        (ParameterDescriptor(read_only=True), 2, "Trying to set a read-only parameter: p."),
        (ParameterDescriptor(), "two", "Wrong parameter type"),
        (
            ParameterDescriptor(integer_range=[IntegerRange(from_value=1, to_value=11, step=2)]),
            4,
            "The parameter value for p is not a valid step",
        ),
        (
            ParameterDescriptor(integer_range=[IntegerRange(from_value=1, to_value=11, step=2)]),
            12,
            "out of range",
        ),
    ],
)
def test_a_descriptor_refuses_what_it_does_not_allow(
    node: Node, descriptor: ParameterDescriptor, value: object, reason: str
) -> None:
    node.declare_parameter("p", 1, descriptor)
    (result,) = node.set_parameters([Parameter("p", value=value)])
    assert not result.successful and reason in result.reason
    assert node.get_parameter("p").value == 1


def test_a_range_allows_what_is_on_its_steps_and_the_description_says_so(node: Node) -> None:
    rng = FloatingPointRange(from_value=0.0, to_value=1.0, step=0.25)
    node.declare_parameter(
        "gain", 0.5, ParameterDescriptor(description="how hard", floating_point_range=[rng])
    )
    assert node.set_parameters([Parameter("gain", value=0.75)])[0].successful
    assert not node.set_parameters([Parameter("gain", value=0.8)])[0].successful
    described = node.describe_parameter("gain")
    assert (described.name, described.type, described.description) == (
        "gain",
        Parameter.Type.DOUBLE.value,
        "how hard",
    )


def test_parameters_go_to_and_from_their_messages() -> None:
    param = Parameter("limits", value=[1.5, 2.5])
    assert param.type_ == Parameter.Type.DOUBLE_ARRAY
    back = Parameter.from_parameter_msg(param.to_parameter_msg())
    assert (back.name, back.type_, back.value) == ("limits", Parameter.Type.DOUBLE_ARRAY, [1.5, 2.5])
    with pytest.raises(ValueError, match="not a INTEGER"):
        Parameter("n", Parameter.Type.INTEGER, "seven")
