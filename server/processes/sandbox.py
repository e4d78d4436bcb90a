"""A student's node process on a server that serves others: run inside bubblewrap (``bwrap``).

The sandbox has its own PID, mount, IPC, UTS and network namespaces (and a user namespace when the
server is not root; as root, the node drops to a uid of its own as it starts: see
server/processes/confinement.py, which also sets its rlimits and nice). What it sees:

- its workspace, read-write, at the path the server knows it by (tracebacks name the same files);
- the system's ``/usr``, Python, the venv and the lab's client code (``server``, ``sim``,
  ``client``), read-only;
- a private ``/tmp``, a minimal ``/dev``, its own ``/proc``; nothing else of the server;
- no network but loopback of its own: its world's Zenoh router is a Unix socket bound in at
  ``/run/ros2lab``, and it logs in there with its world's login, so it reaches its world only.

Its environment is built afresh (no variable of the server's: no token, no path of the server).
"""

from __future__ import annotations

import functools
import os
import shutil
import subprocess
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from server.transport.router_socket import SOCKET_NAME, socket_endpoint

from .command import NodeCommand
from .confinement import LIMITS_ENV, Confinement
from .interface_modules import WORKSPACE_ENV

SOCKET_DIR = "/run/ros2lab"  # where the router's Unix socket's folder is bound inside
PROBE_TIMEOUT_S = 10.0
INSIDE_UID = 1000  # the node's uid inside its user namespace (not root)
PROJECT = Path(__file__).resolve().parents[2]
CLIENT_CODE = ("server", "sim", "client")  # the lab's code a node process imports
# Only what a node process needs; the server's own environment never reaches it.
KEPT_ENV = (
    "PYTHONUNBUFFERED",
    "PYTHONDONTWRITEBYTECODE",
    "ROS_DOMAIN_ID",
    "ZENOH_CONFIG_OVERRIDE",
    WORKSPACE_ENV,
)


INSIDE_ROUTER = socket_endpoint(f"{SOCKET_DIR}/{SOCKET_NAME}")


def _bwrap() -> str | None:
    return shutil.which("bwrap")


class StudentCodeRefusedError(RuntimeError):
    """This server serves others and cannot sandbox a student's node: it does not run it."""

    def __init__(self, why: str) -> None:
        super().__init__(
            f"students' nodes do not run on this server: {why} (the server's --student-code unsandboxed "
            "runs them without a sandbox)"
        )


@functools.cache
def probe() -> str | None:
    """Why no sandbox can be built here, in one line (None: it can). Checked once per process."""
    bwrap = _bwrap()
    if bwrap is None:
        return "no bubblewrap (bwrap) on this machine: install Debian's 'bubblewrap'"
    argv = [bwrap, *_namespaces(os.geteuid() == 0), "--ro-bind", "/", "/", "--proc", "/proc",
            "--dev", "/dev", "--", "true"]  # fmt: skip
    try:
        done = subprocess.run(argv, capture_output=True, text=True, timeout=PROBE_TIMEOUT_S, check=False)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return f"bubblewrap could not start: {exc}"
    if done.returncode != 0:
        why = (done.stderr.strip().splitlines() or [f"exit code {done.returncode}"])[-1]
        return f"bubblewrap cannot build a sandbox here ({why}): the kernel or container refuses namespaces"
    return None


def _namespaces(root: bool) -> list[str]:
    # As root, no user namespace: the node's processes must belong to a uid other than 0 outside too
    # (root's processes are not counted against RLIMIT_NPROC), so it drops to one itself.
    users = ["--cap-add", "CAP_SETUID", "--cap-add", "CAP_SETGID"] if root else ["--unshare-user"]
    return [
        *users,
        "--unshare-pid",
        "--unshare-net",
        "--unshare-ipc",
        "--unshare-uts",
        "--unshare-cgroup-try",
    ]


@dataclass(frozen=True)
class Sandbox:
    """How this server sandboxes a world's node processes: ``socket`` is the host path of the Unix
    socket its Zenoh router listens on."""

    socket: Path
    confinement: Confinement

    def wrap(self, command: NodeCommand, workspace: Path | None) -> NodeCommand:
        """``command`` (made with ``router=INSIDE_ROUTER``) run inside bwrap, with a clean environment."""
        bwrap = _bwrap()
        if bwrap is None:
            raise OSError("no bubblewrap (bwrap) on this machine")
        root = os.geteuid() == 0
        env = {key: command.env[key] for key in KEPT_ENV if key in command.env}
        env.update(PATH="/usr/bin:/bin", HOME="/tmp", TMPDIR="/tmp", LANG="C.UTF-8")
        # Under a root server each world's nodes run as a uid of that world's (processes are then
        # counted per world, not across the class, and no world's node can signal another's).
        confinement = self.confinement.for_domain(int(command.env.get("ROS_DOMAIN_ID", "0")))
        env[LIMITS_ENV] = confinement.encode(drop_root=root)
        ws = workspace.resolve() if workspace is not None else None
        if ws is not None and root:
            confinement.give(ws)
        argv = [bwrap, *_namespaces(root), "--die-with-parent", "--new-session", "--as-pid-1",
                "--hostname", "ros2lab-node", *([] if root else ["--uid", str(INSIDE_UID), "--gid", str(INSIDE_UID)]),
                *self._mounts(ws), "--", *command.argv]  # fmt: skip
        return NodeCommand(argv, env, command.zid, sandboxed=True)

    def _mounts(self, workspace: Path | None) -> list[str]:
        out = ["--ro-bind", "/usr", "/usr"]
        for link in ("bin", "lib", "lib64", "sbin"):  # Debian's merged /usr: these are links into it
            target = Path("/") / link
            if target.is_symlink():
                out += ["--symlink", os.readlink(target), str(target)]
            elif target.is_dir():
                out += ["--ro-bind", str(target), str(target)]
        # Zenoh's shared memory wants a /dev/shm the node may write: a private one. The private
        # /tmp comes before the binds, so Python or a project that lives below /tmp still shows.
        out += ["--proc", "/proc", "--dev", "/dev", "--perms", "1777", "--tmpfs", "/dev/shm",
                "--perms", "1777", "--tmpfs", "/tmp", "--dir", "/run"]  # fmt: skip
        for path in _python_dirs():
            out += [*_parents(path), "--ro-bind", str(path), str(path)]
        out += ["--ro-bind", str(self.socket.parent), SOCKET_DIR]
        if workspace is not None and workspace.is_dir():
            out += [*_parents(workspace), "--bind", str(workspace), str(workspace), "--chdir", str(workspace)]
        else:
            out += ["--chdir", "/tmp"]
        return out


def _parents(path: Path) -> list[str]:
    """The folders above ``path``, made open to the node (bwrap would make them root's own, 0700)."""
    out: list[str] = []
    for parent in reversed(path.parents[:-1]):
        out += ["--perms", "0755", "--dir", str(parent)]
    return out


def _python_dirs() -> Iterator[Path]:
    """Python's own folders, the venv's and the lab's code, each once (none inside another)."""
    wanted = {Path(sys.base_prefix).resolve(), Path(sys.prefix).resolve()}
    wanted |= {(PROJECT / name).resolve() for name in CLIENT_CODE}
    executable = Path(sys.executable).resolve()
    if not any(executable.is_relative_to(p) for p in wanted):
        wanted.add(executable.parent)
    kept = sorted(p for p in wanted if p.exists())
    for path in kept:
        if not any(path != other and path.is_relative_to(other) for other in kept):
            yield path
