"""A test starter's children (tests/support/forked_server.py and forked_cli.py): the starter wakes
when one ends, reaps it with its exit code, and ends every one still running when its pytest
process has gone. Only the starter's own children are reaped, so a pid it still holds can never
be another process's."""

from __future__ import annotations

import contextlib
import os
import signal
from collections.abc import Collection, Iterable, Iterator


def wake_on_child_exit() -> tuple[int, int]:
    """Ctrl-C left to the children themselves; a child's end (SIGCHLD) writes to a pipe the
    starter's selector watches. The pipe's two ends, read end first."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    wake_r, wake_w = os.pipe()
    os.set_blocking(wake_r, False)
    os.set_blocking(wake_w, False)
    signal.set_wakeup_fd(wake_w)
    signal.signal(signal.SIGCHLD, lambda *_: None)
    return wake_r, wake_w


def drain(wake_r: int) -> None:
    """Empty the wake-up pipe (its bytes only say that a signal came)."""
    with contextlib.suppress(BlockingIOError):
        while os.read(wake_r, 512):
            pass


def reaped(running: Collection[int]) -> Iterator[tuple[int, int]]:
    """Each child that has ended, with its exit code, while ``running`` (which the caller updates)
    holds any; stops when none has ended."""
    while running:
        try:
            pid, status = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            return
        yield pid, os.waitstatus_to_exitcode(status)


def end_all(pids: Iterable[int]) -> None:
    """Kill these children and wait for each (the pytest process has gone)."""
    pids = list(pids)
    for pid in pids:
        os.kill(pid, signal.SIGKILL)
    for pid in pids:
        os.waitpid(pid, 0)
