"""A student's node process on a server that serves others: run inside bubblewrap (``bwrap``).

The layers, each enough on its own for what it stops (docs/sandbox.md says what each leaves):

- its own PID, mount, IPC, UTS and network namespaces (and a user namespace when the server is not
  root); as root, every capability dropped but the two that ``setpriv`` needs to make the node a uid
  of its world's, with no group and no capability left, before Python starts;
- a seccomp filter (server/host/processes/seccomp_filter.py) loaded by bwrap before anything runs;
- Python started isolated (``-I``): no variable of the environment, no user site, and neither the
  current folder nor the workspace on ``sys.path``; the lab's runner and packages come from the
  installed lab, the student's folders are added by the runner after them;
- what it sees: its workspace read-only, at the path the server knows it by (tracebacks name the
  same files); the system's ``/usr``, Python, the venv and the lab's client code read-only; a
  private, size-capped ``/tmp`` (its home) and ``/dev/shm``, a minimal ``/dev``, its own ``/proc``;
- no network but loopback of its own: its world's Zenoh router is a Unix socket bound in at
  ``/run/ros2lab``, and it logs in there with its world's login, so it reaches its world only;
- limits: a memory cgroup and a pids cgroup where the machine gives them
  (server/host/processes/cgroups.py), rlimits always (node_runtime/process/confinement.py);
- the sandbox's pid 1 is the lab's, not the student's (node_runtime/process/node_init.py): it holds the
  lifeline to the server, so the node ends with the server however the server ends.

Its environment is built afresh (no variable of the server's: no token, no path of the server).
"""

from __future__ import annotations

import functools
import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from node_runtime.ament.workspace import WORKSPACE_ENV
from node_runtime.process.confinement import LIMITS_ENV, Confinement
from node_runtime.transport.router_socket import SOCKET_NAME, socket_endpoint
from server.host.processes import cgroups, seccomp_filter
from server.host.processes.command import RUNNER_MODULE, NodeCommand, PreparedStart

SOCKET_DIR = "/run/ros2lab"  # where the router's Unix socket's folder is bound inside
PROBE_TIMEOUT_S = 10.0
INSIDE_UID = 1000  # the node's uid inside its user namespace (not root)
PROJECT = Path(__file__).resolve().parents[3]
CLIENT_CODE = ("node_runtime", "server", "sim", "client")  # the lab's code a node process imports
# Only what a node process needs; the server's own environment never reaches it.
KEPT_ENV = (
    "PYTHONUNBUFFERED",
    "PYTHONDONTWRITEBYTECODE",
    "ROS_DOMAIN_ID",
    "ZENOH_CONFIG_OVERRIDE",
    WORKSPACE_ENV,
)


INSIDE_ROUTER = socket_endpoint(f"{SOCKET_DIR}/{SOCKET_NAME}")
SECCOMP_FD = "{seccomp-fd}"  # in a wrapped argv: the descriptor of the filter, made as the node starts
SETPRIV = "/usr/bin/setpriv"  # util-linux: becomes the world's uid, with no group and no capability
TMP_MIB = 64  # the node's /tmp (its home: ROS logs, scratch files), a tmpfs counted in its memory
SHM_MIB = 64  # its /dev/shm (Zenoh's shared memory)


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
    """Why no sandbox can be built here, in one line (None: it can): bubblewrap with every layer
    a node gets (namespaces, capabilities dropped, the seccomp filter, size-capped tmpfs, and as
    root the change of uid), run once per process."""
    bwrap = _bwrap()
    if bwrap is None:
        return "no bubblewrap (bwrap) on this machine: install Debian's 'bubblewrap'"
    try:
        seccomp_filter.program()
    except seccomp_filter.SeccompUnavailableError as exc:
        return f"no seccomp filter: {exc}"
    root = os.geteuid() == 0
    if root and not os.access(SETPRIV, os.X_OK):
        return f"no {SETPRIV} to make a node a uid of its own: install Debian's 'util-linux'"
    fd = seccomp_filter.program_fd()
    inside = [*_drop_root(Confinement()), "/bin/true"] if root else ["/bin/true"]
    argv = [
        bwrap,
        *_namespaces(root),
        "--seccomp",
        str(fd),
        "--ro-bind",
        "/",
        "/",
        "--proc",
        "/proc",
        "--dev",
        "/dev",
        "--size",
        str(1024 * 1024),
        "--tmpfs",
        "/tmp",
        "--",
        *inside,
    ]
    try:
        done = subprocess.run(
            argv, capture_output=True, text=True, timeout=PROBE_TIMEOUT_S, check=False, pass_fds=[fd]
        )
    except (OSError, subprocess.TimeoutExpired) as exc:
        return f"bubblewrap could not start: {exc}"
    finally:
        os.close(fd)
    if done.returncode != 0:
        why = (done.stderr.strip().splitlines() or [f"exit code {done.returncode}"])[-1]
        return f"bubblewrap cannot build a sandbox here ({why}): the kernel or container refuses namespaces"
    return None


def memory_layer() -> str:
    """How a node's memory is counted here, in a few words (for the server's banner)."""
    found = cgroups.parent()
    if isinstance(found, str):
        return f"address space (RLIMIT_AS; {found})"
    return f"whole, shared memory and tmpfs included (cgroup v{found.version})"


def cpu_layer(nice: int) -> str:
    """How the nodes' CPU is weighed against the worlds here, in a few words (for the banner)."""
    found = cgroups.parent()
    if isinstance(found, str) or not found.cpu_weighed:
        return f"nice {nice}"
    if found.cpu_idle:
        return f"nice {nice}, all in one idle CPU group (a world's loop takes their core at once)"
    weight, of = (cgroups.CPU_SHARES, 1024) if found.version == 1 else (cgroups.CPU_WEIGHT, 100)
    return f"nice {nice}, all in one CPU group weighed {weight} to a process group's {of}"


def _namespaces(root: bool) -> list[str]:
    # As root, no user namespace: the node's processes must belong to a uid other than 0 outside too
    # (root's processes are not counted against RLIMIT_NPROC), so setpriv makes it one. bwrap run by
    # root keeps every capability unless told: all go but the three setpriv needs, and those go too
    # as it changes the uid.
    users = (
        [
            "--cap-drop",
            "ALL",
            "--cap-add",
            "CAP_SETUID",
            "--cap-add",
            "CAP_SETGID",
            "--cap-add",
            "CAP_SETPCAP",
        ]
        if root
        else ["--unshare-user"]
    )
    return [
        *users,
        "--unshare-pid",
        "--unshare-net",
        "--unshare-ipc",
        "--unshare-uts",
        "--unshare-cgroup-try",
    ]


def _drop_root(confinement: Confinement) -> list[str]:
    """setpriv's command prefix: the world's uid and gid, no group, no capability (not even in the
    bounding set), no new privileges."""
    return [
        SETPRIV,
        "--reuid",
        str(confinement.uid),
        "--regid",
        str(confinement.gid),
        "--clear-groups",
        "--inh-caps",
        "-all",
        "--bounding-set",
        "-all",
        "--no-new-privs",
        "--",
    ]


def _isolated(argv: list[str]) -> list[str]:
    """The runner's command started isolated (``python -I``): nothing of the environment, the
    current folder or the workspace decides what Python imports first."""
    at = argv.index(RUNNER_MODULE)
    return [sys.executable, "-I", "-B", "-u", "-m", RUNNER_MODULE, *argv[at + 1 :]]


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
        counted = cgroups.parent()
        if isinstance(counted, str):  # no memory cgroup here: the address space stands in for it
            confinement = confinement.counting_address_space()
        env[LIMITS_ENV] = confinement.encode()
        ws = workspace.resolve() if workspace is not None else None
        if ws is not None and root:
            _open_to_read(ws)
        inside = [*(_drop_root(confinement) if root else []), *_isolated(command.argv)]
        argv = [
            bwrap,
            *_namespaces(root),
            "--die-with-parent",
            "--new-session",
            "--as-pid-1",
            "--seccomp",
            SECCOMP_FD,
            "--hostname",
            "ros2lab-node",
            *([] if root else ["--uid", str(INSIDE_UID), "--gid", str(INSIDE_UID)]),
            *self._mounts(ws),
            "--",
            *inside,
        ]
        start = _Start(confinement, None if isinstance(counted, str) else counted)
        return NodeCommand(argv, env, command.zid, sandboxed=True, prepare=start.prepare)

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
        # Both are capped: a tmpfs's pages are memory, which an rlimit does not count.
        out += [
            "--proc",
            "/proc",
            "--dev",
            "/dev",
            "--perms",
            "1777",
            "--size",
            str(SHM_MIB * MIB),
            "--tmpfs",
            "/dev/shm",
            "--perms",
            "1777",
            "--size",
            str(TMP_MIB * MIB),
            "--tmpfs",
            "/tmp",
            "--dir",
            "/run",
        ]
        for path in _python_dirs():
            out += [*_parents(path), "--ro-bind", str(path), str(path)]
        out += ["--ro-bind", str(self.socket.parent), SOCKET_DIR]
        if workspace is not None and workspace.is_dir():
            # Read-only: a node never changes the tree the API serves (no link, no race, no disk
            # filled through it); it writes in its /tmp.
            out += [
                *_parents(workspace),
                "--ro-bind",
                str(workspace),
                str(workspace),
                "--chdir",
                str(workspace),
            ]
        else:
            out += ["--chdir", "/tmp"]
        return out


MIB = 1024 * 1024


@dataclass(frozen=True)
class _Start:
    """What a sandboxed node's start makes as it starts: its control group (where the machine
    gives them) and the descriptor bwrap reads the seccomp filter from."""

    confinement: Confinement
    groups: cgroups.CgroupParent | None

    def prepare(self, argv: list[str], label: str) -> PreparedStart:
        group = None
        if self.groups is not None:
            # The node's processes and threads, and its pid 1 (node_runtime/process/node_init.py).
            name = re.sub(r"[^A-Za-z0-9_.-]", "_", label)
            group = self.groups.make(name, self.confinement.memory_mib, self.confinement.processes + 1)
        fd = seccomp_filter.program_fd()
        wrapped = [str(fd) if arg == SECCOMP_FD else arg for arg in argv]
        if group is not None:
            wrapped = [*group.join_prefix(), *wrapped]
        return PreparedStart(wrapped, (fd,), functools.partial(self._finish, group))

    def _finish(self, group: cgroups.NodeCgroup | None, _code: int) -> str | None:
        if group is None:
            return None
        killed = group.oom_kills() > 0
        group.remove()
        return self.confinement.memory_line() if killed else None


def _open_to_read(workspace: Path) -> None:
    """Let the node's uid into its workspace folder (a root server's folders may be its own alone);
    what is inside, the API writes readable to all (files 0644, folders 0755)."""
    try:
        mode = workspace.stat().st_mode
        if workspace.is_dir() and mode & 0o005 != 0o005:
            workspace.chmod(mode | 0o005)
    except OSError:
        pass  # the node then says it cannot read its file, in its output


def _parents(path: Path) -> list[str]:
    """The folders above ``path``, made open to the node (bwrap would make them root's own, 0700)."""
    out: list[str] = []
    for parent in reversed(path.parents[:-1]):
        out += ["--perms", "0755", "--dir", str(parent)]
    return out


@functools.cache
def _python_dirs() -> tuple[Path, ...]:
    """Python's own folders, the venv's and the lab's code, each once (none inside another).
    The server's own installation: found once (resolving them took a start about a millisecond
    of the loop, and a class presses Run sixty times at once)."""
    wanted = {Path(sys.base_prefix).resolve(), Path(sys.prefix).resolve()}
    wanted |= {(PROJECT / name).resolve() for name in CLIENT_CODE}
    executable = Path(sys.executable).resolve()
    if not any(executable.is_relative_to(p) for p in wanted):
        wanted.add(executable.parent)
    kept = sorted(p for p in wanted if p.exists())
    return tuple(
        path for path in kept if not any(path != other and path.is_relative_to(other) for other in kept)
    )
