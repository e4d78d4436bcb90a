"""The lab's own packages come first in a node process (node_runtime/process/lab_packages.py): the
names it pins are the client's packages, and a folder of the student's named like one of them,
first on ``sys.path``, does not replace it (the live sandbox test runs this through a class
server; this one runs a plain node process)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from support.app import REPO

from node_runtime.process.lab_packages import CLIENT_PACKAGES


def test_lab_packages_are_the_clients_packages() -> None:
    on_disk = sorted(p.name for p in (REPO / "client").iterdir() if (p / "__init__.py").is_file())
    assert list(CLIENT_PACKAGES) == on_disk


def test_lab_packages_a_students_rclpy_beside_the_node_does_not_replace_the_labs(tmp_path: Path) -> None:
    for name in ("rclpy", "std_msgs", "server"):
        (tmp_path / name).mkdir()
        (tmp_path / name / "__init__.py").write_text("raise SystemExit('the student shadow ran')\n")
    node = tmp_path / "node.py"
    node.write_text(
        "import rclpy, std_msgs.msg, server\n"
        "print(rclpy.__file__, std_msgs.msg.__file__, server.__file__)\n"
        "if __name__ == '__main__':\n    pass\n"
    )
    done = subprocess.run(
        [sys.executable, "-P", "-m", "node_runtime.process.runner", str(node)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    assert all(Path(f).is_relative_to(REPO) for f in done.stdout.split()), done.stdout
    control = subprocess.run(
        [sys.executable, str(node)], cwd=tmp_path, capture_output=True, text=True, timeout=60, check=False
    )
    assert "the student shadow ran" in control.stderr  # plain Python: the student's folder wins
