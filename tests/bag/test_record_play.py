"""A recorded flight, read back with mcap-ros2-support, and played back onto the bus.

The lab runs on a ManualClock: 15 s of flight are 15 s of sim time, stepped at every timer's
deadline, so the counts and intervals asserted here are the graph's own, not the machine's.
"""

from __future__ import annotations

import itertools
import shutil
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import yaml
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory

from node_runtime.bus import ManualClock, Node
from node_runtime.msgs import Bool, Message, get_type
from server.host.settings import LabSettings, Settings
from server.peripherals.bag.player import BagError
from server.world.lab import Lab

FLIGHT_S = 15.0
RECORD_MARGIN_S = 1e-3
T0_S = 1_700_000_000.0  # an epoch time, so stamps look like a real recording's
TARGET = {"x": 5.0, "y": 5.0, "z": 10.0}
NOMINAL_RATES_HZ = {  # the launch's own rates (publish_rate_hz, controller RATE_HZ, the 1 Hz setpoint)
    "/uav/sensors/gps": 100.0,
    "/uav/sensors/velocity": 100.0,
    "/uav/sensors/attitude": 100.0,
    "/uav/sensors/pressure": 10.0,
    "/uav/input/position": 1.0,
}


@dataclass(frozen=True)
class Decoded:
    topic: str
    log_time_ns: int
    msg: Any


def read_decoded(path: Path, topics: list[str] | None = None) -> list[Decoded]:
    """Every message of an MCAP, decoded by mcap-ros2-support from the schemas in the file."""
    with path.open("rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        return [
            Decoded(channel.topic, message.log_time, msg)
            for _, channel, message, msg in reader.iter_decoded_messages(topics, log_time_order=True)
        ]


def fly_lab(bag_dir: Path) -> Lab:
    lab = Lab(Settings(lab=LabSettings(launch="fly", viewer=False, bag_dir=bag_dir)), ManualClock(T0_S))
    lab.start_nodes()
    return lab


@pytest.fixture(scope="module")
def flight(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Path, dict[str, int]]]:
    """Fly to (5, 5, 10) at 1 Hz for 15 s while recording every topic; (bag folder, counts on the bus)."""
    bag_dir = tmp_path_factory.mktemp("bags")
    lab = fly_lab(bag_dir)
    lab.executor.spin_for(0.01)  # every node up and publishing
    # Counted from when the recorder is up: its node's own declaration (use_sim_time, on
    # /parameter_events) comes before it subscribes, as a ros2 bag recorder's does.
    recording = lab.bags.record(all_topics=True, name="flight")
    before = {name: t.publish_count for name, t in lab.bus.topics.items()}
    lab.publishers.start("/uav/input/position", TARGET, "geometry_msgs/msg/Vector3", 1.0)
    lab.executor.spin_for(FLIGHT_S - RECORD_MARGIN_S)  # [start, start + 15 s): 15 setpoints, not 16
    lab.bags.stop_recording("flight")
    on_bus = {name: t.publish_count - before.get(name, 0) for name, t in lab.bus.topics.items()}
    assert recording.writer.stats.dropped == 0
    yield bag_dir / "flight", on_bus
    lab.publishers.stop_all()
    lab.launcher.shutdown()


def test_recorded_flight_has_the_topics_at_their_rates_and_decodes(
    flight: tuple[Path, dict[str, int]],
) -> None:
    folder, on_bus = flight
    counts: dict[str, int] = {}
    last_gps = None
    for m in read_decoded(folder / "flight_0.mcap"):
        counts[m.topic] = counts.get(m.topic, 0) + 1
        if m.topic == "/uav/sensors/gps":
            last_gps = m.msg
        if m.topic == "/uav/input/position":
            assert (m.msg.x, m.msg.y, m.msg.z) == (5.0, 5.0, 10.0)
    for topic, rate_hz in NOMINAL_RATES_HZ.items():
        assert counts[topic] == pytest.approx(rate_hz * FLIGHT_S, rel=0.05), topic
    # Every message the graph published while recording is in the bag, on every visible topic.
    for topic, count in counts.items():
        assert count == on_bus[topic], topic
    assert {t for t, n in on_bus.items() if n and not t.startswith("/_")} == set(counts)
    assert last_gps is not None and last_gps.header.frame_id == "world"
    assert last_gps.pose.position.z > 3.0  # climbing towards 10 m: the decoded pose is the flight's


def test_recorded_bag_is_ros2_profile_with_full_definitions(flight: tuple[Path, dict[str, int]]) -> None:
    folder, _ = flight
    with (folder / "flight_0.mcap").open("rb") as f:
        reader = make_reader(f)
        assert reader.get_header().profile == "ros2"
        summary = reader.get_summary()
    assert summary is not None
    schemas = {s.name: s for s in summary.schemas.values()}
    pose = schemas["geometry_msgs/msg/PoseStamped"]
    assert pose.encoding == "ros2msg"
    assert b"MSG: std_msgs/Header" in pose.data and b"MSG: geometry_msgs/Quaternion" in pose.data
    for channel in summary.channels.values():
        assert channel.message_encoding == "cdr"
        assert channel.metadata["topic_type_hash"].startswith("RIHS01_")
    info = yaml.safe_load((folder / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    assert info["storage_identifier"] == "mcap"
    assert info["relative_file_paths"] == ["flight_0.mcap"]
    assert info["message_count"] == sum(summary.statistics.channel_message_counts.values())
    assert info["duration"]["nanoseconds"] == pytest.approx(FLIGHT_S * 1e9, rel=0.01)


class Echo:
    """``ros2 topic echo`` on several topics at once: (bus time, topic, message) in arrival order."""

    def __init__(self, lab: Lab, topics: dict[str, type[Message]]) -> None:
        self.lab = lab
        self.got: list[tuple[float, str, Message]] = []
        with lab.bus.activate():
            self.node = Node("echo")
        for topic, msg_type in topics.items():
            self.node.create_subscription(msg_type, topic, self._keep(topic), 10_000)

    def _keep(self, topic: str) -> object:
        return lambda msg: self.got.append((self.lab.bus.clock.now(), topic, msg))


def recorded(folder: Path) -> list[tuple[float, str]]:
    """(log time in s, topic) of every message in the bag, in log-time order."""
    return [(m.log_time_ns / 1e9, m.topic) for m in read_decoded(folder / "flight_0.mcap")]


def test_bag_play_republishes_in_order_with_the_recorded_timing(
    flight: tuple[Path, dict[str, int]], tmp_path: Path
) -> None:
    folder, _ = flight
    lab = Lab(
        Settings(lab=LabSettings(launch="rocket", viewer=False, bag_dir=tmp_path)), ManualClock(5_000.0)
    )
    topics = {t: get_type(type_name) for t, type_name in _bag_types(folder).items()}
    echo = Echo(lab, topics)
    start_s = lab.bus.clock.now()
    _, player = lab.bags.play(folder, rate=1.0)
    lab.executor.spin_for(FLIGHT_S + 1.0)
    assert player.finished and not player.skipped
    want = recorded(folder)
    assert [topic for _, topic, _ in echo.got] == [topic for _, topic in want]
    t_rec0 = want[0][0]
    for (t_play, _, _), (t_rec, _) in zip(echo.got, want, strict=True):
        assert t_play - start_s == pytest.approx(t_rec - t_rec0, abs=1e-6)
    # The played messages are the recorded ones, field for field.
    gps_played = [m for _, t, m in echo.got if t == "/uav/sensors/gps"]
    gps_recorded = [m.msg for m in read_decoded(folder / "flight_0.mcap", ["/uav/sensors/gps"])]
    assert [g.pose.position.z for g in gps_played] == [g.pose.position.z for g in gps_recorded]
    lab.bags.reap_players()
    assert "rosbag2_player" not in {n.get_name() for n in lab.bus.nodes}


def test_bag_play_at_double_rate_halves_the_intervals(
    flight: tuple[Path, dict[str, int]], tmp_path: Path
) -> None:
    folder, _ = flight
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, bag_dir=tmp_path)), ManualClock(0.0))
    echo = Echo(lab, {"/uav/input/position": get_type("geometry_msgs/msg/Vector3")})
    _, player = lab.bags.play(folder, rate=2.0)
    lab.executor.spin_for(FLIGHT_S / 2 + 0.5)
    assert player.finished
    times = [t for t, _, _ in echo.got]
    assert len(times) == pytest.approx(FLIGHT_S, abs=1)
    gaps = [b - a for a, b in itertools.pairwise(times)]
    assert all(g == pytest.approx(0.5, abs=1e-6) for g in gaps)


def record_pair(lab: Lab, name: str) -> None:
    """A two-message bag: True, then False 0.25 s later."""
    with lab.bus.activate():
        talker = Node("talker")
    pub = talker.create_publisher(Bool, "/flag", 10)
    lab.bags.record(["/flag"], name=name)
    pub.publish(Bool(data=True))
    lab.executor.spin_for(0.25)
    pub.publish(Bool(data=False))
    lab.executor.spin_for(0.01)
    lab.bags.stop_recording(name)
    talker.destroy_node()


def test_bag_play_loop_starts_over(tmp_path: Path) -> None:
    """A two-message bag looped: the pair comes again and again, with the recorded gap."""
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, bag_dir=tmp_path)), ManualClock(0.0))
    record_pair(lab, "pair")
    echo = Echo(lab, {"/flag": Bool})
    _, player = lab.bags.play(tmp_path / "pair", loop=True)
    lab.executor.spin_for(1.0)
    assert not player.finished
    assert [m.data for _, _, m in echo.got][:6] == [True, False, True, False, True, False]


def test_a_looping_playback_whose_file_vanishes_ends_instead_of_crashing(tmp_path: Path) -> None:
    """Deleted on disk between two loops (rm -r in a terminal): the player finishes, as at a
    damaged file's end, with a warning; its node does not crash."""
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, bag_dir=tmp_path)), ManualClock(0.0))
    record_pair(lab, "pair")
    _, player = lab.bags.play(tmp_path / "pair", loop=True)
    lab.executor.spin_for(0.1)  # the first message is out; the second is due at 0.25 s
    shutil.rmtree(tmp_path / "pair")
    lab.executor.spin_for(1.0)
    assert player.finished and player.state != "crashed"
    assert player.published == 2  # one loop, then nothing more


class CreepingClock(ManualClock):
    """A clock that moves a little at every reading, as the wall clock does on a busy machine."""

    STEP_S = 5e-6  # more than the player's rounding allowance (DUE_EPS_S)

    def now(self) -> float:
        self.advance(self.STEP_S)
        return super().now()


def test_playback_survives_time_passing_while_it_schedules(tmp_path: Path) -> None:
    """Time moves between the player's readings of the clock: a message due within a few
    microseconds is then due at once, never a timer of zero or negative period (which crashed
    the player). Gaps of 1..60 us between recorded messages cover that window."""
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, bag_dir=tmp_path)), CreepingClock(0.0))
    with lab.bus.activate():
        talker = Node("talker")
    pub = talker.create_publisher(Bool, "/flag", 100)
    lab.bags.record(["/flag"], name="close")
    for k in range(60):
        pub.publish(Bool(data=k % 2 == 0))
        lab.executor.spin_for(k * 1e-6)
    lab.executor.spin_for(0.01)
    lab.bags.stop_recording("close")
    talker.destroy_node()
    echo = Echo(lab, {"/flag": Bool})
    _, player = lab.bags.play(tmp_path / "close")
    lab.executor.spin_for(1.0)
    assert player.state != "crashed" and player.finished
    assert [m.data for _, _, m in echo.got] == [k % 2 == 0 for k in range(60)]


def test_deleting_a_bag_stops_its_playbacks(tmp_path: Path) -> None:
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, bag_dir=tmp_path)), ManualClock(0.0))
    record_pair(lab, "pair")
    record_pair(lab, "other")
    pair_id, pair_player = lab.bags.play(tmp_path / "pair", loop=True)
    _, other_player = lab.bags.play(tmp_path / "other", loop=True)
    lab.executor.spin_for(0.1)
    lab.bags.detach_bag("pair")
    assert pair_player.state == "destroyed" and pair_id not in lab.bags.players
    lab.executor.spin_for(1.0)
    assert other_player.state == "active" and other_player.published > 2  # the other bag plays on


def test_bag_play_refuses_what_is_not_a_bag(tmp_path: Path) -> None:
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, bag_dir=tmp_path)), ManualClock(0.0))
    (tmp_path / "notes.mcap").write_text("not an mcap")
    nodes_before = len(lab.bus.nodes)
    for path in (tmp_path / "notes.mcap", tmp_path / "missing", tmp_path):
        with pytest.raises(BagError):
            lab.bags.play(path)
    with pytest.raises(ValueError, match="rate"):
        lab.bags.play(tmp_path / "notes.mcap", rate=0)
    assert len(lab.bus.nodes) == nodes_before  # no node left behind


@pytest.mark.parametrize("name", ["../escape", "a/b", "", ".hidden", "x" * 101])
def test_bag_names_cannot_leave_the_bag_folder(tmp_path: Path, name: str) -> None:
    lab = Lab(
        Settings(lab=LabSettings(launch="rocket", viewer=False, bag_dir=tmp_path / "bags")), ManualClock(0.0)
    )
    with pytest.raises(ValueError, match="bag name"):
        lab.bags.record(all_topics=True, name=name)
    assert not (tmp_path / "bags").exists()


def _bag_types(folder: Path) -> dict[str, str]:
    with (folder / "flight_0.mcap").open("rb") as f:
        summary = make_reader(f).get_summary()
    assert summary is not None
    return {c.topic: summary.schemas[c.schema_id].name for c in summary.channels.values()}
