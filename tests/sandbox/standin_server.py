"""A stand-in for the server in tests/sandbox/test_sandbox_parent.py: starts one sandboxed node
through the real Supervisor, prints bwrap's pid and the node's, then waits for a line on stdin:
"stop" stops the node as the server does (Ctrl-C first) and prints "stopped"; end of stdin (or a
kill) ends this process with the node still running."""

from __future__ import annotations

import sys
import time
from pathlib import Path

from node_runtime.bus import Bus, SystemClock
from node_runtime.process.confinement import Confinement
from server.host.processes.command import node_command
from server.host.processes.sandbox import INSIDE_ROUTER, Sandbox
from server.host.processes.supervisor import Supervisor


def main() -> None:
    workspace, node = Path(sys.argv[1]), Path(sys.argv[2])
    command = node_command(node, [], router=INSIDE_ROUTER, env={}, workspace=workspace)
    wrapped = Sandbox(workspace.parent / "router" / "router.sock", Confinement()).wrap(command, workspace)
    supervisor = Supervisor(Bus(SystemClock()), lambda _process: None)
    process = supervisor.start(wrapped, "sleeper", screen=False, node_name=None)
    while not any("asleep" in line for line in process.output()[0]):  # bounded by the test's wait
        time.sleep(0.05)
    children = Path(f"/proc/{process.pid}/task/{process.pid}/children").read_text().split()
    print(process.pid, children[0], flush=True)
    if sys.stdin.readline().strip() == "stop":
        supervisor.stop(process, grace_s=1.0)
        print("stopped", flush=True)
        sys.stdin.readline()


if __name__ == "__main__":
    main()
