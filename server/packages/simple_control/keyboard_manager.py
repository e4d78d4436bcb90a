"""KeyboardManagerNode for the drone: arrow keys on /keydown → setpoints on /uav/input/position.

Each arrow press moves the setpoint ``step_m`` (1 m) in x or y, from (0, 0, 3). The mapping
fits the page's default camera, which looks from -y towards +y: RIGHT → +x (right on screen),
LEFT → -x, UP → +y (away from the viewer), DOWN → -y.

``mode``:
- ``lab``: the handout's node: publishes its setpoint every tick at 20 Hz and reads the last key
  seen in each tick (so it overrides anyone else publishing positions);
- ``adopt`` (default): takes the latest setpoint seen on /uav/input/position as its own and
  publishes only when a key changes it, at once, so keys and REST or rqt-style publishing mix.
"""

from __future__ import annotations

from server.bus import Node
from server.msgs import Key, Vector3

START_M = (0.0, 0.0, 3.0)
ARROWS = {
    Key.KEY_RIGHT: (1.0, 0.0),
    Key.KEY_LEFT: (-1.0, 0.0),
    Key.KEY_UP: (0.0, 1.0),
    Key.KEY_DOWN: (0.0, -1.0),
}


class KeyboardManager(Node):
    def __init__(self) -> None:
        super().__init__("KeyboardManagerNode")
        self.mode = self.declare_parameter("mode", "adopt").value
        if self.mode not in ("adopt", "lab"):
            raise ValueError(f"mode must be 'adopt' or 'lab', got {self.mode!r}")
        self.step_m = float(self.declare_parameter("step_m", 1.0).value)
        rate_hz = float(self.declare_parameter("rate_hz", 20.0).value)
        start_delay_s = float(self.declare_parameter("start_delay_s", 0.0).value)
        if not (0.0 < self.step_m <= 10.0 and 0.0 < rate_hz <= 1000.0 and start_delay_s >= 0.0):
            raise ValueError("step_m must be in (0, 10], rate_hz in (0, 1000], start_delay_s >= 0")
        self.position_pub = self.create_publisher(Vector3, "/uav/input/position", 1)
        self.keyboard_sub = self.create_subscription(Key, "/keydown", self.get_key, 1)
        if self.mode == "adopt":
            self.create_subscription(Vector3, "/uav/input/position", self.adopt, 10)
        self.pos = Vector3(x=START_M[0], y=START_M[1], z=START_M[2])
        self.key_code = -1
        self.period_s = 1.0 / rate_hz
        self.timer = None
        if start_delay_s > 0:  # the handout's node sleeps 10 s to let the simulator start
            self._delay = self.create_timer(start_delay_s, self.start)
        else:
            self.start()

    def start(self) -> None:
        if getattr(self, "_delay", None) is not None:
            self._delay.cancel()
        if self.mode == "lab" and self.timer is None:
            self.timer = self.create_timer(self.period_s, self.mainloop)
        self.started = True

    def adopt(self, msg: Vector3) -> None:
        self.pos = msg

    def get_key(self, msg: Key) -> None:
        if self.mode == "lab":
            self.key_code = msg.code
        elif getattr(self, "started", False) and self.apply_key(msg.code):
            self.position_pub.publish(self.pos)

    def apply_key(self, code: int) -> bool:
        """Move the setpoint for an arrow key; returns whether it moved."""
        move = ARROWS.get(code)
        if move is None:
            return False
        pos = self.pos.copy()
        pos.x += move[0] * self.step_m
        pos.y += move[1] * self.step_m
        self.pos = pos
        return True

    def mainloop(self) -> None:
        self.position_pub.publish(self.pos)
        self.apply_key(self.key_code)
        if self.key_code != -1:
            self.key_code = -1
