"""/api/topics and /api/publish through the real app: the rocket launch's graph, publishing, and
every kind of bad request, which must be refused with a message naming the problem and must
change nothing (no message published, no topic created)."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from typing import Any

import pytest
from labclient import LabClient, wait_until

ROCKET_TOPICS = {
    "/countdown": ("std_msgs/msg/Int64", ["/CountDownNode"], {"/MainControllerNode"}),
    "/cmd_vel": ("std_msgs/msg/Float64", ["/MainControllerNode"], {"/RocketEngineNode"}),
    "/sensor_vel": ("std_msgs/msg/Float64", ["/RocketEngineNode"], set()),
    "/abort_takeoff": ("std_msgs/msg/Bool", ["/KeyboardManager"], {"/MainControllerNode"}),
    "/keydown": ("keyboard_msgs/msg/Key", ["/keyboard"], {"/KeyboardManager"}),
    "/keyup": ("keyboard_msgs/msg/Key", ["/keyboard"], set()),
}  # name → (type, publishers, subscribers that must be among them)
COUNTDOWN_END_S = 20.0  # start_delay 0: 10 … 0 at 1 Hz, with room for a loaded machine
LIMIT = 64 * 1024  # Listening.max_body_bytes


def detail_text(response: Any) -> str:
    """The error's detail as one string (FastAPI's validation errors are a list)."""
    detail = response.json()["detail"]
    return detail if isinstance(detail, str) else json.dumps(detail)


# -- the graph -------------------------------------------------------------------------------
def test_list_topics_rocket_launch_has_lab_topics_with_types(rocket_lab: LabClient) -> None:
    response = rocket_lab.http.get("/api/topics")

    assert response.status_code == 200
    topics = {t["name"]: t for t in response.json()}
    assert set(topics) == set(ROCKET_TOPICS)
    for name, (type_name, publishers, subscribers) in ROCKET_TOPICS.items():
        assert topics[name]["type"] == type_name, name
        assert topics[name]["publishers"] == publishers, name
        assert subscribers <= set(topics[name]["subscribers"]), name


def test_list_topics_hidden_true_adds_rosout(rocket_lab: LabClient) -> None:
    visible = {t["name"] for t in rocket_lab.http.get("/api/topics").json()}
    every = {t["name"] for t in rocket_lab.http.get("/api/topics", params={"hidden": "true"}).json()}

    assert "/rosout" not in visible
    assert "/rosout" in every
    assert visible < every


def test_topic_detail_countdown_running_has_latest_and_count(counting_lab: LabClient) -> None:
    latest = counting_lab.wait_latest("/countdown", lambda m: True, "has a message")
    detail = counting_lab.topic("countdown")

    assert detail["name"] == "/countdown"
    assert detail["type"] == "std_msgs/msg/Int64"
    assert set(latest) == {"data"} and 0 <= latest["data"] <= 10
    assert detail["publish_count"] >= 1
    assert isinstance(detail["latest_time"], float)
    assert detail["publisher_depths"] == [1000]


def test_topic_detail_nothing_published_yet_latest_is_null(rocket_lab: LabClient) -> None:
    detail = rocket_lab.topic("cmd_vel")

    assert detail["latest"] is None
    assert detail["latest_time"] is None
    assert detail["publish_count"] == 0


@pytest.mark.parametrize(
    ("path", "status", "named"),
    [("nowhere", 404, "/nowhere"), ("bad%20name", 422, "invalid topic name"), ("2fast", 422, "digit")],
)
def test_topic_detail_bad_name_refused_naming_it(
    rocket_lab: LabClient, path: str, status: int, named: str
) -> None:
    response = rocket_lab.http.get(f"/api/topics/{path}")

    assert response.status_code == status
    assert named in detail_text(response)


# -- publishing ------------------------------------------------------------------------------
def test_publish_abort_before_launch_cmd_vel_never_published(make_lab: Callable[..., LabClient]) -> None:
    aborted = make_lab(start_delay="0")
    control = make_lab(start_delay="0")  # started just after: shows when /cmd_vel would have come

    result = aborted.publish("/abort_takeoff", {"data": True})

    assert result == {"topic": "/abort_takeoff", "type": "std_msgs/msg/Bool", "subscribers": 2}
    aborted.wait_latest(
        "/countdown", lambda m: m["data"] == 0, "reached 0", COUNTDOWN_END_S
    )  # it counts on after an abort
    wait_until(
        lambda: control.publish_count("/cmd_vel") >= 3,
        "the control rocket's /cmd_vel",
        timeout_s=COUNTDOWN_END_S,
    )
    cmd_vel = aborted.topic("/cmd_vel")
    assert cmd_vel["publish_count"] == 0
    assert cmd_vel["latest"] is None


def test_publish_existing_topic_without_type_uses_its_type(rocket_lab: LabClient) -> None:
    result = rocket_lab.publish("/countdown", {"data": 7})

    assert result == {"topic": "/countdown", "type": "std_msgs/msg/Int64", "subscribers": 2}
    assert rocket_lab.latest("/countdown") == {"data": 7}
    assert rocket_lab.publish_count("/countdown") == 1


def test_publish_new_topic_with_type_creates_it(rocket_lab: LabClient) -> None:
    result = rocket_lab.publish("greeting", {"data": "hello"}, "std_msgs/msg/String")

    assert result == {"topic": "/greeting", "type": "std_msgs/msg/String", "subscribers": 0}
    detail = rocket_lab.topic("greeting")
    assert detail["type"] == "std_msgs/msg/String"
    assert detail["publishers"] == ["/_rest_api"]
    assert detail["latest"] == {"data": "hello"}
    assert "/greeting" in {t["name"] for t in rocket_lab.http.get("/api/topics").json()}


def _chunks(total: int) -> Iterator[bytes]:
    """A body without Content-Length (chunked), so only the running count can stop it."""
    yield b'{"topic": "/countdown", "msg": {"data": 1}, "pad": "'
    for _ in range(total // 1024):
        yield b"x" * 1024
    yield b'"}'


JSON = {"content-type": "application/json"}
BAD_PUBLISH = [
    pytest.param(
        {"content": b'{"topic": "/countdown", "msg": ', "headers": JSON},
        422,
        "malformed JSON",
        id="malformed-json",
    ),
    pytest.param({"content": b"[1, 2]", "headers": JSON}, 422, "valid dictionary", id="not-an-object"),
    pytest.param({"json": {"msg": {"data": 1}}}, 422, '"topic"', id="topic-missing"),
    pytest.param({"json": {"topic": 5, "msg": {"data": 1}}}, 422, '"topic"', id="topic-not-a-string"),
    pytest.param({"json": {"topic": "/countdown", "msg": "7"}}, 422, '"msg"', id="msg-not-an-object"),
    pytest.param(
        {"json": {"topic": "/countdown", "msg": {"data": 1}, "qos": 1}}, 422, "qos", id="extra-field"
    ),
    pytest.param(
        {"json": {"topic": "/countdown", "msg": {"data": "ten"}}},
        422,
        "data: expected an integer",
        id="field-wrong-type",
    ),
    pytest.param(
        {"json": {"topic": "/countdown", "msg": {"data": 2**63}}},
        422,
        "out of range for int64",
        id="field-out-of-range",
    ),
    pytest.param(
        {"json": {"topic": "/countdown", "msg": {"count": 1}}},
        422,
        "no field 'count'",
        id="unknown-msg-field",
    ),
    pytest.param(
        {
            "content": b'{"topic": "/speed", "type": "std_msgs/msg/Float64", "msg": {"data": NaN}}',
            "headers": JSON,
        },
        422,
        "NaN is not a JSON number",
        id="nan",
    ),
    pytest.param(
        {"json": {"topic": "/speed", "type": "std_msgs/msg/Float128", "msg": {}}},
        422,
        "unknown message type 'std_msgs/msg/Float128'",
        id="unknown-type",
    ),
    pytest.param(
        {"json": {"topic": "/bad topic", "type": "std_msgs/msg/Bool", "msg": {}}},
        422,
        "invalid topic name '/bad topic'",
        id="invalid-topic-name",
    ),
    pytest.param(
        {"json": {"topic": "", "type": "std_msgs/msg/Bool", "msg": {}}},
        422,
        "must not be empty",
        id="empty-topic-name",
    ),
    pytest.param(
        {"json": {"topic": "/countdown", "type": "std_msgs/msg/Bool", "msg": {"data": True}}},
        409,
        "/countdown carries std_msgs/msg/Int64",
        id="type-conflict",
    ),
    pytest.param(
        {"json": {"topic": "/speed", "msg": {"data": 1.0}}},
        404,
        "unknown topic '/speed'",
        id="unknown-topic-without-type",
    ),
    pytest.param(
        {
            "content": b'{"topic": "/countdown", "msg": {"data": 1}, "pad": "' + b"x" * LIMIT + b'"}',
            "headers": JSON,
        },
        413,
        f"body larger than {LIMIT} bytes",
        id="oversized",
    ),
    pytest.param(
        {"content": _chunks(LIMIT + 1024), "headers": JSON},
        413,
        f"body larger than {LIMIT} bytes",
        id="oversized-chunked",
    ),
]


@pytest.mark.parametrize(("request_kwargs", "status", "named"), BAD_PUBLISH)
def test_publish_bad_request_refused_naming_problem_and_changes_nothing(
    rocket_lab: LabClient, request_kwargs: dict[str, Any], status: int, named: str
) -> None:
    topics_before = rocket_lab.topic_names()

    response = rocket_lab.http.post("/api/publish", **request_kwargs)

    assert response.status_code == status, response.text
    assert named in detail_text(response)
    assert rocket_lab.publish_count("/countdown") == 0
    assert rocket_lab.latest("/countdown") is None
    assert rocket_lab.topic_names() == topics_before
    assert rocket_lab.healthy()
