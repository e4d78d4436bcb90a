"""Checkpoint 3: one launch file of the student's workspace starts the simulator, the keyboard and
the student's keyboard manager; then the arrow keys fly the drone.

Met when, after such a launch, an arrow keydown from the lab's keyboard node, a setpoint published
by the student's process and the drone's GPS moved at least MOVE_M in x and MOVE_M in y from where
it was at the launch have all been seen.
"""

from __future__ import annotations

from server.world.checkpoints.declared import Checkpoint, Evidence, Question, Step
from server.world.checkpoints.events import Event, Gps, KeyDown, Launch, Setpoint
from server.world.checkpoints.keyboard_abort import from_keyboard
from server.world.checkpoints.page_names import (
    CODE,
    DRONE_TEMPLATE,
    LAUNCH_TEMPLATE,
    NEW_FILE,
    NEW_PACKAGE,
    RUN,
)
from server.world.checkpoints.timeline import Timeline, Track

ARROWS = {273: "up", 274: "down", 275: "right", 276: "left"}  # SDL codes
SIMULATORS = frozenset({"flightgoggles", "simple_sim"})
KEYBOARD_PKG = "keyboard"
MOVE_M = 2.0


def qualifies(launch: Launch) -> str | None:
    """Why this launch is not checkpoint 3's, or None when it is."""
    if not launch.in_workspace:
        return (
            f"{launch.file} is the lab's, not a file of your workspace: open your launch file in "
            f"the {CODE} view and press {RUN}"
        )
    pkgs = {node.pkg for node in launch.nodes}
    if not pkgs & SIMULATORS:
        return f"{launch.file} starts no simulator ({' or '.join(sorted(SIMULATORS))})"
    if KEYBOARD_PKG not in pkgs:
        return f"{launch.file} starts no keyboard node"
    if not any(node.student for node in launch.nodes):
        return f"{launch.file} starts no node of your own"
    return None


class LaunchAndKeysCheck:
    def __init__(self) -> None:
        self.timeline = Timeline(120)
        self.track = Track()
        self._launch: Launch | None = None
        self._origin: tuple[float, float, float] | None = None
        self._reach = [0.0, 0.0]
        self._keys = 0
        self._setpoints = 0
        self._note = f"start one launch file of your workspace: open it in the {CODE} view and press {RUN}"
        self.started = False

    def feed(self, event: Event) -> Evidence | None:
        if isinstance(event, Launch):
            why = qualifies(event)
            if why is None:
                self._launch, self._origin, self._reach = event, None, [0.0, 0.0]
                self._keys = self._setpoints = 0
                self.timeline.clear()
                self.timeline.add(event.t_s, "launch", event.file)
                self.started = True
                self._note = "launched: fly with the arrow keys"
            elif self._launch is None:
                self._note = why
        elif self._launch is None:
            return None
        elif isinstance(event, KeyDown) and event.code in ARROWS and from_keyboard(event.source):
            self._keys += 1
            self.timeline.add(event.t_s, "key", ARROWS[event.code], event.source)
        elif isinstance(event, Setpoint) and event.source.student and self._keys:
            self._setpoints += 1
            self.timeline.add(event.t_s, "setpoint", [round(v, 3) for v in event.xyz], event.source)
        elif isinstance(event, Gps):
            self.track.add(event.t_s, event.xyz)
            if self._origin is None:
                self._origin = event.xyz
            self._reach[0] = max(self._reach[0], abs(event.xyz[0] - self._origin[0]))
            self._reach[1] = max(self._reach[1], abs(event.xyz[1] - self._origin[1]))
            return self._met(event.t_s)
        return None

    def _met(self, now_s: float) -> Evidence | None:
        launch = self._launch
        if launch is None or not self._keys or not self._setpoints or min(self._reach) < MOVE_M:
            if launch is not None:
                self._note = (
                    f"{self._keys} arrow keys, {self._setpoints} setpoints from your node; moved "
                    f"{self._reach[0]:.1f} m in x, {self._reach[1]:.1f} m in y (2 m each)"
                )
            return None
        self._note = "done: your launch and the arrow keys flew the drone"
        evidence: Evidence = {
            "launch_file": launch.file,
            "launch_text": launch.text,
            "nodes": [
                {"pkg": n.pkg, "exec": n.exec, "name": n.name, "student": n.student} for n in launch.nodes
            ],
            "moved_m": [round(v, 2) for v in self._reach],
            "timeline": self.timeline.entries(),
            "track": self.track.since(launch.t_s),
        }
        self._launch = None  # met: another launch may meet it again, with newer evidence
        return evidence

    def tick(self, now_s: float) -> Evidence | None:
        return None

    def progress(self, now_s: float) -> str:
        return self._note


CHECKPOINT = Checkpoint(
    name="launch_and_keys",
    title="One launch file, then fly with the arrow keys",
    steps=(
        Step(
            "Write a launch file in your workspace that starts the simulator, the keyboard and your "
            "drone keyboard manager.",
            ("ros2lab pkg create --build-type ament_python drone_keys",),
            page=(
                f"In the {CODE} view: {NEW_PACKAGE} (drone_keys), then {NEW_FILE} in it twice: Start "
                f"from \u201c{DRONE_TEMPLATE}\u201d, then from \u201c{LAUNCH_TEMPLATE}\u201d; fill "
                "in their TODOs."
            ),
        ),
        Step(
            "Start it: one launch starts everything.",
            ("ros2lab launch drone_keys fly.launch",),
            page=f"Open your launch file in the {CODE} view and press {RUN}.",
        ),
        Step(
            "Fly with the arrow keys: at least 2 m in x and 2 m in y.",
            (),
            page="Click the 3D view, then press the arrow keys.",
        ),
    ),
    check=LaunchAndKeysCheck,
    questions=(
        Question("final", "What does one launch file give you that starting each node by hand did not?"),
    ),
    wants_graph=True,
)
