"""The introspection API through the real app: /api/graph, /api/nodes, /api/hz, /api/types.

The app runs on its own clock in TestClient's event-loop thread; changes to the graph are made
on that thread (``portal.call``), and waits on the live lab are bounded polls.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest
from fastapi.testclient import TestClient

from api import deps
from node_runtime.bus import ManualClock, Node
from server.app import create_app
from server.host.settings import LabSettings, Listening, Settings
from server.world.lab import Lab

LAB_NODES = {"/CountDownNode", "/MainControllerNode", "/RocketEngineNode", "/KeyboardManager", "/keyboard"}
LAB_TOPICS = {"/countdown", "/cmd_vel", "/sensor_vel", "/abort_takeoff", "/keydown", "/keyup"}
LAB_EDGES = {
    ("/CountDownNode", "/countdown", "publish"),
    ("/countdown", "/MainControllerNode", "subscribe"),
    ("/MainControllerNode", "/cmd_vel", "publish"),
    ("/cmd_vel", "/RocketEngineNode", "subscribe"),
    ("/RocketEngineNode", "/sensor_vel", "publish"),
    ("/keyboard", "/keydown", "publish"),
    ("/keyboard", "/keyup", "publish"),
    ("/keydown", "/KeyboardManager", "subscribe"),
    ("/KeyboardManager", "/abort_takeoff", "publish"),
    ("/abort_takeoff", "/MainControllerNode", "subscribe"),
}
WAIT_S = 5.0


@pytest.fixture
def client() -> Iterator[TestClient]:
    app = create_app(
        Settings(
            listen=Listening(allowed_hosts=("testserver",)), lab=LabSettings(launch="rocket", viewer=False)
        )
    )
    with TestClient(app) as test_client:
        yield test_client


def lab_of(client: TestClient) -> Lab:
    return client.app.state.lab  # type: ignore[attr-defined]


def on_loop(client: TestClient, fn: Callable[[], Any]) -> Any:
    """Run ``fn`` on the app's event-loop thread, where the executor touches the bus."""
    assert client.portal is not None
    return client.portal.call(fn)


def poll(fetch: Callable[[], Any], done: Callable[[Any], bool], timeout_s: float = WAIT_S) -> Any:
    """Fetch until ``done`` holds or ``timeout_s`` passes; returns the last value either way."""
    deadline = time.monotonic() + timeout_s
    value = fetch()
    while not done(value) and time.monotonic() < deadline:
        time.sleep(0.02)
        value = fetch()
    return value


def edges(graph: dict[str, Any]) -> set[tuple[str, str, str]]:
    return {(e["from"], e["to"], e["kind"]) for e in graph["edges"]}


# -- /api/graph --------------------------------------------------------------------------------
def test_graph_rocket_launch_has_the_lab_nodes_topics_and_edges(client: TestClient) -> None:
    graph = client.get("/api/graph").json()
    assert {n["name"] for n in graph["nodes"]} == LAB_NODES
    assert {t["name"] for t in graph["topics"]} == LAB_TOPICS
    assert edges(graph) == LAB_EDGES
    assert all(n["state"] == "active" and not n["hidden"] for n in graph["nodes"])
    assert {t["name"]: t["type"] for t in graph["topics"]}["/keydown"] == "keyboard_msgs/msg/Key"
    assert isinstance(graph["version"], int)


def test_graph_hidden_true_adds_debug_nodes_rosout_and_their_edges_once(client: TestClient) -> None:
    graph = client.get("/api/graph", params={"hidden": "true"}).json()
    hidden_nodes = {n["name"] for n in graph["nodes"] if n["hidden"]}
    assert {"/_rest_api", "/_rocket_view"} <= hidden_nodes
    assert {t["name"] for t in graph["topics"] if t["hidden"]} >= {"/rosout"}
    assert ("/CountDownNode", "/rosout", "publish") in edges(graph)
    assert ("/sensor_vel", "/_rocket_view", "subscribe") in edges(graph)
    assert len(graph["edges"]) == len(edges(graph))


def test_graph_after_destroy_node_drops_it_and_its_unused_topics_and_changes_version(
    client: TestClient,
) -> None:
    before = client.get("/api/graph").json()
    on_loop(client, lambda: lab_of(client).bus.get_node("/keyboard").destroy_node())
    after = client.get("/api/graph").json()
    assert after["version"] != before["version"]
    assert "/keyboard" not in {n["name"] for n in after["nodes"]}
    topics = {t["name"] for t in after["topics"]}
    assert "/keyup" not in topics  # only the keyboard used it
    assert "/keydown" in topics  # KeyboardManager still subscribes
    assert all("/keyboard" not in (e["from"], e["to"]) for e in after["edges"])
    assert client.get("/api/nodes/keyboard").status_code == 404


def test_graph_and_nodes_node_crashing_in_its_timer_shows_crashed(client: TestClient) -> None:
    def start_fragile() -> Node:
        with lab_of(client).bus.activate():
            node = Node("Fragile")

        def fail() -> None:
            raise RuntimeError("sensor unplugged")

        node.create_timer(0.01, fail)
        return node

    on_loop(client, start_fragile)
    crashed = {
        "name": "/Fragile",
        "namespace": "/",
        "state": "crashed",
        "location": "app",
        "exit_code": None,
        "respawn": None,
    }
    nodes = poll(lambda: client.get("/api/nodes").json(), lambda ns: crashed in ns)
    assert crashed in nodes
    graph = client.get("/api/graph").json()
    assert {"name": "/Fragile", "state": "crashed", "hidden": False, "location": "app"} in graph["nodes"]
    info = client.get("/api/nodes/Fragile").json()
    assert info["crash_reason"] == "RuntimeError: sensor unplugged"
    assert all(n["state"] == "active" for n in nodes if n["name"] != "/Fragile")


# -- /api/nodes --------------------------------------------------------------------------------
def test_nodes_default_lists_lab_nodes_sorted_and_hidden_true_adds_debug_nodes(client: TestClient) -> None:
    nodes = client.get("/api/nodes").json()
    assert [n["name"] for n in nodes] == sorted(LAB_NODES)
    assert all(n["namespace"] == "/" and n["state"] == "active" for n in nodes)
    everything = [n["name"] for n in client.get("/api/nodes", params={"hidden": "true"}).json()]
    assert everything == sorted(everything)
    assert {"/_rest_api", "/_rocket_view"} <= set(everything) and set(everything) >= LAB_NODES


def test_node_info_main_controller_has_its_endpoints_timer_and_origin(client: TestClient) -> None:
    info = poll(
        lambda: client.get("/api/nodes/MainControllerNode").json(), lambda i: i["timers"][0]["calls"] > 0
    )
    assert (info["name"], info["namespace"], info["state"], info["crash_reason"]) == (
        "/MainControllerNode",
        "/",
        "active",
        None,
    )
    assert {"topic": "/cmd_vel", "type": "std_msgs/msg/Float64", "depth": 1000} in info["publishers"]
    assert {p["topic"] for p in info["publishers"]} == {"/cmd_vel", "/rosout", "/parameter_events"}
    assert {s["topic"] for s in info["subscribers"]} == {"/countdown", "/abort_takeoff"}
    [timer] = info["timers"]
    assert timer["period_s"] == 0.1 and timer["calls"] > 0
    assert 0.0 <= timer["lateness_p50_ms"] <= timer["lateness_p99_ms"]
    assert isinstance(info["parameters"], dict)
    assert info["origin"]["package"] == "rocketship"


def test_node_info_countdown_shows_its_parameter(client: TestClient) -> None:
    info = client.get("/api/nodes/CountDownNode").json()
    assert info["parameters"]["start_delay_s"] == pytest.approx(5.0)


def test_node_info_unknown_node_is_404(client: TestClient) -> None:
    assert client.get("/api/nodes/NoSuchNode").status_code == 404


# -- /api/hz -----------------------------------------------------------------------------------
def test_hz_sensor_vel_is_10_hz_on_the_labs_clock() -> None:
    # The app runs on a manual clock that only this test moves: the engine's 10 Hz timer fires at
    # its exact deadlines, so the rate is exact whatever else the machine is doing.
    clock = ManualClock(100.0)
    app = create_app(
        Settings(
            listen=Listening(allowed_hosts=("testserver",)), lab=LabSettings(launch="rocket", viewer=False)
        ),
        clock=clock,
    )
    with TestClient(app) as manual:
        on_loop(manual, lambda: lab_of(manual).executor.spin_for(3.0))
        rate = manual.get("/api/hz/sensor_vel", params={"window": 10}).json()
    assert rate["window"] == 10, rate
    assert rate["topic"] == "/sensor_vel" and rate["count"] >= 11
    assert rate["rate_hz"] == pytest.approx(10.0, rel=1e-9)
    assert rate["min_s"] == pytest.approx(0.1) and rate["max_s"] == pytest.approx(0.1)
    assert rate["std_dev_s"] == pytest.approx(0.0, abs=1e-9)


def test_hz_topic_with_no_messages_yet_has_null_rate(client: TestClient) -> None:
    # The countdown waits 5 s before its first message; /keyup has none until a key is released.
    rate = client.get("/api/hz/keyup").json()
    assert rate == {
        "topic": "/keyup",
        "window": 0,
        "rate_hz": None,
        "min_s": None,
        "max_s": None,
        "std_dev_s": None,
        "count": 0,
        "watch": None,
    }


def test_hz_unknown_topic_is_404(client: TestClient) -> None:
    assert client.get("/api/hz/no_such_topic").status_code == 404


@pytest.mark.parametrize("window", [1, 10_001, "many"])
def test_hz_window_out_of_range_is_422(client: TestClient, window: Any) -> None:
    assert client.get("/api/hz/sensor_vel", params={"window": window}).status_code == 422


# -- /api/types --------------------------------------------------------------------------------
def test_types_lists_every_lab_type_sorted(client: TestClient) -> None:
    names = client.get("/api/types").json()
    assert names == sorted(names)
    assert {"std_msgs/msg/Int64", "geometry_msgs/msg/Vector3", "keyboard_msgs/msg/Key"} <= set(names)


def test_types_vector3_schema_is_an_object_of_three_numbers(client: TestClient) -> None:
    schema = client.get("/api/types/geometry_msgs/msg/Vector3").json()
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert (schema["title"], schema["type"], schema["additionalProperties"]) == (
        "geometry_msgs/msg/Vector3",
        "object",
        False,
    )
    assert {k: (v["type"], v["default"]) for k, v in schema["properties"].items()} == {
        "x": ("number", 0.0),
        "y": ("number", 0.0),
        "z": ("number", 0.0),
    }


def test_types_key_schema_code_is_uint16_and_header_nested(client: TestClient) -> None:
    schema = client.get("/api/types/keyboard_msgs/msg/Key").json()
    code = schema["properties"]["code"]
    assert (code["type"], code["minimum"], code["maximum"]) == ("integer", 0, 65535)
    assert schema["properties"]["modifiers"]["maximum"] == 65535
    assert schema["properties"]["header"]["title"] == "std_msgs/msg/Header"
    assert schema["properties"]["header"]["additionalProperties"] is False


def test_types_default_of_twist_short_name_is_all_zeros(client: TestClient) -> None:
    zeros = {"x": 0.0, "y": 0.0, "z": 0.0}
    assert client.get("/api/types/geometry_msgs/Twist/default").json() == {"linear": zeros, "angular": zeros}


@pytest.mark.parametrize(
    "path", ["/api/types/nope_msgs/msg/Nothing", "/api/types/nope_msgs/msg/Nothing/default"]
)
def test_types_unknown_type_is_404(client: TestClient, path: str) -> None:
    assert client.get(path).status_code == 404


# -- /tools ------------------------------------------------------------------------------------
def test_tools_page_is_served_with_its_scripts_and_a_same_origin_only_policy(client: TestClient) -> None:
    response = client.get("/tools")
    assert response.status_code == 200 and response.headers["content-type"].startswith("text/html")
    assert "/static/build/tools.js" in response.text
    assert "default-src 'self'" in response.headers["content-security-policy"]
    for asset in ("build/tools.js", "tools.css", "build/lab.js"):
        assert client.get(f"/static/{asset}").status_code == 200, asset


def test_nodes_and_topics_look_the_lab_up_on_the_loop_never_in_the_thread_pool(
    client: TestClient, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A plain ``def`` dependency runs in FastAPI's thread pool: each call would go to a thread and
    back, two more turns of a loop a class's worlds keep busy. The lab is found on the loop."""
    threads: list[threading.Thread] = []
    find = deps.lab_of

    def recorded(conn: Any) -> Lab:
        threads.append(threading.current_thread())
        return find(conn)

    monkeypatch.setattr(deps, "lab_of", recorded)
    loop_thread = on_loop(client, threading.current_thread)
    for path in ("/api/nodes", "/api/topics", "/api/graph"):
        assert client.get(path).status_code == 200
    assert threads == [loop_thread] * 3
