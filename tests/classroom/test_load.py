"""Placement by load: the CPU meter on injected clocks and counters, a hello's load read as
untrusted input, the choice among the places with room and the machines' world budgets, and the
cores a process may use under a container's CPU quota."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from server.base.cores import usable_cores
from server.classroom.budget import within_budget
from server.classroom.load import (
    HOST_FULL,
    PROCESS_FULL_CORES,
    Choice,
    CpuLoad,
    CpuMeter,
    choose,
    host_times,
    machine_id,
)
from server.classroom.workers import WorkerRef


class Counters:
    """A process's CPU seconds, the machine's (busy, total) ticks and a monotonic clock, stepped by hand."""

    def __init__(self) -> None:
        self.t = 100.0
        self.cpu = 3.0
        self.busy, self.total = 1000, 4000

    def host(self) -> tuple[int, int]:
        return self.busy, self.total


def meter(c: Counters) -> CpuMeter:
    return CpuMeter(now=lambda: c.t, process_time=lambda: c.cpu, host=c.host, cores=2, rss=lambda: None)


def test_the_meter_reports_cores_used_and_the_machines_busy_share_over_each_window() -> None:
    c = Counters()
    m = meter(c)
    # nothing measured yet; the loop's class is that of the thread that made the meter (this one)
    assert m.read() == CpuLoad(0.0, None, 2, loop="normal")
    c.t += 2.0
    c.cpu += 1.0  # one CPU-second in two: half a core
    c.busy, c.total = c.busy + 300, c.total + 400
    load = m.read()
    assert load.process_cores == pytest.approx(0.5)
    assert load.host_busy == pytest.approx(0.75)
    assert not load.saturated
    c.t += 0.5  # under a window: the last load again, not a noisy half-window
    c.cpu += 0.5
    assert m.read() == load
    c.t += 0.5  # a whole window since the last: 0.5 CPU-s in 1 s
    assert m.read().process_cores == pytest.approx(0.5)
    c.t += 1.0
    c.cpu += PROCESS_FULL_CORES + 0.05  # the loop thread near a whole core: full, however idle the machine
    c.busy, c.total = c.busy + 10, c.total + 200
    assert m.read().saturated
    c.t += 1.0
    c.cpu += 0.1
    c.busy, c.total = c.busy + int(HOST_FULL * 200), c.total + 200  # the machine busy (or stolen)
    assert m.read().saturated


def test_a_machine_without_proc_stat_is_judged_by_the_process_alone() -> None:
    c = Counters()
    m = CpuMeter(now=lambda: c.t, process_time=lambda: c.cpu, host=lambda: None, cores=4, rss=lambda: None)
    c.t += 1.0
    c.cpu += 0.2
    assert m.read() == CpuLoad(pytest.approx(0.2), None, 4, loop="normal")  # type: ignore[arg-type]


@pytest.mark.skipif(not Path("/proc/stat").exists(), reason="Linux's /proc/stat only")
def test_host_times_and_machine_id_read_this_machine() -> None:
    assert machine_id() == machine_id() and len(machine_id() or "") == 16
    first = host_times()
    assert first is not None and 0 <= first[0] <= first[1]
    second = host_times()
    assert second is not None and second[1] >= first[1] and second[0] >= first[0]


@pytest.mark.parametrize(
    "body",
    [
        None,
        "busy",
        [],
        {"process_cores": True, "host_busy": 0.1, "cores": 2},
        {"process_cores": -1, "host_busy": 0.1, "cores": 2},
        {"process_cores": 0.1, "host_busy": 1.5, "cores": 2},
        {"process_cores": 0.1, "host_busy": "0.5", "cores": 2},
        {"process_cores": 0.1, "host_busy": 0.1, "cores": 0},
        {"process_cores": float("nan"), "host_busy": 0.1, "cores": 2},
        {"host_busy": 0.1, "cores": 2},
        {"process_cores": 0.1, "host_busy": 0.1, "cores": 2, "machine": 7},
        {"process_cores": 0.1, "host_busy": 0.1, "cores": 2, "machine": "m" * 65},
    ],
)
def test_a_hellos_load_of_any_other_shape_is_not_taken(body: object) -> None:
    assert CpuLoad.parse(body) is None


def test_a_hellos_load_reads_back_as_it_was_described() -> None:
    load = CpuLoad(0.4321, 0.5, 8, "3f2a")
    assert CpuLoad.parse(load.describe()) == CpuLoad(0.432, 0.5, 8, "3f2a")
    assert CpuLoad.parse({"process_cores": 0, "host_busy": None, "cores": 1}) == CpuLoad(0.0, None, 1)


def ref(wid: str) -> WorkerRef:
    return WorkerRef(wid, f"http://127.0.0.1/{wid}", 0, 10, "t")


IDLE, BUSY = CpuLoad(0.1, 0.2, 2, "m1"), CpuLoad(0.95, 0.5, 2, "m1")  # BUSY: its process's loop is full


def test_a_new_world_goes_to_the_lowest_share_but_never_to_a_full_process_while_another_has_room() -> None:
    here, wa, wb = Choice(0.5, None, IDLE), Choice(0.2, ref("wa"), BUSY), Choice(0.4, ref("wb"), IDLE)
    assert choose([here, wa, wb]) == (wb, False)  # wa has the fewest worlds, but its loop is full
    assert choose([here, Choice(0.2, ref("wa"), IDLE), wb])[0].ref == ref("wa")
    # Every place full: a student still gets a world, on the least full, and the caller is told.
    assert choose([Choice(0.5, None, BUSY), Choice(0.3, ref("wa"), BUSY)]) == (
        Choice(0.3, ref("wa"), BUSY),
        True,
    )
    # A tie goes to a worker, so the class server keeps its core for the pages; unknown load is not full.
    assert choose([Choice(0.0, None, IDLE), Choice(0.0, ref("wa"), None)])[0].ref == ref("wa")
    with pytest.raises(ValueError):
        choose([])


def test_a_busy_machine_counts_against_its_places_only_beside_another_machine() -> None:
    busy_m1 = CpuLoad(0.2, 0.95, 2, "m1")  # the process is fine; its machine is busy (or stolen)
    here, wa = Choice(0.0, None, busy_m1), Choice(0.5, ref("wa"), CpuLoad(0.3, 0.95, 2, "m1"))
    # One machine: the world costs it the same wherever it goes, so worlds / capacity decides.
    assert choose([here, wa]) == (here, False)
    # A worker on another machine with CPU to spare takes it, though it has more worlds.
    wb = Choice(0.6, ref("wb"), CpuLoad(0.3, 0.4, 16, "m2"))
    assert choose([here, wa, wb]) == (wb, False)
    # Both machines busy: by worlds / capacity again, and full.
    wb_busy = Choice(0.6, ref("wb"), CpuLoad(0.3, 0.92, 16, "m2"))
    assert choose([here, wa, wb_busy]) == (here, True)
    assert busy_m1.saturated and not busy_m1.process_full


def test_a_new_world_goes_to_a_machine_with_budget_left_while_there_is_one() -> None:
    # The class server's machine (2 cores, 15 worlds a core) holds 30 worlds over two places; a
    # worker on another machine is fuller by share but has budget left: it takes the world.
    here_load, local_load = CpuLoad(0.3, 0.5, 2, "m1"), CpuLoad(0.2, 0.5, 2, "m1")
    remote = WorkerRef("w2", "http://w2", 20, 24, "token", load=CpuLoad(0.4, 0.5, 2, "m2"))
    here = Choice(10 / 60, None, here_load)
    local = Choice(20 / 30, WorkerRef("local-1", "http://l1", 20, 30, "token", load=local_load), local_load)
    far = Choice(20 / 24, remote, remote.load)
    places = [("server", 10, here_load), ("local-1", 20, local_load), ("w2", 20, remote.load)]
    choices = [("server", here), ("local-1", local), ("w2", far)]
    assert within_budget(choices, places, per_core=15) == [far]
    assert choose(within_budget(choices, places, per_core=15)) == (far, False)
    # Without a budget, or with room left on the first machine, the lowest share wins as before.
    assert choose(within_budget(choices, places, per_core=0)) == (here, False)
    assert choose(within_budget(choices, places, per_core=16)) == (here, False)
    # Every machine at its budget (a join the instructor let through): it still goes somewhere.
    assert within_budget(choices, places, per_core=5) == [here, local, far]


@pytest.mark.parametrize(
    ("cpu_max", "most"),
    [
        ("max 100000\n", None),  # no quota: the affinity
        ("150000 100000\n", 2),  # a container's --cpus 1.5: two cores' worth of turns
        ("50000 100000\n", 1),  # half a core
        ("100000 100000\n", 1),
        ("800000 100000\n", None),  # a quota above the affinity does not add cores
        ("garbled\n", None),
        ("0 100000\n", None),
    ],
)
def test_the_usable_cores_are_the_affinitys_or_fewer_under_a_cgroup_quota(
    tmp_path: Path, cpu_max: str, most: int | None
) -> None:
    affinity = len(os.sched_getaffinity(0))
    quota = tmp_path / "cpu.max"
    quota.write_text(cpu_max)
    assert usable_cores(quota) == (affinity if most is None else min(affinity, most))
    assert usable_cores(tmp_path / "absent") == affinity  # a machine without cgroup v2's file
