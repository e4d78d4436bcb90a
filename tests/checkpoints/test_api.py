"""The checkpoints' REST through the real app (TestClient, its lifespan entered): checkpoint 2 by REST
alone, the answers and their limit, the page's capture, the signed report and its verification."""

from __future__ import annotations

import json
import re
import struct
import zlib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from support.app_pool import lab_client
from support.wait import wait_until

from server.world.checkpoints.signing import ReportSigner

from .conftest import lab_settings

FLY_TIMEOUT_S = 60.0
PNG = {"content-type": "image/png"}
FILE = {"content-type": "application/octet-stream"}  # a report file as it is, whatever is in it


def tiny_png() -> bytes:
    """A valid 1×1 PNG."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(b"\0\0\0\0"))
        + chunk(b"IEND", b"")
    )


@pytest.fixture(scope="module")
def fly(tmp_path_factory: pytest.TempPathFactory) -> Iterator[TestClient]:
    """One drone lab for the module (the kinematic sim: quick to fly), its state in a temp folder."""
    state = tmp_path_factory.mktemp("state")
    settings = lab_settings(state, "fly", simple="true")
    with lab_client(settings) as client:
        yield client


def checkpoint(client: TestClient, name: str) -> dict[str, Any]:
    body = client.get("/api/checkpoints").json()
    return next(c for c in body["checkpoints"] if c["name"] == name)


def test_checkpoints_lists_the_labs_three_with_steps_and_the_questions(fly: TestClient) -> None:
    body = fly.get("/api/checkpoints").json()
    assert [c["name"] for c in body["checkpoints"]] == ["keyboard_abort", "fly_to_point", "launch_and_keys"]
    for c in body["checkpoints"]:
        assert c["title"] and c["steps"] and c["state"] in ("not_started", "in_progress", "done")
        assert all(isinstance(s["commands"], list) for s in c["steps"])
    assert [q["id"] for q in body["questions"]] == ["q1", "q2", "q3", "final"]
    assert [q.get("shows_graph", False) for q in body["questions"]] == [True, False, False, False]
    assert isinstance(body["version"], int)


def test_answer_saved_over_8_kib_refused_413_unchanged_unknown_404(fly: TestClient) -> None:
    saved = fly.put("/api/checkpoints/answers/q2", json={"text": "/keydown in, /abort_takeoff out"})
    assert saved.status_code == 200, saved.text
    assert saved.json()["answer"] == "/keydown in, /abort_takeoff out" and saved.json()["saved_at"]
    version = fly.get("/api/checkpoints").json()["version"]
    refused = fly.put("/api/checkpoints/answers/q2", json={"text": "é" * 4097})  # 8194 bytes of UTF-8
    assert refused.status_code == 413 and "8192 bytes" in refused.json()["detail"]
    body = fly.get("/api/checkpoints").json()
    assert (
        next(q for q in body["questions"] if q["id"] == "q2")["answer"] == "/keydown in, /abort_takeoff out"
    )
    assert (
        fly.put("/api/checkpoints/answers/q2", json={"text": "x" * 8192}).status_code == 200
    )  # the limit itself
    assert fly.get("/api/checkpoints").json()["version"] > version
    unknown = fly.put("/api/checkpoints/answers/q9", json={"text": "hi"})
    assert unknown.status_code == 404 and "q9" in unknown.json()["detail"]


def test_capture_must_be_a_png_of_at_most_2_mib(fly: TestClient) -> None:
    not_png = fly.post("/api/checkpoints/fly_to_point/capture", content=b"GIF89a....", headers=PNG)
    assert not_png.status_code == 422 and "PNG" in not_png.json()["detail"]
    huge = fly.post(
        "/api/checkpoints/fly_to_point/capture",
        content=b"\x89PNG\r\n\x1a\n" + b"\0" * (2 * 1024 * 1024),
        headers=PNG,
    )
    assert huge.status_code == 413
    assert fly.post("/api/checkpoints/nope/capture", content=tiny_png(), headers=PNG).status_code == 404
    assert checkpoint(fly, "fly_to_point")["has_capture"] is False
    ok = fly.post("/api/checkpoints/fly_to_point/capture", content=tiny_png(), headers=PNG)
    assert ok.status_code == 200 and checkpoint(fly, "fly_to_point")["has_capture"] is True


def held_at_target(client: TestClient, since: list[float]) -> bool:
    """The drone has been within 0.3 m of (5, 5, 10) for 4 s by the lab's clock."""
    gps = client.get("/api/topics/uav/sensors/gps").json()
    p = gps["latest"]["pose"]["position"]
    near = ((p["x"] - 5) ** 2 + (p["y"] - 5) ** 2 + (p["z"] - 10) ** 2) ** 0.5 <= 0.3
    stamp = gps["latest"]["header"]["stamp"]
    now = stamp["sec"] + stamp["nanosec"] / 1e9
    if not near:
        since.clear()
        return False
    if not since:
        since.append(now)
    return now - since[0] >= 4.0


def test_fly_to_point_by_rest_at_5_hz_is_not_done_and_at_1_hz_is(fly: TestClient) -> None:
    body = {
        "topic": "/uav/input/position",
        "msg": {"x": 5.0, "y": 5.0, "z": 10.0},
        "type": "geometry_msgs/msg/Vector3",
        "rate_hz": 5.0,
    }
    started = fly.post("/api/publishers", json=body)
    assert started.status_code == 201, started.text
    publisher = started.json()["id"]
    since: list[float] = []
    wait_until(
        lambda: held_at_target(fly, since), "the drone held at (5, 5, 10) for 4 s", FLY_TIMEOUT_S, poll_s=0.2
    )
    state = checkpoint(fly, "fly_to_point")
    assert state["state"] == "in_progress" and state["done_at"] is None, state
    # What keeps it from done is the rate it reads, far above 1.2 Hz (on a loaded machine the REST
    # publisher's 5 Hz timer runs late and reads as low as 2.9 Hz: still not once a second; and a
    # first tick late by up to 0.16 s, the rest on their schedule, reads up to 6.25 Hz over its 5
    # positions: a CI run read 5.2).
    read = re.search(r" at ([0-9.]+) Hz", state["progress"])
    assert read is not None and 2.0 <= float(read.group(1)) <= 6.25, state["progress"]
    # The same publisher at 1 Hz: the legitimate use is met.
    assert fly.patch(f"/api/publishers/{publisher}", json={"rate_hz": 1.0}).status_code == 200
    done = wait_until(
        lambda: (c := checkpoint(fly, "fly_to_point"))["state"] == "done" and c,
        "fly_to_point done",
        30.0,
        poll_s=0.2,
    )
    assert done["done_at"].endswith("Z") and done["evidence"]["publisher"] == "/_rest_api"
    assert 0.8 <= done["evidence"]["rate_hz"] <= 1.2 and done["evidence"]["track"]
    fly.delete(f"/api/publishers/{publisher}")


def test_report_json_and_html_verify_and_a_changed_byte_fails(fly: TestClient) -> None:
    fly.put("/api/checkpoints/answers/final", json={"text": "one command <b>starts</b> it all"})
    report = fly.get("/api/checkpoints/report", params={"format": "json"})
    assert report.status_code == 200 and report.headers["content-type"].startswith("application/json")
    assert 'filename="checkpoints-lab.json"' in report.headers["content-disposition"]
    content = json.loads(report.content)
    assert content["signature"]["algorithm"] == "HMAC-SHA256"
    assert [c["name"] for c in content["checkpoints"]] == [
        "keyboard_abort",
        "fly_to_point",
        "launch_and_keys",
    ]
    assert any(q["answer"] == "one command <b>starts</b> it all" for q in content["questions"])

    def verify(data: bytes) -> dict[str, Any]:
        answer = fly.post("/api/checkpoints/verify", content=data, headers=FILE)
        assert answer.status_code == 200, answer.text
        return answer.json()

    assert verify(report.content)["valid"] is True
    changed = bytearray(report.content)
    at = report.content.index(b"one command")
    changed[at] = ord("O")
    assert verify(bytes(changed)) == {
        "valid": False,
        "reason": verify(bytes(changed))["reason"],
        "student": None,
    }
    assert "edited" in verify(bytes(changed))["reason"]

    page = fly.get("/api/checkpoints/report", params={"format": "html"})
    assert page.headers["content-type"].startswith("text/html")
    assert b"one command &lt;b&gt;starts&lt;/b&gt; it all" in page.content  # escaped, never markup
    assert verify(page.content)["valid"] is True
    edited = page.content.replace(b"Checkpoints of", b"Checkpoints 0f", 1)
    assert "edited" in verify(edited)["reason"]

    other = ReportSigner(b"\x01" * 32).json_file(json.loads(report.content))
    other_verdict = verify(other)
    assert other_verdict["valid"] is False and "another server" in other_verdict["reason"]
    for junk in (b"hello", b'{"kind": "something else"}', b"<html>a page</html>", b""):
        verdict = verify(junk)
        assert verdict["valid"] is False and verdict["reason"].startswith("not a report"), junk


def test_report_keeps_verifying_after_a_restart_with_the_same_state_folder(tmp_path: Path) -> None:
    settings = lab_settings(tmp_path)
    with lab_client(settings) as first:
        report = first.get("/api/checkpoints/report", params={"format": "json"}).content
    assert (tmp_path / "report-key").stat().st_mode & 0o077 == 0  # the key is this user's alone
    with lab_client(lab_settings(tmp_path)) as second:
        assert second.post("/api/checkpoints/verify", content=report, headers=FILE).json()["valid"] is True
    with lab_client(lab_settings(tmp_path / "elsewhere")) as third:
        assert (
            "another server"
            in third.post("/api/checkpoints/verify", content=report, headers=FILE).json()["reason"]
        )


def test_since_the_current_version_is_204_until_something_changes(tmp_path: Path) -> None:
    with lab_client(lab_settings(tmp_path)) as lab:
        version = lab.get("/api/checkpoints").json()["version"]
        assert lab.get("/api/checkpoints", params={"since": version}).status_code == 204
        lab.put("/api/checkpoints/answers/q1", json={"text": "four nodes"})
        again = lab.get("/api/checkpoints", params={"since": version})
        assert again.status_code == 200 and again.json()["version"] > version
