"""``ros2lab launch`` shows what its nodes print, as ``ros2 launch`` does: a node process's own
output (its log lines, its prints, its traceback) once each, behind its label, and its death.

The app and the CLI run as processes of their own on loopback, ended by their ids.
"""

from __future__ import annotations

import os
import queue
import re
import signal
import subprocess
import threading
import time
from pathlib import Path

import pytest
from support.app import App
from support.forked_cli import cli_command
from support.http import HTTP

from .conftest import make_workspace

TALKY = """
import rclpy
from rclpy.node import Node


class Talky(Node):
    def __init__(self):
        super().__init__('Talky')
        self.get_logger().info('starting up')
        print('a plain print', flush=True)
        self.create_timer(0.5, self.tick)

    def tick(self):
        raise RuntimeError('wires crossed')


def main():
    rclpy.init()
    rclpy.spin(Talky())


if __name__ == '__main__':
    main()
"""
ONCE = """
<launch>
  <node pkg="faults" exec="talky.py" name="Talky"/>
</launch>
"""
READ_S = 60.0


def lines_of(proc: subprocess.Popen[str]) -> tuple[queue.Queue[str | None], threading.Thread]:
    out: queue.Queue[str | None] = queue.Queue()

    def pump() -> None:
        assert proc.stdout is not None
        for line in proc.stdout:
            out.put(line.rstrip("\n"))
        out.put(None)

    reader = threading.Thread(target=pump, daemon=True)
    reader.start()
    return out, reader


def read_until(out: queue.Queue[str | None], seen: list[str], pattern: str) -> re.Match[str]:
    deadline = time.monotonic() + READ_S
    while True:
        try:
            line = out.get(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            pytest.fail(f"no line like {pattern!r} within {READ_S} s; got {seen[-20:]}")
        if line is None:
            pytest.fail(f"output ended before a line like {pattern!r}; got {seen[-20:]}")
        seen.append(line)
        if found := re.fullmatch(pattern, line):
            return found


def test_launch_prints_its_node_processs_output_once_and_its_death(tmp_path: Path) -> None:
    make_workspace(tmp_path, {"src/faults/talky.py": TALKY, "src/faults/launch/once.launch": ONCE})
    app = App(tmp_path, "--launch", "rocket", cwd=tmp_path)
    cli: subprocess.Popen[str] | None = None
    reader: threading.Thread | None = None
    try:
        cli = subprocess.Popen(
            cli_command("launch", "faults", "once.launch"),
            env={**os.environ, "TELEOP_URL": app.url, "PYTHONUNBUFFERED": "1"},
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            cwd=tmp_path,
        )
        (out, reader), seen = lines_of(cli), []
        label = read_until(
            out, seen, r"\[(talky\.py-\d+)\] \[INFO\] \[\d+\.\d+\] \[Talky\]: starting up"
        ).group(1)
        read_until(out, seen, re.escape(f"[{label}] a plain print"))
        read_until(out, seen, re.escape(f"[{label}] RuntimeError: wires crossed"))
        read_until(out, seen, re.escape(f"[ERROR] [{label}]: process has died [exit code 1]"))
        # Its log line came once: from its own output, not again from /rosout.
        assert sum("starting up" in line for line in seen) == 1, seen
        # The server keeps the lines for anyone who asks, with how many there were.
        launches = HTTP.get(f"{app.url}/api/launches", timeout=10).json()
        group = next(g for g in launches if g["file"].endswith("once.launch"))
        output = HTTP.get(f"{app.url}/api/launches/{group['id']}/output", timeout=10).json()
        (process,) = output["processes"]
        assert process["label"] == label and process["printed"] == len(process["lines"]) >= 3
        assert output["group"]["nodes"][0]["state"] == "died"
        assert HTTP.get(f"{app.url}/api/launches/nope/output", timeout=10).status_code == 404
        cli.send_signal(signal.SIGINT)
        assert cli.wait(timeout=30) == 0
    finally:
        if cli is not None:
            if cli.poll() is None:
                cli.kill()
            cli.wait()
            if reader is not None:
                reader.join(timeout=10)  # its output ends with it
            for stream in (cli.stdout, cli.stderr):
                if stream is not None:
                    stream.close()
        app.stop()
