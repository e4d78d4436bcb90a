"""The tests' server starter (support/forked_server.py): a forked server is ``python -m server`` as
the shell runs it (its arguments, working folder, environment, output, exit codes, Ctrl-C), and the
starter ends every server it started when its test process goes away."""

from __future__ import annotations

import os
import signal
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import end, free_ports, wait_healthy
from support.forked_server import ForkedProcess, Starter
from support.http import HTTP
from support.wait import wait_until


@pytest.fixture(scope="module")
def starter() -> Iterator[Starter]:
    own = Starter()  # not the process's shared one, so this module can close it
    yield own
    own.close()


def lab_args(port: int, zenoh_port: int, state: Path) -> list[str]:
    return [
        "--host",
        "127.0.0.1",
        "--port",
        str(port),
        "--zenoh-listen",
        f"tcp/127.0.0.1:{zenoh_port}",
        "--state-dir",
        str(state),
        "--launch",
        "rocket",
        "--no-foxglove",
    ]


def alive(pid: int) -> bool:
    """Whether ``pid`` is a process that has not ended (a zombie has ended)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except (FileNotFoundError, IndexError):
        return False


def test_a_forked_server_serves_from_its_folder_with_its_environment_and_ends_on_ctrl_c(
    starter: Starter, tmp_path: Path
) -> None:
    port, zenoh_port = free_ports(2)
    log = tmp_path / "server.log"
    env = {**os.environ, "ROS_DOMAIN_ID": "17"}
    proc = starter.start(lab_args(port, zenoh_port, tmp_path / "state"), tmp_path, log, env)
    url = f"http://127.0.0.1:{port}"
    try:
        wait_healthy(url, proc, 60.0, log.read_text)
        assert proc.poll() is None
        assert Path(f"/proc/{proc.pid}/cwd").resolve() == tmp_path.resolve()
        assert HTTP.get(f"{url}/api/zenoh/join", timeout=5).json()["domain_id"] == 17
        assert Path(f"/proc/{proc.pid}/fd/1").resolve() == log.resolve()
        assert Path(f"/proc/{proc.pid}/fd/0").resolve() == Path(os.devnull)
    finally:
        end(proc)
    assert proc.returncode == 0  # Ctrl-C, then the interpreter's own shutdown
    text = log.read_text()
    assert "Uvicorn running on" in text and "Finished server process" in text, text[-2000:]
    proc.send_signal(signal.SIGINT)  # after the end: not sent to whatever took the id since
    assert proc.wait(timeout=1) == 0


def test_a_forked_server_refuses_a_bad_option_as_the_shell_would(starter: Starter, tmp_path: Path) -> None:
    log = tmp_path / "server.log"
    proc = starter.start(["--no-such-option"], tmp_path, log, dict(os.environ))
    assert proc.wait(timeout=30) == 2
    assert "unrecognized arguments: --no-such-option" in log.read_text()
    assert "usage: python -m server" in log.read_text()


def test_wait_times_out_while_the_server_runs_and_kill_ends_it(starter: Starter, tmp_path: Path) -> None:
    port, zenoh_port = free_ports(2)
    log = tmp_path / "server.log"
    proc = starter.start(lab_args(port, zenoh_port, tmp_path / "state"), tmp_path, log, dict(os.environ))
    try:
        wait_healthy(f"http://127.0.0.1:{port}", proc, 60.0, log.read_text)
        with pytest.raises(subprocess.TimeoutExpired):
            proc.wait(timeout=0.2)
        proc.kill()
        assert proc.wait(timeout=30) == -signal.SIGKILL
    finally:
        end(proc)


def test_a_starter_whose_test_process_goes_kills_what_it_started(tmp_path: Path) -> None:
    own = Starter()
    port, zenoh_port = free_ports(2)
    log = tmp_path / "server.log"
    proc: ForkedProcess = own.start(
        lab_args(port, zenoh_port, tmp_path / "state"), tmp_path, log, dict(os.environ)
    )
    try:
        wait_healthy(f"http://127.0.0.1:{port}", proc, 60.0, log.read_text)
        assert alive(proc.pid)
        own.close()  # as when the pytest process ends: the starter's stdin closes
        assert own.proc.returncode == 0
        assert not alive(proc.pid)
    finally:
        own.close()  # again on a failure before it: its pipes closed and it reaped, whatever happened
        wait_until(lambda: not alive(proc.pid), "the forked server to be gone", 10.0)
