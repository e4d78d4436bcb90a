"""keyboard_node (ref §2.1): device key events → keyboard_msgs/Key on /keydown and /keyup."""

from __future__ import annotations

from collections.abc import Callable

import pytest

from node_runtime.bus import Bus, Executor, ManualClock, NodeOverrides
from node_runtime.msgs import Key, Message
from server.packages.keyboard.keyboard import KeyboardNode
from server.peripherals.devices.keyboard import KeyboardDevice

from .conftest import Recorder

Record = Callable[[dict[str, type[Message]]], Recorder]


@pytest.fixture
def device(bus: Bus) -> KeyboardDevice:
    device = bus.devices["keyboard"] = KeyboardDevice()
    return device


@pytest.fixture
def rec(record: Record) -> Recorder:
    return record({"/keydown": Key, "/keyup": Key})


def _keys(rec: Recorder, topic: str) -> list[int]:
    return [m.code for _, m in rec.got[topic]]


def test_keyboard_node_name_and_topics_match_original(bus: Bus, device: KeyboardDevice) -> None:
    with bus.activate():
        node = KeyboardNode()
    assert node.get_name() == "keyboard_node"
    assert bus.get_topic("/keydown").msg_type is Key
    assert bus.get_topic("/keyup").msg_type is Key


def test_keyboard_node_keydown_publishes_key_with_code_modifiers_and_stamp(
    bus: Bus, clock: ManualClock, executor: Executor, device: KeyboardDevice, rec: Recorder
) -> None:
    with bus.activate():
        KeyboardNode()
    clock.set(3.25)
    device.key_down(Key.KEY_A, Key.MODIFIER_NUM, "tab-1")
    executor.spin_some()
    assert len(rec.got["/keydown"]) == 1 and rec.got["/keyup"] == []
    msg = rec.got["/keydown"][0][1]
    assert (msg.code, msg.modifiers) == (97, 4096)
    assert (msg.header.stamp.sec, msg.header.stamp.nanosec) == (3, 250_000_000)
    assert msg.header.frame_id == ""


def test_keyboard_node_keyup_publishes_on_keyup_only(
    bus: Bus, clock: ManualClock, executor: Executor, device: KeyboardDevice, rec: Recorder
) -> None:
    with bus.activate():
        KeyboardNode()
    device.key_down(Key.KEY_SPACE, 0, "tab-1")
    clock.set(1.5)
    device.key_up(Key.KEY_SPACE, Key.MODIFIER_LSHIFT, "tab-1")
    executor.spin_some()
    assert _keys(rec, "/keydown") == [32]
    up = rec.got["/keyup"][0][1]
    assert (up.code, up.modifiers, up.header.stamp.sec, up.header.stamp.nanosec) == (32, 1, 1, 500_000_000)


def test_keyboard_node_keyup_of_unheld_key_publishes_nothing(
    bus: Bus, executor: Executor, device: KeyboardDevice, rec: Recorder
) -> None:
    with bus.activate():
        KeyboardNode()
    device.key_up(Key.KEY_A, 0, "tab-1")
    executor.spin_some()
    assert rec.got["/keyup"] == []


def test_keyboard_node_repeated_keydown_dropped_by_default(
    bus: Bus, executor: Executor, device: KeyboardDevice, rec: Recorder
) -> None:
    with bus.activate():
        node = KeyboardNode()
    assert node.get_parameter("allow_repeat").value is False
    first = device.key_down(Key.KEY_UP, 0, "tab-1")
    repeats = [device.key_down(Key.KEY_UP, 0, "tab-1") for _ in range(5)]
    executor.spin_some()
    assert not first.repeat and all(e.repeat for e in repeats)
    assert _keys(rec, "/keydown") == [273]


def test_keyboard_node_allow_repeat_true_publishes_repeats(
    bus: Bus, executor: Executor, device: KeyboardDevice, rec: Recorder
) -> None:
    with bus.activate(NodeOverrides(parameters={"allow_repeat": True})):
        KeyboardNode()
    for _ in range(3):
        device.key_down(Key.KEY_UP, 0, "tab-1")
    executor.spin_some()
    assert _keys(rec, "/keydown") == [273, 273, 273]


def test_keyboard_node_same_key_from_two_sources_is_not_a_repeat(
    bus: Bus, executor: Executor, device: KeyboardDevice, rec: Recorder
) -> None:
    with bus.activate():
        KeyboardNode()
    device.key_down(Key.KEY_A, 0, "tab-1")
    device.key_down(Key.KEY_A, 0, "tab-2")
    executor.spin_some()
    assert _keys(rec, "/keydown") == [97, 97]


def test_keyboard_node_release_all_emits_keyups_for_held_keys(
    bus: Bus, executor: Executor, device: KeyboardDevice, rec: Recorder
) -> None:
    with bus.activate():
        KeyboardNode()
    for code in (Key.KEY_A, Key.KEY_SPACE, Key.KEY_LEFT):
        device.key_down(code, 0, "tab-1")
    device.key_down(Key.KEY_B, 0, "tab-2")
    device.key_up(Key.KEY_SPACE, 0, "tab-1")
    released = device.release_all("tab-1")
    executor.spin_some()
    assert sorted(e.code for e in released) == [97, 276]
    assert sorted(_keys(rec, "/keyup")) == [32, 97, 276]
    assert device.held("tab-1") == set() and device.held() == {98}
    assert device.release_all("tab-1") == []


def test_keyboard_node_no_device_logs_warning_and_runs(bus: Bus, caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level("WARNING"), bus.activate():
        node = KeyboardNode()
    assert node.state == "active"
    assert any("no keyboard attached" in r.getMessage() for r in caplog.records)


def test_keyboard_node_destroyed_stops_publishing(
    bus: Bus, executor: Executor, device: KeyboardDevice, rec: Recorder
) -> None:
    with bus.activate():
        node = KeyboardNode()
    node.destroy_node()
    device.key_down(Key.KEY_A, 0, "tab-1")
    executor.spin_some()
    assert rec.got["/keydown"] == []


def test_keyboard_node_renamed_by_launch_keeps_root_topics(
    bus: Bus, executor: Executor, device: KeyboardDevice, rec: Recorder
) -> None:
    with bus.activate(NodeOverrides(name="keyboard")):
        node = KeyboardNode()
    device.key_down(Key.KEY_Z, 0, "tab-1")
    executor.spin_some()
    assert node.get_name() == "keyboard"
    assert _keys(rec, "/keydown") == [122]
