"""One program run on ROS 2's own rclpy (the oracle: Kilted's wheels on Fast DDS, in the venv
scripts/_oracle.sh makes) and on the lab's (a student's node: ``python -m node_runtime.process.runner
FILE`` on a Zenoh router of its own), and what each printed, compared.

What a user sees is compared: everything the program prints and logs, in order (stdout and stderr
in one pipe, both unbuffered), and its exit code. What legitimately differs is normalised first: a
log line's time stamp, and a traceback's frames (the files and lines of each rclpy's own code,
and the lab's runner beneath a student's file): the traceback's first and last lines stay, the
exception's type and message. A line ``measured LABEL: NUMBER UNIT`` is a rate or a time the program
measured: the two runs' numbers must agree within TIMING_TOLERANCE instead of exactly.

``python tests/differential/harness.py PROGRAM...`` runs programs on both and prints the
differences (a router of its own on a free loopback port), for writing a new program.
"""

from __future__ import annotations

import difflib
import json
import os
import queue
import re
import subprocess
import sys
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
PROGRAMS = HERE / "programs"
PENDING = HERE / "pending"
# What the oracle imports beside ROS 2's wheels (oracle_path/README.md).
ORACLE_PATH = HERE / "oracle_path"
RUN_BOUND_S = 40.0  # a program ends by itself within seconds; this only bounds a broken one
TIMING_TOLERANCE = 0.2  # relative, on a loaded 2-core machine
# Each program in flight runs in a ROS domain of its own, from this range. Fast DDS binds ports
# 7400 + 250 * domain and a few after: up to domain 49 that stays below 20000, where the other
# tests' free ports start (tests/support/app.py).
DOMAINS = range(10, 50)

_STAMP = re.compile(r"^\[(DEBUG|INFO|WARN|ERROR|FATAL)\] \[\d+(?:\.\d+)?\] ", re.MULTILINE)
_MEASURED = re.compile(r"^measured (?P<label>[^:]+): (?P<value>-?\d+(?:\.\d+)?) (?P<unit>\S+)$")
# The environment either side reads to find its graph: set anew for every run.
_GRAPH_VARIABLES = ("ROS_", "RMW_", "ZENOH_", "ROS2LAB_", "RCUTILS_", "FASTDDS_", "AMENT_")


class MissingOracle(RuntimeError):
    """The oracle's venv is not there (or its install did not finish)."""


def oracle_python(venv: Path) -> Path:
    """The oracle's interpreter in ``venv``/oracle, which scripts/_oracle.sh makes."""
    oracle = venv / "oracle"
    python = oracle / "bin" / "python"
    if not python.is_file() or not (oracle / ".installed").is_file():
        raise MissingOracle(
            f"ROS 2's own rclpy, the differential suite's reference, is not installed in {oracle}: "
            "run scripts/test.sh (it installs it once per machine) before tests/differential"
        )
    return python


@dataclass(frozen=True)
class Run:
    """What one side printed (stdout and stderr as one stream) and its exit code (None: it was
    killed after RUN_BOUND_S)."""

    output: str
    code: int | None


def _base_env() -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(_GRAPH_VARIABLES)}
    env.pop("PYTHONPATH", None)
    env["PYTHONUNBUFFERED"] = "1"
    return env


def oracle_env(domain: int) -> dict[str, str]:
    """Fast DDS on loopback only, in ``domain``."""
    env = _base_env()
    env.update(
        ROS_DOMAIN_ID=str(domain),
        RMW_IMPLEMENTATION="rmw_fastrtps_cpp",
        ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST",
        PYTHONPATH=str(ORACLE_PATH),
    )
    return env


def lab_env(domain: int, router: str) -> dict[str, str]:
    """A student's node of the lab whose Zenoh router listens at ``router`` (tcp/HOST:PORT)."""
    env = _base_env()
    env.update(
        ROS_DOMAIN_ID=str(domain),
        ZENOH_CONFIG_OVERRIDE=f"connect/endpoints={json.dumps([router])}",
        ZENOH_ROUTER_CHECK_ATTEMPTS="10",
    )
    return env


def run(command: list[str], env: Mapping[str, str], bound_s: float = RUN_BOUND_S) -> Run:
    """``command`` to its end, or killed (by its own id) after ``bound_s``."""
    proc = subprocess.Popen(
        command,
        env=dict(env),
        cwd=HERE,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    try:
        output, _ = proc.communicate(timeout=bound_s)
        return Run(output, proc.returncode)
    except subprocess.TimeoutExpired:
        proc.kill()
        output, _ = proc.communicate()
        return Run(output + f"\n(killed: it did not end within {bound_s:.0f} s)\n", None)


def run_oracle(python: Path, program: Path, domain: int) -> Run:
    return run([str(python), str(program)], oracle_env(domain))


def run_lab(program: Path, domain: int, router: str) -> Run:
    return run([sys.executable, "-m", "node_runtime.process.runner", str(program)], lab_env(domain, router))


def _without_frames(lines: list[str]) -> list[str]:
    """Each traceback's frames (its indented lines) as one ``  ...`` line."""
    kept: list[str] = []
    in_traceback = False
    for line in lines:
        if line.startswith("Traceback (most recent call last):"):
            in_traceback = True
            kept.append(line)
        elif in_traceback and line.startswith(" "):
            if kept[-1] != "  ...":
                kept.append("  ...")
        else:
            in_traceback = False
            kept.append(line)
    return kept


def _without_destructor_noise(lines: list[str]) -> list[str]:
    """Less each exception a destructor raised that the interpreter printed and ignored (``Exception
    ignored in: <function Executor.__del__ ...>``, its traceback and its exception): when the
    garbage collector finds an object in a cycle is a matter of timing, and ROS 2's rclpy prints one
    now and then for an executor collected after ``rclpy.shutdown()``."""
    kept: list[str] = []
    skipping = False
    for line in lines:
        if line.startswith("Exception ignored in: <function ") and ".__del__ at " in line:
            skipping = True
        elif skipping and (line == "Traceback (most recent call last):" or line == "  ..."):
            pass
        elif skipping:
            skipping = False  # the exception's own line ends the block
        else:
            kept.append(line)
    return kept


def normalise(result: Run) -> list[str]:
    """The lines a user sees, less what legitimately differs, with the exit code last."""
    text = _STAMP.sub(r"[\1] [<stamp>] ", result.output)
    lines = _without_destructor_noise(_without_frames([line.rstrip() for line in text.splitlines()]))
    while lines and not lines[-1]:
        lines.pop()
    code = "killed" if result.code is None else str(result.code)
    return [*lines, f"(exit code {code})"]


def _timing_apart(lines: list[str]) -> tuple[list[str], list[tuple[str, float, str]]]:
    """The lines with each measured number taken out, and the numbers."""
    kept: list[str] = []
    numbers: list[tuple[str, float, str]] = []
    for line in lines:
        match = _MEASURED.match(line)
        if match:
            numbers.append((match["label"], float(match["value"]), match["unit"]))
            kept.append(f"measured {match['label']}: <number> {match['unit']}")
        else:
            kept.append(line)
    return kept, numbers


def compare(oracle: Run, ours: Run, tolerance: float = TIMING_TOLERANCE) -> str | None:
    """None when the lab's rclpy printed what ROS 2's did; else a readable account of how not."""
    want, want_numbers = _timing_apart(normalise(oracle))
    got, got_numbers = _timing_apart(normalise(ours))
    problems: list[str] = []
    if want != got:
        diff = difflib.unified_diff(want, got, "ROS 2's rclpy", "the lab's rclpy", lineterm="", n=3)
        problems.append("\n".join(diff))
    for (label, expected, unit), (_, value, _) in zip(want_numbers, got_numbers, strict=False):
        if abs(value - expected) > tolerance * abs(expected) + 1e-9:
            problems.append(
                f"measured {label}: {value} {unit} on the lab's rclpy, {expected} {unit} on ROS 2's "
                f"(more than {tolerance:.0%} apart)"
            )
    return "\n".join(problems) if problems else None


def worker_share(worker: str | None, workers: int) -> tuple[int, int]:
    """This pytest-xdist worker's index and the number of workers (``PYTEST_XDIST_WORKER`` "gw3"
    and ``PYTEST_XDIST_WORKER_COUNT``); (0, 1) without xdist."""
    if not worker or not worker.startswith("gw") or not worker[2:].isdigit():
        return 0, 1
    return int(worker[2:]), max(1, workers)


def worker_domains(index: int, workers: int, domains: range = DOMAINS) -> range:
    """The DOMAINS of worker ``index`` of ``workers``: a slice of its own, so two workers never run
    programs in one domain (two programs' nodes of one name would meet: an action client would
    hear another program's server). More workers than domains share them round."""
    size = max(1, len(domains) // workers)
    start = domains.start + (index * size) % (len(domains) - size + 1)
    return range(start, start + size)


class Domains:
    """DOMAINS handed out to the programs in flight, each back when its program ended."""

    def __init__(self, domains: range = DOMAINS) -> None:
        self._free: queue.SimpleQueue[int] = queue.SimpleQueue()
        for domain in domains:
            self._free.put(domain)

    @contextmanager
    def one(self) -> Iterator[int]:
        domain = self._free.get(timeout=RUN_BOUND_S * 2)
        try:
            yield domain
        finally:
            self._free.put(domain)


@contextmanager
def zenoh_router(port: int) -> Iterator[str]:
    """A Zenoh router on 127.0.0.1:``port``, multicast scouting off, in this process."""
    import zenoh

    endpoint = f"tcp/127.0.0.1:{port}"
    config = zenoh.Config()
    config.insert_json5("mode", '"router"')
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("listen/endpoints", json.dumps([endpoint]))
    session: Any = zenoh.open(config)
    try:
        yield endpoint
    finally:
        session.close()


def main(argv: list[str]) -> int:
    import socket

    if not argv:
        print("usage: python tests/differential/harness.py PROGRAM...", file=sys.stderr)
        return 2
    try:
        python = oracle_python(Path(sys.prefix))
    except MissingOracle as exc:
        print(exc, file=sys.stderr)
        return 2
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        port = int(sock.getsockname()[1])
    status = 0
    with zenoh_router(port) as router:
        for index, name in enumerate(argv):
            program = Path(name).resolve()
            domain = DOMAINS[index % len(DOMAINS)]
            oracle, ours = run_oracle(python, program, domain), run_lab(program, domain, router)
            problem = compare(oracle, ours)
            print(f"== {program.name}: {'the same' if problem is None else 'different'}")
            print("\n".join(normalise(oracle)) if problem is None else problem)
            if problem is not None:
                status = 1
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
