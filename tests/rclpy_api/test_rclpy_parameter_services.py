"""A node's parameters as other nodes reach them, in one process: its six parameter services
through AsyncParameterClient, /parameter_events, overrides from ``--params-file`` and ``-p``, and
undeclared parameters when the node allows them."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import rclpy
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor, ParameterEvent, SetParametersResult
from rclpy.exceptions import (
    InvalidParameterTypeException,
    ParameterImmutableException,
    ParameterNotDeclaredException,
)
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.parameter_client import AsyncParameterClient

PARAMS_FILE = """\
/**:
  ros__parameters:
    shared: 1
    speed: 0.5
/robots/arm:
  ros__parameters:
    speed: 2.0
    gains:
      p: 1.5
      d: [0.1, 0.2]
other:
  ros__parameters:
    speed: 9.0
"""


RCLPY_OWN = "start_type_description_service"  # every rclpy node declares it (read-only, true)


@pytest.fixture
def ctx(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Iterator[rclpy.Context]:
    monkeypatch.setenv("ROS2LAB_NO_ZENOH", "1")
    params = tmp_path / "params.yaml"
    params.write_text(PARAMS_FILE)
    context = rclpy.Context()
    with rclpy.init(args=["--ros-args", "--params-file", str(params), "-p", "shared:=3"], context=context):
        yield context


def spun(ctx: rclpy.Context, node: Node, future: Any) -> Any:
    """Spin every node of the process (the server is one too: as in rclpy, a node no executor
    has runs nothing) until ``future`` is done."""
    executor = rclpy.executors.SingleThreadedExecutor(context=ctx)
    assert ctx.bus is not None
    for each in ctx.bus.nodes:
        executor.add_node(each)
    executor.spin_until_future_complete(future, timeout_sec=5.0)
    assert future.done(), "the service did not answer"
    return future.result()


def test_the_params_file_gives_each_node_its_sections_and_p_wins(ctx: rclpy.Context) -> None:
    arm = Node("arm", namespace="/robots", context=ctx)
    other = Node("other", context=ctx)
    assert arm.declare_parameter("speed", 0.0).value == 2.0  # its own section over /**
    assert other.declare_parameter("speed", 0.0).value == 9.0
    assert arm.declare_parameter("shared", 0).value == 3  # -p over the file
    assert arm.declare_parameter("gains.d", [0.0]).value == [0.1, 0.2]
    assert Node("third", context=ctx).declare_parameter("speed", 0.0).value == 0.5  # /** only


def test_overrides_are_declared_automatically_when_asked(ctx: rclpy.Context) -> None:
    node = Node(
        "arm",
        namespace="/robots",
        context=ctx,
        automatically_declare_parameters_from_overrides=True,
        parameter_overrides=[Parameter("extra", value="x")],
    )
    names = node.list_parameters([], 0).names
    assert {"speed", "gains.p", "gains.d", "shared", "extra", "use_sim_time", RCLPY_OWN} == set(names)
    assert node.list_parameters(["gains"], 0).names == ["gains.p", "gains.d"]
    assert set(node.list_parameters([], 1).names) == {"speed", "shared", "extra", "use_sim_time", RCLPY_OWN}


def test_undeclared_parameters_are_refused_unless_the_node_allows_them(ctx: rclpy.Context) -> None:
    strict = Node("strict", context=ctx)
    with pytest.raises(ParameterNotDeclaredException, match="undeclared parameter"):
        strict.set_parameters([Parameter("free", value=1)])
    with pytest.raises(ParameterNotDeclaredException):
        strict.get_parameter("free")
    loose = Node("loose", context=ctx, allow_undeclared_parameters=True)
    assert loose.get_parameter("free").type_ == Parameter.Type.NOT_SET
    assert loose.set_parameters([Parameter("free", value=1)])[0].successful
    assert loose.get_parameter("free").value == 1
    assert loose.set_parameters([Parameter("free", value="now text")])[0].successful  # dynamically typed


def test_declaring_with_a_wrong_type_or_twice_raises_as_rclpy_does(ctx: rclpy.Context) -> None:
    node = Node("strict", context=ctx, parameter_overrides=[Parameter("rate", value="fast")])
    with pytest.raises(InvalidParameterTypeException, match="expecting type 'DOUBLE'"):
        node.declare_parameter("rate", 1.0)
    node.declare_parameter("fixed", 1, ParameterDescriptor(read_only=True))
    with pytest.raises(ParameterImmutableException):
        node.undeclare_parameter("fixed")
    with pytest.raises(Exception, match="already declared"):
        node.declare_parameter("fixed", 2)


def test_parameter_events_tell_what_was_declared_changed_and_undeclared(ctx: rclpy.Context) -> None:
    node = Node("talker", context=ctx)
    watcher = Node("watcher", context=ctx)
    events: list[ParameterEvent] = []
    watcher.create_subscription(ParameterEvent, "/parameter_events", events.append, 10)
    node.declare_parameter("volume", 3)
    node.set_parameters([Parameter("volume", value=4)])
    node.undeclare_parameter("volume")
    marker = Node("marker", context=ctx)
    marker.declare_parameter("done", True)
    executor = rclpy.executors.SingleThreadedExecutor(context=ctx)
    executor.add_node(watcher)
    while not any(e.node == "/marker" for e in events):
        executor.spin_once(timeout_sec=1.0)
    mine = [e for e in events if e.node == "/talker"]
    assert [[p.name for p in e.new_parameters] for e in mine] == [["volume"], [], []]
    assert [p.value.integer_value for p in mine[1].changed_parameters] == [4]
    assert [p.name for p in mine[2].deleted_parameters] == ["volume"]


def test_another_node_sets_lists_gets_and_describes_through_the_services(ctx: rclpy.Context) -> None:
    node = Node("guarded", context=ctx)
    rng = FloatingPointRange(from_value=0.0, to_value=10.0, step=0.0)
    node.declare_parameter("limit", 1.0, ParameterDescriptor(floating_point_range=[rng]))
    node.declare_parameter("name", "rover", ParameterDescriptor(read_only=True))
    node.declare_parameter("mode", "auto")
    heard: list[str] = []

    def check(params: list[Parameter]) -> SetParametersResult:
        for p in params:
            if p.name == "mode" and p.value not in ("auto", "manual"):
                return SetParametersResult(successful=False, reason=f"no such mode: {p.value}")
        heard.extend(f"{p.name}={p.value}" for p in params)
        return SetParametersResult(successful=True)

    node.add_on_set_parameters_callback(check)
    caller = Node("caller", context=ctx)
    client = AsyncParameterClient(caller, "guarded")
    assert client.wait_for_services(timeout_sec=2.0)
    changes = [
        Parameter("mode", value="manual"),
        Parameter("mode", value="warp"),
        Parameter("limit", value=11.0),
        Parameter("name", value="x"),
        Parameter("nope", value=1),
    ]
    answer = spun(ctx, caller, client.set_parameters(changes))
    results = [(r.successful, r.reason) for r in answer.results]
    assert results[0] == (True, "")
    assert results[1] == (False, "no such mode: warp")
    assert results[2] == (False, "Parameter limit out of range Min: 0.0, Max: 10.0, value: 11.0")
    assert results[3] == (False, "Trying to set a read-only parameter: name.")
    assert results[4][0] is False and "undeclared" in results[4][1]
    assert heard == ["mode=manual"] and node.get_parameter("mode").value == "manual"
    listed = spun(ctx, caller, client.list_parameters())
    assert sorted(listed.result.names) == ["limit", "mode", "name", RCLPY_OWN, "use_sim_time"]
    got = spun(ctx, caller, client.get_parameters(["limit", "mode"]))
    assert [v.double_value for v in got.values[:1]] + [got.values[1].string_value] == [1.0, "manual"]
    assert spun(ctx, caller, client.get_parameters(["limit", "missing"])).values == []
    described = spun(ctx, caller, client.describe_parameters(["limit"])).descriptors
    assert described[0].name == "limit" and described[0].floating_point_range[0].to_value == 10.0
    types = spun(ctx, caller, client.get_parameter_types(["limit", "name"])).types
    assert list(types) == [Parameter.Type.DOUBLE.value, Parameter.Type.STRING.value]
    atomic = spun(
        ctx,
        caller,
        client.set_parameters_atomically([Parameter("limit", value=2.0), Parameter("mode", value="warp")]),
    ).result
    assert (atomic.successful, node.get_parameter("limit").value) == (False, 1.0)  # all or none
