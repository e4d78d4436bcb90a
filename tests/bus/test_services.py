"""Services on the bus: a call is queued, the executor runs the server, the client's future completes."""

from __future__ import annotations

import pytest

from node_runtime.bus import Bus, Executor, Node, TopicTypeError
from node_runtime.msgs import Bool, get_service_type

AddTwoInts = get_service_type("example_interfaces/srv/AddTwoInts")
Trigger = get_service_type("std_srvs/srv/Trigger")


class _Adder(Node):
    def __init__(self, bus: Bus, name: str = "adder") -> None:
        super().__init__(name, context=bus)
        self.calls = 0
        self.srv = self.create_service(AddTwoInts, "add_two_ints", self.add)

    def add(self, request, response):  # type: ignore[no-untyped-def]
        self.calls += 1
        response.sum = request.a + request.b
        return response


def test_call_async_runs_server_only_when_executor_spins(bus: Bus, executor: Executor) -> None:
    adder = _Adder(bus)
    client = Node("caller", context=bus).create_client(AddTwoInts, "/add_two_ints")
    assert client.service_is_ready()
    future = client.call_async(AddTwoInts.Request(a=2, b=40))
    assert not future.done() and adder.calls == 0  # never inside call_async
    executor.spin_some()
    assert future.done() and future.result() == AddTwoInts.Response(sum=42)
    assert adder.calls == 1


def test_request_is_copied_so_later_changes_do_not_reach_the_server(bus: Bus, executor: Executor) -> None:
    _Adder(bus)
    client = Node("caller", context=bus).create_client(AddTwoInts, "add_two_ints")
    request = AddTwoInts.Request(a=1, b=1)
    future = client.call_async(request)
    request.a = 100
    executor.spin_some()
    assert future.result() == AddTwoInts.Response(sum=2)


def test_done_callback_runs_when_the_response_arrives(bus: Bus, executor: Executor) -> None:
    _Adder(bus)
    client = Node("caller", context=bus).create_client(AddTwoInts, "add_two_ints")
    seen: list[int] = []
    client.call_async(AddTwoInts.Request(a=3, b=4)).add_done_callback(lambda f: seen.append(f.result().sum))
    executor.spin_some()
    assert seen == [7]


def test_call_without_server_waits_and_is_not_ready(bus: Bus, executor: Executor) -> None:
    client = Node("caller", context=bus).create_client(Trigger, "/nobody")
    assert not client.service_is_ready()
    future = client.call_async(Trigger.Request())
    executor.spin_for(1.0)
    assert not future.done()


def test_server_that_raises_crashes_its_node_and_leaves_the_call_pending(
    bus: Bus, executor: Executor
) -> None:
    class Broken(Node):
        def __init__(self) -> None:
            super().__init__("broken", context=bus)
            self.create_service(Trigger, "/go", lambda req, res: 1 / 0)

    broken = Broken()
    future = Node("caller", context=bus).create_client(Trigger, "/go").call_async(Trigger.Request())
    executor.spin_some()
    assert broken.state == "crashed" and "ZeroDivisionError" in (broken.crash_reason or "")
    assert not future.done()


def test_server_returning_wrong_type_is_a_fault_of_its_node(bus: Bus, executor: Executor) -> None:
    node = Node("sloppy", context=bus)
    node.create_service(Trigger, "/go", lambda req, res: Bool(data=True))
    Node("caller", context=bus).create_client(Trigger, "/go").call_async(Trigger.Request())
    executor.spin_some()
    assert node.state == "crashed" and "not std_srvs/srv/Trigger_Response" in (node.crash_reason or "")


def test_call_with_wrong_request_type_raises_type_error(bus: Bus) -> None:
    client = Node("caller", context=bus).create_client(AddTwoInts, "add_two_ints")
    with pytest.raises(TopicTypeError, match="takes example_interfaces/srv/AddTwoInts_Request"):
        client.call_async(Trigger.Request())  # type: ignore[arg-type]


def test_service_of_other_type_on_same_name_conflicts(bus: Bus) -> None:
    _Adder(bus)
    with pytest.raises(TopicTypeError, match="is a example_interfaces/srv/AddTwoInts"):
        Node("other", context=bus).create_service(Trigger, "/add_two_ints", lambda q, r: r)


def test_destroying_nodes_drops_the_service_from_the_graph(bus: Bus) -> None:
    adder = _Adder(bus)
    caller = Node("caller", context=bus)
    caller.create_client(AddTwoInts, "add_two_ints")
    assert "/add_two_ints" in bus.services
    adder.destroy_node()
    assert "/add_two_ints" in bus.services  # the client still names it
    caller.destroy_node()
    assert "/add_two_ints" not in bus.services


def test_service_names_resolve_like_topics(bus: Bus) -> None:
    node = Node("n", namespace="/ns", context=bus)
    server = node.create_service(Trigger, "~/reset", lambda q, r: r)
    assert server.srv_name == "/ns/n/reset"
