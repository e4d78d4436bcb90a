"""The watch on a real bus with a manual clock: messages reach the checks with their publishers,
met checkpoints land in the world's progress, the queue stays bounded, and stop removes the taps."""

from __future__ import annotations

from node_runtime.ament.index import PackageIndex
from node_runtime.bus import Bus, Executor, ManualClock, Node
from node_runtime.msgs import get_type
from node_runtime.msgs.wire import dds_type_name, type_hash
from node_runtime.transport.keys import EntityKind, EntityToken, keep_last
from node_runtime.transport.remote_graph import RemoteGraph
from server.services.launch.launcher import Launcher
from server.world.checkpoints.catalog import LAB_CHECKPOINTS
from server.world.checkpoints.events import Source
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.sources import Sources
from server.world.checkpoints.watcher import MAX_QUEUED, CheckpointWatch

Vector3 = get_type("geometry_msgs/msg/Vector3")
PoseStamped = get_type("geometry_msgs/msg/PoseStamped")
ZID = "ef719c5dcbcb0e27f57de879a132a6ff"


def watch_on(bus: Bus, remote: RemoteGraph | None = None) -> CheckpointWatch:
    launcher = Launcher(bus, PackageIndex(workspace=None))
    watch = CheckpointWatch(
        bus, launcher, PackageIndex(workspace=None), Progress(LAB_CHECKPOINTS), lambda: remote
    )
    watch.start()
    return watch


def test_watch_1_hz_setpoints_and_the_drone_at_the_point_meet_fly_to_point() -> None:
    clock = ManualClock()
    bus = Bus(clock)
    executor = Executor(bus)
    watch = watch_on(bus)
    with bus.activate():
        node = Node("student_tools")
    setpoints = node.create_publisher(Vector3, "/uav/input/position", 10)
    gps = node.create_publisher(PoseStamped, "/uav/sensors/gps", 10)
    node.create_timer(1.0, lambda: setpoints.publish(Vector3(x=5.0, y=5.0, z=10.0)))

    def at_target() -> None:
        msg = PoseStamped()
        msg.pose.position.x, msg.pose.position.y, msg.pose.position.z = 5.0, 5.0, 10.0
        gps.publish(msg)

    node.create_timer(0.01, at_target)  # 100 Hz, as the sim: the tap thins it
    executor.spin_for(4.0)
    assert "fly_to_point" not in watch.progress.records
    assert "positions to (5, 5, 10) at 1.0 Hz; 0.0 m" in watch.lines()["fly_to_point"][1]
    executor.spin_for(4.0)
    record = watch.progress.records["fly_to_point"]
    assert record.evidence["publisher"] == "/student_tools"
    assert all(e["student"] is False for e in record.evidence["setpoints"])  # a node inside the app
    assert len(record.evidence["track"]) >= 20
    assert watch.dropped == 0


def test_watch_queue_is_bounded_while_nothing_drains_it() -> None:
    bus = Bus(ManualClock())
    watch = watch_on(bus)
    with bus.activate():
        node = Node("flood")
    pub = node.create_publisher(Vector3, "/uav/input/position", 10)
    for _ in range(MAX_QUEUED + 100):
        pub.publish(Vector3(x=1.0))
    assert watch.dropped == 100
    watch.drain()
    assert watch.progress.records == {}


def test_watch_stop_removes_its_taps_and_node() -> None:
    bus = Bus(ManualClock())
    watch = watch_on(bus)
    with bus.activate():
        node = Node("later")
    pub = node.create_publisher(Vector3, "/uav/input/position", 10)
    assert pub.topic.tap is not None and any(n.get_name() == "_checkpoints" for n in bus.nodes)
    watch.stop()
    assert pub.topic.tap is None and bus.taps == {}
    assert not any(n.get_name() == "_checkpoints" for n in bus.nodes)
    pub.publish(Vector3(x=1.0))  # still delivered, untapped


def test_sources_a_remote_publisher_the_lab_did_not_start_is_the_students() -> None:
    bus = Bus(ManualClock())
    remote = RemoteGraph("0" * 32, 0)
    token = EntityToken(
        0,
        ZID,
        3,
        7,
        EntityKind.PUBLISHER,
        "/",
        "KeyboardManager",
        topic="/abort_takeoff",
        dds_type=dds_type_name("std_msgs/msg/Bool"),
        type_hash=type_hash("std_msgs/msg/Bool"),
        qos=keep_last(1),
    )
    sources = Sources(
        Launcher(bus, PackageIndex(workspace=None)), PackageIndex(workspace=None), lambda: remote
    )
    assert sources.of(token.gid).node == ""  # its token has not arrived yet: not known
    remote.apply(token.key, True)
    found = sources.of(token.gid)
    assert found == Source("/KeyboardManager", f"zenoh:{ZID[:8]}", student=True)
    remote.apply(token.key, False)
    assert remote.publisher(token.gid) is None
