"""ROS 2's tutorial programs, in our own versions written as Kilted writes them (tests/processes/
tutorials), each pair run as two node processes against a live lab, checked by what they print."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import REPO, App
from support.http import HTTP

from .node_process import NodeProcess

TUTORIALS = Path(__file__).resolve().parent / "tutorials" / "src" / "py_tutorials"
STAMP = r"\[\d+\.\d{9}\]"


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[App]:
    root = tmp_path_factory.mktemp("tutorials")
    app = App(
        root,
        "--launch",
        str(REPO / "server/packages/rocketship/launch/rocket.launch"),
        "--workspace",
        "no_workspace",
        "start_delay:=600",
        cwd=root,
    )
    try:
        yield app
    finally:
        app.stop()


@pytest.fixture
def run(lab: App) -> Iterator[type[NodeProcess]]:
    started: list[NodeProcess] = []

    class Started(NodeProcess):
        def __init__(self, file: str, *args: str) -> None:
            super().__init__(lab, TUTORIALS / file, *args)
            started.append(self)

    yield Started
    for proc in started:
        proc.kill()


def stopped_cleanly(proc: NodeProcess) -> None:
    assert proc.interrupt() == 0, proc.text[-3000:]
    assert "Traceback" not in proc.text, proc.text[-3000:]


@pytest.mark.parametrize(
    ("publisher", "subscriber"),
    [
        ("publisher_member_function.py", "subscriber_lambda.py"),
        ("publisher_local_function.py", "subscriber_member_function.py"),
    ],
)
def test_publisher_and_subscriber_print_what_was_sent_and_heard(
    run: type[NodeProcess], publisher: str, subscriber: str
) -> None:
    listener = run(subscriber)
    talker = run(publisher)
    heard = listener.wait_for(rf'^\[INFO\] {STAMP} \[minimal_subscriber\]: I heard: "Hello World: (\d+)"$', 3)
    numbers = [int(m[1]) for m in heard]
    assert numbers == sorted(numbers) and len(set(numbers)) == 3
    for n in numbers:  # each was published, and said so, as rclpy says it
        talker.wait_for(rf'^\[INFO\] {STAMP} \[minimal_publisher\]: Publishing: "Hello World: {n}"$')
    stopped_cleanly(talker)
    stopped_cleanly(listener)


@pytest.mark.parametrize(
    ("client", "node_name", "a", "b"),
    [
        ("client_async.py", "minimal_client_async", 2, 3),
        ("client_sync.py", "minimal_client_sync", 40, 2),
        ("client_done_callback.py", "minimal_client_callback", -7, 10),
    ],
)
def test_service_and_client_add_two_ints(
    run: type[NodeProcess], client: str, node_name: str, a: int, b: int
) -> None:
    server = run("service_member_function.py")
    caller = run(client, str(a), str(b))
    assert caller.finish() == 0, caller.text  # the client ends by itself once it has its answer
    caller.wait_for(rf"^\[INFO\] {STAMP} \[{node_name}\]: Result of add_two_ints: for {a} \+ {b} = {a + b}$")
    server.wait_for(rf"^\[INFO\] {STAMP} \[minimal_service\]: Incoming request\na: {a} b: {b}$")
    assert "Traceback" not in caller.text
    stopped_cleanly(server)


def test_synchronous_call_from_a_reentrant_timer_completes_on_a_multithreaded_executor(
    run: type[NodeProcess],
) -> None:
    server = run("service_member_function.py")
    caller = run("reentrant_caller.py")
    done = caller.wait_for(
        rf"^\[INFO\] {STAMP} \[reentrant_caller\]: call (\d+) from the timer: \d+ \+ 100 = (\d+)$", 3
    )
    assert [(int(m[1]), int(m[2])) for m in done] == [(1, 101), (2, 102), (3, 103)]
    stopped_cleanly(caller)
    stopped_cleanly(server)


def test_guard_condition_triggered_from_a_callback_runs_its_own_callback(run: type[NodeProcess]) -> None:
    listener = run("guard_listener.py")
    talker = run("publisher_member_function.py")
    fired = listener.wait_for(
        rf'^\[INFO\] {STAMP} \[guard_listener\]: guard condition triggered after (\d+) messages, last "Hello World: \d+"$',
        2,
    )
    assert [int(m[1]) for m in fired] == [5, 10]
    stopped_cleanly(talker)
    stopped_cleanly(listener)


def test_a_transient_local_late_joiner_gets_the_sample_published_before_it_came(
    run: type[NodeProcess], lab: App
) -> None:
    """The publisher publishes once, in its constructor, before the subscriber's process exists:
    only the publisher's cache (rmw_zenoh's advanced publisher) can hand it over."""
    talker = run("latched_publisher.py")
    talker.wait_for(rf'^\[INFO\] {STAMP} \[latched_publisher\]: Published once: "the lab floor"$')

    def listed() -> bool:  # 404 until the graph has the publisher's token
        reply = HTTP.get(f"{lab.url}/api/topics/map_name", timeout=5.0)
        return reply.status_code == 200 and reply.json()["endpoints"] != []

    lab.wait_for(listed, "the publisher in the graph")
    listener = run("late_subscriber.py")
    listener.wait_for(rf'^\[INFO\] {STAMP} \[late_subscriber\]: Late joiner got: "the lab floor"$')
    stopped_cleanly(listener)
    stopped_cleanly(talker)


def test_parameters_in_a_class_take_ros_args_and_a_callback_refuses_with_its_reason(
    run: type[NodeProcess],
) -> None:
    node = run("parameter_node.py", "--ros-args", "-p", "my_parameter:=earth")
    node.wait_for(rf"^\[INFO\] {STAMP} \[minimal_param_node\]: Hello earth!$")
    node.wait_for(
        rf"^\[INFO\] {STAMP} \[minimal_param_node\]: Setting it empty: False, my_parameter must not be empty$"
    )
    node.wait_for(rf"^\[INFO\] {STAMP} \[minimal_param_node\]: Hello world!$")  # the node set it back
    stopped_cleanly(node)
