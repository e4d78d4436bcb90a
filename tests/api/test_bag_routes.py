"""REST for bags through the real app: record, stop, download, play; bad requests change nothing."""

from __future__ import annotations

import io
from collections.abc import Callable
from pathlib import Path

import pytest
import yaml
from labclient import LabClient, wait_until
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory

MCAP_MAGIC = b"\x89MCAP0\r\n"


@pytest.fixture
def bag_lab(make_lab: Callable[..., LabClient], tmp_path: Path) -> LabClient:
    return make_lab(bag_dir=tmp_path / "bags")


def publish_flags(lab: LabClient, values: list[bool]) -> None:
    for value in values:
        r = lab.http.post(
            "/api/publish", json={"topic": "/flag", "type": "std_msgs/msg/Bool", "msg": {"data": value}}
        )
        assert r.status_code == 200, r.text


def record_flags(lab: LabClient, name: str, values: list[bool]) -> dict[str, object]:
    publish_flags(lab, [False])  # the topic exists (the API's publisher made it) before recording
    r = lab.http.post("/api/bag/recordings", json={"topics": ["flag"], "name": name})
    assert r.status_code == 201, r.text
    assert r.json()["topics"] == ["/flag"] and r.json()["recording"] is True
    publish_flags(lab, values)
    r = lab.http.post(f"/api/bag/recordings/{name}/stop")
    assert r.status_code == 200, r.text
    return r.json()


def test_record_stop_download_gives_an_mcap_of_what_was_published(bag_lab: LabClient) -> None:
    summary = record_flags(bag_lab, "flags", [True, False, True])
    assert summary["counts"] == {"/flag": 3} and summary["recording"] is False
    r = bag_lab.http.get("/api/bag/recordings/flags/download")
    assert r.status_code == 200 and r.content.startswith(MCAP_MAGIC)
    assert "flags_0.mcap" in r.headers["content-disposition"]
    reader = make_reader(io.BytesIO(r.content), decoder_factories=[DecoderFactory()])
    assert [m.data for _, _, _, m in reader.iter_decoded_messages()] == [True, False, True]
    meta = yaml.safe_load(bag_lab.http.get("/api/bag/recordings/flags/metadata.yaml").text)
    assert meta["rosbag2_bagfile_information"]["message_count"] == 3
    listed = bag_lab.http.get("/api/bag/recordings").json()
    assert [b["name"] for b in listed] == ["flags"]


def test_play_publishes_the_bag_back_and_leaves_the_graph(bag_lab: LabClient) -> None:
    record_flags(bag_lab, "again", [True, True])
    before = bag_lab.publish_count("/flag")
    r = bag_lab.http.post("/api/bag/players", json={"bag": "again", "rate": 2.0})
    assert r.status_code == 201, r.text
    player_id = r.json()["id"]
    done = wait_until(
        lambda: (p := bag_lab.http.get(f"/api/bag/players/{player_id}").json())["finished"] and p,
        "the playback to finish",
    )
    assert done["published"] == 2
    assert bag_lab.publish_count("/flag") == before + 2
    nodes = {n["name"] for n in bag_lab.http.get("/api/nodes").json()}
    assert "/rosbag2_player" not in nodes


@pytest.mark.parametrize(
    ("method", "path", "body", "status"),
    [
        ("post", "/api/bag/recordings", {}, 422),  # no topics, not all
        ("post", "/api/bag/recordings", {"all": True, "name": "../up"}, 422),
        ("post", "/api/bag/recordings", {"all": True, "extra": 1}, 422),
        ("post", "/api/bag/recordings", {"all": 0, "topics": ["/flag"]}, 422),  # not a bool
        ("post", "/api/bag/recordings", {"topics": "/flag"}, 422),
        ("delete", "/api/bag/recordings/nope", None, 404),
        ("post", "/api/bag/recordings/nope/stop", None, 404),
        ("post", "/api/bag/recordings", {"all": True, "name": "."}, 422),
        ("get", "/api/bag/recordings/nope/download", None, 404),
        ("post", "/api/bag/players", {"bag": "nope"}, 422),
        ("post", "/api/bag/players", {"bag": "x", "rate": 0}, 422),
        ("post", "/api/bag/players", {"bag": "x", "rate": 1e9}, 422),
        ("post", "/api/bag/players", {"bag": "x", "loop": "yes"}, 422),
        ("post", "/api/bag/players", {"bag": "0" * 4000}, 422),  # longer than a file name may be
        ("get", "/api/bag/players/play99", None, 404),
        ("delete", "/api/bag/players/play99", None, 404),
    ],
)
def test_bad_bag_requests_are_4xx_and_change_nothing(
    bag_lab: LabClient, tmp_path: Path, method: str, path: str, body: dict[str, object] | None, status: int
) -> None:
    nodes_before = bag_lab.http.get("/api/nodes", params={"hidden": True}).json()
    kwargs = {"json": body} if body is not None else {}
    r = getattr(bag_lab.http, method)(path, **kwargs)
    assert r.status_code == status, r.text
    assert isinstance(r.json()["detail"], str | list)
    assert bag_lab.http.get("/api/nodes", params={"hidden": True}).json() == nodes_before
    assert not (tmp_path / "bags").exists() or not any((tmp_path / "bags").iterdir())


def test_a_running_recording_is_not_downloadable_and_its_name_is_taken(bag_lab: LabClient) -> None:
    r = bag_lab.http.post("/api/bag/recordings", json={"all": True, "name": "live"})
    assert r.status_code == 201
    assert bag_lab.http.get("/api/bag/recordings/live/download").status_code == 409
    assert bag_lab.http.post("/api/bag/recordings", json={"all": True, "name": "live"}).status_code == 409
    assert bag_lab.http.post("/api/bag/recordings/live/stop").status_code == 200
    assert bag_lab.http.get("/api/bag/recordings/live/download").status_code == 200
    assert bag_lab.http.post("/api/bag/recordings/live/stop").status_code == 200  # stopped: a no-op


def test_deleting_a_bag_removes_it_from_the_folder_and_the_list(bag_lab: LabClient, tmp_path: Path) -> None:
    record_flags(bag_lab, "gone", [True])
    live = bag_lab.http.post("/api/bag/recordings", json={"topics": ["/flag"], "name": "live_gone"})
    assert live.status_code == 201
    for name in ("gone", "live_gone"):  # a finished bag, and one still recording
        r = bag_lab.http.delete(f"/api/bag/recordings/{name}")
        assert r.status_code == 200 and r.json() == {"name": name, "deleted": True}, r.text
        assert bag_lab.http.get(f"/api/bag/recordings/{name}/download").status_code == 404
        assert bag_lab.http.delete(f"/api/bag/recordings/{name}").status_code == 404
    assert bag_lab.http.get("/api/bag/recordings").json() == []
    assert "/rosbag2_recorder" not in {n["name"] for n in bag_lab.http.get("/api/nodes").json()}
