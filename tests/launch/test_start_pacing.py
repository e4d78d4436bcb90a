"""Students' node processes started at their turn (server/host/processes/start_pacing.py), as the
page's Run and Launch start them where the server serves others, on a ManualClock: a start the
pacer defers is a process waiting with no pid, which starts when its turn comes; one stopped
while it waits never starts; the run's output says it waited; waiting starts count against the
running limits; the lab's own nodes, run as processes, are never paced. The processes are real (a student's file that prints and sleeps), ended by the
launcher."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from support.wait import wait_until

from node_runtime.bus import ManualClock
from node_runtime.limits import LimitExceededError
from server.host.processes.sandbox import StudentCodeRefusedError
from server.host.processes.start_pacing import StartPacer
from server.host.settings import LabLimits, LabSettings, Settings
from server.services.launch.launcher import ProcessTransport
from server.services.launch.output import GroupOutput
from server.world.lab import Lab

SLEEPER = """import time


def main():
    print('sleeper up', flush=True)
    time.sleep(60)


if __name__ == '__main__':
    main()
"""


@pytest.fixture
def lab(tmp_path: Path) -> Iterator[Lab]:
    workspace = tmp_path / "workspace"
    (workspace / "src" / "pacing").mkdir(parents=True)
    (workspace / "src" / "pacing" / "sleeper.py").write_text(SLEEPER)
    settings = Settings(
        lab=LabSettings(launch="rocket", viewer=False, workspace=workspace),
        limits=LabLimits(max_running_nodes=3),
    )
    lab = Lab(settings, ManualClock(0.0))
    # A router nobody listens on: the sleeper never asks for one, and each start is real.
    lab.launcher.transport = ProcessTransport("tcp/127.0.0.1:9")
    lab.launcher.start_pacer = StartPacer(1, hold_s=1.0, clock=lab.bus.clock.now)
    try:
        yield lab
    finally:
        lab.launcher.shutdown()


def started(lab: Lab, group_id: str) -> bool:
    process = lab.launch_groups.get(group_id).entries[0].process
    return process is not None and process.pid is not None


def test_a_deferred_start_waits_with_no_pid_and_starts_at_its_turn(lab: Lab) -> None:
    first = lab.launch_groups.run("pacing", "sleeper.py")
    second = lab.launch_groups.run("pacing", "sleeper.py")
    assert started(lab, first.id)
    waiting = second.describe()["nodes"][0]
    assert (waiting["state"], waiting["exit_code"]) == ("waiting", None)
    assert second.entries[0].process is not None and second.entries[0].process.pid is None

    lab.executor.spin_until(0.9)  # the first still holds the one slot
    assert second.describe()["nodes"][0]["state"] == "waiting"
    lab.executor.spin_until(1.0)  # its turn
    assert second.describe()["nodes"][0]["state"] == "running" and started(lab, second.id)
    assert (lab.launcher.start_pacer.admitted, lab.launcher.start_pacer.deferred) == (2, 1)  # type: ignore[union-attr]

    reader = GroupOutput(second, lambda: second.id in lab.launch_groups, lab.joined_names)
    process = second.entries[0].process
    wait_until(lambda: process.output()[1] >= 1, "the second sleeper's first line")
    assert [f["text"] for f in reader.poll() if f["type"] == "line"] == ["sleeper up"]


def test_a_start_stopped_while_it_waits_never_starts_and_its_output_says_so(lab: Lab) -> None:
    lab.launch_groups.run("pacing", "sleeper.py")
    second = lab.launch_groups.run("pacing", "sleeper.py")
    reader = GroupOutput(second, lambda: second.id in lab.launch_groups, lab.joined_names)
    process = second.entries[0].process
    assert process is not None
    assert reader.poll() == [{"type": "waiting", "node": process.label}]
    assert reader.poll() == []  # said once

    lab.launch_groups.stop(second.id)
    lab.executor.spin_until(5.0)  # long past its turn
    assert (process.state, process.pid) == ("stopped", None)
    assert process not in lab.launcher.supervisor.processes
    assert reader.poll() == [
        {"type": "exit", "node": process.label, "code": None, "signal": None},
        {"type": "end"},
    ]
    assert reader.ended


def test_waiting_starts_count_against_the_running_limit(lab: Lab) -> None:
    for _ in range(3):  # one starts, two wait
        lab.launch_groups.run("pacing", "sleeper.py")
    states = [g.describe()["nodes"][0]["state"] for g in lab.launch_groups.values()]
    assert states == ["running", "waiting", "waiting"]
    with pytest.raises(LimitExceededError, match="running node processes in this world"):
        lab.launch_groups.run("pacing", "sleeper.py")


def test_each_waiting_start_takes_its_own_turn_in_order(lab: Lab) -> None:
    groups = [lab.launch_groups.run("pacing", "sleeper.py") for _ in range(3)]
    turns = []
    for t in (0.5, 1.0, 1.5, 2.0):
        lab.executor.spin_until(t)
        turns.append([g.describe()["nodes"][0]["state"] for g in groups])
    assert turns == [
        ["running", "waiting", "waiting"],
        ["running", "running", "waiting"],
        ["running", "running", "waiting"],
        ["running", "running", "running"],
    ]


def test_a_lab_on_loopback_does_not_pace_its_launchers_starts(tmp_path: Path) -> None:
    """Starts are paced only where the lab serves others: a lab on loopback has no pacer on its
    launcher, so its user's runs start as they ask; it keeps one for ros2lab run's joins."""
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, workspace=None)), ManualClock(0.0))
    try:
        assert lab.launcher.start_pacer is None
        assert lab.start_pacer.admit() is None  # the pacer its join route asks
    finally:
        lab.launcher.shutdown()


def test_the_labs_own_nodes_run_as_processes_start_at_once_while_students_starts_wait(lab: Lab) -> None:
    """With every lab node as its own process (``--node-processes all``), the lab's nodes are not
    students' code: they start as asked even when the pacer has no slot free, and never take one."""
    lab.launcher.all_processes = True
    held = lab.launch_groups.run("pacing", "sleeper.py")  # takes the pacer's one slot
    waiting = lab.launch_groups.run("pacing", "sleeper.py")
    assert started(lab, held.id) and waiting.describe()["nodes"][0]["state"] == "waiting"
    pacer = lab.launcher.start_pacer
    assert pacer is not None
    counts = (pacer.admitted, pacer.deferred)

    lab_node = lab.launch_groups.run("rocketship", "countdown")
    entry = lab_node.entries[0]
    assert entry.process is not None, entry.error  # a process, not a node inside the app
    assert entry.process.pid is not None  # started now, not told to wait for a turn
    assert (pacer.admitted, pacer.deferred) == counts  # and it asked the pacer nothing
    assert waiting.describe()["nodes"][0]["state"] == "waiting"  # the student's start still waits


def node_names(lab: Lab) -> set[str]:
    return {n.fully_qualified_name for n in lab.bus.nodes}


def test_a_paced_launcher_has_its_timer_node_before_the_first_start_waits(lab: Lab) -> None:
    """A class world's Runs wait for their turn on the launcher's hidden timer node: it is made as
    the world's graph comes up, so sixty Runs in one second make no node on the worlds' loop."""
    assert "/_launch_timers" not in node_names(lab)  # the fixture's launcher has no graph yet
    lab.launcher.use_graph(ProcessTransport("tcp/127.0.0.1:9"), None)
    before = node_names(lab)
    assert "/_launch_timers" in before

    lab.launch_groups.run("pacing", "sleeper.py")
    waiting = lab.launch_groups.run("pacing", "sleeper.py")
    assert waiting.describe()["nodes"][0]["state"] == "waiting"  # its timer is on the node made before
    assert node_names(lab) == before
    lab.executor.spin_until(1.0)
    assert started(lab, waiting.id)


def test_a_launcher_that_paces_nothing_makes_no_timer_node_as_its_graph_comes_up(tmp_path: Path) -> None:
    """Without a pacer (a lab on loopback), or where students' code is refused, no start ever waits
    for a turn: the graph gets no hidden node for it."""
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, workspace=None)), ManualClock(0.0))
    try:
        lab.launcher.use_graph(ProcessTransport("tcp/127.0.0.1:9"), None)
        assert "/_launch_timers" not in node_names(lab)
        lab.launcher.start_pacer = StartPacer(1, hold_s=1.0, clock=lab.bus.clock.now)
        lab.launcher.use_graph(ProcessTransport("tcp/127.0.0.1:9"), StudentCodeRefusedError("no sandbox"))
        assert "/_launch_timers" not in node_names(lab)
    finally:
        lab.launcher.shutdown()
