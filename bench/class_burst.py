"""Bench: a class told "run it now", measured from outside.

    .venv/bin/python bench/class_burst.py [--worlds 30] [--per-world 2] [--joined-timeout-s 300]
        [--steady-s 30] [--via cli|page] [--starts all-at-once|paced [--starts-over-s 60]]
        [--probers 10] [--cli-nice N] [--page-clients [--clients-nice N]]
        [--loop-priority realtime|normal]

A class server (``--classroom --launch fly``, its Zenoh router on a free loopback port) with
``--worlds`` students joined, one world each, one after the other (``joins``: how many were
admitted, how long the joins took, and at which student the class held a join in its queue for
a minute, saying it was full; then no more join, and the class is measured with those it
admitted). Then ``--worlds`` × ``--per-world`` ``ros2lab run``
of the handout's keyboard manager (examples/workspace, rocketship), each with its student's token
and a node name of its own, all started in the same instant (one barrier releases a thread per
start), as a class told "run it now" does; ``--starts paced`` spreads them evenly over
``--starts-over-s`` instead. They are started in one session of their own, apart from the class
server's (bench/laptops.py), whose scheduling group runs at ``--cli-nice`` (10: they stand for
commands on the students' laptops, which take the cores only as far as the class leaves them
free, rather than in terminals on the class server). Until 2026-11-30 each ran at that niceness
in the bench's session, the class server's, where sixty at nice 10 outweighed it. What is
measured:

* the time from the first start until every node is in its own world's ``GET /api/nodes``
  (each world polled in turn, every 0.5 s);
* how long the class server took to answer a student's ordinary calls meanwhile (``answers``):
  ``--probers`` students (an even sample) each call, one after the other 0.5 s apart as a page
  polls, ``GET /api/nodes`` (``nodes``), ``GET /api/topics`` (``topics``), ``GET
  /api/workspace/files`` (``workspace_tree``) and the keyboard manager's file
  (``workspace_file``), from a second before the starts until every node is listed; with ``--via
  page`` the starts' own ``POST /api/run`` too (``run``). Per kind: the slowest answer, the p99,
  the median, how many calls, how many took over a second, and errors (a call unanswered in 30 s
  counts as one, at 30 s); and the slowest calls with whose they were and when
  (``slowest_answers``);
* every world's dynamics timer rate over that time (``flightgoggles_uav_dynamics``' timer calls,
  read with the world's token before the starts and once all are joined): median and lowest, and
  the same split by where the worlds run (``by_place``: "server", the class server's own loop, or
  a world worker's id, from the instructor's list of worlds), and each place's loop thread: its
  share of a core and how long it waited for one while it could run (``loop_threads``,
  ``waited_ms_per_s``, from the kernel's schedstat: what the machine's other loads cost the
  worlds' ticks, apart from what the loop itself did), and in the steady window below the
  scheduling class each loop thread ran in (``loop_scheduling``: "realtime" or "normal", as
  ``--loop-priority``, passed to the class server, and the machine allow);
* the class server's CPU (cores) over that time, the share of the machine's CPU time the
  hypervisor stole, and the load average;
* then, one second later, each node process's RSS (the ``runner`` children of the ``ros2lab run``
  processes): median, max and sum;
* then, with every node running, ``--steady-s`` seconds of the class as it then is: every world's
  dynamics rate, the class server's CPU and that of every node process (with its sandbox), and at
  its end the class's memory (RSS of the class server, its world workers, the nodes, and all of
  them with their sandboxes: ``steady.rss_mib``).

``--page-clients`` opens a page-like client per student (bench/page_client.py: viser's scene and
GUI stream, the HUD's pose stream, the key channel's heartbeat) once they have joined, held open
through the starts and the steady window, and adds each channel's median rate over the steady
window (``steady.page_hz``): the class as it is with every page open. The clients run in a
process of the bench's own, on the same cores as the class, where a class's pages would run on
the students' machines; ``--clients-nice 10`` runs that process below the class's processes, so
they take the cores only when the class leaves them free (and apart from the bench's timing
threads, which a paused client would otherwise hold up).

The keyboard manager is saved into each student's workspace through the workspace API before the
starts (the file the probers read). ``--via page`` starts the nodes as the page's Run does
instead of ``ros2lab run``: ``POST /api/run`` with the student's token, so the class server starts
each node process (in its sandbox, where bubblewrap is installed) at the turn its start pacer
gives it.

Every child is ended by its own id (Ctrl-C to each ``ros2lab run``, which passes it on). Prints
the machine (bench/machine.py) and one JSON object, also written to bench/results/class_burst.json.
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import json
import os
import shutil
import signal
import statistics
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

import httpx
from laptops import LaptopProcess, Laptops
from live_server import READER, LiveServer, class_join, cpu_s, rss_mib
from machine import machine_info, save_results
from page_client import OpenPages, median_rates

from server.base.loop_priority import SCHEDULINGS, scheduling_of
from server.host.settings import Settings, default_of

CODE = "BURST1"
DYNAMICS = "flightgoggles_uav_dynamics"
WORKSPACE = REPO / "examples" / "workspace"
ROS2LAB = str(Path(sys.executable).parent / "ros2lab")
POLL_S = 0.5
JOIN_WAIT_S = 60.0  # a join the class queues at its capacity: held this long, the class is full
MANAGER = "src/rocketship/src/keyboard_manager.py"
PROBE_GAP_S = 0.5  # a prober's pause between calls: about a page's polls (tools 1 s, editor 1.5 s)
PROBE_TIMEOUT_S = 30.0  # a call unanswered so long counts as answered then (and as an error)
ANSWER_AIM_S = 1.0


def cpu_jiffies() -> tuple[int, int]:
    """(steal, total) jiffies of every CPU so far (/proc/stat's first line)."""
    values = [int(v) for v in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:9]]
    return values[7], sum(values)


def get(server: LiveServer, token: str, path: str) -> Any:
    reply = READER.get(server.url + path, headers={"Authorization": f"Bearer {token}"})
    reply.raise_for_status()
    return reply.json()


def dynamics_lateness_p99_ms(server: LiveServer, token: str) -> float:
    """The p99 of how late the world's dynamics timer ran over its last ticks (the node's own record)."""
    timers = get(server, token, f"/api/nodes/{DYNAMICS}")["timers"]
    return float(timers[0]["lateness_p99_ms"] or 0.0)


def dynamics_calls(server: LiveServer, token: str) -> tuple[int, float]:
    timers = get(server, token, f"/api/nodes/{DYNAMICS}")["timers"]
    return int(timers[0]["calls"]), time.monotonic()


def places(server: LiveServer) -> dict[str, str]:
    """Where each world runs: "server" (the class server's own loop) or its world worker's id, from
    the instructor's list of worlds (the instructor's link is in the class server's log)."""
    listed = get(server, server.instructor_token(), "/api/classroom/worlds")["worlds"]
    return {w["world"]: w["worker"] or "server" for w in listed}


def by_place(
    rates: dict[str, float], where: dict[str, str], late: dict[str, float] | None = None
) -> dict[str, dict[str, Any]]:
    """The dynamics rates (and with ``late``, the tick lateness p99s) of the worlds, split by where
    they run: which loop kept its time, and which did not."""
    split: dict[str, dict[str, Any]] = {}
    for place in sorted(set(where.values())):
        mine = [w for w in rates if where.get(w) == place]
        if not mine:
            continue
        row: dict[str, Any] = {"worlds": len(mine), "dynamics_hz": summary_of([rates[w] for w in mine], 1)}
        if late is not None:
            row["tick_lateness_p99_ms"] = summary_of([late[w] for w in mine], 2, high=True)
        split[place] = row
    return split


def summary_of(values: list[float], digits: int, high: bool = False) -> dict[str, float]:
    """Median and the worst (lowest, or with ``high`` largest) of ``values``."""
    worst = max(values) if high else min(values)
    return {
        "median": round(statistics.median(values), digits),
        ("largest" if high else "lowest"): round(worst, digits),
    }


def is_runner(pid: int) -> bool:
    """Whether ``pid`` is a node process (the lab's runner, whatever started it)."""
    try:  # bubblewrap's own process carries the same command line: not a node
        proc = Path(f"/proc/{pid}")
        return (proc / "comm").read_text().strip() != "bwrap" and b"node_runtime.process.runner" in (
            proc / "cmdline"
        ).read_bytes()
    except FileNotFoundError:
        return False


def is_worker(pid: int) -> bool:
    """Whether ``pid`` is a world worker the class server started (``--workers``)."""
    try:
        return b"world-worker" in Path(f"/proc/{pid}/cmdline").read_bytes()
    except FileNotFoundError:
        return False


def loop_threads(server: LiveServer) -> dict[str, int]:
    """The processes whose main thread runs worlds: the class server's and each world worker's,
    by place name ("server", or the worker's ``--id``)."""
    found = {"server": server.proc.pid}
    for pid in descendants(server.proc.pid):
        if is_worker(pid):
            argv = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
            found[argv[argv.index(b"--id") + 1].decode()] = pid
    return found


def schedstat(pid: int) -> tuple[float, float] | None:
    """(seconds run, seconds waited for a core while runnable) of ``pid``'s main thread so far."""
    try:
        run_ns, wait_ns, _ = Path(f"/proc/{pid}/task/{pid}/schedstat").read_text().split()
    except (FileNotFoundError, ProcessLookupError):
        return None
    return int(run_ns) / 1e9, int(wait_ns) / 1e9


def loop_waits(
    before: dict[str, tuple[float, float] | None],
    after: dict[str, tuple[float, float] | None],
    window_s: float,
) -> dict[str, dict[str, float]]:
    """Each loop thread's share of a core over the window and how long it waited for one while it
    could run (ms a second): what the machine's other loads cost a world's ticks, apart from what
    its own loop did."""
    waits: dict[str, dict[str, float]] = {}
    for place, start in before.items():
        end = after.get(place)
        if start is None or end is None:
            continue
        waits[place] = {
            "run_cores": round((end[0] - start[0]) / window_s, 2),
            "waited_ms_per_s": round(1000 * (end[1] - start[1]) / window_s, 1),
        }
    return waits


def children(pid: int) -> list[int]:
    try:
        return [int(p) for p in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    except FileNotFoundError:
        return []


def start(laptops: Laptops, server: LiveServer, token: str, node: str, env: dict[str, str]) -> LaptopProcess:
    """``ros2lab run`` of the handout's keyboard manager as ``node``, in the world of ``token``,
    started by ``laptops`` (in their session, at its niceness)."""
    argv = [
        ROS2LAB,
        "--url",
        server.url,
        "run",
        "--workspace",
        str(WORKSPACE),
        "rocketship",
        "keyboard_manager.py",
        "--ros-args",
        "-r",
        f"__node:={node}",
    ]
    return laptops.start(argv, {**env, "ROS2LAB_TOKEN": token})


def join(server: LiveServer, name: str) -> tuple[str, str] | None:
    """(world, token) of a new student; a join queued at the class's capacity (202) is polled for
    ``JOIN_WAIT_S``, and None if the class still held it in its queue then (it said it was full)."""
    reply = class_join(server.url, name, CODE, JOIN_WAIT_S, timeout_s=180)
    if reply.status_code == 202:
        return None
    if reply.status_code != 201:
        raise RuntimeError(f"{name}'s join answered {reply.status_code}: {reply.text}")
    return reply.json()["world"], reply.json()["token"]


def join_class(server: LiveServer, students: int) -> tuple[dict[str, str], dict[str, Any]]:
    """The students' worlds and tokens, joined one after the other until all are in or the class
    holds one in its queue past ``JOIN_WAIT_S`` (the class is full: no more join; the held one
    leaves the queue once nobody polls it). With how the joins went."""
    tokens: dict[str, str] = {}
    said_full: int | None = None
    started = time.monotonic()
    for i in range(students):
        joined = join(server, f"student{i:02d}")
        if joined is None:
            said_full = i + 1
            break
        tokens[joined[0]] = joined[1]
    took_s = round(time.monotonic() - started, 1)
    return tokens, {"admitted": len(tokens), "said_full_at_student": said_full, "joins_s": took_s}


def save_manager(server: LiveServer, token: str) -> None:
    """The handout's keyboard manager in the student's workspace, as the page's editor saves it."""
    reply = READER.put(
        f"{server.url}/api/workspace/files/{MANAGER}",
        headers={"Authorization": f"Bearer {token}"},
        json={"text": (WORKSPACE / MANAGER).read_text()},
    )
    if reply.status_code not in (200, 201):
        raise RuntimeError(f"saving the keyboard manager: {reply.status_code} {reply.text}")


class Answers:
    """How long the class server took to answer each kind of call, from any thread."""

    SLOWEST = 8  # the slowest calls kept with who made them and when

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._seconds: dict[str, list[float]] = {}
        self._errors: dict[str, list[str]] = {}
        self._slowest: list[tuple[float, str, str, float]] = []  # seconds, kind, who, when (monotonic)
        self.started = time.monotonic()  # ``when`` is given from here: the starts' instant

    def record(
        self, kind: str, seconds: float, error: str | None = None, who: str = "", at: float = 0.0
    ) -> None:
        with self._lock:
            self._seconds.setdefault(kind, []).append(seconds)
            if error is not None:
                self._errors.setdefault(kind, []).append(error)
            self._slowest.append((seconds, kind, who, at))
            self._slowest.sort(reverse=True)
            del self._slowest[self.SLOWEST :]

    def timed(
        self, kind: str, call: Callable[[], httpx.Response], ok: tuple[int, ...] = (200,), who: str = ""
    ) -> httpx.Response | None:
        """``call``'s answer, recorded under ``kind`` (None, and recorded as its timeout, if none came)."""
        at, t0 = time.monotonic(), time.perf_counter()
        try:
            reply = call()
        except httpx.HTTPError as exc:
            self.record(kind, time.perf_counter() - t0, f"{type(exc).__name__}: {exc}"[:200], who, at)
            return None
        error = None if reply.status_code in ok else f"{reply.status_code}: {reply.text[:160]}"
        self.record(kind, time.perf_counter() - t0, error, who, at)
        return reply

    def slowest(self) -> list[dict[str, Any]]:
        """The slowest calls: how long, which kind, whose, and when (s after the starts)."""
        with self._lock:
            return [
                {"s": round(s, 3), "kind": kind, "student": who, "at_s": round(at - self.started, 1)}
                for s, kind, who, at in self._slowest
            ]

    def summary(self) -> dict[str, dict[str, Any]]:
        """Per kind: the slowest answer, the p99 (nearest rank), the median, how many calls, how
        many took over ``ANSWER_AIM_S`` and the first few errors."""
        with self._lock:
            out: dict[str, dict[str, Any]] = {}
            for kind, seconds in sorted(self._seconds.items()):
                ordered = sorted(seconds)
                errors = self._errors.get(kind, [])
                out[kind] = {
                    "max_s": round(ordered[-1], 3),
                    "p99_s": round(ordered[max(0, -(-len(ordered) * 99 // 100) - 1)], 3),
                    "median_s": round(statistics.median(ordered), 3),
                    "calls": len(ordered),
                    "over_aim": sum(1 for s in ordered if s > ANSWER_AIM_S),
                    "errors": len(errors),
                    "first_errors": errors[:3],
                }
            return out


class Prober:
    """One student's page while the class starts, on a thread of its own: the ordinary calls in
    turn (the node list, the topic list, the workspace's tree and a file in it), ``PROBE_GAP_S``
    apart, each timed into ``answers``, until ``stop``."""

    CALLS = (
        ("nodes", "/api/nodes"),
        ("topics", "/api/topics"),
        ("workspace_tree", "/api/workspace/files"),
        ("workspace_file", f"/api/workspace/files/{MANAGER}"),
    )

    def __init__(self, url: str, token: str, answers: Answers, stop: threading.Event, who: str = "") -> None:
        self.client = httpx.Client(
            base_url=url, headers={"Authorization": f"Bearer {token}"}, timeout=PROBE_TIMEOUT_S
        )
        self.answers, self.stop, self.who = answers, stop, who
        self.thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        while not self.stop.is_set():
            for kind, path in self.CALLS:
                self.answers.timed(kind, lambda path=path: self.client.get(path), who=self.who)
                if self.stop.wait(PROBE_GAP_S):
                    break
        self.client.close()


def start_in_page(server: LiveServer, token: str, node: str, answers: Answers) -> None:
    """The page's Run of the student's keyboard manager as ``node``, timed as ``run``."""
    answers.timed(
        "run",
        lambda: READER.post(
            f"{server.url}/api/run",
            headers={"Authorization": f"Bearer {token}"},
            json={"package": "rocketship", "executable": "keyboard_manager.py", "name": node},
        ),
        ok=(201,),
        who=node,
    )


def at_times(starts: list[Callable[[], Any]], offsets: list[float]) -> list[threading.Thread]:
    """Each of ``starts`` on a thread of its own, at its offset in seconds from the moment every
    thread is ready (one barrier releases them: with every offset 0, the whole class presses Run
    in the same instant)."""
    released: list[float] = []
    barrier = threading.Barrier(len(starts), action=lambda: released.append(time.monotonic()))

    def go(call: Callable[[], Any], offset: float) -> None:
        barrier.wait()
        delay = released[0] + offset - time.monotonic()
        if delay > 0:
            time.sleep(delay)
        call()

    threads = [
        threading.Thread(target=go, args=(c, o), daemon=True) for c, o in zip(starts, offsets, strict=True)
    ]
    for thread in threads:
        thread.start()
    return threads


def start_offsets(count: int, starts: str, over_s: float) -> list[float]:
    """When each of ``count`` starts goes, in seconds from the first: all at once, or ``paced``
    evenly over ``over_s``."""
    if starts == "all-at-once" or count < 2:
        return [0.0] * count
    return [i * over_s / (count - 1) for i in range(count)]


def descendants(pid: int) -> list[int]:
    """Every process below ``pid``."""
    found, todo = [], [pid]
    while todo:
        kids = children(todo.pop())
        found += kids
        todo += kids
    return found


def tree_cpu_s(pids: list[int]) -> dict[int, float]:
    out = {}
    for pid in pids:
        with contextlib.suppress(FileNotFoundError, ProcessLookupError):
            out[pid] = cpu_s(pid)
    return out


def steady(
    server: LiveServer,
    tokens: dict[str, str],
    roots: list[int],
    seconds: float,
    pages: OpenPages | None,
    where: dict[str, str],
) -> dict[str, Any]:
    """The class with every node running, over ``seconds``: each world's dynamics rate and tick
    lateness (also split by where the worlds run), the class server's CPU, the node processes' and
    the world workers' (of the processes below ``roots`` alive throughout); with ``pages``, what
    each page's channels carried a second."""
    nodes = [p for root in {*roots, server.proc.pid} for p in descendants(root)]  # the workers too
    steal0, total0 = cpu_jiffies()
    cpu0, nodes0 = cpu_s(server.proc.pid), tree_cpu_s(nodes)
    before = {w: dynamics_calls(server, t) for w, t in tokens.items()}
    loops = loop_threads(server)
    sched0 = {place: schedstat(pid) for place, pid in loops.items()}
    if pages is not None:
        pages.mark()
    own0 = time.process_time()  # this bench's own CPU, and its page clients': on the same cores
    pages0 = cpu_s(pages.pid) if pages is not None else 0.0
    time.sleep(seconds)
    own1 = time.process_time()
    pages1 = cpu_s(pages.pid) if pages is not None else 0.0
    page_rates, page_errors = pages.rates() if pages is not None else ([], [])
    after = {w: dynamics_calls(server, t) for w, t in tokens.items()}
    cpu1, nodes1 = cpu_s(server.proc.pid), tree_cpu_s(nodes)
    sched1 = {place: schedstat(pid) for place, pid in loops.items()}
    steal1, total1 = cpu_jiffies()
    late_of = {w: dynamics_lateness_p99_ms(server, t) for w, t in tokens.items()}
    late = sorted(late_of.values())
    window_s = max(t for _, t in after.values()) - min(t for _, t in before.values())
    rate_of = {w: (after[w][0] - before[w][0]) / (after[w][1] - before[w][1]) for w in tokens}
    rates = sorted(rate_of.values())
    used = {p: nodes1[p] - nodes0[p] for p in nodes1 if p in nodes0}
    node_s = sum(t for p, t in used.items() if is_runner(p))
    workers_s = sum(t for p, t in used.items() if is_worker(p))
    return {
        "window_s": round(window_s, 1),
        "dynamics_hz": summary_of(rates, 1),
        "tick_lateness_p99_ms": summary_of(late, 2, high=True),
        "by_place": by_place(rate_of, where, late_of),
        "loop_threads": loop_waits(sched0, sched1, window_s),
        "loop_scheduling": {place: scheduling_of(pid) for place, pid in loops.items()},
        "server_cpu_cores": round((cpu1 - cpu0) / window_s, 2),
        "node_processes": sum(1 for p in nodes1 if is_runner(p)),
        "node_processes_cpu_cores": round(node_s / window_s, 2),
        "world_workers_cpu_cores": round(workers_s / window_s, 2),
        "stolen": round((steal1 - steal0) / max(1, total1 - total0), 4),
        "bench_cpu_cores": round((own1 - own0) / window_s, 2),
        "page_clients_cpu_cores": round((pages1 - pages0) / window_s, 2),
        "page_hz": median_rates(page_rates) if pages is not None else None,
        "page_errors": page_errors[:5],
        "rss_mib": class_rss_mib(server, nodes),
    }


def class_rss_mib(server: LiveServer, below: list[int]) -> dict[str, float]:
    """The class's memory at the end of the window: the class server's RSS, its world workers',
    the node processes', and all of them with every other process below them (the sandboxes), a
    sum of RSS (pages two processes share count twice: an upper bound)."""
    alive: dict[int, float] = {}
    for pid in below:
        with contextlib.suppress(FileNotFoundError, ProcessLookupError, RuntimeError):
            alive[pid] = rss_mib(pid)
    own = server.rss_mib()
    return {
        "class_server": round(own, 1),
        "world_workers": round(sum(m for p, m in alive.items() if is_worker(p)), 1),
        "node_processes": round(sum(m for p, m in alive.items() if is_runner(p)), 1),
        "all": round(own + sum(alive.values()), 1),
    }


def burst(
    server: LiveServer,
    tokens: dict[str, str],
    per_world: int,
    timeout_s: float,
    via: str,
    steady_s: float,
    pages: OpenPages | None = None,
    starts: str = "all-at-once",
    starts_over_s: float = 60.0,
    probers: int = 10,
    cli_nice: int = 0,
) -> dict[str, Any]:
    wanted = {w: {f"/{w}_node{i}" for i in range(per_world)} for w in tokens}
    for token in tokens.values():  # the Run's file, and the file the probers read
        save_manager(server, token)
    answers, probing = Answers(), threading.Event()
    step = max(1, len(tokens) // max(1, probers)) if probers > 0 else 0
    probed = list(tokens.items())[::step][:probers] if probers > 0 else []
    probes = [Prober(server.url, t, answers, probing, who=w) for w, t in probed]
    for probe in probes:
        probe.thread.start()
    time.sleep(1.0)  # each prober's first calls answered before the starts
    where = places(server)
    loops = loop_threads(server)
    sched0 = {place: schedstat(pid) for place, pid in loops.items()}
    steal0, total0 = cpu_jiffies()
    cpu0 = cpu_s(server.proc.pid)
    before = {w: dynamics_calls(server, t) for w, t in tokens.items()}
    env = {k: v for k, v in os.environ.items() if k not in ("ROS_DOMAIN_ID", "ROS2LAB_WORKSPACE")}
    laptops = Laptops(cli_nice) if via == "cli" else None
    runs: list[LaptopProcess] = []
    calls: list[Callable[[], Any]] = []
    for w, names in wanted.items():
        for name in sorted(names):
            node = name.lstrip("/")
            if via == "page":
                calls.append(functools.partial(start_in_page, server, tokens[w], node, answers))
            else:
                assert laptops is not None
                calls.append(
                    functools.partial(
                        lambda t, n: runs.append(start(laptops, server, t, n, env)), tokens[w], node
                    )
                )
    t0 = answers.started = time.monotonic()
    starters = at_times(calls, start_offsets(len(calls), starts, starts_over_s))
    try:
        pending = dict(wanted)
        joined_at: list[float] = []
        unanswered = 0
        refused: dict[int, int] = {}  # the node lists answered with an error, by status
        while pending and time.monotonic() - t0 < timeout_s:
            for w in list(pending):
                try:
                    listed = {n["name"] for n in get(server, tokens[w], "/api/nodes")}
                except httpx.TimeoutException:  # a starved server: not yet, and counted
                    unanswered += 1
                    continue
                except httpx.HTTPStatusError as exc:  # a world worker that did not answer in time: 502
                    refused[exc.response.status_code] = refused.get(exc.response.status_code, 0) + 1
                    continue
                if pending[w] <= listed:
                    del pending[w]
                    joined_at.append(time.monotonic() - t0)
            time.sleep(POLL_S)
        all_joined_s = time.monotonic() - t0 if not pending else None
        probing.set()
        for thread in starters:
            thread.join(timeout=PROBE_TIMEOUT_S)
        for probe in probes:
            probe.thread.join(timeout=PROBE_TIMEOUT_S)
        after = {w: dynamics_calls(server, t) for w, t in tokens.items()}
        cpu1 = cpu_s(server.proc.pid)
        sched1 = {place: schedstat(pid) for place, pid in loops.items()}
        steal1, total1 = cpu_jiffies()
        window_s = max(t for _, t in after.values()) - min(t for _, t in before.values())
        time.sleep(1.0)
        roots = [run.pid for run in runs] if runs else [server.proc.pid]
        node_rss = [rss_mib(p) for root in roots for p in descendants(root) if is_runner(p)]
        exited = sum(1 for run in runs if run.poll() is not None)
        running = (
            steady(server, tokens, roots, steady_s, pages, where) if steady_s > 0 and not pending else None
        )
    finally:
        probing.set()
        for thread in starters:
            thread.join(timeout=PROBE_TIMEOUT_S)
        for run in runs:  # Ctrl-C to every one first: they stop together, not one after another
            run.send_signal(signal.SIGINT)
        for run in list(runs):
            run.end()
        if laptops is not None:
            laptops.close()
    rate_of = {w: (after[w][0] - before[w][0]) / (after[w][1] - before[w][1]) for w in tokens}
    rates = sorted(rate_of.values())
    rss_summary: dict[str, float] | None = None
    if node_rss:
        rss_summary = {
            "median": round(statistics.median(node_rss), 1),
            "max": round(max(node_rss), 1),
            "sum": round(sum(node_rss), 1),
            "count": len(node_rss),
        }
    return {
        "nodes": sum(len(names) for names in wanted.values()),
        "via": via,
        "starts": starts,
        "answers": answers.summary(),
        "slowest_answers": answers.slowest(),
        "probed_students": len(probes),
        "all_joined_s": round(all_joined_s, 1) if all_joined_s is not None else None,
        "not_joined_worlds": sorted(pending),
        "node_lists_unanswered_in_60_s": unanswered,
        "node_lists_refused": {str(code): n for code, n in sorted(refused.items())},
        "ros2lab_exited_early": exited,
        "worlds_joined_s": {"median": round(statistics.median(joined_at), 1)} if joined_at else None,
        "dynamics_hz": summary_of(rates, 1),
        "by_place": by_place(rate_of, where),
        "loop_threads": loop_waits(sched0, sched1, window_s),
        "server_cpu_cores": round((cpu1 - cpu0) / window_s, 2),
        "stolen": round((steal1 - steal0) / max(1, total1 - total0), 4),
        "load_average_after": list(os.getloadavg()),
        "node_rss_mib": rss_summary,
        "steady": running,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--worlds", type=int, default=30)
    parser.add_argument("--per-world", type=int, default=2)
    parser.add_argument("--joined-timeout-s", type=float, default=300.0)
    parser.add_argument(
        "--workers",
        default="auto",
        help="world workers on this machine: the server's --workers (N, auto or 0)",
    )
    parser.add_argument(
        "--local-worlds", type=int, default=0, help="with --workers N: worlds the class server hosts"
    )
    parser.add_argument(
        "--steady-s", type=float, default=30.0, help="the class measured with every node running"
    )
    parser.add_argument(
        "--via", choices=["cli", "page"], default="cli", help="ros2lab run, or the page's Run"
    )
    parser.add_argument(
        "--page-clients", action="store_true", help="a page-like client per student, open throughout"
    )
    parser.add_argument(
        "--clients-nice",
        type=int,
        default=0,
        help="added to the page clients' thread's niceness: they stand for pages on the students' machines",
    )
    parser.add_argument(
        "--starts",
        choices=["all-at-once", "paced"],
        default="all-at-once",
        help="every start in the same instant (a class told 'run it now'), or spread evenly over --starts-over-s",
    )
    parser.add_argument("--starts-over-s", type=float, default=60.0, help="with --starts paced")
    parser.add_argument(
        "--cli-nice",
        type=int,
        default=0,
        help="with --via cli: the niceness of the session the ros2lab runs start in, all of them in one "
        "(10: they stand for the students' laptops, not terminals on the class server; bench/laptops.py)",
    )
    parser.add_argument(
        "--loop-priority",
        choices=SCHEDULINGS,
        default=default_of(Settings, "loop_priority"),
        help="the class server's --loop-priority (its world workers take the same): its worlds' loop "
        "threads in the real-time class, or in the fair class with the rest",
    )
    parser.add_argument(
        "--probers",
        type=int,
        default=10,
        help="students (an even sample) whose ordinary calls are timed while the class starts",
    )
    args = parser.parse_args(argv)
    print(json.dumps(machine_info()), flush=True)
    root = Path(tempfile.mkdtemp(prefix="class_burst_"))
    spread = ["--workers", args.workers]
    if args.workers not in ("auto", "0"):
        spread += ["--local-worlds", str(args.local_worlds)]
    server = LiveServer(
        root, "fly", "--classroom", "--class-code", CODE, "--max-worlds", str(args.worlds), *spread,
        "--loop-priority", args.loop_priority,
    )  # fmt: skip
    pages: OpenPages | None = None
    try:
        tokens, joins = join_class(server, args.worlds)
        if joins["said_full_at_student"] is not None:
            time.sleep(35.0)  # the held join leaves the queue unpolled before the class is measured
        if args.page_clients:
            pages = OpenPages(server.url, list(tokens.values()), args.clients_nice)
            pages.open()
        time.sleep(3.0)  # every world flying (and every page open) before the starts
        results = {
            "args": vars(args),
            "joins": joins,
            **burst(
                server,
                tokens,
                args.per_world,
                args.joined_timeout_s,
                args.via,
                args.steady_s,
                pages,
                starts=args.starts,
                starts_over_s=args.starts_over_s,
                probers=args.probers,
                cli_nice=args.cli_nice,
            ),
        }
    finally:
        if pages is not None:
            pages.close()
        server.stop()
        shutil.rmtree(root, ignore_errors=True)
    print(json.dumps(results, indent=1))
    save_results("class_burst", results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
