"""The class's capacity verdict (capacity.py) over fake places, whether a world is late
(lateness.py) from its timers on a manual clock, and the join queue (join_queue.py) stepped on a
manual clock: bounded in count and time, oldest first, and what the instructor lets through."""

from __future__ import annotations

import threading

import pytest

from api.errors import status_for
from node_runtime.bus import Bus, Executor, ManualClock, Node
from server.classroom import ClassroomError
from server.classroom.capacity import NEAR_CORES, PlaceLoad, judge
from server.classroom.errors import AtCapacityError, JoinLapsedError, UnknownTicketError
from server.classroom.join_queue import JoinQueue
from server.classroom.lateness import LATE_TICK_S, RECENT_TICKS, STALLED_S, SkippedCalls, timer_late
from server.classroom.load import PROCESS_FULL_CORES, CpuLoad, CpuMeter, resident_mb
from server.host.settings import JoinQueueSettings


def place(
    worlds: int,
    cores: float,
    late: int = 0,
    most: int = 60,
    name: str = "server",
    machine: str = "m1",
    vcpus: int = 2,
) -> PlaceLoad:
    return PlaceLoad(name, worlds, most, CpuLoad(cores, 0.5, vcpus, machine, 300.0), late)


def test_an_idle_class_is_ok_and_says_no_reason() -> None:
    capacity = judge([place(10, 0.2)], class_room=50)
    assert (capacity.verdict, capacity.reasons, capacity.worlds, capacity.room) == ("ok", (), 10, 50)


def test_a_busy_process_whose_worlds_keep_time_is_near_not_full() -> None:
    capacity = judge([place(30, PROCESS_FULL_CORES + 0.05)], class_room=30)
    assert capacity.verdict == "near"
    assert "saturated" in capacity.reasons[0]
    assert judge([place(30, NEAR_CORES + 0.01)], class_room=30).verdict == "near"


def test_saturated_with_a_quarter_of_the_worlds_late_is_full() -> None:
    assert judge([place(20, 0.95, late=4)], class_room=40).verdict == "near"  # a fifth late
    capacity = judge([place(20, 0.95, late=5)], class_room=40)
    assert capacity.verdict == "full"
    assert capacity.reasons == ("the CPU of every place with room is saturated and 5 of 20 worlds are late",)


def test_late_worlds_on_an_idle_process_are_near_not_full() -> None:
    capacity = judge([place(8, 0.1, late=8)], class_room=40)
    assert capacity.verdict == "near"
    assert capacity.reasons == ("8 of 8 worlds are late",)


def test_another_place_with_idle_cpu_keeps_the_class_open() -> None:
    busy = place(20, 0.95, late=20)
    idle = place(2, 0.1, name="w1", most=30)
    assert judge([busy, idle], class_room=30).verdict == "near"
    assert judge([busy], class_room=30).verdict == "full"


def test_every_place_at_its_count_is_full_and_little_room_is_near() -> None:
    assert judge([place(4, 0.1, most=4)], class_room=10).verdict == "full"
    capacity = judge([place(3, 0.1, most=4)], class_room=10)
    assert (capacity.verdict, capacity.room) == ("near", 1)
    assert capacity.reasons == ("room for 1 more world",)


def test_a_machine_at_its_world_budget_is_full_though_its_worlds_keep_time() -> None:
    # 15 worlds a core on 2 cores, shared by the class server and a worker on the same machine:
    # idle CPU and no late world (the students' nodes have not started yet) do not hide it.
    server, worker = place(16, 0.3), place(13, 0.2, name="local-1")
    capacity = judge([server, worker], class_room=60, per_core=15)
    assert (capacity.verdict, capacity.room) == ("near", 1)
    assert [m.describe() for m in capacity.machines] == [
        {"machine": "m1", "worlds": 29, "cores": 2, "budget": 30}
    ]
    capacity = judge([place(16, 0.3), place(14, 0.2, name="local-1")], class_room=60, per_core=15)
    assert (capacity.verdict, capacity.room) == ("full", 0)
    assert capacity.reasons == (
        "every place with room is on a machine at its world budget (15 worlds a core: 30 worlds on 2 cores)",
    )
    # No budget (--worlds-per-core 0): the same places by count and CPU alone.
    unbudgeted = judge([place(16, 0.3), place(14, 0.2, name="local-1")], class_room=60, per_core=0)
    assert (unbudgeted.verdict, unbudgeted.room, unbudgeted.machines) == ("ok", 60, ())


def test_another_machine_with_budget_left_keeps_the_class_open_and_its_room_counts() -> None:
    spent = place(30, 0.3)
    other = place(5, 0.2, name="w1", machine="m2", vcpus=4, most=30)
    capacity = judge([spent, other], class_room=100, per_core=15)
    # the other machine: 25 left by count, 55 by its budget; the spent one adds nothing
    assert (capacity.verdict, capacity.room) == ("ok", 25)
    assert {m.machine: m.room for m in capacity.machines} == {"m1": 0, "m2": 55}
    # Two places on one machine share its budget: their rooms by count are not added past it.
    a, b = place(10, 0.2, name="a", machine="m3"), place(10, 0.2, name="b", machine="m3")
    assert judge([a, b], class_room=100, per_core=12).room == 4


def test_a_place_that_reports_no_load_is_not_budgeted() -> None:
    silent = PlaceLoad("w1", 40, 60, None, None)
    capacity = judge([silent], class_room=60, per_core=1)
    assert (capacity.verdict, capacity.room, capacity.machines) == ("ok", 20, ())


def test_a_timer_is_late_when_its_recent_calls_ran_late_or_it_is_stalled_now() -> None:
    clock = ManualClock(0.0)
    bus = Bus(clock)
    node = Node("ticker", context=bus)
    timer = node.create_timer(0.01, lambda: None)
    deadline = timer.next_deadline_s
    # Never called yet: its world is still starting, however overdue its first call is.
    assert not timer_late(timer, deadline + STALLED_S + 5.0)
    timer.lateness_s.append(0.001)  # its first call
    assert not timer_late(timer, deadline)
    assert not timer_late(timer, deadline + 0.5)  # the loop busy for a moment (a world starting)
    assert timer_late(timer, deadline + STALLED_S + 0.001)  # stalled
    for _ in range(RECENT_TICKS // 2):  # late calls, but too few to judge a timer just started
        timer.lateness_s.append(LATE_TICK_S * 2)
    assert not timer_late(timer, timer.next_deadline_s)
    for _ in range(RECENT_TICKS):
        timer.lateness_s.append(LATE_TICK_S * 2)
    assert timer_late(timer, timer.next_deadline_s)  # on time now, but its last calls were late
    for _ in range(RECENT_TICKS // 2 + 1):
        timer.lateness_s.append(0.001)
    assert not timer_late(timer, timer.next_deadline_s)  # the median of the last calls is on time
    timer.cancel()
    assert not timer_late(timer, deadline + 10.0)


def test_the_share_of_calls_skipped_is_read_over_the_worlds_of_a_process() -> None:
    """Two worlds with a 100 Hz tick on a manual clock: on time, nothing skipped; one world's turn
    held up 50 ms, five of its calls skipped of the calls due to both; a world that joins counts
    from its first reading, one that leaves counts no more."""
    clock = ManualClock(0.0)
    worlds: dict[str, Bus] = {}

    def world(name: str) -> Executor:
        bus = Bus(clock)
        Node("dynamics", context=bus).create_timer(0.01, lambda: None)
        worlds[name] = bus
        return Executor(bus)

    ada, bob = world("ada"), world("bob")
    meter = SkippedCalls(lambda: list(worlds.values()), now=clock.now, window_s=0.5)
    clock.advance(0.005)  # the loop's turns half way between the ticks' deadlines
    for _ in range(50):  # 0.5 s on time
        clock.advance(0.01)
        ada.spin_some(), bob.spin_some()
    assert meter.read() == 0.0
    for step in range(50):  # 0.5 s more; ada gets no turn for 50 ms: six calls due, one made
        clock.advance(0.01)
        if not 10 <= step < 15:
            ada.spin_some()
        bob.spin_some()
    due = ada.bus.timer_calls_skipped + ada.bus.timer_calls + bob.bus.timer_calls - 100  # since 0.5 s
    assert ada.bus.timer_calls_skipped == 5 and bob.bus.timer_calls_skipped == 0
    assert meter.read() == pytest.approx(5 / due)
    clock.advance(0.1)
    assert meter.read() == pytest.approx(5 / due)  # read again within the window: the same share
    clock.advance(0.005)
    carl = world("carl")  # carl joins after a long start: his first call comes 0.4 s late
    clock.advance(0.405)
    carl.spin_some(), ada.spin_some(), bob.spin_some()
    assert carl.bus.timer_calls_skipped > 0 and ada.bus.timer_calls_skipped > 5
    del worlds["ada"]  # and ada leaves: neither counts now
    meter.read()
    for _ in range(50):
        clock.advance(0.01)
        carl.spin_some(), bob.spin_some()
    assert meter.read() == 0.0  # carl and bob on time since; ada's and carl's start not counted


def queue(clock: ManualClock, size: int = 3) -> JoinQueue:
    return JoinQueue(JoinQueueSettings(size=size, wait_s=60.0, abandon_s=10.0, retry_after_s=15.0), clock)


def test_the_queue_is_oldest_first_and_refuses_past_its_size_with_retry_after() -> None:
    clock = ManualClock(100.0)
    q = queue(clock, size=2)
    ada = q.add("Ada", "ada", "10.0.0.1")
    bob = q.add("Bob", "bob", "10.0.0.2")
    with pytest.raises(ClassroomError) as refused:
        q.add("Cy", "cy", "10.0.0.3")
    assert isinstance(refused.value, AtCapacityError)
    assert (status_for(refused.value), refused.value.retry_after_s) == (503, 15.0)
    assert "2 joins already wait (at most 2)" in str(refused.value)
    assert q.find(bob.ticket)[1] == 1 and q.find(ada.ticket)[1] == 0
    assert q.holds("ada") and not q.holds("cy")
    q.admit(ada)
    assert q.find(bob.ticket)[1] == 0
    assert q.add("Cy", "cy", "10.0.0.3").world == "cy"  # room in the queue again
    assert (q.admitted, q.refused) == (1, 1)


def test_a_join_that_waits_too_long_or_stops_polling_leaves_with_503_naming_why() -> None:
    clock = ManualClock(0.0)
    q = queue(clock)
    polled = q.add("Ada", "ada", "a")
    silent = q.add("Bob", "bob", "b")
    for _ in range(5):
        clock.advance(9.0)
        q.find(polled.ticket)  # Ada's page polls; Bob's was closed
    with pytest.raises(ClassroomError) as gone:
        q.find(silent.ticket)
    assert isinstance(gone.value, JoinLapsedError)
    assert status_for(gone.value) == 503 and "not polled for 10 s" in str(gone.value)
    clock.advance(16.0)  # 61 s since Ada joined the queue
    with pytest.raises(ClassroomError) as timed_out:
        q.find(polled.ticket)
    assert isinstance(timed_out.value, JoinLapsedError)
    assert status_for(timed_out.value) == 503 and "for 60 s while your join waited" in str(timed_out.value)
    assert len(q) == 0
    with pytest.raises(ClassroomError) as unknown:
        q.find("never-given")
    assert isinstance(unknown.value, UnknownTicketError) and status_for(unknown.value) == 404


def test_the_instructor_lets_a_given_count_through() -> None:
    q = queue(ManualClock(0.0))
    assert not q.use_let_through()
    q.let_in(2)
    assert q.use_let_through() and q.use_let_through() and not q.use_let_through()
    assert q.describe()["let_through"] == 0


def test_the_meter_reports_this_process_resident_memory_and_a_hello_carries_it() -> None:
    rss = [120.0]
    now = [0.0]
    meter = CpuMeter(
        now=lambda: now[0], process_time=lambda: 0.0, host=lambda: None, cores=2, rss=lambda: rss[0]
    )
    rss[0] = 180.0
    now[0] = 2.0
    load = meter.read()
    assert load.rss_mb == 180.0 and load.describe()["rss_mb"] == 180.0
    assert CpuLoad.parse(load.describe()) == load
    older = {k: v for k, v in load.describe().items() if k != "rss_mb"}  # a worker without the field
    parsed = CpuLoad.parse(older)
    assert parsed is not None and parsed.rss_mb is None and parsed.process_cores == load.process_cores
    garbled = CpuLoad.parse({**load.describe(), "rss_mb": "lots"})
    assert garbled is not None and garbled.rss_mb is None
    real = resident_mb()
    assert real is not None and real > 10  # this interpreter, from /proc/self/statm


def test_the_meter_reports_its_loop_threads_scheduling_class_and_a_hello_carries_it() -> None:
    meter = CpuMeter(process_time=lambda: 0.0, host=lambda: None, cores=2, rss=lambda: 100.0)
    assert meter.loop_thread == threading.get_native_id()  # the thread that made it
    load = meter.read()
    assert load.loop == "normal" and load.describe()["loop"] == "normal"
    assert CpuLoad.parse(load.describe()) == load
    assert CpuLoad.parse({**load.describe(), "loop": "realtime"}).loop == "realtime"  # type: ignore[union-attr]
    for garbled in ("fifo", 1, None):  # a worker's hello is untrusted: anything else is not known
        parsed = CpuLoad.parse({**load.describe(), "loop": garbled})
        assert parsed is not None and parsed.loop is None and parsed.process_cores == load.process_cores
    gone = CpuMeter(process_time=lambda: 0.0, host=lambda: None, cores=2, loop_thread=-1)
    assert gone.read().loop is None
