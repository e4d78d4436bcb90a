"""A node process stays small: what the handout's nodes import (rclpy, the runner, std_msgs and
keyboard messages, their CDR on the way out) loads neither numpy nor asyncio, which together
were about 30 MiB of a node process's memory. A message with a fixed-size numeric array still
gets numpy, loaded at that first use."""

from __future__ import annotations

import json
import subprocess
import sys

PROBE = """
import json, sys
import rclpy, server.processes.runner
from std_msgs.msg import String, Int32
from keyboard_msgs.msg import Key
from server.transport.cdr import encode
light = [m for m in ("numpy", "asyncio") if m in sys.modules]
sent = [encode(String(data="hi")), encode(Int32(data=3)), encode(Key(code=97))]
after_light = [m for m in ("numpy", "asyncio") if m in sys.modules]
from sensor_msgs.msg import Imu
covariance = Imu().orientation_covariance
print(json.dumps({"light": light, "after_light": after_light, "numpy_later": "numpy" in sys.modules,
                  "covariance": [type(covariance).__module__, len(covariance)], "sent": len(sent)}))
"""


def test_a_handout_node_process_loads_neither_numpy_nor_asyncio() -> None:
    done = subprocess.run(
        [sys.executable, "-c", PROBE], capture_output=True, text=True, timeout=120, check=False,
        env={"PYTHONPATH": "client:.", "PATH": ""},
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout.strip().splitlines()[-1])
    assert seen["sent"] == 3 and seen["light"] == [] and seen["after_light"] == []
    assert seen["numpy_later"] and seen["covariance"] == ["numpy", 9]
