"""Bench: a student's node process started in the sandbox against one started as today, in one run.

    .venv/bin/python bench/sandbox_start.py [--tries 5]

This process opens a Zenoh router (multicast scouting off) on a free loopback TCP port and on a
Unix socket (node_runtime/transport/router_socket.py), as a class server's router does. Each try starts
the handout's keyboard manager (examples/workspace, rocketship) twice, alternating which goes
first: once as the lab's launcher runs a node file (``python -m node_runtime.process.runner FILE``,
connecting over TCP) and once wrapped by server/host/processes/sandbox.py (bubblewrap, the default
limits, connecting over the Unix socket). What is measured, each from just before ``Popen``:

* start → joined: until the node's liveliness token is on the router (a Zenoh liveliness query
  for ``@ros2_lv/0/**`` every 20 ms, matching the node's name);
* memory one second later: the node process's VmRSS (/proc/PID/status), and the PSS of every
  process it takes (/proc/PID/smaps_rollup: shared pages counted once across them): the node alone
  as today; in the sandbox bwrap, the sandbox's pid 1 (node_runtime/process/node_init.py, which
  stays as the node's parent) and the node.

Then Ctrl-C (as the supervisor sends it) and the process is ended by its id. Median and max over
``--tries``. Prints the machine (bench/machine.py) and one JSON object, also written to
bench/results/sandbox_start.json.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))  # run as a script from anywhere: the app's packages live at the root

import zenoh
from live_server import end, rss_mib
from machine import machine_info, save_results

from node_runtime.process.confinement import Confinement
from node_runtime.transport.router_socket import new_socket_path, open_to_nodes, remove, socket_endpoint
from server.host.processes.command import NodeCommand, node_command
from server.host.processes.sandbox import INSIDE_ROUTER, Sandbox, probe

KEYBOARD_MANAGER = REPO / "examples" / "workspace" / "src" / "rocketship" / "src" / "keyboard_manager.py"
NODE_NAME = "KeyboardManagerNode"
JOIN_TIMEOUT_S = 60.0
SETTLE_S = 1.0


def pss_mib(pid: int) -> float:
    """Proportional set size of the process, in MiB."""
    for line in Path(f"/proc/{pid}/smaps_rollup").read_text().splitlines():
        if line.startswith("Pss:"):
            return int(line.split()[1]) / 1024.0
    raise RuntimeError(f"no Pss for pid {pid}")


def child_pid(pid: int) -> int | None:
    """The node inside bwrap (its child), as the supervisor finds it for Ctrl-C."""
    children = Path(f"/proc/{pid}/task/{pid}/children").read_text().split()
    return int(children[0]) if children else None


def free_port() -> int:
    import socket

    with socket.socket() as probe_socket:
        probe_socket.bind(("127.0.0.1", 0))
        return int(probe_socket.getsockname()[1])


def open_router(tcp: str, unix: Path) -> Any:
    config = zenoh.Config()
    config.insert_json5("mode", '"router"')
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("listen/endpoints", json.dumps([tcp, socket_endpoint(unix)]))
    session = zenoh.open(config)
    open_to_nodes(unix)  # as open_session does: a root server's node runs as a uid of its own
    return session


def joined(session: Any) -> bool:
    return any(
        NODE_NAME in str(reply.ok.key_expr)
        for reply in session.liveliness().get("@ros2_lv/0/**")
        if reply.ok is not None
    )


def one_start(session: Any, command: NodeCommand) -> dict[str, float]:
    prepared = command.prepare(command.argv, "bench") if command.prepare is not None else None
    argv, fds = (prepared.argv, prepared.pass_fds) if prepared is not None else (command.argv, ())
    started = time.perf_counter()
    proc = subprocess.Popen(
        argv,
        env=command.env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        pass_fds=fds,
    )
    for fd in fds:
        os.close(fd)
    sandboxed = command.sandboxed
    try:
        while not joined(session):
            if time.perf_counter() - started > JOIN_TIMEOUT_S or proc.poll() is not None:
                raise RuntimeError(f"the node did not join (sandboxed={sandboxed}, exit {proc.poll()})")
            time.sleep(0.02)
        start_s = time.perf_counter() - started
        time.sleep(SETTLE_S)
        # In the sandbox: bwrap, the sandbox's pid 1 below it, and the node below that.
        chain = [proc.pid]
        while sandboxed and len(chain) < 3 and (below := child_pid(chain[-1])) is not None:
            chain.append(below)
        if sandboxed and len(chain) < 3:
            raise RuntimeError(f"the sandbox's processes were not all there: {chain}")
        return {
            "start_s": start_s,
            "node_rss_mib": rss_mib(chain[-1]),
            "total_pss_mib": sum(map(pss_mib, chain)),
        }
    finally:
        target = child_pid(proc.pid) if sandboxed and proc.poll() is None else None
        if target is not None:
            os.kill(
                target, signal.SIGINT
            )  # Ctrl-C to the sandbox's pid 1, by its id, as the supervisor sends it
        end(proc)
        if prepared is not None:
            prepared.finish(proc.returncode or 0)


def summary(rows: list[dict[str, float]]) -> dict[str, float]:
    keys = rows[0].keys()
    return {
        f"{k}_{f.__name__}": round(f(r[k] for r in rows), 3) for k in keys for f in (statistics.median, max)
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--tries", type=int, default=5)
    args = parser.parse_args()
    why = probe()
    if why is not None:
        print(f"no sandbox here: {why}", file=sys.stderr)
        return 2
    tcp = f"tcp/127.0.0.1:{free_port()}"
    socket_path = new_socket_path()
    workspace = Path(tempfile.mkdtemp(prefix="sandbox-bench-"))
    node_file = workspace / "keyboard_manager.py"
    shutil.copy(KEYBOARD_MANAGER, node_file)
    session = open_router(tcp, socket_path)
    sandbox = Sandbox(socket_path, Confinement())
    rows: dict[str, list[dict[str, float]]] = {"unsandboxed": [], "sandboxed": []}
    try:
        for i in range(args.tries):
            order = ["unsandboxed", "sandboxed"] if i % 2 == 0 else ["sandboxed", "unsandboxed"]
            for kind in order:
                if kind == "sandboxed":
                    command = sandbox.wrap(
                        node_command(node_file, [], router=INSIDE_ROUTER, env={}), workspace
                    )
                else:
                    command = node_command(node_file, [], router=tcp, workspace=workspace)
                rows[kind].append(one_start(session, command))
    finally:
        session.close()
        remove(socket_path)
        shutil.rmtree(workspace, ignore_errors=True)
    result = {"tries": args.tries, **{kind: summary(r) for kind, r in rows.items()}}
    print(json.dumps(machine_info()))
    print(json.dumps(result, indent=2))
    save_results("sandbox_start", result)
    return 0


if __name__ == "__main__":
    sys.exit(main())
