"""Every program in programs/ prints the same on the lab's rclpy as on ROS 2's own (harness.py).

The programs of the tests a run collects start together when the first of them asks (a few at a
time, each on both sides at once, each in a ROS domain of its own), so the file takes about as long
as its slowest programs rather than their sum; a program whose name ends in ``_timing`` measures a
rate and runs alone, under the timing mark."""

from __future__ import annotations

import os
import threading
from concurrent.futures import Future, ThreadPoolExecutor
from pathlib import Path

import pytest

from .harness import PROGRAMS, Domains, Run, compare, run_lab, run_oracle, worker_domains, worker_share

ALL = sorted(PROGRAMS.glob("*.py"))
if not ALL:  # an empty parametrisation would skip, and the suite must not pass by running nothing
    raise RuntimeError(f"no programs in {PROGRAMS}")
# The programs that end in an exception on purpose, and the exit code Python gives them.
EXITS_WITH = {"callback_exception": 1}
AT_ONCE = 3  # programs in flight together (each two processes); the machine has two cores


def timed(program: Path) -> bool:
    return program.stem.endswith("_timing")


def case(program: Path) -> object:
    return pytest.param(program, id=program.stem, marks=[pytest.mark.timing] if timed(program) else [])


WORKER, WORKERS = worker_share(
    os.environ.get("PYTEST_XDIST_WORKER"), int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1"))
)
DOMAINS = Domains(worker_domains(WORKER, WORKERS))


def both(oracle: Path, router: str, program: Path) -> tuple[Run, Run]:
    with DOMAINS.one() as domain, ThreadPoolExecutor(2) as pool:
        theirs = pool.submit(run_oracle, oracle, program, domain)
        ours = pool.submit(run_lab, program, domain, router)
        return theirs.result(), ours.result()


class Batch:
    """The collected programs' runs, started together on first use; a program not among them
    runs when its test asks for it.

    Under pytest-xdist every worker collects every test but runs a share of them that the
    scheduler picks as it goes: a worker starts ahead only its likely share (every WORKERS-th
    program), so the programs are not all run once per worker."""

    def __init__(self, oracle: Path, router: str, programs: list[Path]) -> None:
        self.oracle, self.router, self.programs = oracle, router, programs
        self.lock = threading.Lock()
        self.pool: ThreadPoolExecutor | None = None
        self.runs: dict[Path, Future[tuple[Run, Run]]] = {}

    def result(self, program: Path) -> tuple[Run, Run]:
        with self.lock:
            if self.pool is None:
                self.pool = ThreadPoolExecutor(AT_ONCE)
                for each in self.programs:
                    self.runs[each] = self.pool.submit(both, self.oracle, self.router, each)
            started = self.runs.get(program)
        return both(self.oracle, self.router, program) if started is None else started.result()

    def close(self) -> None:
        if self.pool is not None:
            self.pool.shutdown(wait=True)


@pytest.fixture(scope="module")
def batch(request: pytest.FixtureRequest, oracle: Path, router: str) -> object:
    collected = [
        item.callspec.params["program"]
        for item in request.session.items
        if item.path == Path(__file__)
        and hasattr(item, "callspec")
        and not timed(item.callspec.params["program"])
    ]
    runs = Batch(oracle, router, collected[WORKER::WORKERS])
    request.addfinalizer(runs.close)
    return runs


@pytest.mark.parametrize("program", [case(p) for p in ALL])
def test_program_prints_what_ros2_rclpy_prints(
    program: Path, request: pytest.FixtureRequest, oracle: Path, router: str
) -> None:
    if timed(program):
        with DOMAINS.one() as domain:
            theirs = run_oracle(oracle, program, domain)
            ours = run_lab(program, domain, router)  # after it, not beside it: each measures a rate
    else:
        theirs, ours = request.getfixturevalue("batch").result(program)
    expected = EXITS_WITH.get(program.stem, 0)  # a program's own bug shows on ROS 2's rclpy first
    assert theirs.code == expected, (
        f"{program.name} ended with {theirs.code} on ROS 2's own rclpy:\n{theirs.output}"
    )
    problem = compare(theirs, ours)
    assert problem is None, f"{program.name}: the lab's rclpy differs from ROS 2's\n{problem}"
