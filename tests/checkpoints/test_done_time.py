"""A checkpoint's done time is the first moment it was met: the student's Guide (world_view, what
GET /api/checkpoints answers) and the instructor's table (table, what GET /api/classroom/checkpoints
answers) show that one time, and further publishing moves neither. Bus and wall clock by hand."""

from __future__ import annotations

from node_runtime.ament.index import PackageIndex
from node_runtime.bus import Bus, Executor, ManualClock, Node
from node_runtime.msgs import get_type
from server.services.launch.launcher import Launcher
from server.world.checkpoints.catalog import LAB_CHECKPOINTS
from server.world.checkpoints.class_table import table
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.view import world_view
from server.world.checkpoints.watcher import CheckpointWatch

Vector3 = get_type("geometry_msgs/msg/Vector3")
PoseStamped = get_type("geometry_msgs/msg/PoseStamped")
EPOCH_S = 1_760_000_000.0


def _done_times(watch: CheckpointWatch, name: str) -> tuple[str | None, str | None, int]:
    lines = watch.lines()
    guide = next(
        c for c in world_view(watch.progress, lines, watch.version)["checkpoints"] if c["name"] == name
    )
    (student,) = table([c.name for c in LAB_CHECKPOINTS], [("w1", watch.progress, lines)])["students"]
    return guide["done_at"], student["cells"][name]["done_at"], guide["times_done"]


def test_fly_to_point_done_time_is_one_time_and_10_s_more_publishing_keeps_it() -> None:
    clock = ManualClock()
    bus = Bus(clock)
    executor = Executor(bus)
    progress = Progress(LAB_CHECKPOINTS, wall=lambda: EPOCH_S + clock.now())
    packages = PackageIndex(workspace=None)
    watch = CheckpointWatch(bus, Launcher(bus, packages), packages, progress)
    watch.start()
    with bus.activate():
        node = Node("position_publisher")
    setpoints = node.create_publisher(Vector3, "/uav/input/position", 10)
    gps = node.create_publisher(PoseStamped, "/uav/sensors/gps", 10)
    node.create_timer(1.0, lambda: setpoints.publish(Vector3(x=5.0, y=5.0, z=10.0)))

    def at_target() -> None:
        msg = PoseStamped()
        msg.pose.position.x, msg.pose.position.y, msg.pose.position.z = 5.0, 5.0, 10.0
        gps.publish(msg)

    node.create_timer(0.01, at_target)
    executor.spin_for(8.0)
    guide_at, table_at, times = _done_times(watch, "fly_to_point")
    assert guide_at is not None and guide_at == table_at and times == 1
    line = watch.lines()["fly_to_point"][1]
    executor.spin_for(10.0)  # ten more positions at 1 Hz, the drone still at the point
    assert _done_times(watch, "fly_to_point") == (guide_at, table_at, 1)
    assert watch.lines()["fly_to_point"][1] == line


def test_progress_met_again_keeps_the_first_time_and_the_newest_evidence() -> None:
    now = [EPOCH_S]
    progress = Progress(LAB_CHECKPOINTS, wall=lambda: now[0])
    progress.met("keyboard_abort", {"try": 1})
    now[0] += 60.0
    record = progress.met("keyboard_abort", {"try": 2})
    assert (record.done_at_s, record.evidence, record.times) == (EPOCH_S, {"try": 2}, 2)
