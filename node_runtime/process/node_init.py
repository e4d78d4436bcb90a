"""Pid 1 of a sandboxed node's namespace: the lab's, never the student's.

The sandbox's first process is the runner (node_runtime/process/runner.py), which takes its limits on
and then splits: its child goes on to run the node; the first process stays pid 1 of the
namespace and does three things only. It holds the lifeline (node_runtime/process/lifeline.py) and
ends when the server's end closes; it forwards Ctrl-C and the other stop signals to the node; and
it ends with the node's exit code once the node has ended. When pid 1 ends, the kernel ends every
process left in its namespace (a daemon the node forked, a thread it left), so the whole sandbox
ends with the node, and with the server.

The node cannot reach that process: it runs in another process (closing or replacing its own
descriptors, its own signal handlers or ``prctl`` change nothing of pid 1's), the kernel ignores
SIGKILL and SIGSTOP sent to a namespace's pid 1 from inside, pid 1 is not dumpable (so a process of
the same uid cannot open its memory), and the seccomp filter refuses ``ptrace``.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import signal
import threading

from node_runtime.process import lifeline

FORWARDED = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT, signal.SIGUSR1, signal.SIGUSR2)
PR_SET_DUMPABLE = 4


def split() -> None:
    """Fork: return in the child, which runs the node; the parent stays pid 1 until the node has
    ended (or the server has) and never returns."""
    line = os.environ.pop(lifeline.LIFELINE_ENV, None)
    fd = int(line) if line is not None and line.isdigit() else None
    # Held until pid 1 forwards them: a Ctrl-C that comes as the node starts reaches the node.
    held = signal.pthread_sigmask(signal.SIG_BLOCK, FORWARDED)
    child = os.fork()
    if child == 0:
        signal.pthread_sigmask(signal.SIG_SETMASK, held)
        if fd is not None:
            with contextlib.suppress(OSError):
                os.close(fd)
        return
    os._exit(_stay(child, fd, held))


def _stay(child: int, fd: int | None, held: set[int | signal.Signals]) -> int:
    """Pid 1's life: the node's exit code, as a shell reports it (128 + a signal that ended it)."""
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(PR_SET_DUMPABLE, 0, 0, 0, 0)
    for sig in FORWARDED:
        signal.signal(sig, lambda number, _frame: _forward(child, number))
    if fd is not None:  # started while they are blocked, it keeps them blocked: they come to the
        # main thread, which runs Python's handlers (one delivered to this thread would wait there
        # until the main thread next woke, at the node's end)
        threading.Thread(target=_hold, args=(fd,), name="lifeline", daemon=True).start()
    signal.pthread_sigmask(signal.SIG_SETMASK, held)
    while True:
        try:
            pid, status = os.waitpid(-1, 0)  # orphans the node left are reaped too
        except ChildProcessError:
            return 0
        if pid == child:
            code = os.waitstatus_to_exitcode(status)
            return 128 - code if code < 0 else code


def _forward(child: int, number: int) -> None:
    with contextlib.suppress(ProcessLookupError):
        os.kill(child, number)


def _hold(fd: int) -> None:
    """End pid 1 (so the whole namespace) once the server's end of the lifeline is closed."""
    try:
        while os.read(fd, 1):
            pass
    except OSError:
        pass
    os._exit(1)
