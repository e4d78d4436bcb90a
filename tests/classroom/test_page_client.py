"""bench/page_client.py against a live lab (``python -m server --launch fly``): it decodes viser's
real stream (its batch frames: header, zstd, msgpack) into scene and GUI messages, reads the HUD's
pose stream and keeps the key channel's heartbeat, as an open page does; a frame cut short is
refused by name rather than miscounted. Short and bounded: one server, a 3 s window."""

from __future__ import annotations

import asyncio
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import App

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
from page_client import PageClient, viser_messages

WINDOW_S = 3.0


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[App]:
    app = App(tmp_path_factory.mktemp("page_client"), "--launch", "fly", "--no-foxglove")
    try:
        yield app
    finally:
        app.stop()


def test_the_page_client_counts_a_live_labs_viser_pose_and_key_channels(lab: App) -> None:
    client = PageClient(lab.url)
    frames: list[bytes] = []
    add = client.counts.add_viser

    def keep(frame: bytes) -> None:
        frames.append(frame)
        add(frame)

    client.counts.add_viser = keep  # type: ignore[method-assign]
    rates = asyncio.run(asyncio.wait_for(client.run(WINDOW_S, warm_s=0.0), WINDOW_S + 30.0))

    assert client.errors == []
    types = client.counts.viser_types
    assert types["ThemeConfigurationMessage"] == 1  # the page's backlog, decoded from viser's own frames
    assert any(t.startswith("Gui") for t in types) and rates["viser_gui"] > 0
    assert rates["viser_scene"] > 0 and rates["pose_gps"] > 0
    assert rates["keys_sent"] > 0 and "keys" not in rates  # heartbeats are taken without an error frame
    with pytest.raises(ValueError, match="shorter than its compressed payload"):
        viser_messages(frames[0][: len(frames[0]) // 2])
    with pytest.raises(ValueError, match="shorter than its header"):
        viser_messages(b"\x00" * 8)
