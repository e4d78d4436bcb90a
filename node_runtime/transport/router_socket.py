"""A Unix socket a Zenoh router also listens on, for node processes that have no network: the
sandboxed nodes of a server that serves others (server/host/processes/sandbox.py binds its folder in).

Its folder is made private to this router (a fresh ``mkdtemp``); the socket is opened to every
uid once the router listens, because a root server's sandboxed node runs as a uid of its own. The
router still asks every session for its login, as on TCP.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from pathlib import Path

SOCKET_NAME = "router.sock"


def socket_endpoint(path: Path | str) -> str:
    """The Zenoh locator of a Unix socket (``unixsock-stream/<path>``)."""
    return f"unixsock-stream/{path}"


def new_socket_path() -> Path:
    """Where a router's socket goes: a folder of its own (the sandbox binds the folder, so the
    socket made again when the router reopens is the one the sandbox sees)."""
    folder = Path(tempfile.mkdtemp(prefix="ros2lab-router-"))
    folder.chmod(0o711)  # other uids reach the socket by its name, and list nothing
    return folder / SOCKET_NAME


def open_to_nodes(path: Path) -> None:
    """Let a sandboxed node of another uid connect (connect needs write on the socket)."""
    with contextlib.suppress(FileNotFoundError):
        path.chmod(0o666)


def remove(path: Path) -> None:
    shutil.rmtree(path.parent, ignore_errors=True)
    with contextlib.suppress(OSError):
        os.rmdir(path.parent)
