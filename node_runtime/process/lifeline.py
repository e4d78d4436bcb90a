"""The server's lifeline to its sandboxed node processes: a pipe whose write end only the server
holds. A node in the sandbox gets the read end (``LIFELINE_ENV`` names its descriptor) and ends
itself when the read returns end-of-file, which happens when the server has ended, however it
ended (a crash or SIGKILL included).

A sandboxed node cannot rely on the kernel's parent-death signal: it is pid 1 of its own pid
namespace, a child of bubblewrap, and bubblewrap, which runs without the capability to signal
another uid, dies without its request reaching the node; nor can it watch the server's pid,
which its namespace does not show.
"""

from __future__ import annotations

import os
import threading

LIFELINE_ENV = "ROS2LAB_LIFELINE_FD"

_read_end: int | None = None
_made = threading.Lock()


def read_end() -> int:
    """The descriptor to pass to a sandboxed node (made on first use; the write end stays here,
    not inheritable, so no other process keeps the line open)."""
    global _read_end
    with _made:
        if _read_end is None:
            _read_end, _write_end = os.pipe()  # both non-inheritable: pass_fds passes the read end
        return _read_end


def hold_on(fd: int) -> None:
    """In the node: a daemon thread that ends this process once the server's end is closed."""

    def wait() -> None:
        try:
            while os.read(fd, 1):
                pass
        except OSError:
            pass
        os._exit(1)  # the server is gone: nothing may outlive it

    threading.Thread(target=wait, name="lifeline", daemon=True).start()


def hold_on_from_env() -> None:
    """``hold_on`` the descriptor ``LIFELINE_ENV`` names, if it names one."""
    value = os.environ.get(LIFELINE_ENV)
    if value is not None and value.isdigit():
        hold_on(int(value))
