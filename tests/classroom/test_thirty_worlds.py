"""A class of 30 with no browser: 30 worlds of the fly launch run for 30 s of wall time, and every
world's dynamics keeps its nominal 100 Hz (at most one tick in 20 skipped, see KEEPS, on the CPU
time the machine was given).

The worlds run as a class would on a machine of two cores: the class server hosts half itself
(``--local-worlds 15``) and places the other half on a world worker (``--max-worlds 15``), so the
load ties and the placement alternates. Each world's rate is its dynamics node's timer calls over
the window, read through the class server's API with that student's token (a worker's world is answered by its
worker), each count with the time it was read. Both processes are ended by their ids.

The readings go through the tests' one kept client (support/http.py): read with a new client each
(``httpx.get``), the 30 readings at each end of the window took the worlds' cores for seconds and
cost every world 2 to 4 Hz of the rate measured (quiet machine: slowest world 96 Hz read that way,
99 Hz through the kept client).
"""

from __future__ import annotations

import json
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from support.app import REPO, App, WorldWorker, instructor_token, wait_for_workers
from support.http import HTTP

pytestmark = pytest.mark.timing  # its rates are the point: measured with nothing else running

CODE = "CLS030"
WORLDS = 30
WINDOW_S = 30.0
NOMINAL_HZ = 100.0  # flightgoggles_uav_dynamics' publish_rate_hz in the fly launch
# Of the nominal rate: at most 1 tick in 20 may come so late (a whole period) that the timer skips
# it, as rcl's does; the physics itself follows the clock and loses no time. Slowest world, on a
# 2-vCPU AMD EPYC: 99.7 to 99.9 Hz on a quiet machine; 98.2 beside a process that keeps a core
# busy; 96.5 in one whole-suite run on a day the hypervisor's steal reached 28 %. Beside two such
# processes 89 to 95 Hz, and with both processes held to one core 92 to 95 Hz: those fail or nearly.
# The hypervisor's steal (CPU time the machine's vCPUs were owed but not given) is taken off that
# floor in proportion: in CI runs a burst of steal of about 8 % over a window has held every world,
# ours and everyone's, near 94 Hz, with no change in the code.
KEEPS = 0.95
DYNAMICS = "flightgoggles_uav_dynamics"
RESULT = REPO / "artifacts" / "thirty_worlds.json"
ADMIT_WAIT_S = 120.0  # a join the class queued, polled until it is admitted


def admitted(url: str, reply: httpx.Response) -> httpx.Response:
    """The join's answer once the class admits it. While worlds start one after another the class
    server can judge itself full for a moment (its loop saturated and a quarter of its worlds late,
    capacity.py) and queue a join (202 with a ticket), as it would a student's; the page polls the
    ticket, and so does this, until the join is admitted or ADMIT_WAIT_S has passed."""
    deadline = time.monotonic() + ADMIT_WAIT_S
    while reply.status_code == 202 and time.monotonic() < deadline:
        time.sleep(float(reply.json()["poll_s"]))
        reply = HTTP.get(f"{url}/api/classroom/join/{reply.json()['ticket']}", timeout=60)
    return reply


@pytest.fixture(scope="module")
def class_of_thirty(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[App, dict[str, str]]]:
    root: Path = tmp_path_factory.mktemp("thirty_worlds")
    app = App(
        root,
        "--classroom",
        "--class-code",
        CODE,
        "--launch",
        "fly",
        "--max-worlds",
        str(WORLDS),
        "--local-worlds",
        str(WORLDS // 2),
        "--workers",
        "0",
    )  # (its own worker w1 below, none started as the class grows)
    worker: WorldWorker | None = None
    try:
        instructor = instructor_token(app.log_tail(100_000))
        worker = WorldWorker(root, app.router, instructor, "w1", "--max-worlds", str(WORLDS // 2))
        wait_for_workers(app.url, instructor, {"w1"})
        tokens: dict[str, str] = {}
        for i in range(WORLDS):
            reply = HTTP.post(
                f"{app.url}/api/classroom/join", json={"name": f"student{i:02d}", "code": CODE}, timeout=60
            )
            reply = admitted(app.url, reply)
            assert reply.status_code == 201, reply.text
            tokens[reply.json()["world"]] = reply.json()["token"]
        yield app, tokens
    finally:
        if worker is not None:
            worker.stop()
        app.stop()


def cpu_jiffies() -> tuple[int, int]:
    """(steal, total) time of every CPU so far, in jiffies, from /proc/stat's first line."""
    user, nice, system, idle, iowait, irq, softirq, steal = (
        int(v) for v in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:9]
    )
    return steal, user + nice + system + idle + iowait + irq + softirq + steal


def dynamics_calls(app: App, token: str) -> tuple[int, float]:
    """How often the world's dynamics timer has run, and when that was read (monotonic s)."""
    reply = HTTP.get(
        f"{app.url}/api/nodes/{DYNAMICS}", headers={"Authorization": f"Bearer {token}"}, timeout=10
    )
    assert reply.status_code == 200, reply.text
    timers: list[dict[str, Any]] = reply.json()["timers"]
    assert len(timers) == 1 and timers[0]["period_s"] == pytest.approx(1 / NOMINAL_HZ)
    return int(timers[0]["calls"]), time.monotonic()


def test_thirty_worlds_each_keep_their_dynamics_rate_for_thirty_seconds(
    class_of_thirty: tuple[App, dict[str, str]],
) -> None:
    app, tokens = class_of_thirty
    instructor = instructor_token(app.log_tail(100_000))
    listed = HTTP.get(
        f"{app.url}/api/classroom/worlds", headers={"Authorization": f"Bearer {instructor}"}, timeout=30
    ).json()["worlds"]
    placed = {w["world"]: w["worker"] for w in listed}
    assert sorted(placed) == sorted(tokens)
    on_worker = sum(1 for where in placed.values() if where == "w1")
    assert on_worker == WORLDS // 2, placed  # half the class on the worker, half on the class server

    # Every world flies already: its dynamics have run (the first reading is the window's start).
    steal0, total0 = cpu_jiffies()
    start = {world: dynamics_calls(app, token) for world, token in tokens.items()}
    assert all(calls > 0 for calls, _ in start.values()), start
    time.sleep(WINDOW_S)
    end = {world: dynamics_calls(app, token) for world, token in tokens.items()}
    steal1, total1 = cpu_jiffies()
    stolen = (steal1 - steal0) / max(1, total1 - total0)  # the share of the machine's CPU time
    floor = KEEPS * NOMINAL_HZ * (1.0 - stolen)

    rates = {world: (end[world][0] - start[world][0]) / (end[world][1] - start[world][1]) for world in tokens}
    # The rates measured, for a CI log's reader (git-ignored, beside the browser tests' screenshots).
    RESULT.parent.mkdir(parents=True, exist_ok=True)
    RESULT.write_text(
        json.dumps(
            {
                "window_s": WINDOW_S,
                "stolen": round(stolen, 4),
                "floor_hz": round(floor, 2),
                "hz": {w: round(hz, 2) for w, hz in sorted(rates.items())},
            }
        )
    )
    slow = {world: round(hz, 1) for world, hz in rates.items() if hz < floor}
    assert not slow, (
        f"worlds below {floor:.1f} Hz ({KEEPS:.0%} of {NOMINAL_HZ:.0f} Hz, less the {stolen:.1%} of CPU time "
        f"the hypervisor stole): {slow}; all: {sorted(rates.values())}"
    )
    # A timer never runs more often than its period allows (a check on the reading itself).
    assert max(rates.values()) <= NOMINAL_HZ * 1.01, rates
