"""A student's node that prints one endless line, with no newline, on a live class server that
sandboxes students' nodes: the server reads a node's output a chunk at a time and keeps a line cut
at MAX_LINE_CHARS (server/host/processes/output_lines.py), so while the line pours in its memory stays
where it was, another student's world on the same server keeps its dynamics rate, and the page
sees the cut line (marked so) as soon as its limit is reached, then the node's next line. The
control: an ordinary node's lines print whole.

Read whole, as before, a line of 1 GiB took the class server's peak from 122 MiB to 2.6 GiB and
stopped the other world's loop for more than 10 s (this test, unsandboxed). The class server hosts
both worlds itself (``--workers 0``); it runs as a process of its own on loopback and is ended by
its id.
"""

from __future__ import annotations

import json
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from support.app import REPO, App
from support.http import HTTP
from support.sandbox import require_sandbox
from support.wait import wait_until

from server.host.processes.output_lines import MAX_LINE_CHARS

pytestmark = pytest.mark.timing  # a world's rate across real seconds: measured with nothing else running

CODE = "FLD042"
CLASS_READY_S = 120.0  # a class server's start on a 2-core machine that runs other suites too
DYNAMICS = "flightgoggles_uav_dynamics"
NOMINAL_HZ = 100.0  # its publish_rate_hz in the fly launch
KEEPS = 0.95  # of the nominal rate, less the share of CPU time the hypervisor stole (as test_thirty_worlds)
# How long the node prints its line, and how much of it at most: the time ends it first (a sandboxed
# node wrote 1 GiB in 2.5 s here, too short a window to read a rate on).
FLOOD_S = 10.0
FLOOD_MIB = 16 * 1024
RSS_ROOM_MIB = 100  # the server's peak resident memory over its resident memory before the flood
MARK = f" … [cut: line longer than {MAX_LINE_CHARS} characters]"
RESULT = REPO / "artifacts" / "output_flood.json"

FLOOD = f"""
import sys
import time


def main():
    chunk = b"x" * (1 << 20)
    deadline = time.monotonic() + {FLOOD_S}
    written = 0
    while written < {FLOOD_MIB} and time.monotonic() < deadline:
        sys.stdout.buffer.write(chunk)
        written += 1
    sys.stdout.buffer.write(b"\\ndone " + str(written).encode() + b" MiB\\n")
    sys.stdout.buffer.flush()


if __name__ == "__main__":
    main()
"""
ORDINARY = """
def main():
    print("hello from an ordinary node")
    print("y" * 4096)
    print("héllo wörld € 😀 " * 200)
    print("the end")


if __name__ == "__main__":
    main()
"""


@dataclass
class Student:
    app: App
    token: str
    world: str

    def headers(self) -> dict[str, str]:
        return {"Authorization": f"Bearer {self.token}"}

    def get(self, path: str) -> Any:
        reply = HTTP.get(self.app.url + path, headers=self.headers(), timeout=10.0)
        assert reply.status_code == 200, reply.text
        return reply.json()

    def run(self, executable: str) -> str:
        """``POST /api/run`` of a node of the package ``flood``; its group id."""
        started = HTTP.post(
            self.app.url + "/api/run",
            headers=self.headers(),
            timeout=30.0,
            json={"package": "flood", "executable": executable},
        )
        assert started.status_code == 201, started.text
        return str(started.json()["id"])

    def lines(self, group: str) -> tuple[list[str], dict[str, Any]]:
        """What the run's process printed as the API gives it, and its node (state, exit code)."""
        reply = self.get(f"/api/launches/{group}/output")
        (node,) = reply["group"]["nodes"]
        return [line for process in reply["processes"] for line in process["lines"]], node

    def stop(self, group: str) -> None:
        HTTP.delete(f"{self.app.url}/api/launches/{group}", headers=self.headers(), timeout=30.0)


@dataclass
class Class:
    app: App
    ada: Student  # prints
    bob: Student  # flies


def join(app: App, name: str) -> Student:
    reply = HTTP.post(f"{app.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=30)
    assert reply.status_code == 201, reply.text
    return Student(app, reply.json()["token"], reply.json()["world"])


@pytest.fixture(scope="module")
def klass(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Class]:
    require_sandbox()
    root = tmp_path_factory.mktemp("flood")
    app = App(
        root,
        "--classroom",
        "--class-code",
        CODE,
        "--launch",
        "fly",
        "--workers",
        "0",
        "--no-foxglove",
        cwd=root,
        ready_s=CLASS_READY_S,
    )
    try:
        ada, bob = join(app, "Ada"), join(app, "Bob")
        package = root / "workspaces" / ada.world / "src" / "flood"
        package.mkdir(parents=True)
        (package / "flood.py").write_text(FLOOD.lstrip())
        (package / "ordinary.py").write_text(ORDINARY.lstrip())
        wait_until(lambda: dynamics_calls(bob)[0] > 0, "Bob's world to fly", 60.0, poll_s=0.2)
        yield Class(app, ada, bob)
    finally:
        app.stop()


def dynamics_calls(student: Student) -> tuple[int, float]:
    """How often the world's dynamics timer has run, and when that was read (monotonic s)."""
    timers: list[dict[str, Any]] = student.get(f"/api/nodes/{DYNAMICS}")["timers"]
    return int(timers[0]["calls"]), time.monotonic()


def memory_kib(pid: int) -> dict[str, int]:
    """The process's resident memory now (VmRSS) and at its peak (VmHWM), in KiB."""
    fields = dict(line.split(":", 1) for line in Path(f"/proc/{pid}/status").read_text().splitlines())
    return {name: int(fields[name].split()[0]) for name in ("VmRSS", "VmHWM")}


def cpu_jiffies() -> tuple[int, int]:
    """(steal, total) time of every CPU so far, in jiffies, from /proc/stat's first line."""
    values = [int(v) for v in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:9]]
    return values[7], sum(values)


def ended(student: Student, group: str) -> tuple[list[str], int | None] | None:
    """Its lines and exit code once the run's node has ended."""
    lines, node = student.lines(group)
    return None if node["state"] in ("waiting", "running") else (lines, node["exit_code"])


def done(student: Student, group: str) -> list[str] | None:
    lines = student.lines(group)[0]
    return lines if lines and lines[-1].startswith("done") else None


def test_output_flood_ordinary_nodes_lines_print_whole(klass: Class) -> None:
    group = klass.ada.run("ordinary.py")
    try:
        lines, code = wait_until(
            lambda: ended(klass.ada, group), "the ordinary node to end", 60.0, poll_s=0.2
        )
    finally:
        klass.ada.stop(group)
    assert lines == ["hello from an ordinary node", "y" * 4096, "héllo wörld € 😀 " * 200, "the end"]
    assert code == 0


def test_output_flood_endless_line_is_cut_and_neither_memory_nor_another_world_suffers(
    klass: Class,
) -> None:
    ada, bob, pid = klass.ada, klass.bob, klass.app.proc.pid
    before = memory_kib(pid)
    group = ada.run("flood.py")
    cut = "x" * MAX_LINE_CHARS + MARK
    try:
        # The cut line shows while the node still prints: the window of the rate starts there.
        wait_until(
            lambda: ada.lines(group)[0] == [cut], "the cut line while the node prints", 60.0, poll_s=0.1
        )
        steal0, total0 = cpu_jiffies()
        calls0, t0 = dynamics_calls(bob)
        lines = wait_until(
            lambda: done(ada, group), "the node's line after the flood", FLOOD_S + 30.0, poll_s=0.1
        )
        calls1, t1 = dynamics_calls(bob)
        steal1, total1 = cpu_jiffies()
        after = memory_kib(pid)
        _, code = wait_until(lambda: ended(ada, group), "the flood node to end", 30.0, poll_s=0.2)
    finally:
        ada.stop(group)
    rate_hz = (calls1 - calls0) / (t1 - t0)
    stolen = (steal1 - steal0) / max(1, total1 - total0)
    floor_hz = KEEPS * NOMINAL_HZ * (1.0 - stolen)
    grew_mib = (after["VmHWM"] - before["VmRSS"]) / 1024
    RESULT.parent.mkdir(parents=True, exist_ok=True)
    RESULT.write_text(
        json.dumps(
            {
                "flood": lines[-1],
                "window_s": round(t1 - t0, 1),
                "bob_hz": round(rate_hz, 1),
                "floor_hz": round(floor_hz, 1),
                "stolen": round(stolen, 4),
                "rss_before_mib": round(before["VmRSS"] / 1024, 1),
                "peak_after_mib": round(after["VmHWM"] / 1024, 1),
                "rss_after_mib": round(after["VmRSS"] / 1024, 1),
            }
        )
    )
    assert lines == [cut, lines[-1]] and lines[-1].endswith(" MiB") and code == 0, (lines, code)
    assert rate_hz >= floor_hz, f"Bob's world at {rate_hz:.1f} Hz during the flood (floor {floor_hz:.1f})"
    assert grew_mib <= RSS_ROOM_MIB, (
        f"the server's peak {grew_mib:.0f} MiB over its memory before: {before} {after}"
    )
    assert t1 - t0 >= 3.0, f"a window of {t1 - t0:.1f} s only: {lines[-1]}"  # long enough to read a rate on
