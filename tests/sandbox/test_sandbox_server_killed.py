"""No student's node outlives its class server, however hard it tries: a node that ignores every
stop signal, clears its parent-death signal, replaces every descriptor it has (the lifeline's
among them, were it in its own process) and leaves a daemon behind is gone within 10 s of a
SIGKILL of the class server. The same node is first shown to survive what it tries: Ctrl-C does
not end it, and its daemon runs beside it."""

from __future__ import annotations

import contextlib
import os
import signal
from pathlib import Path

from support.app import App
from support.http import HTTP
from support.sandbox import require_sandbox
from support.wait import wait_until

CODE = "KIL042"
GONE_S = 10.0
HOSTILE = """
import ctypes
import os
import signal
import time


def main():
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT):
        signal.signal(sig, signal.SIG_IGN)
    ctypes.CDLL(None).prctl(1, 0, 0, 0, 0)  # PR_SET_PDEATHSIG: none
    null = os.open('/dev/null', os.O_RDWR)
    for fd in range(3, 64):
        if fd != null:
            try:
                os.dup2(null, fd)
            except OSError:
                pass
    if os.fork() == 0:  # a daemon: its own session, its parent gone
        os.setsid()
        if os.fork() == 0:
            while True:
                time.sleep(1)
        os._exit(0)
    print('hostile node ready', flush=True)
    while True:
        time.sleep(1)


if __name__ == '__main__':
    main()
"""


def processes_of(marker: str, python_only: bool = False) -> list[int]:
    """The processes whose command line names ``marker`` (the node's own file): bwrap's, and
    (``python_only``) or only the Python ones (the sandbox's pid 1, the node, its daemon)."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        with contextlib.suppress(OSError):
            argv = (entry / "cmdline").read_bytes().split(b"\0")
            if python_only and b"python" not in Path(argv[0].decode()).name.encode():
                continue
            if marker.encode() in b" ".join(argv):
                state = (entry / "stat").read_text().rsplit(")", 1)[1].split()[0]
                if state != "Z":
                    found.append(int(entry.name))
    return found


def test_sandbox_no_node_outlives_a_sigkilled_class_server(tmp_path: Path) -> None:
    require_sandbox()
    (tmp_path / "world.launch").write_text("<launch>\n</launch>\n")
    (tmp_path / "logs").mkdir()
    app = App(
        tmp_path / "logs",
        "--classroom",
        "--class-code",
        CODE,
        "--launch",
        str(tmp_path / "world.launch"),
        "--no-foxglove",
        cwd=tmp_path,
        ready_s=120.0,
    )
    node_file = ""
    try:
        joined = HTTP.post(f"{app.url}/api/classroom/join", json={"name": "Eve", "code": CODE}, timeout=30)
        assert joined.status_code == 201, joined.text
        headers = {"Authorization": f"Bearer {joined.json()['token']}"}
        saved = HTTP.put(
            f"{app.url}/api/workspace/files/src/evil/hostile.py",
            json={"text": HOSTILE},
            headers=headers,
            timeout=30,
        )
        assert saved.status_code in (200, 201), saved.text
        node_file = str(tmp_path / "workspaces" / joined.json()["world"] / "src" / "evil" / "hostile.py")
        started = HTTP.post(
            f"{app.url}/api/run",
            json={"package": "evil", "executable": "hostile.py"},
            headers=headers,
            timeout=30,
        )
        assert started.status_code == 201, started.text
        output = f"{app.url}/api/launches/{started.json()['id']}/output"

        def ready() -> bool:
            lines = HTTP.get(output, headers=headers, timeout=10).json()["processes"][0]["lines"]
            return "hostile node ready" in lines

        wait_until(ready, "the hostile node to be ready", 60.0, poll_s=0.2)
        # pid 1 of the sandbox, the node and its daemon: the daemon outlived its parent
        wait_until(lambda: len(processes_of(node_file, True)) >= 3, "the node and its daemon", 10.0)
        before = processes_of(node_file, True)
        # Ctrl-C alone does not end it: it ignores it (a marker: the output API still answers after)
        for pid in before:
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGINT)
        assert HTTP.get(output, headers=headers, timeout=10).status_code == 200
        assert set(before) <= set(processes_of(node_file)), "Ctrl-C ended the node: it proves nothing"
        app.proc.send_signal(signal.SIGKILL)
        app.proc.wait(timeout=10)
        wait_until(
            lambda: not processes_of(node_file), "every process of the node to be gone", GONE_S, poll_s=0.2
        )
    finally:
        for pid in processes_of(node_file) if node_file else []:
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
        app.stop()
