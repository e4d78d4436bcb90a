"""Foxglove, rosbridge and ros2 bag see the whole graph, not only this process's nodes: a topic only
another process publishes (here the independent zenoh-ros2-sdk peer, as a student's node process
would) is advertised as a Foxglove channel, listed by rosapi and recorded by `bag record -a`, and
each carries its messages."""

from __future__ import annotations

import io
import json
import struct
import time
from collections.abc import Iterator
from typing import Any

import pytest
from mcap.reader import make_reader
from mcap.records import Schema as McapSchema
from mcap_ros2.decoder import DecoderFactory
from ros_reference import rihs
from support.app import App, JsonProcess, free_port
from support.http import HTTP
from websockets.sync.client import ClientConnection, connect

from .conftest import definitions, service_text

STRING = "std_msgs/msg/String"
READ_S = 10.0


@pytest.fixture(scope="module")
def foxglove_port() -> int:
    return free_port()


@pytest.fixture(scope="module")
def app(tmp_path_factory: pytest.TempPathFactory, foxglove_port: int) -> Iterator[App]:
    """The rocket alone (a small graph), with the Foxglove server on a port of its own."""
    workdir = tmp_path_factory.mktemp("bridges")  # its ./bags too
    lab = App(
        workdir,
        "--launch",
        "rocket",
        "start_delay:=3600",
        "--foxglove-port",
        str(foxglove_port),
        cwd=workdir,
    )
    try:
        yield lab
    finally:
        lab.stop()


def publish(peer: JsonProcess, topic: str, data: str) -> None:
    peer.send(
        cmd="publish", topic=topic, type=STRING, hash=rihs(STRING), msg={"data": data}, node="sdk_talker"
    )


def until_frame(ws: ClientConnection, peer: JsonProcess, topic: str, binary: bool) -> Any:
    """Have the peer publish on ``topic`` until a frame of that kind comes (the first samples may
    go out before the new subscription's route is in place, as for any ROS 2 subscription)."""
    deadline = time.monotonic() + READ_S
    i = 0
    while time.monotonic() < deadline:
        publish(peer, topic, f"n{i}")
        i += 1
        try:
            frame = ws.recv(timeout=0.3)
        except TimeoutError:
            continue
        if isinstance(frame, bytes) == binary:
            return frame
    pytest.fail(f"no message on {topic} reached the client in {READ_S} s ({i} published)")


def rosapi(ws: ClientConnection, which: str, **args: Any) -> dict[str, Any]:
    """Call ``/rosapi/<which>`` over rosbridge, as roslibpy's ``get_nodes`` and the like do."""
    name = f"/rosapi/{which}"
    ws.send(json.dumps({"op": "call_service", "id": name, "service": name, "args": args}))
    deadline = time.monotonic() + READ_S
    while time.monotonic() < deadline:
        reply = json.loads(ws.recv(timeout=READ_S))
        if reply.get("op") == "service_response" and reply.get("id") == name:
            assert reply["result"] is True, reply
            return dict(reply["values"])
    pytest.fail(f"no answer from {name}")


def test_foxglove_advertises_and_carries_a_topic_only_another_process_publishes(
    app: App, sdk_peer: JsonProcess, foxglove_port: int
) -> None:
    sdk_peer.send(cmd="define", types=definitions(STRING))
    publish(sdk_peer, "/sdk_fox", "first")  # declares the peer's publisher
    with connect(
        f"ws://127.0.0.1:{foxglove_port}", subprotocols=["foxglove.sdk.v1"], open_timeout=READ_S
    ) as ws:
        channel = None
        deadline = time.monotonic() + READ_S
        while channel is None and time.monotonic() < deadline:
            try:
                frame = ws.recv(timeout=max(0.05, deadline - time.monotonic()))
            except TimeoutError:
                break
            if isinstance(frame, str) and (msg := json.loads(frame))["op"] == "advertise":
                channel = next((c for c in msg["channels"] if c["topic"] == "/sdk_fox"), None)
        assert channel is not None, "the other process's topic was never advertised"
        assert (channel["encoding"], channel["schemaName"]) == ("cdr", STRING)
        ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 3, "channelId": channel["id"]}]}))
        frame = until_frame(ws, sdk_peer, "/sdk_fox", binary=True)
    opcode, sub_id = struct.unpack_from("<BI", frame)
    assert (opcode, sub_id) == (0x01, 3)
    schema = McapSchema(id=1, name=STRING, encoding="ros2msg", data=channel["schema"].encode())
    decoded = DecoderFactory().decoder_for("cdr", schema)(frame[13:])  # type: ignore[misc]
    assert decoded.data == "first" or decoded.data.startswith("n"), decoded  # one the peer published


def test_rosbridge_lists_and_subscribes_to_a_topic_only_another_process_publishes(
    app: App, sdk_peer: JsonProcess
) -> None:
    sdk_peer.send(cmd="define", types=definitions(STRING))
    publish(sdk_peer, "/sdk_rb", "first")
    with connect(f"ws://127.0.0.1:{app.port}/rosbridge", open_timeout=READ_S) as ws:
        deadline = time.monotonic() + READ_S
        while "/sdk_rb" not in (listed := rosapi(ws, "topics"))["topics"]:
            assert time.monotonic() < deadline, f"/sdk_rb never listed: {listed}"
            time.sleep(0.1)
        assert listed["types"][listed["topics"].index("/sdk_rb")] == STRING
        assert rosapi(ws, "topic_type", topic="/sdk_rb")["type"] == STRING
        # No type given: rosbridge learns it from the other process's publisher, as rosbridge does.
        ws.send(json.dumps({"op": "subscribe", "id": "s1", "topic": "/sdk_rb"}))
        while True:
            message = json.loads(until_frame(ws, sdk_peer, "/sdk_rb", binary=False))
            assert message.get("op") != "status" or message.get("level") != "error", message
            if message.get("op") == "publish":
                break
    assert message["topic"] == "/sdk_rb"
    assert message["msg"]["data"] == "first" or message["msg"]["data"].startswith("n"), message


def test_rosapi_names_another_processs_nodes_endpoints_and_services(app: App, sdk_peer: JsonProcess) -> None:
    """``/rosapi/nodes``, ``publishers``, ``subscribers``, ``node_details``, ``services`` and
    ``service_type`` answer for a node process as ``ros2 node list`` / ``topic info`` would."""
    sdk_peer.send(cmd="define", types=definitions(STRING))
    publish(sdk_peer, "/sdk_api", "first")  # a publisher of node /sdk_talker
    sdk_peer.send(cmd="subscribe", topic="/sdk_api_in", type=STRING, hash=rihs(STRING))
    request, response = service_text("std_srvs/srv/Trigger")
    sdk_peer.send(
        cmd="serve",
        service="/sdk_api_srv",
        type="std_srvs/srv/Trigger",
        request=request,
        response=response,
        node="sdk_server",
        hash=rihs("std_srvs/srv/Trigger"),
    )
    sdk_peer.expect(lambda e: e.get("event") == "done" and e.get("cmd") == "serve", "the server to be up")
    # The subscriber's node as the SDK itself names it (its own graph query, not ours), once its
    # query sees the new subscription.
    deadline = time.monotonic() + READ_S
    while True:
        answered = {id(e) for e in sdk_peer.seen if e.get("event") == "topic_info"}
        sdk_peer.send(cmd="topic_info", topic="/sdk_api_in")
        info = sdk_peer.expect(
            lambda e, old=answered: e.get("event") == "topic_info" and id(e) not in old,
            "the SDK's topic info",
        )
        if info["nodes"] or time.monotonic() > deadline:
            break
        time.sleep(0.2)
    assert len(info["nodes"]) == 1, info
    subscriber = "/" + str(info["nodes"][0]).lstrip("/")
    with connect(f"ws://127.0.0.1:{app.port}/rosbridge", open_timeout=READ_S) as ws:
        deadline = time.monotonic() + READ_S
        while not {"/sdk_talker", "/sdk_server", subscriber} <= set((nodes := rosapi(ws, "nodes"))["nodes"]):
            assert time.monotonic() < deadline, f"the peer's nodes never listed: {nodes}"
            time.sleep(0.1)
        assert "/CountDownNode" in nodes["nodes"] and not any(n.startswith("/_") for n in nodes["nodes"])
        assert rosapi(ws, "publishers", topic="/sdk_api")["publishers"] == ["/sdk_talker"]
        assert rosapi(ws, "subscribers", topic="/sdk_api_in")["subscribers"] == [subscriber]
        details = rosapi(ws, "node_details", node="/sdk_talker")
        assert "/sdk_api" in details["publishing"] and details["services"] == [], details
        assert rosapi(ws, "node_details", node="/sdk_server")["services"] == ["/sdk_api_srv"]
        assert "/sdk_api_srv" in rosapi(ws, "services")["services"]
        assert rosapi(ws, "service_type", service="/sdk_api_srv")["type"] == "std_srvs/srv/Trigger"
        # This process's own answers are unchanged beside them.
        assert rosapi(ws, "publishers", topic="/countdown")["publishers"] == ["/CountDownNode"]


def test_bag_record_all_records_a_topic_only_another_process_publishes(
    app: App, sdk_peer: JsonProcess
) -> None:
    sdk_peer.send(cmd="define", types=definitions(STRING))
    publish(sdk_peer, "/sdk_bag", "first")
    started = app.post("/api/bag/recordings", {"all": True, "name": "from_a_process"})
    assert started.status_code == 201, started.text

    def recorded() -> int:
        listed = {r["name"]: r for r in app.get("/api/bag/recordings")}
        return int(listed["from_a_process"]["counts"].get("/sdk_bag", 0))

    i = 0
    deadline = time.monotonic() + READ_S
    while recorded() < 3:  # ros2 bag record -a subscribes to topics that appear while it runs
        assert time.monotonic() < deadline, f"{recorded()} of the peer's messages recorded in {READ_S} s"
        publish(sdk_peer, "/sdk_bag", f"n{i}")
        i += 1
        time.sleep(0.1)
    stopped = app.post("/api/bag/recordings/from_a_process/stop", {})
    assert stopped.status_code == 200, stopped.text
    assert "/sdk_bag" in stopped.json()["topics"]
    bag = HTTP.get(f"{app.url}/api/bag/recordings/from_a_process/download", timeout=10.0)
    assert bag.status_code == 200
    reader = make_reader(io.BytesIO(bag.content), decoder_factories=[DecoderFactory()])
    texts = [
        decoded.data
        for _schema, channel, _message, decoded in reader.iter_decoded_messages(topics=["/sdk_bag"])
        if channel.topic == "/sdk_bag"
    ]
    assert len(texts) >= 3 and all(t == "first" or t.startswith("n") for t in texts), texts
