"""/api/publishers: periodic publishers, like rqt's Message Publisher (ref §3.8, checkpoint 2).

The flight tests go through the real app (TestClient enters the lifespan, so the fly launch runs
on the system clock): publish (5, 5, 10) at 1 Hz and watch /uav/sensors/gps until the drone is
there. The rate tests use a Lab on a manual clock, where a rate can be counted exactly.
"""

from __future__ import annotations

import itertools
import json
import math
import time
from collections.abc import Iterator
from typing import Any

import pytest
from fastapi.testclient import TestClient
from support.app_pool import lab_client
from support.wait import wait_until

from node_runtime.bus import ManualClock, Node
from node_runtime.msgs import Vector3
from server.host.settings import LabSettings, Listening, Settings
from server.world.lab import Lab

POSITION = "/uav/input/position"
TARGET = {"x": 5.0, "y": 5.0, "z": 10.0}
FLIGHT_DEADLINE_S = 20.0


@pytest.fixture
def client() -> Iterator[TestClient]:
    with lab_client(
        Settings(listen=Listening(allowed_hosts=("testserver",)), lab=LabSettings(launch="fly", viewer=False))
    ) as test_client:
        yield test_client


def _start(client: TestClient, **body: Any) -> Any:
    return client.post("/api/publishers", json={"topic": POSITION, "msg": TARGET, "rate_hz": 1.0, **body})


def _publish_count(client: TestClient, topic: str = POSITION) -> int:
    return client.get(f"/api/topics{topic}").json()["publish_count"]


def _gps_error_m(client: TestClient) -> float:
    latest = client.get("/api/topics/uav/sensors/gps").json()["latest"]
    position = latest["pose"]["position"]
    return max(abs(position[axis] - TARGET[axis]) for axis in "xyz")


# -- through the real app ------------------------------------------------------------------------
@pytest.mark.timing  # the flight is timed on the wall clock
def test_publishers_post_5_5_10_at_1hz_drone_gets_within_10cm(client: TestClient) -> None:
    response = _start(client)
    assert response.status_code == 201
    item = response.json()
    assert (item["topic"], item["type"], item["msg"], item["rate_hz"], item["enabled"]) == (
        POSITION,
        "geometry_msgs/msg/Vector3",
        TARGET,
        1.0,
        True,
    )
    assert item["count"] == 1  # the first one goes at once
    started = time.monotonic()

    wait_until(lambda: _gps_error_m(client) < 0.1, "the drone within 10 cm of (5, 5, 10)", FLIGHT_DEADLINE_S)
    flown_s = time.monotonic() - started
    assert flown_s < 10.0
    listed = client.get("/api/publishers").json()
    assert [p["id"] for p in listed] == [item["id"]]
    assert listed[0]["count"] >= int(flown_s)  # about one a second

    deleted = client.delete(f"/api/publishers/{item['id']}")
    assert deleted.status_code == 200 and deleted.json()["id"] == item["id"]
    assert client.get("/api/publishers").json() == []
    assert client.get(f"/api/publishers/{item['id']}").status_code == 404


def test_publishers_delete_unknown_id_404(client: TestClient) -> None:
    assert client.delete("/api/publishers/pub999").status_code == 404
    assert client.patch("/api/publishers/pub999", json={"enabled": False}).status_code == 404


@pytest.mark.parametrize("rate_hz", [0, -1, 1001, 1e9])
def test_publishers_rate_out_of_range_422_nothing_started(client: TestClient, rate_hz: float) -> None:
    assert _start(client, rate_hz=rate_hz).status_code == 422
    assert client.get("/api/publishers").json() == []


@pytest.mark.parametrize("token", ["NaN", "Infinity", "-Infinity"])
def test_publishers_non_finite_json_number_422_nothing_published(client: TestClient, token: str) -> None:
    before = _publish_count(client)
    raw = f'{{"topic": "{POSITION}", "msg": {{"x": {token}, "y": 0, "z": 3}}, "rate_hz": 1}}'
    response = client.post("/api/publishers", content=raw, headers={"content-type": "application/json"})
    assert response.status_code == 422
    assert client.get("/api/publishers").json() == []
    assert _publish_count(client) == before


@pytest.mark.parametrize("msg", [{"x": 1e9, "y": 0.0, "z": 3.0}, {"x": 0.0, "y": 0.0, "z": -1e5}])
def test_publishers_absurd_setpoint_422_nothing_published(client: TestClient, msg: dict[str, float]) -> None:
    before = _publish_count(client)
    assert _start(client, msg=msg).status_code == 422
    assert client.get("/api/publishers").json() == []
    assert _publish_count(client) == before


@pytest.mark.parametrize("msg", [{"x": "five"}, {"w": 1.0}])
def test_publishers_malformed_message_422(client: TestClient, msg: dict[str, Any]) -> None:
    assert _start(client, msg=msg).status_code == 422


def test_publishers_unknown_type_422(client: TestClient) -> None:
    response = _start(client, topic="/new_topic", type="geometry_msgs/msg/Nope", msg={})
    assert response.status_code == 422
    assert "/new_topic" not in {t["name"] for t in client.get("/api/topics").json()}


def test_publishers_unknown_topic_without_type_404(client: TestClient) -> None:
    assert _start(client, topic="/no_such_topic", msg={"data": 1.0}).status_code == 404


def test_publishers_type_conflict_409(client: TestClient) -> None:
    response = _start(client, type="std_msgs/msg/Float64", msg={"data": 1.0})
    assert response.status_code == 409
    assert client.get(f"/api/topics{POSITION}").json()["type"] == "geometry_msgs/msg/Vector3"


def test_publishers_patch_enabled_false_stops_counting_true_resumes(client: TestClient) -> None:
    item = _start(client, rate_hz=50.0).json()
    url = f"/api/publishers/{item['id']}"
    wait_until(lambda: client.get(url).json()["count"] >= 5, "five publications at 50 Hz", 5.0)

    paused = client.patch(url, json={"enabled": False})
    assert paused.status_code == 200 and paused.json()["enabled"] is False
    count, published = paused.json()["count"], _publish_count(client)
    # A marker publisher at the same rate on a topic of its own: once it has published 15 times,
    # the paused one has had 15 periods in which to publish, and must not have.
    marker = _start(
        client, topic="/pause_marker", type="std_msgs/msg/Float64", msg={"data": 1.0}, rate_hz=50.0
    )
    assert marker.status_code == 201, marker.text
    marker_url = f"/api/publishers/{marker.json()['id']}"
    wait_until(
        lambda: client.get(marker_url).json()["count"] >= 15, "15 periods of the marker publisher", 5.0
    )
    assert client.get(url).json()["count"] == count
    assert _publish_count(client) == published

    assert client.patch(url, json={"enabled": True}).json()["enabled"] is True
    wait_until(lambda: client.get(url).json()["count"] >= count + 5, "five more once resumed", 5.0)


@pytest.mark.parametrize("body", [{"rate_hz": 0}, {"rate_hz": 1001}, {"msg": {"x": 1e9, "y": 0, "z": 3}}])
def test_publishers_patch_invalid_422_publisher_unchanged(client: TestClient, body: dict[str, Any]) -> None:
    item = _start(client, enabled=False).json()
    url = f"/api/publishers/{item['id']}"
    assert client.patch(url, json=body).status_code == 422
    after = client.get(url).json()
    assert (after["rate_hz"], after["msg"], after["enabled"]) == (1.0, TARGET, False)


def test_publishers_patch_nan_raw_json_422(client: TestClient) -> None:
    item = _start(client, enabled=False).json()
    raw = json.dumps({"msg": {"x": math.nan, "y": 0.0, "z": 3.0}})  # Python writes NaN
    response = client.patch(
        f"/api/publishers/{item['id']}", content=raw, headers={"content-type": "application/json"}
    )
    assert response.status_code == 422
    assert client.get(f"/api/publishers/{item['id']}").json()["msg"] == TARGET


# -- the same publishers on a manual clock -------------------------------------------------------
@pytest.fixture
def lab() -> Lab:
    lab = Lab(Settings(lab=LabSettings(launch="fly", viewer=False)), ManualClock(0.0))
    lab.start_nodes()
    return lab


def _received(lab: Lab) -> list[float]:
    times: list[float] = []
    with lab.bus.activate():
        probe = Node("probe")
    probe.create_subscription(Vector3, POSITION, lambda _m: times.append(lab.bus.clock.now()), 1000)
    return times


@pytest.mark.parametrize("rate_hz", [1.0, 20.0, 1000.0])
def test_publishers_on_manual_clock_publish_at_once_then_every_period(lab: Lab, rate_hz: float) -> None:
    times = _received(lab)
    lab.publishers.start(POSITION, TARGET, None, rate_hz)
    lab.executor.spin_until(10.0)
    assert len(times) == round(10.0 * rate_hz) + 1
    assert times[0] == 0.0
    assert max(abs(b - a - 1.0 / rate_hz) for a, b in itertools.pairwise(times)) < 1e-9


def test_publishers_on_manual_clock_disabled_publishes_nothing(lab: Lab) -> None:
    times = _received(lab)
    item = lab.publishers.start(POSITION, TARGET, None, 10.0)
    lab.executor.spin_until(1.0)
    lab.publishers.update(item.id, enabled=False)
    count = item.count
    lab.executor.spin_until(5.0)
    assert item.count == count == len(times)
    lab.publishers.stop(item.id)
    lab.executor.spin_until(6.0)
    assert len(times) == count


def test_publishers_on_manual_clock_drone_reaches_5_5_10(lab: Lab) -> None:
    lab.publishers.start(POSITION, TARGET, None, 1.0)
    lab.executor.spin_until(10.0)
    position = lab.bus.get_topic("/uav/sensors/gps").latest.pose.position  # type: ignore[union-attr]
    assert max(abs(getattr(position, a) - TARGET[a]) for a in "xyz") < 0.1
