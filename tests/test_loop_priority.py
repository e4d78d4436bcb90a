"""server/base/loop_priority.py: the worlds' loop thread takes the real-time class where the machine
allows it, passes it to nothing it starts, gives it back after, and says why when it cannot.

Each test runs the loop's part in a thread or a process of its own, so the test's own thread keeps
its class whatever happens."""

from __future__ import annotations

import os
import subprocess
import sys
import threading
from collections.abc import Callable
from typing import TypeVar

import pytest
from support.app import REPO

from server.base.loop_priority import NOT_PERMITTED, LoopPriority, loop_priority, scheduling_of

T = TypeVar("T")
NOBODY = 65534
SCHEDULING_OF_A_CHILD = "import os; print(os.sched_getscheduler(0))"


def on_a_thread(work: Callable[[], T]) -> T:
    """``work``'s result, run on a new thread (re-raising what it raised)."""
    result: list[T] = []
    failed: list[BaseException] = []

    def run() -> None:
        try:
            result.append(work())
        except BaseException as exc:  # handed back to the test
            failed.append(exc)

    thread = threading.Thread(target=run)
    thread.start()
    thread.join(timeout=60)
    assert not thread.is_alive(), "the thread did not end"
    if failed:
        raise failed[0]
    return result[0]


def require_root() -> None:
    if os.geteuid() != 0:
        pytest.skip("the real-time class needs root or an RLIMIT_RTPRIO here; the suite runs as root")


def test_the_loop_thread_takes_the_real_time_class_and_passes_it_to_no_thread_or_process() -> None:
    require_root()

    def loop() -> dict[str, object]:
        seen: dict[str, object] = {"before": scheduling_of(0)}
        with loop_priority("realtime") as priority:
            seen["priority"] = priority
            seen["during"] = scheduling_of(0)
            seen["its thread"] = on_a_thread(lambda: scheduling_of(0))
            child = subprocess.run(
                [sys.executable, "-c", SCHEDULING_OF_A_CHILD], capture_output=True, text=True, timeout=60
            )
            seen["its process"] = int(child.stdout)
            seen["another thread sees it"] = scheduling_of(threading.get_native_id())
        seen["after"] = scheduling_of(0)
        return seen

    seen = on_a_thread(loop)
    priority = seen["priority"]
    assert isinstance(priority, LoopPriority) and priority.scheduling == "realtime", priority
    assert seen["before"] == "normal" and seen["during"] == "realtime"
    assert seen["another thread sees it"] == "realtime"  # what the class load reads, by the loop's id
    assert seen["its thread"] == "normal"
    assert seen["its process"] == os.SCHED_OTHER
    assert seen["after"] == "normal"
    assert scheduling_of(0) == "normal"  # the test's own thread never changed


def test_normal_leaves_the_thread_as_it_is() -> None:
    def loop() -> tuple[LoopPriority, str | None]:
        with loop_priority("normal") as priority:
            return priority, scheduling_of(0)

    priority, during = on_a_thread(loop)
    assert priority.scheduling == "normal" and "--loop-priority normal" in priority.line()
    assert during == "normal"


# Imports what it needs as root, then (with "nobody") becomes an ordinary user: no capability left
# and no real-time priority allowed by its limit.
LOOP_AS = f"""
import os, resource, sys
sys.path.insert(0, {str(REPO)!r})
from server.base.loop_priority import loop_priority, scheduling_of
if sys.argv[1] == "nobody":
    resource.setrlimit(resource.RLIMIT_RTPRIO, (0, 0))  # whatever this machine's was
    os.setgroups([])
    os.setresgid({NOBODY}, {NOBODY}, {NOBODY})
    os.setresuid({NOBODY}, {NOBODY}, {NOBODY})
with loop_priority("realtime") as priority:
    print(priority.scheduling, scheduling_of(0), priority.why, sep="|")
"""


@pytest.mark.parametrize("who", ["nobody", "root"])
def test_a_loop_that_may_not_stays_normal_and_says_why(who: str) -> None:
    """An ordinary user (no CAP_SYS_NICE, an RLIMIT_RTPRIO of 0) stays in the fair class
    and the line says what it would need; the same process as root takes the real-time class."""
    require_root()
    done = subprocess.run([sys.executable, "-c", LOOP_AS, who], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    taken, during, why = done.stdout.strip().split("|")
    if who == "nobody":
        assert (taken, during, why) == ("normal", "normal", NOT_PERMITTED)
    else:
        assert (taken, during) == ("realtime", "realtime"), why


def test_a_thread_id_the_kernel_does_not_know_has_no_scheduling() -> None:
    assert scheduling_of(-1) is None
    assert scheduling_of(threading.get_native_id()) == "normal"
