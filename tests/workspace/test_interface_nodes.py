"""Students' own interfaces against a live lab, as ROS 2's custom msg and srv tutorial uses them:
nodes started with ``ros2lab run`` talk with ``tutorial_interfaces`` and ``fleet_interfaces``
types, the lab publishes them from REST, echoes them (CLI and Foxglove) and records them to a
bag, and on the wire they carry the RIHS01 hashes rosbags computes from the definitions."""

from __future__ import annotations

import asyncio
import json
import re
import struct
import subprocess
import threading
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import websockets
import zenoh
from mcap.reader import make_reader
from mcap.records import Schema as McapSchema
from mcap_ros2.decoder import DecoderFactory
from processes.node_process import NodeProcess
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from support.app import REPO, App, free_port
from support.forked_cli import cli_command

from .interface_packages import NUM, TELEMETRY, interface_package, tutorial_workspace

BROKEN_CMAKE = (
    'project(broken_interfaces)\nrosidl_generate_interfaces(${PROJECT_NAME} "msg/Bad.msg" "msg/Fine.msg")\n'
)
START_S = 60.0  # a process started through ros2lab run imports the CLI, then rclpy, then joins: slow on a busy machine
HEARD = r'^\[INFO\] \[\d+\.\d+\] \[minimal_subscriber\]: I heard: "(-?\d+)"$'
TELEMETRY_HEARD = (
    r"\[telemetry_subscriber\]: I heard: map uav_1 z=(?P<z>\d+)\.0 codes=\[7, 8, 9\] tags=\['red', 'lead'\] "
    r"samples=\[1\.5, 2\.5\] counts=\[(?P<n>\d+), -?(?P<minus>\d+)\] corner=2\.0$"
)


@dataclass(frozen=True)
class LiveLab:
    app: App
    ws: Path
    foxglove_port: int


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LiveLab]:
    root = tmp_path_factory.mktemp("interface_nodes")
    ws = root / "ws"
    tutorial_workspace(ws)
    interface_package(
        ws / "src/broken_interfaces",
        "broken_interfaces",
        BROKEN_CMAKE,
        {"msg/Bad.msg": "int32 ok\nint32 LIMIT=1.5\n", "msg/Fine.msg": "int32 fine\n"},
    )
    fox = free_port()
    app = App(
        root,
        "--launch",
        str(REPO / "server/packages/rocketship/launch/rocket.launch"),
        "--workspace",
        str(ws),
        "--foxglove-port",
        str(fox),
        "start_delay:=600",
        cwd=root,
    )
    try:
        yield LiveLab(app, ws, fox)
    finally:
        app.stop()


@pytest.fixture
def run(lab: LiveLab, tmp_path: Path) -> Iterator[Any]:
    """``ros2lab run PKG EXEC ARGS`` as a student types it, from a folder with no ./workspace."""
    app = lab.app
    started: list[NodeProcess] = []

    def start(pkg: str, exe: str, *args: str) -> NodeProcess:
        argv = cli_command("--url", app.url, "run", pkg, exe, *args)
        proc = NodeProcess(app, tmp_path / exe, command=argv)
        started.append(proc)
        return proc

    yield start
    for proc in started:
        proc.kill()


def rosbags_store(*definitions: tuple[str, str]) -> Any:
    store = get_typestore(Stores.ROS2_KILTED)
    for name, text in definitions:
        store.register(get_types_from_msg(text, name))
    return store


def test_tutorial_publisher_and_subscriber_and_a_rest_publish(run: Any, lab: LiveLab) -> None:
    app = lab.app
    listener = run("py_custom", "listener")
    talker = run("py_custom", "talker")
    numbers = [int(m[1]) for m in listener.wait_for(HEARD, 3, START_S)]
    assert numbers == sorted(numbers) and len(set(numbers)) == 3
    talker.wait_for(rf'^\[INFO\] \[\d+\.\d+\] \[minimal_publisher\]: Publishing: "{numbers[0]}"$')
    assert talker.interrupt() == 0, talker.text[-2000:]
    response = app.post(
        "/api/publish", {"topic": "/topic", "type": "tutorial_interfaces/msg/Num", "msg": {"num": -42}}
    )
    assert response.status_code == 200, response.text
    assert response.json()["type"] == "tutorial_interfaces/msg/Num"
    listener.wait_for(r'I heard: "-42"$')
    bad = app.post(
        "/api/publish", {"topic": "/topic", "type": "tutorial_interfaces/msg/Num", "msg": {"num": "x"}}
    )
    assert bad.status_code == 422 and "num" in bad.text  # checked as the definition says, nothing sent
    assert listener.interrupt() == 0, listener.text[-2000:]
    assert "Traceback" not in listener.text + talker.text


def test_service_between_two_processes_and_called_from_the_cli(run: Any, lab: LiveLab) -> None:
    app = lab.app
    server = run("py_custom", "service")
    client = run("py_custom", "client", "2", "3", "4")
    assert client.finish(START_S) == 0, client.text[-2000:]
    assert re.search(
        r"\[minimal_client_async\]: Result of add_three_ints: for 2 \+ 3 \+ 4 = 9$", client.text, re.MULTILINE
    ), client.text
    server.wait_for(r"\[minimal_service\]: Incoming request$")
    server.wait_for(r"^a: 2 b: 3 c: 4$")
    call = subprocess.run(
        cli_command(
            "--url",
            app.url,
            "service",
            "call",
            "/add_three_ints",
            "tutorial_interfaces/srv/AddThreeInts",
            "{a: 10, b: 20, c: -5}",
        ),
        capture_output=True,
        text=True,
        timeout=START_S,
        check=False,
    )
    assert call.returncode == 0, call.stderr
    assert "tutorial_interfaces.srv.AddThreeInts_Response(sum=25)" in call.stdout, call.stdout
    server.wait_for(r"^a: 10 b: 20 c: -5$")
    assert server.interrupt() == 0, server.text[-2000:]


def test_students_action_between_two_processes(run: Any) -> None:
    server = run("py_custom", "fibonacci_server")
    client = run("py_custom", "fibonacci_client", "--ros-args", "-p", "order:=5")
    assert client.finish(START_S) == 0, client.text[-2000:]
    assert re.search(
        r"\[fibonacci_action_client\]: Received feedback: array\('i', \[0, 1, 1, 2\]\)$",
        client.text,
        re.MULTILINE,
    ), client.text
    assert re.search(
        r"\[fibonacci_action_client\]: Result: array\('i', \[0, 1, 1, 2, 3, 5\]\)$", client.text, re.MULTILINE
    ), client.text
    server.wait_for(r"\[fibonacci_action_server\]: Executing goal\.\.\.$")
    assert server.interrupt() == 0, server.text[-2000:]


def test_telemetry_echoed_in_foxglove_recorded_and_on_the_wire_with_rosbags_hash(
    run: Any, lab: LiveLab
) -> None:
    app = lab.app
    store = rosbags_store(("tutorial_interfaces/msg/Num", NUM), ("fleet_interfaces/msg/Telemetry", TELEMETRY))
    expected_hash = store.hash_rihs01("fleet_interfaces/msg/Telemetry")
    session = raw_session(app)
    samples: list[tuple[str, bytes]] = []
    lock = threading.Lock()

    def on_sample(sample: zenoh.Sample) -> None:
        with lock:
            if len(samples) < 100:
                samples.append((str(sample.key_expr), sample.payload.to_bytes()))

    subscriber = session.declare_subscriber("0/telemetry/**", on_sample)
    listener = run("py_custom", "telemetry_listener")
    talker = run("py_custom", "telemetry_talker")
    try:
        talker.wait_for(
            r"\[telemetry_publisher\]: modes 0 1, at most 4 codes, prefix uav_$", timeout_s=START_S
        )
        heard = listener.wait_for(TELEMETRY_HEARD, 2, START_S)
        assert all(m["z"] == m["n"] == m["minus"] for m in heard), [m[0] for m in heard]

        echo = subprocess.run(
            cli_command("--url", app.url, "topic", "echo", "/telemetry", "--once"),
            capture_output=True,
            text=True,
            timeout=60,
            check=False,
        )
        assert echo.returncode == 0, echo.stderr
        assert "callsign: uav_1" in echo.stdout and "frame_id: map" in echo.stdout, echo.stdout
        assert "- red" in echo.stdout and "mode: 1" in echo.stdout, echo.stdout

        channel, frame = asyncio.run(foxglove_first(lab.foxglove_port, "/telemetry"))
        assert (channel["schemaName"], channel["schemaEncoding"], channel["encoding"]) == (
            "fleet_interfaces/msg/Telemetry",
            "ros2msg",
            "cdr",
        )
        schema = McapSchema(
            id=1, name=channel["schemaName"], encoding="ros2msg", data=channel["schema"].encode()
        )
        shown = DecoderFactory().decoder_for("cdr", schema)(frame)
        assert (shown.callsign, list(shown.codes), shown.corners[1].y) == ("uav_1", [7, 8, 9], 2.0)

        recording = app.post("/api/bag/recordings", {"topics": ["/telemetry"], "name": "telemetry"})
        assert recording.status_code == 201, recording.text
        app.wait_for(
            lambda: any(
                r.get("name") == "telemetry" and r.get("messages", 0) >= 2
                for r in app.get("/api/bag/recordings")
            ),
            "two messages recorded",
        )
        assert app.post("/api/bag/recordings/telemetry/stop", {}).status_code == 200
        with lock:
            got = list(samples)
    finally:
        subscriber.undeclare()
        session.close()
        assert talker.interrupt() == 0, talker.text[-2000:]
        assert listener.interrupt() == 0, listener.text[-2000:]

    keys = {key for key, _ in got}
    assert keys == {f"0/telemetry/fleet_interfaces::msg::dds_::Telemetry_/{expected_hash}"}, keys
    raw = store.deserialize_cdr(got[-1][1], "fleet_interfaces/msg/Telemetry")
    assert (raw.header.frame_id, raw.callsign, raw.codes.tolist(), raw.tags) == (
        "map",
        "uav_1",
        [7, 8, 9],
        ["red", "lead"],
    )

    bag = next((app.log_path.parent / "bags" / "telemetry").glob("*.mcap"))  # the lab runs in its folder
    with bag.open("rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        decoded = [(schema, msg) for schema, _channel, _message, msg in reader.iter_decoded_messages()]
    assert len(decoded) >= 2
    schema, msg = decoded[0]
    assert (
        schema is not None
        and schema.name == "fleet_interfaces/msg/Telemetry"
        and schema.encoding == "ros2msg"
    )
    assert "MSG: tutorial_interfaces/Num" in schema.data.decode()
    assert (msg.callsign, list(msg.codes), [c.num for c in msg.counts][1:]) == (
        "uav_1",
        [7, 8, 9],
        [-int(msg.position[2])],
    )


async def foxglove_first(port: int, topic: str) -> tuple[dict[str, Any], bytes]:
    """A Foxglove client's view of ``topic``: its channel and the payload of its first message."""
    async with (
        websockets.connect(
            f"ws://127.0.0.1:{port}", subprotocols=["foxglove.sdk.v1"], open_timeout=START_S, max_size=None
        ) as ws,
        asyncio.timeout(START_S),
    ):
        channel: dict[str, Any] | None = None
        while channel is None:
            frame = await ws.recv()
            if isinstance(frame, str) and json.loads(frame)["op"] == "advertise":
                channel = next((c for c in json.loads(frame)["channels"] if c["topic"] == topic), None)
        await ws.send(
            json.dumps({"op": "subscribe", "subscriptions": [{"id": 7, "channelId": channel["id"]}]})
        )
        while True:
            frame = await ws.recv()
            if isinstance(frame, bytes) and frame[0] == 0x01 and struct.unpack_from("<I", frame, 1)[0] == 7:
                return channel, frame[13:]  # opcode, subscription id, log time, then the CDR


def raw_session(app: App) -> Any:
    config = zenoh.Config()
    config.insert_json5("mode", json.dumps("client"))
    config.insert_json5("connect/endpoints", json.dumps([f"tcp/{app.router}"]))
    config.insert_json5("scouting/multicast/enabled", "false")
    return zenoh.open(config)


def test_broken_definition_is_logged_and_the_lab_and_other_types_work(lab: LiveLab) -> None:
    app, ws = lab.app, lab.ws
    bad = ws / "src/broken_interfaces/msg/Bad.msg"
    assert f"{bad}:2: '1.5' is not an integer" in app.log_tail(20000)
    fine = app.post(
        "/api/publish", {"topic": "/fine", "type": "broken_interfaces/msg/Fine", "msg": {"fine": 1}}
    )
    assert fine.status_code == 200, fine.text
    missing = app.post("/api/publish", {"topic": "/bad", "type": "broken_interfaces/msg/Bad", "msg": {}})
    assert missing.status_code == 422 and "broken_interfaces/msg/Bad" in missing.text  # as any unknown type
    listed = subprocess.run(
        cli_command("--url", app.url, "interface", "package", "broken_interfaces"),
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert (listed.returncode, listed.stdout, listed.stderr) == (
        1,
        "broken_interfaces/msg/Fine\n",
        f"{bad}:2: '1.5' is not an integer\n",
    )
    assert app.get("/api/health")["status"] == "ok"
