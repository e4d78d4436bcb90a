"""rclpy.qos: profiles as rclpy builds them, the presets by name, and the depth a queue keeps."""

from __future__ import annotations

import pytest
from rclpy.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    InvalidQoSProfileException,
    QoSDurabilityPolicy,
    QoSPresetProfiles,
    QoSProfile,
    QoSReliabilityPolicy,
    ReliabilityPolicy,
    WireQoS,
    keep_depth,
    qos_profile_sensor_data,
    qos_profile_system_default,
)

from node_runtime.transport.keys import qos_text
from node_runtime.transport.publishing import wire_qos


def test_a_profile_takes_rclpy_keywords_and_compares_by_value() -> None:
    qos = QoSProfile(
        depth=1, reliability=QoSReliabilityPolicy.BEST_EFFORT, durability=QoSDurabilityPolicy.TRANSIENT_LOCAL
    )
    assert QoSReliabilityPolicy is ReliabilityPolicy and QoSDurabilityPolicy is DurabilityPolicy
    assert qos.history == HistoryPolicy.KEEP_LAST and qos.depth == 1
    assert qos == QoSProfile(
        depth=1, reliability=ReliabilityPolicy.BEST_EFFORT, durability=DurabilityPolicy.TRANSIENT_LOCAL
    )
    assert qos != QoSProfile(depth=1)


@pytest.mark.parametrize(
    ("kwargs", "what"),
    [
        ({}, "history or a depth"),
        ({"depth": 0}, "depth of at least 1"),
        ({"depth": 1, "colour": 2}, "colour"),
    ],
)
def test_a_profile_that_cannot_be_is_refused_saying_why(kwargs: dict[str, int], what: str) -> None:
    with pytest.raises(InvalidQoSProfileException, match=what):
        QoSProfile(**kwargs)


def test_presets_are_rclpys_and_found_by_short_key() -> None:
    assert qos_profile_sensor_data.reliability == ReliabilityPolicy.BEST_EFFORT
    assert qos_profile_sensor_data.depth == 5
    assert QoSPresetProfiles.get_from_short_key("sensor_data") is qos_profile_sensor_data
    assert QoSPresetProfiles.SYSTEM_DEFAULT.value is qos_profile_system_default
    assert "services_default" in QoSPresetProfiles.short_keys()


def test_queue_depth_is_the_profiles_or_rmw_zenohs_default_for_keep_all_and_system_default() -> None:
    assert keep_depth(7) == 7
    assert keep_depth(QoSProfile(depth=3)) == 3
    assert keep_depth(QoSProfile(history=HistoryPolicy.KEEP_ALL)) == 42
    assert keep_depth(qos_profile_system_default) == 42


@pytest.mark.parametrize(
    ("qos", "text"),
    [
        (WireQoS(10, 0, 0), "::,10:,:,:,,"),  # the system's defaults are rmw_zenoh's
        (WireQoS(5, int(ReliabilityPolicy.BEST_EFFORT), int(DurabilityPolicy.VOLATILE)), "2::,5:,:,:,,"),
        (WireQoS(1, int(ReliabilityPolicy.RELIABLE), int(DurabilityPolicy.TRANSIENT_LOCAL)), ":1:,1:,:,:,,"),
    ],
)
def test_reliability_and_durability_go_into_the_tokens_qos_field_as_rmw_zenoh_writes_it(
    qos: WireQoS, text: str
) -> None:
    assert qos_text(wire_qos(qos.depth, qos)) == text
