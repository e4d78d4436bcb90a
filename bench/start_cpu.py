"""Bench: the CPU a node's start spends before it needs the lab, in one run.

    .venv/bin/python bench/start_cpu.py [--tries 15]

Two measures, each a median over ``--tries``, alternating what they compare:

* ``ros2lab run`` (the handout's keyboard manager from examples/workspace) against a socket this
  process listens on and never answers: the CPU of the command's process when its first request
  has reached the socket (``/proc/PID/schedstat``), which is what sixty of them at once spend side
  by side before any has asked for its turn;
* a node process's imports (the runner, rclpy, two message packages), in a process with a
  sandboxed node's environment (``PYTHONDONTWRITEBYTECODE``, no ``PYTHONPYCACHEPREFIX``): the
  lab's code loaded from the bytecode the set-up compiled beside it (scripts/_venv.sh's
  ``compile_lab``), against a copy of the lab's packages with no bytecode, first on the path, as
  each node start compiled them before the set-up did.

Prints the machine (bench/machine.py) and one JSON object, also written to
bench/results/start_cpu.json.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
from machine import machine_info, save_results

ROS2LAB = Path(sys.executable).with_name("ros2lab")
WORKSPACE = REPO / "examples" / "workspace"
LAB_PACKAGES = ("node_runtime", "server", "sim", "client")
NODE_IMPORTS = (
    "import node_runtime.process.runner as runner; runner.lab_packages.pin(); "
    "import rclpy; from rclpy.node import Node; import std_msgs.msg, geometry_msgs.msg"
)


def cpu_s(pid: int) -> float:
    return int(Path(f"/proc/{pid}/schedstat").read_text().split()[0]) / 1e9


def ros2lab_ask_cpu(silent: socket.socket) -> float:
    """CPU-s of one ``ros2lab run`` when its first request reached ``silent``."""
    url = f"http://127.0.0.1:{silent.getsockname()[1]}"
    argv = [
        str(ROS2LAB),
        "--url",
        url,
        "run",
        "--workspace",
        str(WORKSPACE),
        "rocketship",
        "keyboard_manager.py",
    ]
    proc = subprocess.Popen(
        argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=tempfile.gettempdir()
    )
    try:
        conn, _ = silent.accept()
        with conn:
            conn.settimeout(30)
            conn.recv(4096)  # its request is here
            return cpu_s(proc.pid)
    finally:
        proc.kill()
        proc.wait()


def imports_cpu(path_first: Path | None, cwd: Path) -> float:
    """CPU-s of a node's imports in a node's environment, run in ``cwd`` (a folder of no package:
    ``-c`` puts it first on the path); ``path_first``: a folder put first on the path after it (a
    copy of the lab's packages without bytecode)."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPYCACHEPREFIX", "PYTHONPATH")}
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    if path_first is not None:
        env["PYTHONPATH"] = str(path_first)
    code = f"{NODE_IMPORTS}; import os; print(open(f'/proc/{{os.getpid()}}/schedstat').read().split()[0])"
    done = subprocess.run(
        [sys.executable, "-c", code],
        env=env,
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=120,
        check=True,
    )
    return int(done.stdout.split()[-1]) / 1e9


def summary(values: list[float]) -> dict[str, float]:
    return {"median": round(statistics.median(values), 4), "max": round(max(values), 4), "tries": len(values)}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--tries", type=int, default=15)
    args = parser.parse_args(argv)
    print(json.dumps(machine_info()), flush=True)

    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen(16)
        silent.settimeout(60)
        asks = [ros2lab_ask_cpu(silent) for _ in range(args.tries)]

    compiled: list[float] = []
    loaded: list[float] = []
    with tempfile.TemporaryDirectory() as folder, tempfile.TemporaryDirectory() as elsewhere:
        bare = Path(folder)
        for name in LAB_PACKAGES:
            shutil.copytree(REPO / name, bare / name, ignore=shutil.ignore_patterns("*.pyc"))
        for i in range(args.tries):  # alternated, which goes first too
            for path_first in (bare, None) if i % 2 else (None, bare):
                taken = imports_cpu(path_first, Path(elsewhere))
                (compiled if path_first is not None else loaded).append(taken)

    result = {
        "ros2lab_run_cpu_s_at_its_first_ask": summary(asks),
        "node_imports_cpu_s": {"from_bytecode": summary(loaded), "compiled_at_start": summary(compiled)},
    }
    print(json.dumps(result, indent=1))
    save_results("start_cpu", result)
    return 0


if __name__ == "__main__":
    sys.exit(main())
