"""``ros2lab bag record | info | play`` against a live server, and ``bag info``'s layout offline."""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from pathlib import Path

import pytest
from support.http import HTTP

from server.cli.bag import BagInfo, format_info, format_size

from .conftest import LiveServer, Result, Running


def test_bag_record_info_play_round_trip(
    live_server: LiveServer, ros2lab: Callable[..., Result], start: Callable[..., Running], tmp_path: Path
) -> None:
    pub = live_server.post(
        "/api/publishers",
        {"topic": "/cli_bag_flag", "type": "std_msgs/msg/Bool", "msg": {"data": True}, "rate_hz": 50},
    )
    out = tmp_path / "run1"
    recorder = start("bag", "record", "/cli_bag_flag", "-o", str(out))
    recorder.read_until(lambda line: "Recording to 'run1'" in line)
    live_server.wait_until(
        lambda: any(b.get("messages", 0) >= 10 for b in live_server.get("/api/bag/recordings")),
        "ten messages recorded",
    )
    code, err = recorder.interrupt()
    assert code == 0, err
    live_server.wait_until(lambda: out.is_dir() and (out / "metadata.yaml").is_file(), "the bag fetched")
    assert (out / "run1_0.mcap").read_bytes().startswith(b"\x89MCAP0\r\n")
    assert HTTP.delete(live_server.url + f"/api/publishers/{pub['id']}", timeout=5.0).status_code == 200

    info = ros2lab("bag", "info", str(out))
    assert info.code == 0, info.err
    match = re.search(
        r"Topic: /cli_bag_flag \| Type: std_msgs/msg/Bool \| Count: (\d+) \| Serialization Format: cdr",
        info.out,
    )
    assert match is not None, info.out
    recorded = int(match.group(1))
    assert recorded >= 10
    assert re.search(r"^Messages:          \d+$", info.out, re.MULTILINE)

    before = live_server.get("/api/topics/cli_bag_flag")["publish_count"]
    played = ros2lab("bag", "play", str(out), "--rate", "4")
    assert played.code == 0, played.err
    assert f"Played {recorded} messages" in played.out
    assert live_server.get("/api/topics/cli_bag_flag")["publish_count"] == before + recorded


def test_bag_record_refuses_an_existing_output_folder(ros2lab: Callable[..., Result], tmp_path: Path) -> None:
    result = ros2lab("bag", "record", "-a", "-o", str(tmp_path))
    assert result.code == 1 and "already exists" in result.err


@pytest.mark.parametrize("args", [["bag", "record"], ["bag", "record", "-a", "/x"]])
def test_bag_record_needs_topics_or_all_but_not_both(ros2lab: Callable[..., Result], args: list[str]) -> None:
    result = ros2lab(*args)
    assert result.code == 1 and "-a" in result.err


def test_bag_info_of_what_is_not_a_bag_is_one_line(ros2lab: Callable[..., Result], tmp_path: Path) -> None:
    (tmp_path / "x.mcap").write_text("hello")
    for path in (tmp_path / "x.mcap", tmp_path / "missing"):
        result = ros2lab("bag", "info", str(path))
        assert result.code == 1 and result.err.startswith("error: ") and result.err.count("\n") == 1


def test_bag_info_layout_is_ros2s(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("TZ", "UTC")  # ros2 bag info prints local time
    time.tzset()
    info = BagInfo(
        files=["a_0.mcap"],
        size_bytes=1_300_000,
        start_ns=1_700_000_000_012_000_000,
        end_ns=1_700_000_015_500_000_000,
        topics=[("/a", "std_msgs/msg/Bool", 3, "cdr"), ("/b", "std_msgs/msg/Int64", 4, "cdr")],
    )
    lines = format_info(info).splitlines()
    assert lines[0] == ""
    assert lines[1] == "Files:             a_0.mcap"
    assert lines[2] == "Bag size:          1.2 MiB"
    assert lines[3] == "Storage id:        mcap"
    assert lines[4] == "Duration:          15.488s"
    assert lines[5].startswith("Start:             Nov 14 2023 ") and lines[5].endswith(
        ".012 (1700000000.012)"
    )
    assert lines[7] == "Messages:          7"
    assert (
        lines[8]
        == "Topic information: Topic: /a | Type: std_msgs/msg/Bool | Count: 3 | Serialization Format: cdr"
    )
    assert (
        lines[9] == " " * 19 + "Topic: /b | Type: std_msgs/msg/Int64 | Count: 4 | Serialization Format: cdr"
    )
    assert [format_size(n) for n in (512, 2048, 5 * 1024**3)] == ["512 B", "2.0 KiB", "5.0 GiB"]
    monkeypatch.undo()
    time.tzset()
