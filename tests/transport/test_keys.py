"""rmw_zenoh's names: data keys, liveliness tokens and their QoS field, entity GIDs, attachments."""

from __future__ import annotations

import pytest

from node_runtime.msgs.wire import dds_type_name, type_hash
from node_runtime.transport.attachment import ATTACHMENT_BYTES, Attachment
from node_runtime.transport.keys import (
    EntityKind,
    EntityToken,
    QoS,
    data_key,
    entity_gid,
    keep_last,
    mangle,
    parse_qos,
    qos_text,
)

ZID = "ef719c5dcbcb0e27f57de879a132a6ff"


@pytest.mark.parametrize(
    ("qos", "text"),
    [
        (keep_last(10), "::,10:,:,:,,"),
        (keep_last(5, best_effort=True), "2::,5:,:,:,,"),
        (keep_last(1, transient_local=True), ":1:,1:,:,:,,"),
        (QoS(), "::,:,:,:,,"),
        (QoS(history=2, deadline=(1, 500), lease=(10, 0)), "::2,:1,500:,:,10,"),
    ],
    ids=["keep-last-10", "best-effort-5", "transient-local-1", "rmw-zenoh-default", "durations"],
)
def test_qos_text_writes_only_what_differs_from_rmw_zenoh_default(qos: QoS, text: str) -> None:
    assert qos_text(qos) == text
    assert parse_qos(text) == qos


@pytest.mark.parametrize("text", ["", "::", "x::,10:,:,:,,", "::,10:,:,:", "::,10,3:,:,:,,", ":::::"])
def test_parse_qos_malformed_is_none(text: str) -> None:
    assert parse_qos(text) is None


def test_data_key_is_domain_name_dds_type_and_hash() -> None:
    key = data_key(
        0,
        "/uav/sensors/gps",
        dds_type_name("geometry_msgs/msg/PoseStamped"),
        type_hash("geometry_msgs/msg/PoseStamped"),
    )
    assert key == (
        "0/uav/sensors/gps/geometry_msgs::msg::dds_::PoseStamped_/"
        "RIHS01_10f3786d7d40fd2b54367835614bff85d4ad3b5dab62bf8bca0cc232d73b4cd8"
    )
    assert data_key(7, "chatter", "T", "H") == "7/chatter/T/H"


def test_mangle_slashes_and_empty() -> None:
    assert mangle("/uav/sensors/gps") == "%uav%sensors%gps"
    assert mangle("/") == "%" and mangle("") == "%"


def test_node_token_key_and_round_trip() -> None:
    token = EntityToken(0, ZID, 3, 3, EntityKind.NODE, "/", "talker")
    assert token.key == f"@ros2_lv/0/{ZID}/3/3/NN/%/%/talker"
    assert EntityToken.parse(token.key) == token
    assert token.node_fqn == "/talker"


def test_publisher_token_key_and_round_trip() -> None:
    token = EntityToken(
        0,
        ZID,
        3,
        7,
        EntityKind.PUBLISHER,
        "/lab",
        "talker",
        topic="/chatter",
        dds_type="std_msgs::msg::dds_::String_",
        type_hash=type_hash("std_msgs/msg/String"),
        qos=keep_last(10),
    )
    assert token.key == (
        f"@ros2_lv/0/{ZID}/3/7/MP/%/%lab/talker/%chatter/std_msgs::msg::dds_::String_/"
        "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18/::,10:,:,:,,"
    )
    assert EntityToken.parse(token.key) == token
    assert token.node_fqn == "/lab/talker"


def test_endpoint_token_without_topic_fields_refuses_to_form() -> None:
    with pytest.raises(ValueError, match="needs a topic"):
        _ = EntityToken(0, ZID, 1, 2, EntityKind.SUBSCRIPTION, "/", "n").key


@pytest.mark.parametrize(
    "key",
    [
        "",
        "@ros2_lv",
        f"@ros2_lv/0/{ZID}/1/1/NN/%/%",
        f"@other/0/{ZID}/1/1/NN/%/%/n",
        f"@ros2_lv/x/{ZID}/1/1/NN/%/%/n",
        f"@ros2_lv/0/{ZID}/1/1/XX/%/%/n",
        f"@ros2_lv/0/{ZID}/1/1/NN/%/%/n/extra",
        f"@ros2_lv/0/{ZID}/1/2/MP/%/%/n/%t/T/H",
        f"@ros2_lv/0/{ZID}/1/2/MP/%/%/n/%t/T/H/notqos",
        f"@ros2_lv/0/{ZID}//2/MP/%/%/n/%t/T/H/::,:,:,:,,",
    ],
)
def test_parse_token_malformed_is_none(key: str) -> None:
    assert EntityToken.parse(key) is None


def test_entity_gid_is_xxh3_128_low_then_high_little_endian() -> None:
    # XXH3-128 of the empty input is 99aa06d3014798d8 6001c324468d497f (high, low; canonical form).
    assert entity_gid("") == bytes.fromhex("7f498d4624c30160" + "d8984701d306aa99")
    token = EntityToken(0, ZID, 1, 1, EntityKind.NODE, "/", "n")
    assert token.gid == entity_gid(token.key) and len(token.gid) == 16


def test_attachment_is_33_bytes_rmw_zenoh_layout_and_round_trips() -> None:
    gid = bytes(range(16))
    data = Attachment(5, 1_700_000_000_123_456_789, gid).pack()
    assert len(data) == ATTACHMENT_BYTES == 33
    assert (
        data == (5).to_bytes(8, "little") + (1_700_000_000_123_456_789).to_bytes(8, "little") + b"\x10" + gid
    )
    assert Attachment.unpack(data) == Attachment(5, 1_700_000_000_123_456_789, gid)


@pytest.mark.parametrize(
    "data", [None, b"", b"\x00" * 32, b"\x00" * 34, b"\x00" * 16 + b"\x08" + b"\x00" * 16]
)
def test_attachment_unpack_wrong_shape_is_none(data: bytes | None) -> None:
    assert Attachment.unpack(data) is None


def test_attachment_pack_refuses_a_gid_of_wrong_length() -> None:
    with pytest.raises(ValueError, match="16 bytes"):
        Attachment(1, 0, b"short").pack()
