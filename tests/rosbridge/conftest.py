"""A live lab server for the rosbridge client tests (roslibpy in process, npm's roslib under node).

``python -m server --launch rocket start_delay:=1`` in a subprocess on free loopback ports, with
rosbridge also on a port of its own (as rosbridge_server's 9090). Each test resets the rocket
through the REST API first, so it sees a countdown from 10 and a rocket that has not aborted.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest
from support.app import end, free_ports, wait_healthy
from support.forked_server import start_server
from support.http import HTTP

READY_S = 30.0
STOP_S = 10.0


@dataclass
class RosbridgeServer:
    port: int
    rosbridge_port: int
    log_path: Path

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    @property
    def urls(self) -> dict[str, str]:
        """The two ways in: the app's /rosbridge, and rosbridge's own port at /."""
        return {
            "app": f"ws://127.0.0.1:{self.port}/rosbridge",
            "port": f"ws://127.0.0.1:{self.rosbridge_port}",
        }

    def reset_rocket(self) -> None:
        assert HTTP.post(f"{self.url}/api/rocket/reset", timeout=5.0).status_code == 200

    def log_tail(self) -> str:
        return self.log_path.read_text(errors="replace")[-3000:]


@pytest.fixture(scope="session")
def rosbridge_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[RosbridgeServer]:
    workdir = tmp_path_factory.mktemp("rosbridge_server")
    port, rosbridge_port = free_ports(2)
    server = RosbridgeServer(port, rosbridge_port, workdir / "server.log")
    proc = start_server(
        ["--host", "127.0.0.1", "--port", str(server.port), "--launch", "rocket",
         "--rosbridge-port", str(server.rosbridge_port), "--no-foxglove", "--no-zenoh", "start_delay:=1"],
        cwd=workdir, log=server.log_path,
    )  # fmt: skip
    try:
        wait_healthy(server.url, proc, READY_S, server.log_tail)
        yield server
    finally:
        end(proc, STOP_S)
