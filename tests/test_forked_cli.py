"""The tests' CLI starter (support/forked_cli.py): a forked command is ``python -m server VERB`` as
the shell runs it (its arguments, working folder, environment, output, exit codes, Ctrl-C), a
command whose client is killed is killed with it, and the starter ends every command it started
when its test process goes away."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest
from support.app import free_port
from support.forked_cli import Starter
from support.wait import wait_until

from server.cli import COLCON_HINT


@pytest.fixture(scope="module")
def starter() -> Iterator[Starter]:
    own = Starter()  # not the process's shared one, so this module can close it
    yield own
    own.close()


def plain(*args: str) -> list[str]:
    return [sys.executable, "-m", "server", *args]


def children(starter: Starter) -> list[int]:
    """The processes the starter has forked and not reaped."""
    pid = starter.proc.pid
    return [int(child) for child in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]


@contextmanager
def silent_lab() -> Iterator[tuple[str, socket.socket]]:
    """A URL whose port accepts connections and never answers: a command asking it waits."""
    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen(16)
        silent.settimeout(60)
        yield f"http://127.0.0.1:{silent.getsockname()[1]}", silent


def asking(silent: socket.socket) -> socket.socket:
    """The command's connection, once its request has come."""
    conn, _ = silent.accept()
    conn.settimeout(60)
    assert conn.recv(4096).startswith(b"GET /api/")
    return conn


def test_a_forked_command_prints_and_exits_as_python_m_server(starter: Starter, tmp_path: Path) -> None:
    hint = subprocess.run(
        starter.command(("colcon", "build"), False), capture_output=True, text=True, timeout=60
    )
    assert (hint.returncode, hint.stdout, hint.stderr) == (0, COLCON_HINT + "\n", "")
    url = f"http://127.0.0.1:{free_port()}"  # nothing listens: one line, exit 2, the URL from the environment
    env = {**os.environ, "TELEOP_URL": url}
    forked = subprocess.run(
        starter.command(("topic", "list"), False), capture_output=True, text=True, env=env, timeout=60
    )
    shell = subprocess.run(plain("topic", "list"), capture_output=True, text=True, env=env, timeout=60)
    assert (forked.returncode, forked.stdout, forked.stderr) == (shell.returncode, shell.stdout, shell.stderr)
    assert forked.returncode == 2 and url in forked.stderr
    usage = subprocess.run(
        starter.command(("topic", "nope"), False), capture_output=True, text=True, timeout=60
    )
    assert usage.returncode == 2 and "invalid choice: 'nope'" in usage.stderr


def test_a_forked_command_works_in_the_folder_it_was_started_in(starter: Starter, tmp_path: Path) -> None:
    args = ("pkg", "create", "probe_pkg", "--build-type", "ament_python")
    done = subprocess.run(
        starter.command(args, False), capture_output=True, text=True, cwd=tmp_path, timeout=60
    )
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "probe_pkg" / "setup.py").is_file()


def test_ctrl_c_reaches_the_forked_command_and_it_ends_as_on_ctrl_c(starter: Starter) -> None:
    with silent_lab() as (url, silent):
        proc = subprocess.Popen(
            starter.command(("--url", url, "topic", "list"), False),
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )
        with asking(silent):
            assert len(children(starter)) == 1
            proc.send_signal(signal.SIGINT)
            out, err = proc.communicate(timeout=30)
    assert (proc.returncode, out, err) == (0, b"", b"")  # the CLI's own answer to Ctrl-C
    wait_until(lambda: not children(starter), "the command to be reaped", 10.0)


def test_a_killed_client_takes_its_command_with_it(starter: Starter) -> None:
    with silent_lab() as (url, silent):
        proc = subprocess.Popen(starter.command(("--url", url, "topic", "list"), False))
        with asking(silent):
            (command,) = children(starter)
            proc.kill()
            assert proc.wait(timeout=30) == -signal.SIGKILL
            wait_until(lambda: command not in children(starter), "the command to be killed", 10.0)


def test_a_starter_whose_test_process_goes_kills_what_it_started() -> None:
    own = Starter()
    try:
        with silent_lab() as (url, silent):
            proc = subprocess.Popen(own.command(("--url", url, "topic", "list"), False))
            with asking(silent):
                (command,) = children(own)
                own.close()  # as when the pytest process ends: the starter's stdin closes
                assert own.proc.returncode == 0
                assert not Path(f"/proc/{command}").exists()
                assert proc.wait(timeout=30) != 0  # its client is told the starter has gone
    finally:
        own.close()
