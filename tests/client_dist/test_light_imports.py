"""A node process stays small: what the handout's nodes import (rclpy, the runner, std_msgs and
keyboard messages, their CDR on the way out) loads neither numpy nor asyncio, which together
were about 30 MiB of a node process's memory. A message with a fixed-size numeric array still
gets numpy, loaded at that first use.

A node made and joined to a router, with the handout's publisher and subscription, loads none of
numpy (every node's /parameter_events carries rcl_interfaces' ParameterValue, whose bool and byte
sequences are lists and ``array.array``), rosbags (its typestore of every lab type was 9 MiB: the
lab's types' hashes come from a generated table) nor PyYAML (only ROS arguments need it); a
student's own type, which the table cannot hold, still gets its hash through rosbags then."""

from __future__ import annotations

import json
import subprocess
import sys

from node_runtime.msgs.wire import computed_type_hash, type_hash

HEAVY = ("numpy", "asyncio", "rosbags", "yaml")

PROBE = """
import json, sys
import rclpy, node_runtime.process.runner
from std_msgs.msg import String, Int32
from keyboard_msgs.msg import Key
from node_runtime.transport.cdr import encode
light = [m for m in ("numpy", "asyncio") if m in sys.modules]
sent = [encode(String(data="hi")), encode(Int32(data=3)), encode(Key(code=97))]
after_light = [m for m in ("numpy", "asyncio") if m in sys.modules]
from sensor_msgs.msg import Imu
covariance = Imu().orientation_covariance
print(json.dumps({"light": light, "after_light": after_light, "numpy_later": "numpy" in sys.modules,
                  "covariance": [type(covariance).__module__, len(covariance)], "sent": len(sent)}))
"""

# The handout's keyboard manager's endpoints, on a node joined to a router this process opens
# (loopback, no scouting), then one message each way.
JOINED_PROBE = """
import json, os, socket, sys, threading
import zenoh
with socket.socket() as s:
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
config = zenoh.Config()
config.insert_json5("mode", '"router"')
config.insert_json5("scouting/multicast/enabled", "false")
config.insert_json5("listen/endpoints", json.dumps([f"tcp/127.0.0.1:{port}"]))
router = zenoh.open(config)
os.environ["ZENOH_CONFIG_OVERRIDE"] = f'connect/endpoints=["tcp/127.0.0.1:{port}"]'
import rclpy, node_runtime.process.runner
from rclpy.node import Node
from std_msgs.msg import Bool
from keyboard_msgs.msg import Key
rclpy.init()
node = Node("KeyboardManagerNode")
heard = threading.Event()
pub = node.create_publisher(Bool, "/abort_takeoff", 1)
node.create_subscription(Bool, "/abort_takeoff", lambda msg: heard.set(), 1)
node.create_subscription(Key, "/keydown", lambda msg: None, 1)
for _ in range(200):
    pub.publish(Bool(data=True))
    rclpy.spin_once(node, timeout_sec=0.05)
    if heard.is_set():
        break
print(json.dumps({"heard": heard.is_set(), "loaded": [m for m in HEAVY if m in sys.modules]}))
rclpy.try_shutdown()
router.close()
"""


def _run(code: str) -> dict[str, object]:
    done = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
        env={"PYTHONPATH": "client:.", "PATH": ""},
    )
    assert done.returncode == 0, done.stderr
    seen: dict[str, object] = json.loads(done.stdout.strip().splitlines()[-1])
    return seen


def test_a_handout_node_process_loads_neither_numpy_nor_asyncio() -> None:
    seen = _run(PROBE)
    assert seen["sent"] == 3 and seen["light"] == [] and seen["after_light"] == []
    assert seen["numpy_later"] and seen["covariance"] == ["numpy", 9]


def test_a_joined_handout_node_loads_no_numpy_rosbags_or_yaml() -> None:
    seen = _run(f"HEAVY = {HEAVY!r}\n" + JOINED_PROBE)
    assert seen == {"heard": True, "loaded": []}


def test_a_type_outside_the_table_is_hashed_from_its_definition() -> None:
    # The table's own entries against the per-type typestore a student's type gets: a message
    # nesting others, a service (its hash covers its event type) and an action.
    for name in ("sensor_msgs/msg/Imu", "std_srvs/srv/SetBool", "example_interfaces/action/Fibonacci"):
        assert computed_type_hash(name) == type_hash(name)


# ``ros2lab run`` against a closed port (it gives up at once): which of the other verbs' modules
# and their libraries it loaded on the way.
RUN_PROBE = """
import json, socket, sys
with socket.socket() as s:
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
from server.cli import main
code = main(["--url", f"http://127.0.0.1:{port}", "run", "--join-timeout", "0", "pkg", "exe"])
others = [m for m in ("server.cli.bag", "server.cli.topic", "server.cli.interface", "mcap", "pydantic")
          if m in sys.modules]
print(json.dumps({"code": code, "loaded": others}))
"""


def test_ros2lab_run_loads_none_of_the_other_verbs() -> None:
    seen = _run(RUN_PROBE)
    assert seen == {"code": 1, "loaded": []}
