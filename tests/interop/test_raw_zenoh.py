"""A plain ``eclipse-zenoh`` subscriber on ``0/**`` against the real app: what goes over the wire is
rmw_zenoh's, checked with nothing of this project (keys by pattern, ROS 2's own type hashes,
the 33-byte attachment read by hand, the GID from xxhash of the publisher's liveliness token,
the payload decoded by rosbags)."""

from __future__ import annotations

import json
import re
import struct
import threading
import time
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest
import xxhash
import zenoh
from ros_reference import ROS_REFERENCE_HASHES
from rosbags.typesys import Stores, get_typestore
from support.app import App

DATA_KEY = re.compile(
    r"^0/(?P<topic>[A-Za-z0-9_/]+)/(?P<pkg>[a-z0-9_]+)::msg::dds_::(?P<type>[A-Za-z0-9]+)_/RIHS01_(?P<hash>[0-9a-f]{64})$"
)
LISTEN_S = 4.0


@pytest.fixture(scope="module")
def fly(tmp_path_factory: pytest.TempPathFactory) -> Iterator[App]:
    lab = App(tmp_path_factory.mktemp("raw_zenoh"), "--launch", "fly")
    try:
        yield lab
    finally:
        lab.stop()


@pytest.fixture
def raw_session(fly: App) -> Iterator[Any]:
    config = zenoh.Config()
    config.insert_json5("mode", json.dumps("client"))
    config.insert_json5("connect/endpoints", json.dumps([f"tcp/{fly.router}"]))
    config.insert_json5("scouting/multicast/enabled", "false")
    session = zenoh.open(config)
    try:
        yield session
    finally:
        session.close()


def test_a_raw_subscriber_on_the_domain_sees_rmw_zenohs_keys_attachments_and_cdr(raw_session: Any) -> None:
    samples: list[tuple[str, bytes, bytes | None]] = []
    lock = threading.Lock()

    def on_sample(sample: zenoh.Sample) -> None:
        attachment = sample.attachment.to_bytes() if sample.attachment is not None else None
        with lock:
            if len(samples) < 20_000:
                samples.append((str(sample.key_expr), sample.payload.to_bytes(), attachment))

    subscriber = raw_session.declare_subscriber("0/**", on_sample)
    deadline = time.monotonic() + LISTEN_S + 10.0
    while time.monotonic() < deadline:
        time.sleep(0.1)
        with lock:
            gps = sum(1 for key, _, _ in samples if key.startswith("0/uav/sensors/gps/"))
        if gps >= 4 * 10:  # the GPS publishes at 10 Hz or more: a few seconds' worth
            break
    subscriber.undeclare()
    with lock:
        got = list(samples)
    keys = {key for key, _, _ in got}
    assert any(k.startswith("0/uav/sensors/gps/geometry_msgs::msg::dds_::PoseStamped_/") for k in keys), keys
    assert len(keys) >= 5, keys  # the fly launch publishes many topics

    # The publishers' GIDs, computed here from their liveliness tokens with xxhash alone.
    tokens = [str(reply.ok.key_expr) for reply in raw_session.liveliness().get("@ros2_lv/0/**") if reply.ok]
    gid_of_token = {xxhash.xxh3_128_digest(token.encode())[::-1]: token for token in tokens}
    assert gid_of_token, "the app declares no liveliness tokens"

    store = get_typestore(Stores.ROS2_HUMBLE)
    by_publisher: dict[tuple[str, bytes], list[int]] = {}
    now_ns = time.time_ns()
    for key, payload, attachment in got:
        match = DATA_KEY.match(key)
        assert match, f"not an rmw_zenoh data key: {key}"
        name = f"{match['pkg']}/msg/{match['type']}"
        if name in ROS_REFERENCE_HASHES:
            assert match["hash"] == ROS_REFERENCE_HASHES[name], name
        assert attachment is not None and len(attachment) == 33, (key, attachment)
        sequence, stamp_ns = struct.unpack_from("<qq", attachment, 0)
        assert attachment[16] == 16  # the GID's length
        gid = attachment[17:33]
        assert gid in gid_of_token, f"{key}: its GID is no publisher token's XXH3-128"
        token = gid_of_token[gid]
        assert "/MP/" in token and match["topic"].replace("/", "%") in token, (key, token)
        assert 0 < now_ns - stamp_ns < 60e9, (key, stamp_ns)  # a wall-clock source timestamp
        assert payload[:4] == b"\x00\x01\x00\x00", key  # CDR, little-endian
        by_publisher.setdefault((key, gid), []).append(sequence)
        if name == "geometry_msgs/msg/PoseStamped":
            pose = store.deserialize_cdr(payload, name)
            position = pose.pose.position
            assert np.isfinite([position.x, position.y, position.z]).all()
    for (key, _), sequences in by_publisher.items():
        assert sequences == list(range(sequences[0], sequences[0] + len(sequences))), (key, sequences[:10])
    first = [seqs[0] for (key, _), seqs in by_publisher.items() if key.startswith("0/uav/sensors/gps/")]
    assert first and all(s >= 1 for s in first)
