"""The Foxglove WebSocket server through the real app, with a client written here on `websockets`
speaking ``foxglove.sdk.v1`` as Foxglove and Lichtblick do.

The app runs on the system clock in TestClient's thread; reads are bounded by deadlines.
"""

from __future__ import annotations

import asyncio
import json
import struct
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import websockets
from fastapi.testclient import TestClient
from handshake import handshake_refusal, handshake_status
from mcap.records import Schema as McapSchema
from mcap_ros2.decoder import DecoderFactory
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from support.wait import wait_until
from websockets.asyncio.client import ClientConnection
from websockets.exceptions import ConnectionClosed

from api.errors import CloseCode
from server.app import create_app
from server.host.settings import LabSettings, Listening, Settings

SUBPROTOCOL = "foxglove.sdk.v1"
READ_S = 10.0
SERVER_MESSAGE_DATA = 0x01  # opcode of a binary frame: uint32 subscription id, uint64 log time, payload
CLIENT_MESSAGE_DATA = 0x01  # opcode of a client's binary frame: uint32 channel id, payload


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[TestClient]:
    """Both labs (rocket counting down later, drone hovering) with the Foxglove server on a free port."""
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(
            launch="all",
            launch_args={"start_delay": "3600"},
            viewer=False,
            foxglove_port=0,
            bag_dir=tmp_path_factory.mktemp("bags"),
        ),
    )
    with TestClient(create_app(settings)) as client:
        yield client


def port(lab: TestClient) -> int:
    bridges = lab.app.state.bridges  # type: ignore[attr-defined]
    return int(bridges.foxglove_port)


async def connect(lab: TestClient, **kwargs: Any) -> ClientConnection:
    return await websockets.connect(
        f"ws://127.0.0.1:{port(lab)}",
        subprotocols=[SUBPROTOCOL],
        open_timeout=READ_S,
        max_size=None,
        **kwargs,
    )


async def next_json(ws: ClientConnection, op: str) -> dict[str, Any]:
    """The next text frame with this op (binary frames and other ops in between are skipped)."""
    async with asyncio.timeout(READ_S):
        while True:
            frame = await ws.recv()
            if isinstance(frame, str) and (msg := json.loads(frame))["op"] == op:
                return dict(msg)


async def channels_until(ws: ClientConnection, topics: set[str]) -> dict[str, dict[str, Any]]:
    """Advertised channels by topic, read until every one of ``topics`` is among them."""
    seen: dict[str, dict[str, Any]] = {}
    while not topics <= set(seen):
        for channel in (await next_json(ws, "advertise"))["channels"]:
            seen[channel["topic"]] = channel
    return seen


def run(coro: Any) -> Any:
    return asyncio.run(coro)


def test_server_info_and_channels_with_ros2msg_schemas(lab: TestClient) -> None:
    async def scenario() -> tuple[dict[str, Any], dict[str, dict[str, Any]]]:
        async with await connect(lab) as ws:
            assert ws.subprotocol == SUBPROTOCOL
            info = await next_json(ws, "serverInfo")
            return info, await channels_until(ws, {"/uav/sensors/gps", "/keydown", "/countdown", "/tf"})

    info, channels = run(scenario())
    assert "clientPublish" in info["capabilities"] and "cdr" in info["supportedEncodings"]
    gps = channels["/uav/sensors/gps"]
    assert (gps["encoding"], gps["schemaEncoding"], gps["schemaName"]) == (
        "cdr",
        "ros2msg",
        "geometry_msgs/msg/PoseStamped",
    )
    for section in ("MSG: std_msgs/Header", "MSG: builtin_interfaces/Time", "MSG: geometry_msgs/Quaternion"):
        assert section in gps["schema"]
    assert channels["/tf"]["schemaName"] == "tf2_msgs/msg/TFMessage"
    assert channels["/countdown"]["schemaName"] == "std_msgs/msg/Int64"
    assert set(channels) >= {t["name"] for t in lab.get("/api/topics").json()}


def decoder_for(channel: dict[str, Any]) -> Any:
    """mcap-ros2-support's CDR decoder, built from the schema the server advertised."""
    schema = McapSchema(id=1, name=channel["schemaName"], encoding="ros2msg", data=channel["schema"].encode())
    return DecoderFactory().decoder_for("cdr", schema)


def test_gps_frames_decode_to_the_pose_the_rest_api_reports(lab: TestClient) -> None:
    async def scenario() -> tuple[Any, dict[str, Any]]:
        async with await connect(lab) as ws:
            gps = (await channels_until(ws, {"/uav/sensors/gps"}))["/uav/sensors/gps"]
            decode = decoder_for(gps)
            await ws.send(
                json.dumps({"op": "subscribe", "subscriptions": [{"id": 7, "channelId": gps["id"]}]})
            )
            decoded: dict[tuple[int, int], Any] = {}
            rest: dict[str, Any] | None = None
            async with asyncio.timeout(READ_S):
                while True:
                    frame = await ws.recv()
                    if isinstance(frame, str):
                        continue
                    opcode, sub_id, log_time = struct.unpack_from("<BIQ", frame)
                    assert (opcode, sub_id) == (SERVER_MESSAGE_DATA, 7) and log_time > 0
                    msg = decode(frame[13:])
                    decoded[(msg.header.stamp.sec, msg.header.stamp.nanosec)] = msg
                    if rest is None:  # the REST API's latest pose, asked once frames flow
                        rest = await asyncio.to_thread(lambda: lab.get("/api/topics/uav/sensors/gps").json())
                    stamp = rest["latest"]["header"]["stamp"]
                    if (key := (stamp["sec"], stamp["nanosec"])) in decoded:
                        return decoded[key], rest["latest"]

    msg, latest = run(scenario())
    position = latest["pose"]["position"]
    assert (msg.pose.position.x, msg.pose.position.y, msg.pose.position.z) == (
        position["x"],
        position["y"],
        position["z"],
    )
    orientation = latest["pose"]["orientation"]
    assert msg.pose.orientation.w == orientation["w"] and msg.header.frame_id == "world"


def key_cdr(schema_text: str, code: int) -> bytes:
    """A keyboard_msgs/msg/Key in CDR, encoded by rosbags from the advertised schema."""
    store = get_typestore(Stores.EMPTY)
    store.register(get_types_from_msg(schema_text, "keyboard_msgs/msg/Key"))
    Key, Header, Time = (
        store.types[n]
        for n in ("keyboard_msgs/msg/Key", "std_msgs/msg/Header", "builtin_interfaces/msg/Time")
    )
    msg = Key(header=Header(stamp=Time(sec=0, nanosec=0), frame_id=""), code=code, modifiers=0)
    return bytes(store.serialize_cdr(msg, "keyboard_msgs/msg/Key"))


def test_client_published_key_a_aborts_the_rocket(lab: TestClient) -> None:
    main = lab.app.state.lab.bus.get_node("/MainControllerNode")  # type: ignore[attr-defined]
    assert not main.abort_mission

    async def scenario() -> None:
        async with await connect(lab) as ws:
            keydown = (await channels_until(ws, {"/keydown"}))["/keydown"]
            advertise = {"id": 3, "topic": "/keydown", "encoding": "cdr", "schemaName": keydown["schemaName"]}
            await ws.send(json.dumps({"op": "advertise", "channels": [advertise]}))
            await ws.send(struct.pack("<BI", CLIENT_MESSAGE_DATA, 3) + key_cdr(keydown["schema"], 97))
            await asyncio.to_thread(wait_until, lambda: main.abort_mission, "the rocket to abort", READ_S)

    run(scenario())
    assert lab.get("/api/topics/abort_takeoff").json()["latest"] == {"data": True}
    assert lab.get("/api/topics/keydown").json()["latest"]["code"] == 97


def test_client_publish_with_a_nan_setpoint_or_wrong_type_is_refused(lab: TestClient) -> None:
    before = lab.get("/api/topics/uav/input/position").json()["publish_count"]
    bridge = lab.app.state.bridges.foxglove.node  # type: ignore[attr-defined]
    refused = bridge.refused

    async def scenario() -> None:
        async with await connect(lab) as ws:
            await next_json(ws, "serverInfo")
            channels = [
                {
                    "id": 1,
                    "topic": "/uav/input/position",
                    "encoding": "json",
                    "schemaName": "geometry_msgs/msg/Vector3",
                },
                {
                    "id": 2,
                    "topic": "/uav/input/position",
                    "encoding": "json",
                    "schemaName": "std_msgs/msg/Bool",
                },
            ]
            await ws.send(json.dumps({"op": "advertise", "channels": channels}))
            await ws.send(struct.pack("<BI", CLIENT_MESSAGE_DATA, 1) + b'{"x": NaN, "y": 0, "z": 1}')
            await ws.send(struct.pack("<BI", CLIENT_MESSAGE_DATA, 2) + b'{"data": true}')
            await asyncio.to_thread(
                wait_until, lambda: bridge.refused == refused + 2, "both messages refused", READ_S
            )
            status = await next_json(ws, "status")
            assert "/uav/input/position" in status["message"]

    run(scenario())
    assert lab.get("/api/topics/uav/input/position").json()["publish_count"] == before


@pytest.mark.parametrize("origin", ["http://evil.example", "null", "https://127.0.0.1.evil.example"])
def test_a_page_on_another_site_never_connects(lab: TestClient, origin: str) -> None:
    server = lab.app.state.bridges.foxglove.server  # type: ignore[attr-defined]
    refused = server.refused

    async def scenario() -> ConnectionClosed:
        async with await connect(lab, origin=origin) as ws:
            with pytest.raises(ConnectionClosed) as caught:
                await next_json(ws, "serverInfo")  # nothing comes before the close
        return caught.value

    closed = run(scenario())
    assert closed.rcvd is not None and closed.rcvd.code == CloseCode.FORBIDDEN
    assert "cross-site" in closed.rcvd.reason
    assert server.refused == refused + 1


@pytest.mark.parametrize(
    ("headers", "code"),
    [
        ((("Host", "evil.example"),), CloseCode.MISDIRECTED),  # a DNS-rebinding page
        (
            (("Host", "rebound.example:8765"), ("Origin", "http://rebound.example:8765")),
            CloseCode.MISDIRECTED,
        ),
        ((("Host", "127.0.0.1"), ("Host", "evil.example")), CloseCode.BAD_REQUEST),
    ],
)
def test_a_foreign_or_ambiguous_host_is_refused(
    lab: TestClient, headers: tuple[tuple[str, str], ...], code: int
) -> None:
    protocol = ("Sec-WebSocket-Protocol", SUBPROTOCOL)
    assert run(handshake_refusal(port(lab), "/", (*headers, protocol))) == code
    # The same handshake with this machine's name goes through.
    assert run(handshake_status(port(lab), "/", (("Host", "127.0.0.1"), protocol))) == 101


def test_the_pages_own_origin_and_a_client_without_origin_connect(lab: TestClient) -> None:
    async def scenario(origin: str | None) -> str:
        async with await connect(lab, origin=origin) as ws:
            return (await next_json(ws, "serverInfo"))["op"]

    assert run(scenario(None)) == "serverInfo"
    assert run(scenario(f"http://127.0.0.1:{port(lab)}")) == "serverInfo"


def test_tf_of_the_drone_follows_its_gps_pose(tmp_path: Path) -> None:
    from node_runtime.bus import ManualClock, Node
    from node_runtime.msgs import PoseStamped, TFMessage
    from server.world.lab import Lab

    drone = Lab(Settings(lab=LabSettings(launch="fly", viewer=False, bag_dir=tmp_path)), ManualClock(0.0))
    got: dict[str, Any] = {}
    with drone.bus.activate():
        probe = Node("probe")
    probe.create_subscription(TFMessage, "/tf", lambda m: got.__setitem__("tf", m), 10)
    probe.create_subscription(PoseStamped, "/uav/sensors/gps", lambda m: got.__setitem__("gps", m), 10)
    drone.start_nodes()
    drone.executor.spin_for(3.0)  # taking off
    (tf,) = got["tf"].transforms
    gps = got["gps"]
    assert (tf.header.frame_id, tf.child_frame_id) == ("world", "uav/imu")
    assert tf.header.stamp.to_dict() == gps.header.stamp.to_dict()
    t, p = tf.transform.translation, gps.pose.position
    assert (t.x, t.y, t.z) == (p.x, p.y, p.z) and p.z > 0.5
    assert tf.transform.rotation.to_dict() == gps.pose.orientation.to_dict()


def test_a_client_message_the_server_does_not_understand_gets_an_error_status_and_changes_nothing(
    lab: TestClient,
) -> None:
    async def scenario() -> tuple[list[str], dict[str, Any]]:
        async with await connect(lab) as ws:
            gps = (await channels_until(ws, {"/uav/sensors/gps"}))["/uav/sensors/gps"]
            errors = []
            for bad in (
                "not json",
                json.dumps({"op": "getParameters", "parameterNames": []}),
                json.dumps({"op": "subscribe", "subscriptions": [{"id": -1, "channelId": gps["id"]}]}),
                json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": 99999}]}),
            ):
                await ws.send(bad)
                errors.append((await next_json(ws, "status"))["message"])
            await ws.send(struct.pack("<BI", CLIENT_MESSAGE_DATA, 42) + b"{}")  # a channel never advertised
            errors.append((await next_json(ws, "status"))["message"])
            # The same connection still serves: a good subscription's frames arrive.
            await ws.send(
                json.dumps({"op": "subscribe", "subscriptions": [{"id": 5, "channelId": gps["id"]}]})
            )
            async with asyncio.timeout(READ_S):
                while not isinstance(frame := await ws.recv(), bytes):
                    pass
            return errors, {"sub": struct.unpack_from("<BI", frame)[1]}

    errors, good = run(scenario())
    assert "JSON" in errors[0] and "getParameters" in errors[1] and "uint32" in errors[2]
    assert "99999" in errors[3] and "42" in errors[4]
    assert good["sub"] == 5


def test_unsubscribing_the_last_client_drops_the_bus_subscription(lab: TestClient) -> None:
    node = lab.app.state.bridges.foxglove.node  # type: ignore[attr-defined]

    async def scenario() -> None:
        async with await connect(lab) as ws:
            gps = (await channels_until(ws, {"/uav/sensors/gps"}))["/uav/sensors/gps"]
            await ws.send(
                json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": gps["id"]}]})
            )
            await asyncio.to_thread(
                wait_until, lambda: "/uav/sensors/gps" in node.forwarding, "the subscription", READ_S
            )
            await ws.send(json.dumps({"op": "unsubscribe", "subscriptionIds": [1]}))
            await asyncio.to_thread(
                wait_until, lambda: "/uav/sensors/gps" not in node.forwarding, "its end", READ_S
            )

    run(scenario())


def test_with_no_client_the_graph_is_not_walked_and_a_client_that_comes_gets_what_changed(
    lab: TestClient, monkeypatch: pytest.MonkeyPatch
) -> None:
    """While no client is connected the bridge leaves its channels as they are (a class's graph
    changes with every node that starts, and the sync walked all of it on the worlds' loop); a
    client that comes gets every topic there is, each advertised once, and new ones live."""
    bridge = lab.app.state.bridges.foxglove.node  # type: ignore[attr-defined]
    bus = lab.app.state.lab.bus  # type: ignore[attr-defined]
    # The tests before share this lab: the server ends their clients' sessions once it has seen
    # their connections close, which may come after those tests end.
    wait_until(lambda: not bridge.server.sessions, "the earlier tests' clients gone", READ_S)
    walks, syncs = [0], [0]
    known_topics, sync = bus.known_topics, bridge.sync

    def counted_walk() -> Any:
        walks[0] += 1
        return known_topics()

    def counted_sync() -> None:
        syncs[0] += 1
        sync()

    monkeypatch.setattr(bus, "known_topics", counted_walk)
    monkeypatch.setattr(bridge, "sync", counted_sync)
    for timer in bridge.timers:  # the timer calls the bound method it was given: give it the counted one
        monkeypatch.setattr(timer, "callback", counted_sync)

    def publish(topic: str) -> None:
        made = lab.post(
            "/api/publish", json={"topic": topic, "msg": {"data": "hi"}, "type": "std_msgs/msg/String"}
        )
        assert made.status_code == 200, made.text

    publish("/made_while_nobody_watched")
    wait_until(lambda: syncs[0] >= 3, "three syncs of the bridge after the topic was made")
    assert walks[0] == 0 and "/made_while_nobody_watched" not in bridge.channels

    async def scenario() -> tuple[list[str], dict[str, dict[str, Any]]]:
        async with await connect(lab) as ws:
            first = (await next_json(ws, "advertise"))["channels"]
            publish("/made_while_watched")
            return [c["topic"] for c in first], await channels_until(ws, {"/made_while_watched"})

    first, later = run(scenario())
    assert "/made_while_nobody_watched" in first and first.count("/made_while_nobody_watched") == 1
    assert "/made_while_watched" in later and walks[0] >= 2
