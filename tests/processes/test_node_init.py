"""The sandbox's pid 1 (node_runtime/process/node_init.py), run here as a plain process: it forwards
Ctrl-C to the node it split off, ends with the node's exit code as a shell reports it, and ends
at once when the server's end of the lifeline closes, whatever the node does. Each process is
ended by its id."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
from collections.abc import Iterator

import pytest
from support.app import REPO

from node_runtime.process.lifeline import LIFELINE_ENV

NODE = """
import os, sys, time
from node_runtime.process import node_init
node_init.split()
if sys.argv[1] == 'stubborn':  # its handlers before it says it is there
    import signal
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGUSR1, lambda *_: print('still here', flush=True))
    null = os.open('/dev/null', os.O_RDONLY)
    for fd in range(3, 32):  # what a node may do to its own descriptors reaches no lifeline
        if fd != null:
            try:
                os.dup2(null, fd)
            except OSError:
                pass
print('node', os.getpid(), flush=True)
if sys.argv[1] == 'exit7':
    sys.exit(7)
time.sleep(60)
"""


@pytest.fixture
def lifeline() -> Iterator[tuple[int, int]]:
    read_end, write_end = os.pipe()
    try:
        yield read_end, write_end
    finally:
        for fd in (read_end, write_end):
            with contextlib.suppress(OSError):
                os.close(fd)


def start(kind: str, read_end: int) -> tuple[subprocess.Popen[str], int]:
    proc = subprocess.Popen(
        [sys.executable, "-c", NODE, kind],
        cwd=REPO,
        stdout=subprocess.PIPE,
        text=True,
        env={**os.environ, LIFELINE_ENV: str(read_end)},
        pass_fds=[read_end],
    )
    assert proc.stdout is not None
    node = int(proc.stdout.readline().split()[1])
    assert node != proc.pid  # the node is pid 1's child, not pid 1
    return proc, node


def end(proc: subprocess.Popen[str], node: int) -> None:
    for pid in (node, proc.pid):
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGKILL)
    proc.communicate(timeout=10)


def test_node_init_forwards_ctrl_c_and_ends_with_the_nodes_code(lifeline: tuple[int, int]) -> None:
    proc, node = start("sleep", lifeline[0])
    try:
        proc.send_signal(signal.SIGINT)  # to pid 1, as the server's Stop sends it
        assert proc.wait(timeout=10) == 128 + signal.SIGINT  # the node died of it; pid 1 says so
    finally:
        end(proc, node)


def test_node_init_ends_with_the_nodes_own_exit_code(lifeline: tuple[int, int]) -> None:
    proc, node = start("exit7", lifeline[0])
    try:
        assert proc.wait(timeout=10) == 7
    finally:
        end(proc, node)


def test_node_init_ends_when_the_lifeline_closes_whatever_the_node_does(lifeline: tuple[int, int]) -> None:
    proc, node = start("stubborn", lifeline[0])
    try:
        proc.send_signal(signal.SIGINT)  # the stubborn node ignores Ctrl-C: pid 1 stays with it
        proc.send_signal(signal.SIGUSR1)  # forwarded after it: the node's answer is the marker
        assert proc.stdout is not None and proc.stdout.readline().strip() == "still here"
        assert proc.poll() is None
        os.close(lifeline[1])  # the server has ended
        assert proc.wait(timeout=10) == 1
    finally:
        end(proc, node)
