"""A node process loads the lab's own code from bytecode the set-up compiled, and compiles none of
it as it starts: it runs with PYTHONDONTWRITEBYTECODE (a student's folder gets no __pycache__),
so it could never keep what it compiled, and each start compiled every lab module it imports
again. Read from ``python -v`` ("code object from" a .py file: compiled now) in a process with
the environment a sandboxed node has (no PYTHONPYCACHEPREFIX), after the set-up's ``compile_lab``
(scripts/_venv.sh), which the README's commands run."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from support.app import REPO

# What a student's node imports as it starts: the runner, rclpy, messages (node_runtime/process/runner.py).
NODE_IMPORTS = (
    "import node_runtime.process.runner as runner; runner.lab_packages.pin(); "
    "import rclpy; from rclpy.node import Node; import std_msgs.msg, geometry_msgs.msg"
)
LAB_CODE = ("node_runtime", "server", "sim", "client")


def compiled_now(code: str, cwd: Path) -> list[str]:
    """The source files ``python -v -c code`` compiled (rather than loaded from bytecode), in a
    process with a node's environment."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPYCACHEPREFIX"}
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    result = subprocess.run(
        [sys.executable, "-v", "-c", code], cwd=cwd, env=env, capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 0, result.stderr[-2000:]
    prefix = "# code object from "
    return [line[len(prefix) :] for line in result.stderr.splitlines() if line.startswith(prefix + "/")]


def test_a_node_compiles_none_of_the_labs_code_after_the_set_up(tmp_path: Path) -> None:
    setup = subprocess.run(
        ["bash", "-c", "set -euo pipefail; source scripts/_venv.sh; compile_lab"],
        cwd=REPO,
        env={**os.environ, "TELEOP_VENV": sys.prefix},
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert setup.returncode == 0 and setup.stderr == "", setup.stderr
    lab = [str(REPO / name) + os.sep for name in LAB_CODE]
    compiled = compiled_now(NODE_IMPORTS, REPO)
    assert [f for f in compiled if f.startswith(tuple(lab))] == []

    # The reading can tell: a module nothing compiled is compiled as it is imported.
    (tmp_path / "fresh_module.py").write_text("VALUE = 1\n")
    assert compiled_now("import fresh_module", tmp_path) == [str(tmp_path / "fresh_module.py")]
