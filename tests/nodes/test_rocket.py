"""The rocketship package against the lab (ref §1, §2.3): countdown, controller, engine, keyboard manager."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from node_runtime.bus import Bus, Executor, ManualClock, Node, NodeOverrides, Publisher
from node_runtime.msgs import Bool, Float64, Int64, Key, Message
from server.packages.keyboard.keyboard import KeyboardNode
from server.packages.rocketship.countdown import CountDownNode
from server.packages.rocketship.keyboard_manager import KeyboardManager
from server.packages.rocketship.main_controller import MainControllerNode
from server.packages.rocketship.rocket_engine import RocketEngineNode
from server.peripherals.devices.keyboard import KeyboardDevice

from .conftest import Recorder

TOPICS: dict[str, type[Message]] = {
    "/countdown": Int64,
    "/cmd_vel": Float64,
    "/sensor_vel": Float64,
    "/abort_takeoff": Bool,
}
LAUNCH_S = 15.0  # 5 s start delay, then 10 → 0 at 1 Hz
CONTROLLER = "MainControllerNode"
Record = Callable[[dict[str, type[Message]]], Recorder]


@pytest.fixture
def rec(record: Record) -> Recorder:
    return record(TOPICS)


@pytest.fixture
def abort_pub(bus: Bus) -> Publisher:
    """What the students' rqt Message Publisher does: Bool on /abort_takeoff."""
    return Node("rqt_publisher", context=bus).create_publisher(Bool, "/abort_takeoff", 10)


def start_rocket(bus: Bus, **params: Any) -> tuple[CountDownNode, MainControllerNode, RocketEngineNode]:
    with bus.activate(NodeOverrides(parameters=params)):
        return CountDownNode(), MainControllerNode(), RocketEngineNode()


# -- CountDownNode ----------------------------------------------------------------------------
def test_countdown_during_5s_start_delay_publishes_nothing(
    bus: Bus, executor: Executor, rec: Recorder
) -> None:
    with bus.activate():
        CountDownNode()
    executor.spin_until(4.99)
    assert rec.data("/countdown") == []


def test_countdown_after_delay_publishes_10_to_0_once_per_second(
    bus: Bus, executor: Executor, rec: Recorder
) -> None:
    with bus.activate():
        CountDownNode()
    executor.spin_until(15.5)
    assert rec.data("/countdown") == list(range(10, -1, -1))
    assert rec.times("/countdown") == pytest.approx([5.0 + k for k in range(11)])


def test_countdown_after_reaching_0_stays_alive_and_quiet(
    bus: Bus, executor: Executor, rec: Recorder
) -> None:
    with bus.activate():
        node = CountDownNode()
    executor.spin_until(120.0)
    assert len(rec.data("/countdown")) == 11
    assert node.state == "active" and node in bus.nodes


@pytest.mark.parametrize("delay_s", [0.0, 2.0, 7.5])
def test_countdown_start_delay_param_sets_first_message_time(
    bus: Bus, executor: Executor, rec: Recorder, delay_s: float
) -> None:
    with bus.activate(NodeOverrides(parameters={"start_delay_s": delay_s})):
        CountDownNode()
    executor.spin_until(delay_s + 20.0)
    assert rec.data("/countdown") == list(range(10, -1, -1))
    assert rec.times("/countdown")[0] == pytest.approx(delay_s)
    assert rec.times("/countdown")[-1] == pytest.approx(delay_s + 10.0)


@pytest.mark.parametrize("delay", [-1.0, "5", True, 1e6])
def test_countdown_bad_start_delay_param_raises(bus: Bus, delay: object) -> None:
    with bus.activate(NodeOverrides(parameters={"start_delay_s": delay})), pytest.raises(ValueError):
        CountDownNode()


# -- MainControllerNode -----------------------------------------------------------------------
def test_main_controller_start_logs_ready_for_countdown(bus: Bus, rec: Recorder, executor: Executor) -> None:
    start_rocket(bus)
    executor.spin_some()
    assert rec.logs(CONTROLLER) == ["Rocket Ready for Countdown"]


def test_main_controller_countdown_logs_each_number_then_launches(
    bus: Bus, executor: Executor, rec: Recorder
) -> None:
    _, controller, _ = start_rocket(bus)
    executor.spin_until(LAUNCH_S - 0.5)
    assert not controller.launch
    executor.spin_until(LAUNCH_S + 0.05)
    countdown_logs = [line for line in rec.logs(CONTROLLER) if line.startswith("Countdown")]
    assert countdown_logs == [f"Countdown: {n}s" for n in range(10, -1, -1)]
    assert controller.launch and not controller.abort_mission


def test_main_controller_before_launch_publishes_no_cmd_vel(
    bus: Bus, executor: Executor, rec: Recorder
) -> None:
    start_rocket(bus)
    executor.spin_until(LAUNCH_S - 0.01)
    assert rec.data("/cmd_vel") == []


def test_main_controller_after_launch_first_velocities_match_lab(
    bus: Bus, executor: Executor, rec: Recorder
) -> None:
    start_rocket(bus)
    executor.spin_until(LAUNCH_S + 1.05)
    first = rec.data("/cmd_vel")[:2]
    assert [f"{v:.6f}" for v in first] == ["0.076450", "0.077994"]
    velocity_logs = [line for line in rec.logs(CONTROLLER) if line.startswith("Requested")]
    assert velocity_logs[:2] == ["Requested Velocity: 0.076450m/s", "Requested Velocity: 0.077994m/s"]


def test_main_controller_after_launch_publishes_at_10hz(bus: Bus, executor: Executor, rec: Recorder) -> None:
    start_rocket(bus)
    executor.spin_until(LAUNCH_S + 10.0)
    times = rec.times("/cmd_vel")
    assert LAUNCH_S <= times[0] <= LAUNCH_S + 0.1 + 1e-9
    assert np.diff(times) == pytest.approx(np.full(len(times) - 1, 0.1))
    assert len(times) in (100, 101)


def test_main_controller_velocity_curve_monotonic_half_at_50s_capped_at_1684(
    bus: Bus, executor: Executor, rec: Recorder
) -> None:
    start_rocket(bus)
    executor.spin_until(LAUNCH_S + 200.0)
    v = np.array(rec.data("/cmd_vel"))
    t = np.array(rec.times("/cmd_vel")) - LAUNCH_S
    assert np.all(np.diff(v) >= 0)
    half = int(np.argmax(v >= 842.0))
    assert 49.5 <= t[half] <= 50.5
    assert v[half] == pytest.approx(842.0, abs=10.0)
    assert v.max() <= 1684.0
    assert v[-1] == pytest.approx(1684.0, abs=1e-3)
    # The lab: the log first shows 1684.000000 roughly 159 s after launch.
    top = rec.log_times(CONTROLLER, "Requested Velocity: 1684.000000m/s")
    assert 155.0 <= top[0] - LAUNCH_S <= 163.0


def test_main_controller_abort_before_launch_cmd_vel_never_published(
    bus: Bus, executor: Executor, rec: Recorder, abort_pub: Publisher
) -> None:
    _, controller, _ = start_rocket(bus)
    executor.spin_until(8.5)
    abort_pub.publish(Bool(data=True))
    executor.spin_until(60.0)
    logs = rec.logs(CONTROLLER)
    assert "Abort Abort Abort!!!" in logs
    assert rec.data("/cmd_vel") == []
    assert rec.data("/countdown") == list(range(10, -1, -1))  # the countdown itself runs on
    assert [line for line in logs if line.startswith("Countdown")] == [
        f"Countdown: {n}s" for n in (10, 9, 8, 7)
    ]
    assert not controller.launch and controller.abort_mission


def test_main_controller_abort_before_countdown_ignores_every_countdown(
    bus: Bus, executor: Executor, rec: Recorder, abort_pub: Publisher
) -> None:
    start_rocket(bus)
    executor.spin_until(1.0)
    abort_pub.publish(Bool(data=True))
    executor.spin_until(30.0)
    assert not any(line.startswith("Countdown") for line in rec.logs(CONTROLLER))
    assert rec.data("/cmd_vel") == []


def test_main_controller_each_abort_true_logs_again(
    bus: Bus, executor: Executor, rec: Recorder, abort_pub: Publisher
) -> None:
    start_rocket(bus)
    for t in (6.2, 6.4, 6.6):
        executor.spin_until(t)
        abort_pub.publish(Bool(data=True))
    executor.spin_until(7.0)
    assert rec.logs(CONTROLLER).count("Abort Abort Abort!!!") == 3


def test_main_controller_abort_after_launch_logs_failed_and_cmd_vel_continues(
    bus: Bus, executor: Executor, rec: Recorder, abort_pub: Publisher
) -> None:
    _, controller, _ = start_rocket(bus)
    executor.spin_until(20.05)
    abort_pub.publish(Bool(data=True))
    executor.spin_until(25.0)
    logs = rec.logs(CONTROLLER)
    assert "Abort Failed" in logs and "Abort Abort Abort!!!" not in logs
    after = rec.data("/cmd_vel", after_s=20.05)
    assert len(after) >= 49
    assert after[0] > rec.data("/cmd_vel")[0]
    assert controller.launch and not controller.abort_mission


def test_main_controller_abort_false_is_ignored(
    bus: Bus, executor: Executor, rec: Recorder, abort_pub: Publisher
) -> None:
    start_rocket(bus)
    for t in (8.5, 20.0):
        executor.spin_until(t)
        abort_pub.publish(Bool(data=False))
    executor.spin_until(25.0)
    assert not any("Abort" in line for line in rec.logs(CONTROLLER))
    assert len(rec.data("/cmd_vel")) >= 99


# -- RocketEngineNode -------------------------------------------------------------------------
def test_engine_before_launch_publishes_zero_at_10hz(bus: Bus, executor: Executor, rec: Recorder) -> None:
    start_rocket(bus)
    executor.spin_until(LAUNCH_S - 0.05)
    readings = rec.data("/sensor_vel")
    assert len(readings) == 149
    assert set(readings) == {0.0}
    assert np.diff(rec.times("/sensor_vel")) == pytest.approx(np.full(148, 0.1))


def test_engine_after_launch_sensor_follows_cmd_within_noise(
    bus: Bus, executor: Executor, rec: Recorder
) -> None:
    start_rocket(bus)
    executor.spin_until(LAUNCH_S + 60.0)
    cmds = rec.got["/cmd_vel"]
    after = [(t, m.data) for t, m in rec.got["/sensor_vel"] if t > cmds[0][0]]
    errors = [v - max(c.data for tc, c in cmds if tc <= t) for t, v in after[::25]]
    assert len(errors) > 10
    assert all(abs(e) < 60.0 for e in errors)  # 6 sigma
    assert any(e != 0.0 for e in errors)


def _engine_readings(seed: int, n: int, cmd: float = 500.0) -> list[float]:
    """Feed the engine a constant command before each of its n ticks; return what it senses."""
    bus = Bus(ManualClock())
    executor = Executor(bus)
    readings: list[float] = []
    Node("plot", context=bus).create_subscription(
        Float64, "/sensor_vel", lambda m: readings.append(m.data), 10
    )
    with bus.activate(NodeOverrides(parameters={"seed": seed})):
        RocketEngineNode()
    feeder = Node("feeder", context=bus).create_publisher(Float64, "/cmd_vel", 10)
    for k in range(n):
        feeder.publish(Float64(data=cmd))
        executor.spin_until((k + 1) * 0.1)
    return readings


def test_engine_constant_cmd_noise_is_gaussian_std_10() -> None:
    readings = _engine_readings(seed=3, n=2000)
    assert len(readings) == 2000
    noise = np.array(readings) - 500.0
    assert len(set(readings)) == 2000  # a fresh draw per command
    # σ=10 over 2000 samples: the sample std lies within ±0.5 with overwhelming odds.
    assert 9.3 < noise.std(ddof=1) < 10.7
    assert abs(noise.mean()) < 1.5
    assert 0.6 < np.mean(np.abs(noise) < 10.0) < 0.76  # about 68% within one sigma


def test_engine_one_cmd_value_held_between_ticks(bus: Bus, executor: Executor, rec: Recorder) -> None:
    with bus.activate():
        RocketEngineNode()
    Node("feeder", context=bus).create_publisher(Float64, "/cmd_vel", 10).publish(Float64(data=100.0))
    executor.spin_until(1.05)
    readings = rec.data("/sensor_vel")
    assert len(readings) == 10
    assert len(set(readings)) == 1 and readings[0] != 100.0


def test_engine_same_seed_gives_same_sequence() -> None:
    assert _engine_readings(seed=11, n=50) == _engine_readings(seed=11, n=50)


def test_engine_different_seed_gives_different_sequence() -> None:
    assert _engine_readings(seed=11, n=50) != _engine_readings(seed=12, n=50)


# -- KeyboardManager ----------------------------------------------------------------------------
@pytest.fixture
def keydown_pub(bus: Bus) -> Publisher:
    return Node("fake_keyboard", context=bus).create_publisher(Key, "/keydown", 10)


def test_keyboard_manager_no_key_publishes_false_at_10hz(bus: Bus, executor: Executor, rec: Recorder) -> None:
    with bus.activate():
        KeyboardManager()
    executor.spin_until(1.05)
    assert rec.data("/abort_takeoff") == [False] * 10
    assert rec.times("/abort_takeoff") == pytest.approx([0.1 * k for k in range(1, 11)])


def test_keyboard_manager_key_a_then_true_forever(
    bus: Bus, executor: Executor, rec: Recorder, keydown_pub: Publisher
) -> None:
    with bus.activate():
        KeyboardManager()
    executor.spin_until(1.05)
    keydown_pub.publish(Key(code=Key.KEY_A))
    executor.spin_until(2.05)
    keydown_pub.publish(Key(code=Key.KEY_B))
    executor.spin_until(5.05)
    assert rec.data("/abort_takeoff")[:10] == [False] * 10
    after = rec.data("/abort_takeoff", after_s=1.05)
    assert len(after) == 40 and all(after)
    assert rec.logs("KeyboardManagerNode") == ["a key was pressed!"]


@pytest.mark.parametrize("code", [Key.KEY_B, Key.KEY_SPACE, 65, Key.KEY_UP, Key.KEY_KP1])
def test_keyboard_manager_other_key_does_not_abort(
    bus: Bus, executor: Executor, rec: Recorder, keydown_pub: Publisher, code: int
) -> None:
    with bus.activate():
        KeyboardManager()
    executor.spin_until(0.55)
    keydown_pub.publish(Key(code=code))
    executor.spin_until(2.05)
    assert rec.data("/abort_takeoff") == [False] * 20


def test_keyboard_manager_a_then_other_key_in_one_period_sees_only_last(
    bus: Bus, executor: Executor, rec: Recorder, keydown_pub: Publisher
) -> None:
    # ref §2.3: only the last key that arrives within a 100 ms window is seen.
    with bus.activate():
        KeyboardManager()
    executor.spin_until(0.52)
    keydown_pub.publish(Key(code=Key.KEY_A))
    executor.spin_until(0.56)
    keydown_pub.publish(Key(code=Key.KEY_B))
    executor.spin_until(1.05)
    assert not any(rec.data("/abort_takeoff"))


# -- the whole chain --------------------------------------------------------------------------
def test_full_chain_key_a_on_device_before_launch_aborts_launch(
    bus: Bus, executor: Executor, rec: Recorder
) -> None:
    device = bus.devices["keyboard"] = KeyboardDevice()
    start_rocket(bus)
    with bus.activate(NodeOverrides(name="keyboard")):
        KeyboardNode()
    with bus.activate(NodeOverrides(name="KeyboardManager")):
        KeyboardManager()
    executor.spin_until(8.03)
    device.key_down(Key.KEY_A, 0, "tab-1")
    executor.spin_until(8.07)
    device.key_up(Key.KEY_A, 0, "tab-1")
    executor.spin_until(40.0)
    assert "Abort Abort Abort!!!" in rec.logs(CONTROLLER)
    assert rec.data("/cmd_vel") == []
    assert set(rec.data("/sensor_vel")) == {0.0}
    assert rec.data("/abort_takeoff", after_s=8.1) and all(rec.data("/abort_takeoff", after_s=8.1))
    assert not any(rec.data("/abort_takeoff")[:80])  # 0.1 s .. 8.0 s


def test_full_chain_no_key_rocket_launches(bus: Bus, executor: Executor, rec: Recorder) -> None:
    bus.devices["keyboard"] = KeyboardDevice()
    start_rocket(bus)
    with bus.activate():
        KeyboardNode()
        KeyboardManager()
    executor.spin_until(20.0)
    assert not any(rec.data("/abort_takeoff"))
    assert len(rec.data("/cmd_vel")) >= 49
