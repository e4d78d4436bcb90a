"""npm's roslib 2.x, driven by node, against the live lab: the rocket through rosbridge.

The client is tests/js/roslib_client.mjs with roslib from tests/js's lock file (``npm ci``, run
by scripts/test.sh). Without node or those packages the test is skipped, except in CI
(CI=true), where it must run.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

from .conftest import RosbridgeServer

JS_DIR = Path(__file__).resolve().parents[1] / "js"
CLIENT_TIMEOUT_S = 60.0


def node_binary() -> str:
    node = shutil.which("node")
    missing = None
    if node is None:
        missing = "no node on PATH (apt-get install nodejs)"
    elif not (JS_DIR / "node_modules" / "roslib").is_dir():
        missing = "roslib is not installed (npm ci --prefix tests/js, as scripts/test.sh does)"
    if missing is not None:
        if os.environ.get("CI") == "true":
            pytest.fail(f"{missing}; in CI the roslib test must run")
        pytest.skip(missing)
    assert node is not None
    return node


@pytest.mark.parametrize("way", ["app", "port"])
def test_roslib_countdown_abort_topics_and_reset(rosbridge_server: RosbridgeServer, way: str) -> None:
    node = node_binary()
    rosbridge_server.reset_rocket()
    done = subprocess.run(
        [node, str(JS_DIR / "roslib_client.mjs"), rosbridge_server.urls[way]],
        cwd=JS_DIR,
        capture_output=True,
        text=True,
        timeout=CLIENT_TIMEOUT_S,
        check=False,
    )
    steps = [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]
    assert done.returncode == 0, f"{done.stdout}\n{done.stderr}"
    assert [s["step"] for s in steps] == [
        "connected",
        "countdown",
        "aborted",
        "topics",
        "reset",
        "countdown_again",
        "ok",
    ]
    topics = next(s for s in steps if s["step"] == "topics")
    assert topics["types"][topics["topics"].index("/countdown")] == "std_msgs/msg/Int64"
    assert next(s for s in steps if s["step"] == "reset")["message"] == "rocket back on the pad"
