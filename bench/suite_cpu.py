"""Where the suite's time goes: a pytest plugin that writes each test file's wall time and CPU.

CPU is the test process's own plus that of every process under it (servers, node processes,
Chromium): children it reaped (``RUSAGE_CHILDREN``) and, read from ``/proc``, the live ones with
what they reaped themselves. A file whose CPU is far below its wall time is waiting (real-time
flights, countdowns, process starts); the suite's CPU over the cores is the floor of its wall time.

Run pytest with it, as scripts/check runs a part (each xdist worker appends its own lines)::

    SUITE_CPU_OUT=cpu.jsonl PYTHONPATH=bench .venv/bin/python -m pytest -p suite_cpu -n 2 --dist loadfile ...
    .venv/bin/python bench/suite_cpu.py cpu.jsonl   # the table, the slowest files first

Linux only (``/proc``).
"""

from __future__ import annotations

import json
import os
import resource
import sys
import time
from pathlib import Path
from typing import Any

import pytest

TICK_S = 1.0 / os.sysconf("SC_CLK_TCK")


def _stat(pid: int) -> tuple[int, float] | None:
    """(parent pid, CPU seconds of the process and the children it reaped) from /proc."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = text[text.rindex(")") + 2 :].split()
    # After the name: state ppid ...; utime stime cutime cstime are fields 14-17 (1-based).
    ticks = sum(int(f) for f in fields[11:15])
    return int(fields[1]), ticks * TICK_S


def _live_descendants_cpu() -> dict[int, float]:
    """CPU seconds of each live process under this one (not this one itself)."""
    parents: dict[int, int] = {}
    cpu: dict[int, float] = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit() and (found := _stat(int(entry))) is not None:
            parents[int(entry)], cpu[int(entry)] = found
    me = os.getpid()
    under: dict[int, float] = {}
    for pid in cpu:
        up, seen = parents.get(pid), 0
        while up is not None and up > 1 and seen < 64:
            if up == me:
                under[pid] = cpu[pid]
                break
            up, seen = parents.get(up), seen + 1
    return under


def _own_cpu() -> float:
    me = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime


class _Mark:
    def __init__(self) -> None:
        self.wall = time.monotonic()
        self.own = _own_cpu()
        self.live = _live_descendants_cpu()

    def cpu_since(self, start: _Mark) -> float:
        live = sum(cpu - start.live.get(pid, 0.0) for pid, cpu in self.live.items())
        return self.own - start.own + live


class SuiteCpu:
    def __init__(self, out: Path) -> None:
        self.out = out
        self.file: str | None = None
        self.tests = 0
        self.start = _Mark()

    def _write(self, what: str, tests: int) -> None:
        end = _Mark()
        record: dict[str, Any] = {
            "file": what,
            "tests": tests,
            "wall_s": round(end.wall - self.start.wall, 2),
            "cpu_s": round(end.cpu_since(self.start), 2),
            "worker": os.environ.get("PYTEST_XDIST_WORKER", "main"),
        }
        with self.out.open("a") as f:
            f.write(json.dumps(record) + "\n")
        self.start = end

    def pytest_collection_finish(self) -> None:
        self._write("(collection)", 0)

    def pytest_runtest_logstart(self, nodeid: str) -> None:
        file = nodeid.split("::", 1)[0]
        if file != self.file:
            if self.file is not None:
                self._write(self.file, self.tests)
            self.file, self.tests = file, 0
        self.tests += 1

    def pytest_sessionfinish(self) -> None:
        if self.file is not None:
            self._write(self.file, self.tests)
            self.file = None


def pytest_configure(config: pytest.Config) -> None:
    out = os.environ.get("SUITE_CPU_OUT")
    # Under pytest-xdist the controller hears every worker's tests; only the workers record.
    controller = not os.environ.get("PYTEST_XDIST_WORKER") and config.getoption("numprocesses", None)
    if out and not controller:
        config.pluginmanager.register(SuiteCpu(Path(out)), "suite_cpu_recorder")


def main() -> None:
    """Print the records of the files given, summed per test file, the slowest first."""
    rows: dict[str, list[float]] = {}
    for name in sys.argv[1:]:
        for line in Path(name).read_text().splitlines():
            r = json.loads(line)
            row = rows.setdefault(r["file"], [0, 0.0, 0.0])
            row[0] += r["tests"]
            row[1] += r["wall_s"]
            row[2] += r["cpu_s"]
    print(f"{'file':70} {'tests':>5} {'wall s':>8} {'cpu s':>8} {'cpu/wall':>8}")
    for file, (tests, wall, cpu) in sorted(rows.items(), key=lambda kv: -kv[1][1]):
        print(f"{file:70} {tests:5.0f} {wall:8.1f} {cpu:8.1f} {cpu / max(wall, 0.01):8.2f}")
    wall = sum(r[1] for r in rows.values())
    cpu = sum(r[2] for r in rows.values())
    print(f"{'total':70} {sum(r[0] for r in rows.values()):5.0f} {wall:8.1f} {cpu:8.1f}")


if __name__ == "__main__":
    main()
