"""The parameter services of the lab's own (bus) nodes, called as ``ros2 param`` calls them: through
the bus's service clients, answered by the executor, on a manual clock."""

from __future__ import annotations

from typing import Any

import pytest

from node_runtime.bus import Bus, Executor, ManualClock, Node, NodeOverrides
from node_runtime.bus.parameter_service import serve_parameters
from node_runtime.bus.parameter_values import double_range, from_value_msg, read_only, to_value_msg
from node_runtime.msgs import Message, PoseStamped, Vector3
from node_runtime.msgs.generated.rcl_interfaces import (
    DescribeParameters,
    GetParameters,
    GetParameterTypes,
    ListParameters,
    Parameter,
    ParameterEvent,
    SetParameters,
    SetParametersAtomically,
)
from node_runtime.params_file import value_from_text
from server.packages.flightcontroller.position_controller import PositionControllerNode
from server.packages.simple_control.keyboard_manager import KeyboardManager


class _Tuned(Node):
    def __init__(self, bus: Bus) -> None:
        super().__init__("tuned", namespace="/lab", context=bus)
        self.declare_parameter("seed", 7, read_only("random seed"))
        self.declare_parameter("gain", 1.5, double_range(0.0, 10.0, "P gain"))
        self.declare_parameter("label", "drone")
        self.declare_parameter("limits.low", [1, 2])


@pytest.fixture
def tuned(bus: Bus) -> _Tuned:
    node = _Tuned(bus)
    serve_parameters(node)
    return node


def _call(bus: Bus, executor: Executor, srv: Any, name: str, **request: Any) -> Any:
    caller = Node("ros2param", context=bus)
    future = caller.create_client(srv, name).call_async(srv.Request(**request))
    assert not future.done()  # answered by the executor, never inside the call
    executor.spin_some()
    caller.destroy_node()
    assert future.done()
    return future.result()


def _param(name: str, value: Any) -> Parameter:
    return Parameter(name=name, value=to_value_msg(value))


def _set_one(bus: Bus, executor: Executor, node: str, name: str, value: Any) -> Any:
    """The one result of ``node``'s ``set_parameters`` for one parameter, as ``ros2 param set``."""
    (result,) = _call(
        bus, executor, SetParameters, f"{node}/set_parameters", parameters=[_param(name, value)]
    ).results
    return result


def test_a_served_node_lists_its_parameters_and_prefixes(bus: Bus, executor: Executor, tuned: _Tuned) -> None:
    result = _call(bus, executor, ListParameters, "/lab/tuned/list_parameters").result
    assert sorted(result.names) == ["gain", "label", "limits.low", "seed", "use_sim_time"]
    assert list(result.prefixes) == ["limits"]
    shallow = _call(bus, executor, ListParameters, "/lab/tuned/list_parameters", depth=1).result
    assert sorted(shallow.names) == ["gain", "label", "seed", "use_sim_time"]


def test_get_and_types_answer_each_name_and_nothing_for_an_undeclared_one(
    bus: Bus, executor: Executor, tuned: _Tuned
) -> None:
    values = _call(
        bus, executor, GetParameters, "/lab/tuned/get_parameters", names=["seed", "gain", "limits.low"]
    )
    assert [from_value_msg(v) for v in values.values] == [7, 1.5, [1, 2]]
    types = _call(bus, executor, GetParameterTypes, "/lab/tuned/get_parameter_types", names=["label", "seed"])
    assert list(types.types) == [4, 2]  # string, integer
    missing = _call(bus, executor, GetParameters, "/lab/tuned/get_parameters", names=["seed", "nope"])
    assert list(missing.values) == []  # as rclpy answers


def test_describe_gives_type_read_only_and_range(bus: Bus, executor: Executor, tuned: _Tuned) -> None:
    seed, gain = _call(
        bus, executor, DescribeParameters, "/lab/tuned/describe_parameters", names=["seed", "gain"]
    ).descriptors
    assert (seed.name, seed.type, seed.read_only, seed.description) == ("seed", 2, True, "random seed")
    assert (gain.type, gain.read_only) == (3, False)
    assert (gain.floating_point_range[0].from_value, gain.floating_point_range[0].to_value) == (0.0, 10.0)


def test_a_set_in_range_takes_effect_and_one_out_of_range_is_refused_with_the_reason(
    bus: Bus, executor: Executor, tuned: _Tuned
) -> None:
    results = _call(
        bus,
        executor,
        SetParameters,
        "/lab/tuned/set_parameters",
        parameters=[_param("gain", 4.0), _param("gain", 11.0), _param("label", "rocket")],
    ).results
    assert [r.successful for r in results] == [True, False, True]
    assert "out of range" in results[1].reason and "Max: 10.0" in results[1].reason
    assert tuned.get_parameter("gain").value == 4.0  # the refused 11.0 changed nothing
    assert tuned.get_parameter("label").value == "rocket"


@pytest.mark.parametrize(
    ("name", "value", "reason"),
    [
        ("seed", 8, "Trying to set a read-only parameter: seed."),
        ("label", 3, "Wrong parameter type"),
        # ``ros2 param set /lab/tuned gain 5`` sends what YAML reads in "5": an integer, which
        # rclpy refuses for a double parameter (an integer is no double there).
        ("gain", value_from_text("5"), "Wrong parameter type, expected '3' got '2'"),
        ("nope", 1, "'nope' of /lab/tuned was not declared"),
    ],
)
def test_a_refused_set_says_why_and_changes_nothing(
    bus: Bus, executor: Executor, tuned: _Tuned, name: str, value: Any, reason: str
) -> None:
    before = tuned.get_parameters_dict()
    (result,) = _call(
        bus, executor, SetParameters, "/lab/tuned/set_parameters", parameters=[_param(name, value)]
    ).results
    assert not result.successful and reason in result.reason
    assert tuned.get_parameters_dict() == before


def test_an_atomic_set_with_one_refusal_changes_none(bus: Bus, executor: Executor, tuned: _Tuned) -> None:
    refused = _call(
        bus,
        executor,
        SetParametersAtomically,
        "/lab/tuned/set_parameters_atomically",
        parameters=[_param("gain", 2.0), _param("seed", 1)],
    ).result
    assert not refused.successful and "read-only" in refused.reason
    assert tuned.get_parameter("gain").value == 1.5
    wrong_type = _call(
        bus,
        executor,
        SetParametersAtomically,
        "/lab/tuned/set_parameters_atomically",
        parameters=[_param("label", "x"), _param("gain", 2)],  # an integer is no double, as in rclpy
    ).result
    assert not wrong_type.successful
    assert wrong_type.reason == "Wrong parameter type, expected '3' got '2'"
    unchanged = {"use_sim_time": False, "seed": 7, "gain": 1.5, "label": "drone", "limits.low": [1, 2]}
    assert tuned.get_parameters_dict() == unchanged
    accepted = _call(
        bus,
        executor,
        SetParametersAtomically,
        "/lab/tuned/set_parameters_atomically",
        parameters=[_param("gain", 2.0), _param("label", "x")],
    ).result
    assert accepted.successful
    assert tuned.get_parameters_dict()["gain"] == 2.0 and tuned.get_parameter("label").value == "x"


def test_a_lab_node_declares_use_sim_time_false_as_every_rclpy_node_does(
    bus: Bus, executor: Executor, tuned: _Tuned
) -> None:
    got = _call(bus, executor, GetParameters, "/lab/tuned/get_parameters", names=["use_sim_time"])
    assert [from_value_msg(v) for v in got.values] == [False]
    (described,) = _call(
        bus, executor, DescribeParameters, "/lab/tuned/describe_parameters", names=["use_sim_time"]
    ).descriptors
    assert (described.name, described.type, described.read_only) == ("use_sim_time", 1, False)  # a bool
    with bus.activate(NodeOverrides(parameters={"use_sim_time": True})):  # a launch's override wins
        assert Node("timed", context=bus).get_parameter("use_sim_time").value is True


def _events(bus: Bus, node: str) -> list[ParameterEvent]:
    """``node``'s events on /parameter_events (each caller's node publishes its own declaration)."""
    events: list[ParameterEvent] = []

    def heard(event: ParameterEvent) -> None:
        if event.node == node:
            events.append(event)

    Node("_watcher", context=bus).create_subscription(ParameterEvent, "/parameter_events", heard, 1000)
    return events


def _names(params: Any) -> list[str]:
    return [p.name for p in params]


def test_parameter_events_tell_each_declaration_and_each_set_that_took_effect(
    bus: Bus, executor: Executor, clock: ManualClock
) -> None:
    events = _events(bus, "/lab/tuned")
    clock.set(12.5)
    tuned = _Tuned(bus)
    serve_parameters(tuned)
    executor.spin_some()
    assert [_names(e.new_parameters) for e in events] == [
        ["use_sim_time"],
        ["seed"],
        ["gain"],
        ["label"],
        ["limits.low"],
    ]
    assert [from_value_msg(e.new_parameters[0].value) for e in events] == [False, 7, 1.5, "drone", [1, 2]]
    assert (events[0].stamp.sec, events[0].stamp.nanosec) == (12, 500_000_000)
    events.clear()
    clock.set(20.0)
    _call(
        bus,
        executor,
        SetParameters,
        "/lab/tuned/set_parameters",
        parameters=[_param("gain", 4.0), _param("gain", 11.0), _param("label", "rocket")],
    )
    _call(
        bus,
        executor,
        SetParametersAtomically,
        "/lab/tuned/set_parameters_atomically",
        parameters=[_param("gain", 2.0), _param("seed", 1)],
    )  # (refused: seed is read-only)
    executor.spin_some()
    assert [(_names(e.new_parameters), _names(e.changed_parameters)) for e in events] == [
        ([], ["gain"]),
        ([], ["label"]),
    ]  # (one event per set that took effect; the refused 11.0 and the atomic set: none)
    assert from_value_msg(events[0].changed_parameters[0].value) == 4.0
    assert [(e.stamp.sec, list(e.deleted_parameters)) for e in events] == [(20, []), (20, [])]


def test_a_dynamically_typed_parameter_is_new_at_its_first_value_and_deleted_when_set_to_nothing(
    bus: Bus, executor: Executor, tuned: _Tuned
) -> None:
    events = _events(bus, "/lab/tuned")
    tuned.declare_parameter("free")  # no value: dynamically typed, not set yet
    for value in ("anything", None):
        (result,) = _call(
            bus, executor, SetParameters, "/lab/tuned/set_parameters", parameters=[_param("free", value)]
        ).results
        assert result.successful
    executor.spin_some()
    assert [
        (_names(e.new_parameters), _names(e.changed_parameters), _names(e.deleted_parameters)) for e in events
    ] == [(["free"], [], []), (["free"], [], []), ([], [], ["free"])]  # as rclpy tells them
    assert not tuned.has_parameter("free")
    (static,) = _call(
        bus, executor, SetParameters, "/lab/tuned/set_parameters", parameters=[_param("label", None)]
    ).results
    assert (static.successful, static.reason) == (False, "Static parameter cannot be undeclared")


def test_a_lab_node_publishes_an_event_for_a_set_and_none_while_it_only_runs(
    bus: Bus, executor: Executor, clock: ManualClock
) -> None:
    with bus.activate(NodeOverrides(parameters={"mode": "lab"})):
        manager = KeyboardManager()
    serve_parameters(manager)
    events = _events(bus, "/KeyboardManagerNode")
    executor.spin_until(clock.now() + 2.0)  # its timer publishes at 20 Hz
    assert manager.timer is not None and manager.timer.call_count >= 39
    assert events == []  # no tick publishes one
    result = _set_one(bus, executor, "/KeyboardManagerNode", "rate_hz", 50.0)
    assert result.successful
    executor.spin_until(clock.now() + 2.0)
    assert [_names(e.changed_parameters) for e in events] == [["rate_hz"]]  # the set's, and only it


def test_serving_twice_adds_nothing_and_the_services_go_with_the_node(bus: Bus, tuned: _Tuned) -> None:
    assert serve_parameters(tuned) == []
    assert len([s for s in tuned.services if s.srv_name.startswith("/lab/tuned/")]) == 6
    tuned.destroy_node()
    assert not [name for name in bus.services if name.startswith("/lab/tuned/")]


def test_an_override_the_descriptor_refuses_stops_the_node_at_its_declaration(bus: Bus) -> None:
    with (
        bus.activate(NodeOverrides(parameters={"gain": 99.0})),
        pytest.raises(ValueError, match="out of range"),
    ):
        _Tuned(bus)
    with bus.activate(NodeOverrides(parameters={"gain": 3})):  # the legitimate override still works
        assert _Tuned(bus).get_parameter("gain").value == 3.0


def test_a_keyboard_managers_rate_set_over_its_service_changes_how_often_it_publishes(
    bus: Bus, executor: Executor, clock: ManualClock
) -> None:
    with bus.activate(NodeOverrides(parameters={"mode": "lab"})):
        manager = KeyboardManager()
    serve_parameters(manager)
    seen: list[Message] = []
    Node("listener", context=bus).create_subscription(Vector3, "/uav/input/position", seen.append, 100)
    executor.spin_until(clock.now() + 1.0)
    at_20_hz = len(seen)
    result = _set_one(bus, executor, "/KeyboardManagerNode", "rate_hz", 50.0)
    assert result.successful
    seen.clear()
    executor.spin_until(clock.now() + 1.0)
    assert 19 <= at_20_hz <= 21 and 49 <= len(seen) <= 51
    refused = _set_one(bus, executor, "/KeyboardManagerNode", "rate_hz", 0.0)
    assert not refused.successful and "rate_hz" in refused.reason
    assert manager.get_parameter("rate_hz").value == 50.0


def test_the_position_controllers_lab_gains_set_over_its_service_scale_its_command(
    bus: Bus, executor: Executor, clock: ManualClock
) -> None:
    with bus.activate(NodeOverrides(parameters={"mode": "lab"})):
        controller = PositionControllerNode()
    serve_parameters(controller)
    commands: list[Vector3] = []
    talker = Node("talker", context=bus)
    Node("listener", context=bus).create_subscription(Vector3, "/uav/input/velocity", commands.append, 100)
    talker.create_publisher(Vector3, "/uav/input/position", 10).publish(Vector3(x=1.0, y=0.0, z=2.0))
    talker.create_publisher(PoseStamped, "/uav/sensors/gps", 10).publish(PoseStamped())
    executor.spin_until(clock.now() + 0.1)
    before = commands[-1]
    result = _set_one(bus, executor, "/PositionControllerNode", "gains.p", 2.0)
    assert result.successful
    executor.spin_until(clock.now() + 0.1)
    after = commands[-1]
    assert (before.x, before.z) == pytest.approx((1.0, 2.0))  # P alone: gain 1 × the error
    assert (after.x, after.z) == pytest.approx((2.0, 4.0))
    refused = _set_one(bus, executor, "/PositionControllerNode", "gains.p", -1.0)
    assert not refused.successful and "out of range" in refused.reason
    assert controller.controller.pids[0].kp == 2.0
