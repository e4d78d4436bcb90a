"""A sandboxed node never outlives its server: it is pid 1 of its own pid namespace under bwrap,
where the kernel's parent-death signal does not reach it and the server's pid cannot be watched,
so it holds a lifeline (node_runtime/process/lifeline.py) and ends when the server has ended, however
it ended; and the server's Stop ends it even when it ignores Ctrl-C. The server here is a
stand-in process that starts the node through the real Supervisor (tests/sandbox/
standin_server.py). Every process is ended by its id."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from support.app import REPO
from support.sandbox import require_sandbox
from support.wait import wait_until

SLEEPER = "import time\n\n\ndef main():\n    print('asleep', flush=True)\n    time.sleep(600)\n"
STUBBORN = (
    "import signal\nimport time\n\n\ndef main():\n    signal.signal(signal.SIGINT, signal.SIG_IGN)\n"
    "    print('asleep', flush=True)\n    time.sleep(600)\n"
)
WAIT_S = 30.0
STOP_S = 5.0  # far below the 600 s the node would sleep, were it not ended


@pytest.fixture(autouse=True)
def _a_sandbox_on_this_machine() -> None:
    require_sandbox()


def alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state != "Z"


def uid_of(pid: int) -> int:
    line = next(x for x in Path(f"/proc/{pid}/status").read_text().splitlines() if x.startswith("Uid:"))
    return int(line.split()[1])


class Standin:
    def __init__(self, tmp_path: Path, code: str) -> None:
        workspace = tmp_path / "workspace"
        (workspace / "src" / "sleepy").mkdir(parents=True)
        node = workspace / "src" / "sleepy" / "sleeper.py"
        node.write_text(code)
        (tmp_path / "router").mkdir()
        self.proc = subprocess.Popen(
            [sys.executable, str(Path(__file__).with_name("standin_server.py")), str(workspace), str(node)],
            cwd=REPO,
            env={**os.environ, "PYTHONPATH": str(REPO)},
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )
        assert self.proc.stdout is not None
        self.bwrap, self.node = (int(v) for v in self.proc.stdout.readline().split())

    def say(self, line: str) -> str:
        assert self.proc.stdin is not None and self.proc.stdout is not None
        self.proc.stdin.write(line + "\n")
        self.proc.stdin.flush()
        return self.proc.stdout.readline().strip()

    def end(self) -> None:
        for pid in (self.node, self.bwrap):
            if alive(pid):
                os.kill(pid, signal.SIGKILL)
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.communicate(timeout=10)


@pytest.fixture
def sleeper(tmp_path: Path) -> Iterator[Standin]:
    standin = Standin(tmp_path, SLEEPER)
    try:
        yield standin
    finally:
        standin.end()


def test_a_sandboxed_node_ends_when_its_server_is_killed(sleeper: Standin) -> None:
    assert alive(sleeper.node) and alive(sleeper.bwrap)  # asleep for minutes, unless its server goes
    if os.geteuid() == 0:  # a root server: the node dropped to its world's uid
        assert uid_of(sleeper.node) != 0
    sleeper.proc.kill()  # as a crash would end the server
    sleeper.proc.wait(timeout=10)
    wait_until(lambda: not alive(sleeper.node), "the node gone with its server", WAIT_S)


def test_a_sandboxed_node_that_ignores_ctrl_c_is_ended_by_stop(tmp_path: Path) -> None:
    standin = Standin(tmp_path, STUBBORN)
    try:
        assert alive(standin.node)
        assert standin.say("stop") == "stopped"  # Ctrl-C ignored, then ended: stop returned
        # bwrap is reaped when Stop returns; the node inside its pid namespace is killed by the
        # kernel (or by the sandbox's pid 1 whose lifeline broke) an instant after, not later.
        wait_until(lambda: not alive(standin.node), "the stubborn node ended by Stop", STOP_S)
        assert not alive(standin.bwrap)
        assert standin.proc.poll() is None  # the server stand-in itself still runs
    finally:
        standin.end()
