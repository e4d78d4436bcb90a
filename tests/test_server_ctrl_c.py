"""Ctrl-C pressed again while ``python -m server`` stops (a student who thinks the first one was
not heard): the lab still stops as one Ctrl-C stops it, its worlds and Zenoh session closed, with
exit code 0 and no traceback, where it used to print two and hang for good.

The second comes ``AGAIN_S`` after the first, before uvicorn's next look at its exit flag (every
0.1 s), when it used to take the second as "force quit" and skip the app's own stop. Two that come
closer together are one Ctrl-C to Python, and then the test shows only that one stops it."""

from __future__ import annotations

import queue
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from support.app import REPO, free_ports, healthy, own_state
from support.wait import wait_until

AGAIN_S = 0.02
ENDED_S = 30.0


@pytest.mark.parametrize("classroom", [False, True], ids=["lab", "class server"])
def test_a_second_ctrl_c_while_the_server_stops_lets_it_stop_as_the_first_would(
    tmp_path: Path, classroom: bool
) -> None:
    port, zenoh, foxglove = free_ports(3)
    args = ["--host", "127.0.0.1", "--port", str(port), "--zenoh-listen", f"tcp/127.0.0.1:{zenoh}",
            "--foxglove-port", str(foxglove)]  # fmt: skip
    if classroom:
        args += ["--classroom", "--workers", "0"]
    proc = subprocess.Popen(
        [sys.executable, "-m", "server", *args, *own_state(tmp_path, args)],
        cwd=tmp_path,
        env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"},
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    lines: queue.Queue[str | None] = queue.Queue()
    seen: list[str] = []

    def read() -> None:
        assert proc.stdout is not None
        for line in proc.stdout:
            lines.put(line)
        lines.put(None)

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        wait_until(lambda: healthy(f"http://127.0.0.1:{port}"), "the server up", 60.0, poll_s=0.1)
        proc.send_signal(signal.SIGINT)
        time.sleep(AGAIN_S)
        proc.send_signal(signal.SIGINT)
        try:
            code = proc.wait(timeout=ENDED_S)
        except subprocess.TimeoutExpired:
            pytest.fail(f"the server still ran {ENDED_S} s after the second Ctrl-C")
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=10)
    reader.join(timeout=10)
    if proc.stdout is not None:
        proc.stdout.close()
    while (line := lines.get(timeout=10)) is not None:
        seen.append(line)
    output = "".join(seen)
    assert code == 0, output[-3000:]
    assert "Traceback" not in output, output[-3000:]
