"""``KeyDeadMan`` on a ManualClock: a silent source's keys are released ``timeout_s`` after its
last frame (at the first check after it, every ``timeout_s / 5``), heartbeats keep them held, a
check that runs late after a stalled loop decides nothing, and nothing stays behind once no
channel is watched."""

from __future__ import annotations

import pytest

from node_runtime.bus import Bus, Executor, ManualClock
from node_runtime.msgs import Key
from server.peripherals.devices.deadman import NODE_NAME, KeyDeadMan
from server.peripherals.devices.keyboard import KeyboardDevice, KeyEvent

TIMEOUT_S = 0.5
KEY_RIGHT, KEY_A = Key.KEY_RIGHT, Key.KEY_A


@pytest.fixture
def keyboard() -> KeyboardDevice:
    return KeyboardDevice()


@pytest.fixture
def deadman(keyboard: KeyboardDevice, bus: Bus) -> KeyDeadMan:
    return KeyDeadMan(keyboard, bus, TIMEOUT_S)


def keyups(keyboard: KeyboardDevice) -> list[KeyEvent]:
    events: list[KeyEvent] = []
    keyboard.add_listener(lambda e: events.append(e) if e.kind == "keyup" else None)
    return events


def test_deadman_silent_source_holding_a_key_is_released_at_timeout(
    deadman: KeyDeadMan, keyboard: KeyboardDevice, clock: ManualClock, executor: Executor
) -> None:
    released = keyups(keyboard)
    deadman.watch("tab")
    keyboard.key_down(KEY_RIGHT, 0, "tab")
    deadman.feed("tab")

    executor.spin_until(TIMEOUT_S - 0.001)
    assert keyboard.held("tab") == {KEY_RIGHT}
    executor.spin_until(TIMEOUT_S)
    assert keyboard.held("tab") == set()
    assert [(e.code, e.source) for e in released] == [(KEY_RIGHT, "tab")]


def test_deadman_heartbeats_keep_a_held_key_held(
    deadman: KeyDeadMan, keyboard: KeyboardDevice, clock: ManualClock, executor: Executor
) -> None:
    released = keyups(keyboard)
    deadman.watch("tab")
    keyboard.key_down(KEY_A, 0, "tab")
    for _ in range(15):  # 3 s of heartbeats every 200 ms
        executor.spin_for(0.2)
        deadman.feed("tab")
    assert keyboard.held("tab") == {KEY_A}
    assert released == []
    executor.spin_for(TIMEOUT_S + deadman.check_period_s)  # then silence, noticed at the next check
    assert keyboard.held("tab") == set()
    assert len(released) == 1


def test_deadman_source_holding_nothing_is_left_alone(
    deadman: KeyDeadMan, keyboard: KeyboardDevice, executor: Executor
) -> None:
    released = keyups(keyboard)
    deadman.watch("tab")
    keyboard.key_down(KEY_A, 0, "tab")
    keyboard.key_up(KEY_A, 0, "tab")
    executor.spin_for(10 * TIMEOUT_S)
    assert len(released) == 1  # only the real key-up


def test_deadman_one_silent_source_does_not_release_anothers_keys(
    deadman: KeyDeadMan, keyboard: KeyboardDevice, executor: Executor
) -> None:
    deadman.watch("frozen")
    deadman.watch("alive")
    keyboard.key_down(KEY_A, 0, "frozen")
    keyboard.key_down(KEY_RIGHT, 0, "alive")
    for _ in range(5):
        executor.spin_for(0.2)
        deadman.feed("alive")
    assert keyboard.held("frozen") == set()
    assert keyboard.held("alive") == {KEY_RIGHT}


def test_deadman_late_check_after_a_stalled_loop_waits_for_the_queued_frames(
    deadman: KeyDeadMan, keyboard: KeyboardDevice, clock: ManualClock, executor: Executor
) -> None:
    deadman.watch("tab")
    keyboard.key_down(KEY_A, 0, "tab")
    clock.set(0.9)  # the loop was stuck for 0.9 s: the checks due meanwhile run late, at once
    executor.spin_some()
    assert keyboard.held("tab") == {KEY_A}, "a late check decides nothing"
    deadman.feed("tab")  # the heartbeat that waited behind the stall is read
    executor.spin_for(0.4)
    assert keyboard.held("tab") == {KEY_A}
    executor.spin_for(0.1)  # now really silent for 0.5 s, checked on time
    assert keyboard.held("tab") == set()


def test_deadman_node_exists_only_while_a_source_is_watched(deadman: KeyDeadMan, bus: Bus) -> None:
    def names() -> set[str]:
        return {n.get_name() for n in bus.nodes}

    assert NODE_NAME not in names()
    deadman.watch("a")
    deadman.watch("b")
    assert NODE_NAME in names()
    deadman.unwatch("a")
    assert NODE_NAME in names()
    deadman.unwatch("b")
    assert NODE_NAME not in names()
    assert deadman.watched == frozenset()


def test_deadman_unwatched_source_is_never_released(
    deadman: KeyDeadMan, keyboard: KeyboardDevice, executor: Executor
) -> None:
    deadman.watch("tab")
    keyboard.key_down(KEY_A, 0, "tab")
    deadman.unwatch("tab")
    executor.spin_for(10 * TIMEOUT_S)
    assert keyboard.held("tab") == {KEY_A}  # its handler releases them when it closes, not the timer


@pytest.mark.parametrize("timeout_s", [0.0, -1.0, float("nan"), 1e9])
def test_deadman_timeout_out_of_range_refused(keyboard: KeyboardDevice, bus: Bus, timeout_s: float) -> None:
    with pytest.raises(ValueError, match="timeout"):
        KeyDeadMan(keyboard, bus, timeout_s)
